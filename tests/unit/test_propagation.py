"""Exact modal propagation of the compiled integrator (``kernels/src/propagation.c``) against quadrature and an
ODE solver."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad, solve_ivp

from flexbeam.kernels import core

MOMENT_SERIES = 1.0  # propagation.c: power series below this argument, recurrences above
THETAS = [0.0, 1e-8, 0.3, 0.999 * MOMENT_SERIES, MOMENT_SERIES, 1.001 * MOMENT_SERIES, 2.5, 40.0, 3.0e3]


@pytest.mark.parametrize("theta", THETAS)
def test_moments_equal_their_integrals(theta):
    """Cm, Sm of the kernels' moments are the integrals of cos(theta (1 - u)) u^m and sin(...) u^m / theta.

    Truth: adaptive quadrature of the defining integrals (sin(theta x) / theta written as
    x sinc, so theta = 0 is the limit 1 / ((m + 1) (m + 2))), on both sides of the
    series/recurrence switch.
    """
    p = 4
    Cm, Sm = core.moments(theta)
    for m in range(p):
        if theta < 10.0:
            c = quad(lambda u, m=m: math.cos(theta * (1 - u)) * u**m, 0, 1, epsabs=1e-15, epsrel=1e-13)[0]
            s = quad(
                lambda u, m=m: (1 - u) * np.sinc(theta * (1 - u) / math.pi) * u**m, 0, 1, epsabs=1e-15, epsrel=1e-13
            )[0]
        else:  # oscillatory weights (QAWO): cos(theta (1 - u)) = cos theta cos(theta u) + sin theta sin(theta u)
            ic = quad(lambda u, m=m: u**m, 0, 1, weight="cos", wvar=theta, epsabs=1e-16, epsrel=1e-13)[0]
            is_ = quad(lambda u, m=m: u**m, 0, 1, weight="sin", wvar=theta, epsabs=1e-16, epsrel=1e-13)[0]
            c = math.cos(theta) * ic + math.sin(theta) * is_
            s = (math.sin(theta) * ic - math.cos(theta) * is_) / theta
        assert_allclose(Cm[m], c, rtol=1e-11, atol=1e-14 / (1 + theta))
        assert_allclose(Sm[m], s, rtol=1e-11, atol=1e-14 / (1 + theta) ** 2)


@pytest.mark.parametrize("radau", [False, True])
@pytest.mark.parametrize("omega", [0.0, 50.0, 2.0e4, 3.0e5])
def test_step_weights_propagate_a_forced_oscillator(omega, radau):
    """eta'' + w^2 eta = f(t), f the cubic through four nodal values (at Gauss's nodes, or Radau's: a resting
    contact's), against DOP853 at rtol 1e-12.

    The step spans from a fraction of a period (w = 50) to ~100 periods (w = 3e5), where
    the exact propagation is the point of the method.
    """
    c = np.array(core.nodes(radau))
    Vinv = np.linalg.inv(np.vander(c, 4, increasing=True))
    h = 2e-3
    fn = np.array([3.0, -1.0, 2.0, 0.5]) * (1.0 + omega**2 * 1e-6)
    coef = Vinv @ fn
    forcing = lambda t: np.polyval(coef[::-1], t / h)
    s = np.array([0.1, 0.5, 1.0])
    weights = [core.weights(omega, h, si, radau) for si in s]
    Cw, SW, WS = (np.array([[w[i] for w in weights]]) for i in range(3))
    RE, RV = np.array([[w[3] for w in weights]]), np.array([[w[4] for w in weights]])
    eta0, v0 = 1e-3, -0.2
    sol = solve_ivp(
        lambda t, y: [y[1], forcing(t) - omega**2 * y[0]],
        (0, h),
        [eta0, v0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-16,
        t_eval=s * h,
        max_step=h / max(1.0, omega * h / 0.5),
    )
    eta = Cw[0] * eta0 + SW[0] * v0 + RE[0] @ fn
    v = -WS[0] * eta0 + Cw[0] * v0 + RV[0] @ fn
    scale_e = abs(eta0) + abs(v0) * h + np.max(np.abs(fn)) * h * h
    assert_allclose(eta, sol.y[0], rtol=0, atol=1e-9 * scale_e)
    assert_allclose(v, sol.y[1], rtol=0, atol=1e-9 * (abs(v0) + omega * abs(eta0) + np.max(np.abs(fn)) * h))


def test_radau_nodes_are_radau_iia():
    """The kernel's Radau IIA nodes (kernels/src/propagation.c) and their Python mirror (integrate/dense.py):
    x = 2 c - 1 the zeros of P_4(x) - P_3(x) (Hairer & Wanner, Solving ODEs II, Sec. IV.5), the last c = 1; the
    weights integrate every polynomial of degree <= 2p - 2 = 6 on [0, 1] exactly, and not degree 7 (the rule's
    order); the Lebesgue function of the nodes stays below the bound the event search takes for them (fb_tables'
    lebesgue: 3.5, its maximum 3.447 at the step's start; Gauss's 3.0, its maximum 2.856)."""

    from numpy.polynomial import legendre

    from flexbeam.integrate.dense import RADAU_NODES, RADAU_WEIGHTS

    c = np.array(core.nodes(True))
    assert_allclose(c, RADAU_NODES, rtol=0, atol=4e-16)
    assert c[-1] == 1.0
    x = 2.0 * c - 1.0
    assert_allclose(legendre.legval(x, [0, 0, 0, -1, 1]), 0.0, atol=1e-14)
    for m in range(7):
        assert RADAU_WEIGHTS @ c**m == pytest.approx(1.0 / (m + 1), rel=1e-15, abs=1e-16)
    assert abs(RADAU_WEIGHTS @ c**7 - 1.0 / 8.0) > 1e-5
    s = np.linspace(0.0, 1.0, 20001)
    for nodes, bound in ((c, 3.5), (np.array(core.nodes()), 3.0)):
        lebesgue = sum(
            np.abs(np.prod([(s - nodes[k]) / (nodes[j] - nodes[k]) for k in range(4) if k != j], axis=0))
            for j in range(4)
        )
        assert bound - 0.16 < lebesgue.max() < bound
