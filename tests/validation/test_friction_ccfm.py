"""Coulomb friction under CCFM (issue 28): slip, stop, stick and unstick as located events, against closed forms.

**A bar sliding to rest.**  The rigid steel bar of ``test_free_beam_two_stops.py`` (``joint.kind = "free"``, no
modes, 20 cm, 12.7 mm across) lies horizontal on two identical hemispherical stops beneath its material points
x = L/2 -+ a L, under gravity g, and slides along its axis at v0.  Both contacts slip in the same direction, so the
friction forces are -mu_k F_1 and -mu_k F_2 along the bar and G's momentum balances read

    m (v_x(t) - v0) = -mu_k int_0^t (F_1 + F_2) dt,      m (v_y(t) - v_y(0)) = int_0^t (F_1 + F_2) dt - m g t

(the stops' normals vertical; the friction's moment about G, mu_k (F_1 + F_2) c, only shares the load unequally
between the stops).  Eliminating the normal impulse, v_x(t) = v0 - mu_k (g t + v_y(t) - v_y(0)): the slip stops at

    T = (v0 / mu_k - v_y(T) + v_y(0)) / g,

exactly as long as the normals stay vertical, and G has slid d = int_0^T v_x dt = v0^2 / (2 mu_k g) - mu_k int_0^T
(v_y - v_y(0)) dt.  The bar, started touching, settles on the stops and bounces a little while it slides; the terms
in v_y carry that.  The neglected ones are the normals' tilt: the bar turns by at most theta_max during the slide,
tilting each normal by as much and adding at most theta_max (F_1 + F_2) along the bar and mu_k theta_max
(F_1 + F_2) across it, so T and d are as above to within a relative theta_max (1/mu_k + mu_k) (the test bounds it by
twice that).  At T the slip stops as a located event (it is never stepped over) and the bar sticks: both points lie
on one rigid line, so the second stop follows the first's multiplier (:func:`flexbeam.methods.coulomb.grouped`).

**Stick on an incline.**  The same bar resting on two stops along a line inclined at alpha: the tangential load
m g sin(alpha) and the normal load m g cos(alpha) leave it at rest for tan(alpha) < mu_s.  It settles (slips a little
while the normal forces ring), then sticks: its contact points creep less than 1e-9 m over 1 s (the slip velocity
integrated on the dense output).

Steeper than the friction angle (tan(alpha) > mu_s) the same bar's stick ends as its normal forces build up, and it
slides down at v_d(t) = g t (sin(alpha) - mu_k cos(alpha)) - mu_k (v_n(t) - v_n(0)) (the momentum balances along and
across the incline), within the same tilt bound.

**Rough ground, stiff contact vs IMM.**  The rigid line bar of ``test_friction_impact.py`` strikes rough ground: CCFM
with an elastic Hertz contact (no tangential compliance) and Coulomb friction against IMM's Stronge process with
e = 1.  Both integrate the same slip/stick process over the normal impulse; they differ only by the bar's motion
during the contact, which turns it by omega t_c and changes its inverse mass matrix to first order in that angle, so
the velocities after agree to within (omega t_c) v0 -- and the difference shrinks as the contact stiffens.

**Friction power.**  F_t v_t <= 0 at every step's nodes of every run here, but for the stick's residual: a slipping
pair's kinetic force opposes its slip velocity (its sign is fixed for the phase and the slip ends at the located
stop), except that a slip starting from rest (a stick that ended) may run back by its start's residual before its
stop fires; a sticking pair's multiplier works only on that residual slip velocity, which is the kernel's rest noise
(1e-9 m/s) plus the integrator's velocity error (:func:`friction_power`).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.contact.laws import threlfall
from flexbeam.errors import ModelError
from flexbeam.integrate.phases import ContactMode
from flexbeam.model.system import BeamSystem
from flexbeam.validation import bars

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_impact import after, rough_bar  # noqa: E402

STEEL = bars.STEEL_BAR
A, R_STOP, G = 0.3, 0.01, 9.81
#: the kernel's stick noise: the slip velocity a stick holds to, and a slip starting from rest may run back (m/s)
VT_NOISE = 1e-9


def bar_on_stops(mu: float, v0: float, t_end: float, alpha: float = 0.0, mu_s: float | None = None) -> fb.Case:
    """The rigid bar with G at (0, 0.1 m) and its axis at ``alpha``, touching two stops beneath x = L/2 -+ a L, moving
    along its axis at ``v0``; Coulomb friction mu_k = ``mu`` (mu_s = ``mu_s``, default mu)."""
    d, v = A * STEEL["length"], (v0 * math.cos(alpha), v0 * math.sin(alpha))
    mu_s = mu if mu_s is None else mu_s
    return bars.bar_on_stops([-d, d], v, mu=mu, mu_s=mu_s, angle=alpha, t_end=t_end, stop_radius=R_STOP)


def states(sol, times: np.ndarray) -> np.ndarray:
    """The run's states at sorted ``times`` (each in the first segment holding it)."""
    out = np.empty((times.size, sol.source.run.segments[0].y0.size))
    for seg in sol.source.run.segments:
        inside = (times >= seg.t0) & (times <= seg.t1)
        if inside.any():
            out[inside] = seg.states(times[inside])
    return out


