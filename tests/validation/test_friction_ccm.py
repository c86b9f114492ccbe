"""Coulomb friction under CCM (issue 28): held contacts that slip, stop, stick and unstick, and Painlevé's paradox.

**A bar sliding to rest.**  The rigid steel bar of ``test_friction_ccfm.py`` lies on two hemispherical stops and slides
along its axis at v0 under gravity.  CCM holds both gaps closed, so the bar neither bounces nor turns: the normals
stay vertical, the normal forces carry the weight, F_1 + F_2 = m g, and the kinetic friction -mu_k (F_1 + F_2)
decelerates G at mu_k g.  The slip stops (a located event) at T = v0 / (mu_k g) after G slid d = v0^2 / (2 mu_k g);
the friction's impulse over the contacts is m v0.  The integrator's relative tolerance ``solver.fast_rtol`` bounds the
relative error of v_x, so of T and d (plus the tilt bound 2 theta_max (1/mu_k + mu_k) of test_friction_ccfm.py, here
~0 since nothing turns).

**Incline.**  Along a line at alpha, held normals give the momentum balances exactly: at rest for tan(alpha) < mu_s
(a stick; its contact points creep less than 1e-9 m over 1 s), and sliding down at v_d = g t (sin(alpha) - mu_k
cos(alpha)) for tan(alpha) > mu_s (its stick ends at once: the bar lies along the incline, W_tn = 0, so the stick's
ratio lambda_t / lambda_n = tan(alpha)).

**CCM vs a stiff CCFM.**  The same incline slide under CCFM with a Hertz-type law of stiffness K: the bar settles
into its static compliance delta ~ (m g / K)^(2/3) while sliding, so its velocity and position differ from CCM's by
an amount that shrinks as K^(-2/3), by 10^(2/3) = 4.6 per decade (asserted: at least 3).

**Painlevé's rod.**  A uniform rigid rod (mass m, length 2 l, no thickness) touches the ground y = 0 with its end
P = G - l (cos th, sin th).  In the axes t = (-1, 0), n = (0, 1) its Jacobians over (x_G, y_G, th) are
J_t = (-1, 0, -l sin th), J_n = (0, 1, -l cos th), and with M = diag(m, m, m l^2 / 3)

    W_tt = (1 + 3 sin^2 th) / m,   W_nt = 3 sin th cos th / m,   W_nn = (1 + 3 cos^2 th) / m,

so a slip with s = sign(v_t) (friction -mu s lambda_n along t) has the effective inverse mass
a = W_nn - mu s W_nt = (1 + 3 cos^2 th - 3 mu s sin th cos th) / m.  With s = +1 (the end sliding away from the rod's
lean) a < 0 between the roots of tan^2 th - (3 mu / (1 - eps)) tan th + 4 = 0 wherever a = eps W_nn, i.e. for
mu = 1.5 and eps = 0 between th = 50.64 and 73.05 degrees.  CCM resolves the slip where a falls to eps W_nn,
eps = :data:`flexbeam.methods.painleve.SHARE` (a located event), by a tangential impact.
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.errors import FlexbeamWarning, ModelError
from flexbeam.methods import coulomb, painleve
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import initial_state

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_ccfm import STEEL, G, bar_on_stops, creep, friction_power, states  # noqa: E402

#: the exponential integrator's relative tolerance (solver.fast_rtol, default)
RTOL = 1e-6
DATA = Path(__file__).parent / "data"
MASS = STEEL["density"] * math.pi * STEEL["radius"] ** 2 * STEEL["length"]
ROD_L, ROD_MASS = 0.5, 7800.0 * 1e-4 * 0.5


def run(case: fb.Case, method: str = "ccm"):
    sol = fb.simulate(case, method)
    assert sol.status == "success", sol.message
    assert all(np.all(np.isfinite(np.asarray(v, float))) for k, v in sol.arrays.items() if k != "phase")
    return sol


def energy_drift(sol) -> float:
    """The largest change of the total energy T + V + E_d - W over the samples [J] (the energy balance)."""
    E = sol["total_energy"]
    return float(np.max(np.abs(E - E[0])))


@pytest.mark.parametrize("mu", [0.3, 0.6])
def test_a_bar_sliding_on_two_stops_stops_after_v0_squared_over_2_mu_g(mu):
    """The located stop at T = v0 / (mu_k g) and G's slide v0^2 / (2 mu_k g) within fast_rtol (plus the tilt bound);
    while it slips the collocated normal multipliers carry m g within fast_rtol and the Dataset's friction force is
    mu_k times its normal force;
    the records' tangential impulses add up to m v0; it then sticks (state 2) to the end; friction power <= 0."""
    v0 = 0.1
    T, d = v0 / (mu * G), v0**2 / (2.0 * mu * G)
    case = bar_on_stops(mu, v0, 1.5 * T)
    sol = run(case)
    segs = sol.source.run.segments
    slip_end = [s.t1 for s in segs if s.phase.friction is not None and s.phase.friction[0, 0] != 0.0][-1]
    assert all((s.phase.friction[:, 1] != 0.0).all() for s in segs if s.t0 >= slip_end)
    y = states(sol, np.linspace(0.0, slip_end, 401))
    rel = 2.0 * float(np.max(np.abs(y[:, 2]))) * (1.0 / mu + mu) + RTOL
    assert abs(slip_end - T) <= rel * T, (slip_end, T)
    assert abs((y[-1, 0] - y[0, 0]) - d) <= rel * d, (y[-1, 0] - y[0, 0], d)
    t, state = sol.time, sol["pair_friction_state"]
    slipping = (t > 0.0) & (t < slip_end)
    assert np.all(state[slipping] == 1.0) and np.all(state[t > slip_end] == 2.0)
    Fn, Ft = sol["pair_contact_force"][slipping], sol["pair_tangential_force"][slipping]
    np.testing.assert_array_equal(Ft, mu * Fn)  # kinetic friction against v_t < 0 (t = (-1, 0), v_x > 0)
    slip = [s for s in segs if s.t1 <= slip_end and s.dense is not None]
    carried = np.concatenate([s.dense.nodal_forces(0)[1] + s.dense.nodal_forces(1)[1] for s in slip])
    np.testing.assert_allclose(carried, MASS * G, rtol=RTOL)  # the collocated multipliers carry the weight
    assert sum(c.tangential_impulse for c in sol.contacts) == pytest.approx(MASS * v0, rel=RTOL)
    assert max(p - a for p, a, _ in friction_power(sol, BeamSystem.from_case(case))) <= 0.0
    # the energy balance: friction's dissipation booked (measured drift 1e-13 of 1/2 m v0^2; bound 1e3 x that)
    assert energy_drift(sol) <= 1e-10 * 0.5 * MASS * v0**2
    assert sol["dissipated_energy"][-1] == pytest.approx(0.5 * MASS * v0**2, rel=RTOL)


