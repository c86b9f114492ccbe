"""CCFM's resting contact (issue 25, item 3): a contact under its law that outlasts its impact by
RESTING_DURATIONS t_c rests, its step bound t_c / CONTACT_STEPS lifts (flexbeam.methods.base).

The seed beam (free joint, gravity) ends its bouncing at t = 0.71 s and rests on the sphere under its weight.  Its
static solution: the moments about O of the weight m g L / 2 (a uniform beam, theta ~ 0) and of the contact force at
x_P balance, F_s = m g L / (2 x_P), and the Hertz spring F = K d^n gives the penetration d_s = (F_s / K)^(1/n).  The
beam is not still: its first bending mode pinned at O and propped at P (166 Hz) rings with a damping ratio ~1e-3
(the contact point is near its node, the contact's dashpot barely damps it), the force +-5 % about F_s at t = 3 s.
Once resting, the contact collocates at Radau IIA's nodes (kernels/src/propagation.c, fb_radau): the contact spring's
own mode (1.4 kHz), which the resting steps do not resolve, is damped in the end state instead of flooring the step.
"""

import math

import numpy as np
import pytest

import flexbeam as fb
import flexbeam.methods.base as base
from flexbeam.integrate.dense import RADAU_WEIGHTS, gauss_nodes, radau_steps

T_END = 3.0
WINDOW = (2.9, 3.0)  # the mean over 16.6 periods of the 166 Hz ringing


def _run(resting: float, overrides: dict | None = None, t_end: float = T_END):
    old = base.RESTING_DURATIONS
    base.RESTING_DURATIONS = resting
    try:
        ov = {"solver.t_end": t_end, "solver.memory_limit": 2e10, **(overrides or {})}
        case = fb.load_case("seed-experiment", ov)
        return fb.simulate(case, "ccfm")
    finally:
        base.RESTING_DURATIONS = old


@pytest.fixture(scope="module")
def runs():
    return _run(base.RESTING_DURATIONS), _run(math.inf)


def _resting_segment(sol):
    seg = sol.source.run.segments[-1]
    assert seg.phase.name == "contact" and seg.t0 < 1.0  # one contact from the end of the bouncing to t_end
    return seg


def _steps_between(seg, a, b):
    t = seg.dense.records[:, 0]
    return int(np.count_nonzero((t >= a) & (t < b)))


def static_force(case) -> float:
    """F_s = m g L / (2 x_P): the contact force that holds the uniform beam, pinned at O, level on the stop at x_P."""
    b = case.beam
    m = b.density * math.pi * b.radius**2 * b.length
    return m * case.model.gravity * b.length / (2.0 * case.contact.position)


def test_rest_is_the_static_solution(runs):
    """Mean force and penetration over WINDOW equal F_s and d_s.  Tolerance 0.5 %: the mean of a ringing of relative
    amplitude a = 0.05 over a window of w T = 105 rad differs from its centre by <= 2 a / (w T) = 0.1 %, the Hertz
    curvature shifts the mean force by (3/16) a^2 = 0.05 %, the moment arms change by O(theta^2, w'^2) < 1e-8."""
    sol, _ = runs
    seg = _resting_segment(sol)
    F_s = static_force(fb.load_case("seed-experiment"))
    K, n = seg.phase.parameters[0][:2]
    d_s = (F_s / K) ** (1.0 / n)
    rec = seg.dense.records
    inside = (rec[:, 0] >= WINDOW[0]) & (rec[:, 0] + rec[:, 1] <= WINDOW[1])
    _, w = gauss_nodes()
    w = np.where(radau_steps(rec)[inside, None], RADAU_WEIGHTS[None, :], w[None, :])  # each step's own quadrature
    F_nodes = seg.dense._forces(0)[inside]
    h = rec[inside, 1]
    F_mean = float(np.sum(h * np.sum(F_nodes * w, axis=1)) / np.sum(h))
    times = np.linspace(*WINDOW, 2001)
    cols, _, _ = sol.source.system.outputs(times, seg.states(times), seg.phase.buffer)
    d_mean = -float(np.mean(cols["gap"]))
    assert F_mean == pytest.approx(F_s, rel=5e-3)
    assert d_mean == pytest.approx(d_s, rel=5e-3)


def test_same_answer_as_the_bounded_steps(runs):
    """At t_end the force, tip deflection and hub angle of the run with the lifted bound match the run that keeps
    t_c / CONTACT_STEPS to the whole contact: both are error-controlled to fast_rtol = 1e-6 (measured: 1.5e-5 N of
    7.8 N, 7e-12 m, 1.1e-11 rad); the tolerances are 1e-4 of the static force, 1e-9 m and 1e-9 rad (50-135x)."""
    ends = []
    for sol in runs:
        seg = _resting_segment(sol)
        assert seg.t1 == T_END
        cols, _, _ = sol.source.system.outputs(np.array([seg.t1]), seg.y1[None, :], seg.phase.buffer)
        ends.append({k: v[0] for k, v in cols.items()})
    a, b = ends
    assert a["contact_force"] == pytest.approx(b["contact_force"], abs=7.5e-4)
    assert a["tip_deflection"] == pytest.approx(b["tip_deflection"], abs=1e-9)
    assert a["theta"] == pytest.approx(b["theta"], abs=1e-9)
    assert len(runs[0].source.run.segments) == len(runs[1].source.run.segments)


