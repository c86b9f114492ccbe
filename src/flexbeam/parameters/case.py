"""Validated case parameters (SI units, angles in radians).

A *case* is everything needed to run one simulation: the beam, the hub, the model
options, the drive at the joint O, the obstacle, the contact law, the initial state
and the solver settings.  Each section is a pydantic model with ``extra="forbid"``
so that a misspelt key is an error, and every number is checked to be finite and in
its physical range at construction.  :func:`flexbeam.parameters.io.load_case` turns a
:class:`pydantic.ValidationError` into a one-line :class:`~flexbeam.errors.ParameterError`
naming the field.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field, model_validator

from ..contact.laws import LAW_NAMES, NEEDS_RESTITUTION
from . import slenderness


def _finite(value: float) -> float:
    if not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


Finite = Annotated[float, AfterValidator(_finite)]
Positive = Annotated[float, Field(gt=0), AfterValidator(_finite)]
NonNegative = Annotated[float, Field(ge=0), AfterValidator(_finite)]


def _finite_first(value: object) -> object:
    """NaN and +-inf named as such before a bounded field's range is checked."""
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


def Bounded(lo: float, hi: float):  # noqa: N802 - a type
    """A finite float in [lo, hi]."""
    return Annotated[float, BeforeValidator(_finite_first), Field(ge=lo, le=hi)]


#: an angle [rad]: within +-1000 rad (160 turns), where double precision still resolves 1e-13 rad; at 1e6 rad the
#: integrators cannot resolve the motion of a step (measured: step-size underflow after 3.5e5 steps)
Angle = Bounded(-1e3, 1e3)
#: an angular rate [rad/s]: within +-1e4 rad/s (~1e5 rpm; a 1 m beam's tip would move at 10 km/s)
MAX_RATE = 1e4
Rate = Bounded(-MAX_RATE, MAX_RATE)
#: the smallest sphere obstacle [m]
MIN_SPHERE_RADIUS = 1e-6

CONTACT_LAWS = LAW_NAMES  # the registry of contact laws (flexbeam.contact.laws.LAWS)


class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid", validate_assignment=True)


