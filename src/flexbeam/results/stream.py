"""A run streamed to its result file, in a memory that does not grow with the run.

The phase loop (:func:`flexbeam.integrate.loop.run_phases`) hands every segment -- a phase, or a part of a long
phase (:data:`~flexbeam.integrate.modal.BLOCK_RECORDS` steps) -- to a :class:`RunStream` as soon as it is made.
The stream

* evaluates the segment's output samples, in batches, and appends them to the result file
  (:class:`~flexbeam.results.samplefile.SampleFile`): the same samples an in-memory run evaluates, bit for bit;
* adds the segment to the run's summaries: the energy balance at its step boundaries, the tip deflection's extremes
  (:class:`~flexbeam.results.arrays.RunSource`'s own evaluations, segment by segment) and the first sensor-force
  pulse;
* keeps the segment while a contact record may still need it, and completes each record once the run has moved
  past its end, exactly as an in-memory run does (:meth:`Solution.contact
  <flexbeam.results.solution.Solution.contact>`, on the segments kept; the impulse over a phase handed on in parts
  is the sum of its parts' -- each correctly rounded --, equal to round-off);
* then drops the segment with its dense output.

A contact that outlasts :data:`WINDOW_RECORDS` steps (a beam coming to rest on its stop) is completed stretch by
stretch instead (:class:`LongContact`): its impulse summed segment by segment as in memory, its energies at its ends,
its peak found among the candidates of each stretch (the maxima of the integrator's nodal forces that could be the
largest so far, refined on the dense output), its force peaks -- for the first contact of a pair -- kept above 5 %
of the largest so far.  What the run keeps in memory is then a few blocks of steps, two chunks of samples and the
contact records: :func:`flexbeam.memory.estimate` with ``stream``.
"""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..integrate.loop import RunResult, Segment
from ..integrate.modal import BLOCK_RECORDS
from ..kernels import OUTPUT_COLUMNS, PAIR_COLUMNS
from ..model.system import SUPPORT_COLUMNS, BeamSystem
from ..parameters.case import Case
from . import export
from .arrays import RunSource, sample_grid, total_energy
from .peaks import PEAK_XTOL, interior_maxima, zoom_max
from .records import ContactEvent
from .samplefile import SampleFile
from .solution import Solution
from .summary import sensor_pulse

if TYPE_CHECKING:
    from pathlib import Path

#: steps kept for the open contact records before the earliest of them is completed stretch by stretch
WINDOW_RECORDS = 4 * BLOCK_RECORDS
#: output samples evaluated at a time
BATCH = export.TIME_CHUNK
#: samples of the first sensor-force pulse kept (16 MB); a pulse not over by then ends there (its duration NaN)
PULSE_SAMPLES = 2**20
#: the force peaks of a long first contact kept: above this share of the largest so far (the metrics' threshold)
PEAK_SHARE = 0.05


def steps_of(seg: Segment) -> int:
    """The steps of a segment's dense output (what it holds)."""
    dense = seg.dense
    if dense is None:
        return 0
    records = getattr(dense, "records", None)
    return int(records.shape[0]) if records is not None else max(0, len(dense.breaks) - 1)


def sample_times(seg: Segment, step: float, batch: int | None = None):
    """The output sample times of a segment, in batches of at most ``batch``: those of
    :func:`~flexbeam.results.arrays.sample_grid` for a whole phase; for a part of one (``opens``/``closes`` False)
    the phase's start where it opens, the multiples of ``step`` after its start up to its end (included where the
    phase goes on), and the phase's end where it closes."""
    batch = BATCH if batch is None else batch
    t0, t1 = seg.t0, seg.t1
    if t1 <= t0:
        yield np.array([t0 if seg.opens else t1])
        return
    k0, k1 = math.floor(t0 / step) + 1, math.floor(t1 / step)
    if seg.opens and seg.closes and k1 - k0 + 3 <= batch:
        yield sample_grid(t0, t1, step)
        return
    head = [np.array([t0])] if seg.opens else []
    for kb in range(k0, k1 + 1, batch):
        grid = np.arange(kb, min(kb + batch, k1 + 1)) * step
        grid = grid[(grid > t0) & ((grid < t1) if seg.closes else (grid <= t1))]
        if head:
            grid = np.concatenate([*head, grid])
            head = []
        if grid.size:
            yield grid
    tail = [*head, np.array([t1])] if seg.closes else head
    if tail:
        yield np.concatenate(tail)


