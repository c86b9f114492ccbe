"""Wiring: case -> system -> initial state -> impact method -> integrator -> Solution."""

from __future__ import annotations

import math
import platform
from collections.abc import Callable

import numpy as np

from . import numerics as nm
from .errors import ParameterError
from .integrate.loop import PhaseMethod, RunResult, Stop, run_phases
from .integrate.modal import ModalStepper
from .memory import check as check_memory
from .methods.base import ImpactMethod
from .methods.ccfm import CCFM
from .model.clearance import penetrations
from .model.system import BeamSystem
from .parameters.case import Case
from .parameters.io import dump_case
from .registry import IMPACT_METHODS, METHOD_NAMES, check_method, impact_method
from .results.arrays import RunSource
from .results.solution import Solution
from .version import __version__


def initial_state(system: BeamSystem, case: Case) -> tuple[np.ndarray, dict[str, float]]:
    """Initial state vector for ``case.initial`` and a dict of derived values.

    * ``impact``: frame angle = impact angle, beam straight (q = 0: the hub angle is the frame angle) and at
      rest in the floating frame, theta' chosen so that P's normal velocity delta' = J_theta theta' equals the
      impact velocity.
    * ``state``: theta, theta' as given, beam straight.
    * ``release``: at rest in the static equilibrium of the beam under gravity with the hub held at the release
      angle (:func:`release_state`); the release angle, when not given, is solved for (shooting with
      :func:`scipy.optimize.brentq` on the free flight) so that P reaches the obstacle at the impact velocity.
    """
    y, info = _initial_state(system, case)
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
    for p in penetrations(system.beam, case.beam.surface_offset, theta, q, system.contact.obstacles):
        if p.depth > START_INSIDE:
            raise ParameterError(
                f"{_obstacle_field(p.obstacle)}.centre: the beam starts {p.depth:.3g} m inside this obstacle, deepest "
                f"at x = {p.x:.6g} m ({p.surface}); allowed: no overlap (a contact may start closed, to "
                f"{START_INSIDE:g} m); move the obstacle or the initial state"
            )


def _obstacle_field(index: int) -> str:
    return "obstacle" if index == 0 else f"obstacles[{index - 1}]"


def _initial_state(system: BeamSystem, case: Case) -> tuple[np.ndarray, dict[str, float]]:
    init = case.initial
    if system.prescribed:
        th, thd, _ = system.drive.motion(0.0)
        return system.state(th, thd), {}
    if init.kind == "state":
        return system.state(init.angle, init.rate), {}
    if init.kind == "impact":
        y = system.state(init.impact_angle, 0.0)
        J_theta = system.gap(0.0, y)[3][0]
        y = system.state(init.impact_angle, init.impact_rate(J_theta))
        return y, {"impact_rate": float(y[system.n + 1])}
    angle = init.release_angle
    info: dict[str, float] = {}
    if angle is None:
        angle = solve_release_angle(system, case)
    info["release_angle"] = float(angle)
    return release_state(system, angle), info


def release_state(system: BeamSystem, angle: float) -> np.ndarray:
    """At rest in static equilibrium under gravity with the hub held at the hub angle ``angle``.

    The potential V = 1/2 q^T K q + g [sin(theta)(m1 - 1/2 q^T G q) + cos(theta) s_f q] is stationary under the
    constraint theta + d q = angle (d = 0 in the hub frame):
    [K - g sin(theta) (G - d^T s_f)] q = -g cos(theta) [s_f - (m1 - 1/2 q^T G q) d^T], theta = angle - d q,
    solved by fixed-point iteration on theta and q^T G q (d q is of the order of the static slope).
    """
    b, g = system.beam, system.g
    q = np.zeros(b.n)
    theta = angle
    if b.n:
        for _ in range(50):
            s, c = nm.sin(theta), nm.cos(theta)
            A = b.Kff - g * s * b.G + g * s * np.outer(b.d, b.sf)
            rhs = -g * c * b.sf + g * c * (b.m1 - 0.5 * nm.dot(q, nm.matmul(b.G, q))) * b.d
            q_new = nm.solve(A, rhs)
            theta_new = angle - nm.dot(b.d, q_new)
            done = abs(theta_new - theta) <= 1e-15 * max(1.0, abs(angle)) and np.allclose(
                q_new, q, rtol=1e-14, atol=0.0
            )
            q, theta = q_new, theta_new
            if done:
                break
    return system.state(theta, 0.0, q)


class _UntilImpact(CCFM):
    """Free flight that stops at the first impact, reporting P's normal velocity."""

    def transition(self, phase, event, t, y, pair=0):
        raise Stop("impact", repr(self.gap_event(t, y, pair)[1]))


def _first_impact_velocity(system: BeamSystem, case: Case, angle: float) -> float:
    stepper = ModalStepper(system, rtol=1e-10, atol=1e-13)
    run = run_phases(_UntilImpact(system, case), stepper, release_state(system, angle), 10.0)
    if run.status != "impact":
        raise ParameterError(f"initial.release_angle: released at {angle:.6g} rad the beam does not reach the obstacle")
    return float(run.message)