class Beam(_Section):
    """Uniform Euler-Bernoulli beam.

    ``section = "circle"`` takes ``radius``; ``section = "general"`` takes ``area``,
    ``second_moment`` and ``half_depth`` (centre line to the surface at the contact).
    The beam must be slender (Euler-Bernoulli theory neglects shear and rotary inertia): a
    first bending frequency more than 1 % above Timoshenko's is warned about, more than 10 %
    refused -- for a solid circle with nu = 0.3, r/L above 0.066 and above 0.217
    (:mod:`flexbeam.parameters.slenderness`).
    """

    length: Positive = Field(description="beam length L [m]")
    density: Positive = Field(description="mass density rho [kg/m^3]")
    youngs_modulus: Positive = Field(description="Young's modulus E [Pa]")
    poisson_ratio: Annotated[float, Field(gt=-1.0, lt=0.5)] = Field(
        0.3, description="Poisson ratio nu [-] (isotropic: -1 < nu < 1/2)"
    )
    section: Literal["circle", "general"] = "circle"
    radius: Positive | None = Field(None, description="circular section radius [m]")
    area: Positive | None = Field(None, description="cross-section area S [m^2]")
    second_moment: Positive | None = Field(None, description="second moment of area I [m^4]")
    half_depth: NonNegative | None = Field(None, description="distance from the centre line to the contact surface [m]")

    @model_validator(mode="after")
    def _section_complete(self) -> Beam:
        if self.section == "circle":
            if self.radius is None:
                raise ValueError("beam.radius: required when beam.section = 'circle'")
        else:
            for name in ("area", "second_moment", "half_depth"):
                if getattr(self, name) is None:
                    raise ValueError(f"beam.{name}: required when beam.section = 'general'")
        self._representable()
        slenderness.check(self)  # Euler-Bernoulli theory: warn above r/L ~ 0.066, refuse above ~ 0.22
        return self

    def _representable(self) -> None:
        """The derived section and beam properties must be positive finite doubles (a radius of 1e-300 m has an
        area of 0, one of 1e300 m an infinite one); the message names the field that made each."""
        size = "beam.radius" if self.section == "circle" else "beam.area"
        derived = (
            ("section area S", size, lambda: self.section_area),
            ("second moment I", "beam.radius" if self.section == "circle" else "beam.second_moment",
             lambda: self.section_second_moment),
            ("mass per length rho S", "beam.density", lambda: self.line_density),
            ("bending stiffness E I", "beam.youngs_modulus", lambda: self.bending_stiffness),
            ("mass rho S L", "beam.length", lambda: self.mass),
            ("first bending frequency sqrt(E I / rho S) / L^2", "beam.length",
             lambda: math.sqrt(self.bending_stiffness / self.line_density) / self.length**2),
        )  # fmt: skip
        for what, name, value in derived:
            try:
                v = value()
            except (OverflowError, ZeroDivisionError):
                v = math.inf
            if not 1e-300 < v < 1e300:
                raise ValueError(f"{name}: gives a {what} of {v:.3g}, outside the positive doubles (1e-300, 1e300)")

    @property
    def section_area(self) -> float:
        """Cross-section area S [m^2]."""
        if self.area is not None:
            return self.area
        assert self.radius is not None
        r = self.radius
        return math.pi * (r * r)  # products, not libm's pow: the same bits on every machine

    @property
    def section_second_moment(self) -> float:
        """Second moment of area I [m^4]."""
        if self.second_moment is not None:
            return self.second_moment
        assert self.radius is not None
        r2 = self.radius * self.radius
        return math.pi * (r2 * r2) / 4.0

    @property
    def surface_offset(self) -> float:
        """Distance c from the centre line to the beam surface at the contact [m]."""
        if self.half_depth is not None:
            return self.half_depth
        assert self.radius is not None
        return self.radius

    @property
    def line_density(self) -> float:
        """Mass per unit length mu = rho S [kg/m]."""
        return self.density * self.section_area

    @property
    def bending_stiffness(self) -> float:
        """Bending stiffness EI [N m^2]."""
        return self.youngs_modulus * self.section_second_moment

    @property
    def mass(self) -> float:
        """Beam mass [kg]."""
        return self.line_density * self.length


class Hub(_Section):
    """Rigid hub at the revolute joint O: the beam root sits at ``radius`` along e1."""

    # positions ~ r_h + L carry a round-off of ~1e-16 (r_h + L), and the beam's rotary inertia the difference
    # (r_h + L)^3 - r_h^3: at most 1e3 m keeps both well resolved for a beam of a millimetre or more
    radius: Bounded(0.0, 1e3) = Field(0.0, description="hub radius r_h [m] (at most 1e3 m)")
    inertia: NonNegative = Field(0.0, description="hub moment of inertia about O, J_h [kg m^2]")


class Model(_Section):
    """Discretisation and physics options of the rigid-flexible coupling model.

    ``frame`` chooses the body reference frame together with its shape functions
    (``docs/formulation.md``): the *system* frame is pinned at O and carries the rigid rotation
    of hub and beam, with the flexible eigenmodes of the hub + beam system as shapes (no light
    coordinate for a hub without inertia); the *hub* frame is the hub's tangent frame with
    clamped-free modes (the seed paper's choice, and the natural one for a prescribed hub angle).
    """

    modes: Annotated[int, Field(ge=0, le=64)] = Field(8, description="number of assumed modes n (0 = rigid beam)")
    frame: Literal["auto", "system", "hub"] = Field(
        "auto",
        description="body frame and shape functions: 'system' (frame pinned at O carrying the rigid rotation, "
        "flexible eigenmodes of the hub + beam system), 'hub' (the hub's tangent frame, clamped-free modes, as "
        "in the seed paper), 'auto' (system for a free or torque-driven joint, hub for a prescribed angle)",
    )
    coupling: Literal["first-order", "zeroth-order"] = Field(
        "first-order",
        description="first-order keeps the coupling deformation u_x (centrifugal stiffening)",
    )
    gravity: Bounded(0.0, 1e4) = Field(
        9.81, description="gravitational acceleration g [m/s^2] (0 = off; at most 1e4, ~1000 g)"
    )
    quadrature_points: Annotated[int, Field(ge=0, le=4000)] = Field(
        0, description="Gauss points for the modal integrals (0 = automatic, else >= modes + 1)"
    )

    @model_validator(mode="after")
    def _enough_points(self) -> Model:
        # The mass matrix of theta and the n modal coordinates is a sum of one rank-one term
        # per Gauss point: it is singular with fewer than n + 1 points.
        if 0 < self.quadrature_points < self.modes + 1:
            raise ValueError(
                f"model.quadrature_points: must be 0 (automatic) or >= model.modes + 1 = {self.modes + 1} "
                f"(got {self.quadrature_points})"
            )
        return self


