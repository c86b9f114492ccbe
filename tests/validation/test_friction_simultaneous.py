"""Friction at simultaneous impacts (IMM): Newton's law with one restitution e for the normal and tangential rows
(``flexbeam.methods.frictional_lcp``), which never gains energy.

* **Energy and the law** over Hypothesis-drawn Delassus matrices W = J M^-1 J^T (2 and 3 pairs, positive definite
  and singular), approach velocities, mu and e: the kinetic energy computed from the generalised velocities,
  z'^T M z' / 2, does not grow; the normal conditions (xi_n >= 0, P_n >= 0, P_n xi_n = 0 with xi = v+ + e v-) and
  Coulomb's (|P_t| <= mu P_n, P_t xi_t <= 0, P_t = -mu sign(xi_t) P_n when slipping) hold.
* **A rigid line bar landing flat on two stops** beneath its ends (mass m, length L, no spin, G moving at (v_x, -v0),
  no gravity; the stops' normals n = (0, 1), tangents t = (-1, 0)).  The normal rows J_n = [0, 1, -+L/2] and the
  tangential rows J_t = [-1, 0, 0] (the ends' lever arm along n is 0).  By symmetry P_n1 = P_n2 = P_n and
  P_t1 = P_t2 = P_t, the moments cancel, so omega+ = 0 and v_Gy+ = -v0 + 2 P_n / m; xi_n = 0 gives
  P_n = (1 + e) m v0 / 2, v_Gy+ = e v0.  The ends' tangential velocity is v_t = -v_x.
  Slip throughout (xi_t = -(v_x+ + e v_x) < 0, P_t = +mu P_n, a force -mu P_n along x at each end):
  v_x+ = v_x - 2 mu P_n / m = v_x - mu (1 + e) v0, consistent when v_x+ + e v_x > 0, i.e. v_x > mu v0.
  Stick (xi_t = 0): v_x+ = -e v_x -- the ends spring back along the ground (the law's tangential restitution e) --
  with the tangential impulse 2 P_t = (1 + e) m v_x, inside the cone 2 mu P_n = mu (1 + e) m v0 when v_x <= mu v0.
* **The same bar with spin** (asymmetric: the ends approach at -v0 -+ omega L/2): against an independent solution,
  Stewart & Trinkle's LCP (the cone's two edges and a slack per pair) written here from the hand-built J and M, its
  active set found by scipy's mixed-integer LP (complementarity as binaries), then solved exactly.
* **Two pairs, one idle, equal one pair's Stronge process** where the laws coincide: Stronge's process with a single
  mode (slip in one direction throughout, or stick from v_t- = 0) for any e, and for e = 0 also a slip that stops and
  sticks (both end at v+ = 0).  The second pair separating fast, its impulse is 0 and the first's is
  ``frictional_impulse``'s.
* **A rigid rod on its joint striking two rough stops at once** (W of rank 1): both contacts stick, the rod leaves at
  -e times its approach rate, and the impulses are the least-norm ones (closed form in the test).
* **Simulations**: a flexible steel bar dropped flat on two stops with mu = 0.3 (IMM, gravity): no warning, the energy
  balance closes, no jump gains kinetic energy; a very stiff elastic CCFM contact with Coulomb friction on the line
  bar's symmetric flat landing (slip throughout) leaves G's velocity at the closed form IMM gives with e = 1.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import Bounds, LinearConstraint, milp

import flexbeam as fb
from flexbeam.errors import FlexbeamWarning
from flexbeam.methods import base as methods_base
from flexbeam.methods.friction import frictional_impulse
from flexbeam.methods.frictional_lcp import solve_frictional_impact
from flexbeam.methods.impulse import frictional_impulses
from flexbeam.validation.bars import STEEL_BAR, bar_on_stops

sys.path.insert(0, str(Path(__file__).parent))
import test_obstacles as ob  # noqa: E402

L, M_BAR, R_STOP = 0.5, 7800.0 * 1e-4 * 0.5, 0.1


# ------------------------------------------------------------------------------------------- the law on random W
def _draw_problem(draw, s: int):
    """(M, J, zd, e, mu): n coordinates with masses in [0.1, 10], J's 2 s rows (normals then tangents) random in
    [-1, 1]; n = 2 s + 1 (W positive definite) or s + 1 < 2 s (W singular; v- = J z'- then)."""
    n = draw(st.sampled_from([2 * s + 1, s + 1]))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    M = np.diag(rng.uniform(0.1, 10.0, n))
    J = rng.uniform(-1.0, 1.0, (2 * s, n))
    zd = rng.uniform(-1.0, 1.0, n)
    e = draw(st.sampled_from([0.0, 0.3, 1.0])) if draw(st.booleans()) else draw(st.floats(0.0, 1.0))
    mu = rng.uniform(0.0, 2.0, s) if draw(st.booleans()) else np.full(s, draw(st.floats(0.0, 2.0)))
    return M, J, zd, e, mu


@st.composite
def problems(draw):
    return _draw_problem(draw, draw(st.sampled_from([2, 3])))


@settings(max_examples=150, deadline=None)
@given(problems())
def test_no_energy_gain_and_the_law_holds(problem):
    """T+ <= T- computed from z' (tolerance: the solver accepts residuals of 1e-10 max|(1 + e) v-| in xi, which can do
    at most that times sum |P| of work, plus 1e-13 T- for the energy's own round-off), and every condition of the law
    holds to that residual (impulses: the residual over max |W|)."""
    M, J, zd, e, mu = problem
    s = J.shape[0] // 2
    W, v_minus = J @ np.diag(1.0 / np.diag(M)) @ J.T, J @ zd
    assert_the_law_and_no_gain(M, J, zd, e, mu, solve_frictional_impact(W, v_minus, np.full(s, e), mu, mu))


def assert_the_law_and_no_gain(M: np.ndarray, J: np.ndarray, zd: np.ndarray, e: float, mu: np.ndarray, P) -> None:
    """T+ <= T- from z' and every condition of the law, to the bounds of test_no_energy_gain_and_the_law_holds."""
    s = J.shape[0] // 2
    Minv = np.diag(1.0 / np.diag(M))
    W = J @ Minv @ J.T
    v_minus = J @ zd
    approaching = v_minus[:s] < 0.0
    assert P is not None
    zd_plus = zd + Minv @ J.T @ P
    T_minus, T_plus = 0.5 * zd @ M @ zd, 0.5 * zd_plus @ M @ zd_plus
    q = (1.0 + e) * v_minus
    tol_v = 1e-10 * np.max(np.abs(q)) + 1e-15
    tol_p = tol_v / np.max(np.abs(W))
    assert T_plus - T_minus <= tol_v * np.sum(np.abs(P)) + 1e-13 * T_minus
    xi = J @ zd_plus + e * v_minus
    Pn, Pt, xn, xt = P[:s], P[s:], xi[:s], xi[s:]
    assert np.all(Pn >= 0.0) and np.all(xn >= -2 * tol_v)
    assert np.all(np.abs(Pn * xn) <= 2 * tol_v * (Pn + tol_p))
    assert np.all(np.abs(Pt) <= mu * Pn + tol_p)
    assert np.all(Pt * xt <= 2 * tol_v * np.abs(Pt))
    slipping = np.abs(xt) > 2 * tol_v
    assert np.allclose(Pt[slipping], -mu[slipping] * np.sign(xt[slipping]) * Pn[slipping], rtol=1e-9, atol=tol_p)
    if not approaching.any():  # nothing approaches: v- already satisfies the law (P = 0 is the least-norm solution)
        assert np.all(P == 0.0)


@settings(max_examples=60, deadline=None)
@given(problems(), st.floats(0.0, 1.0), st.floats(0.0, 1.0))
def test_different_restitutions_never_gain_energy(problem, e1, e2):
    """With a restitution per pair the caller's guard (:func:`frictional_impulses`) keeps T+ <= T- (the same bound):
    Newton's law where it does not gain, else the smallest e for all, with a warning."""
    M, J, zd, _, mu = problem
    s = J.shape[0] // 2
    e = np.array([e1, e2, 0.5 * (e1 + e2)][:s])
    Minv = np.diag(1.0 / np.diag(M))
    W, v_minus = J @ Minv @ J.T, J @ zd
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexbeamWarning)
        P = frictional_impulses(W, v_minus, e, mu, mu)
    zd_plus = zd + Minv @ J.T @ P
    T_minus, T_plus = 0.5 * zd @ M @ zd, 0.5 * zd_plus @ M @ zd_plus
    tol_v = 1e-10 * 2.0 * np.max(np.abs(v_minus)) + 1e-15
    assert T_plus - T_minus <= tol_v * np.sum(np.abs(P)) + 1e-9 * (abs(P @ v_minus) + P @ W @ P)


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 1.0), st.floats(0.0, 2.0), st.sampled_from([0.0, 0.5]))
def test_one_idle_pair_leaves_stronges_process(seed, e, mu, vt0_scale):
    """Pair 2 separating at 10 m/s (the coupling of W cannot stop it: |W_12 P| < 10 here), pair 1 approaching at -1
    m/s: P_2 = 0, and where Stronge's process keeps one mode (or, for e = 0, slips then sticks: module docstring)
    pair 1's impulses equal ``frictional_impulse``'s to 1e-9 relative (round-off of two different algorithms)."""
    rng = np.random.default_rng(seed)
    J = rng.uniform(-1.0, 1.0, (4, 5))
    W = J @ J.T / 10.0  # masses 10 kg: |W| <= 0.5
    v_minus = np.array([-1.0, 10.0, vt0_scale * rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)])
    P = solve_frictional_impact(W, v_minus, np.full(2, e), np.full(2, mu), np.full(2, mu))
    assert P[1] == 0.0
    imp = frictional_impulse((W[2, 2], W[2, 0], W[0, 0]), v_minus[2], v_minus[0], e, mu, mu)
    single = len(imp.modes) == 1 or (e == 0.0 and imp.modes[-1] == "stick")
    if single and not imp.painleve:
        assert P[0] == pytest.approx(imp.normal, rel=1e-9, abs=1e-12)
        assert P[2] == pytest.approx(imp.tangential, rel=1e-9, abs=1e-12)


