"""Wiring: case -> system -> initial state -> impact method -> integrator -> Solution."""

from __future__ import annotations

import math
import os
import platform
from collections.abc import Callable
from pathlib import Path

import numpy as np

from .contact.setup import OBSTACLE_PLANE
from .errors import ModelError, ParameterError
from .integrate.loop import PhaseMethod, RunResult, Segment, Stop, run_phases
from .integrate.modal import ModalStepper
from .memory import check as check_memory
from .methods.base import ImpactMethod
from .methods.ccfm import CCFM
from .model.clearance import penetrations
from .model.joints import JOINTS
from .model.system import BeamSystem
from .parameters.case import Case
from .parameters.io import dump_case
from .registry import IMPACT_METHODS, METHOD_NAMES, check_method, impact_method
from .results.arrays import RunSource
from .results.solution import Solution
from .version import __version__


def initial_state(system: BeamSystem, case: Case) -> tuple[np.ndarray, dict[str, float]]:
    """Initial state vector for ``case.initial`` and a dict of derived values, as the case's joint defines them
    (:meth:`flexbeam.model.joints.Joint.initial_state`; the revolute joint: ``impact``, ``state``, ``release``
    from rest, its angle solved for by shooting on the free flight when not given), checked by
    :func:`check_start`."""
    y, info = system.joint.initial_state(system, case, lambda y0: first_impact_velocity(system, case, y0))
    check_start(system, case, y)
    return y, info


#: a contact point, or any point of the beam, may start this far inside an obstacle [m]: the round-off of the
#: placement and of the body's geometry (~1e-16 of the beam's reach, 1e-15 m here) with a wide margin
START_INSIDE = 1e-9


def check_start(system: BeamSystem, case: Case, y: np.ndarray) -> None:
    """Refuse a start state ``y`` at t = 0 in which the beam reaches into an obstacle.

    Each contact pair's gap (its point's, or for ``contact.anywhere`` the capsule's of ``kernels/src/nearest.c``)
    must be >= -:data:`START_INSIDE`, and so must every obstacle's clearance from the whole body of the beam -- its
    deformed centre line thickened by the surface offset, with flat end faces
    (:func:`flexbeam.model.clearance.penetrations`).  A contact that starts exactly closed (gap 0, as the
    ``impact`` initial kind places it) passes.

    Raises
    ------
    ParameterError
        Naming the obstacle's ``centre`` field, the depth and where along the beam.
    """
    for k, pair in enumerate(system.contact.pairs):  # no pair may start inside its obstacle
        delta = system.gap(0.0, y, k)[0]
        if delta < -START_INSIDE:
            raise ParameterError(
                f"{_obstacle_field(pair.obstacle)}.centre: the beam starts {-delta:.3g} m inside this obstacle (its "
                f"contact point at x = {pair.position:g} m); move the obstacle or the initial state"
            )
    theta, _, q, _ = system.split(0.0, y)
    origin = system.joint.origin(0.0, y, system.n)
    at = None if origin is None else tuple(origin[0])
    obstacles = system.contact.seen_from(case.base.motion(0.0)[0])  # a ground obstacle where the base sees it
    for p in penetrations(system.beam, case.beam.surface_offset, theta, q, obstacles, at):
        if p.depth > START_INSIDE:
            raise ParameterError(
                f"{_obstacle_field(p.obstacle)}.centre: the beam starts {p.depth:.3g} m inside this obstacle, deepest "
                f"at x = {p.x:.6g} m ({p.surface}); allowed: no overlap (a contact may start closed, to "
                f"{START_INSIDE:g} m); move the obstacle or the initial state"
            )


def _obstacle_field(index: int) -> str:
    return "obstacle" if index == 0 else f"obstacles[{index - 1}]"


class _UntilImpact(CCFM):
    """Free flight that stops at the first impact, reporting P's normal velocity."""

    def transition(self, phase, event, t, y, pair=0):
        raise Stop("impact", repr(self.gap_event(t, y, pair)[1]))


