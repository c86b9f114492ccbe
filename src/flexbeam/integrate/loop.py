"""The phase loop shared by every integrator: phases, events and the impact method's transitions.

An integrator (a *stepper*: :class:`~flexbeam.integrate.modal.ModalStepper`, compiled and the default, or
:class:`~flexbeam.integrate.reference.ReferenceStepper`, scipy's DOP853) advances one
:class:`~flexbeam.integrate.phases.Phase` until one of its events or t_end and returns the phase's dense output; at each
event the impact method decides the next phase and may make the velocities jump.  Every phase, and every jump,
starts a new :class:`Segment`.  A numerical failure ends the run with ``status = "failed"`` and a message with
the time and the cause; what was computed is kept.

A run streamed to disk (``sink``: :class:`flexbeam.results.stream.RunStream`) hands each segment on as it is made
instead of keeping it; a stepper with a ``hand_on`` hook (the compiled one) hands a long phase on in parts of one or
two :data:`~flexbeam.integrate.modal.BLOCK_RECORDS` steps while it runs, so that no phase's dense output grows with
the run.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from ..errors import SolverError
from ..interrupt import interrupted_message
from .phases import FRICTION_EVENTS, PAINLEVE_EVENTS, EventKind, Phase

MAX_STALLED = 100  # consecutive zero-length phases before the run is declared stalled
#: A storm of friction events: STORM_EVENTS consecutive friction switches of the contacts (stops, ends of sticks,
#: Painlevé's slips; the phase loop's and those a stepper takes), no other event between them, within STORM_SPAN [s]
#: end the run as making no progress.  Impacts are not counted: they are contacts, capped by solver.max_contacts
#: (IMM's chatter of the axially stiff rod-end: impacts 1e-11-1e-8 s apart, stopped there with its own advice).
#: The least span of 100 friction switches in a row, measured over frictional cases (every method, up to 1 s:
#: tip-wall, also with axial modes, two-stops, the seed case, free-bar-drop, rod-end with 32 axial modes, the shaker)
#: is 8.4e-3 s (the seed case under CCM), 8000 times the span; a single pair anywhere on a bar lying flat on a floor,
#: its one contact point jumping between the bar's ends, switched its slip's direction every 1-3 ns (100 stops in
#: 5e-7 s): ~1e8 switches a second of the run.
STORM_EVENTS = 100
STORM_SPAN = 1e-6
#: the event kinds a storm counts (built once: the loop tests each event against it)
_STORM_KINDS = FRICTION_EVENTS + PAINLEVE_EVENTS


class DenseOutput(Protocol):
    """States of a phase at any times inside it (rows), and the step boundaries ``breaks``."""

    breaks: np.ndarray

    def __call__(self, times: np.ndarray) -> np.ndarray: ...


@dataclass
class Segment:
    """One phase interval: its start and end states and its dense output (None for a zero-length phase).

    A phase handed on in parts (a streamed run) gives several segments: ``opens`` is False for all but its first,
    ``closes`` False for all but its last (their ends are step boundaries inside the phase)."""

    phase: Phase
    t0: float
    t1: float
    y0: np.ndarray
    y1: np.ndarray
    dense: DenseOutput | None = None
    opens: bool = True
    closes: bool = True

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
class Switch:
    """A switch the stepper took inside a phase without ending it (``kernels/src/switching.c``): the part of the
    phase before it (its dense output, steps and node evaluations), the time and state there (before any jump), the
    event and the rule's row -- CCFM's Coulomb friction (a stop, the end of a stick: the pair's friction row after it,
    a stop's stick or the slip it broke into at once), or CCM's contact on one pair (an onset, row[0] 1 if the pair
    is then held; a release).  ``record``: what the rule computed for the contact record -- an onset's jump [P, v-,
    v+, T-, T+, 0], a release's [0, 0, 0, 0, 0, delta'] (zeros for a friction switch) --, ``y_after`` the state after
    the switch (y moved by an onset's jump)."""

    t: float
    y: np.ndarray
    event: EventKind
    pair: int
    row: np.ndarray
    dense: DenseOutput | None
    steps: int
    nfev: int
    record: np.ndarray
    y_after: np.ndarray


@dataclass
class PhaseRun:
    """What a stepper returns for one phase (``switches``: the switches it took inside the phase, in time order; the
    rest of the fields are those of the part after the last of them)."""

    t1: float
    y1: np.ndarray
    event: EventKind | None
    dense: DenseOutput | None
    steps: int = 0
    nfev: int = 0
    failure: str = ""
    pair: int = 0  #: the contact pair the event belongs to
    #: where ``dense`` starts (time, state) when the phase's earlier steps were handed on in parts (``hand_on``)
    t0: float | None = None
    y0: np.ndarray | None = None
    switches: list[Switch] = field(default_factory=list)


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

    def kernel_switched(self, phase: Phase, switch: Switch) -> tuple[Phase, np.ndarray]: ...


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
    method: PhaseMethod,
    stepper: Stepper,
    y0: np.ndarray,
    t_end: float,
    progress: Callable[[float], None] | None = None,
    sink: Callable[[Segment], None] | None = None,
    stop: Callable[[], str] | None = None,
) -> RunResult:
    """Integrate from t = 0 to ``t_end``, switching phases at events as ``method`` decides.

    A floating-point overflow, division by zero or invalid operation outside the compiled kernels (in the impulse
    map, an event's root, a state scaled beyond double precision) ends the run with ``status = "failed"`` at its
    time, keeping what was computed, instead of a RuntimeWarning and NaN states.

    With a ``sink`` every segment goes to it, in time order, and none is kept (``RunResult.segments`` is empty); a
    stepper with a ``hand_on`` attribute hands its long phases to the sink in parts.

    ``stop``: asked after each phase and by the stepper (its ``stop``) between blocks of steps for a cause that ends
    the run where it is ("Ctrl-C", :mod:`flexbeam.interrupt`; "" goes on): ``status = "interrupted"``, what was
    computed kept (:func:`_interrupted`).
    """
    wall0 = time.perf_counter()
    y0 = np.asarray(y0, float)
    segments: list[Segment] = []
    keep = segments.append if sink is None else sink
    parts = sink is not None and hasattr(stepper, "hand_on")
    steps = nfev = events = 0
    phase_steps: list[tuple[str, int]] = []
    status, message = "success", "integration reached t_end"
    t = 0.0
    try:
        phase, y = method.start(0.0, y0)
    except Stop as ended:
        return RunResult([], ended.status, ended.message, 0.0, 0.0, 0, 0, stepper.name)
    if not np.array_equal(y, y0):  # a jump at the start: keep the state before it
        keep(Segment(method.free_phase(), 0.0, 0.0, y0.copy(), y0.copy()))
    stalled = 0
    recent: deque[float] = deque(maxlen=STORM_EVENTS)  # the times of the latest friction events in a row
    stepper.stop = stop
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        try:
            while t < t_end:
                if parts:
                    stepper.hand_on = _hand_on(sink, phase, progress)
                run = stepper.advance(phase, t, y, t_end)
                for sw in run.switches:  # the parts of the phase that switches inside the stepper ended
                    steps, nfev, events = steps + sw.steps, nfev + sw.nfev, events + 1
                    phase_steps.append((phase.name, sw.steps))
                    keep(Segment(phase, t, sw.t, y.copy(), sw.y.copy(), sw.dense))
                    t = sw.t
                    phase, y = method.kernel_switched(phase, sw)
                    stalled = 0
                    _tally(recent, sw.event, t)
                steps, nfev = steps + run.steps, nfev + run.nfev
                phase_steps.append((phase.name, run.steps))
                if run.t0 is None:
                    keep(Segment(phase, t, run.t1, y.copy(), run.y1.copy(), run.dense))
                else:  # the rest of a phase handed on in parts
                    keep(Segment(phase, run.t0, run.t1, run.y0, run.y1.copy(), run.dense, opens=False))
                stalled = stalled + 1 if run.t1 == t else 0
                t, y = run.t1, run.y1
                if progress is not None:
                    progress(t)
                if run.failure or (run.switches and storm(recent)):  # (a storm: the phase's last part kept)
                    last = run.switches[-1] if run.switches else None
                    status, message = "failed", run.failure or storm_message(recent, last.event, last.pair)
                    break
                if run.event is None:  # t_end, or (t < t_end) where the stepper was stopped
                    if why := _interrupted(stop, t, t_end):
                        status, message = "interrupted", why
                    break
                events += 1
                _tally(recent, run.event, t)
                if storm(recent):
                    status, message = "failed", storm_message(recent, run.event, run.pair)
                    break
                try:
                    phase, y = method.transition(phase, run.event, t, y, run.pair)
                except Stop as ended:
                    status, message = ended.status, ended.message
                    break
                except SolverError as err:
                    status, message = "failed", str(err)
                    break
                if stalled > MAX_STALLED:
                    status, message = "failed", f"events keep recurring without progress at t = {t:.9g} s"
                    break
                if why := _interrupted(stop, t, t_end):  # (after the event's transition)
                    status, message = "interrupted", why
                    break
        except (FloatingPointError, OverflowError, ZeroDivisionError) as exc:
            status, message = "failed", f"floating-point failure at t = {t:.9g} s: {exc}"
        finally:
            if parts:
                stepper.hand_on = None
            stepper.stop = None
    wall = time.perf_counter() - wall0
    return RunResult(segments, status, message, t, wall, steps, nfev, stepper.name, events, phase_steps)


