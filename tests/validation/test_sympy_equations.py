"""Lagrange's equations derived with sympy from the kinematics, against flexbeam's kernels.

Independent derivation (nothing of flexbeam's equations is used), in both body frames:

* kinematics of a two-mode beam on a hub of radius r_h and inertia J_h, in a frame turned by theta:
  the beam is clamped to the hub's rim, whose angle relative to the frame is alpha = asin(d q) (d_i = phi_i'(0),
  zero in the hub frame: there the frame is the hub); the root sits at r_h (cos alpha, sin alpha) and the
  inextensible beam shortens, rho(x) = (r_h cos alpha + x - 1/2 int_0^x (du_y/dxi)^2 dxi, u_y),
  u_y = phi_1(x) q_1 + phi_2(x) q_2 (first-order model; the zeroth-order model keeps rho_x = r_h + x);
  r = A(theta) rho;
* T = 1/2 J_h (theta' + alpha')^2 + 1/2 int mu |r'|^2 dx, truncated to second order in (q, q') with a
  bookkeeping parameter eps (q -> eps q, q' -> eps q', keep eps^0..eps^2);
  V = 1/2 int EI (u_y'')^2 dx + g int mu r_y dx; a joint torque tau on the hub angle theta + alpha;
* M = d^2 T / dz' dz',  Q = tau d(theta + alpha)/dz - (d/dt dT/dz')|_{z''=0} + dT/dz - dV/dz.

Shape functions: in the hub frame the classical clamped-free eigenfunctions written out in this file; in the
system frame flexbeam's hub + beam eigenmodes, taken as given (they are checked against closed forms and their
boundary conditions in tests/unit/test_modes.py): this test checks the equations for the shapes.

cos(theta) and sin(theta) are the symbols C, S (d/dtheta = -S d/dC + C d/dS) and C^2 + S^2 = 1
is imposed by polynomial reduction.  The x-dependence stays symbolic (b = r_h + x, phi_i(x),
phi_i''(x), H_ij(x) = int_0^x phi_i' phi_j') until the integrals over x: each monomial of these becomes one
symbol <w * monomial> = int_0^L w(x) monomial(x) dx (w = mu or EI), evaluated here by Gauss-Legendre
quadrature, with H(x) itself computed by a nested quadrature of phi_i' phi_j' (not by flexbeam's integration
by parts).

M(q) and the parts of Q (elastic, velocity-dependent, gravity, torque) are compared with
``BeamSystem.mass_matrix`` / ``BeamSystem.generalized_forces`` at random states to 1e-10
relative, for both coupling models and both frames, with and without a hub.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import brentq

from flexbeam.model.modes import cantilever_modes
from flexbeam.model.system import BeamSystem
from flexbeam.parameters.case import Case

RTOL = 1e-10
L, MU, EI = 1.3, 2.1, 3.6  # length [m], line density [kg/m], bending stiffness [N m^2]
GRAV, TAU = 9.81, -1.7

# ---------------------------------------------------------------------------------------
# symbols
# ---------------------------------------------------------------------------------------
th, w, eps = sp.symbols("theta omega epsilon", real=True)
q = sp.symbols("q1:3", real=True)
u = sp.symbols("qd1:3", real=True)
C, S = sp.symbols("C S", real=True)  # cos(theta), sin(theta)
g, tau, Jh, rh = sp.symbols("g tau J_h r_h", real=True)
d = sp.symbols("d1:3", real=True)  # hub slopes phi_i'(0) (zero in the hub frame)
# x-dependent quantities at one material point
b = sp.Symbol("b", real=True)  # r_h + x
p = sp.symbols("phi1:3", real=True)  # phi_i(x)
a = sp.symbols("ddphi1:3", real=True)  # phi_i''(x)
h11, h12, h22 = sp.symbols("H11 H12 H22", real=True)  # H_ij(x) = int_0^x phi_i' phi_j'
XSYMS = (b, *p, *a, h11, h12, h22)
Z, ZD = (th, *q), (w, *u)


def _d_theta(expr):
    """d/dtheta of an expression in C = cos(theta), S = sin(theta)."""
    return -S * sp.diff(expr, C) + C * sp.diff(expr, S)


def _d(expr, var):
    return _d_theta(expr) if var is th else sp.diff(expr, var)


def _reduce_trig(expr):
    """Impose C^2 + S^2 = 1 (remainder of the polynomial division)."""
    return sp.reduced(sp.expand(expr), [C**2 + S**2 - 1], C, S)[1]


def _truncate(expr, order=2):
    """Keep eps^0..eps^order, then eps = 1."""
    poly = sp.Poly(sp.expand(expr), eps)
    return sp.expand(sum(coeff * eps**k for (k,), coeff in poly.terms() if k <= order).subs(eps, 1))


def _integrate(expr, weight: str, integrals: dict):
    """Replace every monomial of the x-quantities by the symbol of its weighted integral."""
    poly = sp.Poly(sp.expand(expr), *XSYMS)
    out = 0
    for monom, coeff in poly.terms():
        key = (weight, monom)
        if key not in integrals:
            integrals[key] = sp.Symbol(f"I{len(integrals)}", real=True)
        out += coeff * integrals[key]
    return sp.expand(out)


@functools.cache
def derive(first_order: bool):
    """Symbolic M(q), Q(z, z') and the integral symbols they use."""
    qe = [eps * qi for qi in q]  # q -> eps q; then dr/dt = sum dr/dq_i q_i' carries eps q_i' too
    H = [[h11, h12], [h12, h22]]
    uy = p[0] * qe[0] + p[1] * qe[1]
    slope = d[0] * qe[0] + d[1] * qe[1]  # sin(alpha), the root slope in the frame
    # the rim's shortening r_h (1 - cos alpha) = r_h (1 - sqrt(1 - sin^2 alpha)), as a series in eps
    rim = rh * sp.series(1 - sp.sqrt(1 - slope**2), eps, 0, 3).removeO()
    ux = (
        (-rim - sp.Rational(1, 2) * sum(H[i][j] * qe[i] * qe[j] for i in range(2) for j in range(2)))
        if first_order
        else sp.Integer(0)
    )
    X, Y = b + ux, uy
    r = sp.Matrix([C * X - S * Y, S * X + C * Y])
    # r' = dr/dtheta theta' + sum dr/dq_i q_i' (dr/dq_i carries the eps of q -> eps q: q' -> eps q')
    rdot = r.applyfunc(_d_theta) * w + sum((r.diff(qi) * ui for qi, ui in zip(q, u)), sp.zeros(2, 1))
    density_T = _truncate(_reduce_trig(sp.Rational(1, 2) * (rdot.T * rdot)[0]))
    assert not density_T.has(C) and not density_T.has(S)  # the kinetic energy is frame-invariant
    uyxx = a[0] * qe[0] + a[1] * qe[1]
    density_Ve = _truncate(sp.Rational(1, 2) * uyxx**2)
    density_Vg = _truncate(g * r[1])
    integrals: dict = {}
    # alpha' = (d q')/sqrt(1 - (d q)^2) = eps (d q') + O(eps^3): the hub's energy to second order
    alpha_rate = eps * (d[0] * u[0] + d[1] * u[1])
    T_hub = _truncate(sp.Rational(1, 2) * Jh * (w + alpha_rate) ** 2)
    T = T_hub + _integrate(density_T, "mu", integrals)
    V = _integrate(density_Ve, "EI", integrals) + _integrate(density_Vg, "mu", integrals)
    N = len(Z)
    M = sp.Matrix(N, N, lambda i, j: sp.diff(T, ZD[i], ZD[j]))
    Q = []
    for i in range(N):
        dTdv = sp.diff(T, ZD[i])
        ddt = sum(_d(dTdv, Z[j]) * ZD[j] for j in range(N))  # d/dt at z'' = 0
        # the torque's virtual work tau d(theta + alpha) = tau (d theta + d.dq) to the model's order
        work = tau if i == 0 else tau * d[i - 1]
        Q.append(sp.expand(work - ddt + _d(T, Z[i]) - _d(V, Z[i])))
    assert all(not M[i, j].has(C, S) for i in range(N) for j in range(N))
    return M, sp.Matrix(Q), integrals


# ---------------------------------------------------------------------------------------
# numbers: own mode shapes and quadrature
# ---------------------------------------------------------------------------------------
def _roots(n):
    return [
        brentq(
            lambda z: math.cos(z) * math.cosh(z) + 1.0, (k - 0.5) * math.pi - 0.6, (k - 0.5) * math.pi + 0.6, xtol=1e-15
        )
        for k in range(1, n + 1)
    ]


def modes(x, derivative=0):
    """Classical clamped-free eigenfunctions (int phi^2 = L) and derivatives, shape (m, 2)."""
    x = np.atleast_1d(x)
    cols = []
    for z in _roots(2):
        be = z / L
        sig = (math.cosh(z) + math.cos(z)) / (math.sinh(z) + math.sin(z))
        y = be * x
        ch, sh, c, s = np.cosh(y), np.sinh(y), np.cos(y), np.sin(y)
        cols.append(
            {0: ch - c - sig * (sh - s), 1: be * (sh + s - sig * (ch - c)), 2: be**2 * (ch + c - sig * (sh + s))}[
                derivative
            ]
        )
    return np.stack(cols, axis=1)


def _gauss(lo, hi, m):
    xi, wi = np.polynomial.legendre.leggauss(m)
    return 0.5 * (hi - lo) * xi + 0.5 * (hi + lo), 0.5 * (hi - lo) * wi


def integral_values(integrals: dict, hub_radius: float, shapes=modes) -> dict:
    """Numbers of the integral symbols by Gauss-Legendre quadrature (H by nested quadrature) for ``shapes``
    (x, derivative) -> (m, 2), and of the hub slopes d_i = phi_i'(0) and r_h."""
    x, wx = _gauss(0.0, L, 60)
    H = np.empty((x.size, 2, 2))
    for k, xk in enumerate(x):
        xs, ws = _gauss(0.0, xk, 40)
        d1 = shapes(xs, 1)
        H[k] = (d1 * ws[:, None]).T @ d1
    fields = [hub_radius + x, *shapes(x, 0).T, *shapes(x, 2).T, H[:, 0, 0], H[:, 0, 1], H[:, 1, 1]]
    out = {}
    for (weight, monom), sym in integrals.items():
        f = np.ones_like(x)
        for field_, e in zip(fields, monom):
            f = f * field_**e
        out[sym] = float(np.sum(wx * (MU if weight == "mu" else EI) * f))
    slope = shapes(np.zeros(1), 1)[0] if shapes is not modes else np.zeros(2)
    out.update({d[0]: float(slope[0]), d[1]: float(slope[1]), rh: hub_radius})
    return out


def make_case(
    coupling: str, hub_radius: float, hub_inertia: float, gravity: float, torque: float, frame: str = "hub"
) -> Case:
    return Case.model_validate(
        {
            "beam": {
                "length": L,
                # rho S = MU, E I = EI as before (scaled by powers of two) on a slender section (sqrt(I/S)/L = 0.016)
                "density": 2.0 * 2.0**12,
                "youngs_modulus": 3.0 * 2.0**24,
                "section": "general",
                "area": MU / 2.0 / 2.0**12,
                "second_moment": EI / 3.0 / 2.0**24,
                "half_depth": 0.05,
            },
            "hub": {"radius": hub_radius, "inertia": hub_inertia},
            "model": {"modes": 2, "coupling": coupling, "gravity": gravity, "frame": frame},
            "drive": {"kind": "torque", "torque": torque},
            "contact": {"position": 0.8 * L, "stiffness": 1e6},
        }
    )


# ---------------------------------------------------------------------------------------
# tests
# ---------------------------------------------------------------------------------------
def test_own_mode_shapes_match_flexbeams_convention():
    x = np.linspace(0.0, L, 23)
    for k in range(3):
        np.testing.assert_allclose(modes(x, k), cantilever_modes(x, L, 2, k), rtol=1e-11, atol=1e-11)


def test_kinetic_energy_has_the_textbook_structure():
    """M_theta,theta = J_h + J0 + q^T (M_ff - D) q: quadratic in q, constant elsewhere."""
    M, Q, _ = derive(True)
    assert sp.Poly(M[0, 0], *q).total_degree() == 2
    for i in range(3):
        for j in range(3):
            if (i, j) != (0, 0):
                assert not M[i, j].has(*q, *u, th, w)
    assert sp.Poly(Q[0], *q, *u).total_degree() <= 2
    M0, _, _ = derive(False)
    assert sp.Poly(M0[0, 0], *q).total_degree() == 2  # q^T M_ff q survives without u_x


STATES = np.random.default_rng(2024).uniform(-1.0, 1.0, size=(6, 6)) * [math.pi, 3.0, 0.3, 0.1, 2.0, 1.0]


@pytest.mark.parametrize("frame", ["hub", "system"])
@pytest.mark.parametrize("coupling", ["first-order", "zeroth-order"])
@pytest.mark.parametrize("hub", [(0.0, 0.0), (0.4, 0.25)], ids=["no-hub", "hub"])
def test_mass_matrix_and_forces_match_flexbeam(coupling, hub, frame):
    M_sym, Q_sym, integrals = derive(coupling == "first-order")
    shapes = modes
    if frame == "system":
        shapes = BeamSystem.from_case(make_case(coupling, hub[0], hub[1], 0.0, 0.0, frame)).beam.shapes
    values = integral_values(integrals, hub[0], shapes)
    args = (th, w, *q, *u, g, tau, Jh)
    subs = {**values, C: sp.cos(th), S: sp.sin(th)}
    f_M = sp.lambdify(args, M_sym.subs(subs), "numpy")
    f_Q = sp.lambdify(args, Q_sym.subs(subs), "numpy")

    def sympy_MQ(state, grav, torque):
        return (
            np.array(f_M(*state, grav, torque, hub[1]), float),
            np.array(f_Q(*state, grav, torque, hub[1]), float).ravel(),
        )

    systems = {
        (gr, tq): BeamSystem.from_case(make_case(coupling, hub[0], hub[1], gr, tq, frame))
        for gr in (0.0, GRAV)
        for tq in (0.0, TAU)
    }

    def flex_MQ(state, grav, torque):
        s = systems[(grav, torque)]
        y = s.state(state[0], state[1], state[2:4], state[4:6])
        return s.mass_matrix(0.0, y), s.generalized_forces(0.0, y)

    def close(got, ref):
        scale = np.max(np.abs(ref))
        assert scale > 0.0
        np.testing.assert_allclose(got, ref, rtol=0.0, atol=RTOL * scale)

    for state in STATES:
        static = state.copy()
        static[[1, 4, 5]] = 0.0  # no theta', q'
        # mass matrix
        close(flex_MQ(state, GRAV, TAU)[0], sympy_MQ(state, GRAV, TAU)[0])
        # elastic (static, no gravity, no torque): -K q
        Qe_s = sympy_MQ(static, 0.0, 0.0)[1]
        close(flex_MQ(static, 0.0, 0.0)[1], Qe_s)
        # velocity-dependent (centrifugal, Coriolis, geometric stiffening)
        Qv_s = sympy_MQ(state, 0.0, 0.0)[1] - Qe_s
        Qv_f = flex_MQ(state, 0.0, 0.0)[1] - flex_MQ(static, 0.0, 0.0)[1]
        close(Qv_f, Qv_s)
        # gravity
        Qg_s = sympy_MQ(state, GRAV, 0.0)[1] - sympy_MQ(state, 0.0, 0.0)[1]
        Qg_f = flex_MQ(state, GRAV, 0.0)[1] - flex_MQ(state, 0.0, 0.0)[1]
        close(Qg_f, Qg_s)
        # the joint torque acts on the hub angle theta + d q
        Qt_f = flex_MQ(state, GRAV, TAU)[1] - flex_MQ(state, GRAV, 0.0)[1]
        Qt_s = sympy_MQ(state, GRAV, TAU)[1] - sympy_MQ(state, GRAV, 0.0)[1]
        np.testing.assert_allclose(Qt_f, Qt_s, rtol=0, atol=1e-12)
        if frame == "hub":
            np.testing.assert_allclose(Qt_f, [TAU, 0.0, 0.0], rtol=0, atol=1e-12)
        else:
            assert abs(Qt_f[1]) > 1e-3 * abs(TAU)  # the root slope carries the torque to the modes
        # and the whole thing at once
        close(flex_MQ(state, GRAV, TAU)[1], sympy_MQ(state, GRAV, TAU)[1])


def test_zeroth_order_differs_from_first_order():
    """Sanity: the comparison is sensitive to the coupling deformation (D and G are not small)."""
    state = STATES[0]
    vals = {}
    for coupling in ("first-order", "zeroth-order"):
        M_sym, Q_sym, integrals = derive(coupling == "first-order")
        subs = {**integral_values(integrals, 0.4), C: sp.cos(th), S: sp.sin(th)}
        f_Q = sp.lambdify((th, w, *q, *u, g, tau, Jh), Q_sym.subs(subs), "numpy")
        vals[coupling] = np.array(f_Q(*state, GRAV, 0.0, 0.25), float).ravel()
    diff = np.abs(vals["first-order"] - vals["zeroth-order"])
    assert np.all(diff[1:] > 1e-3 * np.abs(vals["first-order"][1:]))
