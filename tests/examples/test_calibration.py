"""examples/calibration.py: the fit recovers the parameters that made the synthetic measurement."""

from __future__ import annotations

import math

import pytest

from tests.examples.loader import load_example


@pytest.fixture(scope="module")
def ex():
    return load_example("calibration")


def test_fit_recovers_the_true_stiffness_and_restitution(ex):
    """The errors must be consistent with the reported standard uncertainties (within 4 u: a false
    alarm once in 16 000 for a Gaussian estimate) and the stiffness within 1 %."""
    fit = ex.fit
    assert fit.success
    for (key, value), u in zip(fit.fitted.items(), fit.uncertainty):
        assert abs(value - ex.TRUE[key]) < 4 * u, key
    assert fit.fitted["contact.stiffness"] == pytest.approx(ex.TRUE["contact.stiffness"], rel=0.01)
    assert fit.uncertainty[0] < 0.01 * ex.TRUE["contact.stiffness"]
    assert fit.fitted["contact.restitution"] == pytest.approx(ex.TRUE["contact.restitution"], abs=0.02)


def test_residuals_are_the_noise_put_in(ex):
    """Residuals are divided by the largest measured force, which the noise raises a little above the
    true peak; their standard deviation estimates NOISE x peak / max(measured) with relative sampling
    error 1 / sqrt(2 N) ~ 2 % for N ~ 1000 samples: bound 10 % (5 standard errors)."""
    fit, m = ex.fit, ex.measured
    expected = ex.NOISE * ex.force.max() / float(max(abs(m.force.max()), abs(m.force.min())))
    assert fit.sigma == pytest.approx(expected, rel=0.1)
    n = int(fit.data_mask.sum())
    assert 1 / math.sqrt(2 * n) < 0.03


def test_the_clock_offset_is_taken_out(ex):
    """The data clock starts 0.37 ms off; alignment plus the fitted shift leave < one sample (1 us)."""
    assert abs(ex.fit.time_shift) < 1e-6
