"""Properties of the model's building blocks at random states and parameters (Hypothesis).

* the impulse-momentum map (Khulief & Shabana 1987; ``methods/impulse.py``): with W = J M^-1 J^T and
  v^- = J z'^- < 0, the impulse P = -(1 + e) v^- / W >= 0, J z'^+ = -e J z'^- (0 for e = 0), the coordinates
  do not move, and the kinetic energy lost is (1 - e^2) (v^-)^2 / (2 W) (0 for e = 1), booked as dissipated
  energy;
* every contact law: F >= 0, F = 0 out of contact, the damping never feeds energy in ((F - F_k) d' >= 0), and
  its effective restitution on a 1-DOF mass (integrated here with scipy's DOP853, not with flexbeam's
  integrators) is the closed form :func:`flexbeam.validation.law_restitution`;
* the gap Jacobian J = d delta / dz (z = [theta, q]) against central differences, delta' = J z' and
  gamma = J' z' against differences along z', both frames, sphere and half-plane;
* the mass matrix M(z) is symmetric positive definite and its quadratic form is the kinetic energy.

Every tolerance is derived from round-off or from a finite-difference error estimate (in the comments); the
measured worst cases over the examples are quoted next to each.
"""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

import flexbeam as fb
from flexbeam.contact.laws import LAWS, law_force, make_law
from flexbeam.methods.impulse import impulse_jump
from flexbeam.model.system import BeamSystem
from flexbeam.validation import law_restitution

EPS = float(np.finfo(float).eps)
FRAMES = ("system", "hub")
MAX_MODES = 5
#: laws whose damping is infinite at e = 0 (the Case validation forbids e = 0 for them)
POSITIVE_E_LAWS = ("flores", "gonthier", "carvalho_martins", "kelvin_voigt")
#: contact stiffness of the half-plane obstacle (a line contact, so the case must give it) [N/m^1.5]
PLANE_STIFFNESS = 1e8


# ------------------------------------------------------------------------------------------------ strategies
@st.composite
def configurations(draw, obstacle: str = "sphere", hub_inertia=None):
    """(system, y): a seed-case beam in either frame with a random hub, n <= 5 modes and a modest random state.

    theta in [-4 mrad, 0.5 rad] about the impact angle 0 (the sphere touches P at theta = 0; a state more than
    half the sphere's radius inside it is rejected), |q_k| <= 1e-3 / k^2 (tip deflection <~ 2 mm),
    |q'_k| <= 0.3 / k, |theta'| <= 20 rad/s.
    """
    frame = draw(st.sampled_from(FRAMES))
    n = draw(st.integers(1, MAX_MODES))
    if hub_inertia is None:
        hub_inertia = st.one_of(st.just(0.0), st.floats(1e-3, 0.5))
    overrides = {
        "model.modes": n,
        "model.frame": frame,
        "hub.inertia": draw(hub_inertia),
        "hub.radius": draw(st.floats(0.0, 0.05)),
    }
    if obstacle == "half-plane":
        overrides |= {"obstacle.kind": "half-plane", "contact.stiffness": PLANE_STIFFNESS}
    system = BeamSystem.from_case(fb.load_case("seed-experiment", overrides))
    k = np.arange(1, n + 1)
    q = 1e-3 * np.array(draw(st.lists(st.floats(-1.0, 1.0), min_size=n, max_size=n))) / k**2
    qd = 0.3 * np.array(draw(st.lists(st.floats(-1.0, 1.0), min_size=n, max_size=n))) / k
    y = system.state(draw(st.floats(-0.004, 0.5)), draw(st.floats(-20.0, 20.0)), q, qd)
    if obstacle == "sphere":
        assume(system.gap(0.0, y)[0] > -0.5 * system.contact.obstacle.radius)
    return system, y


def positions(system: BeamSystem) -> slice:
    """Slice of z = [theta, q] in the state vector (free joint)."""
    return slice(0, system.n + 1)


def length_scale(system: BeamSystem) -> float:
    """Bound on |r_P| + |c| [m], the magnitudes the gap is computed from (P on the beam's surface, the obstacle
    placed against it)."""
    return 2.0 * (system.beam.length + system.beam.hub_radius + system.contact.offset) + system.contact.obstacle.radius


