"""Lagrange's equations derived with sympy from the kinematics, against flexbeam's kernels.

Independent derivation (nothing of flexbeam's equations is used):

* kinematics of a two-mode beam on a hub of radius r_h and inertia J_h,
  rho(x) = (r_h + x + u_x, u_y), r = A(theta) rho, u_y = phi_1(x) q_1 + phi_2(x) q_2 and the
  coupling (foreshortening) deformation u_x = -1/2 int_0^x (du_y/dxi)^2 dxi = -1/2 q^T H(x) q
  (first-order model) or u_x = 0 (zeroth-order model);
* T = 1/2 J_h theta'^2 + 1/2 int mu |r'|^2 dx, truncated to second order in (q, q') with a
  bookkeeping parameter eps (q -> eps q, q' -> eps q', keep eps^0..eps^2);
  V = 1/2 int EI (u_y'')^2 dx + g int mu r_y dx, a joint torque tau;
* M = d^2 T / dz' dz',  Q = tau e_theta - (d/dt dT/dz')|_{z''=0} + dT/dz - dV/dz.

cos(theta) and sin(theta) are the symbols C, S (d/dtheta = -S d/dC + C d/dS) and C^2 + S^2 = 1
is imposed by polynomial reduction.  The x-dependence stays symbolic (b = r_h + x, phi_i(x),
phi_i''(x), H_ij(x)) until the integrals over x: each monomial of these becomes one symbol
<w * monomial> = int_0^L w(x) monomial(x) dx (w = mu or EI), evaluated here by Gauss-Legendre
quadrature of the classical clamped-free eigenfunctions written out in this file, with H(x)
itself computed by a nested quadrature of phi_i' phi_j' (not by flexbeam's integration by parts).

M(q) and the parts of Q (elastic, velocity-dependent, gravity, torque) are compared with
``BeamSystem.mass_matrix`` / ``BeamSystem.generalized_forces`` at random states to 1e-10
relative, for both coupling models, with and without a hub.
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
g, tau, Jh = sp.symbols("g tau J_h", real=True)
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
    ux = -sp.Rational(1, 2) * sum(H[i][j] * qe[i] * qe[j] for i in range(2) for j in range(2)) \
        if first_order else sp.Integer(0)
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
    T = sp.Rational(1, 2) * Jh * w**2 + _integrate(density_T, "mu", integrals)
    V = _integrate(density_Ve, "EI", integrals) + _integrate(density_Vg, "mu", integrals)
    N = len(Z)
    M = sp.Matrix(N, N, lambda i, j: sp.diff(T, ZD[i], ZD[j]))
    Q = []
    for i in range(N):
        dTdv = sp.diff(T, ZD[i])
        ddt = sum(_d(dTdv, Z[j]) * ZD[j] for j in range(N))  # d/dt at z'' = 0
        Q.append(sp.expand((tau if i == 0 else 0) - ddt + _d(T, Z[i]) - _d(V, Z[i])))
    assert all(not M[i, j].has(C, S) for i in range(N) for j in range(N))
    return M, sp.Matrix(Q), integrals


# ---------------------------------------------------------------------------------------
# numbers: own mode shapes and quadrature
# ---------------------------------------------------------------------------------------
def _roots(n):
    return [brentq(lambda z: math.cos(z) * math.cosh(z) + 1.0, (k - 0.5) * math.pi - 0.6,
                   (k - 0.5) * math.pi + 0.6, xtol=1e-15) for k in range(1, n + 1)]


def modes(x, derivative=0):
    """Classical clamped-free eigenfunctions (int phi^2 = L) and derivatives, shape (m, 2)."""
    x = np.atleast_1d(x)
    cols = []
    for z in _roots(2):
        be = z / L
        sig = (math.cosh(z) + math.cos(z)) / (math.sinh(z) + math.sin(z))
        y = be * x
        ch, sh, c, s = np.cosh(y), np.sinh(y), np.cos(y), np.sin(y)
        cols.append({0: ch - c - sig * (sh - s),
                     1: be * (sh + s - sig * (ch - c)),
                     2: be**2 * (ch + c - sig * (sh + s))}[derivative])
    return np.stack(cols, axis=1)


def _gauss(lo, hi, m):
    xi, wi = np.polynomial.legendre.leggauss(m)
    return 0.5 * (hi - lo) * xi + 0.5 * (hi + lo), 0.5 * (hi - lo) * wi


def integral_values(integrals: dict, hub_radius: float) -> dict:
    """Numbers of the integral symbols by Gauss-Legendre quadrature (H by nested quadrature)."""
    x, wx = _gauss(0.0, L, 60)
    H = np.empty((x.size, 2, 2))
    for k, xk in enumerate(x):
        xs, ws = _gauss(0.0, xk, 40)
        d1 = modes(xs, 1)
        H[k] = (d1 * ws[:, None]).T @ d1
    fields = [hub_radius + x, *modes(x, 0).T, *modes(x, 2).T, H[:, 0, 0], H[:, 0, 1], H[:, 1, 1]]
    out = {}
    for (weight, monom), sym in integrals.items():
        f = np.ones_like(x)
        for field_, e in zip(fields, monom):
            f = f * field_**e
        out[sym] = float(np.sum(wx * (MU if weight == "mu" else EI) * f))
    return out


def make_case(coupling: str, hub_radius: float, hub_inertia: float, gravity: float, torque: float) -> Case:
    return Case.model_validate({
        "beam": {"length": L, "density": 2.0, "youngs_modulus": 3.0, "section": "general",
                 "area": MU / 2.0, "second_moment": EI / 3.0, "half_depth": 0.05},
        "hub": {"radius": hub_radius, "inertia": hub_inertia},
        "model": {"modes": 2, "coupling": coupling, "gravity": gravity},
        "drive": {"kind": "torque", "torque": torque},
        "contact": {"position": 0.8 * L, "stiffness": 1e6},
    })


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


@pytest.mark.parametrize("coupling", ["first-order", "zeroth-order"])
@pytest.mark.parametrize("hub", [(0.0, 0.0), (0.4, 0.25)], ids=["no-hub", "hub"])
def test_mass_matrix_and_forces_match_flexbeam(coupling, hub):
    M_sym, Q_sym, integrals = derive(coupling == "first-order")
    values = integral_values(integrals, hub[0])
    args = (th, w, *q, *u, g, tau, Jh)
    subs = {**values, C: sp.cos(th), S: sp.sin(th)}
    f_M = sp.lambdify(args, M_sym.subs(subs), "numpy")
    f_Q = sp.lambdify(args, Q_sym.subs(subs), "numpy")

    def sympy_MQ(state, grav, torque):
        return (np.array(f_M(*state, grav, torque, hub[1]), float),
                np.array(f_Q(*state, grav, torque, hub[1]), float).ravel())

    systems = {(gr, tq): BeamSystem.from_case(make_case(coupling, hub[0], hub[1], gr, tq))
               for gr in (0.0, GRAV) for tq in (0.0, TAU)}

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
        # joint torque acts on theta only
        Qt_f = flex_MQ(state, GRAV, TAU)[1] - flex_MQ(state, GRAV, 0.0)[1]
        np.testing.assert_allclose(Qt_f, [TAU, 0.0, 0.0], rtol=0, atol=1e-12)
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