# ------------------------------------------------------------------------------------- the rigid bar on two stops
def flat_bar(mu: float, e: float, vx: float, v0: float = 1.0, omega: float = 0.0, inset: float = 0.0) -> fb.Case:
    """The rigid line bar (no modes, no gravity), horizontal with G at the origin, its points x = inset and
    L - inset just touching two stops of radius R_STOP centred beneath them, moving at (vx, -v0) and spinning at
    ``omega``; with an inset the contact points are the bar's points nearest the stops (``contact.anywhere``)."""
    return fb.load_case({
        "name": "flat-rough-bar",
        "beam": {"length": L, "density": 7800.0, "youngs_modulus": 200e9, "poisson_ratio": 0.3, "section": "general",
                 "area": 1e-4, "second_moment": 1e-9, "half_depth": 0.0},
        "joint": {"kind": "free"},
        "model": {"modes": 0, "gravity": 0.0},
        "obstacle": {"kind": "sphere", "centre": [inset - 0.5 * L, -R_STOP], "radius": R_STOP},
        "obstacles": [{"kind": "sphere", "centre": [0.5 * L - inset, -R_STOP], "radius": R_STOP,
                       "contact": {"position": L - inset}}],
        "contact": {"law": "hertz", "position": inset, "stiffness": 1e10, "side": "centre", "restitution": e,
                    "friction": mu, "anywhere": inset > 0.0},
        "initial": {"kind": "state", "position": [0.0, 0.0], "velocity": [vx, -v0], "angle": 0.0, "rate": omega},
        "solver": {"t_end": 1e-3},
    })  # fmt: skip


