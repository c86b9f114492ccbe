"""An output column's extremes over a run, located on the dense output (:meth:`RunSource.extremes
<flexbeam.results.arrays.RunSource.extremes>`).

The column is sampled on a grid per phase -- the tip deflection at every step's collocation nodes, where the
integrator evaluated it; any other column at ``points_per_step`` points of every step -- and every local extremum of
the samples that could exceed the largest one (a smooth peak stands above its largest sample by less than that
sample stands above its lower neighbour) is refined between its neighbours (to PEAK_XTOL; of several nearly equal
peaks the largest is found).  That reach assumes the samples resolve the column.  For the tip, whose deflection has
a derived bound between any two samples (``kernels/src/tip_bound.c``), every interval that bound lets reach the best
value is searched as well: a free flight's steps may span several periods of the modes, which the exact modal
propagation allows (the spinning stop's 0.2 s flight: 27 steps, its tip's minimum between two nodes 6 % below both).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..kernels import OUTPUT_COLUMNS
from .peaks import peak_candidates

if TYPE_CHECKING:
    from ..integrate.loop import Segment
    from .arrays import RunSource

TIP = OUTPUT_COLUMNS.index("tip_deflection")


def column_extremes(
    source: RunSource,
    column: str,
    points_per_step: int = 4,
    reached: tuple[float, float] | None = None,
    window: tuple[float, float] | None = None,
) -> tuple[float, float]:
    """(min, max) of output ``column`` over the run of ``source`` (NaN without a phase of positive length).  A rigid
    beam's tip (no bending modes) lies on its radial line: its deflection is 0, with nothing to search (a search
    through its round-off, flat at ~1e-17 m, found every sample a candidate: 9 s for a held rigid beam's 0.5 s).
    ``reached``: (min, max) reached already elsewhere (a streamed run's earlier parts): what cannot go beyond them is
    not searched, and the result includes them (a resting contact's parts, each searched from scratch, took 17 s of
    40 s streamed: its flat tip left every interval within reach of the part's own best).  ``window``: (t_a, t_b),
    the extremes over that time interval only (a steady state after its transient): each phase's grid is cut to
    it, its ends added as samples, so that every bracket lies inside it."""
    if column == "tip_deflection" and source.system.beam.n == 0:
        inside = any(_cut(seg.t0, seg.t1, window) for seg in source.segments)
        return (0.0, 0.0) if inside else (math.nan, math.nan)
    grids = []
    for i, seg in enumerate(source.segments):
        if not _cut(seg.t0, seg.t1, window):
            continue
        if column == "tip_deflection" and hasattr(seg.dense, "tip_nodes"):
            if seg.t1 > seg.t0:  # (its breaks hold two points or more)
                grids.append(_windowed(source, seg, *tip_grid(source, i), column, window))
            continue
        b = seg.breaks()
        if b.size < 2:
            continue
        frac = np.linspace(0.0, 1.0, points_per_step + 1)[:-1]
        t = np.append((b[:-1, None] + np.diff(b)[:, None] * frac[None, :]).ravel(), b[-1])
        grids.append(_windowed(source, seg, t, source.evaluate(seg, t)[0][column], column, window))
    grids = [g for g in grids if g[1].size]
    if not grids:
        return math.nan, math.nan
    out, slacks = [], {}
    for sign in (-1, 1):
        top, found = peak_candidates([v for _, _, v in grids], sign)
        best = top if reached is None else max(top, sign * reached[(sign + 1) // 2])
        for k, idx, reach in found:
            seg, t, _ = grids[k]
            lo, hi = t[np.maximum(idx - 1, 0)], t[np.minimum(idx + 1, t.size - 1)]
            best = max(best, source._zoom_all(seg, column, sign, lo, hi, floor=best, reach=reach))
        if column == "tip_deflection":
            best = _tip_between(source, grids, sign, best, found, slacks)
        out.append(sign * best)
    return out[0], out[1]


def _tip_between(source: RunSource, grids: list, sign: float, best: float, found: list, slacks: dict) -> float:
    """The best of ``best`` and the tip's extremes in the intervals between samples whose bound -- their larger end
    plus the slack of ``kernels/src/tip_bound.c``, a derivation -- reaches ``best``, but for those within the local
    maxima's brackets searched already (a bracket whose reach is at least ``best`` was searched whatever the
    order).  ``slacks``: each grid's interval slacks, computed once for both signs."""
    for k, (seg, t, v) in enumerate(grids):
        if t.size < 2 or not hasattr(seg.dense, "tip_slacks"):
            continue
        covered = np.zeros(t.size - 1, bool)
        for kk, idx, reach in found:
            if kk == k:
                idx = idx[reach >= best]
                covered[np.maximum(idx - 1, 0)] = covered[np.minimum(idx, t.size - 2)] = True
        if k not in slacks:
            slacks[k] = seg.dense.tip_slacks(seg.y0, seg.y1, seg.t0, seg.t1, t)
        bound = np.maximum(sign * v[:-1], sign * v[1:]) + slacks[k]
        idx = np.nonzero(~covered & (bound >= best) & (t[1:] > t[:-1]))[0]
        if idx.size:
            idx = idx[np.argsort(-bound[idx], kind="stable")]
            found_best = source._zoom_all(seg, "tip_deflection", sign, t[idx], t[idx + 1], floor=best, reach=bound[idx])
            best = max(best, found_best)
    return best


def _cut(t0: float, t1: float, window: tuple[float, float] | None) -> bool:
    """Whether the phase [t0, t1] has a part of positive length in ``window`` (any phase without one)."""
    return window is None or (t1 > t0 and t0 < window[1] and t1 > window[0])


def _windowed(
    source: RunSource, seg: Segment, t: np.ndarray, v: np.ndarray, column: str, window: tuple[float, float] | None
) -> tuple[Segment, np.ndarray, np.ndarray]:
    """The grid (seg, t, v) cut to ``window``, the window's ends inside the phase added as samples (their values from
    the dense output); as it is without a window."""
    if window is None:
        return seg, t, v
    keep = (t > window[0]) & (t < window[1])
    ends = np.array([x for x in window if t[0] <= x <= t[-1]], float)
    t_all = np.concatenate((t[keep], ends))
    v_all = np.concatenate((v[keep], source.evaluate(seg, ends)[0][column] if ends.size else ends))
    order = np.argsort(t_all, kind="stable")
    return seg, t_all[order], v_all[order]


def tip_grid(source: RunSource, i: int) -> tuple[np.ndarray, np.ndarray]:
    """(times, tip deflection) of compiled phase ``i`` at its ends and at every step's collocation nodes, where the
    integrator evaluated it while it ran (the ends with every phase's, :attr:`RunSource.segment_ends`)."""
    seg, ends = source.segments[i], source.segment_ends
    t_nodes, v_nodes = seg.dense.tip_nodes()
    t = np.concatenate(([seg.t0], t_nodes, [seg.t1]))
    v = np.concatenate((ends.start[i, TIP : TIP + 1], v_nodes, ends.end[i, TIP : TIP + 1]))
    return t, v
