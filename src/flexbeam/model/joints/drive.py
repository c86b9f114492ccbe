"""Joint drives: free, constant torque, or a prescribed hub angle theta(t)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ... import numerics as nm
from ...parameters.case import Drive


@dataclass(frozen=True)
class JointDrive:
    """The joint O as the equations see it.

    ``prescribed`` is True when theta(t) is given; then :meth:`motion` returns
    (theta, theta', theta'') and the joint torque is an output.  Otherwise
    :meth:`torque` gives the applied torque tau(t) [N m].
    """

    spec: Drive
    theta0: float = 0.0

    @property
    def prescribed(self) -> bool:
        return self.spec.kind == "prescribed"

    def torque(self, t: float) -> float:
        """Applied joint torque tau(t) [N m] (zero for a free joint)."""
        return self.spec.torque if self.spec.kind == "torque" else 0.0

    def motion(self, t: float) -> tuple[float, float, float]:
        """Prescribed (theta, theta', theta'') at time t.

        ``constant-rate``: theta = theta0 + W t.  ``kane-spinup`` (Kane, Ryan &
        Banerjee 1987, eq. 57): for t < T,
        theta = (W/T)[t^2/2 + (T/2pi)^2 (cos(2 pi t/T) - 1)], then constant rate W.
        """
        W = self.spec.spin_rate
        if self.spec.profile == "constant-rate":
            return self.theta0 + W * t, W, 0.0
        T = self.spec.spin_up_time
        if t < T:
            a = 2.0 * math.pi / T
            ca, sa = nm.cos(a * t), nm.sin(a * t)
            th = (W / T) * (0.5 * t * t + (ca - 1.0) / (a * a))
            thd = (W / T) * (t - sa / a)
            thdd = (W / T) * (1.0 - ca)
            return self.theta0 + th, thd, thdd
        return self.theta0 + W * (t - 0.5 * T), W, 0.0