def part_states(seg: Segment, times: np.ndarray) -> np.ndarray:
    """States at ``times``: :meth:`Segment.states` for a whole phase; for a part, the dense output everywhere but at
    the phase's own ends (its ends inside the phase are evaluated as the whole phase's dense output evaluates them)."""
    if seg.opens and seg.closes:
        return seg.states(times)
    out = np.empty((times.size, seg.y0.size))
    first = (times <= seg.t0) if seg.opens else np.zeros(times.size, bool)
    last = (times >= seg.t1) & ~first if seg.closes else np.zeros(times.size, bool)
    inner = ~first & ~last
    if inner.any():
        out[inner] = seg.dense(times[inner])
    out[first] = seg.y0
    out[last] = seg.y1
    return out


class RunStream:
    """The sink of a streamed run (see the module docstring): ``stream(segment)`` for each segment,
    :meth:`finish` at the end for the :class:`~flexbeam.results.solution.Solution`.

    Parameters
    ----------
    path
        The result file.
    system, case
        What runs.
    contacts
        The impact method's contact log, as it grows (the stream completes its records).
    provenance
        The run's provenance (the tolerance sets the precision of the file's outputs).
    quantize
        Round the outputs of the integrated state to the integrator's precision (as :func:`to_netcdf
        <flexbeam.results.export.to_netcdf>`).
    """

    def __init__(
        self,
        path: str | Path,
        system: BeamSystem,
        case: Case,
        contacts: list[ContactEvent],
        provenance: dict[str, Any],
        quantize: bool = True,
    ) -> None:
        self.system, self.case, self.contacts, self.provenance = system, case, contacts, provenance
        self.per_pair = system.pairs > 1 or any(p.anywhere for p in system.contact.pairs)
        self.names = [c for c in OUTPUT_COLUMNS if system.compliant or c not in SUPPORT_COLUMNS]
        nsb = export.precision_bits(provenance) if quantize else None
        labels = [p.label for p in system.contact.pairs] if self.per_pair else None
        self.file = SampleFile(
            path,
            system.n,
            np.asarray(case.output.measuring_points, float),
            labels,
            nsb,
            float(provenance.get("rtol", math.nan)),
            str(provenance.get("flexbeam_version", "")),
            export.TIME_CHUNK,
        )
        self.window: list[tuple[int, Segment]] = []  # (number, segment), in time order
        self.held = 0  # steps of the window
        self.count = 0
        self.completed: set[int] = set()
        self.long: dict[int, LongContact] = {}
        self.peaks: dict[int, list[tuple[float, float]]] = {}
        self.pending: tuple[np.ndarray, str, dict[str, np.ndarray]] | None = None
        self.energy = EnergyTally()
        self.tip = [math.inf, -math.inf]
        self.sensor = SensorPulse(contacts) if system.compliant else None

    # ----------------------------------------------------------------- a segment
    def __call__(self, seg: Segment) -> None:
        number = self.count
        self.count += 1
        self._sample(seg)
        self._tally(seg)
        self.window.append((number, seg))
        self.held += steps_of(seg)
        self._settle(seg.t0)

    def source(self, segments: list[Segment], t_final: float = math.nan) -> RunSource:
        """A :class:`RunSource` on some of the run's segments."""
        return RunSource(RunResult(list(segments), "", "", t_final, 0.0, 0, 0, ""), self.system)

    def _sample(self, seg: Segment) -> None:
        if self.pending is not None:  # a part's last sample: the phase's end replaces it if the phase ends there
            t, name, rows = self.pending
            self.pending = None
            if not (seg.closes and not seg.opens and seg.t0 == seg.t1 == t[0]):
                self._emit(t, name, rows)
        for t in sample_times(seg, seg.phase.sample_step):
            rows = self._rows(seg, t, part_states(seg, t))
            if not seg.closes and t[-1] == seg.t1:
                self.pending = (t[-1:], seg.phase.name, {k: v[-1:] for k, v in rows.items()})
                t, rows = t[:-1], {k: v[:-1] for k, v in rows.items()}
            self._emit(t, seg.phase.name, rows)

    def _emit(self, t: np.ndarray, name: str, rows: dict[str, np.ndarray]) -> None:
        if not t.size:
            return
        self.file.append(t, name, rows)
        if self.sensor is not None:
            self.sensor.feed(t, rows["sensor_force"])

    def _rows(self, seg: Segment, t: np.ndarray, Y: np.ndarray) -> dict[str, np.ndarray]:
        """The output variables at ``t`` (as :attr:`RunSource.samples` assembles them)."""
        sysm = self.system
        n, nz = sysm.n, sysm.nz
        cols, mv, pc = sysm.outputs(t, Y, seg.phase.buffer)
        out = {name: np.ascontiguousarray(cols[name]) for name in self.names}
        out["q"] = np.ascontiguousarray(Y[:, nz - n : nz])
        out["q_rate"] = np.ascontiguousarray(Y[:, 2 * nz - n : 2 * nz])
        out["measuring_velocity"] = mv
        out["total_energy"] = total_energy(cols)
        if self.per_pair:
            for j, name in enumerate(PAIR_COLUMNS):
                out[f"pair_{name}"] = np.ascontiguousarray(pc[:, :, j])
        return out

    def _tally(self, seg: Segment) -> None:
        """The segment's energy checkpoints and tip extremes (:attr:`RunSource.checkpoints`,
        :meth:`RunSource.extremes`, on this segment)."""
        src = self.source([seg])
        _, E, T = src.checkpoints
        self.energy.add(E, T)
        lo, hi = src.extremes("tip_deflection")
        if not math.isnan(lo):
            self.tip = [min(self.tip[0], lo), max(self.tip[1], hi)]

    # ----------------------------------------------------------------- the contact records
    def first_of_pair(self, i: int) -> bool:
        pair = self.contacts[i].pair
        return next(j for j, ev in enumerate(self.contacts) if ev.pair == pair) == i

    def _settle(self, now: float, t_final: float | None = None) -> None:
        """Complete the records that ended before ``now`` (all of them at the end: ``t_final``), then drop what no
        open record needs."""
        for i, ev in enumerate(self.contacts):
            if i in self.completed:
                continue
            if t_final is not None or (math.isfinite(ev.end) and ev.end < now):
                self._complete(i, math.nan if t_final is None else t_final)
        if t_final is None:
            self._trim(now)

    def _complete(self, i: int, t_final: float) -> None:
        src = self.source([s for _, s in self.window], t_final)
        if i in self.long:
            self.long.pop(i).finish(self.window, src, t_final)
        else:  # every segment since before its onset is kept: as in memory
            sol = Solution(contacts=self.contacts, source=src)
            sol._completed = set(range(len(self.contacts))) - {i}
            sol.contact(i)
            if self.first_of_pair(i):
                sol.force_peaks(i)
                self.peaks[i] = sol._peaks.get(i, [])
        self.completed.add(i)

    def _trim(self, now: float) -> None:
        """Drop the segments that end before the earliest open record's onset (before ``now`` without one); when
        the open records hold more than :data:`WINDOW_RECORDS` steps, the earliest goes on stretch by stretch."""
        while True:
            waiting = [i for i in range(len(self.contacts)) if i not in self.completed and i not in self.long]
            cut = min([now, *(self.contacts[i].onset for i in waiting)])
            k = 0
            while k < len(self.window) and self.window[k][1].t1 < cut:
                k += 1
            if k:
                if self.long:
                    context = self.source([s for _, s in self.window])
                    for number, seg in self.window[:k]:
                        for lc in self.long.values():
                            lc.absorb(number, seg, context)
                self.held -= sum(steps_of(s) for _, s in self.window[:k])
                del self.window[:k]
            if self.held <= WINDOW_RECORDS or not waiting:
                return
            i = min(waiting, key=lambda j: self.contacts[j].onset)
            self.long[i] = LongContact(self, i, self.source([s for _, s in self.window]))

    # ----------------------------------------------------------------- the end
    def finish(self, run: RunResult, stats: dict[str, float]) -> Solution:
        """Complete the records, write the file's last samples, records and attributes; the Solution of the run
        (its samples read from the file when asked for)."""
        if self.pending is not None:
            t, name, rows = self.pending
            self.pending = None
            self._emit(t, name, rows)
        self._settle(math.inf, run.t_final)
        lo, hi = self.tip
        summaries: dict[str, Any] = {
            "energy_drift": self.energy.drift(),
            "tip_deflection": (lo, hi) if lo <= hi else (math.nan, math.nan),
        }
        if self.sensor is not None:
            summaries["sensor_pulse"] = self.sensor.result()
        sol = Solution(
            contacts=self.contacts,
            status=run.status,
            message=run.message,
            stats=stats,
            provenance=self.provenance,
            measuring_points=np.asarray(self.case.output.measuring_points, float),
            file=self.file.path,
            summaries=summaries,
        )
        sol._peaks.update(self.peaks)
        self.file.close(sol)
        return sol

    def abort(self) -> None:
        """The run did not finish: no file."""
        self.file.abort()


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
        lo, hi = max(ev.onset, segs[0].t0), min(end, segs[-1].t1)
        a, b = max(lo, t_guess - h), min(hi, t_guess + h)

        def force(t):
            return context.force_many(t, ev.pair)

        if b <= a:
            return t_guess, float(force(np.array([t_guess]))[0])
        return zoom_max(force, a, b, xtol=PEAK_XTOL)

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


