"""Exact propagation of a damped mode eta'' + d eta' + w^2 eta = f(t) (``kernels/src/damped.c``) against independent
solutions: scipy's solve_ivp at tight tolerances, the matrix exponential of the oscillator augmented with its
polynomial forcing (exact for any stiffness), and the closed forms of a linear forcing's response."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from flexbeam.kernels import core

NODES = np.array(core.nodes())
ZETAS = [0.0, 0.01, 0.999, 1.0, 1.001, 50.0]
FORCING = np.array([0.8, -1.3, 0.4, 2.1])  # nodal values of the forcing at the step's Gauss nodes
ETA0, V0 = 0.7, -0.4


def propagate(w, d, h, s, eta0=ETA0, v0=V0, f=FORCING):
    """(eta, v) at the fraction s of a step h by the kernel's damped weights."""
    EE, EV, VE, VV, RE, RV = core.damped_weights(w, d, h, s)
    return EE * eta0 + EV * v0 + float(np.dot(RE, f)), VE * eta0 + VV * v0 + float(np.dot(RV, f))


def monomials(h, f=FORCING):
    """The forcing's monomial coefficients a_m of f = sum_m a_m (tau / h)^m (the interpolant of the nodal values)."""
    return np.linalg.solve(np.vander(NODES, 4, increasing=True), f)


def by_solve_ivp(w, d, h, s):
    a = monomials(h)

    def rhs(t, y):
        x = t / h
        return [y[1], a[0] + x * (a[1] + x * (a[2] + x * a[3])) - d * y[1] - w * w * y[0]]

    sol = solve_ivp(rhs, (0.0, s * h), [ETA0, V0], method="DOP853", rtol=1e-13, atol=1e-15)
    return sol.y[:, -1]


def by_expm(w, d, h, s):
    """The oscillator and the forcing's monomials u^m (u = tau / h, du/dtau = 1 / h) as one linear system
    y' = A y, y = [eta, v, 1, u, u^2, u^3]: exact through exp(A s h) (Higham's scaling and squaring)."""
    a = monomials(h)
    A = np.zeros((6, 6))
    A[0, 1] = 1.0
    A[1, 0], A[1, 1], A[1, 2:] = -w * w, -d, a
    for m in range(1, 4):  # (u^m)' = m u^(m-1) / h
        A[2 + m, 1 + m] = m / h
    return (expm(A * s * h) @ np.array([ETA0, V0, 1.0, 0.0, 0.0, 0.0]))[:2]


def energy_scale(w, eta, v):
    return w * abs(eta) + abs(v)


@pytest.mark.parametrize("zeta", ZETAS)
@pytest.mark.parametrize(("w", "h"), [(2.0, 0.05), (2.0, 1.0), (10.0, 0.3), (10.0, 2.0), (40.0, 0.5)])
@pytest.mark.parametrize("s", [0.37, 1.0])
def test_a_damped_mode_against_solve_ivp(zeta, w, h, s):
    """Every regime of damped.c (the ring's series and upward recurrence, the real roots' divided differences) at
    zeta = 0, 0.01, 0.999, 1, 1.001, 50, against DOP853 at rtol 1e-13: within 1e-10 of the energy-norm scale
    w |eta0| + |v0| + max|f| / w (measured <= 2e-13)."""
    d = 2.0 * zeta * w
    eta, v = propagate(w, d, h, s)
    ref = by_solve_ivp(w, d, h, s)
    scale = w * abs(ETA0) + abs(V0) + float(np.max(np.abs(FORCING))) / w
    assert w * abs(eta - ref[0]) + abs(v - ref[1]) < 1e-10 * scale


@pytest.mark.parametrize("zeta", ZETAS)
@pytest.mark.parametrize("wh", [1e-6, 0.01, 0.5, 2.99, 3.01, 20.0, 300.0, 1e4])
def test_a_damped_mode_against_the_matrix_exponential(zeta, wh):
    """The same propagation against exp(A h) of the augmented system, up to w h = 1e4 (zeta w h = 5e5: the fast root
    e^(-1e6) underflows, the slow one decays like e^(-100)), within 1e-9 of the scale (measured <= 1e-11, at zeta = 0
    and w h = 1e4; the matrix exponential's own error grows with the norm of A h)."""
    w, h = 7.0, wh / 7.0
    d = 2.0 * zeta * w
    eta, v = propagate(w, d, h, 1.0)
    ref = by_expm(w, d, h, 1.0)
    scale = w * abs(ETA0) + abs(V0) + float(np.max(np.abs(FORCING))) / w
    assert math.isfinite(eta) and math.isfinite(v)
    assert w * abs(eta - ref[0]) + abs(v - ref[1]) < 1e-9 * scale


