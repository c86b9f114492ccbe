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
    alarm once in 16 000 for a Gaussian estimate; measured 0.33 u and 0.79 u).  Besides, the fit must be
    useful: stiffness within 1 % (measured 0.06 %) with u below 2 % (measured 0.18 %), restitution within
    0.04 (measured 0.0022; it started 0.2 off)."""
    fit = ex.fit
    assert fit.success
    for (key, value), u in zip(fit.fitted.items(), fit.uncertainty):
        assert abs(value - ex.TRUE[key]) < 4 * u, key
    assert fit.fitted["contact.stiffness"] == pytest.approx(ex.TRUE["contact.stiffness"], rel=0.01)
    assert fit.uncertainty[0] < 0.02 * ex.TRUE["contact.stiffness"]
    assert fit.fitted["contact.restitution"] == pytest.approx(ex.TRUE["contact.restitution"], abs=0.04)


def test_residuals_are_the_noise_put_in(ex):
    """Residuals are divided by the largest measured force, which the noise raises a little above the
    true peak; their standard deviation estimates NOISE x peak / max(measured) with relative sampling
    error 1 / sqrt(2 N) ~ 2 % for N ~ 1000 samples: bound 10 % (5 standard errors)."""
    fit, m = ex.fit, ex.measured
    expected = ex.NOISE * ex.force.max() / float(max(abs(m.force.max()), abs(m.force.min())))
    assert fit.sigma == pytest.approx(expected, rel=0.1)
    n = int(fit.data_mask.sum())
    assert 1 / math.sqrt(2 * n) < 0.03


def test_the_clock_offset_is_recovered(ex):
    """The data clock runs 0.37 ms ahead of the model's.  Data and model are aligned where the force first
    reaches 10 % of the measured peak and the remaining shift is fitted: model time = data time - t_data +
    t_model + shift, so the recovered offset t_data - t_model - shift must be the true one within 4 standard
    uncertainties of the shift (measured 0.16 u, 3.1e-8 s; u = 2e-7 s, a fifth of the sampling interval)."""
    fit, m = ex.fit, ex.measured
    true_offset = m.time[0] - ex.t[0]
    t_data = (m.time[fit.data_mask] - fit.aligned_time)[0]
    offset = t_data - fit.model_reference[1] - fit.time_shift
    assert abs(offset - true_offset) < 4 * fit.time_shift_uncertainty
    assert fit.time_shift_uncertainty < 1e-5  # and resolved: a sixtieth of the contact (measured 2e-7 s)
