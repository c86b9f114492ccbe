"""IMM: impulse-momentum method with a coefficient of restitution.

Each impact is instantaneous: M (z'^+ - z'^-) = J^T P with J z'^+ = -e J z'^-, the coordinates unchanged
(:func:`flexbeam.methods.impulse.impulse_jump`); no force history exists.  Every contact of the run is treated
the same way.

Accumulating impacts (e < 1 with gravity pressing P onto the obstacle: a Zeno sequence whose impact speeds
shrink geometrically) are ended deliberately: once an impact's rebound speed ``e |delta'^-|`` falls below
``solver.rest_velocity`` (always for e = 0: a plastic impact leaves P on the surface) the velocity is cancelled
(e = 0) and P rests on the obstacle if the contact would push -- the contact is then
held by the unilateral constraint of the CCM phase (phase "resting", the force is its multiplier) until that
force would turn tensile, when free motion resumes.
"""

from __future__ import annotations

import numpy as np

from ..phases import Phase
from .base import ImpactMethod
from .impulse import impulse_jump


class IMM(ImpactMethod):
    """Impulse-momentum method."""

    name = "imm"

    def on_impact(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        speed = -self.gap_event(t, y)[1]
        resting = self.case.contact.restitution * speed < self.case.solver.rest_velocity
        jump = impulse_jump(self.system, t, y, 0.0 if resting else self.case.contact.restitution)
        ev = self.log_jump(t, jump)
        if resting and self.holds(t, jump.y):
            return self.constrained_phase(ev, name="resting"), jump.y
        ev.end = t
        ev.velocity_after = jump.velocity_after
        return self.free_phase(), jump.y
