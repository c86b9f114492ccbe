"""The exponential (modal) collocation integrator against the scipy DOP853 reference path."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import flexbeam as fb
from tests.conftest import seed


def _with(case, integrator):
    return case.model_copy(update={"solver": case.solver.model_copy(update={"integrator": integrator})})


def _both(case, method="ccfm"):
    return fb.simulate(_with(case, "reference"), method), fb.simulate(_with(case, "exponential"), method)


def _agree(ref, fast, peak=5e-4, duration=1e-3, drift=1e-5):
    a, b = ref.metrics(), fast.metrics()
    assert b["status"] == "success"
    assert b["contacts"] == a["contacts"]
    assert_allclose(b["peak_force"], a["peak_force"], rtol=peak)
    assert_allclose(b["contact_duration"], a["contact_duration"], rtol=duration)
    assert_allclose(b["post_impact_velocity"], a["post_impact_velocity"], rtol=1e-3)
    assert abs(b["energy_drift_max"]) < drift


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


def test_high_spin_prescribed_impact_agrees():
    """theta(t) prescribed at -30 rad/s into the obstacle: the joint reaction does the work."""
    case = seed(model__modes=4, drive__kind="prescribed", drive__profile="constant-rate",
                drive__spin_rate=-30.0, initial__kind="state", initial__angle=0.02, solver__t_end=2e-3)
    ref, fast = _both(case)
    _agree(ref, fast)
    assert fast.metrics()["contacts"] >= 1


def test_events_of_a_multi_contact_run_agree():
    """Seven contacts in 20 ms with gravity: every onset found, none spurious, at the same time."""
    ref, fast = _both(seed(model__modes=4, solver__t_end=0.02))
    assert len(fast.contacts) == len(ref.contacts) >= 3
    for a, b in zip(ref.contacts, fast.contacts, strict=True):
        assert_allclose(b.onset, a.onset, rtol=0, atol=1e-8)
        assert_allclose(b.duration, a.duration, rtol=1e-3)
        assert_allclose(b.peak_force, a.peak_force, rtol=5e-4)


def _agree_ccm(ref, fast):
    """CCM: as :func:`_agree`, but the contact ends at rest on the surface (lambda = 0), so
    P's normal velocity there is zero up to the integrators' tolerance, not a rebound to
    compare relatively."""
    _agree_events(ref, fast)
    a, b = ref.metrics(), fast.metrics()
    assert_allclose(b["peak_force"], a["peak_force"], rtol=5e-4)
    assert_allclose(b["contact_duration"], a["contact_duration"], rtol=1e-3)
    v0 = abs(a["impact_velocity"])
    assert abs(a["post_impact_velocity"]) < 1e-6 * v0
    assert abs(b["post_impact_velocity"]) < 1e-6 * v0
    assert abs(b["energy_drift_max"]) < 1e-5


def _agree_events(ref, fast):
    assert fast.status == "success"
    assert fast.provenance["integrator"] != ref.provenance["integrator"]
    assert len(fast.contacts) == len(ref.contacts) >= 1


def test_ccm_seed_first_contact_agrees():
    """CCM: the e = 0 jump, the constrained phase (multiplier collocated at the nodes) and
    the release where lambda turns tensile, against the index-1 DAE on DOP853."""
    _agree_ccm(*_both(seed(model__modes=6, solver__t_end=2e-3), "ccm"))


def test_ccm_events_of_a_multi_contact_run_agree():
    """CCM over 20 ms with gravity: five contacts, two of them grazing (lambda tensile right
    after the e = 0 jump, so they end at once).  A contact released at lambda = 0 leaves P at
    rest on the surface, so the next onset is ill-conditioned (the gap grows from second
    order); the first two contacts agree to 1e-8 s and 1e-5, the later onsets to 1e-6 s."""
    ref, fast = _both(seed(model__modes=4, solver__t_end=0.02), "ccm")
    _agree_ccm(ref, fast)
    for k, (a, b) in enumerate(zip(ref.contacts, fast.contacts, strict=True)):
        assert_allclose(b.onset, a.onset, rtol=0, atol=1e-8 if k < 2 else 1e-6)
        if k < 2:
            assert_allclose(b.duration, a.duration, rtol=1e-5)
            assert_allclose(b.peak_force, a.peak_force, rtol=1e-5)


def test_imm_events_of_a_multi_contact_run_agree():
    """IMM over 20 ms: the impulse jumps at the located impacts, rebound velocities and onsets."""
    ref, fast = _both(seed(model__modes=4, solver__t_end=0.02), "imm")
    _agree_events(ref, fast)
    for a, b in zip(ref.contacts, fast.contacts, strict=True):
        assert_allclose(b.onset, a.onset, rtol=0, atol=1e-9)
        assert_allclose(b.velocity_after, a.velocity_after, rtol=1e-6)
    assert abs(fast.metrics()["energy_drift_max"]) < 1e-5


def _calibrated(**overrides):
    return fb.load_case("seed-experiment-calibrated", {k.replace("__", "."): v for k, v in overrides.items()})


def test_compliant_support_first_contact_and_sensor_agree():
    """CCFM on the sensor (mass-spring-damper obstacle): the support's sqrt(m_s) s is one more
    exactly propagated mode, its dashpot collocated; contact and sensor pulses agree."""
    ref, fast = _both(_calibrated(model__modes=4, solver__t_end=2e-3))
    _agree(ref, fast)
    a, b = ref.metrics(), fast.metrics()
    assert "exponential" in fast.provenance["integrator"]
    assert_allclose(b["second_peak_force"], a["second_peak_force"], rtol=5e-4)
    assert_allclose(b["sensor_peak_force"], a["sensor_peak_force"], rtol=5e-4)
    assert_allclose(b["sensor_duration"], a["sensor_duration"], rtol=1e-3)
    assert_allclose(fast["dissipated_energy"][-1], ref["dissipated_energy"][-1], rtol=1e-4)


def test_compliant_support_multi_contact_onsets_agree_and_converge():
    """Three contacts in 30 ms on the sensor.  At the default tolerances the third onset,
    after 24 ms of flight, is within 1e-7 s (the atol-limited phase error of the vibration);
    with fast_rtol 1e-8 and fast_atol 1e-13 every onset is within 2e-9 s of the reference."""
    ref, fast = _both(_calibrated(model__modes=4, solver__t_end=0.03))
    tight = fb.simulate(_with(_calibrated(model__modes=4, solver__t_end=0.03, solver__fast_rtol=1e-8,
                                          solver__fast_atol=1e-13), "exponential"))
    assert len(fast.contacts) == len(tight.contacts) == len(ref.contacts) >= 3
    for a, b, c in zip(ref.contacts, fast.contacts, tight.contacts, strict=True):
        assert_allclose(b.onset, a.onset, rtol=0, atol=1e-7)
        assert_allclose(c.onset, a.onset, rtol=0, atol=2e-9)
        assert_allclose(b.peak_force, a.peak_force, rtol=5e-4)
    assert abs(fast.metrics()["energy_drift_max"]) < 1e-6


@pytest.mark.parametrize("method", ["ccm", "imm"])
def test_constrained_phases_on_a_compliant_support_take_the_reference_path(method):
    sol = fb.simulate(_calibrated(model__modes=2, solver__t_end=1e-3), method)
    assert "DOP853" in sol.provenance["integrator"]


def test_torque_drive_books_the_work():
    """Constant joint torque: W = tau (theta - theta_0) booked exactly, energy conserved."""
    case = seed(model__modes=6, drive__kind="torque", drive__torque=-2.0, initial__kind="state",
                initial__angle=0.05, initial__rate=0.0, solver__t_end=0.02)
    fast = fb.simulate(_with(case, "exponential"))
    assert fast.status == "success"
    assert abs(fast.metrics()["energy_drift_max"]) < 1e-6
    work = -2.0 * (fast["theta"] - fast["theta"][0])
    assert_allclose(fast["drive_work"], work, rtol=0, atol=1e-12 + 1e-9 * np.max(np.abs(work)))


def test_hub_without_inertia_costs_few_steps():
    """J_h = 0 makes the mass matrix nearly singular (a stiff spurious top mode whose
    frequency moves with q); freezing that change per step and the energy-norm error
    keep the step count near that of a hub with inertia."""
    steps = [fb.simulate(_with(seed(model__modes=12, hub__inertia=jh, solver__t_end=0.02), "exponential"))
             .metrics()["steps"] for jh in (0.0, 1e-3)]
    assert steps[0] < 4 * steps[1]
    assert steps[0] < 1000


def test_kane_spinup_tip_deflection_agrees():
    case = fb.load_case("kane-spinup", {"model.modes": 2, "solver.t_end": 4.0})
    ref, fast = _both(case)
    tip_ref = np.interp(fast.time, ref.time, ref["tip_deflection"])
    scale = np.max(np.abs(tip_ref))
    assert np.max(np.abs(fast["tip_deflection"] - tip_ref)) < 1e-4 * scale


def test_strong_mass_coupling_takes_the_full_step_basis_and_agrees():
    """A hard hit (v0 = -2 m/s, 8 modes): |q^T M_c q (M^-1)_00| exceeds FULL_FREEZE_MIN over much
    of the free flight, so those steps propagate the whole frozen rank-one coupling in the
    secular-equation basis; the deflection and the angle stay on the reference's."""
    from flexbeam.integrate.exponential import ModalIntegrator
    from flexbeam.integrate.exponential_kernels import FULL_FREEZE_MIN, _modal_model
    from flexbeam.model.system import BeamSystem

    case = seed(model__modes=8, initial__impact_velocity=-2.0, solver__t_end=0.02)
    ref, fast = _both(case)
    _agree(ref, fast, drift=1e-6)
    a, b = ref.to_xarray(), fast.to_xarray()
    integ = ModalIntegrator(BeamSystem.from_case(case))
    eta = np.column_stack([b.theta.values, b.q.values]) @ integ.lin[3].T
    coupling = np.abs(np.einsum("ij,ij->i", eta, eta @ _modal_model(integ.lin, integ.sysd)[1])) * integ.lin[5]
    assert np.mean(coupling > FULL_FREEZE_MIN) > 0.2  # the strong-coupling path is exercised
    scale = float(np.max(np.abs(a.tip_deflection)))
    assert abs(float(b.tip_deflection[-1] - a.tip_deflection[-1])) < 1e-6 * scale
    # measured 2.5e-9 rad of a 0.018 rad swing (5.3e-9 with only the diagonal frozen)
    assert abs(float(b.theta[-1] - a.theta[-1])) < 1e-6 * float(np.max(np.abs(a.theta)))