class EnergyTally:
    """The energy balance of :func:`~flexbeam.results.summary.energy_drift`, checkpoint batch by batch."""

    def __init__(self) -> None:
        self.E0: float | None = None
        self.deviation = 0.0
        self.kinetic = -math.inf
        self.last = math.nan

    def add(self, E: np.ndarray, T: np.ndarray) -> None:
        if not E.size:
            return
        if self.E0 is None:
            self.E0 = E[0]
        self.deviation = max(self.deviation, np.max(np.abs(E - self.E0)))
        self.kinetic = max(self.kinetic, float(np.max(T)))
        self.last = E[-1]

    def drift(self) -> tuple[float, float]:
        """(end, max) relative change of the total energy."""
        if self.E0 is None:
            return math.nan, math.nan
        scale = max(abs(self.E0), self.kinetic, 1e-300)
        return float((self.last - self.E0) / scale), float(self.deviation / scale)


class SensorPulse:
    """The samples of the first sensor-force pulse (:func:`~flexbeam.results.summary.sensor_pulse`), collected from
    the first contact's onset until the force has been positive and returns to zero (at most
    :data:`PULSE_SAMPLES`)."""

    def __init__(self, contacts: list[ContactEvent]) -> None:
        self.contacts = contacts
        self.tail: tuple[np.ndarray, np.ndarray] | None = None  # the last batch before the first onset
        self.t: list[np.ndarray] = []
        self.f: list[np.ndarray] = []
        self.size = 0
        self.positive = False
        self.done = False

    def feed(self, t: np.ndarray, f: np.ndarray) -> None:
        if self.done:
            return
        if not self.contacts:
            self.tail = (t.copy(), f.copy())
            return
        if self.tail is not None:
            tail, self.tail = self.tail, None
            self.feed(*tail)
        keep = t >= self.contacts[0].onset
        t, f = t[keep], f[keep]
        if not self.positive:
            pos = np.nonzero(f > 0.0)[0]
            if pos.size:
                self.positive = True
                back = np.nonzero(f[pos[0] :] <= 0.0)[0]
                stop = pos[0] + back[0] + 1 if back.size else None
            else:
                stop = None
        else:
            back = np.nonzero(f <= 0.0)[0]
            stop = back[0] + 1 if back.size else None
        if stop is not None:
            t, f = t[:stop], f[:stop]
            self.done = True
        room = PULSE_SAMPLES - self.size
        if t.size > room:
            t, f = t[:room], f[:room]
            self.done = True
        self.t.append(t.copy())
        self.f.append(f.copy())
        self.size += t.size

    def result(self) -> tuple[list[tuple[float, float]], float]:
        if not self.contacts or not self.t:
            return [], math.nan
        samples = SimpleNamespace(
            arrays={"sensor_force": np.concatenate(self.f)}, records=self.contacts[:1], time=np.concatenate(self.t)
        )
        return sensor_pulse(samples, threshold=0.0)  # every positive peak: the metrics choose theirs


__all__ = ["BATCH", "WINDOW_RECORDS", "EnergyTally", "LongContact", "RunStream", "SensorPulse", "sample_times"]