def after(sol) -> np.ndarray:
    """(v_Gx, v_Gy, omega) after the run."""
    return np.array(sol.source.run.segments[-1].y1[3:6])


def simulate_quietly(case: fb.Case, method: str = "imm"):
    with warnings.catch_warnings():
        warnings.simplefilter("error", FlexbeamWarning)
        sol = fb.simulate(case, method)
    assert sol.status == "success", sol.message
    return sol


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize(("mu", "vx"), [(0.3, 0.1), (0.3, 0.29), (0.3, 0.31), (0.3, 1.0), (1.5, 2.0)])
def test_flat_landing_closed_forms(mu, vx, e):
    """The module docstring's closed forms, stick (vx <= mu v0) or slip throughout: impulses, G's velocity and the
    spin to 1e-12 (the spin to 1e-12 v0 / L: round-off)."""
    sol = simulate_quietly(flat_bar(mu, e, vx))
    assert len(sol.contacts) == 2 and sol.contacts[0].onset == sol.contacts[1].onset == 0.0
    Pn = (1.0 + e) * M_BAR / 2.0
    stick = vx <= mu
    vx_after = -e * vx if stick else vx - mu * (1.0 + e)
    Pt = (1.0 + e) * M_BAR * vx / 2.0 if stick else mu * Pn
    for ev in sol.contacts:
        assert ev.impulse == pytest.approx(Pn, rel=1e-12)
        assert ev.tangential_impulse == pytest.approx(Pt, rel=1e-12)
    vG = after(sol)
    assert vG[0] == pytest.approx(vx_after, rel=1e-12, abs=1e-14)
    assert vG[1] == pytest.approx(e, rel=1e-12, abs=1e-14)
    assert abs(vG[2]) <= 1e-12 / L