def test_a_bar_on_an_incline_below_the_friction_angle_stays_put():
    """tan(alpha) = 0.1 < mu_s = 0.3: the contact points creep less than 1e-9 m over 1 s (Simpson's rule on 20001
    samples of the slip velocity on the dense output); friction power <= 0; energy balance to 1e-7 m g L (3.9e-8 J;
    measured 5.7e-9 J at fast_rtol 1e-6, 3.8e-10 J at 1e-8: the held gaps' end-point error, which the stabilisation's
    work lambda delta', booked since 2026-11-26, now shows -- unbooked, the two cancelled to 2e-13 J, the former
    bound 1e-12 J)."""
    case = bar_on_stops(0.2, 0.0, 1.2, alpha=math.atan(0.1), mu_s=0.3)
    sol = run(case)
    system = BeamSystem.from_case(case)
    assert max(abs(c) for c in creep(sol, system, 0.2, 1.2)) < 1e-9
    assert np.all(sol["pair_friction_state"] == 2.0)
    assert max(p - a for p, a, _ in friction_power(sol, system)) <= 0.0
    assert energy_drift(sol) <= 1e-7 * MASS * G * STEEL["length"]


@pytest.mark.parametrize("method", ["ccm", "imm"])
def test_a_group_of_sticking_pairs_shares_its_friction_by_the_normal_forces(method):
    """The rigid bar at rest on an incline, tan(alpha) = 0.4 < mu_s = 0.5: both stops stick, one multiplier holds
    the group (their tangential rows are equal: :func:`flexbeam.methods.coulomb.grouped`).  Statics: the group's
    friction is m g sin(alpha) and its normal forces m g cos(alpha), so the share in proportion to the normal forces
    (:mod:`flexbeam.results.friction`) is F_t,i = -tan(alpha) F_i at each stop (t = (-1, 0) turned by alpha, the bar
    pulled down the incline), and each record's tangential impulse is -tan(alpha) times its normal impulse.  Written
    whole to the holder before: abs(F_t) / F = 0.77 there against mu_s = 0.5, 0 at the follower.  Measured 8.5e-11
    (samples: the collocated multipliers' error, the run held by them at fast_rtol) and 4.3e-15 (records); bounds 1e-8
    and 1e-12."""
    ta = 0.4
    sol = run(bar_on_stops(0.45, 0.0, 0.05, alpha=math.atan(ta), mu_s=0.5), method)
    F, Ft = sol["pair_contact_force"], sol["pair_tangential_force"]
    assert np.all(sol["pair_friction_state"] == 2.0) and np.all(F > 0.0)
    np.testing.assert_allclose(Ft / F, -ta, rtol=1e-8)
    assert sorted(c.pair for c in sol.contacts) == [0, 1]
    for c in sol.contacts:
        assert c.tangential_impulse == pytest.approx(-ta * c.impulse, rel=1e-12)


