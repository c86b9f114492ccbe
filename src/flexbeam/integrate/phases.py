"""The typed description of a phase of motion, shared by the impact methods, the integrators and the Solution.

A run is a sequence of phases separated by events.  In a phase each contact pair (a point of the beam and an
obstacle) is free, in contact under its force law, held closed by a constraint, or resting; an event is one pair's
gap closing or opening, or its constraint's multiplier turning tensile.  An impact method decides, at each event,
which phase comes next and whether the velocities jump; an integrator advances one phase until it ends at one of
its events or at t_end.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from enum import IntEnum
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..results.records import ContactEvent


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
    STOP = 4  #: a slipping pair's slip velocity reaches zero (Coulomb friction, CCFM)
    UNSTICK_PLUS = 5  #: a sticking pair's tangential multiplier reaches +mu_s F (it slips towards -t)
    UNSTICK_MINUS = 6  #: ... reaches -mu_s F (it slips towards +t)
    PAINLEVE = 7  #: a held pair's slip reaches a = W_nn - mu_k s W_nt <= 0 (Painlevé; CCM, IMM at rest, friction)


#: the events of Coulomb friction (a phase with a slipping or sticking pair watches them)
FRICTION_EVENTS = (EventKind.STOP, EventKind.UNSTICK_PLUS, EventKind.UNSTICK_MINUS)
#: what a phase with a held (CCM) slipping pair watches besides (:mod:`flexbeam.methods.painleve`)
PAINLEVE_EVENTS = (EventKind.PAINLEVE,)


@dataclass(frozen=True)
class Phase:
    """One phase: how each contact pair acts, the events that can end it, its output spacing.

    ``modes``: per pair its :class:`ContactMode`; ``parameters`` (pairs x 4): per pair its law's
    [K, n, chi/d'_0, C] (FORCE pairs); ``baumgarte``: the constraints' [alpha, beta] (CONSTRAINT pairs);
    ``records``: per pair the contact record it belongs to (None while that pair is free).
    ``max_step``: a bound on the integrator's step inside the phase [s], up to the time ``max_step_until`` [s]
    (after it the integrator's own bound and error control alone set the step: a contact under its law that has
    outlasted its impact, see :data:`flexbeam.methods.base.RESTING_DURATIONS`; the compiled
    :class:`~flexbeam.integrate.modal.ModalStepper` lifts it there, the reference integrator keeps it).
    ``friction`` (pairs x 5, None without): per pair [sigma, stick, mu_s, v_rest, s] of Coulomb friction under CCFM: a
    slipping pair's tangential force sigma F along its tangent (sigma = -mu_k s, s = sign(v_t) its slip's direction),
    a sticking pair (stick = 1) held tangentially while its multiplier stays within mu_s F
    (:mod:`flexbeam.methods.coulomb`).
    """

    name: str
    modes: tuple[ContactMode, ...]
    events: tuple[EventKind, ...]
    sample_step: float
    parameters: np.ndarray
    records: tuple[ContactEvent | None, ...]
    baumgarte: tuple[float, float] = (0.0, 0.0)
    max_step: float = math.inf
    max_step_until: float = math.inf
    friction: np.ndarray | None = None

    @property
    def underflow_advice(self) -> str:
        """What a failure inside this phase adds when a pair sticks (CCFM's Coulomb friction) or rests (IMM), else
        ""."""
        if self.name == "resting":
            return (
                "; a pair rests there while IMM's impacts may accumulate at another (Zeno): a larger"
                " solver.rest_velocity ends them sooner"
            )
        if self.friction is None or not np.any(self.friction[:, 1] == 1.0):
            return ""
        return (
            "; a pair sticks there (its tangential multiplier collocated as CCM's): fewer modes or"
            " contact.friction_model = 'threlfall' (a regularised law) may carry the run on"
        )

    @property
    def mode(self) -> ContactMode:
        """The phase's overall mode: CONSTRAINT if some pair is held, else FORCE if some pair is under its law."""
        return max(self.modes, default=ContactMode.NONE)

    @property
    def in_contact(self) -> bool:
        """Is some pair in contact during this phase (force law, constraint, or resting)?"""
        return any(self.modes)  # (NONE is 0: as mode != NONE, without comparing the enums)

    @property
    def contact(self) -> ContactEvent | None:
        """The first pair's open contact record, else any open one (None in free flight)."""
        return next((r for r in self.records if r is not None), None)

    @cached_property
    def buffer(self) -> np.ndarray:
        """The kernels' contacts buffer of this phase (:func:`flexbeam.kernels.pack_contacts`)."""
        from ..kernels import pack_contacts

        return pack_contacts([int(m) for m in self.modes], self.parameters, *self.baumgarte, friction=self.friction)

    def with_friction(self, friction: np.ndarray) -> Phase:
        """A copy with the friction rows ``friction`` (the same pairs, modes and records: a friction switch), built
        field by field (``dataclasses.replace`` costs ~10 us, and a long frictional run switches thousands of
        times)."""
        return Phase(self.name, self.modes, self.events, self.sample_step, self.parameters, self.records,
                     self.baumgarte, self.max_step, self.max_step_until, friction)  # fmt: skip

    def with_friction_row(self, pair: int, row: np.ndarray) -> Phase:
        """A copy with pair ``pair``'s friction row switched to ``row`` (a stop or a stick's end)."""
        friction = self.friction.copy()
        friction[pair] = row
        return self.with_friction(friction)

    def with_pair(self, pair: int, mode: ContactMode, parameters=None, record: ContactEvent | None = None,
                  **changes) -> Phase:  # fmt: skip
        """A copy with pair ``pair`` in ``mode`` (its law ``parameters``, its contact ``record``)."""
        modes = list(self.modes)
        modes[pair] = mode
        params = self.parameters.copy()
        params[pair] = 0.0 if parameters is None else parameters
        records = list(self.records)
        records[pair] = record
        return replace(self, modes=tuple(modes), parameters=params, records=tuple(records), **changes)
