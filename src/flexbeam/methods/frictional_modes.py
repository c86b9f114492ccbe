"""The mode patterns of :mod:`flexbeam.methods.frictional_lcp`'s frictional impact law: each pair separating, sticking
or slipping forwards or backwards; a pattern's least-norm impulses and whether they satisfy the law (its equations and
inequalities, to a tolerance)."""

from __future__ import annotations

import numpy as np

from .. import numerics as nm

#: the modes of a pair (FREE: a frictionless pair that pushes)
SEPARATE, STICK, SLIP_FORWARD, SLIP_BACKWARD, FREE = "separate", "stick", "slip+", "slip-", "free"


def least_norm_solve(A: np.ndarray, b: np.ndarray, rcond: float = 1e-12) -> np.ndarray:
    """The least-norm least-squares solution A^+ b of a square (possibly singular, non-symmetric) system.

    The singular triplets come from the symmetric augmented matrix [[0, A], [A^T, 0]], whose eigenpairs are
    (+-sigma_i, (u_i, +-v_i) / sqrt 2) (Golub & Van Loan, Matrix Computations, 4th ed., Sec. 8.6.1), by the
    deterministic Jacobi method of :func:`flexbeam.numerics.eigh`: A^+ b = sum over sigma_i > rcond sigma_max of
    v_i (u_i . b) / sigma_i, with sigma's absolute accuracy eps sigma_max (no squared condition number).
    """
    k = A.shape[0]
    if k == 0:
        return np.zeros(0)
    H = np.zeros((2 * k, 2 * k))
    H[:k, k:], H[k:, :k] = A, A.T
    lam, V = nm.eigh(H)
    top = float(np.max(np.abs(lam)))
    x = np.zeros(k)
    if top == 0.0:
        return x
    for j in np.flatnonzero(lam > rcond * top):
        u, v = V[:k, j], V[k:, j]
        x += v * (2.0 * nm.dot(u, b) / lam[j])
    return x


def pattern_impulse(W: np.ndarray, q: np.ndarray, modes, mu_k: np.ndarray) -> np.ndarray:
    """The least-norm impulses P (normal rows then tangential) that make a mode pattern's equations hold: xi = q + W P
    vanishes in the normal row of every pushing pair and the tangential row of a sticking one."""
    s = len(modes)
    cols, rows = [], []
    for i, mode in enumerate(modes):
        if mode == SEPARATE:
            continue
        rows.append(i)
        if mode == STICK:
            rows.append(s + i)
            cols += [np.eye(2 * s)[i], np.eye(2 * s)[s + i]]
            continue
        c = np.zeros(2 * s)
        sign = {SLIP_FORWARD: 1.0, SLIP_BACKWARD: -1.0, FREE: 0.0}[mode]
        c[i], c[s + i] = 1.0, -sign * mu_k[i]
        cols.append(c / np.sqrt(1.0 + (sign * mu_k[i]) ** 2))  # unit columns: |u| = |P|, the least norm is P's
    if not cols:
        return np.zeros(2 * s)
    B = np.array(cols).T
    A = nm.matmul(W[rows, :], B)
    return nm.matmul(B, least_norm_solve(A, -q[rows]))


def consistent(W: np.ndarray, q: np.ndarray, P: np.ndarray, modes, mu_s: np.ndarray, tol_v: float,
                tol_p: float) -> bool:  # fmt: skip
    """Whether the impulses P of a mode pattern satisfy the law's equations and inequalities (module docstring)."""
    s = len(modes)
    xi = q + nm.matmul(W, P)
    for i, mode in enumerate(modes):
        xn, xt, pn, pt = xi[i], xi[s + i], P[i], P[s + i]
        if mode == SEPARATE:
            ok = xn >= -tol_v
        else:
            ok = abs(xn) <= tol_v and pn >= -tol_p
            if mode == STICK:
                ok = ok and abs(xt) <= tol_v and abs(pt) <= mu_s[i] * max(pn, 0.0) + tol_p
            elif mode in (SLIP_FORWARD, SLIP_BACKWARD):
                ok = ok and (xt if mode == SLIP_FORWARD else -xt) >= -tol_v
        if not ok:
            return False
    return True


def clipped(P: np.ndarray, modes, mu_s: np.ndarray, mu_k: np.ndarray) -> np.ndarray:
    """P with round-off's negative normal impulses set to 0 and the tangential ones held inside their cones."""
    s = len(modes)
    P = P.copy()
    for i, mode in enumerate(modes):
        P[i] = max(P[i], 0.0)
        bound = (mu_s if mode == STICK else mu_k)[i] * P[i]
        P[s + i] = min(max(P[s + i], -bound), bound)
    return P
