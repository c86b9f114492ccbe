"""The shipped `seed-experiment-calibrated` case against the experiment it was fitted to.

The experiment's reported features (Duan, Zhang & Hong 2013, Sec. 4: peak 584 N, second
peak 297 N, ~0.6 ms) are independent data.  The fit cannot reach all three at once (see
the README); these tests pin down what it does reach, and that the compliant sensor
explains the measurement better than the rigid obstacle of the plain seed case.
"""

from __future__ import annotations

import math

import pytest

import flexbeam as fb
from flexbeam.parameters import reference_data

#: first contact ends by ~0.8 ms; 2 ms covers it and the sensor's ring-down
T_FIRST_CONTACT = 2e-3


def _rms_misfit(metrics: dict, exp: dict) -> float:
    """RMS of the relative misfits in the fitted features (a missing second peak counts 0 N)."""
    pairs = [(metrics["peak_force"], exp["peak_force"]),
             (metrics["second_peak_force"], exp["second_peak_force"]),
             (metrics["contact_duration"], exp["contact_duration"])]
    r = [((m if math.isfinite(m) else 0.0) - v) / v for m, v in pairs]
    return math.sqrt(sum(x * x for x in r) / len(r))


@pytest.fixture(scope="module")
def experiment():
    return reference_data("seed-experiment-calibrated")["experiment"]


@pytest.fixture(scope="module")
def calibrated():
    case = fb.load_case("seed-experiment-calibrated", {"solver.t_end": T_FIRST_CONTACT})
    return fb.simulate(case, "ccfm").metrics()


def test_calibrated_case_shares_the_papers_reference_numbers(experiment):
    assert experiment["peak_force"] == 584.0 and experiment["second_peak_force"] == 297.0


def test_fit_reaches_the_second_peak_and_bounds_the_rest(calibrated, experiment):
    # what the least-squares fit reached (README table): second peak within 5 %,
    # peak within 35 % (the paper's own CCFM: 17.98 %), duration within 30 %
    assert calibrated["second_peak_force"] == pytest.approx(experiment["second_peak_force"], rel=0.05)
    assert calibrated["peak_force"] == pytest.approx(experiment["peak_force"], rel=0.35)
    assert calibrated["contact_duration"] == pytest.approx(experiment["contact_duration"], rel=0.30)
    assert calibrated["contacts"] == 1


def test_compliant_sensor_explains_the_data_better_than_a_rigid_obstacle(calibrated, experiment):
    rigid = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": T_FIRST_CONTACT}), "ccfm").metrics()
    assert _rms_misfit(calibrated, experiment) < 0.5 * _rms_misfit(rigid, experiment)


@pytest.mark.slow
def test_calibrated_case_full_run_balances_energy():
    sol = fb.simulate(fb.load_case("seed-experiment-calibrated"), "ccfm")
    m = sol.metrics()
    assert m["status"] == "success"
    assert m["energy_drift_max"] < 1e-6
