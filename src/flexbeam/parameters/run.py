"""How a case runs: its initial state, the solvers' settings, the outputs and the finite-element reference's
options."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import AfterValidator, BeforeValidator, Field, model_validator

from .fields import MAX_RATE, Angle, Bounded, Finite, NonNegative, Positive, Rate, Section, Speed


def _interval_range(value: object) -> object:
    """An output interval that is no number > 0 (zero, negative, NaN, inf, text, a bool) is named with the whole
    range it must lie in (its upper end, ``solver.t_end``, is checked with the case:
    :class:`~flexbeam.parameters.case.Case`)."""
    number = isinstance(value, (int, float)) and not isinstance(value, bool)
    if not number or not 0.0 < value < math.inf:
        raise ValueError("must be in 0 < output.interval <= solver.t_end [s]")
    return value


#: a spacing of the output samples [s]: finite and > 0
Interval = Annotated[float, BeforeValidator(_interval_range), Field(gt=0)]
#: the reference integrator's smallest relative tolerance: 100 machine epsilons, below which scipy's DOP853 raises it
#: to that itself (with a UserWarning, which reached the user's terminal raw)
REFERENCE_RTOL_MIN = 100 * 2.0**-52


def _reference_rtol(value: float) -> float:
    if value < REFERENCE_RTOL_MIN:
        raise ValueError(
            f"must be >= {REFERENCE_RTOL_MIN:.3g} (100 machine epsilons, the reference integrator's finest)"
        )
    return value


class Initial(Section):
    """Initial state.

    * ``impact``: start at the first contact, beam straight (q = q' = 0) at
      theta = ``impact_angle``, with P's normal velocity ``impact_velocity`` (< 0 approaching).
    * ``release``: start from rest, beam straight, at ``release_angle``; if that is
      omitted it is solved for so that P reaches the obstacle at ``impact_velocity``.
    * ``state``: theta = ``angle``, theta' = ``rate``, beam straight and at rest in the
      floating frame (or vibrating: ``modal_displacement``, ``modal_velocity``).

    A free beam (``joint.kind = "free"``) starts with ``state`` -- its centre of mass at ``position`` moving at
    ``velocity``, its frame at ``angle`` turning at ``rate`` -- or ``impact``: at ``impact_angle``, translating
    without spin so that P (the first pair's contact point) touches obstacle 0 with the normal velocity
    ``impact_velocity``.  ``release`` needs a joint to hold the beam.
    """

    kind: Literal["impact", "release", "state"] = "impact"
    impact_velocity: Bounded(-1e3, 1e3) = Field(
        -0.4,
        description="normal velocity of P at first contact [m/s] (negative = approaching; at most 1e3 m/s, "
        "beyond elastic impact)",
    )
    impact_angle: Angle = Field(0.0, description="hub angle at first contact [rad]")
    release_angle: Angle | None = Field(None, description="release hub angle [rad]")
    angle: Angle = Field(0.0, description="initial hub angle theta_0 [rad] (kind = state)")
    rate: Rate = Field(0.0, description="initial hub rate theta'_0 [rad/s] (kind = state)")
    position: tuple[Finite, Finite] = Field(
        (0.0, 0.0), description="initial centre of mass (x_G, y_G) [m] (joint.kind = free, kind = state)"
    )
    velocity: tuple[Speed, Speed] = Field(
        (0.0, 0.0),
        description="initial velocity of the centre of mass [m/s] (joint.kind = free, kind = state; each component "
        "within +-1e4 m/s)",
    )
    modal_displacement: list[Finite] = Field(
        default_factory=list,
        description="initial modal coordinates q_1, q_2, ... [m] (kind = state; the others 0)",
    )
    modal_velocity: list[Finite] = Field(
        default_factory=list,
        description="initial modal velocities q'_1, q'_2, ... [m/s] (kind = state; the others 0)",
    )
    axial_displacement: list[Finite] = Field(
        default_factory=list,
        description="initial axial modal coordinates p_1, p_2, ... [m] (kind = state, model.axial_modes > 0; the "
        "others 0)",
    )
    axial_velocity: list[Finite] = Field(
        default_factory=list,
        description="initial axial modal velocities p'_1, p'_2, ... [m/s] (kind = state, model.axial_modes > 0; "
        "the others 0)",
    )

    def impact_rate(self, J_theta: float, velocity: float | None = None) -> float:
        """The hub rate giving P the normal velocity ``velocity`` (default ``impact_velocity``) when P moves
        ``J_theta`` m per radian along its normal; a one-line ParameterError when that needs more than
        :data:`MAX_RATE` (P at or next to the joint)."""
        from ..errors import ParameterError

        v = self.impact_velocity if velocity is None else velocity
        J_theta = float(J_theta)
        if J_theta == 0.0:  # (P on the joint's axis: the rate needed is unbounded, and the position is the cause)
            raise ParameterError(
                f"contact.position: P does not move along the contact normal as the beam turns (0 m per radian), so "
                f"no hub rate gives initial.impact_velocity = {v:g} m/s; put P away from the joint"
            )
        if not abs(v) <= MAX_RATE * abs(J_theta):
            raise ParameterError(
                f"initial.impact_velocity: P (contact.position) moves {abs(J_theta):.3g} m per radian along the "
                f"contact normal, so {v:g} m/s needs a hub rate above {MAX_RATE:g} rad/s"
            )
        return v / J_theta

    @model_validator(mode="after")
    def _approaching(self) -> Initial:
        if self.kind != "state" and not self.impact_velocity < 0.0:
            raise ValueError("initial.impact_velocity: must be < 0 m/s (P approaching the obstacle)")
        return self


class Solver(Section):
    """Integration settings.

    ``integrator = "exponential"`` (default): exact modal propagation with Gauss
    collocation of the coupling and contact terms, compiled (fast; tolerances
    ``fast_rtol``/``fast_atol``); it serves every impact method on a rigidly held
    obstacle and on a compliant ``obstacle.support``.
    ``"reference"``: scipy's DOP853, event-driven (``rtol``/``atol``).

    A run whose estimated memory (dense output, phases and, when they are written or drawn, output
    samples; :func:`flexbeam.memory.estimate`) exceeds ``memory_limit`` is refused before it starts.
    """

    integrator: Literal["exponential", "reference"] = Field(
        "exponential",
        description="time integrator (exponential: compiled, every method and obstacle; reference: scipy's DOP853)",
    )
    fast_rtol: Annotated[float, Field(gt=0, lt=1)] = Field(
        1e-6, description="relative tolerance of the exponential integrator"
    )
    fast_atol: Annotated[float, Field(gt=0, lt=1)] = Field(
        1e-9, description="absolute tolerance of the exponential integrator"
    )

    t_end: Positive = Field(0.1, description="simulated time [s]")
    rtol: Annotated[float, Field(gt=0, lt=1), AfterValidator(_reference_rtol)] = Field(
        1e-9, description="relative tolerance of the reference integrator"
    )
    atol: Annotated[float, Field(gt=0, lt=1)] = Field(1e-12, description="absolute tolerance")
    max_step: Positive | None = Field(None, description="largest step [s] (omitted = automatic)")
    sample_step: Positive = Field(
        1e-5, description="output spacing outside contact [s] (output.interval, when given, replaces it)"
    )
    contact_sample_step: Positive = Field(
        2e-7, description="output spacing in contact [s] (output.interval, when given, replaces it)"
    )
    max_contacts: Annotated[int, Field(ge=1)] = Field(
        1000, description="stop with a status after this many contacts (Zeno guard)"
    )
    baumgarte_frequency: NonNegative = Field(2000.0, description="CCM: Baumgarte stabilisation alpha = beta [1/s]")
    rest_velocity: NonNegative = Field(
        1e-6, description="IMM: impacts slower than this [m/s] start resting contact (Zeno)"
    )
    memory_limit: Positive | None = Field(
        None,
        description="largest memory a run may hold [B], estimated before it starts (omitted = half the "
        "physical memory)",
    )


class Output(Section):
    """What to record besides the contact point, and how often.

    ``interval`` is the spacing of the stored output samples in every phase; omitted, the samples lie on the grids
    of ``solver.sample_step`` in free flight and ``solver.contact_sample_step`` in contact (the same samples: an
    interval replaces both spacings).  Every phase's ends are samples too.  The finite-element reference
    (``--method fem``) stores its own steps.
    """

    measuring_points: list[NonNegative] = Field(
        default_factory=list,
        description="material coordinates of measuring points on the beam [m]",
    )
    interval: Interval | None = Field(
        None,
        description="spacing of the output samples in every phase [s], at most solver.t_end (omitted = "
        "solver.sample_step in free flight, solver.contact_sample_step in contact)",
    )


class Fem(Section):
    """Settings of the independent finite-element reference (``--method fem``)."""

    elements: Annotated[int, Field(ge=1, le=2000)] = Field(32, description="number of beam finite elements")
    time_step: Positive | None = Field(
        None,
        description="time step [s] (omitted = automatic, ~200 steps a contact; a fixed step that resolves a contact "
        "in fewer than 20 is warned of)",
    )
    rho_inf: Annotated[float, Field(ge=0.0, le=1.0)] = Field(
        0.9, description="spectral radius at infinite frequency of the generalized-alpha scheme"
    )
    friction_velocity: Annotated[float, Field(gt=0.0, le=1.0)] = Field(
        1e-4,
        description="transition velocity v_s [m/s] of the reference's regularised Coulomb friction (Brown & McPhee "
        "2016; 0 < v_s <= 1 m/s): Coulomb's law as v_s -> 0",
    )
