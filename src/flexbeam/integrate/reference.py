"""The reference integrator: scipy's DOP853 on the equations in physical coordinates, one phase at a time.

It steps :class:`scipy.integrate.DOP853` (8th-order Dormand-Prince with 7th-order dense output) one step at a
time, in the spirit of ``solve_ivp`` but with control over each step:

* after every step each event function of the current phase is evaluated on the
  step's dense output at ``CHECK_POINTS`` interior points; a sign change in the
  watched direction is located by :func:`scipy.optimize.brentq`;
* events that also supply their time derivative (the gap: delta and delta') are
  additionally checked for a dip between two check points by the cubic Hermite
  interpolant through (value, rate) at both ends; a predicted dip is searched by
  subdivision, so that a grazing impact inside one step is not lost;
* in free flight the next step is bounded from the state: P may travel at most a
  quarter of the obstacle's size, or half the gap, per step, so that P cannot pass
  through an obstacle between two check points;
* a phase that cannot make progress (its steps collapsing, e.g. on a right-hand side
  that switches at every step) ends as a failure once its steps exceed
  ``EFFORT_BASE + EFFORT_RATE r (t - t0)``, r the phase's characteristic rate
  (:meth:`ReferenceStepper.rate`).

The phase loop (:mod:`flexbeam.integrate.loop`) restarts it at every event.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..model.system import BeamSystem
from .loop import PhaseRun
from .modal_basis import OMEGA_RIGID_DEFAULT, ModalBasis
from .phases import ContactMode, EventKind, Phase

CHECK_POINTS = 4
#: exceptions of a step that end a phase as a numerical failure
#: the explicit reference integrator refuses a beam whose structural damping makes its fastest root this many times
#: its fastest undamped frequency: its steps (~ 1 / that root) would multiply as much (a fuzzed Kelvin-Voigt
#: c = 6.4 s gave 7e5, a run of hours; the damped tests stay below the limit)
DAMPING_STIFFNESS_LIMIT = 1e3


def check_damping_stiffness(system: BeamSystem, omega: float, rate: float) -> None:
    """A one-line ParameterError naming the beam's damping when it would make the explicit reference integrator
    (compliant supports, ``solver.integrator = "reference"``) take :data:`DAMPING_STIFFNESS_LIMIT` times the steps
    of the undamped beam; the exponential integrator propagates any damping exactly."""
    if rate <= DAMPING_STIFFNESS_LIMIT * max(omega, OMEGA_RIGID_DEFAULT):
        return
    beam = system.case.beam
    field = "beam.kelvin_voigt" if beam.kelvin_voigt > 0.0 else "beam.viscous_damping"
    raise ParameterError(
        f"{field}: damping this strong (its fastest mode decays at {rate:.3g} 1/s, {rate / omega:.3g} times the "
        f"fastest frequency) is beyond the explicit reference integrator (used here); reduce it below "
        f"{DAMPING_STIFFNESS_LIMIT:g} times"
    )


_FAILURES = (np.linalg.LinAlgError, FloatingPointError, ZeroDivisionError, ValueError, OverflowError)
_HERMITE_DEPTH = 3
#: Bounded effort: a phase may take EFFORT_BASE + EFFORT_RATE r (t - t0) steps.  An explicit method needs about one
#: step per 1 / omega_max (its stability bound); measured over the test suite (fast and slow) and the presets: at
#: most 7547 steps in a phase and 5.6 per unit of r (t - t0); the bound is >= 18 times every phase's use.
EFFORT_BASE = 2000
EFFORT_RATE = 100.0


@dataclass
class Event:
    """A scalar event function of a phase: ``fun(t, y)`` returns ``(value, rate)`` (rate NaN when unknown);
    ``direction`` -1 for a crossing from positive to negative, +1 for negative to positive."""

    kind: EventKind
    fun: Callable[[float, np.ndarray], tuple[float, float]]
    direction: int = 0
    pair: int = 0


class PiecewiseDense:
    """y(t) on [ts[0], ts[-1]] from one scipy dense output per step; called on an array of times, rows."""

    def __init__(self, ts: list[float], pieces: list[Any]) -> None:
        self.breaks, self.pieces = np.asarray(ts, float), pieces

    def __call__(self, times: np.ndarray) -> np.ndarray:
        """The rows y(t) at ``times``: each step's piece called once on its times, in their order (the times grouped
        by a stable sort on their step, so that a call costs its times and the steps they touch)."""
        times = np.atleast_1d(np.asarray(times, float))
        idx = np.clip(np.searchsorted(self.breaks, times, side="left") - 1, 0, len(self.pieces) - 1)
        out = np.empty((times.size, self.pieces[0](self.breaks[0]).size))
        if not times.size:
            return out
        order = np.argsort(idx, kind="stable")
        for group in np.split(order, np.flatnonzero(np.diff(idx[order])) + 1):
            out[group] = self.pieces[idx[group[0]]](times[group]).T
        return out


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
    res = minimize_scalar(
        lambda t: s * g(t), bounds=(ta, tb), method="bounded", options={"xatol": 1e-14 * max(1.0, abs(tb))}
    )
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


class ReferenceStepper:
    """Advances phases of one system with scipy's DOP853 (rtol, atol) on :meth:`BeamSystem.rhs_function`."""

    name = "scipy DOP853, event-driven (reference)"

    def __init__(
        self, system: BeamSystem, rtol: float = 1e-9, atol: float = 1e-12, max_step: float | None = None
    ) -> None:
        self.system = system
        self.rtol, self.atol = rtol, atol
        self.max_step = max_step or math.inf
        #: asked after each step for a cause to end the phase there, by a run that may be stopped (run_phases)
        self.stop = None
        basis = ModalBasis.of(system)
        # the largest root modulus of the linearised modes: w, or up to the damping coefficient 2 zeta w when overdamped
        rates = basis.omega if basis.damp is None else np.maximum(basis.omega, basis.damp)
        self.omega_max = float(np.max(rates, initial=0.0))
        check_damping_stiffness(system, float(np.max(basis.omega, initial=0.0)), self.omega_max)

    def rate(self, phase: Phase) -> float:
        """The phase's characteristic rate [1/s]: the linearised system's highest frequency, or a strongly damped mode's
        damping coefficient (what limits an explicit method's step; ``OMEGA_RIGID_DEFAULT`` for a rigid beam), or the
        phase's step bound if tighter."""
        return max(self.omega_max, OMEGA_RIGID_DEFAULT, 1.0 / min(self.max_step, phase.max_step))

    def _events(self, phase: Phase) -> list[Event]:
        """Per pair the event its mode can end on: a free pair's impact, a pair under its law separating, a held
        pair's release."""
        sysm = self.system
        out = []
        for k, mode in enumerate(phase.modes):

            def gap(t: float, y: np.ndarray, k=k) -> tuple[float, float]:
                delta, rate, _, _ = sysm.gap(t, y, k)
                return delta, rate

            def multiplier(t: float, y: np.ndarray, k=k) -> tuple[float, float]:
                return float(sysm.rhs(t, y, phase.buffer)[1][k]), float("nan")

            if mode == ContactMode.NONE and EventKind.IMPACT in phase.events:
                out.append(Event(EventKind.IMPACT, gap, -1, k))
            elif mode == ContactMode.FORCE and EventKind.SEPARATION in phase.events:
                out.append(Event(EventKind.SEPARATION, gap, +1, k))
            elif mode == ContactMode.CONSTRAINT and EventKind.RELEASE in phase.events:
                out.append(Event(EventKind.RELEASE, multiplier, -1, k))
        return out

    def safe_step(self, t: float, y: np.ndarray, phase: Phase) -> float:
        """Largest free-flight step that cannot carry a free pair's point through its obstacle.

        A point moves at most |v_P| h (to first order) in a step h; allowing a quarter of the obstacle's size
        (sphere radius; 1 mm for a point) or half the current gap keeps at least one event check point inside the
        obstacle, and the Hermite check on (delta, delta') catches a shallower dip.  A half-plane cannot be
        passed through.  An obstacle fixed to the ground on a moving base adds the base's speed |v_O|.
        """
        sysm = self.system
        out = math.inf
        for k, mode in enumerate(phase.modes):
            ob = sysm.contact.obstacles[sysm.contact.pairs[k].obstacle]
            if mode != ContactMode.NONE or ob.kind != 0:
                continue
            _, v, _, _ = sysm.point_state(t, y, sysm.pair_point(k))
            speed = math.hypot(v[0], v[1]) + (math.hypot(*sysm.case.base.motion(t)[1]) if ob.ground else 0.0)
            if speed > 0.0:
                out = min(out, max(0.25 * (ob.radius or 1e-3), 0.5 * sysm.gap(t, y, k)[0]) / speed)
        return out

    def advance(self, phase: Phase, t: float, y: np.ndarray, t_end: float) -> PhaseRun:
        # an overflow or invalid operation (a case scaled beyond double precision) ends the phase as a failure with
        # its time, as a non-finite state does on the compiled path, instead of a RuntimeWarning and NaN states
        with np.errstate(over="raise", invalid="raise", divide="raise"):
            try:
                return self._advance(phase, t, y, t_end)
            except _FAILURES as exc:
                return PhaseRun(float(t), np.asarray(y, float).copy(), None, None, 0, 0,
                                f"step failed at t = {t:.9g} s: {type(exc).__name__}: {exc}")  # fmt: skip

    def _advance(self, phase: Phase, t: float, y: np.ndarray, t_end: float) -> PhaseRun:
        from scipy.integrate import DOP853  # imported here: the compiled path does not need scipy

        fun = self.system.rhs_function(phase.buffer)
        events = self._events(phase)
        limit = (lambda t, y: self.safe_step(t, y, phase)) if ContactMode.NONE in phase.modes else None
        cap = min(self.max_step, phase.max_step, t_end - t)

        def start(first_step: float | None = None) -> DOP853:
            out = DOP853(fun, t, y, t_end, rtol=self.rtol, atol=self.atol, max_step=cap, first_step=first_step)
            if limit is not None:
                out.max_step = min(cap, limit(t, y))
            return out

        solver, retried = start(), False
        ts: list[float] = [t]
        pieces: list[Any] = []
        steps = 0
        t0, rate = t, self.rate(phase)
        while solver.status == "running":
            ta = solver.t
            try:
                msg = solver.step()
            except _FAILURES as exc:
                if steps == 0 and not retried and rate > 1.0 / cap:
                    # scipy's first-step guess (two rhs evaluations) can lie far beyond the explicit method's
                    # stability bound ~1 / rate when the phase starts at rest in its fast modes, and diverge: retry
                    # once from a first step at that bound
                    solver, retried = start(first_step=1.0 / rate), True
                    continue
                return self._result(
                    ta,
                    y,
                    None,
                    ts,
                    pieces,
                    steps,
                    solver,
                    f"step failed at t = {ta:.9g} s: {type(exc).__name__}: {exc}",
                )
            steps += 1
            if solver.status == "failed":
                return self._result(
                    ta, y, None, ts, pieces, steps, solver, f"step failed at t = {solver.t:.9g} s: {msg}"
                )
            tb = solver.t
            dense = solver.dense_output()
            hit = _find_event(events, dense, ta, tb)
            t_stop = hit[0] if hit else tb
            ts.append(tb)
            pieces.append(dense)
            y = dense(t_stop) if hit else solver.y.copy()
            if not np.all(np.isfinite(y)):
                return self._result(
                    t_stop, y, None, ts, pieces, steps, solver, f"non-finite state at t = {t_stop:.9g} s"
                )
            if hit:
                return self._result(t_stop, y, hit[1].kind, ts, pieces, steps, solver, pair=hit[1].pair)
            if self.stop is not None and self.stop():  # (the run's loop says why: run_phases)
                return self._result(tb, y, None, ts, pieces, steps, solver)
            if limit is not None:
                solver.max_step = min(cap, limit(tb, y))
            if steps >= EFFORT_BASE + EFFORT_RATE * rate * (tb - t0) and solver.status == "running":
                failure = (
                    f"no progress at t = {tb:.9g} s ({phase.name} phase): {steps} steps advanced the phase "
                    f"{tb - t0:.3g} s from t = {t0:.9g} s, the step size now {solver.step_size:.3g} s "
                    f"({solver.nfev} evaluations of the right-hand side)"
                )
                return self._result(tb, y, None, ts, pieces, steps, solver, failure)
        return self._result(solver.t, y, None, ts, pieces, steps, solver)

    @staticmethod
    def _result(t1, y1, event, ts, pieces, steps, solver, failure: str = "", pair: int = 0) -> PhaseRun:
        dense = PiecewiseDense(ts, pieces) if pieces else None
        return PhaseRun(float(t1), np.asarray(y1, float).copy(), event, dense, steps, solver.nfev, failure, pair)