def creep(sol, system: BeamSystem, t0: float, t1: float) -> list[float]:
    """Each pair's creep over [t0, t1] [m]: its slip velocity integrated by Simpson's rule on 20001 samples of the
    dense output."""
    from scipy.integrate import simpson

    t = np.linspace(t0, t1, 20001)
    y = states(sol, t)
    return [
        float(simpson(np.array([system.tangent(ti, yi, k)[2] for ti, yi in zip(t, y)]), x=t))
        for k in range(system.pairs)
    ]


def nodal_friction(sol, system: BeamSystem):
    """Yield (friction row, F, lambda, v_t, t) of every frictional pair in every phase at the steps' Gauss nodes inside
    the phase: the kernel's nodal normal forces F and tangential unknowns lambda (a stick's multiplier, the
    regularised law's force) from the step records, v_t from the dense output's states."""
    c = np.array([0.5 - math.sqrt(525 + 70 * math.sqrt(30)) / 70, 0.5 - math.sqrt(525 - 70 * math.sqrt(30)) / 70])
    c = np.concatenate((c, 1.0 - c[::-1]))
    for seg in sol.source.run.segments:
        fr, dense = seg.phase.friction, seg.dense
        if fr is None or dense is None:
            continue
        N, S = dense.stepper.basis.N, system.pairs
        recs = dense.records
        t = (recs[:, 0:1] + recs[:, 1:2] * c[None, :]).ravel()
        inner = (t > seg.t0) & (t < seg.t1)
        y = seg.dense(t[inner])
        for k in range(S):
            if seg.phase.modes[k] == ContactMode.NONE or not (fr[k, 0] or fr[k, 1] == 1.0):  # CCFM's or CCM's
                continue
            F = recs[:, 4 + 6 * N + 4 * k : 4 + 6 * N + 4 * k + 4].ravel()[inner]
            lam = recs[:, 4 + 6 * N + 4 * S + 8 + 4 * k : 4 + 6 * N + 4 * S + 8 + 4 * k + 4].ravel()[inner]
            vt = np.array([system.tangent(ti, yi, k)[2] for ti, yi in zip(t[inner], y)])
            yield fr[k], F, lam, vt, t[inner]


def friction_power(sol, system: BeamSystem, rtol: float = 1e-6) -> list[tuple[float, float, float]]:
    """(F_t v_t, its allowance, t) of every frictional pair at every step's Gauss nodes: F_t = sigma F (slip), the
    nodal tangential unknown (the regularised law's force, solved with the normal forces) or lambda_t (stick).  The
    allowance abs(F_t) (VT_NOISE + 25 rtol V) admits the stick's residual slip velocity: the kernel's rest noise, and
    the integrator's velocity error, rtol of the run's speed scale V (the largest slip or approach speed; measured up
    to 2.5 rtol V on the flexible runs here, falling with rtol: integration error)."""
    rows, V = [], max((abs(c.velocity_before) for c in sol.contacts), default=0.0)
    for row, F, lam, vt, t in nodal_friction(sol, system):
        # the regularised law ([mu_k, -1, v_0]): its force is the kernel's nodal tangential unknown, lam
        rows.append((lam if row[1] < 0.0 else row[0] * F + lam, vt, t))
        V = max(V, float(np.max(np.abs(vt), initial=0.0)))
    noise = VT_NOISE + 25.0 * rtol * V
    return [(float(f * v), float(abs(f) * noise), float(ti)) for Ft, vt, t in rows for f, v, ti in zip(Ft, vt, t)]


