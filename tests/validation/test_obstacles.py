"""Several obstacles and contact anywhere on the beam, checked against closed forms of a rigid rod.

With ``model.modes = 0`` and no gravity the beam is a rigid rod of inertia ``J_O = rho A L^3 / 3`` about the
joint that turns at constant rate between contacts.  Contact geometry is exact (the gaps below are written out
in the rod's coordinates, independently of the package), so these are the truths:

* **IMM between two stops** (one below and one above the same material point ``x_P``): every impact flips the
  rate by ``-e`` (the normal velocity of a pinned rod is linear in its rate, whatever the normal's direction),
  so the times between impacts are ``theta_u / (e^k omega_0)``, ``theta_u`` the angle at which the upper gap
  closes.
* **Elastic CCFM between the same stops**: each contact is a rigid-body Hertz impact of the effective mass
  ``J_O / x_P^2`` on ``K delta^n``, of duration ``t_c = (delta_m / v_0) 2 int_0^1 (1 - u^{n+1})^{-1/2} du``
  with ``delta_m = ((n+1) m v_0^2 / (2K))^{1/(n+1)}`` (Johnson, *Contact Mechanics*, 1985, Sec. 11.4), after
  which the rod leaves at ``theta = 0`` with its rate restored; onsets are ``t_c + theta_u / omega_0`` apart.
* **CCM** (``e = 0`` at onset, then a held contact): the rod stops at the first stop and stays.
* **A simultaneous impact on two stops**: the Delassus matrix of a rigid rod is singular (rank 1), the velocities
  after are still unique (``omega^+ = -e omega^-``) and the least-norm impulses are proportional to the lever
  arms, ``P_i = x_i J_O (1 + e) omega_0 / (x_1^2 + x_2^2)``.
* **Contact anywhere**: a straight rod's lower surface nearest a sphere of centre ``C`` is the foot of the
  perpendicular, so a spinning rod touches a sphere at distance ``d`` from the joint at the material point
  ``sqrt(d^2 - (c + r_s)^2)`` and at the angle where the perpendicular distance is ``c + r_s``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, optimize

import flexbeam as fb
from flexbeam.model.beam import case_shapes
from flexbeam.parameters.case import Case

V0 = 0.4  # impact speed of P [m/s] (the seed case's)
R_S = 0.01  # sphere radius [m]
CLEARANCE = 0.002  # gap of the upper stop with the rod at theta = 0 [m]


def _rod(overrides: dict | None = None, obstacles: list[dict] | None = None) -> Case:
    base = {"model.modes": 0, "model.gravity": 0.0, "solver.t_end": 0.04}
    case = fb.load_case("seed-experiment", {**base, **(overrides or {})})
    data = case.model_dump()
    data["obstacles"] = obstacles or []
    return Case.model_validate(data)


def _upper_stop(case: Case) -> dict:
    c, x_p = case.beam.surface_offset, case.contact.position
    return {"kind": "sphere", "radius": R_S, "centre": [x_p, c + CLEARANCE + R_S], "contact": {"side": "above"}}


def _inertia(case: Case) -> float:
    b = case.beam
    return b.density * math.pi * b.radius**2 * b.length**3 / 3.0


def _upper_contact(case: Case) -> tuple[float, float]:
    """theta at which the upper surface point x_P + c e2 reaches the upper sphere (exact rod geometry), and the
    lever arm |r_P x n| of the contact normal about the joint there (the normal velocity is omega times it)."""
    c, x_p = case.beam.surface_offset, case.contact.position
    centre = np.array([x_p, c + CLEARANCE + R_S])

    def point(th: float) -> np.ndarray:
        return np.array([x_p * math.cos(th) - c * math.sin(th), x_p * math.sin(th) + c * math.cos(th)])

    # the gap turns negative again once the point is past the sphere: bracket the first root only
    theta_u = optimize.brentq(
        lambda th: np.linalg.norm(point(th) - centre) - R_S, 0.0, 2.5 * CLEARANCE / x_p, xtol=1e-15
    )
    p = point(theta_u)
    n = (p - centre) / np.linalg.norm(p - centre)
    return theta_u, abs(p[0] * n[1] - p[1] * n[0])


def _onsets(sol, pair: int | None = None) -> np.ndarray:
    return np.array([ev.onset for ev in sol.contacts if pair is None or ev.pair == pair])


def test_imm_between_two_stops_follows_the_restitution_law():
    e = 0.8
    case = _rod({"contact.restitution": e})
    sol = fb.simulate(_rod({"contact.restitution": e}, [_upper_stop(case)]), "imm")
    omega0 = V0 / case.contact.position
    theta_u, _ = _upper_contact(case)
    onsets = _onsets(sol)
    assert [ev.pair for ev in sol.contacts] == [0, 1, 0, 1, 0]
    expected = np.cumsum([0.0] + [theta_u / (e**k * omega0) for k in range(1, len(onsets))])
    # free flight is linear in t, so the dense output is exact and Brent finds its root to ~1e-16 s (measured
    # 2e-17 s); 1e-8 s only leaves room for the round-off of summing the intervals on another CPU
    np.testing.assert_allclose(onsets, expected, rtol=0, atol=1e-8)
    for ev in sol.contacts:
        np.testing.assert_allclose(ev.velocity_after, -e * ev.velocity_before, rtol=1e-9)


def _hertz_duration(mass: float, stiffness: float, n: float, v0: float) -> float:
    delta_m = ((n + 1.0) * mass * v0**2 / (2.0 * stiffness)) ** (1.0 / (n + 1.0))
    shape, _ = integrate.quad(lambda u: 1.0 / math.sqrt(1.0 - u ** (n + 1.0)), 0.0, 1.0, limit=200)
    return delta_m / v0 * 2.0 * shape


def test_elastic_ccfm_between_two_stops_is_periodic_with_the_hertz_contact_time():
    stiffness = 1.0e9
    over = {"contact.law": "hertz", "contact.stiffness": stiffness, "solver.t_end": 0.03}
    case = _rod(over)
    sol = fb.simulate(_rod(over, [_upper_stop(case)]), "ccfm")
    x_p, n = case.contact.position, case.contact.exponent
    omega0 = V0 / x_p
    theta_u, lever_u = _upper_contact(case)
    # each stop is a rigid-body Hertz impact of the mass J_O / lever^2 at the normal speed omega0 lever (the
    # upper stop's normal is tilted against the point's path: lever_u / x_P = 0.99975)
    t_c = [_hertz_duration(_inertia(case) / lever**2, stiffness, n, omega0 * lever) for lever in (x_p, lever_u)]
    onsets = _onsets(sol)
    assert len(onsets) >= 5
    assert [ev.pair for ev in sol.contacts] == [k % 2 for k in range(len(onsets))]
    expected = [t_c[k % 2] + theta_u / omega0 for k in range(len(onsets) - 1)]
    # what the closed form neglects: the normal turning during a contact (theta changes by ~ delta_m / x_P
    # ~ 2e-4 rad: measured 1.2e-5 relative on the duration, <= 7e-9 s on an interval); 1e-7 s is a 14x margin
    # and still half the upper stop's tilt effect (2.1e-7 s) that a lever of x_P would miss
    np.testing.assert_allclose(np.diff(onsets), expected, rtol=0, atol=1e-7)
    for ev in sol.contacts:
        np.testing.assert_allclose(ev.duration, t_c[ev.pair], rtol=2e-4)  # measured 1.2e-5 (same cause)
    assert max(abs(d) for d in sol.energy_drift()) < 1e-5  # elastic: measured 1.9e-7 over 6 contacts


def test_ccm_stops_the_rod_at_the_first_stop():
    case = _rod({"solver.t_end": 0.02})
    sol = fb.simulate(_rod({"solver.t_end": 0.02}, [_upper_stop(case)]), "ccm")
    assert [ev.pair for ev in sol.contacts] == [0]
    np.testing.assert_allclose(sol["theta_rate"][-1], 0.0, atol=1e-12)
    np.testing.assert_allclose(sol.contacts[0].jump_impulse, _inertia(case) * V0 / case.contact.position**2, rtol=1e-9)


@pytest.mark.parametrize("method, e", [("imm", 0.0), ("imm", 0.6), ("imm", 1.0), ("ccm", 0.0)])
def test_a_simultaneous_impact_on_two_stops_shares_the_impulse_by_lever_arm(method, e):
    over = {"contact.law": "hertz", "contact.restitution": e, "solver.t_end": 0.005}
    case = _rod(over)
    c, x1, x2 = case.beam.surface_offset, case.contact.position, 0.3
    second = {"kind": "sphere", "radius": R_S, "centre": [x2, -c - R_S], "contact": {"position": x2}}
    sol = fb.simulate(_rod(over, [second]), method)
    first = [ev for ev in sol.contacts if ev.onset == 0.0]
    assert sorted(ev.pair for ev in first) == [0, 1]
    omega0 = V0 / x1
    scale = _inertia(case) * (1.0 + e) * omega0 / (x1**2 + x2**2)
    jumps = {ev.pair: ev.jump_impulse for ev in first}
    # round-off only: the impulses solve a 2 x 2 problem whose rank-1 matrix has entries ~ x_i x_j / J_O
    np.testing.assert_allclose([jumps[0], jumps[1]], [scale * x1, scale * x2], rtol=1e-9)
    np.testing.assert_allclose(sol["theta_rate"][-1], e * omega0, rtol=1e-9, atol=1e-15)  # free flight after
    # complementarity: both impulses > 0, so both pairs leave at -e times their approach speed (>= 0): with the
    # rate e omega0 checked above, each pair's normal velocity is e omega0 x_i
    for ev in first:
        assert ev.jump_impulse > 0.0
        np.testing.assert_allclose(ev.velocity_before, -omega0 * (x1 if ev.pair == 0 else x2), rtol=1e-12)
    # energy: T+ = e^2 T- (kinetic only: no gravity, no deformation)
    for ev in first:
        np.testing.assert_allclose(ev.energy_after, e**2 * ev.energy_before, rtol=1e-9, atol=1e-15)


def test_contact_anywhere_finds_the_foot_of_the_perpendicular_on_a_spinning_rod():
    """A rod spun up to 20 rad/s meets a sphere at 0.5 m from the joint off its contact point's circle."""
    case = _rod({"solver.t_end": 0.02, "initial.kind": "state", "initial.rate": 20.0})
    c = case.beam.surface_offset
    d, phi = 0.5, 0.3  # sphere centre at distance d, direction phi (the rod turns towards it)
    centre = [d * math.cos(phi), d * math.sin(phi)]
    data = case.model_dump()
    data["obstacle"].update({"centre": centre, "radius": R_S})
    data["contact"].update({"anywhere": True, "side": "above"})
    sol = fb.simulate(Case.model_validate(data), "imm")
    first = sol.contacts[0]
    # the upper surface (offset +c along e2) touches when the perpendicular distance is c + r_s
    theta_c = phi - math.asin((c + R_S) / d)
    np.testing.assert_allclose(first.onset, theta_c / 20.0, rtol=0, atol=1e-9)
    x_c = math.sqrt(d**2 - (c + R_S) ** 2)
    k = np.searchsorted(sol.time, first.onset)
    # measured 7e-14 m (onset 2e-18 s): the capsule search's tolerance; 1e-6 m is a position a user can see
    np.testing.assert_allclose(sol["pair_contact_position"][k, 0], x_c, rtol=0, atol=1e-6)


