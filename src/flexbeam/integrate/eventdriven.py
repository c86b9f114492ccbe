"""Event-driven integration over phases (free flight, contact, constrained contact).

The reference integrator steps scipy's :class:`scipy.integrate.DOP853` (8th-order
Dormand-Prince with 7th-order dense output) one step at a time, in the spirit of
``solve_ivp`` but with control over each step:

* after every step each event function of the current phase is evaluated on the
  step's dense output at ``CHECK_POINTS`` interior points; a sign change in the
  watched direction is located by :func:`scipy.optimize.brentq`;
* events that also supply their time derivative (the gap: delta and delta') are
  additionally checked for a dip between two check points by the cubic Hermite
  interpolant through (value, rate) at both ends; a predicted dip is searched by
  subdivision, so that a grazing impact inside one step is not lost;
* a phase may bound the next step from the state (the free phase does: P may
  travel at most a quarter of the obstacle's size, or half the gap, per step), so
  that P cannot pass through an obstacle between two check points;
* at an event the phase's method decides the next phase and may apply a velocity
  jump (impulse); the solver is restarted there, so every phase and every jump
  starts a new dense-output segment.

A numerical failure of the solver ends the run with ``status = "failed"`` and a
message giving the time and the cause; what was computed is kept.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from ..errors import SolverError

CHECK_POINTS = 4
MAX_STALLED = 100  # consecutive zero-length phases before the run is declared stalled
_HERMITE_DEPTH = 3


@dataclass
class Event:
    """A scalar event function of a phase.

    ``fun(t, y)`` returns ``(value, rate)``; ``rate`` may be NaN when unknown.
    ``direction``: -1 for a crossing from positive to negative, +1 for negative to
    positive, 0 for both.
    """

    name: str
    fun: Callable[[float, np.ndarray], tuple[float, float]]
    direction: int = 0


@dataclass
class Phase:
    """One phase of motion: its right-hand side, its events and its sampling step."""

    name: str
    fun: Callable[[float, np.ndarray], np.ndarray]
    events: list[Event]
    sample_step: float
    data: dict[str, Any] = field(default_factory=dict)
    keep_dense: bool = False
    max_step: float = math.inf
    #: optional ``(t, y) -> largest safe next step``, re-evaluated after every step
    step_limit: Callable[[float, np.ndarray], float] | None = None


class Stop(Exception):
    """Raised by a method's transition to end the run cleanly with a status."""

    def __init__(self, status: str, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


class PhaseMethod(Protocol):
    """What an impact method gives the integrator."""

    def start(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        """Initial phase (and possibly a jumped state) at the start."""
        ...

    def free_phase(self) -> Phase:
        """The phase of unconstrained motion."""
        ...

    def transition(self, phase: Phase, event: Event, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        """Next phase and state after ``event`` of ``phase`` at (t, y); may raise Stop."""
        ...


@dataclass
class Segment:
    """One phase interval of the run with its samples and (optionally) dense output."""

    phase: Phase
    t0: float
    t1: float
    times: list[np.ndarray] = field(default_factory=list)
    states: list[np.ndarray] = field(default_factory=list)
    dense_ts: list[float] = field(default_factory=list)
    dense: list[Any] = field(default_factory=list)

    def interpolant(self) -> PiecewiseDense | None:
        if not self.dense:
            return None
        return PiecewiseDense(np.array(self.dense_ts), self.dense)


class PiecewiseDense:
    """y(t) on [ts[0], ts[-1]] from one dense output per step (what scipy's OdeSolution does
    for a scalar t, without importing scipy.integrate on the fast path's start-up)."""

    def __init__(self, ts: np.ndarray, pieces: list[Any]) -> None:
        self.ts, self.pieces = ts, pieces

    def __call__(self, t: float) -> np.ndarray:
        i = int(np.searchsorted(self.ts, t, side="left")) - 1
        return self.pieces[min(max(i, 0), len(self.pieces) - 1)](t)


@dataclass
class RunResult:
    """Raw output of :func:`integrate`: segments, status, statistics."""

    segments: list[Segment]
    status: str
    message: str
    t_final: float
    wall_time: float
    steps: int
    nfev: int
    #: which integrator produced it (recorded in the Solution's provenance)
    integrator: str = "scipy DOP853, event-driven (reference)"


def _sample_grid(ta: float, tb: float, h: float) -> np.ndarray:
    k0 = math.floor(ta / h) + 1
    k1 = math.floor(tb / h)
    if k1 < k0:
        return np.empty(0)
    grid = np.arange(k0, k1 + 1) * h
    return grid[(grid > ta) & (grid < tb)]


def _crosses(ga: float, gb: float, direction: int) -> bool:
    if direction < 0:
        return ga > 0.0 >= gb
    if direction > 0:
        return ga < 0.0 <= gb
    return (ga > 0.0 >= gb) or (ga < 0.0 <= gb)


def _hermite_dip(ta, tb, ga, gb, ra, rb, direction) -> bool:
    """Does the cubic Hermite interpolant cross zero inside (ta, tb) in ``direction``?"""
    if not (math.isfinite(ra) and math.isfinite(rb)):
        return False
    if direction < 0 and not (ga > 0 and gb > 0):
        return False
    if direction > 0 and not (ga < 0 and gb < 0):
        return False
    if direction == 0 and (ga == 0 or gb == 0 or (ga > 0) != (gb > 0)):
        return False
    h = tb - ta
    s = np.linspace(0.0, 1.0, 33)
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    p = h00 * ga + h10 * h * ra + h01 * gb + h11 * h * rb
    return bool(np.min(p) < 0.0) if ga > 0 else bool(np.max(p) > 0.0)


def _find_event(events: list[Event], dense, ta: float, tb: float) -> tuple[float, Event] | None:
    """Earliest event root in (ta, tb] on the dense output, or None."""
    best: tuple[float, Event] | None = None
    ts = np.linspace(ta, tb, CHECK_POINTS + 1)
    for ev in events:
        vals = [ev.fun(t, dense(t)) for t in ts]
        root = _scan(ev, dense, list(ts), vals, 0)
        if root is not None and (best is None or root < best[0]):
            best = (root, ev)
    return best


def _hump(ev: Event, dense, ta: float, tb: float) -> float | None:
    """Root after an excursion that starts at (or just behind) zero.

    A phase that starts exactly on its event surface (the gap right after a
    rebound) has g(ta) = 0 up to round-off, moving the right way (g' > 0 for a
    downward event), and may come back within the same step.  The excursion's
    extremum is located on the dense output and the crossing bracketed after it.
    """
    from scipy.optimize import brentq, minimize_scalar

    s = float(ev.direction) if ev.direction else 1.0
    g = lambda t: ev.fun(t, dense(t))[0]  # noqa: E731
    res = minimize_scalar(lambda t: s * g(t), bounds=(ta, tb), method="bounded",
                          options={"xatol": 1e-14 * max(1.0, abs(tb))})
    t_ext = float(res.x)
    if -s * g(t_ext) <= 0.0:
        return None
    return float(brentq(g, t_ext, tb, xtol=1e-15, rtol=1e-13))


def _leaves_surface(ev: Event, dense, ta: float, tb: float) -> float:
    """Event time when g starts on its surface, at rest on it, and ends beyond it.

    A phase that starts on the event surface with zero rate (P left resting on the
    obstacle, e.g. a CCM contact released at lambda = 0 right after the e = 0 jump)
    can cross within an excursion far below round-off.  The first instant on a
    geometric grid from ta where g is beyond the surface by more than 1e-6 |g(tb)|
    and still moving away (brentq-refined when g is seen on the near side before it)
    is reported, so that the method decides there -- the gap then closes at a
    resolvable rate -- and the contact is not skipped.
    """
    from scipy.optimize import brentq

    s = float(ev.direction)
    g = lambda t: ev.fun(t, dense(t))[0]  # noqa: E731
    h = tb - ta
    prev_t, prev_g = ta, g(ta)
    noise = 1e-6 * abs(g(tb))  # round-off of g near the surface, far below its excursion
    for k in range(48, -1, -1):
        t = ta + h * 2.0**-k
        gt, rt = ev.fun(t, dense(t))
        # beyond the surface (not round-off noise around g = 0) and moving further
        if -s * gt < -noise and not (-s * rt >= 0.0):
            if -s * prev_g > 0.0:
                return float(brentq(g, prev_t, t, xtol=1e-15, rtol=1e-13))
            return t
        prev_t, prev_g = t, gt
    return tb


def _scan(ev: Event, dense, ts, vals, depth) -> float | None:
    for i in range(len(ts) - 1):
        (ga, ra), (gb, rb) = vals[i], vals[i + 1]
        if _crosses(ga, gb, ev.direction):
            from scipy.optimize import brentq

            g = lambda t: ev.fun(t, dense(t))[0]  # noqa: E731
            if gb == 0.0:
                return ts[i + 1]
            return float(brentq(g, ts[i], ts[i + 1], xtol=1e-15, rtol=1e-13))
        d = ev.direction
        if d != 0 and math.isfinite(ra) and -d * ga <= 0.0 and -d * gb < 0.0:
            # starts on (or round-off behind) the surface and ends beyond it
            root = _hump(ev, dense, ts[i], ts[i + 1]) if -d * ra > 0.0 else None
            return root if root is not None else _leaves_surface(ev, dense, ts[i], ts[i + 1])
        if depth < _HERMITE_DEPTH and _hermite_dip(ts[i], ts[i + 1], ga, gb, ra, rb, ev.direction):
            sub = list(np.linspace(ts[i], ts[i + 1], 9))
            sub_vals = [vals[i]] + [ev.fun(t, dense(t)) for t in sub[1:-1]] + [vals[i + 1]]
            root = _scan(ev, dense, sub, sub_vals, depth + 1)
            if root is not None:
                return root
    return None


def start_run(method: PhaseMethod, y0: np.ndarray, segments: list[Segment]) -> tuple[Phase, np.ndarray] | RunResult:
    """Initial phase at t = 0; a jump at the start keeps the state before it as a sample.

    Returns a finished RunResult when the method stops the run at once.
    """
    y0 = np.asarray(y0, float)
    try:
        phase, y = method.start(0.0, y0)
    except Stop as stop:
        return RunResult([], stop.status, stop.message, 0.0, 0.0, 0, 0)
    if not np.array_equal(y, y0):
        segments.append(Segment(method.free_phase(), 0.0, 0.0, [np.array([0.0])], [y0[None, :].copy()]))
    return phase, y


def integrate(
    method: PhaseMethod,
    y0: np.ndarray,
    t_end: float,
    rtol: float,
    atol: float,
    max_step: float | None = None,
    progress: Callable[[float], None] | None = None,
) -> RunResult:
    """Integrate from t = 0 to ``t_end`` switching phases at events.

    Parameters
    ----------
    method
        The impact method: initial phase, transitions at events.
    y0
        Initial state.
    t_end
        Final time [s].
    rtol, atol
        DOP853 tolerances.
    max_step
        Upper bound on the step [s] (None: only the phase's own bound).
    progress
        Called with the current time after each step (for progress bars).
    """
    from scipy.integrate import DOP853  # imported here: the fast path does not need scipy

    t = 0.0
    segments: list[Segment] = []
    steps = nfev = 0
    status, message = "success", "integration reached t_end"
    wall0 = time.perf_counter()
    started = start_run(method, y0, segments)
    if isinstance(started, RunResult):
        return started
    phase, y = started
    stalled = 0
    while t < t_end:
        seg = Segment(phase, t, t)
        segments.append(seg)
        seg.times.append(np.array([t]))
        seg.states.append(y[None, :].copy())
        step_cap = min(max_step or math.inf, phase.max_step, t_end - t)
        solver = DOP853(phase.fun, t, y, t_end, rtol=rtol, atol=atol, max_step=step_cap)
        if phase.step_limit is not None:
            solver.max_step = min(step_cap, phase.step_limit(t, y))
        switched = False
        while solver.status == "running":
            ta = solver.t
            try:
                msg = solver.step()
            except (np.linalg.LinAlgError, FloatingPointError, ZeroDivisionError, ValueError) as exc:
                status, message = "failed", f"step failed at t = {ta:.9g} s: {type(exc).__name__}: {exc}"
                break
            steps += 1
            if solver.status == "failed":
                status, message = "failed", f"step failed at t = {solver.t:.9g} s: {msg}"
                break
            tb = solver.t
            dense = solver.dense_output()
            hit = _find_event(phase.events, dense, ta, tb)
            t_stop = hit[0] if hit else tb
            grid = _sample_grid(ta, t_stop, phase.sample_step)
            if grid.size:
                seg.times.append(grid)
                seg.states.append(dense(grid).T)
            if phase.keep_dense:
                if not seg.dense_ts:
                    seg.dense_ts.append(ta)
                seg.dense_ts.append(tb)
                seg.dense.append(dense)
            y_stop = dense(t_stop) if hit else solver.y.copy()
            if not np.all(np.isfinite(y_stop)):
                status, message = "failed", f"non-finite state at t = {t_stop:.9g} s"
                break
            seg.times.append(np.array([t_stop]))
            seg.states.append(y_stop[None, :].copy())
            seg.t1 = t_stop
            t, y = t_stop, y_stop
            if phase.step_limit is not None:
                solver.max_step = min(step_cap, phase.step_limit(t, y))
            if progress is not None:
                progress(t)
            if hit:
                try:
                    phase, y = method.transition(phase, hit[1], t, y)
                except Stop as stop:
                    status, message = stop.status, stop.message
                    t_end = t
                except SolverError as err:
                    status, message = "failed", str(err)
                    t_end = t
                switched = True
                break
        nfev += solver.nfev
        if status == "failed":
            break
        if not switched and solver.status == "finished":
            t = solver.t
            break
        stalled = stalled + 1 if seg.t1 == seg.t0 else 0
        if stalled > MAX_STALLED:
            status = "failed"
            message = f"events keep recurring without progress at t = {t:.9g} s (phase '{phase.name}')"
            break
    wall = time.perf_counter() - wall0
    return RunResult(segments, status, message, t, wall, steps, nfev)