@pytest.mark.parametrize("mu", [0.3, 0.6])
def test_a_bar_sliding_on_two_stops_stops_at_the_closed_form(mu):
    """The slip's stop time T and G's slide d against the module docstring's momentum balance, within the bound
    2 theta_max (1/mu_k + mu_k) on the normals' tilt; then the bar sticks (both pairs, one holding) till t_end."""
    v0 = 0.1
    T0 = v0 / (mu * G)
    case = bar_on_stops(mu, v0, 1.5 * T0)
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    segs = sol.source.run.segments
    slip_end = [s.t1 for s in segs if s.phase.friction is not None and s.phase.friction[0, 0] != 0.0][-1]
    stuck = [s for s in segs if s.t0 >= slip_end]
    assert stuck and all(s.phase.friction is not None and (s.phase.friction[:, 1] != 0.0).all() for s in stuck)
    t = np.linspace(0.0, slip_end, 4001)
    y = states(sol, t)
    vy0, vyT = y[0, 4], y[-1, 4]
    theta_max = float(np.max(np.abs(y[:, 2])))
    rel = 2.0 * theta_max * (1.0 / mu + mu)
    T = (v0 / mu - vyT + vy0) / G
    assert abs(slip_end - T) <= rel * T, (slip_end, T, rel)
    d = v0**2 / (2.0 * mu * G) - mu * np.trapezoid(y[:, 4] - vy0, t)
    quad = np.max(np.abs(np.diff(y[:, 4]))) * slip_end  # the trapezoidal rule's error bound on the v_y term
    assert abs((y[-1, 0] - y[0, 0]) - d) <= rel * d + mu * quad, (y[-1, 0], d)
    assert abs(y[-1, 3]) <= 1e-6 * v0  # at rest along the bar at the located stop
    assert max(p - a for p, a, _ in friction_power(sol, BeamSystem.from_case(case))) <= 0.0


def test_a_bar_on_an_incline_below_the_friction_angle_sticks():
    """tan(alpha) = 0.1 < mu_s = 0.3: after it settles (t > 0.2 s) the contact points creep less than 1e-9 m over
    1 s (the slip velocity integrated by Simpson's rule on 20001 samples of the dense output)."""
    case = bar_on_stops(0.2, 0.0, 1.2, alpha=math.atan(0.1), mu_s=0.3)
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    system = BeamSystem.from_case(case)
    assert max(abs(c) for c in creep(sol, system, 0.2, 1.2)) < 1e-9
    assert max(p - a for p, a, _ in friction_power(sol, system)) <= 0.0


def test_a_sticking_group_reports_each_pair_within_its_cone():
    """The rigid bar set down on an incline, tan(alpha) = 0.4 < mu_s = 0.5, mu_k = 0.45: while its contacts ring it
    slips and sticks, both stops held by one multiplier when they stick together (a group,
    :func:`flexbeam.methods.coulomb.grouped`).  Each stop's reported friction is its share in proportion to the normal
    forces (:mod:`flexbeam.results.friction`), so abs(F_t) / F is the group's and within mu_s at every sticking
    sample -- but for the stick's end, located on the nodal values where the samples read the interpolants (measured
    1.4e-4 relative above mu_s; bound 1.5e-3).  Written whole to the holder before: 0.93 there, 0 at the follower."""
    case = bar_on_stops(0.45, 0.0, 0.05, alpha=math.atan(0.4), mu_s=0.5)
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    F, Ft, state = sol["pair_contact_force"], sol["pair_tangential_force"], sol["pair_friction_state"]
    both = (state == 2.0).all(axis=1) & (F > 0.0).all(axis=1)
    assert both.sum() > 1000  # (both stick in 109 k of the 250 k samples)
    assert np.all(np.abs(Ft[both]) <= 0.5 * (1.0 + 1.5e-3) * F[both])