# ------------------------------------------------------------------------------------------ impulse map
def approaching(system: BeamSystem, y: np.ndarray) -> np.ndarray:
    """y with its velocities reversed if P moves away from the obstacle, so that J z' < 0."""
    J = system.gap(0.0, y)[3]
    zd = system.velocities(0.0, y)
    v = float(J @ zd)
    # an approach, not a tangential motion to round-off nor a speed at the edge of underflow (the case's rest
    # velocity is 1e-6 m/s)
    assume(abs(v) > max(1e-6 * float(np.abs(J) @ np.abs(zd)), 1e-9))
    return system.with_velocities(0.0, y, -zd) if v > 0.0 else y


def jump_round_off(system: BeamSystem, y: np.ndarray, P: float) -> tuple[float, float]:
    """Round-off bounds of (J z'^+, the kinetic energy change) of the jump at state y with impulse P.

    J z'^+ = J z'^- + (J u) P with u = M^-1 J^T: sums of N + 1 products of size |J_i| |z'_i| and |J_i u_i P|, so
    its error is <= (N + 1) eps times their sum.  The energies are quadratic forms, error <= (N + 1)^2 eps
    (1/2 |z'|^T |M| |z'|) each, and a backward-stable solve (M + E) u~ = J^T, |E| <= N eps |M|, changes T^+ by
    P z'^T E u~, <= N eps |P| |M| |z'| |u|.  Factor 10 for the constants these estimates leave out.
    """
    N = system.n + 1
    M = system.mass_matrix(0.0, y)
    J = system.gap(0.0, y)[3]
    zd = system.velocities(0.0, y)
    u = np.linalg.solve(M, J)
    vel = (N + 1) * EPS * (float(np.abs(J) @ np.abs(zd)) + abs(P) * float(np.abs(J) @ np.abs(u)))
    zd_plus = zd + u * P

    def quadratic_form_size(v: np.ndarray) -> float:
        return 0.5 * float(np.abs(v) @ np.abs(M) @ np.abs(v))

    energy = (N + 1) ** 2 * EPS * (quadratic_form_size(zd) + quadratic_form_size(zd_plus)) + N * EPS * abs(
        P
    ) * np.linalg.norm(M, 2) * (np.linalg.norm(zd) + np.linalg.norm(zd_plus)) * np.linalg.norm(u)
    return 10.0 * vel, 10.0 * energy


@settings(max_examples=40, deadline=None)
@given(config=configurations(), e=st.floats(0.0, 1.0))
def test_impulse_map_identities(config, e):
    """P >= 0, J z'^+ = -e J z'^-, coordinates unchanged, energy lost (1 - e^2) (v^-)^2 / (2 W) and booked.

    Measured worst error / tolerance over 600 random examples: 3.0e-2 (normal velocity), 1.0e-2 (energies; the
    energy error itself <= 1.3e-13 T^-).
    """
    system, y = config
    y = approaching(system, y)
    M = system.mass_matrix(0.0, y)
    J = system.gap(0.0, y)[3]
    v_minus = float(J @ system.velocities(0.0, y))
    W = float(J @ np.linalg.solve(M, J))
    T_minus = system.energies(0.0, y)["kinetic"]

    jump = impulse_jump(system, 0.0, y, e)
    y_plus = jump.y
    v_plus = float(system.gap(0.0, y_plus)[3] @ system.velocities(0.0, y_plus))
    after = system.energies(0.0, y_plus)
    tol_v, tol_T = jump_round_off(system, y, jump.impulse)

    assert jump.impulse > 0.0  # approaching contact: a compressive impulse
    np.testing.assert_array_equal(y_plus[positions(system)], y[positions(system)])
    assert abs(v_plus + e * v_minus) <= tol_v
    lost = T_minus - after["kinetic"]
    assert abs(lost - (1.0 - e * e) * v_minus**2 / (2.0 * W)) <= tol_T
    # the energy leaves T for the dissipated-energy integral; a free joint's torque does no work in a jump
    assert abs(after["dissipated"] - y[-2] - lost) <= tol_T
    assert abs(after["drive_work"] - y[-1]) <= tol_T


