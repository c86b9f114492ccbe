"""CCM: contact constraint method (Duan, Zhang & Hong 2013, Sec. 3.2).

At contact onset the impulse-momentum map with e = 0 makes P's normal velocity zero (generalised velocities
jump, coordinates do not); the contact is then a unilateral constraint delta(q) = 0 whose multiplier lambda is
the contact force, found from the index-1 DAE [M J^T; J 0][z''; -lambda] = [Q; -J'z' - 2 alpha delta' -
beta^2 delta] (see :meth:`ImpactMethod.constrained_phase`).  The contact ends when lambda crosses zero towards
tension (a located event); the motion is then free until the gap closes again, and every later contact is
treated the same way.
"""

from __future__ import annotations

import numpy as np

from ..phases import Phase
from .base import ImpactMethod
from .impulse import impulse_jump


class CCM(ImpactMethod):
    """Contact constraint method."""

    name = "ccm"

    def on_impact(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        jump = impulse_jump(self.system, t, y, 0.0)
        ev = self.log_jump(t, jump)
        if self.holds(t, jump.y):
            return self.constrained_phase(ev), jump.y
        # the closed contact would pull: P leaves at once with zero normal velocity
        ev.end = t
        ev.velocity_after = jump.velocity_after
        return self.free_phase(), jump.y