def test_resting_takes_fewer_steps(runs):
    """From t = 2 s the bounded run takes 1 / (t_c / 8) = 14 200 steps per second; the error control alone ~2 500
    (resolving the 166 Hz ringing, 0.56 N at 2-3 s): asserted >= 4x fewer."""
    on, off = (_resting_segment(s) for s in runs)
    n_on, n_off = _steps_between(on, 2.0, 3.0), _steps_between(off, 2.0, 3.0)
    assert n_off > 13000
    assert n_on * 4 < n_off


def test_a_resting_contact_collocates_at_radau_nodes(runs):
    """The lifted run's steps are Gauss's up to the time the bound lifts (the phase's max_step_until, 20 t_c after
    the onset) and Radau's from there, its first Radau step starting there; the bounded run takes no Radau step."""
    on, off = (_resting_segment(s) for s in runs)
    rec = on.dense.records
    radau = radau_steps(rec)
    until = on.phase.max_step_until
    assert on.t0 < until < 1.0
    assert not radau[rec[:, 0] < until].any() and radau[rec[:, 0] >= until].all()
    assert rec[radau][0, 0] == until
    assert not radau_steps(off.dense.records).any()


def test_at_rest_radau_steps_are_ten_times_fewer_and_static():
    """20 s of the seed beam: by 15 s its ringing has decayed to ~1e-5 N, and the resting contact takes fewer than a
    tenth of the bounded run's 1 / (t_c / 8) = 14 200 steps per second (issue 25's target; measured 531, 27x; the
    Gauss nodes' floor was ~1 800, 7.9x, whatever the ringing: docs/performance.md, "A resting contact").  At
    t_end the force and penetration are the static solution's, F_s and d_s, within 5e-5 (measured 4.0e-6 and
    2.2e-6: the ringing's remainder), and the energy balance holds as on the Gauss steps (4.3e-7 both)."""
    sol = _run(base.RESTING_DURATIONS, t_end=20.0)
    seg = _resting_segment(sol)
    assert seg.t1 == 20.0
    bounded_rate = 1.0 / seg.phase.max_step
    assert bounded_rate > 13000
    assert _steps_between(seg, 15.0, 20.0) / 5.0 < 0.1 * bounded_rate
    F_s = static_force(fb.load_case("seed-experiment"))
    K, n = seg.phase.parameters[0][:2]
    cols, _, _ = sol.source.system.outputs(np.array([seg.t1]), seg.y1[None, :], seg.phase.buffer)
    assert cols["contact_force"][0] == pytest.approx(F_s, rel=5e-5)
    assert -cols["gap"][0] == pytest.approx((F_s / K) ** (1.0 / n), rel=5e-5)
    assert abs(sol.metrics()["energy_drift_max"]) < 4.3e-6


def test_rest_then_lift_off_separates_on_time():
    """The beam clamped to a hub turning up at Omega = 1e-4 rad/s falls on the sphere, rests there from 0.065 s and
    is lifted off: the contact ends where the rigid lift Omega t x_P has taken up the clamped beam's static sag at P
    (quasi-static: the lift is 6e-5 m/s), at the same time as with the bounded steps (to 1e-4 s: 6e-9 m of lift)."""
    ov = {"drive.kind": "prescribed", "drive.profile": "constant-rate", "drive.spin_rate": 1e-4,
          "initial.kind": "state", "initial.angle": 1e-4}  # fmt: skip
    ends = []
    for resting in (base.RESTING_DURATIONS, math.inf):
        sol = _run(resting, ov, t_end=2.5)
        run = sol.source.run
        rest = max(run.segments, key=lambda s: s.t1 - s.t0 if s.phase.name == "contact" else 0.0)
        assert rest.t1 - rest.t0 > 1.5 and run.segments[-1].phase.name == "free"
        ends.append(rest.t1)
    assert ends[0] == pytest.approx(ends[1], abs=1e-4)
    # the quasi-static separation: the lift (theta_0 + Omega t) x_P equals the sag w_P of the beam clamped at the hub
    # under its weight, w_P = q x^2 (6 L^2 - 4 L x + x^2) / (24 E I) (Euler-Bernoulli; the 12 modes' to 1e-3)
    c = fb.load_case("seed-experiment")
    b = c.beam
    A, inertia = math.pi * b.radius**2, math.pi * b.radius**4 / 4.0
    x, L = c.contact.position, b.length
    w_P = b.density * A * c.model.gravity * x**2 * (6 * L**2 - 4 * L * x + x**2) / (24.0 * b.youngs_modulus * inertia)
    t_sep = (w_P / x - 1e-4) / 1e-4
    assert ends[0] == pytest.approx(t_sep, rel=2e-2)


def test_the_bound_stays_lifted_in_a_phase_a_friction_event_starts_later():
    """The seed beam under the stiff linear Kelvin-Voigt law (t_c = 14.5 us at its last onset, the bound t_c / 8 =
    1.8 us) with mu = 0.3: its last contact starts at 0.248 s and rests; its stick, entered at 0.297 s (a friction
    event: a new phase of the same contact, well past the 20 t_c at which the bound lifted), used to take the bound
    again to t_end -- 552 000 steps per second.  Its steps are now the error control's: median >= 4x the bound
    (measured 8.5x)."""
    case = fb.load_case(
        "seed-experiment",
        {"solver.t_end": 0.5, "contact.law": "kelvin_voigt", "contact.restitution": 0.6, "contact.friction": 0.3},
    )
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    last = sol.source.run.segments[-1]
    assert last.phase.friction is not None and last.t0 > last.phase.max_step_until
    assert np.median(last.dense.records[:, 1]) >= 4.0 * last.phase.max_step
