"""Friction at simultaneous impacts: Newton's restitution with one coefficient in the normal and tangential
directions, a linear complementarity problem that never gains energy (Glocker, *Energetic consistency conditions for
standard impacts, Part I: Newton-type inequality impact laws and Kane's example*, Multibody Syst. Dyn. 29 (2013)
77-117; Pfeiffer & Glocker, *Multibody Dynamics with Unilateral Contacts*, Wiley 1996, Ch. 7).

**The law.**  s pairs impact at once.  Their normal and tangential velocities relative to the obstacles,
v = (v_n1 .. v_ns, v_t1 .. v_ts), jump by v+ = v- + W P with the Delassus matrix W = J M^-1 J^T of all 2 s rows and
the impulses P = (P_n, P_t).  With each pair's restitution e_i applied to both its rows, xi = v+ + e v-, pair i obeys

* normal: xi_ni >= 0, P_ni >= 0, P_ni xi_ni = 0;
* tangential (planar Coulomb): abs(P_ti) <= mu_s P_ni when xi_ti = 0 (stick), P_ti = -mu_k sign(xi_ti) P_ni otherwise
  (slip),

so that P_i . xi_i = -mu_k P_ni abs(xi_ti) <= 0 for every pair: P . xi <= 0.

**Energy.**  T+ - T- = P . (v- + v+) / 2 (the work of the impulses; relative to the obstacles).  With one common e,
v- = (xi - W P) / (1 + e), hence

    T+ - T- = P . xi / (1 + e) - (1 - e) / (2 (1 + e)) P . W P <= 0        (0 <= e <= 1, W positive semi-definite),

whatever the slip pattern: the law is energetically consistent (Glocker 2013, Part I).  Since the conditions are
positively homogeneous in (xi, P) and xi = (1 + e) v- + W P, the impulses are (1 + e) times those of the plastic
impact (e = 0): the rebound repeats the compression's impulse.  The price is the *tangential* restitution e_t = e_n
= e: a contact that sticks leaves with xi_t = 0, v_t+ = -e v_t- (it springs back along the surface, like a
superball), whereas Stronge's process (:mod:`flexbeam.methods.friction`, the law of one pair alone) ends a stick with
v_t+ = 0.  With different e_i per pair the identity above fails and Newton's law can gain energy (Glocker 2013,
Part I; Kane's example); the caller then checks the energy and, should it grow, applies the smallest e_i to all the
pairs (with a warning).

**Where it agrees with Stronge's process (one pair).**  When that process keeps one mode throughout: slip in one
direction (P_t = -mu_k s P_n with s = sign v_t- = sign v_t+, so sign xi_t = s, and the normal slope is constant,
where Stronge's energetic e is Newton's), or stick from the start (v_t- = 0, P = -(1 + e) W^-1 v-); and, for e = 0,
also a slip that stops and sticks (both end at v+ = 0).  A slip that reverses, or stops and sticks with e > 0, is
resolved differently.

**Solution.**  In the plane the Coulomb cone has two edges, so each pair is in one of four modes -- separating
(P_i = 0, xi_ni >= 0), sticking (xi_i = 0, abs(P_ti) <= mu_s P_ni), slipping forwards or backwards (xi_ni = 0,
P_ti = -+mu_k P_ni, +-xi_ti >= 0) -- and every one of the 4^s mode patterns (2 modes for a frictionless pair) is tried:
its linear equations are solved for the least-norm impulses (the pseudo-inverse, :func:`least_norm_solve`), and the
consistent patterns' impulse of least norm is returned.  A solution exists for the impact problem of a positive
definite W, and whenever the approach velocities are those of the bodies, v- in the range of J, with one e (the
Stewart-Trinkle LCP is then processable by Lemke's method: Anitescu & Potra, Nonlinear Dynamics 14 (1997) 231-247);
it is unique for small enough mu.  With a singular W (a rigid rod on two stops, a bar flat on two points) the
impulses are split by the least norm -- equally between identical pairs -- as :func:`~flexbeam.methods.impulse.
solve_impact_lcp` does without friction.  The tolerance on the conditions is 1e-10 of the largest (1 + e) abs(v-).
"""

from __future__ import annotations

import itertools

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


def _pattern_impulse(W: np.ndarray, q: np.ndarray, modes, mu_k: np.ndarray) -> np.ndarray:
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


def _consistent(W: np.ndarray, q: np.ndarray, P: np.ndarray, modes, mu_s: np.ndarray, tol_v: float,
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


def solve_frictional_impact(W: np.ndarray, v_minus: np.ndarray, e: np.ndarray, mu_s: np.ndarray,
                            mu_k: np.ndarray) -> np.ndarray | None:  # fmt: skip
    """The impulses P = (P_n1 .. P_ns, P_t1 .. P_ts) [N s] of the frictional impact law of the module docstring.

    Parameters
    ----------
    W
        The 2 s x 2 s Delassus matrix of the pairs' normal rows then tangential rows [1/kg] (positive semi-definite).
    v_minus
        The rows' velocities before the impact, relative to the obstacles [m/s].
    e
        Each pair's coefficient of restitution in [0, 1] (applied to its normal and its tangential row).
    mu_s, mu_k
        Each pair's static and kinetic coefficients of friction, mu_s >= mu_k >= 0.

    Returns
    -------
    The consistent impulses of least norm, or None when no mode pattern is consistent (see the module docstring for
    when a solution exists).
    """
    s = e.size
    q = np.concatenate(((1.0 + e) * v_minus[:s], (1.0 + e) * v_minus[s:]))
    tol_v = 1e-10 * max(float(np.max(np.abs(q), initial=0.0)), 1e-300)
    tol_p = tol_v / max(float(np.max(np.abs(W))), 1e-300)
    choices = [(SEPARATE, STICK, SLIP_FORWARD, SLIP_BACKWARD) if mu_s[i] > 0.0 else (SEPARATE, FREE) for i in range(s)]
    best: np.ndarray | None = None
    for modes in itertools.product(*choices):
        P = _pattern_impulse(W, q, modes, mu_k)
        if not _consistent(W, q, P, modes, mu_s, tol_v, tol_p):
            continue
        if best is None or nm.dot(P, P) < nm.dot(best, best) - 1e-30:
            best = _clipped(P, modes, mu_s, mu_k)
    return best


def _clipped(P: np.ndarray, modes, mu_s: np.ndarray, mu_k: np.ndarray) -> np.ndarray:
    """P with round-off's negative normal impulses set to 0 and the tangential ones held inside their cones."""
    s = len(modes)
    P = P.copy()
    for i, mode in enumerate(modes):
        P[i] = max(P[i], 0.0)
        bound = (mu_s if mode == STICK else mu_k)[i] * P[i]
        P[s + i] = min(max(P[s + i], -bound), bound)
    return P


def impulse_work(W: np.ndarray, v_minus: np.ndarray, P: np.ndarray) -> float:
    """The work of the impulses, T+ - T- = P . v- + P . W P / 2 [J] (relative to the obstacles)."""
    return nm.dot(P, v_minus) + 0.5 * nm.dot(P, nm.matmul(W, P))