def stewart_trinkle(W: np.ndarray, q: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """(P_n, P_t) solving Stewart & Trinkle's LCP (Int. J. Numer. Meth. Eng. 39 (1996) 2673) for xi = q + W P:
    z = (P_n, beta+, beta-, lambda) >= 0, P_t = beta+ - beta-, w = (xi_n, xi_t + lambda, -xi_t + lambda,
    mu P_n - beta+ - beta-) >= 0, z . w = 0.  The active set comes from scipy's MILP (w_j <= U (1 - b_j), z_j <= U b_j,
    the smallest sum z), the values from the exact linear equations of that set (numpy's lstsq)."""
    s = mu.size
    Id, Z = np.eye(s), np.zeros((s, s))
    Wnn, Wnt, Wtn, Wtt = W[:s, :s], W[:s, s:], W[s:, :s], W[s:, s:]
    A = np.block([[Wnn, Wnt, -Wnt, Z], [Wtn, Wtt, -Wtt, Id], [-Wtn, -Wtt, Wtt, Id], [np.diag(mu), -Id, -Id, Z]])
    b = np.concatenate((q[:s], q[s:], -q[s:], np.zeros(s)))
    m = 4 * s
    U = 100.0 * (np.max(np.abs(b)) + 1.0) / np.min(np.linalg.eigvalsh(Wnn))
    c = np.concatenate((np.ones(m), np.zeros(m)))
    cons = [LinearConstraint(np.hstack((A, np.zeros((m, m)))), -b, np.inf),
            LinearConstraint(np.hstack((A, U * np.eye(m))), -np.inf, U - b),
            LinearConstraint(np.hstack((np.eye(m), -U * np.eye(m))), -np.inf, 0.0)]  # fmt: skip
    res = milp(c, constraints=cons, integrality=np.concatenate((np.zeros(m), np.ones(m))),
               bounds=Bounds(np.zeros(2 * m), np.concatenate((np.full(m, np.inf), np.ones(m)))))  # fmt: skip
    assert res.success
    active = res.x[m:] > 0.5
    rows = np.vstack((A[active], np.eye(m)[~active]))
    rhs = np.concatenate((-b[active], np.zeros(np.sum(~active))))
    z = np.linalg.lstsq(rows, rhs, rcond=None)[0]
    assert np.all(z >= -1e-12) and np.all(A @ z + b >= -1e-12) and abs(z @ (A @ z + b)) <= 1e-12
    return np.concatenate((z[:s], z[s : 2 * s] - z[2 * s : 3 * s]))


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize(("mu", "vx", "omega"), [(0.3, 0.1, 2.0), (0.3, 0.6, -3.0), (0.8, 0.5, 3.0), (0.1, 0.0, 1.0)])
def test_spinning_bar_against_an_independent_lcp(mu, vx, omega, e):
    """The bar spinning as it lands flat (the ends at -v0 -+ omega L/2): G's velocity and the spin after the IMM run
    equal those of :func:`stewart_trinkle`'s impulses on the hand-built J = [J_n; J_t] and M = diag(m, m, m L^2/12),
    to 1e-9 (the MILP's active set is exact; the rest is round-off of a 3 x 3 system, 1e-12, with a margin for the
    velocity-level tolerance 1e-10 of the solver's acceptance)."""
    sol = simulate_quietly(flat_bar(mu, e, vx, omega=omega))
    assert len(sol.contacts) == 2
    r = np.array([-0.5 * L, 0.5 * L])
    J = np.array([[0.0, 1.0, r[0]], [0.0, 1.0, r[1]], [-1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]])
    Minv = np.diag([1.0 / M_BAR, 1.0 / M_BAR, 12.0 / (M_BAR * L * L)])
    zd = np.array([vx, -1.0, omega])
    P = stewart_trinkle(J @ Minv @ J.T, (1.0 + e) * (J @ zd), np.full(2, mu))
    expected = zd + Minv @ J.T @ P
    assert np.allclose(after(sol), expected, rtol=0.0, atol=1e-9)
    T = lambda v: 0.5 * (M_BAR * (v[0] ** 2 + v[1] ** 2) + M_BAR * L * L / 12.0 * v[2] ** 2)  # noqa: E731
    assert T(after(sol)) <= T(zd) * (1.0 + 1e-12)


@pytest.mark.parametrize("e", [0.0, 0.6, 1.0])
def test_rigid_rod_on_two_rough_stops_singular_w(e):
    """test_obstacles.py's rigid rod on its revolute joint striking two stops at x_1 = x_P and x_2 = 0.3 m at once,
    with mu = 0.3: one coordinate, four rows, W of rank 1.  The contact points lie at the surface offset c below the
    axis, r_i = (x_i, -c), so omega z x r_i = omega (c, x_i): J_n,i = x_i and J_t,i = -c (t = (-1, 0)).  Every pushing
    pair leaves at xi_n = 0, i.e. omega+ = -e omega-, and then xi_t = -c (omega+ + e omega-) = 0: both stick.  The
    impulses with J_O (omega+ - omega-) = sum x_i P_ni - c sum P_ti are not unique; the least-norm ones are
    k (x_1, x_2, -c, -c), k = J_O (1 + e) omega_0 / (x_1^2 + x_2^2 + 2 c^2) (inside the cone: c <= mu x_i).  Checked
    to 1e-9 (round-off of a rank-1 problem with entries x_i x_j / J_O, as test_obstacles.py's frictionless case),
    omega+ = e omega_0 and T+ = e^2 T-, no warning."""
    over = {"contact.law": "hertz", "contact.restitution": e, "solver.t_end": 0.005, "contact.friction": 0.3}
    case = ob._rod(over)
    c, x1, x2 = case.beam.surface_offset, case.contact.position, 0.3
    second = {"kind": "sphere", "radius": ob.R_S, "centre": [x2, -c - ob.R_S], "contact": {"position": x2}}
    sol = simulate_quietly(ob._rod(over, [second]))
    first = {ev.pair: ev for ev in sol.contacts if ev.onset == 0.0}
    assert sorted(first) == [0, 1]
    omega0 = ob.V0 / x1
    k = ob._inertia(case) * (1.0 + e) * omega0 / (x1**2 + x2**2 + 2.0 * c * c)
    assert c <= 0.3 * min(x1, x2)
    for pair, x in ((0, x1), (1, x2)):
        assert first[pair].jump_impulse == pytest.approx(k * x, rel=1e-9)
        assert abs(first[pair].tangential_impulse) == pytest.approx(k * c, rel=1e-9)
        assert first[pair].energy_after == pytest.approx(e**2 * first[pair].energy_before, rel=1e-9, abs=1e-15)
    np.testing.assert_allclose(sol["theta_rate"][-1], e * omega0, rtol=1e-9, atol=1e-15)


# ----------------------------------------------------------------------------------------------------- simulations
def steel_bar_on_stops(modes: int, mu: float, e: float, vx: float, v0: float = 1.0) -> fb.Case:
    """The steel bar (:mod:`flexbeam.validation.bars`, as test_free_beam_two_stops.py's) horizontal, G at (0, 0.1 m),
    both stops (r = 1 cm, beneath x = L/2 -+ 0.3 L) touching its lower surface, moving at (vx, -v0), gravity on,
    friction mu."""
    a = 0.3 * STEEL_BAR["length"]
    return bar_on_stops([-a, a], (vx, -v0), modes=modes, mu=mu, restitution=e, name="rough-flat-bar")


@pytest.mark.parametrize(("e", "tolerances"), [(0.5, "default"), (0.5, "tight"), (0.0, "default"), (0.0, "tight")])
def test_flexible_bar_dropped_flat_on_rough_stops(monkeypatch, e, tolerances):
    """A flexible steel bar (2 modes, gravity) dropped flat on two stops, sliding at 0.5 m/s, mu = 0.3: the run ends
    without a warning (none about frictionless simultaneous impacts), at least one jump has two frictional pairs, no
    jump's kinetic energy grows (beyond 1e-12 relative round-off), and the energy balance closes within
    test_energy.py's bounds: 1e-5 at the default tolerance (the integrator's error; measured 2.5e-8), 1e-9 at
    fast_rtol = 1e-10 (measured 2e-14: the jumps' work is booked exactly).  (e = 0 comes to rest and bounces 20
    times; its resting phase at the tight tolerance failed in a step-size underflow at t = 0 before the resting
    multiplier's round-off was told from its error: kernels/src/collocation.c, multiplier_error.)"""
    jumps = []
    original = methods_base.impulse_jump

    def recording(*args, **kwargs):
        jump = original(*args, **kwargs)
        jumps.append(jump)
        return jump

    monkeypatch.setattr(methods_base, "impulse_jump", recording)
    case = steel_bar_on_stops(modes=2, mu=0.3, e=e, vx=0.5)
    if tolerances == "tight":
        case = fb.load_case(case.model_dump(), {"solver.fast_rtol": 1e-10, "solver.fast_atol": 1e-13})
    sol = simulate_quietly(case)
    assert any(j.impulses.size == 2 and j.tangential is not None and np.all(j.tangential != 0.0) for j in jumps)
    for jump in jumps:
        assert jump.kinetic_after <= jump.kinetic_before * (1.0 + 1e-12)
    end, worst = sol.energy_drift()
    bound = 1e-9 if tolerances == "tight" else 1e-5
    assert abs(end) < bound and worst < bound


def test_stiff_elastic_contact_agrees_on_a_symmetric_slip():
    """CCFM, Hertz (elastic) contact with Coulomb friction, the line bar landing flat at v_x = 1 m/s on two stops
    0.05 m inside its ends, mu = 0.3: both points slip throughout (v_x stays above 2 mu v0 = 0.6 m/s: the compliant
    contact slips while its normal impulse grows to (1 + e) m v0 / 2, e = 1), each pair's tangential impulse is
    mu P_n, so G leaves at (v_x - 2 mu v0, v0) -- the flat landing's closed form with e = 1, which IMM gives to
    round-off.  G's velocity: within 2e-6 m/s (measured 1.8e-7 at K = 1e12 and 1e14 N/m^1.5: the integrator's
    fast_rtol = 1e-6 of the 1 m/s impact, x10).  The compliant bar turns slightly while in contact (measured
    omega = 6.0 rad/s^2 times the contact's duration t_c, 2.7e-5 s and 4.2e-6 s), which vanishes with t_c: the
    stiffer contact's spin is below a third of the softer's (t_c's ratio 6.3) and its ends' speed from it below 1e-5
    m/s."""
    case = flat_bar(0.3, 1.0, 1.0, inset=0.05)
    imm = after(simulate_quietly(case))
    assert imm == pytest.approx([1.0 - 0.6, 1.0, 0.0], abs=1e-12)
    spins = []
    for K in (1e12, 1e14):
        ccfm = after(simulate_quietly(fb.load_case(case.model_dump(), {"contact.stiffness": K}), "ccfm"))
        assert np.allclose(ccfm[:2], imm[:2], rtol=0.0, atol=2e-6), ccfm - imm
        spins.append(abs(ccfm[2]))
    assert spins[1] < spins[0] / 3.0 and spins[1] * 0.5 * L < 1e-5
