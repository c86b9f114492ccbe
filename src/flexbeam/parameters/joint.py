"""The joint that holds the beam: its kind and its drive (docs/architecture.md, *Adding a joint kind*)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from .fields import Finite, Positive, Rate, Section


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
