"""LAPACK general-band storage of the FE matrices (Numba): the held hub angle and a band LU solve.

An n x n matrix with kl = ku = :data:`BAND` is stored as ``ab`` of shape (3 BAND + 1, n),
A[i, j] = ab[2 BAND + i - j, j] (the layout of :func:`scipy.linalg.lapack.dgbsv`, whose
first BAND rows are workspace for the pivoting LU).
"""

from __future__ import annotations

import numpy as np

from .jit import fem_jit

#: half-bandwidth of the assembled matrices
BAND = 5


@fem_jit
def fix_first_dof(ab):
    """Replace row and column 0 of a band matrix by the identity (theta held)."""
    off = 2 * BAND
    n = ab.shape[1]
    for j in range(min(n, BAND + 1)):
        ab[off - j, j] = 0.0
    for i in range(min(n, BAND + 1)):
        ab[off + i, 0] = 0.0
    ab[off, 0] = 1.0


@fem_jit
def band_solve(ab, x):
    """Solve A x = b in place (b given in x) by band LU *without* pivoting.

    ``ab`` is in LAPACK general-band layout (offset 2 BAND) and is overwritten.  The
    iteration matrices here are symmetric and, for a dynamic step, dominated by the
    positive definite c_M M, so no pivoting is needed; a pivot smaller than 1e-13
    times the largest diagonal entry returns False and the caller falls back to
    LAPACK ``dgbsv`` (partial pivoting).
    """
    n = ab.shape[1]
    off = 2 * BAND
    big = 0.0
    for k in range(n):
        big = max(big, abs(ab[off, k]))
    small = 1e-13 * big
    for k in range(n):
        piv = ab[off, k]
        if not abs(piv) > small:
            return False
        iend = min(n, k + BAND + 1)
        for i in range(k + 1, iend):
            lik = ab[off + i - k, k] / piv
            if lik != 0.0:
                for j in range(k + 1, iend):
                    ab[off + i - j, j] -= lik * ab[off + k - j, j]
                x[i] -= lik * x[k]
    for k in range(n - 1, -1, -1):
        acc = x[k]
        for j in range(k + 1, min(n, k + BAND + 1)):
            acc -= ab[off + k - j, j] * x[j]
        x[k] = acc / ab[off, k]
    return True


def band_to_dense(ab: np.ndarray) -> np.ndarray:
    """Dense matrix from the band storage ``ab`` (for small meshes and tests)."""
    n = ab.shape[1]
    A = np.zeros((n, n))
    off = 2 * BAND
    for j in range(n):
        for i in range(max(0, j - BAND), min(n, j + BAND + 1)):
            A[i, j] = ab[off + i - j, j]
    return A