def test_a_bar_on_an_incline_above_the_friction_angle_unsticks_and_slides():
    """tan(alpha) = 0.5 > mu_s = 0.3: the bar set down on the incline starts sticking (at rest, lying along the
    incline: W_tn = 0), its stick ends as soon as the normal forces build up, and it slides down.  Along the bar's
    axis d (downhill) and across it, the momentum balances give, as for the sliding bar above,
    v_d(t) = g t (sin(alpha) - mu_k cos(alpha)) - mu_k (v_n(t) - v_n(0)), to within the normals' tilt
    2 theta_max (1/mu_k + mu_k) relative (theta_max: the bar's turn off the incline)."""
    alpha, mu = math.atan(0.5), 0.2
    sol = fb.simulate(bar_on_stops(mu, 0.0, 0.05, alpha=alpha, mu_s=0.3), "ccfm")
    assert sol.status == "success", sol.message
    rows = [s.phase.friction for s in sol.source.run.segments if s.phase.friction is not None]
    assert rows[0][0, 1] > 0.0 and rows[-1][0, 0] != 0.0  # it stuck first, it slips at the end
    t = np.linspace(0.0, 0.05, 2001)
    y = states(sol, t)
    ca, sa = math.cos(alpha), math.sin(alpha)
    v_d = -(y[:, 3] * ca + y[:, 4] * sa)
    v_n = -y[:, 3] * sa + y[:, 4] * ca
    closed = G * t * (sa - mu * ca) - mu * (v_n - v_n[0])
    theta_max = float(np.max(np.abs(y[:, 2] - alpha)))
    assert abs(v_d[-1] - closed[-1]) <= 2.0 * theta_max * (1.0 / mu + mu) * closed[-1], (v_d[-1], closed[-1])


@pytest.mark.parametrize(("angle", "mu"), [(45.0, 0.1), (45.0, 2.0), (20.0, 0.3), (70.0, 0.5)])
def test_stiff_frictional_contact_agrees_with_stronges_impact(angle, mu):
    """Rough ground (test_friction_impact.py's rigid bar dropped straight): CCFM with an elastic Hertz contact and
    Coulomb friction leaves G's velocity and the spin of IMM's Stronge process with e = 1 to within omega t_c v0
    (module docstring; omega the larger spin, t_c the contact's duration); a contact 100 times stiffer comes closer."""
    case = rough_bar(angle, mu, 1.0)
    imm = after(fb.simulate(case, "imm"))
    diffs = []
    for K in (1e10, 1e12):
        stiff = fb.load_case(case.model_dump(), {"contact.stiffness": K})
        sol = fb.simulate(stiff, "ccfm")
        assert sol.status == "success", sol.message
        ev = sol.contacts[0]
        got = after(sol)
        L = 0.5
        scale = max(abs(got[2]), abs(imm[2])) * (ev.end - ev.onset)
        diff = np.abs(got - imm) * np.array([1.0, 1.0, 0.5 * L])  # the spin as the end's speed
        assert diff.max() <= scale * 1.0, (diff, scale)
        diffs.append(diff.max())
        assert max(p - a for p, a, _ in friction_power(sol, BeamSystem.from_case(stiff))) <= 0.0
    assert diffs[1] < 0.5 * diffs[0]


def test_outputs_and_the_contact_records_tangential_impulse(tmp_path):
    """The Dataset holds each pair's tangential force, slip velocity and friction state (with units); a contact that
    slips throughout (rough_bar at 45 degrees, mu = 0.1: slip in one direction) has the tangential impulse sigma P
    (its normal impulse P, sigma = -mu_k sign(v_t)) to round-off, and it matches IMM's within the impact test's
    bound; the result file keeps them."""
    case = rough_bar(45.0, 0.1, 1.0)
    sol = fb.simulate(case, "ccfm")
    ev = sol.contacts[0]
    sigma = next(s.phase.friction[0, 0] for s in sol.source.run.segments if s.phase.friction is not None)
    assert abs(sigma) == 0.1
    assert ev.tangential_impulse == pytest.approx(sigma * ev.impulse, rel=1e-12)
    imm = fb.simulate(case, "imm").contacts[0]
    assert abs(ev.tangential_impulse - imm.tangential_impulse) <= 0.1 * abs(imm.tangential_impulse)
    ds = sol.to_xarray()
    assert ds["pair_tangential_force"].attrs["units"] == "N"
    assert ds["pair_slip_velocity"].attrs["units"] == "m/s"
    state = ds["pair_friction_state"].values[:, 0]
    force = ds["contact_force"].values  # one pair: its force is the case's contact force
    slipping = state == 1.0
    assert slipping.any() and np.allclose(ds["pair_tangential_force"].values[slipping, 0], sigma * force[slipping])
    # against the friction force, but for the dense output's error at the onset from rest (the slip starts at v_t = 0
    # under a force growing as d^1.5): the integrator's relative tolerance (fast_rtol = 1e-6) of the 1 m/s impact
    assert np.all(ds["pair_slip_velocity"].values[slipping, 0] * np.sign(sigma) <= 1e-6 * 1.0)
    path = tmp_path / "rough.nc"
    sol.to_xarray().to_netcdf(path)
    import xarray as xr

    with xr.open_dataset(path) as back:
        assert "pair_friction_state" in back and "contact_tangential_impulse" in back