def test_a_bar_on_an_incline_above_the_friction_angle_slides_at_the_closed_form():
    """tan(alpha) = 0.5 > mu_s = 0.3: it slides down with the acceleration g (sin(alpha) - mu_k cos(alpha)): the
    velocity and distance after 0.05 s within fast_rtol; friction power <= 0; the work of gravity equals the kinetic
    energy gained plus friction's dissipation mu_k m g cos(alpha) x distance, within fast_rtol."""
    alpha, mu = math.atan(0.5), 0.2
    case = bar_on_stops(mu, 0.0, 0.05, alpha=alpha, mu_s=0.3)
    sol = run(case)
    acc = G * (math.sin(alpha) - mu * math.cos(alpha))
    y0, y1 = sol.source.run.segments[0].y0, sol.source.run.segments[-1].y1
    ca, sa = math.cos(alpha), math.sin(alpha)
    v_d, s_d = -(y1[3] * ca + y1[4] * sa), -((y1[0] - y0[0]) * ca + (y1[1] - y0[1]) * sa)
    assert v_d == pytest.approx(acc * 0.05, rel=RTOL)
    assert s_d == pytest.approx(0.5 * acc * 0.05**2, rel=RTOL)
    assert sol["dissipated_energy"][-1] == pytest.approx(mu * MASS * G * ca * s_d, rel=RTOL)
    assert max(p - a for p, a, _ in friction_power(sol, BeamSystem.from_case(case))) <= 0.0


def test_threlfalls_law_under_ccm_creeps_at_its_closed_form_speed():
    """contact.friction_model = "threlfall" on the incline tan(alpha) = 0.1 < mu_k = 0.2: the held bar creeps down at
    v = -(v_0 / 3) ln(1 - tan(alpha) / mu_k), where the regularised friction balances gravity's pull, within
    fast_rtol after 0.3 s (the approach to it decays at a rate ~ 3 mu_k g cos(alpha) / v_0 ~ 6e3 /s)."""
    alpha, mu, v0 = math.atan(0.1), 0.2, 1e-3
    overrides = {"contact.friction_model": "threlfall", "contact.friction_velocity": v0}
    sol = run(fb.load_case(bar_on_stops(mu, 0.0, 0.3, alpha=alpha).model_dump(), overrides))
    y = sol.source.run.segments[-1].y1
    v_d = -(y[3] * math.cos(alpha) + y[4] * math.sin(alpha))
    assert v_d == pytest.approx(-(v0 / 3.0) * math.log(1.0 - math.tan(alpha) / mu), rel=RTOL)


