"""A search for :mod:`flexbeam.methods.frictional_lcp`'s consistent mode pattern that stops at the first one found, for
many pairs at once when the law's solution is certified unique.

**Uniqueness** (mu_s = mu_k = mu_i at every pair).  The law is then De Saxce's cone complementarity (De Saxce & Feng,
*The bipotential method*, Math. Comput. Modelling 28 (1998) 225-245): with K_i = {abs(P_t) <= mu_i P_n} and the
modified velocity xi^_i = (xi_ni + mu_i abs(xi_ti), xi_ti), P_i in K_i, xi^_i in K_i* and P_i . xi^_i = 0; hence the
variational inequality (Q - P) . xi^ >= 0 for every Q in K.  Two solutions P, P' (d = P' - P, xi' - xi = W d) give
d . W d <= sum_i mu_i abs(d_ni) abs((W d)_ti) <= norm(d)^2 norm(diag(mu) W_t)_2, W_t the tangential rows of W, so

    lambda_min(W) > norm(diag(mu) W_t)_2        (W positive definite, mu_s = mu_k)

makes the solution unique (derived here; the usual argument for small friction).
With a singular W (fewer coordinates than 2 s rows, e.g. a bar with few modes on many stops) or mu_s > mu_k it is not
certified, and the caller enumerates every pattern for the least-norm one.

**Search.**  From a guess -- the frictionless normal problem's pushing pairs slipping against their approach's
tangential velocity (sticking when it is 0) -- a pattern is solved and checked; the pairs that break it change mode
(a separating pair that penetrates pushes, a pushing pair that pulls separates, a sticking pair outside its cone
slips against its tangential impulse, a slipping pair whose velocity reversed sticks), as in an active-set method,
until a pattern is consistent or one repeats; the remaining patterns then follow in order of the number of pairs whose
mode differs from the guess.  Every pattern is visited at most once, so the search ends; it returns the first
consistent pattern's impulses, the unique solution when certified.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator

import numpy as np

from .. import numerics as nm
from .frictional_modes import FREE, SEPARATE, SLIP_BACKWARD, SLIP_FORWARD, STICK, consistent, pattern_impulse

FRICTIONAL_MODES = (SEPARATE, STICK, SLIP_FORWARD, SLIP_BACKWARD)


def certified_unique(W: np.ndarray, mu_s: np.ndarray, mu_k: np.ndarray) -> bool:
    """Whether the module docstring's condition lambda_min(W) > norm(diag(mu) W_t)_2 with mu_s = mu_k holds, with a
    margin of 1e-8 max abs(W) for the eigenvalues' round-off (:func:`flexbeam.numerics.eigh`, Jacobi)."""
    s = mu_s.size
    if not np.array_equal(mu_s, mu_k):
        return False
    lam = nm.eigh(W)[0]
    A = mu_k[:, None] * W[s:, :]
    norm2 = float(np.max(nm.eigh(nm.matmul(A, np.ascontiguousarray(A.T)))[0], initial=0.0))
    return float(np.min(lam)) > np.sqrt(max(norm2, 0.0)) + 1e-8 * float(np.max(np.abs(W)))


def first_consistent(W: np.ndarray, q: np.ndarray, mu_s: np.ndarray, mu_k: np.ndarray, tol_v: float,
                     tol_p: float) -> tuple[np.ndarray, tuple[str, ...]] | None:  # fmt: skip
    """The impulses and modes of the first consistent pattern in the module docstring's order, or None (none is)."""
    seen: set[tuple[str, ...]] = set()
    for modes in _ordered(W, q, mu_s, mu_k, tol_v, tol_p, seen):
        if modes in seen:
            continue
        seen.add(modes)
        P = pattern_impulse(W, q, modes, mu_k)
        if consistent(W, q, P, modes, mu_s, tol_v, tol_p):
            return P, modes
    return None


def _ordered(W, q, mu_s, mu_k, tol_v, tol_p, seen) -> Iterator[tuple[str, ...]]:
    """The patterns: the active-set walk from the guess, then all of them by their distance from the guess."""
    guess = _guess(W, q, mu_s)
    modes = guess
    while modes not in seen:
        yield modes
        P = pattern_impulse(W, q, modes, mu_k)
        modes = _repaired(W, q, P, modes, mu_s, tol_v, tol_p)
    s = len(guess)
    for d in range(s + 1):
        for where in itertools.combinations(range(s), d):
            others = [[m for m in _choices(mu_s[i]) if m != guess[i]] for i in where]
            for alt in itertools.product(*others):
                modes = list(guess)
                for i, m in zip(where, alt, strict=True):
                    modes[i] = m
                yield tuple(modes)


def _choices(mu: float) -> tuple[str, ...]:
    return FRICTIONAL_MODES if mu > 0.0 else (SEPARATE, FREE)


def _guess(W: np.ndarray, q: np.ndarray, mu_s: np.ndarray) -> tuple[str, ...]:
    """The frictionless normal problem's pushing pairs (:func:`~flexbeam.methods.frictional_modes.pattern_impulse` of
    all pairs pushing, then those with P_n > 0) slipping against q_t (sticking when q_t = 0); the others separating."""
    s = mu_s.size
    P = pattern_impulse(W, q, (FREE,) * s, np.zeros(s))
    modes = []
    for i in range(s):
        if P[i] <= 0.0:
            modes.append(SEPARATE)
        elif mu_s[i] == 0.0:
            modes.append(FREE)
        else:
            modes.append(STICK if q[s + i] == 0.0 else SLIP_FORWARD if q[s + i] > 0.0 else SLIP_BACKWARD)
    return tuple(modes)


def _repaired(W, q, P, modes, mu_s, tol_v, tol_p) -> tuple[str, ...]:
    """The pattern with every pair that breaks the law (module docstring) moved to the mode its violation points to."""
    s = len(modes)
    xi = q + nm.matmul(W, P)
    new = list(modes)
    for i, mode in enumerate(modes):
        xn, xt, pn, pt = xi[i], xi[s + i], P[i], P[s + i]
        slip = SLIP_FORWARD if xt > 0.0 else SLIP_BACKWARD
        if mode == SEPARATE and xn < -tol_v:
            new[i] = FREE if mu_s[i] == 0.0 else (STICK if abs(xt) <= tol_v else slip)
        elif mode != SEPARATE and pn < -tol_p:
            new[i] = SEPARATE
        elif mode == STICK and abs(pt) > mu_s[i] * max(pn, 0.0) + tol_p:
            new[i] = SLIP_BACKWARD if pt > 0.0 else SLIP_FORWARD
        elif (mode == SLIP_FORWARD and xt < -tol_v) or (mode == SLIP_BACKWARD and xt > tol_v):
            new[i] = STICK
    return tuple(new)