def _tally(recent: deque[float], event: EventKind, t: float) -> None:
    """The latest friction events in a row: one more at ``t``, or none after an event of another kind."""
    if event in _STORM_KINDS:
        recent.append(t)
    else:
        recent.clear()


def _interrupted(stop: Callable[[], str] | None, t: float, t_end: float) -> str:
    """The message of a run that ``stop`` ends at ``t`` before ``t_end``, keeping what was computed; else ""."""
    cause = stop() if stop is not None and t < t_end else ""
    return interrupted_message(t, cause) if cause else ""


def storm(recent: deque[float]) -> bool:
    """Have the latest STORM_EVENTS friction events in a row (their times in ``recent``) come within STORM_SPAN?"""
    return len(recent) == STORM_EVENTS and recent[-1] - recent[0] < STORM_SPAN


def storm_message(recent: deque[float], event: EventKind, pair: int) -> str:
    """The failure message of a storm of friction events (:func:`storm`)."""
    return (
        f"events keep recurring without progress at t = {recent[-1]:.9g} s: {len(recent)} friction switches within "
        f"{recent[-1] - recent[0]:.2g} s, the last a {event.name.lower()} of pair {pair}"
    )


def _hand_on(sink: Callable[[Segment], None], phase: Phase, progress: Callable[[float], None] | None):
    """A stepper's ``hand_on`` for one phase: its finished part (t0, y0, t1, y1, dense; ``opens`` for the phase's
    first) to the sink as a segment that does not close the phase; the progress moves on to its end."""

    def hand_on(t0: float, y0: np.ndarray, t1: float, y1: np.ndarray, dense: DenseOutput, opens: bool) -> None:
        sink(Segment(phase, t0, t1, y0, y1, dense, opens=opens, closes=False))
        if progress is not None:
            progress(t1)

    return hand_on