@settings(max_examples=25, deadline=None)
@given(config=configurations())
def test_elastic_impulse_keeps_the_kinetic_energy(config):
    """e = 1: T^+ = T^- (measured worst |T^+ - T^-| / tolerance 1e-2 over 600 random examples)."""
    system, y = config
    y = approaching(system, y)
    jump = impulse_jump(system, 0.0, y, 1.0)
    _, tol_T = jump_round_off(system, y, jump.impulse)
    assert abs(system.energies(0.0, jump.y)["kinetic"] - system.energies(0.0, y)["kinetic"]) <= tol_T


@settings(max_examples=25, deadline=None)
@given(config=configurations())
def test_plastic_impulse_stops_the_normal_velocity(config):
    """e = 0: J z'^+ = 0 (measured worst |J z'^+| / tolerance 3e-2 over 600 random examples)."""
    system, y = config
    y = approaching(system, y)
    jump = impulse_jump(system, 0.0, y, 0.0)
    tol_v, _ = jump_round_off(system, y, jump.impulse)
    assert abs(float(system.gap(0.0, jump.y)[3] @ system.velocities(0.0, jump.y))) <= tol_v


# ------------------------------------------------------------------------------------------- contact laws
def law_e(name: str):
    """Restitutions a law supports: [0, 1] for Hertz, Hunt-Crossley and Lankarani-Nikravesh, (0, 1] for the laws
    whose damping is infinite at e = 0.

    Lower bounds: Kelvin-Voigt 1e-3; Flores, Gonthier and Carvalho-Martins 0.05, because the reference
    ``law_restitution`` brackets its root between 1e-12 and (1 - 1e-15)/chi and raises for chi >~ 37 (Flores at
    e < 0.04, Gonthier and Carvalho-Martins at e < 0.026), where the root lies within 1e-15 of 1/chi.
    """
    if name == "kelvin_voigt":
        return st.floats(1e-3, 1.0)
    return st.floats(0.05, 1.0) if name in POSITIVE_E_LAWS else st.floats(0.0, 1.0)


@st.composite
def law_setups(draw):
    """(name, law, m, v0): a law with random K [N/m^n], exponent n, e, a mass m [kg] and impact speed v0 [m/s]."""
    name = draw(st.sampled_from(list(LAWS)))
    K = 10.0 ** draw(st.floats(5.0, 11.0))
    n = draw(st.floats(1.0, 2.5))
    law = make_law(name, K, n, draw(law_e(name)))
    return name, law, 10.0 ** draw(st.floats(-2.0, 1.0)), 10.0 ** draw(st.floats(-2.0, 1.0))


@settings(max_examples=200, deadline=None)
@given(setup=law_setups(), d=st.floats(-1e-3, 1e-3), rate=st.floats(-10.0, 10.0))
def test_law_force_is_compressive_and_never_feeds_energy(setup, d, rate):
    """F >= 0 and F_k = K d^n >= 0 in contact, F = F_k = 0 out of it, and (F - F_k) d' >= 0: the damping part
    only dissipates, also where the force is clipped at zero (exact signs, no tolerance)."""
    _, law, m, v0 = setup
    F, Fk = law_force(law.parameters(v0, m), d, rate)
    assert F == law.force(d, rate, v0, m)
    if d <= 0.0:
        assert F == 0.0 and Fk == 0.0  # out of contact: no force, no potential
        return
    assert F >= 0.0 and Fk >= 0.0
    assert (F - Fk) * rate >= 0.0  # the damping part dissipates: exact sign, no tolerance needed


