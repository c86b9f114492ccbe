"""CCFM: continuous contact force method.

While the gap delta is closed the contact force F = L(delta)[F_k + F_d] of the chosen law
(:mod:`flexbeam.contact.laws`) acts on the beam as the generalised force J^T F (Duan, Zhang & Hong 2013,
Sec. 3.1).  The phase starts when delta crosses zero downwards and ends when it crosses zero upwards; both
instants are located as events.  The damping reference velocity d'_0 of the hysteresis laws is the approach
speed at the onset of each contact, and the linear law's effective mass 1/(J M^-1 J^T) is taken there too.
"""

from __future__ import annotations

import numpy as np

from ..phases import ContactMode, EventKind, Phase
from .base import CONTACT_STEPS, ImpactMethod


class CCFM(ImpactMethod):
    """Continuous contact force method."""

    name = "ccfm"

    def contact_phase(self, t: float, y: np.ndarray) -> Phase:
        ev = self.new_contact(t, y)
        m_eff = self.system.effective_mass(t, y)
        p = self.system.law.parameters(-ev.velocity_before, m_eff)
        step = self.contact_time(-ev.velocity_before, m_eff, float(p[0]), float(p[1])) / CONTACT_STEPS
        return Phase(
            "contact",
            ContactMode.FORCE,
            (EventKind.SEPARATION,),
            self.case.solver.contact_sample_step,
            p,
            ev,
            max_step=step,
        )

    def on_impact(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        return self.contact_phase(t, y), y