def test_contact_anywhere_on_the_flexible_seed_beam_stays_near_the_material_point():
    """The seed beam hits the sphere straight: the nearest surface point moves off x_P only by the deformation
    (second order in the slope), so the first contact matches the fixed-point run's closely."""
    fixed = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 0.002}), "ccfm")
    anywhere = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 0.002, "contact.anywhere": True}), "ccfm")
    peak_f, peak_a = fixed.contacts[0].peak_force, anywhere.contacts[0].peak_force
    np.testing.assert_allclose(peak_a, peak_f, rtol=1e-4)  # measured 2.1e-6
    in_contact = anywhere["pair_contact_force"][:, 0] > 0.0
    x = anywhere["pair_contact_position"][in_contact, 0]
    assert np.all(np.abs(x - 0.585) < 1e-4)  # measured 9.0e-6 m


def test_flexible_beam_between_two_elastic_stops_keeps_its_energy():
    over = {"model.modes": 8, "model.gravity": 0.0, "contact.law": "hertz", "solver.t_end": 0.03}
    case = fb.load_case("seed-experiment", over)
    data = case.model_dump()
    data["obstacles"] = [_upper_stop(case)]
    sol = fb.simulate(Case.model_validate(data), "ccfm")
    assert {ev.pair for ev in sol.contacts} == {0, 1}
    assert max(abs(d) for d in sol.energy_drift()) < 1e-5  # measured 4.7e-7 (three contacts, 8 modes)


