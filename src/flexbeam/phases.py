"""The typed description of a phase of motion, shared by the impact methods, the integrators and the Solution.

A run is a sequence of phases (free flight, contact under a force law, contact held by a constraint, resting
contact) separated by events (the gap closing or opening, a constraint's multiplier turning tensile).  An
impact method decides, at each event, which phase comes next and whether the velocities jump; an integrator
advances one phase until it ends at one of its events or at t_end.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import IntEnum
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .solution import ContactEvent


class ContactMode(IntEnum):
    """How the contact acts during a phase (the integer is what the compiled kernels read)."""

    NONE = 0  #: no contact force
    FORCE = 1  #: CCFM: the contact law's force F(d, d') acts as J^T F
    CONSTRAINT = 2  #: CCM (and IMM's resting contact): the unilateral constraint held closed by its multiplier


class EventKind(IntEnum):
    """What can end a phase (the integer is what the compiled kernels report)."""

    IMPACT = 1  #: the gap closes (crosses zero downwards)
    SEPARATION = 2  #: the gap opens (crosses zero upwards) during a force-law contact
    RELEASE = 3  #: the constraint's multiplier turns tensile


@dataclass(frozen=True)
class Phase:
    """One phase: its contact mode and parameters, the events that can end it, its output spacing.

    ``parameters``: the law's [K, n, chi/d'_0, C] (FORCE) or the Baumgarte [alpha, beta, 0, 0] (CONSTRAINT).
    ``contact``: the contact record this phase belongs to (None in free flight).
    ``max_step``: a bound on the integrator's step inside the phase [s].
    """

    name: str
    mode: ContactMode
    events: tuple[EventKind, ...]
    sample_step: float
    parameters: np.ndarray = field(default_factory=lambda: np.zeros(4))
    contact: ContactEvent | None = None
    max_step: float = math.inf

    @property
    def in_contact(self) -> bool:
        """Is P in contact during this phase (force law, constraint, or resting)?"""
        return self.mode != ContactMode.NONE
