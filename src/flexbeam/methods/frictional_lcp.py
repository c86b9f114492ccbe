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

**Many pairs.**  The enumeration costs 4^s pattern solutions (~3 ms for 3 pairs, ~12 s for 8;
benchmarks/frictional_impacts.py).  For s > :data:`ENUMERATED_PAIRS` pairs with mu_s = mu_k and a positive definite W
such that lambda_min(W) > norm(diag(mu) W_t)_2 (W_t: the tangential rows of W), the solution is unique
(:mod:`flexbeam.methods.frictional_search`, De Saxce's bipotential form of the law), so the first consistent
pattern is it: an active-set walk from the frictionless normal problem's pushing pairs, slipping against their
approach's tangential velocity, finds it, in ~0.5-2.5 ms for the 8-stop bar; the same pattern, hence the same
impulses bit for bit, as the enumeration wherever one pattern is consistent.  Otherwise (s <= 3, mu_s > mu_k, a
singular W -- a bar with fewer than 2 s - 3 modes on s stops -- or larger mu) every pattern is still tried.
"""

from __future__ import annotations

import itertools

import numpy as np

from .. import numerics as nm
from .frictional_modes import (
    FREE,
    SEPARATE,
    SLIP_BACKWARD,
    SLIP_FORWARD,
    STICK,
    clipped,
    consistent,
    least_norm_solve,
    pattern_impulse,
)
from .frictional_search import certified_unique, first_consistent

__all__ = ["FREE", "SEPARATE", "SLIP_BACKWARD", "SLIP_FORWARD", "STICK", "impulse_work", "least_norm_solve",
           "solve_frictional_impact"]  # fmt: skip

#: the most pairs solved by the enumeration of all mode patterns whatever W (bit for bit with the first version)
ENUMERATED_PAIRS = 3


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
    when a solution exists).  More than :data:`ENUMERATED_PAIRS` pairs whose solution is certified unique
    (:func:`~flexbeam.methods.frictional_search.certified_unique`) are solved by
    :func:`~flexbeam.methods.frictional_search.first_consistent`; all others by trying every pattern.
    """
    s = e.size
    q = np.concatenate(((1.0 + e) * v_minus[:s], (1.0 + e) * v_minus[s:]))
    tol_v = 1e-10 * max(float(np.max(np.abs(q), initial=0.0)), 1e-300)
    tol_p = tol_v / max(float(np.max(np.abs(W))), 1e-300)
    if s > ENUMERATED_PAIRS and certified_unique(W, mu_s, mu_k):
        found = first_consistent(W, q, mu_s, mu_k, tol_v, tol_p)
        return None if found is None else clipped(found[0], found[1], mu_s, mu_k)
    choices = [(SEPARATE, STICK, SLIP_FORWARD, SLIP_BACKWARD) if mu_s[i] > 0.0 else (SEPARATE, FREE) for i in range(s)]
    best: np.ndarray | None = None
    for modes in itertools.product(*choices):
        P = pattern_impulse(W, q, modes, mu_k)
        if not consistent(W, q, P, modes, mu_s, tol_v, tol_p):
            continue
        if best is None or nm.dot(P, P) < nm.dot(best, best) - 1e-30:
            best = clipped(P, modes, mu_s, mu_k)
    return best


def impulse_work(W: np.ndarray, v_minus: np.ndarray, P: np.ndarray) -> float:
    """The work of the impulses, T+ - T- = P . v- + P . W P / 2 [J] (relative to the obstacles)."""
    return nm.dot(P, v_minus) + 0.5 * nm.dot(P, nm.matmul(W, P))