def first_impact_velocity(system: BeamSystem, case: Case, y0: np.ndarray) -> float:
    """P's normal velocity at the first impact of a free flight from ``y0`` (NaN if it does not reach an obstacle
    within 10 s): the shooting function of a start whose impact speed is solved for."""
    stepper = ModalStepper(system, rtol=1e-10, atol=1e-13)
    run = run_phases(_UntilImpact(system, case), stepper, y0, 10.0)
    return float(run.message) if run.status == "impact" else math.nan


def simulate(
    case: Case,
    method: str = "ccfm",
    progress: Callable[[float], None] | None = None,
    outputs: bool = False,
    stream: str | Path | None = None,
    state: np.ndarray | None = None,
    stop: Callable[[], str] | None = None,
) -> Solution:
    """Run ``case`` with an impact method and return the :class:`Solution`.

    ``state``: start from this state vector of the case's model (the last state of an earlier run of the same beam:
    continuation, :mod:`flexbeam.bifurcation`) instead of ``[initial]``; its dissipated energy and work start again
    at zero, and the start checks of ``[initial]`` are the caller's.

    Before it starts, the memory the run will hold is estimated (:func:`flexbeam.memory.estimate`; with
    ``outputs``, its output samples included, for a caller that will write or plot them) and a run above
    ``solver.memory_limit`` is refused with a :class:`~flexbeam.errors.ParameterError`.

    With ``stream`` (a path) the run writes its result file as it goes (:mod:`flexbeam.results.stream`): the output
    samples go to the file in chunks, each finished stretch of dense output is dropped once its samples are written
    and its contact records completed, and the memory held does not grow with ``solver.t_end``.  The Solution keeps
    the contact records and the metrics; its arrays are read from the file when asked for.  Not for the
    finite-element reference (``method = "fem"``).

    ``stop``: asked as the run goes (between blocks of steps) for a cause to end it where it is -- "Ctrl-C" from
    :func:`flexbeam.interrupt.ctrl_c_flag`, "" to go on: the Solution then has ``status = "interrupted"`` and all
    that was computed, streamed or not (``flexbeam run --keep-interrupted``).
    """
    check_method(method)  # an unknown method is named before anything else
    if stream is not None and (not isinstance(stream, (str, os.PathLike)) or not str(stream).strip()):
        raise ParameterError(f"stream: the path of the result file to write (got {stream!r})")
    if stream is not None and method == "fem":
        raise ParameterError(
            "--stream: the finite-element reference (method 'fem') keeps its outputs in memory; run it without "
            "streaming, or stream a modal method (ccfm, ccm, imm)"
        )
    check_joint_method(case, method)
    check_friction_method(case, method)
    check_memory(case, method, outputs, stream=stream is not None)
    if method == "fem":
        if case.obstacle.support.compliant:
            raise ParameterError(
                "obstacle.support: the finite-element reference (method 'fem') takes a rigidly "
                "fixed obstacle only; omit obstacle.support.stiffness"
            )
        initial_state(BeamSystem.from_case(case), case)  # the same start checks as the modal model's
        from .fem import simulate_fem

        return simulate_fem(case, progress=progress, stop=stop)
    cls = impact_method(method)
    system = BeamSystem.from_case(case)
    if state is None:
        y0, info = initial_state(system, case)
    else:
        y0, info = _continued(system, state), {}
    impact = cls(system, case)
    stepper = make_stepper(case, method, system)
    impact.locates_friction = isinstance(stepper, ModalStepper)
    if isinstance(stepper, ModalStepper):
        stepper.switching = impact
    if stream is not None:
        return _streamed(Path(stream), impact, stepper, y0, system, case, info, progress, stop)
    run = run_phases(impact, stepper, y0, case.solver.t_end, progress, stop=stop)
    if run.status == "failed":
        run.message += lying_flat_advice(system, run.t_final, run.segments[-1] if run.segments else None)
    return collect(run, impact, system, case, info, stepper)