def solve_release_angle(system: BeamSystem, case: Case) -> float:
    """Release angle from rest that gives P the impact velocity at first contact."""
    init = case.initial
    th_i = init.impact_angle
    y = system.state(th_i, 0.0)
    rate = init.impact_rate(system.gap(0.0, y)[3][0])
    b = system.beam
    if system.g <= 0.0 or b.m1 <= 0.0:
        raise ParameterError("initial.kind: 'release' needs gravity (model.gravity > 0)")
    # rigid estimate: g m1 (sin th_r - sin th_i) = 1/2 J_c rate^2 (falling towards -theta)
    s = nm.sin(th_i) + 0.5 * b.Jc * (rate * rate) / (system.g * b.m1)
    if s >= 1.0:
        raise ParameterError(
            f"initial.impact_velocity: {init.impact_velocity:g} m/s cannot be reached by release "
            "from rest under gravity"
        )
    guess = nm.asin(s)
    target = init.impact_velocity

    def miss(angle: float) -> float:
        return _first_impact_velocity(system, case, angle) - target

    from scipy.optimize import brentq

    lo, hi = th_i + 0.8 * (guess - th_i), min(th_i + 1.25 * (guess - th_i), 0.5 * math.pi)
    try:
        return float(brentq(miss, lo, hi, xtol=1e-12, rtol=1e-10))
    except ValueError:
        raise ParameterError(
            "initial.release_angle: no release angle near the rigid estimate "
            f"{guess:.6g} rad gives the impact velocity; give initial.release_angle"
        ) from None


def simulate(
    case: Case,
    method: str = "ccfm",
    progress: Callable[[float], None] | None = None,
    outputs: bool = False,
) -> Solution:
    """Run ``case`` with an impact method and return the :class:`Solution`.

    Before it starts, the memory the run will hold is estimated (:func:`flexbeam.memory.estimate`; with
    ``outputs``, its output samples included, for a caller that will write or plot them) and a run above
    ``solver.memory_limit`` is refused with a :class:`~flexbeam.errors.ParameterError`.
    """
    check_method(method)  # an unknown method is named before anything else
    check_memory(case, method, outputs)
    if method == "fem":
        if case.obstacle.support.compliant:
            raise ParameterError(
                "obstacle.support: the finite-element reference (method 'fem') takes a rigidly "
                "fixed obstacle only; omit obstacle.support.stiffness"
            )
        initial_state(BeamSystem.from_case(case), case)  # the same start checks as the modal model's
        from .fem import simulate_fem

        return simulate_fem(case, progress=progress)
    cls = impact_method(method)
    system = BeamSystem.from_case(case)
    y0, info = initial_state(system, case)
    impact = cls(system, case)
    stepper = make_stepper(case, method, system)
    run = run_phases(impact, stepper, y0, case.solver.t_end, progress)
    return collect(run, impact, system, case, info, stepper)


def make_stepper(case: Case, method: str, system: BeamSystem):
    """The integrator of a run: the compiled modal one (``solver.integrator = "exponential"``) where it
    applies, else scipy's DOP853 (:func:`uses_exponential`)."""
    s = case.solver
    if uses_exponential(case, method, system):
        return ModalStepper(system, s.fast_rtol, s.fast_atol, s.max_step)
    from .integrate.reference import ReferenceStepper

    return ReferenceStepper(system, s.rtol, s.atol, s.max_step)


def uses_exponential(case: Case, method: str, system: BeamSystem) -> bool:
    """Does ``solver.integrator = "exponential"`` apply to this run?

    Every impact method on a rigid obstacle, and CCFM on a compliant support (its s as one more exactly
    propagated mode).  Constrained phases against a compliant support (CCM, IMM's resting contact) take the
    reference path (the collocated multiplier does work ~5e-6 of the energy over a contact against the stiff
    support, above the energy tests' 1e-6), and so does a compliant support with theta(t) prescribed.  The
    Solution's provenance names the integrator that ran.
    """
    if case.solver.integrator != "exponential":
        return False
    return not system.compliant or (method == "ccfm" and not system.prescribed)


def collect(
    run: RunResult, method: ImpactMethod, system: BeamSystem, case: Case, info: dict[str, float], stepper=None
) -> Solution:
    """The Solution of a run: the contact log is completed and the outputs evaluated on demand, from the dense
    output (:class:`~flexbeam.results.arrays.RunSource`)."""
    exponential = isinstance(stepper, ModalStepper)
    provenance = {
        "flexbeam_version": __version__,
        "python": platform.python_version(),
        "case_name": case.name,
        "case_toml": lambda: dump_case(case),
        "method": method.name,
        "integrator": run.integrator,
        "frame": system.beam.frame,
        "rtol": case.solver.fast_rtol if exponential else case.solver.rtol,
        "atol": case.solver.fast_atol if exponential else case.solver.atol,
        "contact_law": system.law.name,
        "contact_stiffness": system.law.stiffness,
        "contact_exponent": system.law.exponent,
        "compliant_support": int(system.compliant),
        "contact_pairs": [p.label for p in system.contact.pairs],
        **info,
    }
    return Solution(
        contacts=method.contacts,
        status=run.status,
        message=run.message,
        stats={"steps": run.steps, "nfev": run.nfev, "wall_time": run.wall_time},
        provenance=provenance,
        measuring_points=np.asarray(case.output.measuring_points, float),
        source=RunSource(run, system),
    )


__all__ = [
    "IMPACT_METHODS",
    "METHOD_NAMES",
    "PhaseMethod",
    "initial_state",
    "release_state",
    "simulate",
    "solve_release_angle",
]
