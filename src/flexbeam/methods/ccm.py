"""CCM: contact constraint method (Duan, Zhang & Hong 2013, Sec. 3.2).

At contact onset the impulse-momentum map with e = 0 makes the normal velocities of the impacting pairs zero
(generalised velocities jump, coordinates do not; several pairs at once through the impact LCP of
:mod:`flexbeam.methods.impulse`); each closed contact is then a unilateral constraint delta_k(q) = 0 whose
multiplier lambda_k is its contact force, found from the index-1 DAE [M J^T; J 0][z''; -lambda] = [Q; -J'z' -
2 alpha delta' - beta^2 delta] over the held pairs (see :meth:`ImpactMethod.phase`).  The held set is the one
whose multipliers are all compressive (:meth:`ImpactMethod.held_set`); a pair's contact ends when its lambda
crosses zero towards tension (a located event); it is then free until its gap closes again, and every later
contact is treated the same way.
"""

from __future__ import annotations

import numpy as np

from ..integrate.phases import ContactMode, Phase
from .base import ImpactMethod
from .impulse import impulse_jump


class CCM(ImpactMethod):
    """Contact constraint method."""

    name = "ccm"

    def on_impact(self, phase: Phase, t: float, y: np.ndarray, pairs: list[int]) -> tuple[Phase, np.ndarray]:
        jump = impulse_jump(self.system, t, y, 0.0, pairs)
        events = dict(zip(pairs, self.log_jump(t, jump, pairs)))
        held_before = [k for k, m in enumerate(phase.modes) if m == ContactMode.CONSTRAINT]
        held = self.held_set(t, jump.y, [*held_before, *pairs], phase)
        modes, records = list(phase.modes), list(phase.records)
        for k in set(held_before) | set(pairs):
            rec = events.get(k, records[k])
            if k in held:
                modes[k], records[k] = ContactMode.CONSTRAINT, rec
                continue
            # the closed contact would pull: the pair leaves at once with zero normal velocity
            rec.end = t
            rec.velocity_after = self.gap_event(t, jump.y, k)[1]
            modes[k], records[k] = ContactMode.NONE, None
        return self.phase(modes, phase.parameters, records), jump.y
