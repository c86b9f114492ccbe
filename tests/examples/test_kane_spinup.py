"""examples/kane_spinup.py: the first-order tip follows the quasi-static deflection, the zeroth-order one diverges."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.examples.loader import load_example


@pytest.fixture(scope="module")
def ex():
    return load_example("kane_spinup")


def omega_1(case) -> float:
    """First cantilever frequency 1.8751^2 sqrt(EI / (mu L^4)) [rad/s] (3.80 for Kane's beam)."""
    b = case.beam
    return 1.87510407**2 * math.sqrt(b.bending_stiffness / (b.line_density * b.length**4))


def test_first_order_tip_follows_the_quasi_static_deflection(ex):
    """The spin-up's acceleration varies at 2 pi / T_s = 0.42 rad/s, far below the beam's first
    frequency (>= 3.8 rad/s), so the dynamic response exceeds the static one by about
    r^2 = (0.42 / 3.8)^2 = 1.2 % (a slowly forced oscillator, 1 / (1 - r^2)); bound 2 r^2."""
    r2 = (2 * math.pi / ex.Ts / omega_1(ex.case)) ** 2
    peak = np.max(np.abs(ex.tip_quasi))
    assert peak > 0.05 * ex.case.beam.length  # a real deflection (0.57 m)
    np.testing.assert_allclose(ex.tip_first, ex.tip_quasi, atol=2 * r2 * peak)
    assert ex.first.metrics()["tip_deflection_min"] == pytest.approx(ex.tip_quasi.min(), rel=2 * r2)


def test_first_order_returns_to_a_small_vibration(ex):
    """After the spin-up theta'' = 0: the quasi-static deflection is zero."""
    after = ex.first.time >= ex.Ts
    assert ex.first.status == "success"
    assert np.max(np.abs(ex.first["tip_deflection"][after])) < 0.02 * np.max(np.abs(ex.tip_quasi))


def test_zeroth_order_diverges(ex):
    """Above omega_1 the zeroth-order stiffness K - theta'^2 M is indefinite: the tip leaves the beam's length."""
    tip = ex.zeroth["tip_deflection"]
    assert ex.W > omega_1(ex.case)
    assert not np.all(np.isfinite(tip)) or np.nanmax(np.abs(tip)) > ex.case.beam.length