@pytest.mark.slow
def test_seed_experiment_full_run_agrees():
    """The seed case as published: 12 modes, 0.1 s, six contacts (the reference takes ~30 s)."""
    ref, fast = _both(seed())
    _agree(ref, fast, drift=1e-5)
    for a, b in list(zip(ref.contacts, fast.contacts, strict=True))[:4]:
        assert_allclose(b.onset, a.onset, rtol=0, atol=1e-7)
        assert_allclose(b.peak_force, a.peak_force, rtol=5e-4)


@pytest.mark.slow
def test_seed_experiment_ccm_full_run_agrees():
    """CCM on the seed case as published (12 modes, 0.1 s; the reference takes ~45 s).

    The contacts of the first 20 ms (eight, one grazing) agree; later on, grazing
    re-contacts (P released at rest on the surface) decide the sequence, which is
    ill-conditioned -- the reference at rtol 1e-8 and 1e-9 parts there too -- so only the
    first contacts, the first contact's metrics and the energy balance are compared.
    """
    ref, fast = _both(seed(), "ccm")
    assert fast.status == "success"
    a, b = ref.metrics(), fast.metrics()
    assert_allclose(b["peak_force"], a["peak_force"], rtol=5e-4)
    assert_allclose(b["contact_duration"], a["contact_duration"], rtol=1e-3)
    assert abs(b["energy_drift_max"]) < 1e-5
    early = [c for c in ref.contacts if c.onset < 0.02]
    assert len(early) >= 8
    for x, y in zip(early, fast.contacts[: len(early)], strict=True):
        assert_allclose(y.onset, x.onset, rtol=0, atol=1e-8)
        if x.duration > 0:
            assert_allclose(y.peak_force, x.peak_force, rtol=5e-4)


@pytest.mark.slow
def test_kane_spinup_full_run_agrees():
    case = fb.load_case("kane-spinup")
    ref, fast = _both(case)
    tip_ref = np.interp(fast.time, ref.time, ref["tip_deflection"])
    scale = np.max(np.abs(tip_ref))
    assert np.max(np.abs(fast["tip_deflection"] - tip_ref)) < 1e-4 * scale
    assert abs(fast.metrics()["energy_drift_max"]) < 1e-6
