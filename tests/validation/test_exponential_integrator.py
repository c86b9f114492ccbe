"""The exponential (modal) collocation integrator against the scipy DOP853 reference path."""

from __future__ import annotations

import numpy as np
from numpy.testing import assert_allclose

import flexbeam as fb
from tests.conftest import seed


def _both(case, method="ccfm"):
    ref = fb.simulate(case.model_copy(update={"solver": case.solver.model_copy(update={"integrator": "reference"})}),
                      method)
    fast = fb.simulate(case.model_copy(update={"solver": case.solver.model_copy(update={"integrator": "exponential"})}),
                       method)
    return ref, fast


def _agree(ref, fast, peak=5e-4, duration=1e-3):
    a, b = ref.metrics(), fast.metrics()
    assert b["status"] == "success"
    assert b["contacts"] == a["contacts"]
    assert_allclose(b["peak_force"], a["peak_force"], rtol=peak)
    assert_allclose(b["contact_duration"], a["contact_duration"], rtol=duration)
    assert_allclose(b["post_impact_velocity"], a["post_impact_velocity"], rtol=1e-3)
    assert abs(b["energy_drift_max"]) < 1e-5


def test_seed_first_contact_agrees():
    _agree(*_both(seed(model__modes=6, solver__t_end=2e-3)))


def test_seed_damped_law_agrees_and_books_dissipation():
    ref, fast = _both(seed(model__modes=4, contact__law="hunt_crossley", contact__restitution=0.5,
                           solver__t_end=2e-3))
    _agree(ref, fast)
    assert_allclose(fast["dissipated_energy"][-1], ref["dissipated_energy"][-1], rtol=1e-3)


def test_rigid_rod_agrees():
    _agree(*_both(seed(model__modes=0, contact__law="hertz", solver__t_end=2e-3)))


def test_spinning_beam_impact_agrees():
    """A beam spun at 8 rad/s into the obstacle: centrifugal and Coriolis terms active."""
    case = seed(model__modes=4, initial__kind="state", initial__angle=0.05, initial__rate=-8.0,
                solver__t_end=0.01)
    _agree(*_both(case))


def test_kane_spinup_tip_deflection_agrees():
    case = fb.load_case("kane-spinup", {"model.modes": 2, "solver.t_end": 4.0})
    ref, fast = _both(case)
    tip_ref = np.interp(fast.time, ref.time, ref["tip_deflection"])
    scale = np.max(np.abs(tip_ref))
    assert np.max(np.abs(fast["tip_deflection"] - tip_ref)) < 1e-4 * scale