def test_spinning_stop_preset_as_a_rigid_rod_meets_the_sphere_where_geometry_says():
    """``spinning-stop`` with the modes off: theta = tau t^2 / (2 J_O) from rest, so the upper surface touches the
    sphere (distance d, direction phi) at t = sqrt(2 J_O theta_c / tau), theta_c = phi - asin((c + r_s) / d)."""
    case = fb.load_case("spinning-stop", {"model.modes": 0})
    centre = np.array(case.obstacle.centre)
    d, phi = float(np.hypot(*centre)), math.atan2(centre[1], centre[0])
    reach = case.beam.surface_offset + case.obstacle.radius
    sol = fb.simulate(case, "imm")
    first = sol.contacts[0]
    t_c = math.sqrt(2.0 * _inertia(case) * (phi - math.asin(reach / d)) / case.drive.torque)
    np.testing.assert_allclose(first.onset, t_c, rtol=1e-9)  # dense output of a quadratic theta(t): exact
    k = np.searchsorted(sol.time, first.onset)
    np.testing.assert_allclose(sol["pair_contact_position"][k, 0], math.sqrt(d**2 - reach**2), rtol=0, atol=1e-6)


def test_tip_wall_preset_as_a_rigid_rod_is_a_hertz_impact_on_the_plane():
    """``tip-wall`` with the modes off and an elastic law: the tip's contact on the half-plane lasts the
    rigid-body Hertz time of the mass J_O / L^2 and returns the speed."""
    case = fb.load_case("tip-wall", {"model.modes": 0, "model.gravity": 0.0, "contact.law": "hertz"})
    sol = fb.simulate(case, "ccfm")
    first = sol.contacts[0]
    length = case.beam.length
    t_c = _hertz_duration(_inertia(case) / length**2, case.contact.stiffness, case.contact.exponent, V0)
    np.testing.assert_allclose(first.duration, t_c, rtol=2e-5)  # measured 1.0e-6
    np.testing.assert_allclose(first.velocity_after, V0, rtol=1e-6)  # measured 8.2e-8


