"""CCFM: continuous contact force method.

While the gap delta is closed the contact force F = L(delta)[F_k + F_d] of the
chosen law (:mod:`flexbeam.contact.laws`) acts on the beam as the generalised force
J^T F (Duan, Zhang & Hong 2013, Sec. 3.1).  The phase starts when delta crosses zero
downwards and ends when it crosses zero upwards; both instants are located as events.
The damping reference velocity d'_0 of the hysteresis laws is the approach speed at
the onset of each contact, and the linear law's effective mass 1/(J M^-1 J^T) is
taken there too.
"""

from __future__ import annotations

import numpy as np

from ..integrate.eventdriven import Event, Phase
from ..model.system import CONTACT_FORCE
from .base import ImpactMethod


class CCFM(ImpactMethod):
    """Continuous contact force method."""

    name = "ccfm"

    def __post_init__(self) -> None:
        super().__post_init__()
        self.separation_event = Event("separation", self.gap_event, +1)

    def contact_phase(self, t: float, y: np.ndarray) -> Phase:
        ev = self.new_contact(t, y)
        rate = -ev.velocity_before
        lawp = self.system.law.parameters(rate, self.system.effective_mass(t, y))
        return Phase(
            "contact",
            self.system.rhs_function(CONTACT_FORCE, lawp),
            [self.separation_event],
            self.case.solver.contact_sample_step,
            data={"mode": CONTACT_FORCE, "p": lawp, "contact": ev},
            keep_dense=True,
        )

    def on_impact(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        return self.contact_phase(t, y), y