class Drive(_Section):
    """What happens at the joint O.

    * ``free``: no torque (tau = 0).
    * ``torque``: constant driving torque ``torque`` [N m].
    * ``prescribed``: theta(t) given by ``profile``: ``"constant-rate"``
      (theta = theta_0 + ``spin_rate`` t) or ``"kane-spinup"`` (Kane, Ryan & Banerjee
      1987: theta = (W/T)[t^2/2 + (T/2 pi)^2 (cos(2 pi t/T) - 1)] for t < T, then
      constant rate W = ``spin_rate``, T = ``spin_up_time``).
    """

    kind: Literal["free", "torque", "prescribed"] = "free"
    torque: Finite = Field(0.0, description="constant joint torque tau [N m] (kind = torque)")
    profile: Literal["constant-rate", "kane-spinup"] = "constant-rate"
    spin_rate: Rate = Field(0.0, description="final spin rate Omega_s [rad/s]")
    spin_up_time: Positive = Field(15.0, description="spin-up time T_s [s] (kane-spinup)")


class Support(_Section):
    """How the obstacle is held: rigidly (default) or on a mass-spring-damper.

    With ``stiffness`` given the obstacle (e.g. the hemisphere on its force sensor) is a
    body of ``mass`` m_s that translates by s along the unit ``direction`` u on a linear
    spring k_s and dashpot c_s to ground:  m_s s'' + c_s s' + k_s s = (d delta / d s) F,
    with s measured from the static equilibrium (gravity preload cancels).  A force
    sensor under it reads the support force -(k_s s + c_s s').
    """

    stiffness: Positive | None = Field(
        None, description="support stiffness k_s [N/m] (omitted = rigidly fixed obstacle)"
    )
    mass: Positive | None = Field(None, description="moving mass m_s of the obstacle [kg]")
    damping: NonNegative = Field(0.0, description="support damping c_s [N s/m]")
    direction: tuple[Finite, Finite] | None = Field(
        None, description="unit axis u along which the obstacle moves (default: its outward contact normal at impact)"
    )

    @model_validator(mode="after")
    def _complete(self) -> Support:
        if self.stiffness is not None and self.mass is None:
            raise ValueError("obstacle.support.mass: required (> 0 kg) when obstacle.support.stiffness is given")
        if self.stiffness is None and (self.mass is not None or self.damping != 0.0):
            raise ValueError(
                "obstacle.support.stiffness: required (> 0 N/m) when obstacle.support.mass or damping is given"
            )
        if self.direction is not None:
            norm = math.hypot(*self.direction)
            if not math.isclose(norm, 1.0, rel_tol=1e-9):
                raise ValueError(f"obstacle.support.direction: must be a unit vector (got length {norm:.6g})")
        return self

    @property
    def compliant(self) -> bool:
        return self.stiffness is not None


