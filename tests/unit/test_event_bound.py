"""The event search's bounds on a step's dense output (``fb_dense_bounds``, events.c; forcing_bound.c) against the
exact response of a mode, eta'' + c eta' + w^2 eta = f(t / h), sampled densely.

The fast modes' bound is their free amplitude plus (max|f| + |f(0)| + V(f)) / w^2 (V the forcing's total
variation over the step: the forced response by parts, forcing_bound.c); the slow modes' is the curvature term
(T^2 / 8) max|eta''|.  The forcings are the collocation's cubics through 4 nodal values, including those that change
sign within the step at a rate matched to w, where the replaced argument's 2 max|f| / w^2 is not a bound
(``test_two_max_f_over_w2_is_not_a_bound``).  The reference is the closed form (a polynomial particular solution plus
the homogeneous exponentials, numpy, independent of the kernels); the only allowance is its own evaluation rounding,
64 ulp of the largest term it adds (REF_ULP: a sum of a few products, each a few ulp).
"""

from __future__ import annotations

import numpy as np
import pytest

from flexbeam.kernels import _core

REF_ULP = 64.0 * np.finfo(float).eps
NODES = np.array(_core.nodes())
SAMPLES = np.linspace(0.0, 1.0, 4001)  # fractions of the step at which the exact response is evaluated


def exact_response(w, c, h, eta0, v0, fn):
    """eta(t), eta''(t) at t = SAMPLES h and the rounding allowance, for f the cubic through the nodal values fn.

    Particular solution q (a cubic: q'' + c q' + w^2 q = p, solved from the top degree down) plus
    C1 e^(l1 t) + C2 e^(l2 t), l = -c/2 +- sqrt(c^2/4 - w^2) (complex when underdamped)."""
    a = np.linalg.solve(np.vander(NODES, 4, increasing=True), fn)  # f(u) = sum a_m u^m
    p = a / h ** np.arange(4)  # in t
    q = np.zeros(4)
    q[3] = p[3] / w**2
    q[2] = (p[2] - 3 * c * q[3]) / w**2
    q[1] = (p[1] - 2 * c * q[2] - 6 * q[3]) / w**2
    q[0] = (p[0] - c * q[1] - 2 * q[2]) / w**2
    disc = np.sqrt(complex(c * c / 4 - w * w))
    l1, l2 = -c / 2 + disc, -c / 2 - disc
    A, B = eta0 - q[0], v0 - q[1]  # C1 + C2 = A, l1 C1 + l2 C2 = B
    C1 = (B - l2 * A) / (l1 - l2)
    C2 = A - C1
    t = SAMPLES * h
    e1, e2 = C1 * np.exp(l1 * t), C2 * np.exp(l2 * t)
    qt = np.polynomial.polynomial.polyval(t, q)
    qdd = np.polynomial.polynomial.polyval(t, np.polynomial.polynomial.polyder(q, 2))
    eta = qt + (e1 + e2).real
    acc = qdd + (l1 * l1 * e1 + l2 * l2 * e2).real
    scale = np.abs(q).sum() * (1 + h) ** 3 + abs(C1) + abs(C2)
    return eta, acc, REF_ULP * scale * np.array([1.0, abs(l1) ** 2 + w * w])


def bounds(w, c, h, eta0, v0, fn, dx):
    one = np.ones(1)
    return _core.dense_bounds(w * one, c * one, h, eta0 * one, v0 * one, np.asarray(fn, float), one, 0.0, dx)


def cases():
    rng = np.random.default_rng(7)
    signs = [np.array([(s >> i) & 1 for i in range(4)]) * 2.0 - 1.0 for s in range(16)]  # every sign pattern
    t3 = np.cos(3 * np.arccos(2 * NODES - 1))  # T_3(2u - 1): three sign changes
    shapes = [*signs, t3, np.ones(4), *(rng.normal(size=(6, 4)))]
    for wh in (0.8, 2.0, 4.0, 6.0, 8.26, 10.0, 14.0, 20.0, 40.0, 100.0):
        for zeta in (0.0, 0.05, 0.7, 2.0):
            for ic in (0.0, 1.0):
                for i, fn in enumerate(shapes):
                    yield wh, zeta, ic, i, fn


CASES = list(cases())


@pytest.mark.parametrize("h", [1.0, 2.5e-4])
def test_fast_modes_bound_their_exact_response(h):
    """Every case: free amplitude + (max|f| + |f(0)| + V) / w^2 >= max |eta| over the dense samples."""
    worst = 0.0
    for wh, zeta, ic, i, fn in CASES:
        w = wh / h
        c, F = 2 * zeta * w, 1e3 * (1 + i % 3)
        eta0, v0 = ic * F / w**2 * 0.7, -ic * F / w * 0.4
        eta, _, tol = exact_response(w, c, h, eta0, v0, F * fn)
        _, fast = bounds(w, c, h, eta0, v0, F * fn, 1.0)  # dx = 1: w h > pi / 4, the mode is fast
        seen = np.abs(eta).max()
        assert seen - tol[0] <= fast, (wh, zeta, ic, i, seen, fast)
        worst = max(worst, seen / fast)
    assert worst > 0.9  # the bound is attained within 10 % by some case (constant forcing from rest: 2 F / w^2)


@pytest.mark.parametrize("h", [1.0, 2.5e-4])
def test_slow_modes_bound_their_curvature(h):
    """Samples T = dx h apart with w T <= pi / 4: curve = T^2 / 8 max|eta''| bound, i.e. 8 curve / T^2 >= |eta''|."""
    for wh, zeta, ic, i, fn in CASES:
        w = wh / h
        dx = 0.25 * np.pi / wh * (1 - 1e-9)  # w dx h just below pi / 4: slow, at the edge
        c, F = 2 * zeta * w, 1e3 * (1 + i % 3)
        eta0, v0 = ic * F / w**2 * 0.7, -ic * F / w * 0.4
        _, acc, tol = exact_response(w, c, h, eta0, v0, F * fn)
        curve, fast = bounds(w, c, h, eta0, v0, F * fn, dx)
        assert fast == 0.0
        T = dx * h
        assert np.abs(acc).max() - tol[1] <= 8.0 * curve / T**2, (wh, zeta, ic, i)


def test_two_max_f_over_w2_is_not_a_bound():
    """The replaced argument: a forcing that changes sign within the step at a rate matched to w drives the mode
    past 2 max|f| / w^2 -- T_3(2u - 1) (max|f| = 1 on the step) from rest reaches about 3.35 / w^2 at w h = 8.26 --
    while the bound by parts (max|f| + |f(0)| + V = 1 + 1 + 6) holds."""
    fn = np.cos(3 * np.arccos(2 * NODES - 1))
    w = 8.26
    eta, _, tol = exact_response(w, 0.0, 1.0, 0.0, 0.0, fn)
    seen = (np.abs(eta).max() - tol[0]) * w**2
    assert seen > 3.3  # > 2 max|f| = 2 by far more than any rounding
    _, fast = bounds(w, 0.0, 1.0, 0.0, 0.0, fn, 1.0)
    assert seen <= fast * w**2
    assert fast * w**2 == pytest.approx(8.0, rel=1e-9)  # max|f| = 1, |f(0)| = 1, V = 3 x 2