FREE_BAR = Path(__file__).parent / "data" / "free-bar-drop.toml"


@pytest.mark.parametrize(
    ("case", "overrides"),
    [
        (str(FREE_BAR), {"contact.friction": 0.3}),
        (str(FREE_BAR), {"contact.friction": 0.3, "contact.friction_static": 0.5, "initial.impact_angle": 1.2}),
        ("two-stops", {"contact.friction": 0.5}),
        ("seed-experiment", {"contact.friction": 0.3, "solver.t_end": 0.02}),
        ("seed-experiment", {"contact.friction": 0.3, "solver.t_end": 0.02, "contact.friction_model": "threlfall"}),
    ],
)
def test_flexible_beams_with_friction_book_their_energy(case, overrides):
    """Flexible beams (8-12 modes) slipping, sticking and ringing against their stops: each run reaches t_end, its
    energy balance T + V + U_c + E_d - W (friction's dissipation in E_d) drifts within test_energy.py's bounds (1e-5 at
    the default tolerance, 1e-9 at fast_rtol = 1e-10: then the bookkeeping, not the integration, would show), and its
    friction power is <= 0 at every step's nodes."""
    for extra, bound in (({}, 1e-5), ({"solver.fast_rtol": 1e-10, "solver.fast_atol": 1e-13}, 1e-9)):
        run = fb.load_case(case, {**overrides, **extra})
        sol = fb.simulate(run, "ccfm")
        assert sol.status == "success", sol.message
        end, worst = sol.energy_drift()
        assert abs(end) < bound and worst < bound, (extra, end, worst)
        rtol = run.solver.fast_rtol
        assert max(p - a for p, a, _ in friction_power(sol, BeamSystem.from_case(run), rtol)) <= 0.0


@pytest.mark.parametrize("v0", [1e-3, 1e-4])
def test_threlfalls_regularised_law_creeps_at_its_closed_form_speed(v0):
    """``contact.friction_model = "threlfall"`` (Threlfall 1978): no stick, so the bar on the incline of the stick test
    creeps.  Both points slip at the same v_t and carry m g sin(alpha) on m g cos(alpha), so mu_k (1 - exp(-3 v / v_0))
    = tan(alpha): v = -(v_0 / 3) ln(1 - tan(alpha) / mu_k).  The normal forces still ring about their static values
    and the law is nonlinear in v, so the mean slip speed over [0.1, 0.3] s departs from v by the square of the
    ringing's relative amplitude (vmax - vmin) / (vmax + vmin) at most (measured: 1/15 of that)."""
    from scipy.integrate import simpson

    mu, tan_a = 0.2, 0.1
    base = bar_on_stops(mu, 0.0, 0.3, alpha=math.atan(tan_a), mu_s=0.3).model_dump()
    case = fb.load_case(base, {"contact.friction_model": "threlfall", "contact.friction_velocity": v0})
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    system = BeamSystem.from_case(case)
    t = np.linspace(0.1, 0.3, 4001)
    y = states(sol, t)
    vt = np.array([system.tangent(ti, yi, 0)[2] for ti, yi in zip(t, y)])
    v = -(v0 / 3.0) * math.log(1.0 - tan_a / mu)
    mean = simpson(vt, x=t) / (t[-1] - t[0])
    ringing = (vt.max() - vt.min()) / (vt.max() + vt.min())
    assert abs(mean / v - 1.0) <= ringing**2, (mean, v, ringing)
    assert max(p - a for p, a, _ in friction_power(sol, system)) <= 0.0


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
@pytest.mark.parametrize(
    "source",
    [("seed-experiment", {"contact.friction": 0.3, "solver.t_end": 0.02}), ("incline", {})],
    ids=["seed", "incline"],
)
def test_the_regularised_laws_nodal_force_is_the_law_at_the_nodes(source, rtol):
    """The kernel solves the regularised law's tangential force at the collocation nodes with the normal forces by
    Newton's method (kernels/src/nodal.c; fixed-point sweeps took 36 node evaluations a step on the seed case): at
    every step's Gauss nodes it equals mu_k (1 - exp(-3 abs(v_t) / v_0)) sign(v_t) F of Threlfall (1978), evaluated
    here on the dense output's state, within 0.3 rtol of the largest tangential force (measured 0.026 rtol at rtol
    1e-6 and 1e-10 on the seed case, 7e-4 rtol on the creeping bar: the sweeps stop at ITER_TOL = 1e-3 of the
    step's tolerance) -- the nodal force converges with the tolerance, as the integration does."""
    name, overrides = source
    if name == "incline":
        case = fb.load_case(bar_on_stops(0.2, 0.0, 0.1, alpha=math.atan(0.1), mu_s=0.3).model_dump(), {})
    else:
        case = fb.load_case(name, overrides)
    tight = {"solver.fast_rtol": rtol, "solver.fast_atol": rtol * 1e-3}
    case = fb.load_case(case.model_dump(), {"contact.friction_model": "threlfall", **tight})
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    worst, big = 0.0, 0.0
    for row, F, lam, vt, _ in nodal_friction(sol, BeamSystem.from_case(case)):
        law = threlfall(row[0], row[2], vt) * F
        worst, big = max(worst, float(np.max(np.abs(lam - law)))), max(big, float(np.max(np.abs(law))))
    assert big > 0.0 and worst <= 0.3 * rtol * big, (worst, big)


