"""Natural frequencies of the straight beam against the analytic beta L roots.

omega_k = (beta_k L)^2 sqrt(EI / (mu L^4)) with

* clamped-free: cos(bL) cosh(bL) = -1  (1.87510, 4.69409, 7.85476, 10.99554, ...);
* pinned-free:  tan(bL) = tanh(bL)     (0 [rigid], 3.92660, 7.06858, 10.21018, ...)

(e.g. Blevins, *Formulas for Natural Frequency and Mode Shape*, 1979, Table 8-1).
Pinned-free is the free joint with no hub (r_h = J_h = 0): theta is then the root
rotation.  Consistent-mass Hermite elements converge as h^4 from above.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from flexbeam.fem import FemBeam
from tests.fem.cases import seed


def clamped_free_roots(n: int) -> np.ndarray:
    f = lambda z: math.cos(z) + 1.0 / math.cosh(z)  # noqa: E731 - cos cosh = -1, bounded form
    return np.array(
        [brentq(f, (k - 0.5) * math.pi - 0.6, (k - 0.5) * math.pi + 0.6, xtol=1e-15) for k in range(1, n + 1)]
    )


def pinned_free_roots(n: int) -> np.ndarray:
    f = lambda z: math.sin(z) * math.cosh(z) - math.cos(z) * math.sinh(z)  # noqa: E731
    return np.array(
        [
            brentq(lambda z: f(z) / math.cosh(z), (k + 0.2) * math.pi, (k + 0.3) * math.pi, xtol=1e-15)
            for k in range(1, n + 1)
        ]
    )


def bending_frequencies(case, pinned: bool, count: int) -> np.ndarray:
    """Lowest non-zero bending frequencies (axial modes removed by their shape)."""
    beam = FemBeam.from_case(case)
    z, _ = beam.straight(0.0, 0.0)
    M, K = beam.matrices(z)
    if not pinned:
        M, K = M[1:, 1:], K[1:, 1:]
    from scipy.linalg import eigh

    w2, vec = eigh(K, M)
    out = []
    axial = np.zeros(M.shape[0], bool)
    axial[(1 if pinned else 0) :: 3] = True  # X components (the beam lies along X)
    rigid = 1e-6 * _scale(case) ** 2
    for w, v in zip(w2, vec.T, strict=True):
        if w < rigid and pinned:
            continue  # rigid rotation
        if np.sum(v[axial] ** 2) > 0.5 * np.sum(v**2):
            continue  # axial mode
        out.append(math.sqrt(w))
        if len(out) == count:
            break
    return np.array(out)


def _scale(case) -> float:
    b = case.beam
    return math.sqrt(b.bending_stiffness / (b.line_density * b.length**4))


def test_roots():
    # published 10-digit values (Blevins 1979, Table 8-1)
    assert_allclose(
        clamped_free_roots(4), [1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349], rtol=1e-9
    )
    assert_allclose(pinned_free_roots(3), [3.9266023120, 7.0685827457, 10.2101761242], rtol=1e-9)


@pytest.mark.parametrize("elements, rtol", [(10, 1.5e-3), (40, 5e-6)])
def test_clamped_free(elements, rtol):
    case = seed(fem__elements=elements, drive__kind="prescribed", model__gravity=0.0, contact__position=0.7)
    w = bending_frequencies(case, pinned=False, count=4) / _scale(case)
    assert_allclose(w, clamped_free_roots(4) ** 2, rtol=rtol)


@pytest.mark.parametrize("elements, rtol", [(10, 1.5e-3), (40, 5e-6)])
def test_pinned_free(elements, rtol):
    case = seed(
        fem__elements=elements, model__gravity=0.0, hub__radius=0.0, hub__inertia=0.0, contact__position=0.7
    )
    w = bending_frequencies(case, pinned=True, count=3) / _scale(case)
    assert_allclose(w, pinned_free_roots(3) ** 2, rtol=rtol)


def test_convergence_order_is_four():
    """Halving h divides the clamped-free error by ~16 (Hermite cubics, consistent mass)."""
    exact = clamped_free_roots(3)[2] ** 2
    errors = []
    for n in (8, 16, 32):
        case = seed(fem__elements=n, drive__kind="prescribed", model__gravity=0.0, contact__position=0.7)
        errors.append(bending_frequencies(case, False, 3)[2] / _scale(case) - exact)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.array(errors) > 0.0)  # from above (Rayleigh-Ritz)
    assert_allclose(orders, 4.0, atol=0.15)