@pytest.mark.parametrize("zeta", [1.0, 50.0, 1e3])
def test_a_linear_forcing_in_a_stiff_overdamped_mode_reaches_its_closed_form(zeta):
    """f = f0 + f1 t in a mode with w h = 1e5: the free response has decayed (the slow root ~ w / (2 zeta) >= 50 / h:
    e^(-50) at zeta = 1e3; the fast one ~ 2 zeta w underflows), so eta(h) = (f1 h + f0 - d f1 / w^2) / w^2 and
    v(h) = f1 / w^2 exactly (the particular solution A t + B: d A + w^2 (A t + B) = f1 t + f0), to 1e-12
    relative."""
    w, h, f0, f1 = 1e5, 1.0, 3.0, -2.0e3
    d = 2.0 * zeta * w
    f = f0 + f1 * h * NODES
    eta, v = propagate(w, d, h, 1.0, 0.0, 0.0, f)
    assert_allclose(eta, (f1 * h + f0 - d * f1 / w**2) / w**2, rtol=1e-12)
    assert_allclose(v, f1 / w**2, rtol=1e-12)


@pytest.mark.parametrize("w", [0.5, 3.0, 30.0])
def test_continuous_through_critical_damping(w):
    """The weights at zeta = 1 +- 1e-9 differ from those at zeta = 1 by what the equation's own sensitivity gives
    (~1e-9 relative), not by a division by nu = w sqrt(|1 - zeta^2|): the ring's entire functions of nu^2."""
    h = 0.7
    at = np.concatenate([np.ravel(x) for x in core.damped_weights(w, 2.0 * w, h, 1.0)])
    for zeta in (1.0 - 1e-9, 1.0 + 1e-9):
        near = np.concatenate([np.ravel(x) for x in core.damped_weights(w, 2.0 * zeta * w, h, 1.0)])
        assert np.max(np.abs(near - at)) < 1e-7 * np.max(np.abs(at))


@pytest.mark.parametrize(("w", "h"), [(2.0, 0.1), (5.0, 1.0), (100.0, 0.2)])
def test_zero_damping_is_the_undamped_propagation(w, h):
    """d = 0 in damped.c gives propagation.c's weights to round-off (the runs with zero damping never call it: their
    weights are propagation.c's, bit for bit)."""
    C, SW, WS, RE, RV = core.weights(w, h, 1.0)
    EE, EV, VE, VV, RE2, RV2 = core.damped_weights(w, 0.0, h, 1.0)
    scale = 1.0 + w * h
    assert_allclose([EE, EV * w, VE / w, VV], [C, SW * w, -WS / w, C], atol=1e-14 * scale)
    assert_allclose(np.array(RE2) * w * w, np.array(RE) * w * w, atol=1e-13 * scale)
    assert_allclose(RV2, RV, atol=1e-13 * scale * h)


@pytest.mark.parametrize(
    ("zeta", "wh"),
    [(z, wh) for z in (0.01, 0.5, 1.0, 3.0) for wh in (1.0, 7.0, 60.0) if 2.0 * z <= 4.0 * wh],  # d <= 4 w^2 h
)
def test_the_exact_dissipation_of_a_fast_damped_mode(zeta, wh):
    """d int_0^h v^2 dt of a mode turning up to ~10 times in the step (what the step's Gauss nodes cannot integrate),
    by the energy balance and the exact recursion over the cubic forcing's derivatives (damped.c fb_mode_dissipation,
    used for w h >= 1, d <= 4 w^2 h), against DOP853 integrating d v^2 with the mode (rtol 1e-12): to 1e-9 of the
    mode's energy scale (measured <= 1e-12)."""
    w = 5.0
    h, d = wh / w, 2.0 * zeta * w
    a = monomials(h)

    def rhs(t, y):
        x = t / h
        f = a[0] + x * (a[1] + x * (a[2] + x * a[3]))
        return [y[1], f - d * y[1] - w * w * y[0], d * y[1] * y[1]]

    sol = solve_ivp(rhs, (0.0, h), [ETA0, V0, 0.0], method="DOP853", rtol=1e-12, atol=1e-15)
    e1, v1, ref = sol.y[:, -1]
    got = core.damped_dissipation(w, d, h, tuple(float(x) for x in a), ETA0, V0, e1, v1)
    scale = 0.5 * (V0**2 + (w * ETA0) ** 2) + float(np.max(np.abs(FORCING))) ** 2 / w**2
    assert abs(got - ref) < 1e-9 * scale, abs(got - ref) / scale
