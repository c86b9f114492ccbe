"""Outputs of a run, evaluated on demand from its phases' dense output.

The integrators keep each phase's dense output and evaluate nothing while they run.  A :class:`RunSource`
evaluates, when asked: the output samples (the time grid of ``solver.sample_step`` in free flight and
``solver.contact_sample_step`` in contact, plus every phase's ends) for arrays, figures and NetCDF; the contact
force on the dense output for peaks (located to :data:`PEAK_XTOL`) and impulses; and the energies at the step
boundaries for the energy balance of the metrics.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from .. import numerics as nm
from ..integrate.loop import RunResult, Segment
from ..kernels import OUTPUT_COLUMNS, PAIR_COLUMNS
from ..model.system import SUPPORT_COLUMNS, BeamSystem
from .dense_force import compiled_pair_force
from .extremes import column_extremes
from .friction import friction_columns, has_friction
from .limits import check_samples
from .records import CENTRE_VARIABLES, FRICTION_VARIABLES
from .samplegrid import sample_count, sample_grid
from .segment_ends import SegmentEnds
from .tallies import SensorPulse

#: the samples of a segment evaluated at a time for the sensor pulse (RunSource.sensor_pulse)
PULSE_CHUNK = 2**16

#: force evaluations per step when searching a contact's force for local maxima
PEAK_POINTS_PER_STEP = 16


def centre_columns(system: BeamSystem, Y: np.ndarray) -> dict[str, np.ndarray]:
    """A free beam's G position and velocity (samples x 2: its coordinates x_G, y_G and their rates, the first two of
    the state's coordinates and of their rates) at the states ``Y``; empty for a beam on a joint."""
    if system.joint.kind != "free":
        return {}
    nz = system.nz
    return dict(zip(CENTRE_VARIABLES, (np.ascontiguousarray(Y[:, 0:2]), np.ascontiguousarray(Y[:, nz : nz + 2]))))