def test_ccm_and_a_stiffening_ccfm_converge_on_the_incline_slide():
    """The incline slide under CCFM with stiffness K = 1.16e8 ... 1.16e11 N/m^1.5 against CCM: the difference in G's
    downhill velocity and position after 0.05 s falls by at least 3 per decade of K (its static compliance's
    10^(2/3) = 4.6: measured 4.3-4.7), and is below 1e-7 relative at the stiffest."""
    alpha = math.atan(0.5)
    base = bar_on_stops(0.2, 0.0, 0.05, alpha=alpha, mu_s=0.3)
    ca, sa = math.cos(alpha), math.sin(alpha)

    def downhill(sol) -> np.ndarray:
        y = sol.source.run.segments[-1].y1
        return np.array([-(y[0] * ca + y[1] * sa), -(y[3] * ca + y[4] * sa)])

    ref = downhill(run(base))
    errors = []
    for K in (1.16e8, 1.16e9, 1.16e10, 1.16e11):
        sol = run(fb.load_case(base.model_dump(), {"contact.stiffness": K}), "ccfm")
        errors.append(np.abs(downhill(sol) - ref))
    errors = np.array(errors)
    assert np.all(errors[1:] * 3.0 <= errors[:-1]), errors
    assert errors[-1, 1] <= 1e-7 * abs(ref[1])


def painleve_rod(th_deg: float, mu: float, u: float, w: float, t_end: float = 0.04, model: str = "coulomb") -> fb.Case:
    """The uniform rigid rod of length 2 l = ROD_L (no thickness) touching the ground with its end x = 0 at angle
    ``th_deg``, that end sliding at (-u, 0) (away from the rod's lean: s = +1), spinning at ``w``; gravity, Coulomb
    friction mu (``model``: contact.friction_model)."""
    th, half = math.radians(th_deg), 0.5 * ROD_L
    return fb.load_case({
        "name": "painleve-rod",
        "beam": {"length": ROD_L, "density": 7800.0, "youngs_modulus": 200e9, "poisson_ratio": 0.3,
                 "section": "general", "area": 1e-4, "second_moment": 1e-9, "half_depth": 0.0},
        "joint": {"kind": "free"}, "model": {"modes": 0, "gravity": G},
        "obstacle": {"kind": "half-plane", "centre": [0.0, 0.0], "normal": [0.0, 1.0]},
        "contact": {"law": "hertz", "position": 0.0, "stiffness": 1e10, "side": "centre", "restitution": 0.0,
                    "friction": mu, "friction_static": mu, "friction_model": model},
        "initial": {"kind": "state", "position": [half * math.cos(th), half * math.sin(th)],
                    "velocity": [-u - w * half * math.sin(th), w * half * math.cos(th)], "angle": th, "rate": w},
        "solver": {"t_end": t_end},
    })  # fmt: skip


def rod_a(th: float, mu: float) -> float:
    """The module docstring's a = (1 + 3 cos^2 th - 3 mu sin th cos th) / m of the rod sliding with s = +1."""
    c, s = math.cos(th), math.sin(th)
    return (1.0 + 3.0 * c * c - 3.0 * mu * s * c) / ROD_MASS