#: a free beam's mean axis within this angle [rad] of a half-plane's surface lies flat on it (lying_flat_advice)
FLAT_ANGLE = 0.01


def lying_flat_advice(system: BeamSystem, t_final: float, last: Segment | None) -> str:
    """What a failed run's message adds when a free beam ended (at ``t_final``, in segment ``last``) lying along a
    half-plane that a pair anywhere alone touches: that pair holds one point per surface, which jumps between the
    beam's ends (docs/free-beam.md, *A bar that comes to rest on a floor*); else "".  Held in memory or streamed
    alike (a streamed run's message lacked it)."""
    if system.case.joint.kind != "free" or last is None:
        return ""
    theta = system.joint.frame(t_final, last.y1, system.n)[0]
    axis = np.array([np.cos(theta), np.sin(theta)])
    obstacles = system.contact.obstacles
    for pair in system.contact.pairs:  # (a pair anywhere is its surface's only one: setup.check_overlaps)
        ob = obstacles[pair.obstacle]
        if pair.anywhere and ob.kind == OBSTACLE_PLANE and abs(float(axis @ ob.normal)) < FLAT_ANGLE:
            return (
                f"; the beam lies flat on {pair.label}, whose one pair anywhere holds one point, jumping between the "
                f"ends: repeat {pair.label} in [[obstacles]] with a fixed contact point at each end (docs: a bar that "
                "comes to rest on a floor)"
            )
    return ""


def _continued(system: BeamSystem, state: np.ndarray) -> np.ndarray:
    """A copy of ``state`` to start from, its bookkeeping (E_d, W) at zero; a ParameterError if it is not a state of
    ``system``'s size or not finite."""
    y = np.array(state, dtype=float).ravel()
    if y.size != system.size or not np.all(np.isfinite(y)):
        raise ParameterError(f"state: a finite state of {system.size} values, not {y.size}")
    y[-2:] = 0.0
    return y


def check_friction_method(case: Case, method: str) -> None:
    """A one-line ModelError naming ``contact.friction`` when a pair has friction and ``method`` does not model it:
    IMM's frictional impacts (:mod:`flexbeam.methods.friction`), CCFM's and CCM's Coulomb friction
    (:mod:`flexbeam.methods.coulomb`, on the exponential integrator) and the FE reference's regularised law
    (:func:`flexbeam.fem.contact_law.friction_law`)."""
    frictional = (
        case.contact.friction > 0.0
        or (case.contact.friction_static or 0.0) > 0.0
        or any((ob.contact.friction or 0.0) > 0.0 or (ob.contact.friction_static or 0.0) > 0.0 for ob in case.obstacles)
    )
    if frictional and method not in ("imm", "ccfm", "ccm", "fem"):
        raise ModelError(
            f"contact.friction: method '{method}' does not model friction yet; use --method ccfm or ccm (Coulomb's "
            "law with stick and slip), --method imm (Stronge's frictional impact), --method fem (the FE reference) "
            "or friction = 0"
        )
    if frictional and method in ("ccfm", "ccm") and case.solver.integrator != "exponential":
        raise ModelError(
            f"contact.friction: {method.upper()}'s friction runs on the exponential integrator only; set "
            f"solver.integrator = 'exponential' (got '{case.solver.integrator}') or friction = 0"
        )


def check_joint_method(case: Case, method: str) -> None:
    """A one-line ModelError naming ``joint.kind`` when the case's joint kind does not support ``method`` yet
    (:attr:`flexbeam.model.joints.Joint.unsupported_methods`)."""
    kind = case.joint.kind
    if method in JOINTS[kind].unsupported_methods:
        allowed = [m for m in METHOD_NAMES if m not in JOINTS[kind].unsupported_methods]
        raise ModelError(
            f"joint.kind: method '{method}' does not model a {kind!r} joint yet; use one of {', '.join(allowed)}"
        )


