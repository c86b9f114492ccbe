"""Bending frequencies of a rotating uniform cantilever against published and independent values.

Dimensionless groups: T = sqrt(rho A L^4 / EI), gamma = Omega T, omega_bar = omega T,
delta = r_h / L.  The reference is the exact (continuous) beam:

    flapwise:   (EI w'')'' - (N w')' = rho A omega^2 w,
    chordwise:  (EI w'')'' - (N w')' - rho A Omega^2 w = rho A omega^2 w,
    N(x) = rho A Omega^2 [r_h (L - x) + (L^2 - x^2)/2],

clamped at x = 0 (w = w' = 0), free at x = L (w'' = w''' = 0, N(L) = 0), so
omega_chord^2 = omega_flap^2 - Omega^2.

Published values (``data/rotating_cantilever.toml``, with their sources) cover only part of
the grid; the whole grid delta in {0, 1}, gamma = 0..10, modes 1-3 is computed by a
Frobenius power series of the ODE (the method of Wright et al. 1982), independent of
flexbeam's assumed-mode code; it lives in :func:`flexbeam.validation.reference_flapwise`
so that the validation report uses it too.  The series is first checked against
the published numbers, then flexbeam's first-order model (12 cantilever modes) must match it
within 0.5 %.
"""

from __future__ import annotations

import functools
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from flexbeam.model.frequencies import case_frequencies, hub_frame_beam, spin_frequencies
from flexbeam.parameters.case import Case
from flexbeam.validation import ROTATING_DATA, reference_flapwise

DATA_FILE = Path(__file__).parent / "data" / "rotating_cantilever.toml"
DATA = tomllib.loads(DATA_FILE.read_text("utf-8"))
GAMMAS = [float(g) for g in range(11)]
DELTAS = [0.0, 1.0]
MODES = 12
RTOL = 5e-3  # 0.5 %


def _entry_id(e: dict) -> str:
    return f"d{e['delta']:g}-g{e['gamma']:g}-m{e['mode']}"


def test_report_reads_the_same_published_values():
    assert ROTATING_DATA.resolve() == DATA_FILE.resolve()


def test_series_reference_is_the_clamped_free_beam_at_rest():
    """gamma = 0: (beta_k L)^2 with cos(bL) cosh(bL) = -1, found independently by brentq."""
    roots = [brentq(lambda b: math.cos(b) * math.cosh(b) + 1.0, a, a + 1.5) for a in (1.0, 4.0, 7.0)]
    assert np.allclose(reference_flapwise(0.0, 0.0), np.square(roots), rtol=1e-10)
    assert np.allclose(reference_flapwise(0.0, 1.0), np.square(roots), rtol=1e-10)


@pytest.mark.parametrize("entry", DATA["flapwise"], ids=_entry_id)
def test_series_reference_reproduces_published_values(entry):
    ref = reference_flapwise(entry["gamma"], entry["delta"])[entry["mode"] - 1]
    # published with 4 decimals (5 for 3.51602), results of p-version FE and differential-transform computations:
    # half a unit of rounding plus up to one unit of their own error; measured 7.3e-5 at most (gamma = 6)
    assert ref == pytest.approx(entry["value"], abs=1.5e-4)


# ----------------------------------------------------------------------------------------
# flexbeam's modal model
# ----------------------------------------------------------------------------------------
def unit_case(delta: float, modes: int = MODES, coupling: str = "first-order") -> Case:
    """L = 1, rho A = 1, EI = 1 (so T = 1 s and Omega = gamma), hub radius delta."""
    return Case.model_validate(
        {
            "beam": {
                "length": 1.0,
                # rho S = 1, EI = 1 (exact: powers of two) on a slender section, sqrt(I/S)/L = 2^-8
                "density": 2.0**8,
                "youngs_modulus": 2.0**24,
                "section": "general",
                "area": 2.0**-8,
                "second_moment": 2.0**-24,
                "half_depth": 0.0,
            },
            "hub": {"radius": delta},
            "model": {"modes": modes, "coupling": coupling, "gravity": 0.0},
            "contact": {"position": 1.0},
        }
    )


@functools.cache
def modal_beam(delta: float, modes: int = MODES, coupling: str = "first-order"):
    return hub_frame_beam(unit_case(delta, modes, coupling))


