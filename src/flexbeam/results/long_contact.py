"""A contact record of a streamed run completed stretch by stretch (:mod:`flexbeam.results.stream`): a contact
that outlasts the steps the stream keeps -- a beam coming to rest on its stop -- has its impulse summed segment by
segment as in memory, its energies at its ends, its peak found among the candidates of each stretch (the maxima of
the integrator's nodal forces that could be the largest so far, refined on the dense output) and its force peaks --
for the first contact of a pair -- kept above PEAK_SHARE of the largest so far."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..integrate.loop import Segment
from .arrays import RunSource
from .peaks import interior_maxima

if TYPE_CHECKING:
    from .stream import RunStream

#: the force peaks of a long first contact kept: above this share of the largest so far (the metrics' threshold)
PEAK_SHARE = 0.05


class LongContact:
    """A contact record completed stretch by stretch (see the module docstring): started with its segments kept so
    far (``src``), fed every later segment once (:meth:`absorb`), finished at its end."""

    def __init__(self, stream: RunStream, i: int, src: RunSource) -> None:
        self.stream, self.i = stream, i
        self.ev = ev = stream.contacts[i]
        self.first = stream.first_of_pair(i)
        self.jumped = not math.isnan(ev.jump_impulse)
        if self.jumped:  # as Solution.contact: the jump logged kinetic energies, the potential is added
            potential = src.mechanical_energy(ev.onset, after=True) - ev.energy_after
            ev.energy_before += potential
            ev.energy_after += potential
        else:
            ev.energy_before = src.mechanical_energy(ev.onset, after=True)
        self.next = 0  # the number of the next segment to absorb
        self.impulse = 0.0
        self.top, self.top_at = -math.inf, math.nan
        self.best: tuple[float, float] | None = None
        self.nodes = _Maxima()
        self.profile = _Maxima()
        self.peaks: list[tuple[float, float]] = []

    def absorb(self, number: int, seg: Segment, context: RunSource) -> None:
        """Add a segment (each once, in order) to the impulse and the peak candidates; ``context``: the segments
        around it, for refining a peak."""
        if number < self.next:
            return
        self.next = number + 1
        ev = self.ev
        end = ev.end if math.isfinite(ev.end) else math.inf
        if seg.phase.modes[ev.pair] == 0 or seg.t1 <= seg.t0 or seg.t1 < ev.onset or seg.t0 > end:
            return
        lo, hi = max(ev.onset, seg.t0), min(end, seg.t1)
        one = self.stream.source([seg])
        self.impulse += one.impulse(lo, hi, ev.pair)  # segment by segment, as RunSource.impulse sums
        t, f = one.nodal_profile(lo, hi, ev.pair)
        if f.size and float(np.max(f)) > self.top:
            k = int(np.argmax(f))
            self.top, self.top_at = float(f[k]), float(t[k])
        self._candidates(self.nodes, t, f, context, False)
        if self.first:
            self._peaks(*one.force_profile(lo, hi, ev.pair), context, False)

    def _candidates(self, keep: _Maxima, t: np.ndarray, f: np.ndarray, context: RunSource, final: bool) -> None:
        """The largest peak among the nodal maxima that could be the largest so far (as Solution._largest_peak)."""
        for k, tt, ff in keep.maxima(t, f, final):
            left, right = ff[max(k - 1, 0)], ff[min(k + 1, ff.size - 1)]
            if ff[k] + (ff[k] - min(left, right)) < self.top:
                continue
            h = max(tt[k] - tt[max(k - 1, 0)], tt[min(k + 1, tt.size - 1)] - tt[k])
            cand = self._refine(float(tt[k]), h, context)
            if self.best is None or cand[1] > self.best[1]:
                self.best = cand

    def _peaks(self, t: np.ndarray, f: np.ndarray, context: RunSource, final: bool) -> None:
        """The force's local maxima (as Solution._all_peaks, the step the median of the stretch's), those above
        :data:`PEAK_SHARE` of the largest so far."""
        for k, tt, _ in self.profile.maxima(t, f, final):
            h = float(np.median(np.diff(tt))) if tt.size > 1 else 0.0
            self.peaks.append(self._refine(float(tt[k]), h, context))
        if self.peaks:
            top = max(p[1] for p in self.peaks)
            self.peaks = [p for p in self.peaks if p[1] > PEAK_SHARE * top]

    def _refine(self, t_guess: float, h: float, context: RunSource) -> tuple[float, float]:
        """As Solution._refine_max on a run's dense output, within the contact and the segments at hand."""
        ev = self.ev
        segs = context.segments
        end = ev.end if math.isfinite(ev.end) else math.inf
        return context.refine_pair_max(ev.pair, t_guess, h, max(ev.onset, segs[0].t0), min(end, segs[-1].t1))

    def finish(self, window: list[tuple[int, Segment]], src: RunSource, t_final: float) -> None:
        """Absorb the kept segments, take the last candidates; the record's impulse, end energy and peak."""
        for number, seg in window:
            self.absorb(number, seg, src)
        self._candidates(self.nodes, np.empty(0), np.empty(0), src, True)
        if self.first:
            self._peaks(np.empty(0), np.empty(0), src, True)
            self.stream.peaks[self.i] = self.peaks
        ev = self.ev
        end = ev.end if math.isfinite(ev.end) else t_final
        ev.impulse = (ev.jump_impulse if self.jumped else 0.0) + self.impulse
        ev.energy_after = src.mechanical_energy(end)
        peak = self.best
        if peak is None and self.peaks:
            peak = max(self.peaks, key=lambda p: p[1])
        if peak is None and math.isfinite(self.top):
            peak = (self.top_at, self.top)
        if peak is not None:
            ev.peak_time, ev.peak_force = peak


class _Maxima:
    """The local maxima of a signal given stretch by stretch: each stretch is joined to the last two samples of the
    one before (a maximum's neighbours), its last sample waits for the next stretch; the very first sample counts as
    in :func:`~flexbeam.results.peaks.interior_maxima` with ``start``, a rising last one at the end."""

    def __init__(self) -> None:
        self.t, self.f = np.empty(0), np.empty(0)
        self.started = False

    def maxima(self, t: np.ndarray, f: np.ndarray, final: bool) -> list[tuple[int, np.ndarray, np.ndarray]]:
        tt, ff = np.concatenate((self.t, t)), np.concatenate((self.f, f))
        if ff.size < 2:
            self.t, self.f = tt, ff
            return []
        idx = interior_maxima(ff, start=not self.started)
        if final and ff[-1] > ff[-2]:
            idx.append(ff.size - 1)
        if not final:
            idx = [k for k in idx if k < ff.size - 1]
        self.started = True
        self.t, self.f = tt[-2:], ff[-2:]
        return [(k, tt, ff) for k in idx]


__all__ = ["PEAK_SHARE", "LongContact"]