@pytest.mark.parametrize("angle", [20.0, 50.0, 63.4, 80.0])
def test_the_rods_inverse_mass_is_the_closed_form(angle):
    """W of the rod against the module docstring's W_tt, W_nt, W_nn to 1e-12, so a = W_nn - mu W_nt is its a."""
    th = math.radians(angle)
    case = painleve_rod(angle, 1.0, 0.0, 0.0)
    system = BeamSystem.from_case(case)
    y = initial_state(system, case)[0]
    W = coulomb.inverse_mass(system, 0.0, y, [0])
    c, s = math.cos(th), math.sin(th)
    expected = np.array([[1 + 3 * s * s, 3 * s * c], [3 * s * c, 1 + 3 * c * c]]) / ROD_MASS
    np.testing.assert_allclose(W, expected, rtol=1e-12, atol=1e-12 * expected.max())
    assert painleve.slip_inverse_mass(system, 0.0, y, 0, -1.5)[0] == pytest.approx(rod_a(th, 1.5), rel=1e-12)


def kinetic_jump(sol, t: float) -> tuple[float, float]:
    """The kinetic energy just before and just after the jump at t (the segments ending and starting there)."""
    system = sol.source.system
    before = [s.y1 for s in sol.source.run.segments if s.t1 == t][0]
    after = [s.y0 for s in sol.source.run.segments if s.t0 == t][-1]
    return system.energies(t, before)["kinetic"], system.energies(t, after)["kinetic"]


def test_painleve_at_a_slips_start_is_resolved_by_a_tangential_impact():
    """The rod set down at 60 degrees (a = -0.51 1/kg < 0 for mu = 1.5), its end sliding away at 1 m/s: a warning
    naming Painlevé at t = 0, the slip stopped by a tangential impact that does not add kinetic energy, a finished
    run without NaN whose energy balance closes (1e-9 of the energy scale)."""
    assert rod_a(math.radians(60.0), 1.5) < 0.0
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sol = run(painleve_rod(60.0, 1.5, 1.0, 0.0))
    hits = [w for w in caught if issubclass(w.category, FlexbeamWarning) and "Painlevé" in str(w.message)]
    assert len(hits) == 1 and "t = 0 s" in str(hits[0].message)
    T0, T1 = kinetic_jump(sol, 0.0)
    assert T1 <= T0 * (1.0 + 1e-14)
    assert sol.contacts[0].tangential_impulse < 0.0  # along t = (-1, 0): against the slip v_t > 0
    assert energy_drift(sol) <= 1e-9 * max(T0, 1.0)


@pytest.mark.parametrize("model", ["coulomb", "threlfall"])
def test_painleve_reached_while_sliding_is_located_at_the_predicted_angle(model):
    """The rod starting at 48 degrees (a > 0), its end sliding away at 20 m/s and spinning up at 5 rad/s, reaches
    a = eps W_nn while sliding: the warning fires once, where the rod's angle is the root of
    (1 - eps)(1 + 3 cos^2 th) = 3 mu sin th cos th (to 1e-6 rad: the event is bisected to 1e-15 of its step on the
    integrator's dense output, whose angle error is fast_rtol-small), within eps W_nn / |da/dth| of a = 0's
    50.64 degrees; the tangential impact adds no kinetic energy; the run finishes, no NaN, energy balance to 1e-9.
    Threlfall's regularised law at this slip speed is Coulomb's to the last bit (1 - exp(-3 v_t / v_0) = 1 for
    v_t / v_0 = 2e4), so the same angle: its a = W_nn + sigma(v_t) W_nt was not watched before (found by a random
    hunt: the free bar's slip ran into a <= 0 unseen and ended in a step-size underflow, or ran through a = -0.05
    W_nn)."""
    mu, eps = 1.5, painleve.SHARE
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sol = run(painleve_rod(48.0, mu, 20.0, 5.0, model=model))
    hits = [w for w in caught if issubclass(w.category, FlexbeamWarning) and "Painlevé" in str(w.message)]
    assert len(hits) == 1
    t_hit = float(str(hits[0].message).split("t = ")[1].split(" s")[0])
    t_hit = min((s.t1 for s in sol.source.run.segments), key=lambda t: abs(t - t_hit))
    th = [s.y1[2] for s in sol.source.run.segments if s.t1 == t_hit][0]
    k = 3.0 * mu / (1.0 - eps)  # tan^2 - k tan + 4 = 0, the lower root
    predicted = math.atan(0.5 * (k - math.sqrt(k * k - 16.0)))
    assert th == pytest.approx(predicted, abs=1e-6)
    zero = math.atan(0.5 * (3.0 * mu - math.sqrt(9.0 * mu * mu - 16.0)))
    slope = abs(rod_a(zero + 1e-6, mu) - rod_a(zero - 1e-6, mu)) / 2e-6
    assert 0.0 < zero - th <= 2.0 * eps * (1.0 + 3.0 * math.cos(zero) ** 2) / ROD_MASS / slope
    T0, T1 = kinetic_jump(sol, t_hit)
    assert T1 <= T0 * (1.0 + 1e-14)
    assert energy_drift(sol) <= 1e-9 * T0


