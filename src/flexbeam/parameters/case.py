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
import warnings

from pydantic import Field, model_validator

from ..contact.laws import NEEDS_RESTITUTION
from ..errors import FlexbeamWarning
from .body import Beam, Hub, Model
from .contact import SIDES, Contact, ExtraObstacle, Obstacle, PairContact, Support
from .fields import CONTACT_LAWS, Section
from .joint import Base, Drive, Joint
from .run import Fem, Initial, Output, Solver


class Case(Section):
    """A complete simulation case."""

    name: str = "case"
    description: str = ""
    beam: Beam
    hub: Hub = Field(default_factory=Hub)
    model: Model = Field(default_factory=Model)
    joint: Joint = Field(default_factory=Joint)
    drive: Drive = Field(default_factory=Drive)
    base: Base = Field(default_factory=Base)
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
        """The body frame this case uses: ``model.frame`` with ``"auto"`` resolved by the drive kind; a free beam's
        is ``"mean-axis"`` (the frame at its centre of mass, free-free modes)."""
        if self.joint.kind == "free":
            return "mean-axis"
        if self.model.frame != "auto":
            return self.model.frame
        return "hub" if self.drive.kind == "prescribed" else "system"

    def sample_steps(self) -> tuple[float, float]:
        """The spacing of the output samples [s] in free flight and in contact: ``output.interval`` for both when
        given, else ``solver.sample_step`` and ``solver.contact_sample_step``."""
        if self.output.interval is not None:
            return self.output.interval, self.output.interval
        return self.solver.sample_step, self.solver.contact_sample_step

    def sample_step_field(self, contact: bool) -> str:
        """The case field that sets the sample spacing of free flight (or of contact: ``contact``)."""
        if self.output.interval is not None:
            return "output.interval"
        return "solver.contact_sample_step" if contact else "solver.sample_step"

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
        init = self.initial
        for name in ("modal_displacement", "modal_velocity"):
            values = getattr(init, name)
            if len(values) > self.model.modes:
                raise ValueError(f"initial.{name}: {len(values)} values for model.modes = {self.model.modes} modes")
            if values and init.kind != "state":
                raise ValueError(f"initial.{name}: only for initial.kind = 'state' (got '{init.kind}')")
        self._axial()
        if self.joint.kind == "free":
            self._free_beam()
        elif init.position != (0.0, 0.0) or init.velocity != (0.0, 0.0):
            name = "position" if init.position != (0.0, 0.0) else "velocity"
            raise ValueError(
                f"initial.{name}: only for a free beam (joint.kind = 'free'); a revolute joint holds the beam at O"
            )
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
        interval = self.output.interval
        if interval is not None and not interval <= self.solver.t_end:
            raise ValueError(
                f"output.interval: {interval:g} s is longer than the run; allowed: 0 < output.interval <= "
                f"solver.t_end = {self.solver.t_end:g} s"
            )
        step = self.fem.time_step
        if step is not None and not step <= self.solver.t_end:  # (1 s for 1 ms: two steps, a "success" 5x the peak)
            raise ValueError(
                f"fem.time_step: {step:g} s is longer than the run; allowed: 0 < fem.time_step <= solver.t_end = "
                f"{self.solver.t_end:g} s (omitted = automatic, a contact's duration / 200)"
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
        self._support_axis()
        return self

    def _support_axis(self) -> None:
        """Warn where a compliant support's default axis -- the outward contact normal of the straight beam at
        ``initial.impact_angle``, at the contact point (:func:`flexbeam.contact.setup.obstacle_geometry`) -- is not
        taken where the obstacle is struck: a start other than ``impact``.  A sensor under spinning-stop's sphere (a
        ``state`` start, struck at 0.951 rad) moved 26.7 degrees off the contact normal there by default."""
        sup = self.obstacle.support
        if self.initial.kind != "impact" and sup.compliant and sup.direction is None:
            warnings.warn(
                "obstacle.support.direction: omitted, so the support moves along the contact normal of the straight "
                f"beam at initial.impact_angle = {self.initial.impact_angle:g} rad, which need not be where a "
                f"'{self.initial.kind}' start strikes it; give the axis (a unit vector)",
                FlexbeamWarning,
                stacklevel=2,
            )

    def _axial(self) -> None:
        """The axial modes' initial values and what does not model them yet, and a base table that does not cover the
        run: one line naming the field."""
        init, na = self.initial, self.model.axial_modes
        for name in ("axial_displacement", "axial_velocity"):
            values = getattr(init, name)
            if len(values) > na:
                raise ValueError(f"initial.{name}: {len(values)} values for model.axial_modes = {na} modes")
            if values and init.kind != "state":
                raise ValueError(f"initial.{name}: only for initial.kind = 'state' (got '{init.kind}')")
        if na and self.base.moving:
            raise ValueError(
                "model.axial_modes: a moving base (base) does not model the axial modes yet; set "
                "model.axial_modes = 0 or leave the base still"
            )
        table = self.base.table
        if table is not None and not (table[0][0] <= 0.0 and table[-1][0] >= self.solver.t_end):
            raise ValueError(
                f"base.table: covers t = {table[0][0]:g} .. {table[-1][0]:g} s; the run needs 0 .. solver.t_end = "
                f"{self.solver.t_end:g} s (a table is not extrapolated)"
            )

    def _free_beam(self) -> None:
        """What a free beam (``joint.kind = "free"``) does not have, or does not support yet: one line naming the
        field."""
        if self.drive.kind != "free":
            raise ValueError(
                f"drive.kind: a free beam (joint.kind = 'free') has no joint to drive; got '{self.drive.kind}' "
                "(leave drive.kind = 'free')"
            )
        if self.hub.radius != 0.0 or self.hub.inertia != 0.0:
            name = "radius" if self.hub.radius != 0.0 else "inertia"
            raise ValueError(f"hub.{name}: a free beam (joint.kind = 'free') has no hub; leave it 0")
        if self.model.frame != "auto":
            raise ValueError(
                f"model.frame: a free beam (joint.kind = 'free') uses the frame at its centre of mass with the "
                f"free-free modes; leave model.frame = 'auto' (got '{self.model.frame}')"
            )
        if self.model.modes > 62:
            raise ValueError(f"model.modes: at most 62 for a free beam (joint.kind = 'free'; got {self.model.modes})")
        if self.model.modes + self.model.axial_modes > 62:
            raise ValueError(
                f"model.axial_modes: model.modes + model.axial_modes must be at most 62 for a free beam (joint.kind "
                f"= 'free'; got {self.model.modes} + {self.model.axial_modes})"
            )
        if self.initial.kind == "release":
            raise ValueError(
                "initial.kind: 'release' needs a joint to hold the beam; a free beam (joint.kind = 'free') starts "
                "with 'state' or 'impact'"
            )
        if self.base.moving:
            raise ValueError("base: a free beam (joint.kind = 'free') has no joint O to move; leave [base] empty")


__all__ = [
    "CONTACT_LAWS", "SIDES", "Base", "Beam", "Case", "Contact", "Drive", "ExtraObstacle", "Fem", "Hub", "Initial",
    "Joint", "Model", "Obstacle", "Output", "PairContact", "Solver", "Support",
]  # fmt: skip