def _streamed(
    path: Path, impact: ImpactMethod, stepper, y0, system: BeamSystem, case: Case, info, progress, stop=None
) -> Solution:
    """A run streamed to ``path`` (:class:`~flexbeam.results.stream.RunStream`); nothing is left there if it is
    interrupted by an exception (Ctrl-C), and what was computed is if ``stop`` ends it (status "interrupted")."""
    from .results.stream import RunStream

    sink = RunStream(path, system, case, impact.contacts, provenance(stepper.name, impact, system, case, info, stepper))
    try:
        run = run_phases(impact, stepper, y0, case.solver.t_end, progress, sink=sink, stop=stop)
        if run.status == "failed":  # (the sink holds the last segment: a streamed run keeps none)
            run.message += lying_flat_advice(system, run.t_final, sink.window[-1][1] if sink.window else None)
        return sink.finish(run, {"steps": run.steps, "nfev": run.nfev, "wall_time": run.wall_time})
    except BaseException:
        sink.abort()
        raise


def make_stepper(case: Case, method: str, system: BeamSystem):
    """The integrator of a run: the compiled modal one (``solver.integrator = "exponential"``), else scipy's DOP853.

    The compiled one serves every impact method on a rigid obstacle and on a compliant support (its s as one more
    exactly propagated mode; a held pair's multiplier against it held to its effect on the state as well,
    ``kernels/src/collocation.c``), theta free or prescribed.  (Until 2026-11-27 CCM's and IMM's held phases against a
    compliant support took DOP853, and so did a compliant support with theta(t) prescribed: the prescribed joint's
    reaction, booked as the drive's work, took the contact's Jacobian at the support's rest position; both agree with
    the reference integrator now, ``tests/validation/test_modal_integrator.py``.)  The Solution's provenance names
    the integrator that ran; ``method`` and ``system``: kept for the callers, neither decides today.
    """
    s = case.solver
    if s.integrator == "exponential":
        return ModalStepper(system, s.fast_rtol, s.fast_atol, s.max_step)
    from .integrate.reference import ReferenceStepper

    return ReferenceStepper(system, s.rtol, s.atol, s.max_step)


def collect(
    run: RunResult, method: ImpactMethod, system: BeamSystem, case: Case, info: dict[str, float], stepper=None
) -> Solution:
    """The Solution of a run: the contact log is completed and the outputs evaluated on demand, from the dense
    output (:class:`~flexbeam.results.arrays.RunSource`)."""
    return Solution(
        contacts=method.contacts,
        status=run.status,
        message=run.message,
        stats={"steps": run.steps, "nfev": run.nfev, "wall_time": run.wall_time},
        provenance=provenance(run.integrator, method, system, case, info, stepper),
        measuring_points=np.asarray(case.output.measuring_points, float),
        source=RunSource(run, system),
    )


def provenance(
    integrator: str, method: ImpactMethod, system: BeamSystem, case: Case, info: dict[str, float], stepper=None
) -> dict:
    """Version, case (its TOML text when first read), method, integrator, tolerances, contact law and pairs, and the
    derived start values ``info``."""
    exponential = isinstance(stepper, ModalStepper)
    return {
        "flexbeam_version": __version__,
        "python": platform.python_version(),
        "case_name": case.name,
        "case_toml": lambda: dump_case(case),
        "method": method.name,
        "integrator": integrator,
        "frame": system.beam.frame,
        "beam_length": case.beam.length,
        "rtol": case.solver.fast_rtol if exponential else case.solver.rtol,
        "atol": case.solver.fast_atol if exponential else case.solver.atol,
        "contact_law": system.law.name,
        "contact_stiffness": system.law.stiffness,
        "contact_exponent": system.law.exponent,
        "compliant_support": int(system.compliant),
        "contact_pairs": [p.label for p in system.contact.pairs],
        **case.base.drive,
        **info,
    }


__all__ = [
    "IMPACT_METHODS",
    "METHOD_NAMES",
    "PhaseMethod",
    "check_start",
    "first_impact_velocity",
    "initial_state",
    "simulate",
]