def one_dof_impact(law, m: float, v0: float) -> float:
    """-d'_end / v0 of a mass m hitting the law at speed v0: m d'' = -F(d, d') from d = 0, d' = v0 until d = 0.

    Integrated by scipy's DOP853 (rtol 1e-12, atol 1e-15 of the scales) in the undamped contact's scales d_max
    (energy balance 1/2 m v0^2 = K d_max^(n+1) / (n + 1)) and d_max / v0.
    """
    p = law.parameters(v0, m)
    K, n = p[0], p[1]
    dmax = ((n + 1.0) * m * v0**2 / (2.0 * K)) ** (1.0 / (n + 1.0))
    tau = dmax / v0

    def rhs(s, x):  # x = (d / d_max, d' / v0), s = t / tau
        return [x[1], -law_force(p, x[0] * dmax, x[1] * v0)[0] * tau / (m * v0)]

    def separation(s, x):
        return x[0]

    separation.terminal, separation.direction = True, -1
    # the terminal event ends the run; the span only bounds it (the slowest return, speed e_eff v0 over a
    # penetration <= d_max, takes <~ 1 / e_eff scaled times)
    sol = solve_ivp(rhs, (0.0, 1e4), [0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-15, events=separation)
    assert sol.status == 1, "the mass did not come back"
    return -float(sol.y_events[0][0][1])


@settings(max_examples=40, deadline=None)
@given(setup=law_setups())
def test_law_restitution_on_a_rigid_mass_is_the_closed_form(setup):
    """The effective restitution at random m, K, n, v0, e equals the law's closed form.

    The HC family's value is independent of m, K, n and v0 (Carvalho & Martins 2019), the Kelvin-Voigt one of
    k, m and v0 (zeta is set from e and the mass).  Measured worst |error| over 1200 random examples 4.8e-11
    (Lankarani-Nikravesh), 1.6e-11 (Kelvin-Voigt, whose clipped force has a kink); tolerance 1e-9 (20x).
    """
    name, law, m, v0 = setup
    assert abs(one_dof_impact(law, m, v0) - law_restitution(name, law.restitution)) <= 1e-9


# ------------------------------------------------------------------------------------------- gap kinematics
def richardson_error(f, h: float, scale: float) -> tuple[float, float]:
    """Central difference (f(h) - f(-h)) / 2h of a scalar f(s) and a bound on its error.

    Truncation: D_h = f' + h^2 f'''/6 + O(h^4), so D_2h - D_h = h^2 f'''/2 + O(h^4) and the truncation error of
    D_h is |D_2h - D_h| / 3 (the O(h^4) rest is far below it for the steps used).  Round-off: f is computed from
    coordinates of magnitude <= ``scale`` with an absolute error <= 8 eps scale, giving 8 eps scale / h.
    Factor 10 over the sum for the constants these estimates leave out.
    """
    fp, fm, f2p, f2m = f(h), f(-h), f(2 * h), f(-2 * h)
    d1, d2 = (fp - fm) / (2 * h), (f2p - f2m) / (4 * h)
    return d1, 10.0 * (abs(d2 - d1) / 3.0 + 8.0 * EPS * scale / h)


def second_difference(f, h: float, scale: float) -> tuple[float, float]:
    """(f(h) - 2 f(0) + f(-h)) / h^2 and its error bound: truncation |D2_2h - D2_h| / 3 (D2_h = f'' +
    h^2 f''''/12 + O(h^4)), round-off 4 (8 eps scale) / h^2; factor 10 as above."""
    f0 = f(0.0)
    d1 = (f(h) - 2 * f0 + f(-h)) / h**2
    d2 = (f(2 * h) - 2 * f0 + f(-2 * h)) / (4 * h * h)
    return d1, 10.0 * (abs(d2 - d1) / 3.0 + 32.0 * EPS * scale / h**2)


def check_gap_kinematics(system: BeamSystem, y: np.ndarray) -> tuple[float, float, float]:
    """Assert J, delta' and gamma against differences; return the worst error / tolerance of each."""
    delta, rate, gamma, J = system.gap(0.0, y)
    z = positions(system)
    R = length_scale(system)
    worst_J = 0.0
    h = 1e-6  # about (eps R / |delta'''|)^(1/3) for |delta'''| up to ~1e3; the error estimate covers the rest
    for i in range(system.n + 1):

        def along(s, i=i):
            yy = y.copy()
            yy[i] += s
            return system.gap(0.0, yy)[0]

        fd, tol = richardson_error(along, h, R)
        assert abs(J[i] - fd) <= tol, (i, J[i], fd, tol)
        worst_J = max(worst_J, abs(J[i] - fd) / tol)

    zd = system.velocities(0.0, y)
    dr = system.point_state(0.0, y, 0)[3]
    # delta' = n . (dr/dz z') and J z' = (n . dr/dz) z': sums of 2 (N + 1) products of size |dr/dz_i| |z'_i|
    # each; error <= 2 (N + 1) eps times their sum for each, factor 10 again
    tol_rate = 10.0 * 4.0 * (system.n + 1) * EPS * float(np.linalg.norm(dr, axis=0) @ np.abs(zd))
    assert abs(rate - J @ zd) <= tol_rate

    def path(s):
        yy = y.copy()
        yy[z] += s * zd
        return system.gap(0.0, yy)[0]

    hs = 1e-6 / max(float(np.linalg.norm(zd)), 1e-3)  # a step of ~1e-6 in z along z'
    fd_rate, tol = richardson_error(path, hs, R)
    assert abs(rate - fd_rate) <= tol
    worst_rate = abs(rate - fd_rate) / tol
    hs2 = 1e-4 / max(float(np.linalg.norm(zd)), 1e-3)  # second differences: round-off / h^2, a longer step
    fd_gamma, tol = second_difference(path, hs2, R)
    assert abs(gamma - fd_gamma) <= tol, (gamma, fd_gamma, tol)
    return worst_J, worst_rate, abs(gamma - fd_gamma) / tol


@settings(max_examples=30, deadline=None)
@given(config=configurations("sphere"))
def test_sphere_gap_jacobian_rate_and_curvature_match_differences(config):
    """Sphere: J, delta' = J z' and gamma = J' z' against differences.

    Measured worst error / tolerance over 600 random examples: 5.9e-2 (J), 3.2e-2 (delta'), 0.10 (gamma: the
    truncation estimate is the error, the factor 10 is the margin); the tolerance on J is <= 8e-7 |J|, on gamma
    <= 1.1e-2 |gamma|.
    """
    check_gap_kinematics(*config)


@settings(max_examples=30, deadline=None)
@given(config=configurations("half-plane"))
def test_half_plane_gap_jacobian_rate_and_curvature_match_differences(config):
    """Half-plane: as for the sphere (measured worst error / tolerance 2.3e-3, 2.4e-3, 7.5e-2)."""
    check_gap_kinematics(*config)


# ------------------------------------------------------------------------------------------------ mass matrix
@settings(max_examples=40, deadline=None)
@given(config=configurations(hub_inertia=st.one_of(st.just(0.0), st.floats(1e-3, 0.5))))
def test_mass_matrix_is_symmetric_positive_definite_and_gives_the_kinetic_energy(config):
    """M(z) = M^T > 0 and T = 1/2 z'^T M z'.

    Symmetry and T to round-off: entries are sums of O(N^2) products, error <= N^2 eps |M|; T <= (N + 1)^2 eps
    (1/2 |z'|^T |M| |z'|); factor 10.  Positive definiteness: Cholesky succeeds and the smallest eigenvalue
    exceeds the eigen-solver's error N eps |M|_2 (smallest measured: 5.7e-5 kg m^2, hub frame, J_h = 0, the
    light root-slope coordinate of docs/formulation.md).  Measured: M exactly symmetric, T error / tolerance
    <= 1.1e-2 over 600 random examples.
    """
    system, y = config
    N = system.n + 1
    M = system.mass_matrix(0.0, y)
    big = float(np.max(np.abs(M)))
    np.testing.assert_allclose(M, M.T, rtol=0, atol=10.0 * N * N * EPS * big)
    np.linalg.cholesky(M)
    assert np.linalg.eigvalsh(M)[0] > 10.0 * N * EPS * np.linalg.norm(M, 2)
    zd = system.velocities(0.0, y)
    T = system.energies(0.0, y)["kinetic"]
    assert abs(T - 0.5 * zd @ M @ zd) <= 10.0 * (N + 1) ** 2 * EPS * 0.5 * float(np.abs(zd) @ np.abs(M) @ np.abs(zd))
