"""Natural frequencies of the straight beam against the analytic beta L roots.

omega_k = (beta_k L)^2 sqrt(EI / (mu L^4)) with

* clamped-free: cos(bL) cosh(bL) = -1  (1.87510, 4.69409, 7.85476, 10.99554, ...);
* pinned-free:  tan(bL) = tanh(bL)     (0 [rigid], 3.92660, 7.06858, 10.21018, ...)

(e.g. Blevins, *Formulas for Natural Frequency and Mode Shape*, 1979, Table 8-1).
Pinned-free is the free joint with no hub (r_h = J_h = 0): theta is then the root
rotation.

Consistent-mass Hermite elements converge as h^4 from above (Rayleigh-Ritz).  The size of the
error follows from their dispersion relation: a bending wave of wavenumber k on a uniform mesh of
element length h has omega_h / omega - 1 = (k h)^4 / 1440 + O((k h)^6), the next term negative
(the acoustic branch of the two-node Bloch eigenproblem of the element's stiffness and mass
matrices, expanded in k h; it is (kh)^4/1440 less 0.03 % of that at kh = 0.1 and 0.45 % at
kh = 0.4).  With k = beta_k, each frequency's error lies in (0, (beta_k h)^4 / 1440]: measured
0.90-1.0 of that bound for every mode at 8-64 elements, except where round-off dominates (the
first mode at 40 and 64 elements, errors of 5e-9 and 3e-9).  Round-off adds at most eps lambda_max /
lambda_k to omega^2 (a backward-stable generalized eigensolver; the axial modes make lambda_max
7e8 lambda_1 at 40 elements), so the tests allow five times that, halved for omega.
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


def bending_frequencies(case, pinned: bool, count: int, largest: list | None = None) -> np.ndarray:
    """Lowest non-zero bending frequencies (axial modes removed by their shape); ``largest`` receives the
    largest eigenvalue omega^2 of the mesh."""
    beam = FemBeam.from_case(case)
    z, _ = beam.straight(0.0, 0.0)
    M, K = beam.matrices(z)
    if not pinned:
        M, K = M[1:, 1:], K[1:, 1:]
    from scipy.linalg import eigh

    w2, vec = eigh(K, M)
    if largest is not None:
        largest.append(float(w2.max()))
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
    """Blevins (1979), Table 8-1, eight decimals: the table rounds to half a unit of the eighth decimal, the roots
    here are found to ~1e-15 (measured 4.9e-9 off at most, the table's rounding of 10.99554073)."""
    assert_allclose(
        clamped_free_roots(5)[:4], [1.87510407, 4.69409113, 7.85475744, 10.99554073], rtol=0, atol=5e-9 + 1e-12
    )
    assert_allclose(pinned_free_roots(3), [3.92660231, 7.06858275, 10.21017612], rtol=0, atol=5e-9 + 1e-12)


def _check_against_dispersion(case, pinned: bool, roots: np.ndarray, elements: int) -> None:
    largest: list[float] = []
    w = bending_frequencies(case, pinned=pinned, count=roots.size, largest=largest) / _scale(case)
    error = w / roots**2 - 1.0
    lead = (roots / elements) ** 4 / 1440.0  # (beta_k h)^4 / 1440 with h = L / elements, L = 1 in beta_k L
    roundoff = 5.0 * np.finfo(float).eps * largest[0] / (_scale(case) ** 2 * roots**4) / 2.0
    assert np.all(error > -roundoff), error
    assert np.all(error <= lead + roundoff), (error, lead)


@pytest.mark.parametrize("elements", [10, 40])
def test_clamped_free(elements):
    """Within the dispersion bound (module notes): 2.5e-4 and 9.5e-4 for modes 3, 4 at 10 elements."""
    case = seed(fem__elements=elements, drive__kind="prescribed", model__gravity=0.0, contact__position=0.7)
    _check_against_dispersion(case, False, clamped_free_roots(4), elements)


@pytest.mark.parametrize("elements", [10, 40])
def test_pinned_free(elements):
    case = seed(fem__elements=elements, model__gravity=0.0, hub__radius=0.0, hub__inertia=0.0, contact__position=0.7)
    _check_against_dispersion(case, True, pinned_free_roots(3), elements)


def test_convergence_order_is_four():
    """Halving h divides the clamped-free error by ~16 (Hermite cubics, consistent mass).  Measured orders 3.94
    and 3.98 (8-16-32 elements, mode 3); within 0.7 of 4 they tell h^4 from the neighbouring even orders h^2
    (a lumped mass or a wrong shape function) and h^6."""
    exact = clamped_free_roots(3)[2] ** 2
    errors = []
    for n in (8, 16, 32):
        case = seed(fem__elements=n, drive__kind="prescribed", model__gravity=0.0, contact__position=0.7)
        errors.append(bending_frequencies(case, False, 3)[2] / _scale(case) - exact)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.array(errors) > 0.0)  # from above (Rayleigh-Ritz)
    assert_allclose(orders, 4.0, atol=0.7)