class Obstacle(_Section):
    """The obstacle in the plane of motion, fixed or on a compliant support.

    ``kind = "sphere"``: a hemisphere with ``centre`` and ``radius`` > 0 (the gap
    ``|r - c| - r_s`` of a point would never close); ``kind = "half-plane"``: the plane
    through ``centre`` with outward unit ``normal``.  When ``centre`` is omitted the obstacle is placed so that it
    touches the contact point P with the beam straight at ``initial.impact_angle``
    (sphere directly beneath P along the beam normal; plane tangent there).
    ``support``: rigid, or a mass-spring-damper (see :class:`Support`).
    No obstacle may overlap the beam's body at t = 0 (a contact may start closed, gap 0).
    """

    kind: Literal["sphere", "half-plane"] = "sphere"
    centre: tuple[Finite, Finite] | None = Field(None, description="obstacle centre [m]")
    # the gap |r - c| - r_s of a sphere of radius r_s carries a round-off of ~1e-16 r_s: at most 1e3 m keeps it
    # below 1e-12 m (a plane is the limit of a larger sphere)
    radius: Bounded(0.0, 1e3) = Field(
        0.01, description="hemisphere radius r_s [m] (> 0 for a sphere; at most 1e3 m: beyond, a half-plane)"
    )
    normal: tuple[Finite, Finite] | None = Field(
        None, description="outward unit normal of a half-plane (default: beam normal at impact)"
    )
    youngs_modulus: Positive = Field(68.95e9, description="obstacle Young's modulus [Pa]")
    poisson_ratio: Annotated[float, Field(gt=-1.0, lt=0.5)] = Field(
        0.3, description="obstacle Poisson ratio [-] (isotropic: -1 < nu < 1/2)"
    )
    support: Support = Field(default_factory=Support)

    @model_validator(mode="after")
    def _normal_is_unit(self) -> Obstacle:
        if self.kind == "sphere" and self.radius < MIN_SPHERE_RADIUS:
            # the gap |r - c| - r_s of a point never closes, and its normal is undefined at contact; a radius below
            # a micrometre has no Hertz stiffness in double precision (1e-300 m gives K = 0)
            raise ValueError(
                f"obstacle.radius: must be > 0 m for a sphere obstacle, at least {MIN_SPHERE_RADIUS:g} m "
                f"(got {self.radius:g})"
            )
        if self.normal is not None:
            norm = math.hypot(*self.normal)
            if not math.isclose(norm, 1.0, rel_tol=1e-9):
                raise ValueError(f"obstacle.normal: must be a unit vector (got length {norm:.6g})")
        return self


SIDES = {"below": 1.0, "above": -1.0, "centre": 0.0}  # the contact point's offset from the centre line, in c


class Contact(_Section):
    """Contact point P on the beam and the continuous contact force law (CCFM).

    ``side``: the surface P lies on -- ``"below"`` (the side the hub's normal e2 points away from, where the
    obstacle of a falling beam is), ``"above"``, or ``"centre"`` (the centre line, e.g. the middle of the tip's
    end face).
    """

    law: Literal[LAW_NAMES] = Field("lankarani_nikravesh", description="contact force law")
    position: NonNegative = Field(description="material coordinate x_P of the contact point [m]")
    side: Literal["below", "above", "centre"] = Field("below", description="the beam surface P lies on")
    anywhere: bool = Field(
        False,
        description="find the contact point on the deformed beam: the surface point (either side) nearest the "
        "obstacle, moving along the beam (position then only places an obstacle without centre)",
    )
    stiffness: Positive | None = Field(None, description="contact stiffness K [N/m^n] (omitted = Hertz theory)")
    exponent: Annotated[float, Field(ge=1.0, le=3.0)] = Field(1.5, description="force exponent n (1.5 = Hertz)")
    restitution: Annotated[float, Field(ge=0.0, le=1.0)] = Field(0.8, description="coefficient of restitution e [-]")


class PairContact(_Section):
    """Where the beam touches an additional obstacle, and the law of that pair; an omitted field takes the
    ``[contact]`` section's value (``stiffness`` omitted and no ``[contact]`` stiffness: Hertz theory for this
    obstacle's sphere on the beam's cylinder)."""

    position: NonNegative | None = Field(None, description="material coordinate of the contact point [m]")
    side: Literal["below", "above", "centre"] | None = Field(None, description="the beam surface it lies on")
    anywhere: bool | None = Field(None, description="find the contact point on the deformed beam (see contact)")
    law: Literal[LAW_NAMES] | None = Field(None, description="contact force law")
    stiffness: Positive | None = Field(None, description="contact stiffness K [N/m^n]")
    exponent: Annotated[float, Field(ge=1.0, le=3.0)] | None = Field(None, description="force exponent n")
    restitution: Annotated[float, Field(ge=0.0, le=1.0)] | None = Field(
        None, description="coefficient of restitution e [-]"
    )


