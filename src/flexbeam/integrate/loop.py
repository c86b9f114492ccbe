"""The phase loop shared by every integrator: phases, events and the impact method's transitions.

An integrator (a *stepper*: :class:`~flexbeam.integrate.modal.ModalStepper`, compiled and the default, or
:class:`~flexbeam.integrate.reference.ReferenceStepper`, scipy's DOP853) advances one
:class:`~flexbeam.integrate.phases.Phase` until one of its events or t_end and returns the phase's dense output; at each
event the impact method decides the next phase and may make the velocities jump.  Every phase, and every jump,
starts a new :class:`Segment`.  A numerical failure ends the run with ``status = "failed"`` and a message with
the time and the cause; what was computed is kept.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from ..errors import SolverError
from .phases import EventKind, Phase

MAX_STALLED = 100  # consecutive zero-length phases before the run is declared stalled


class DenseOutput(Protocol):
    """States of a phase at any times inside it (rows), and the step boundaries ``breaks``."""

    breaks: np.ndarray

    def __call__(self, times: np.ndarray) -> np.ndarray: ...


@dataclass
class Segment:
    """One phase interval: its start and end states and its dense output (None for a zero-length phase)."""

    phase: Phase
    t0: float
    t1: float
    y0: np.ndarray
    y1: np.ndarray
    dense: DenseOutput | None = None

    def states(self, times: np.ndarray) -> np.ndarray:
        """States at ``times`` (in [t0, t1]); the ends are the exact start and end states."""
        times = np.asarray(times, float)
        out = np.empty((times.size, self.y0.size))
        inner = (times > self.t0) & (times < self.t1)
        if self.dense is not None and inner.any():
            out[inner] = self.dense(times[inner])
        out[times <= self.t0] = self.y0
        out[(times >= self.t1) & ~(times <= self.t0)] = self.y1
        return out

    def breaks(self) -> np.ndarray:
        """Step boundaries inside the segment, t0 and t1 included."""
        if self.dense is None:
            return np.array([self.t0, self.t1])
        b = np.asarray(self.dense.breaks, float)
        return np.unique(np.clip(np.concatenate(([self.t0], b, [self.t1])), self.t0, self.t1))


@dataclass
class PhaseRun:
    """What a stepper returns for one phase."""

    t1: float
    y1: np.ndarray
    event: EventKind | None
    dense: DenseOutput | None
    steps: int = 0
    nfev: int = 0
    failure: str = ""
    pair: int = 0  #: the contact pair the event belongs to


class Stepper(Protocol):
    """An integrator of one phase."""

    name: str

    def advance(self, phase: Phase, t: float, y: np.ndarray, t_end: float) -> PhaseRun: ...


class Stop(Exception):
    """Raised by a method's transition to end the run cleanly with a status."""

    def __init__(self, status: str, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


class PhaseMethod(Protocol):
    """What an impact method gives the loop."""

    def start(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]: ...

    def free_phase(self) -> Phase: ...

    def transition(
        self, phase: Phase, event: EventKind, t: float, y: np.ndarray, pair: int = 0
    ) -> tuple[Phase, np.ndarray]: ...


@dataclass
class RunResult:
    """Segments, status and statistics of a run."""

    segments: list[Segment]
    status: str
    message: str
    t_final: float
    wall_time: float
    steps: int
    nfev: int
    integrator: str
    events: int = 0
    phase_steps: list[tuple[str, int]] = field(default_factory=list)


def run_phases(
    method: PhaseMethod, stepper: Stepper, y0: np.ndarray, t_end: float, progress: Callable[[float], None] | None = None
) -> RunResult:
    """Integrate from t = 0 to ``t_end``, switching phases at events as ``method`` decides.

    A floating-point overflow, division by zero or invalid operation outside the compiled kernels (in the impulse
    map, an event's root, a state scaled beyond double precision) ends the run with ``status = "failed"`` at its
    time, keeping what was computed, instead of a RuntimeWarning and NaN states.
    """
    wall0 = time.perf_counter()
    y0 = np.asarray(y0, float)
    segments: list[Segment] = []
    steps = nfev = events = 0
    phase_steps: list[tuple[str, int]] = []
    status, message = "success", "integration reached t_end"
    t = 0.0
    try:
        phase, y = method.start(0.0, y0)
    except Stop as stop:
        return RunResult([], stop.status, stop.message, 0.0, 0.0, 0, 0, stepper.name)
    if not np.array_equal(y, y0):  # a jump at the start: keep the state before it
        segments.append(Segment(method.free_phase(), 0.0, 0.0, y0.copy(), y0.copy()))
    stalled = 0
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        try:
            while t < t_end:
                run = stepper.advance(phase, t, y, t_end)
                steps += run.steps
                nfev += run.nfev
                phase_steps.append((phase.name, run.steps))
                segments.append(Segment(phase, t, run.t1, y.copy(), run.y1.copy(), run.dense))
                stalled = stalled + 1 if run.t1 == t else 0
                t, y = run.t1, run.y1
                if progress is not None:
                    progress(t)
                if run.failure:
                    status, message = "failed", run.failure
                    break
                if run.event is None:
                    break
                events += 1
                try:
                    phase, y = method.transition(phase, run.event, t, y, run.pair)
                except Stop as stop:
                    status, message = stop.status, stop.message
                    break
                except SolverError as err:
                    status, message = "failed", str(err)
                    break
                if stalled > MAX_STALLED:
                    status, message = "failed", f"events keep recurring without progress at t = {t:.9g} s"
                    break
        except (FloatingPointError, OverflowError, ZeroDivisionError) as exc:
            status, message = "failed", f"floating-point failure at t = {t:.9g} s: {exc}"
    wall = time.perf_counter() - wall0
    return RunResult(segments, status, message, t, wall, steps, nfev, stepper.name, events, phase_steps)
