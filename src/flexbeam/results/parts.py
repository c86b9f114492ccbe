"""A phase handed on in parts (a streamed run, :mod:`flexbeam.results.stream`) evaluated as the whole phase is.

A streamed run's long phase reaches the stream as several segments (``opens``/``closes`` False at the boundaries
inside the phase: step boundaries).  The whole phase's dense output, which a run held in memory evaluates, takes a
step boundary on the step that ends there (``searchsorted`` to the left, :mod:`flexbeam.integrate.dense`) and gives
the exact start and end states only at the phase's own ends; so do :func:`part_states` and a :class:`WholePhasePart`.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from ..integrate.loop import Segment


def part_states(seg: Segment, times: np.ndarray) -> np.ndarray:
    """States at ``times``: :meth:`Segment.states` for a whole phase; for a part, the dense output everywhere but at
    the phase's own ends (its ends inside the phase are evaluated as the whole phase's dense output evaluates them)."""
    if seg.opens and seg.closes:
        return Segment.states(seg, times)
    times = np.asarray(times, float)
    out = np.empty((times.size, seg.y0.size))
    first = (times <= seg.t0) if seg.opens else np.zeros(times.size, bool)
    last = (times >= seg.t1) & ~first if seg.closes else np.zeros(times.size, bool)
    inner = ~first & ~last
    if inner.any():
        out[inner] = seg.dense(times[inner])
    out[first] = seg.y0
    out[last] = seg.y1
    return out


@dataclass
class WholePhasePart(Segment):
    """A part of a phase whose :meth:`states` are :func:`part_states`."""

    def states(self, times: np.ndarray) -> np.ndarray:
        return part_states(self, times)


def as_whole(seg: Segment) -> Segment:
    """``seg`` itself for a whole phase; for a part, a :class:`WholePhasePart` of it."""
    if seg.opens and seg.closes:
        return seg
    return WholePhasePart(**{f.name: getattr(seg, f.name) for f in fields(seg)})


def holding(segments: list[Segment], t: float, after: bool) -> Segment:
    """The segment of ``segments`` (in time order) that a run held in memory evaluates at t -- the first holding t,
    or with ``after`` the last, a phase handed on in parts counting as one (its part that ends at t) -- as
    :func:`as_whole`."""
    segs = [s for s in segments if s.t0 <= t <= s.t1]
    segs = [s for k, s in enumerate(segs) if k == 0 or s.opens or segs[k - 1].closes]
    return as_whole(segs[-1] if after else segs[0])


__all__ = ["WholePhasePart", "as_whole", "holding", "part_states"]