@pytest.mark.parametrize(
    ("setting", "field"),
    [
        ("contact.friction=-0.1", "contact.friction"),
        ("contact.friction_model=viscous", "contact.friction_model"),
        ("contact.friction_velocity=0", "contact.friction_velocity"),
    ],
)
def test_bad_friction_input_is_one_line_exit_2(setting, field):
    """The CLI names the field on one line and exits 2 (mu_k > mu_s: test_friction_impact.py)."""
    import subprocess

    r = subprocess.run(
        [sys.executable, "-m", "flexbeam.cli", "run", "seed-experiment", "--json", "--set", setting],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert r.returncode == 2 and len(r.stderr.splitlines()) == 1, r.stderr
    assert r.stderr.startswith(f"error: {field}"), r.stderr


def test_the_friction_figure(tmp_path):
    """``sol.plot("friction")`` draws each frictional pair's tangential force, its bounds and its slip velocity; a run
    without friction arrays is refused in one line."""
    import matplotlib

    matplotlib.use("Agg")
    sol = fb.simulate(bar_on_stops(0.3, 0.1, 0.01), "ccfm")
    assert sol.plot("friction", tmp_path / "friction.png").stat().st_size > 0
    held = fb.simulate(bar_on_stops(0.3, 0.1, 0.01), "ccm")  # (any method's frictional run; the refusal named CCFM)
    assert held.plot("friction", tmp_path / "held.png").stat().st_size > 0
    plain = fb.simulate(rough_bar(45.0, 0.0, 1.0), "ccfm")
    with pytest.raises(ValueError, match=r"contact.friction > 0 \(any method\)"):
        plain.plot("friction", tmp_path / "none.png")


@pytest.mark.parametrize("method", ["ccfm", "ccm"])
def test_a_streamed_run_writes_the_friction_variables(tmp_path, method):
    """A streamed frictional CCFM or CCM run (``stream=``) writes the friction variables as the in-memory run holds
    them: the state exactly, the force and slip velocity to the file's rounding (2^-24 of each value, nsb = 23)."""
    import xarray as xr

    case = fb.load_case("seed-experiment", {"contact.friction": 0.3, "solver.t_end": 0.02})
    fb.simulate(case, method, stream=tmp_path / "run.nc")
    mem = fb.simulate(case, method)
    with xr.open_dataset(tmp_path / "run.nc") as ds:
        assert np.array_equal(ds["pair_friction_state"].values, mem["pair_friction_state"])
        for name in ("pair_tangential_force", "pair_slip_velocity"):
            np.testing.assert_allclose(ds[name].values, mem[name], rtol=2.0**-24, atol=0.0)


def test_ccfm_friction_needs_the_exponential_integrator():
    case = fb.load_case(rough_bar(45.0, 0.3, 1.0).model_dump(), {"solver.integrator": "reference"})
    with pytest.raises(ModelError, match=r"^contact\.friction: CCFM's friction runs on the exponential"):
        fb.simulate(case, "ccfm")