def test_two_stops_preset_touches_both_stops():
    sol = fb.simulate(fb.load_case("two-stops"), "ccfm")
    pairs = [ev.pair for ev in sol.contacts]
    assert pairs[0] == 0 and 1 in pairs
    above = sol.contacts[pairs.index(1)]
    # the upper stop is met from below: P's normal velocity towards it is negative at onset
    assert above.velocity_before < 0.0 < above.peak_force


def _brute_force_nearest(case: Case, hub_angle: float, q: np.ndarray, centre, radius: float, points: int = 20001):
    """The minimum of the gap of the deformed beam's surface points to a sphere over x in [0, L] and both
    surfaces: a grid of ``points`` stations, then a bounded scalar minimisation around the best one.

    Centre line rho(x) = (r_h + x - 1/2 int_0^x (Psi' q)^2, Psi q) (first order), surface rho -+ c n along the
    centre line's own unit normal n, turned by the frame angle theta = phi - Psi'(0) q (``theta`` in the
    outputs is the hub angle phi).  Returns (gap, x)."""
    shapes = case_shapes(case)
    c, L = case.beam.surface_offset, case.beam.length
    theta = hub_angle - float(shapes(np.zeros(1), 1)[0] @ q)
    rot = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])

    def gaps(x: np.ndarray, side: float, u: np.ndarray) -> np.ndarray:
        w, w1 = shapes(x, 0) @ q, shapes(x, 1) @ q
        tangent = np.stack([1.0 - 0.5 * w1**2, w1]) / np.hypot(1.0 - 0.5 * w1**2, w1)
        surface = np.stack([case.hub.radius + x + u, w]) + side * c * np.stack([-tangent[1], tangent[0]])
        return np.hypot(*(rot @ surface - np.asarray(centre)[:, None])) - radius

    def u_exact(x: float) -> float:
        return -0.5 * integrate.quad(lambda xi: float(shapes(np.array([xi]), 1)[0] @ q) ** 2, 0.0, x)[0]

    grid = np.linspace(0.0, L, points)
    u_grid = -0.5 * integrate.cumulative_trapezoid((shapes(grid, 1) @ q) ** 2, grid, initial=0.0)
    best = (math.inf, math.nan)
    for side in (-1.0, 1.0):
        k = int(np.argmin(gaps(grid, side, u_grid)))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, points - 1)]
        res = optimize.minimize_scalar(
            lambda x, side=side: float(gaps(np.array([x]), side, np.array([u_exact(x)]))[0]),
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": 1e-10},
        )
        if res.fun < best[0]:
            best = (float(res.fun), float(res.x))
    return best