def test_ccm_friction_on_the_reference_integrator_is_refused_in_one_line():
    case = fb.load_case(bar_on_stops(0.3, 0.1, 0.01).model_dump(), {"solver.integrator": "reference"})
    with pytest.raises(ModelError, match=r"^contact\.friction: CCM's friction runs on the exponential") as err:
        fb.simulate(case, "ccm")
    assert "\n" not in str(err.value)


PRESCRIBED = {"drive.kind": "prescribed", "drive.profile": "constant-rate", "drive.spin_rate": -1.0}


@pytest.mark.parametrize(("method", "mu", "drive"), [("ccm", 0.1, {}), ("ccm", 0.3, {}), ("ccm", 0.3, PRESCRIBED),
                                                     ("ccfm", 0.3, PRESCRIBED)])  # fmt: skip
def test_friction_on_a_compliant_support_keeps_each_contact_in_coulombs_cone(method, mu, drive):
    """The calibrated sensor under friction, theta free or prescribed, runs on the exponential integrator now that
    held phases against a compliant support and a compliant support with theta(t) prescribed do (both were refused
    in one line, friction not running on the reference integrator): each contact's tangential impulse within mu of
    its normal one (Coulomb's cone; a contact that slips throughout is at mu exactly), the energy balance closed
    (drift < 5e-6 of the energy; measured 2.7e-8 to 4.7e-7)."""
    case = fb.load_case("seed-experiment-calibrated", {"contact.friction": mu, "solver.t_end": 0.02, **drive})
    sol = run(case, method)
    assert sol.status == "success" and "exponential" in sol.provenance["integrator"]
    assert len(sol.contacts) >= 1
    for c in sol.contacts:
        assert abs(c.tangential_impulse) <= mu * c.impulse * (1.0 + 1e-9)
    assert abs(sol.metrics()["energy_drift_max"]) < 5e-6


