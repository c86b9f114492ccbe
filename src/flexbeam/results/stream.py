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
from typing import TYPE_CHECKING, Any

import numpy as np

from ..integrate.loop import RunResult, Segment
from ..integrate.modal import BLOCK_RECORDS
from ..kernels import OUTPUT_COLUMNS, PAIR_COLUMNS
from ..model.system import SUPPORT_COLUMNS, BeamSystem
from ..parameters.case import Case
from . import export
from .arrays import RunSource, centre_columns, sample_grid, total_energy
from .episode_stream import STREAMED, EpisodeStream
from .files import file_stamp
from .friction import friction_columns
from .long_contact import LongContact
from .parts import part_states
from .records import FRICTION_VARIABLES, ContactEvent
from .samplefile import SampleFile
from .solution import Solution
from .tallies import EnergyTally, SensorPulse

if TYPE_CHECKING:
    from pathlib import Path

#: steps kept for the open contact records before the earliest of them is completed stretch by stretch
WINDOW_RECORDS = 4 * BLOCK_RECORDS
#: output samples evaluated at a time
BATCH = export.TIME_CHUNK


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
        #: CCFM, CCM or IMM with Coulomb friction: the friction variables (time x pair) from the first sample on
        self.rough = provenance.get("method") in ("ccfm", "ccm", "imm") and any(
            p.frictional for p in system.contact.pairs
        )
        self.names = [c for c in OUTPUT_COLUMNS if system.compliant or c not in SUPPORT_COLUMNS]
        nsb = export.precision_bits(provenance) if quantize else None
        labels = [p.label for p in system.contact.pairs] if self.per_pair or self.rough else None
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
        #: a free beam's collision episodes, found as the run goes on
        self.episodes = EpisodeStream(self) if system.joint.kind == "free" else None

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
        if self.rough:
            for name, value in zip(FRICTION_VARIABLES, friction_columns(sysm, seg, t, Y, pc[:, :, 2])):
                out[name] = np.ascontiguousarray(value)
        out.update(centre_columns(sysm, Y))
        return out

    def _tally(self, seg: Segment) -> None:
        """The segment's energy checkpoints and tip extremes (:attr:`RunSource.checkpoints`,
        :meth:`RunSource.extremes`, on this segment)."""
        src = self.source([seg])
        _, E, T = src.checkpoints
        self.energy.add(E, T)
        lo, hi = src.extremes("tip_deflection", reached=(self.tip[0], self.tip[1]))
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
            if self.episodes is not None:
                self.episodes.update(now)
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
            if self.episodes is not None:  # the instants of the open episode still to be read
                cut = min(cut, self.episodes.cut())
            k = 0
            while k < len(self.window) and self.window[k][1].t1 < cut:
                k += 1
            if k:
                for number, seg in self.window[:k] if self.episodes is not None else ():
                    self.episodes.absorb(number, seg)
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
        if self.episodes is not None:
            summaries[STREAMED] = self.episodes.finish(run.t_final)
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
        sol.file_stamp = file_stamp(self.file.close(sol))
        return sol

    def abort(self) -> None:
        """The run did not finish: no file."""
        self.file.abort()


__all__ = ["BATCH", "WINDOW_RECORDS", "EnergyTally", "LongContact", "RunStream", "SensorPulse", "sample_times"]