class ExtraObstacle(Obstacle):
    """One more obstacle (``[[obstacles]]``), rigidly held, with its ``centre`` given and the contact pair
    ``[obstacles.contact]`` through which the beam can touch it."""

    centre: tuple[Finite, Finite] = Field(description="obstacle centre (sphere) or a point of the plane [m]")
    contact: PairContact = Field(default_factory=PairContact)

    @model_validator(mode="after")
    def _rigid(self) -> ExtraObstacle:
        if self.support.compliant:
            raise ValueError("obstacles.support: only [obstacle] may stand on a compliant support")
        return self


class Initial(_Section):
    """Initial state.

    * ``impact``: start at the first contact, beam straight (q = q' = 0) at
      theta = ``impact_angle``, with P's normal velocity ``impact_velocity`` (< 0 approaching).
    * ``release``: start from rest, beam straight, at ``release_angle``; if that is
      omitted it is solved for so that P reaches the obstacle at ``impact_velocity``.
    * ``state``: theta = ``angle``, theta' = ``rate``, beam straight and at rest in the
      floating frame.
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

    def impact_rate(self, J_theta: float, velocity: float | None = None) -> float:
        """The hub rate giving P the normal velocity ``velocity`` (default ``impact_velocity``) when P moves
        ``J_theta`` m per radian along its normal; a one-line ParameterError when that needs more than
        :data:`MAX_RATE` (P at or next to the joint)."""
        from ..errors import ParameterError

        v = self.impact_velocity if velocity is None else velocity
        J_theta = float(J_theta)
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


class Solver(_Section):
    """Integration settings.

    ``integrator = "exponential"`` (default): exact modal propagation with Gauss
    collocation of the coupling and contact terms, compiled (fast; tolerances
    ``fast_rtol``/``fast_atol``); it serves every impact method on a rigidly held
    obstacle and CCFM on a compliant ``obstacle.support``; constrained phases against a
    compliant support (CCM, IMM's resting contact) take the reference path.
    ``"reference"``: scipy's DOP853, event-driven (``rtol``/``atol``).

    A run whose estimated memory (dense output, phases and, when they are written or drawn, output
    samples; :func:`flexbeam.memory.estimate`) exceeds ``memory_limit`` is refused before it starts.
    """

    integrator: Literal["exponential", "reference"] = Field(
        "exponential",
        description="time integrator (exponential: with a rigid obstacle, or CCFM "
        "on a compliant support; else the reference is used)",
    )
    fast_rtol: Annotated[float, Field(gt=0, lt=1)] = Field(
        1e-6, description="relative tolerance of the exponential integrator"
    )
    fast_atol: Annotated[float, Field(gt=0, lt=1)] = Field(
        1e-9, description="absolute tolerance of the exponential integrator"
    )

    t_end: Positive = Field(0.1, description="simulated time [s]")
    rtol: Annotated[float, Field(gt=0, lt=1)] = Field(1e-9, description="relative tolerance")
    atol: Annotated[float, Field(gt=0, lt=1)] = Field(1e-12, description="absolute tolerance")
    max_step: Positive | None = Field(None, description="largest step [s] (omitted = automatic)")
    sample_step: Positive = Field(1e-5, description="output spacing outside contact [s]")
    contact_sample_step: Positive = Field(2e-7, description="output spacing in contact [s]")
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


class Output(_Section):
    """What to record besides the contact point."""

    measuring_points: list[NonNegative] = Field(
        default_factory=list,
        description="material coordinates of measuring points on the beam [m]",
    )


class Fem(_Section):
    """Settings of the independent finite-element reference (``--method fem``)."""

    elements: Annotated[int, Field(ge=1, le=2000)] = Field(32, description="number of beam finite elements")
    time_step: Positive | None = Field(None, description="time step [s] (omitted = automatic)")
    rho_inf: Annotated[float, Field(ge=0.0, le=1.0)] = Field(
        0.9, description="spectral radius at infinite frequency of the generalized-alpha scheme"
    )


class Case(_Section):
    """A complete simulation case."""

    name: str = "case"
    description: str = ""
    beam: Beam
    hub: Hub = Field(default_factory=Hub)
    model: Model = Field(default_factory=Model)
    drive: Drive = Field(default_factory=Drive)
    obstacle: Obstacle = Field(default_factory=Obstacle)
    obstacles: list[ExtraObstacle] = Field(
        default_factory=list, description="more obstacles, each with its own contact pair (at most 7)"
    )
    contact: Contact
    initial: Initial = Field(default_factory=Initial)
    solver: Solver = Field(default_factory=Solver)
    output: Output = Field(default_factory=Output)
    fem: Fem = Field(default_factory=Fem)

    @property
    def frame(self) -> str:
        """The body frame this case uses: ``model.frame`` with ``"auto"`` resolved by the drive kind."""
        if self.model.frame != "auto":
            return self.model.frame
        return "hub" if self.drive.kind == "prescribed" else "system"

    @model_validator(mode="after")
    def _consistent(self) -> Case:
        L = self.beam.length
        rh, mu = self.hub.radius, self.beam.line_density
        try:  # the rigid rotary inertia about O, J_h + mu ((r_h + L)^3 - r_h^3) / 3
            inertia = self.hub.inertia + mu * ((rh + L) ** 3 - rh**3) / 3.0
        except OverflowError:
            inertia = math.inf
        if not inertia < 1e300:
            field = "hub.inertia" if self.hub.inertia >= 0.5 * inertia else "beam.density"
            raise ValueError(f"{field}: gives a rotary inertia about O of {inertia:.3g} kg m^2, not a finite double")
        if not self.contact.position <= L:
            raise ValueError(
                f"contact.position: must lie on the beam, 0 <= x_P <= beam.length = {L:g} m "
                f"(got {self.contact.position:g})"
            )
        for i, x in enumerate(self.output.measuring_points):
            if x > L:
                raise ValueError(f"output.measuring_points[{i}]: must lie on the beam, 0 <= x <= {L:g} m (got {x:g})")
        if self.model.frame == "system" and self.drive.kind == "prescribed":
            raise ValueError(
                "model.frame: 'system' needs a free or torque-driven joint; with drive.kind = 'prescribed' the "
                "hub angle is given and the frame is 'hub' (or 'auto')"
            )
        if self.obstacle.kind == "half-plane" and self.contact.stiffness is None:
            raise ValueError(
                "contact.stiffness: required for a half-plane obstacle (a cylinder on a plane "
                "is a line contact, not a Hertzian point contact)"
            )
        if self.contact.law in NEEDS_RESTITUTION and (self.contact.restitution == 0.0):
            raise ValueError(
                f"contact.restitution: must be in (0, 1] for contact.law = "
                f"'{self.contact.law}' (its damping is infinite at e = 0)"
            )
        if len(self.obstacles) > 7:
            raise ValueError(f"obstacles: at most 7 more obstacles (got {len(self.obstacles)})")
        for i, ob in enumerate(self.obstacles):
            pc = ob.contact
            x = self.contact.position if pc.position is None else pc.position
            if not x <= L:
                raise ValueError(
                    f"obstacles[{i}].contact.position: must lie on the beam, 0 <= x <= {L:g} m (got {x:g})"
                )
            law = pc.law or self.contact.law
            e = self.contact.restitution if pc.restitution is None else pc.restitution
            if law in NEEDS_RESTITUTION and e == 0.0:
                raise ValueError(
                    f"obstacles[{i}].contact.restitution: must be in (0, 1] for law '{law}' (its damping is "
                    f"infinite at e = 0)"
                )
            if ob.kind == "half-plane" and pc.stiffness is None and self.contact.stiffness is None:
                raise ValueError(
                    f"obstacles[{i}].contact.stiffness: required for a half-plane obstacle (a cylinder on a plane "
                    f"is a line contact, not a Hertzian point contact)"
                )
        return self
