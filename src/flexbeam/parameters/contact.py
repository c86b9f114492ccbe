"""The obstacles, how they are held, and the contact pairs' laws."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, model_validator

from .fields import CONTACT_LAWS, MIN_SPHERE_RADIUS, Bounded, Finite, NonNegative, Positive, Section


class Support(Section):
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
        None,
        description="unit axis u along which the obstacle moves (default: its outward contact normal at the pair's "
        "point of the straight beam at initial.impact_angle, where an 'impact' start strikes it; a warning for "
        "other starts)",
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


class Obstacle(Section):
    """The obstacle in the plane of motion, fixed or on a compliant support.

    ``kind = "sphere"``: a hemisphere with ``centre`` and ``radius`` > 0 (the gap
    ``|r - c| - r_s`` of a point would never close); ``kind = "half-plane"``: the plane
    through ``centre`` with outward unit ``normal``.  When ``centre`` is omitted the obstacle is placed so that it
    touches the contact point P with the beam straight at ``initial.impact_angle``
    (sphere directly beneath P along the beam normal; plane tangent there).
    ``support``: rigid, or a mass-spring-damper (see :class:`Support`).
    ``fixed_to``: on a moving base (``[base]``), ``"base"`` (default) carries the obstacle with the joint O, its
    ``centre`` fixed in the base frame; ``"ground"`` holds it still in the plane, its ``centre`` in the inertial
    axes (where O is at r_O = 0), so that the beam sees it at ``centre`` - r_O(t) (docs/formulation.md, *A moving
    base*).  Without base motion the two are the same.
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
    fixed_to: Literal["base", "ground"] = Field(
        "base",
        description="on a moving base: 'base' (carried with the joint O) or 'ground' (still in the plane: the beam "
        "sees it at centre - r_O(t))",
    )

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


class Contact(Section):
    """Contact point P on the beam and the continuous contact force law (CCFM).

    ``side``: the surface P lies on -- ``"below"`` (the side the hub's normal e2 points away from, where the
    obstacle of a falling beam is), ``"above"``, or ``"centre"`` (the centre line, e.g. the middle of the tip's
    end face).
    """

    law: Literal[CONTACT_LAWS] = Field("lankarani_nikravesh", description="contact force law")
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
    friction: Bounded(0.0, 10.0) = Field(
        0.0,
        description="Coulomb friction: the kinetic coefficient mu_k [-] (0 = frictionless; at most 10; IMM, CCFM, CCM)",
    )
    friction_static: Bounded(0.0, 10.0) | None = Field(
        None, description="the static coefficient mu_s >= mu_k [-] (omitted = friction)"
    )
    friction_model: Literal["coulomb", "threlfall"] = Field(
        "coulomb",
        description="CCFM's and CCM's friction law: 'coulomb' (exact stick and slip, their switches located as events) "
        "or 'threlfall' (Threlfall 1978's regularised law mu_k F (1 - exp(-3 v_t / v_0)), no stick)",
    )
    friction_velocity: Positive = Field(
        1e-3, description="the regularised law's slip velocity v_0 [m/s] (its force is 95 % of mu_k F at v_0)"
    )

    @model_validator(mode="after")
    def _static_not_below_kinetic(self) -> Contact:
        check_friction("contact", self.friction, self.friction_static)
        return self


def check_friction(where: str, kinetic: float | None, static: float | None) -> None:
    """mu_s >= mu_k: one line naming ``where``.friction_static otherwise."""
    if kinetic is not None and static is not None and static < kinetic:
        raise ValueError(
            f"{where}.friction_static: the static coefficient must be at least the kinetic one ({where}.friction = "
            f"{kinetic:g}), got {static:g}"
        )


class PairContact(Section):
    """Where the beam touches an additional obstacle, and the law of that pair; an omitted field takes the
    ``[contact]`` section's value (``stiffness`` omitted and no ``[contact]`` stiffness: Hertz theory for this
    obstacle's sphere on the beam's cylinder)."""

    position: NonNegative | None = Field(None, description="material coordinate of the contact point [m]")
    side: Literal["below", "above", "centre"] | None = Field(None, description="the beam surface it lies on")
    anywhere: bool | None = Field(None, description="find the contact point on the deformed beam (see contact)")
    law: Literal[CONTACT_LAWS] | None = Field(None, description="contact force law")
    stiffness: Positive | None = Field(None, description="contact stiffness K [N/m^n]")
    exponent: Annotated[float, Field(ge=1.0, le=3.0)] | None = Field(None, description="force exponent n")
    restitution: Annotated[float, Field(ge=0.0, le=1.0)] | None = Field(
        None, description="coefficient of restitution e [-]"
    )
    friction: Bounded(0.0, 10.0) | None = Field(None, description="kinetic coefficient of friction mu_k [-]")
    friction_static: Bounded(0.0, 10.0) | None = Field(None, description="static coefficient mu_s [-]")
    friction_model: Literal["coulomb", "threlfall"] | None = Field(
        None, description="this pair's friction law under CCFM: 'coulomb' or 'threlfall' (see contact)"
    )
    friction_velocity: Positive | None = Field(None, description="this pair's regularised law's v_0 [m/s]")


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