def test_contact_anywhere_matches_a_brute_force_minimum_on_the_deformed_spinning_beam():
    """``spinning-stop`` (12 modes, the beam bent by the drive and ringing after the impact): at samples before,
    in and after the first contact, the pair's gap and contact position are the brute-force minimum's."""
    case = fb.load_case("spinning-stop", {"solver.t_end": 0.4475})
    sol = fb.simulate(case, "ccfm")
    first = sol.contacts[0]
    t = sol.time
    during = [first.onset + f * first.duration for f in (0.1, 0.3, 0.7)]
    picks = np.searchsorted(t, [first.onset - 2e-4, *during, first.end + 5e-4, first.end + 1e-3])
    moved = []
    for k in picks:
        gap, x = _brute_force_nearest(case, sol["theta"][k], sol["q"][k], case.obstacle.centre, case.obstacle.radius)
        # measured: gaps agree to 1.2e-11 m (the kernels' Hermite station tables), positions to 1.4e-12 m
        np.testing.assert_allclose(sol["pair_gap"][k, 0], gap, rtol=0, atol=2e-10)
        np.testing.assert_allclose(sol["pair_contact_position"][k, 0], x, rtol=0, atol=1e-8)
        moved.append(sol["pair_contact_position"][k, 0])
    assert np.ptp(moved) > 1e-5  # the point moves along the beam (measured 1.2e-4 m)


def test_stiff_ccfm_between_two_stops_tends_to_imm():
    """Elastic contacts of growing stiffness K: the CCFM onsets approach IMM's (e = 1) by the accumulated
    contact time, which falls as the rigid Hertz time ~ K^(-2/5); the impulses tend to 2 m v."""
    over = {"contact.law": "hertz", "contact.restitution": 1.0, "solver.t_end": 0.03}
    case = _rod(over)
    stops = [_upper_stop(case)]
    imm = _onsets(fb.simulate(_rod(over, stops), "imm"))
    gaps = []
    for stiffness in (1e9, 1e11, 1e13):
        sol = fb.simulate(_rod({**over, "contact.stiffness": stiffness}, stops), "ccfm")
        ccfm = _onsets(sol)[: len(imm)]
        assert len(ccfm) == len(imm)
        gaps.append(np.max(np.abs(ccfm - imm)))
        mass = _inertia(case) / case.contact.position**2
        # the first contact is the lower stop's: impulse 2 m v0, up to the normal turning during the contact
        # (measured 9.3e-6, 1.5e-6, 2.7e-7 relative: it shrinks with the contact time, as K^(-2/5))
        np.testing.assert_allclose(sol.contacts[0].impulse, 2.0 * mass * V0, rtol=1e-4)
    ratios = np.array(gaps[:-1]) / np.array(gaps[1:])
    # K^(-2/5) per factor 100 in K: 100^0.4 = 6.3096 (measured 6.3097, 6.3099: 5e-5 relative)
    np.testing.assert_allclose(ratios, 100.0**0.4, rtol=1e-3)
    assert gaps[-1] < 2e-4  # at K = 1e13 the five contacts add 1e-4 s


