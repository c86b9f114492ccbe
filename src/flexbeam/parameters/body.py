"""The beam, its hub and the model options: what the rigid-flexible coupling model is built from."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, model_validator

from . import slenderness
from .fields import Bounded, NonNegative, Positive, Section


class Beam(Section):
    """Uniform Euler-Bernoulli beam.

    ``section = "circle"`` takes ``radius``; ``section = "general"`` takes ``area``,
    ``second_moment`` and ``half_depth`` (centre line to the surface at the contact).
    The beam must be slender (Euler-Bernoulli theory neglects shear and rotary inertia): a
    first bending frequency more than 1 % above Timoshenko's is warned about, more than 10 %
    refused -- for a solid circle with nu = 0.3, r/L above 0.066 and above 0.217
    (:mod:`flexbeam.parameters.slenderness`).
    """

    length: Positive = Field(description="beam length L [m]")
    density: Annotated[Positive, Field(le=1e6)] = Field(
        description="mass density rho [kg/m^3] (at most 1e6, 44x osmium's: 1e300 overflowed the FE reference's sums)"
    )
    youngs_modulus: Positive = Field(description="Young's modulus E [Pa]")
    poisson_ratio: Annotated[float, Field(gt=-1.0, lt=0.5)] = Field(
        0.3, description="Poisson ratio nu [-] (isotropic: -1 < nu < 1/2)"
    )
    section: Literal["circle", "general"] = "circle"
    radius: Positive | None = Field(None, description="circular section radius [m]")
    area: Positive | None = Field(None, description="cross-section area S [m^2]")
    second_moment: Positive | None = Field(None, description="second moment of area I [m^4]")
    half_depth: NonNegative | None = Field(None, description="distance from the centre line to the contact surface [m]")
    kelvin_voigt: Bounded(0.0, 1e3) = Field(
        0.0,
        description="Kelvin-Voigt (stiffness-proportional) material damping c [s]: E -> E (1 + c d/dt), modal ratio "
        "zeta_i = c omega_i / 2 (at most 1e3 s: a 1 Hz mode's zeta 3e3, far overdamped; c K must stay finite)",
    )
    viscous_damping: Bounded(0.0, 1e9) = Field(
        0.0,
        description="viscous damping eta [N s/m^2] per unit length on the deformation velocity relative to the "
        "beam's frame, modal ratio zeta_i = eta / (2 mu omega_i) (at most 1e9 N s/m^2)",
    )
    end_caps: Literal["hemisphere", "flat"] = Field(
        "hemisphere",
        description="the beam's ends for contact anywhere: 'hemisphere' (caps of the surface offset's radius, the "
        "capsule) or 'flat' (end faces across the section: a corner strikes)",
    )

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
    def axial_stiffness(self) -> float:
        """Axial stiffness EA [N]."""
        return self.youngs_modulus * self.section_area

    @property
    def mass(self) -> float:
        """Beam mass [kg]."""
        return self.line_density * self.length


class Hub(Section):
    """Rigid hub at the revolute joint O: the beam root sits at ``radius`` along e1."""

    # positions ~ r_h + L carry a round-off of ~1e-16 (r_h + L), and the beam's rotary inertia the difference
    # (r_h + L)^3 - r_h^3: at most 1e3 m keeps both well resolved for a beam of a millimetre or more
    radius: Bounded(0.0, 1e3) = Field(0.0, description="hub radius r_h [m] (at most 1e3 m)")
    inertia: NonNegative = Field(0.0, description="hub moment of inertia about O, J_h [kg m^2]")


class Model(Section):
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
    axial_modes: Annotated[int, Field(ge=0, le=64)] = Field(
        0,
        description="number of axial modes n_a (0 = inextensible beam): the centre line stretches by "
        "Phi_a(x) p, fixed-free modes on a revolute joint, free-free on a free beam (first-order model only; "
        "modes + axial_modes at most 64, 62 for a free beam)",
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
        if self.axial_modes and self.coupling != "first-order":
            raise ValueError(
                f"model.axial_modes: the axial modes need model.coupling = 'first-order' (got "
                f"'{self.coupling}' with axial_modes = {self.axial_modes})"
            )
        if self.modes + self.axial_modes > 64:
            raise ValueError(
                f"model.axial_modes: model.modes + model.axial_modes must be at most 64 (got "
                f"{self.modes} + {self.axial_modes})"
            )
        return self