class RunSource:
    """Lazy outputs of a run of ``system`` (see the module docstring)."""

    def __init__(self, run: RunResult, system: BeamSystem) -> None:
        self.run, self.system = run, system

    @property
    def segments(self) -> list[Segment]:
        return self.run.segments

    @cached_property
    def segment_ends(self) -> SegmentEnds:
        """The output columns at every segment's two ends, evaluated together."""
        return SegmentEnds(self.segments, self.system)

    @cached_property
    def _starts(self) -> np.ndarray:
        """Each segment's start time (non-decreasing: the segments follow each other)."""
        return np.array([s.t0 for s in self.segments], float)

    @cached_property
    def _ends(self) -> np.ndarray:
        """Each segment's end time (non-decreasing)."""
        return np.array([s.t1 for s in self.segments], float)

    def _around(self, t0: float, t1: float) -> range:
        """The indices of the segments that may touch [t0, t1] (end >= t0 and start <= t1), by bisection: a query
        costs the segments it touches, not the run's length."""
        lo = int(np.searchsorted(self._ends, t0, side="left"))
        hi = int(np.searchsorted(self._starts, t1, side="right"))
        return range(lo, max(lo, hi))

    def evaluate(self, seg: Segment, times: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray]:
        """(columns, measuring velocities, states) of segment ``seg`` at ``times``."""
        cols, mv, _, Y = self.evaluate_pairs(seg, times)
        return cols, mv, Y

    def evaluate_pairs(self, seg: Segment, times: np.ndarray):
        """(columns, measuring velocities, the pairs' columns (samples x pairs x PAIR_COLUMNS), states) at
        ``times``."""
        Y = seg.states(times)
        cols, mv, pc = self.system.outputs(times, Y, seg.phase.buffer)
        return cols, mv, pc, Y

    def pair_force(self, seg: Segment, times: np.ndarray, pair: int) -> np.ndarray:
        """Contact force of ``pair`` in segment ``seg`` at ``times`` (a compiled phase: in the kernels, alone)."""
        forces = compiled_pair_force(seg, times, pair)
        return forces if forces is not None else self.evaluate_pairs(seg, times)[2][:, pair, 2]

    @cached_property
    def samples(self) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
        """(time, phase name, arrays) over the whole run."""
        sysm = self.system
        n, nz = sysm.n, sysm.nz
        self._check_samples(self.segments)  # the exact count, before evaluating
        times, phases, parts, rough = [], [], [], has_friction(self.segments)
        fparts = []
        for seg in self.segments:
            t = sample_grid(seg.t0, seg.t1, seg.phase.sample_step)
            cols, mv, pc, Y = self.evaluate_pairs(seg, t)
            if rough:
                fparts.append(friction_columns(sysm, seg, t, Y, pc[:, :, 2]))
            qs = Y[:, nz - n : nz]
            qds = Y[:, 2 * nz - n : 2 * nz]
            times.append(t)
            phases.append(np.full(t.size, seg.phase.name, dtype=object))
            parts.append((cols, mv, qs, qds, pc, centre_columns(sysm, Y)))
        names = [c for c in OUTPUT_COLUMNS if sysm.compliant or c not in SUPPORT_COLUMNS]
        if not parts:
            empty = {name: np.empty(0) for name in names}
            empty.update(
                q=np.empty((0, n)),
                q_rate=np.empty((0, n)),
                measuring_velocity=np.empty((0, 0)),
                total_energy=np.empty(0),
            )
            return np.empty(0), np.empty(0, dtype=object), empty
        out = {name: np.concatenate([p[0][name] for p in parts]) for name in names}
        out["q"] = np.concatenate([p[2] for p in parts])
        out["q_rate"] = np.concatenate([p[3] for p in parts])
        out["measuring_velocity"] = np.concatenate([p[1] for p in parts])
        out["total_energy"] = total_energy(out)
        if sysm.pairs > 1 or any(p.anywhere for p in sysm.contact.pairs):  # per pair (samples x pairs)
            pc = np.concatenate([p[4] for p in parts])
            for j, name in enumerate(PAIR_COLUMNS):
                out[f"pair_{name}"] = pc[:, :, j]
        for j, name in enumerate(FRICTION_VARIABLES if rough else ()):
            out[name] = np.concatenate([p[j] for p in fparts])
        for name in parts[0][5]:
            out[name] = np.concatenate([p[5][name] for p in parts])
        return np.concatenate(times), np.concatenate(phases), out

    # ---------------------------------------------------------------- contact force on the dense output
    def _contact_segments(self, t0: float, t1: float, pair: int = 0) -> list[Segment]:
        segs = self.segments
        return [
            s
            for s in (segs[i] for i in self._around(t0, t1))
            if s.phase.modes[pair] != 0 and s.t1 >= t0 and s.t0 <= t1 and s.t1 > s.t0
        ]

    def force_at(self, t: float, pair: int = 0) -> float:
        """A pair's contact force at time t on the dense output (0 outside its contact phases)."""
        for i in self._around(t, t):
            seg = self.segments[i]
            if seg.phase.modes[pair] != 0 and seg.t0 <= t <= seg.t1 and seg.t1 > seg.t0:
                return float(self.pair_force(seg, np.array([t]), pair)[0])
        return 0.0

    def force_many(self, times: np.ndarray, pair: int = 0) -> np.ndarray:
        """A pair's contact force at the ``times`` (within one contact phase each; 0 outside its contact
        phases)."""
        times = np.asarray(times, float)
        out = np.zeros(times.size)
        done = np.zeros(times.size, bool)
        if not times.size:
            return out
        for i in self._around(float(np.min(times)), float(np.max(times))):
            seg = self.segments[i]
            if seg.phase.modes[pair] == 0 or seg.t1 <= seg.t0:
                continue
            sel = ~done & (times >= seg.t0) & (times <= seg.t1)
            if sel.any():
                out[sel] = self.pair_force(seg, times[sel], pair)
                done |= sel
        return out

    def force_profile(self, t0: float, t1: float, pair: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(times, force) of a pair at PEAK_POINTS_PER_STEP points of every step of its contact phases in
        [t0, t1]."""
        ts, fs = [], []
        for seg in self._contact_segments(t0, t1, pair):
            b = seg.breaks()
            frac = np.linspace(0.0, 1.0, PEAK_POINTS_PER_STEP + 1)[:-1]
            t = np.append((b[:-1, None] + np.diff(b)[:, None] * frac[None, :]).ravel(), b[-1])
            t = t[(t >= t0) & (t <= t1)]
            if t.size:
                ts.append(t)
                fs.append(self.pair_force(seg, t, pair))
        if not ts:
            return np.empty(0), np.empty(0)
        t, f = np.concatenate(ts), np.concatenate(fs)
        order = np.argsort(t, kind="stable")
        return t[order], f[order]

    def nodal_profile(self, t0: float, t1: float, pair: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(times, force) of a pair at the force's own nodes in [t0, t1]: the compiled integrator's collocated
        contact forces (or multipliers) at every step's Gauss nodes, which it has already computed; a phase of
        the reference integrator is sampled as in :meth:`force_profile`.  Candidates for the force's maxima at
        no cost of evaluation."""
        ts, fs = [], []
        for seg in self._contact_segments(t0, t1, pair):
            if hasattr(seg.dense, "nodal_forces"):
                t, f = seg.dense.nodal_forces(pair)
                keep = (t >= t0) & (t <= t1)
                t, f = t[keep], f[keep]
            else:
                t, f = self.force_profile(max(t0, seg.t0), min(t1, seg.t1), pair)
            if t.size:
                ts.append(t)
                fs.append(f)
        if not ts:
            return np.empty(0), np.empty(0)
        t, f = np.concatenate(ts), np.concatenate(fs)
        order = np.argsort(t, kind="stable")
        return t[order], f[order]

    def impulse(self, t0: float, t1: float, pair: int = 0) -> float:
        """int F dt of a pair over [t0, t1]: over whole steps of the compiled integrator the Gauss quadrature of
        its nodal forces (exact for the collocated force), else 8-point Gauss-Legendre per step on the dense
        output."""
        x, w = nm.leggauss(8)
        total = 0.0
        for seg in self._contact_segments(t0, t1, pair):
            if seg.t0 >= t0 and seg.t1 <= t1 and hasattr(seg.dense, "impulse"):
                total += seg.dense.impulse(pair)
                continue
            b = np.clip(seg.breaks(), t0, t1)
            a, c = b[:-1], b[1:]
            keep = c > a
            a, c = a[keep], c[keep]
            if not a.size:
                continue
            t = (0.5 * (c - a)[:, None] * (x[None, :] + 1.0) + a[:, None]).ravel()
            F = self.pair_force(seg, t, pair).reshape(a.size, x.size)
            total += nm.fsum(0.5 * (c - a) * nm.matmul(F, w))
        return total

    def mechanical_energy(self, t: float, after: bool = False) -> float:
        """T + V_e + V_g at time t (no contact potential, no bookkeeping): in the last segment containing t
        (``after``: after a jump there) or the first."""
        idx = [i for i in self._around(t, t) if self.segments[i].t0 <= t <= self.segments[i].t1]
        if not idx:
            return math.nan
        i = idx[-1] if after else idx[0]
        names = ("kinetic_energy", "elastic_energy", "gravitational_energy")
        ends = [self.segment_ends.column(i, name, t) for name in names]  # at a phase's end: evaluated already
        if ends[0] is not None:
            return float(ends[0] + ends[1] + ends[2])
        cols = self.evaluate(self.segments[i], np.array([t]))[0]
        return float(cols["kinetic_energy"][0] + cols["elastic_energy"][0] + cols["gravitational_energy"][0])

    def _check_samples(self, segments: list[Segment]) -> None:
        """:func:`check_samples` for the output samples of ``segments``: those on the ``solver.contact_sample_step``
        grid and the others counted apart."""
        counts = {True: 0, False: 0}  # on the contact spacing or not
        fine = self.system.case.sample_steps()[1]
        for seg in segments:
            counts[seg.phase.sample_step == fine] += sample_count(seg.t0, seg.t1, seg.phase.sample_step)
        check_samples(self.system.case, self.system.pairs, counts[False], counts[True])

    def sensor_pulse(self, contacts: list) -> tuple[list[tuple[float, float]], float]:
        """The first sensor-force pulse's every positive peak and its duration (:class:`SensorPulse`, as a streamed
        run collects it), from the samples of the segments from the first contact's onset until the pulse is over:
        not the whole run's samples (a resting contact sampled at ``solver.contact_sample_step`` to its end made the
        metrics of 2 s of ``seed-experiment-calibrated`` evaluate 1e7 samples, 25 s and 3 GB)."""
        tally = SensorPulse(contacts)
        for i in self._around(contacts[0].onset, math.inf) if contacts else ():
            seg = self.segments[i]
            self._check_samples([seg])
            grid = sample_grid(seg.t0, seg.t1, seg.phase.sample_step)
            for j in range(0, grid.size, PULSE_CHUNK):  # a resting contact's grid in parts: the pulse may end early
                t = grid[j : j + PULSE_CHUNK]
                tally.feed(t, self.evaluate(seg, t)[0]["sensor_force"])
                if tally.done:
                    return tally.result()
        return tally.result()

    def extremes(self, column: str, points_per_step: int = 4, reached: tuple[float, float] | None = None,
                 window: tuple[float, float] | None = None) -> tuple[float, float]:  # fmt: skip
        """(min, max) of an output column over the run (``window``: over that time interval), located on the dense
        output (``reached``: extremes reached already, :func:`flexbeam.results.extremes.column_extremes`)."""
        return column_extremes(self, column, points_per_step, reached, window)

    def _zoom_all(
        self,
        seg: Segment,
        column: str,
        sign: float,
        lo: np.ndarray,
        hi: np.ndarray,
        points: int = 33,
        floor: float = -math.inf,
        reach: np.ndarray | None = None,
    ) -> float:
        """Largest sign * column over the brackets [lo_k, hi_k] of one segment (or ``floor``, a value already
        reached).  A compiled phase: :meth:`refine_max` (brackets whose bound ``reach`` is below the best value
        yet are skipped).  Otherwise each is zoomed on a grid of ``points`` until below PEAK_XTOL, all brackets in
        one evaluation per level, and a bracket is dropped once it cannot beat the best value seen: a smooth peak
        stands above its largest grid value by less than that value stands above the lower of the grid's two
        neighbours of it."""
        from .peaks import PEAK_XTOL

        found = self.refine_max(seg, OUTPUT_COLUMNS.index(column), sign, lo, hi, reach, floor)
        if found is not None:
            return max(floor, float(np.max(found[1]))) if found[1].size else floor
        lo, hi = lo.astype(float).copy(), hi.astype(float).copy()
        best = floor
        frac = np.linspace(0.0, 1.0, points)
        while lo.size:
            t = lo[:, None] + (hi - lo)[:, None] * frac[None, :]
            v = sign * self.evaluate(seg, t.ravel())[0][column].reshape(t.shape)
            rows = np.arange(t.shape[0])
            i = np.argmax(v, axis=1)
            top = v[rows, i]
            best = max(best, float(np.max(top)))
            if np.all(hi - lo <= PEAK_XTOL):
                return best
            low = np.minimum(v[rows, np.maximum(i - 1, 0)], v[rows, np.minimum(i + 1, points - 1)])
            keep = top + (top - low) >= best
            dt = (hi - lo) / (points - 1)
            centre = t[rows, i]
            lo, hi = np.maximum(lo, centre - dt)[keep], np.minimum(hi, centre + dt)[keep]
        return best

    def refine_max(
        self,
        seg: Segment,
        column: int,
        sign: float,
        lo: np.ndarray,
        hi: np.ndarray,
        reach: np.ndarray | None = None,
        floor: float = -math.inf,
    ) -> tuple[np.ndarray, np.ndarray] | None:
        """(times, values) of the largest ``sign`` x output in each bracket [lo_k, hi_k] of a compiled phase
        (``column`` >= 0: an output column's index; < 0: the contact force of pair -1 - column), located to
        PEAK_XTOL by Brent's method in the kernels in one call; None for a phase without compiled dense output
        (the reference integrator's), which the callers zoom on instead.  ``reach``, ``floor``: brackets whose
        bound is below the best value yet are skipped (value -inf; :meth:`ModalDense.column_max`)."""
        from .peaks import PEAK_XTOL

        if not hasattr(seg.dense, "column_max"):
            return None
        return seg.dense.column_max(
            seg.y0, seg.y1, seg.t0, seg.t1, seg.phase.buffer, column, sign, lo, hi, PEAK_XTOL, reach, floor
        )

    def refine_pair_max(self, pair: int, t_guess: float, h: float, lo: float, hi: float) -> tuple[float, float]:
        """(time, force) of the largest contact force of ``pair`` within ``h`` of ``t_guess`` in [lo, hi]: in the
        kernels when one compiled phase holds the bracket (:meth:`pair_max`), else zoomed on the dense output."""
        from .peaks import PEAK_XTOL, zoom_max

        a, b = max(lo, t_guess - h), min(hi, t_guess + h)
        if b <= a:
            return t_guess, float(self.force_many(np.array([t_guess]), pair)[0])
        found = self.pair_max(pair, a, b)
        return found if found is not None else zoom_max(lambda t: self.force_many(t, pair), a, b, xtol=PEAK_XTOL)

    def pair_max(self, pair: int, a: float, b: float) -> tuple[float, float] | None:
        """(time, force) of the largest contact force of ``pair`` in [a, b] when one compiled contact phase holds
        the whole bracket (:meth:`refine_max`), else None."""
        segs = self._contact_segments(a, b, pair)
        if len(segs) != 1 or not (segs[0].t0 <= a and b <= segs[0].t1):
            return None
        found = self.refine_max(segs[0], -1 - pair, 1.0, np.array([a]), np.array([b]))
        return None if found is None else (float(found[0][0]), float(found[1][0]))

    # ---------------------------------------------------------------- energy balance
    @cached_property
    def checkpoints(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(times, total energy, kinetic energy) at every step boundary of the run."""
        ts, Es, Ts = [], [], []
        for i, seg in enumerate(self.segments):
            if hasattr(seg.dense, "step_energies"):  # the compiled integrator books them at every step's end
                t_end, E_end, T_end = seg.dense.step_energies()
                cols = self.segment_ends.start_columns(i)
                ts.append(np.concatenate(([seg.t0], t_end)))
                Es.append(np.concatenate((total_energy(cols), E_end)))
                Ts.append(np.concatenate((cols["kinetic_energy"], T_end)))
                continue
            t = seg.breaks()
            cols = self.evaluate(seg, t)[0]
            ts.append(t)
            Es.append(total_energy(cols))
            Ts.append(cols["kinetic_energy"])
        if not ts:
            return np.empty(0), np.empty(0), np.empty(0)
        return np.concatenate(ts), np.concatenate(Es), np.concatenate(Ts)


def total_energy(cols: dict[str, np.ndarray]) -> np.ndarray:
    """T + V_e + V_g + U_c + E_d - W: conserved by the equations (the energy balance)."""
    return (
        cols["kinetic_energy"]
        + cols["elastic_energy"]
        + cols["gravitational_energy"]
        + cols["contact_energy"]
        + cols["dissipated_energy"]
        - cols["drive_work"]
    )