def test_contact_anywhere_at_the_tip_takes_the_end_cap():
    """A sphere just beyond the tip's circle (distance d with L < d < L + c + r_s) is touched by the end of the
    beam, closed by a hemispherical cap of radius c about the tip (the capsule of nearest.c): contact when
    |L e1(theta) - C| = c + r_s, i.e. cos(phi - theta) = (L^2 + d^2 - (c + r_s)^2) / (2 L d), at x = L."""
    case = _rod({"solver.t_end": 0.05, "initial.kind": "state", "initial.rate": 20.0})
    c, L = case.beam.surface_offset, case.beam.length
    d, phi = L + 0.5 * (c + R_S), 0.3
    data = case.model_dump()
    data["obstacle"].update({"centre": [d * math.cos(phi), d * math.sin(phi)], "radius": R_S})
    data["contact"].update({"anywhere": True})
    sol = fb.simulate(Case.model_validate(data), "imm")
    first = sol.contacts[0]
    theta_c = phi - math.acos((L**2 + d**2 - (c + R_S) ** 2) / (2.0 * L * d))
    np.testing.assert_allclose(first.onset, theta_c / 20.0, rtol=0, atol=1e-9)  # measured 4e-17 s
    k = np.searchsorted(sol.time, first.onset)
    assert sol["pair_contact_position"][k, 0] == L
    # the impulse acts along the cap's normal, from the sphere's centre through the tip's: its lever about O is
    # |L e1 x n| = L sin(angle between the beam and n), well below L here, and P = (1 + e) J_O omega / lever
    # (the rate flips by -e whatever the lever); a force along the section normal would have lever L
    tip = L * np.array([math.cos(theta_c), math.sin(theta_c)])
    n = (tip - data["obstacle"]["centre"]) / np.linalg.norm(tip - data["obstacle"]["centre"])
    lever = abs(tip[0] * n[1] - tip[1] * n[0])
    assert lever < 0.9 * L
    e = case.contact.restitution
    np.testing.assert_allclose(first.jump_impulse, (1.0 + e) * _inertia(case) * 20.0 / lever, rtol=1e-9)


def test_zeno_on_two_stops_at_once_ends_resting_on_both():
    """A rigid rod falling under gravity on two stops that it meets together (x_P and 0.3 m): W has rank 1, so
    every impact flips the rate by -e exactly as on one stop -- the onsets are the one-stop run's -- until the
    rebound falls below solver.rest_velocity; then the rod rests on both (one held, the other redundant: its
    gap follows the held one's, no spurious contacts at round-off)."""
    over = {"model.gravity": 9.81, "contact.law": "hunt_crossley", "contact.restitution": 0.5, "solver.t_end": 0.2}
    case = _rod(over)
    c = case.beam.surface_offset
    second = {"kind": "sphere", "radius": R_S, "centre": [0.3, -c - R_S], "contact": {"position": 0.3}}
    one = fb.simulate(case, "imm")
    two = fb.simulate(_rod(over, [second]), "imm")
    assert two.status == "success" and two.phase[-1] == "resting"
    single = _onsets(one)
    for pair in (0, 1):
        # measured 6e-13 s (the accumulation point's event location); 1e-9 s is simultaneity's window
        np.testing.assert_allclose(_onsets(two, pair), single, rtol=0, atol=1e-9)
    # the rod rests: its rate is round-off of the held constraint's (measured 3e-15 rad/s)
    assert abs(two["theta_rate"][-1]) < 1e-9