@pytest.mark.parametrize("delta", DELTAS)
@pytest.mark.parametrize("gamma", GAMMAS)
def test_flapwise_frequencies_match_reference(delta, gamma):
    ref = np.array(reference_flapwise(gamma, delta))
    got = spin_frequencies(modal_beam(delta), gamma, "flapwise")[:3]
    np.testing.assert_allclose(got, ref, rtol=RTOL)
    # Ritz (assumed modes) bounds the exact frequencies from above
    assert np.all(got >= ref * (1 - 1e-9))


@pytest.mark.parametrize("delta", DELTAS)
@pytest.mark.parametrize("gamma", GAMMAS)
def test_chordwise_frequencies_match_reference(delta, gamma):
    ref = np.sqrt(np.square(reference_flapwise(gamma, delta)) - gamma**2)
    got = spin_frequencies(modal_beam(delta), gamma, "chordwise")[:3]
    np.testing.assert_allclose(got, ref, rtol=RTOL)


@pytest.mark.parametrize("entry", DATA["flapwise"], ids=_entry_id)
def test_published_flapwise_values(entry):
    got = spin_frequencies(modal_beam(entry["delta"]), entry["gamma"], "flapwise")[entry["mode"] - 1]
    assert got == pytest.approx(entry["value"], rel=RTOL)


def test_frequencies_scale_with_T():
    """A physical beam (Kane et al.'s data) gives omega T equal to the unit beam's omega_bar."""
    mu, EI, L = 1.2, 1.4e4, 10.0
    T = math.sqrt(mu * L**4 / EI)
    case = Case.model_validate(
        {
            "beam": {
                "length": L,
                "density": 3000.0,
                "youngs_modulus": 7e10,
                "section": "general",
                "area": 4e-4,
                "second_moment": 2e-7,
                "half_depth": 0.04,
            },
            "hub": {"radius": 0.5 * L},
            "model": {"modes": MODES, "gravity": 0.0},
            "contact": {"position": L},
        }
    )
    gamma = 7.0
    got = spin_frequencies(hub_frame_beam(case), gamma / T, "flapwise")[:3] * T
    np.testing.assert_allclose(got, reference_flapwise(gamma, 0.5), rtol=RTOL)


# ----------------------------------------------------------------------------------------
# Stability: zeroth-order buckles at Omega = omega_1, first-order does not
# ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("delta", DELTAS)
def test_zeroth_order_chordwise_frequency_becomes_imaginary_past_first_frequency(delta):
    beam0 = modal_beam(delta, MODES, "zeroth-order")
    w1 = spin_frequencies(beam0, 0.0)[0]  # the model's first non-rotating frequency
    assert w1 == pytest.approx(reference_flapwise(0.0, 0.0)[0], rel=1e-6)
    for s in (0.5, 0.9, 0.99):
        # K - Omega^2 M: omega^2 = omega_1^2 - Omega^2 exactly
        assert spin_frequencies(beam0, s * w1)[0] == pytest.approx(w1 * math.sqrt(1 - s * s), rel=1e-8)
    for s in (1.01, 1.5, 10.0 / w1):
        w = spin_frequencies(beam0, s * w1)[0]
        assert w < 0.0  # flagged divergent: omega^2 < 0
        assert -w * w == pytest.approx(w1**2 * (1 - s * s), rel=1e-8)


@pytest.mark.parametrize("delta", DELTAS)
def test_first_order_model_stays_stable_up_to_gamma_10(delta):
    w0 = spin_frequencies(modal_beam(delta), 0.0, "chordwise")
    for gamma in np.linspace(0.0, 10.0, 41):
        w = spin_frequencies(modal_beam(delta), gamma, "chordwise")
        assert np.all(w > 0.0)
        # centrifugal stiffening outweighs the -Omega^2 softening: no mode gets softer
        assert np.all(w >= w0 * (1 - 1e-9))


def test_case_frequencies_gives_both_models():
    both = case_frequencies(unit_case(0.0, 6), 5.0)
    assert both["first-order"][0] > 0.0 > both["zeroth-order"][0]
    ref = math.sqrt(reference_flapwise(5.0, 0.0)[0] ** 2 - 25.0)
    assert both["first-order"][0] == pytest.approx(ref, rel=RTOL)
