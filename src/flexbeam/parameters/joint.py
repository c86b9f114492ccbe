"""The joint that holds the beam: its kind and its drive (docs/architecture.md, *Adding a joint kind*)."""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field, model_validator

from .fields import Bounded, Finite, Positive, Rate, Section


class Joint(Section):
    """The joint that carries the beam's floating frame.

    * ``revolute``: a revolute joint at the fixed point O (the origin); the hub of ``[hub]`` turns about it, as
      ``[drive]`` says.
    * ``free``: no joint, a free-flying beam: its centre of mass (x_G, y_G) and angle theta are free coordinates
      under gravity, the frame at the centre of mass with the free-free bending modes (``docs/formulation.md``, *A
      free-flying beam*); no hub and no drive.  Its start: ``[initial]`` ``state`` (``position``, ``velocity``,
      ``angle``, ``rate``) or ``impact``.
    """

    kind: Literal["revolute", "free"] = Field(
        "revolute",
        description="joint kind: 'revolute' (a revolute joint at O) or 'free' (no joint: a free-flying beam)",
    )


class Drive(Section):
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


class Harmonic(Section):
    """One harmonic of the base's motion along an axis: ``amplitude`` sin(2 pi ``order`` f t + ``phase``), f the
    base's fundamental ``frequency``."""

    axis: Literal["x", "y"] = Field(description="the inertial axis the joint O moves along")
    amplitude: Bounded(-1e3, 1e3) = Field(description="displacement amplitude [m] (|A| <= 1e3 m)")
    order: int = Field(1, ge=1, le=1000, description="multiple k of the fundamental frequency (1..1000)")
    phase: Bounded(-1e3, 1e3) = Field(0.0, description="phase [rad]")


class Base(Section):
    """A moving base: the joint O moves in the plane as prescribed (a cantilever on a shaker).

    ``r_O(t) = sum over harmonics of A_i sin(2 pi k_i f t + phi_i) e_axis + 1/2 acceleration t^2``, the harmonics'
    fundamental ``frequency`` f [Hz] (the drive's period 1/f is that of its Poincare map).  The equations are
    written in the base frame (origin at O, axes parallel to the inertial ones), where the base's motion acts as the
    uniform inertial field g_eff(t) = (0, -g) - a_O(t) on the beam (docs/formulation.md, *A moving base*); an
    obstacle is carried by the base (it moves with O) unless its ``fixed_to = "ground"``.  No harmonic and no
    acceleration: a fixed joint, today's model bit for bit.  A revolute joint only.
    """

    frequency: Positive | None = Field(None, description="fundamental frequency f of the harmonics [Hz]")
    harmonics: list[Harmonic] = Field(default_factory=list, description="the harmonics of r_O(t) (at most 12)")
    acceleration: tuple[Bounded(-1e6, 1e6), Bounded(-1e6, 1e6)] = Field(
        (0.0, 0.0), description="a constant acceleration of O [m/s^2] (|a| <= 1e6 per axis)"
    )

    @property
    def moving(self) -> bool:
        """Does the joint O move (a harmonic of nonzero amplitude, or an acceleration)?"""
        return any(h.amplitude != 0.0 for h in self.harmonics) or any(a != 0.0 for a in self.acceleration)

    def motion(self, t: float) -> tuple[tuple[float, float], tuple[float, float], tuple[float, float]]:
        """(r_O, v_O, a_O) at time ``t`` [s] (the compiled kernels evaluate it in ``base_motion.c``)."""
        ax, ay = self.acceleration
        r, v, a = [0.5 * ax * t * t, 0.5 * ay * t * t], [ax * t, ay * t], [ax, ay]
        for h in self.harmonics:
            k, w = int(h.axis == "y"), 2.0 * math.pi * h.order * (self.frequency or 0.0)
            s, c = math.sin(w * t + h.phase), math.cos(w * t + h.phase)
            r[k] += h.amplitude * s
            v[k] += h.amplitude * w * c
            a[k] -= h.amplitude * w * w * s
        return (r[0], r[1]), (v[0], v[1]), (a[0], a[1])

    @model_validator(mode="after")
    def _frequency_given(self) -> Base:
        if self.harmonics and self.frequency is None:
            raise ValueError("base.frequency: required with base.harmonics (a frequency > 0 in Hz)")
        if len(self.harmonics) > 12:
            raise ValueError(f"base.harmonics: at most 12, not {len(self.harmonics)}")
        return self
