"""Local maxima of a sampled signal and their refinement between the samples (a contact force's peaks)."""

from __future__ import annotations

import math

import numpy as np

#: peak refinement stops at this bracket [s]: near a peak F ~ F_max (1 - ((t - t_p) / tau)^2) with
#: tau >~ 1e-5 s for any contact pulse resolved at all, so the force is then exact to ~1e-10 relative
PEAK_XTOL = 1e-10


def interior_maxima(f: np.ndarray, rtol: float = 1e-9, start: bool = False) -> list[int]:
    """Indices of the sampled local maxima of f (a plateau counts once, at its start).

    A maximum must stand above its lower neighbour by more than ``rtol`` max|f|: the
    round-off ripple of a constant force (a contact resting under a static load) is no peak.
    ``start``: the first sample counts too when it stands above the second by that much.
    """
    tol = rtol * float(np.max(np.abs(f), initial=0.0))
    mid, left, right = f[1:-1], f[:-2], f[2:]
    idx = (np.nonzero((mid > left) & (mid >= right) & (mid - np.minimum(left, right) > tol))[0] + 1).tolist()
    if start and f.size > 1 and f[0] - f[1] > tol:
        idx.insert(0, 0)
    return idx


def zoom_max(f, a: float, b: float, xtol: float, points: int = 33) -> tuple[float, float]:
    """Maximum of f on [a, b] by repeated zooming on a grid: f (vectorised, times -> values) at ``points``
    points, then the grid around the largest value, until the bracket is below ``xtol``.

    For a force near a smooth peak this needs log(xtol / (b - a)) / log(points / 2) calls of f (4 from a step of
    1e-5 s to 1e-10 s), each a single vectorised evaluation.
    """
    best_t, best_f = a, -math.inf
    while True:
        t = np.linspace(a, b, points)
        v = np.asarray(f(t), float)
        i = int(np.argmax(v))
        if v[i] > best_f:
            best_t, best_f = float(t[i]), float(v[i])
        if b - a <= xtol:
            return best_t, best_f
        dt = (b - a) / (points - 1)
        a, b = max(a, t[i] - dt), min(b, t[i] + dt)


def golden_max(f, a: float, b: float, xtol: float) -> tuple[float, float]:
    """Maximum of a unimodal f on [a, b] by golden-section search (Kiefer 1953).

    Plain Python on purpose: the peak refinement then does not import scipy.optimize,
    which would cost the command line ~0.5 s of start-up.
    """
    r = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = b - r * (b - a), a + r * (b - a)
    fc, fd = float(f(c)), float(f(d))
    while b - a > xtol:
        if fc >= fd:
            b, d, fd = d, c, fc
            c = b - r * (b - a)
            fc = float(f(c))
        else:
            a, c, fc = c, d, fd
            d = a + r * (b - a)
            fd = float(f(d))
    return (c, fc) if fc >= fd else (d, fd)


def peak_candidates(grids: list[np.ndarray], sign: float) -> tuple[float, list[tuple[int, np.ndarray, np.ndarray]]]:
    """The largest sample of ``sign`` x the sampled grids (each a phase's samples, none empty) and, grid by grid in
    order, the local maxima that could exceed it: (grid, indices most promising first, their reach).

    A sample is a local maximum when no neighbour within its grid exceeds it (a grid's ends are their own outer
    neighbours); its reach, sample + (sample - lower neighbour), bounds a smooth peak between its neighbours.  All
    grids at once: the same numbers as grid by grid.
    """
    sizes = np.array([g.size for g in grids])
    starts = np.cumsum(sizes) - sizes
    ends = starts + sizes - 1
    sv = sign * np.concatenate(grids)
    left, right = np.empty_like(sv), np.empty_like(sv)
    left[1:], right[:-1] = sv[:-1], sv[1:]
    left[starts], right[ends] = sv[starts], sv[ends]
    peak = (sv >= left) & (sv >= right)
    reach = sv + (sv - np.minimum(left, right))  # bound on the peak between the neighbours
    top = float(np.max(sv))
    cand = np.nonzero(peak & (reach >= top))[0]
    found = []
    if cand.size:
        owner = np.searchsorted(starts, cand, side="right") - 1
        for k in np.unique(owner):
            idx = cand[owner == k]
            idx = idx[np.argsort(-reach[idx], kind="stable")]  # the most promising first
            found.append((int(k), idx - starts[k], reach[idx]))
    return top, found