def test_the_cli_refuses_ccm_friction_on_the_reference_integrator_in_one_line():
    """Through the real CLI: exit 2, one stderr line starting with the field, no traceback."""
    import subprocess

    r = subprocess.run(
        [sys.executable, "-m", "flexbeam.cli", "run", "seed-experiment", "--method", "ccm", "--json", "--set",
         "contact.friction=0.3", "--set", "solver.integrator=reference", "--set", "solver.t_end=1e-4"],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: contact.friction: CCM's friction runs"), r.stderr


def lift_off_run():
    """The free bar (8 modes) dropped nearly upright, at 85 degrees, with mu = 0.3, under CCM to 40 ms; the warnings."""
    case = fb.load_case(
        "tests/validation/data/free-bar-drop.toml",
        {"solver.t_end": 0.04, "initial.impact_angle": math.radians(85.0), "contact.friction": 0.3},
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sol = run(case)
    return sol, [str(w.message) for w in caught if issubclass(w.category, FlexbeamWarning)]


def test_a_held_pair_that_can_neither_stick_nor_slip_lifts_off_where_its_free_motion_separates_it():
    """The nearly upright bar lands on its cap and is held (CCM); at 26.3 ms its stick cannot hold (the kernel's
    unstick), and the slip the load drives has W_nn - mu_k s W_nt = -1.95 1/kg: a Painlevé slip (the 8-mode bar's
    point mobility across its axis, W_tt = 386 1/kg, is ~20 times the rigid bar's), whose tangential impact stops
    nothing (v_t ~ 0) and stuck the pair again -- the run used to stop there, "events keep recurring without
    progress".  Its free normal acceleration delta'' = 51.6 m/s^2 separates it: Painlevé's indeterminate case, in which
    the pair lifts off.  Asserted: the run finishes; at that instant one warning names the tangential impact and one
    the lift-off; the lift-off adds no kinetic energy (no impulse: the state is the same); the gap opens (positive
    1 us later, as delta'' > 0 says); the energy balance within 1e-8 of the energy scale (measured 1e-9)."""
    sol, messages = lift_off_run()
    lifts = [m for m in messages if "lifts it off" in m]
    assert lifts, messages
    t_lift = float(lifts[0].split("t = ")[1].split(" s")[0])
    assert any("tangential impact" in m and f"t = {t_lift:.9g} s" in m for m in messages)
    t_lift = min((s.t1 for s in sol.source.run.segments), key=lambda t: abs(t - t_lift))
    T0, T1 = kinetic_jump(sol, t_lift)
    assert T1 <= T0 * (1.0 + 1e-14)
    after = [s for s in sol.source.run.segments if s.t0 == t_lift][-1]
    assert after.phase.name == "free"
    y = after.states(np.array([t_lift + 1e-6]))[0]
    assert sol.source.system.gap(t_lift + 1e-6, y, 0)[0] > 0.0
    assert abs(sol.metrics()["energy_drift"]) < 1e-8


def test_a_held_pair_with_no_consistent_contact_force_stops_the_run_naming_painleve(monkeypatch):
    """Where the free normal acceleration would press the pair in as well (Painlevé's inconsistent case: no stick,
    no slip, no lift-off), the run stops with status failed and a message naming Painlevé and the way on -- the same
    run with the held pairs' free normal acceleration replaced by a pressing one (no landing of this run is slow
    enough for the grazing test that also reads it)."""
    from flexbeam.methods.held_friction import HeldFriction

    monkeypatch.setattr(HeldFriction, "gap_acceleration", lambda self, t, y, pair=0, contacts=None: -1.0)
    case = fb.load_case(
        "tests/validation/data/free-bar-drop.toml",
        {"solver.t_end": 0.04, "initial.impact_angle": math.radians(85.0), "contact.friction": 0.3},
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexbeamWarning)
        sol = fb.simulate(case, "ccm")
    assert sol.status == "failed"
    assert "Painlevé" in sol.message and "no contact force is consistent" in sol.message
    assert "CCFM" in sol.message


def test_a_held_multiplier_that_turns_tensile_at_a_step_boundary_is_released_there():
    """The shaken cantilever's tip held on its stop under CCM with friction (mu 0.6, 6 modes, 4 s; found by a random
    hunt): at 3.7172 s one step's multiplier interpolant ended at zero and the next began a hair below it, a crossing
    inside neither step, and the release search missed it -- the constraint pulled on for 1.4e-4 s, down to -0.24 N
    (4.3e-2 of the run's largest contact force).  Released at the boundary now: the sampled contact force never
    falls below -1e-4 of the largest (measured -3.2e-6, within a step about a located release)."""
    case = fb.load_case(DATA / "shaker-stop.toml", {"contact.friction": 0.6, "contact.friction_static": 0.9,
                                                    "model.modes": 6, "solver.t_end": 4.0})  # fmt: skip
    sol = run(case, "ccm")
    force = sol.to_xarray()["contact_force"].values
    assert np.nanmin(force) >= -1e-4 * np.nanmax(force)
