"""The switches the compiled stepper takes inside a phase (``kernels/src/switching.c``), as an impact method offers
and books them: which rules apply to a phase (:meth:`KernelSwitches.switch_coef`), and the phase -- with its contact
records, or without (what a failure names) -- after each switch the stepper reports.  CCFM's Coulomb switches are
these defaults; CCM's and IMM's contacts on one pair (an onset or a rebound, a held pair's release) are
:class:`PairSwitches`'."""

from __future__ import annotations

import numpy as np

from ..integrate.loop import Switch
from ..integrate.phases import ContactMode, EventKind, Phase
from .impulse import Jump


class KernelSwitches:
    """The compiled stepper's switches of an impact method (a mixin of
    :class:`~flexbeam.methods.base.ImpactMethod`, whose ``transition`` would decide each of them alike)."""

    def kernel_switches(self) -> np.ndarray | None:
        """What the compiled stepper needs to take this method's friction switches itself (``coef`` of
        ``kernels/src/friction_switch.c``), or None where the method's ``transition`` takes them all: CCFM's, see
        :meth:`flexbeam.methods.ccfm.CCFM.kernel_switches`."""
        return None

    def switch_coef(self, phase: Phase) -> np.ndarray | None:
        """The ``coef`` of the switches the compiled stepper takes inside ``phase`` (``kernels/src/switching.c``), or
        None where the method's ``transition`` takes them all: with friction rows :meth:`kernel_switches`'s (built
        once a run)."""
        if phase.friction is None:
            return None
        if "_friction_coef" not in self.__dict__:
            self._friction_coef = self.kernel_switches()
        return self._friction_coef

    def switched_phase(self, phase: Phase, switch: Switch) -> Phase:
        """The phase after a ``switch`` the stepper took inside ``phase``, without touching the contact records (what
        a failure after it names): a friction switch's row, with the name, step bound, sample step and events the
        method's ``phase`` would give it."""
        return phase.with_friction_row(switch.pair, switch.row)

    def kernel_switched(self, phase: Phase, switch: Switch) -> tuple[Phase, np.ndarray]:
        """The phase and state after a ``switch`` the stepper took (:meth:`switched_phase`, its records logged)."""
        return self.switched_phase(phase, switch), switch.y


class PairSwitches(KernelSwitches):
    """CCM's and IMM's contacts on one frictionless pair taken by the compiled stepper where their ``transition``
    would decide alone (``kernels/src/held_switch.c``): an impact from free flight -- CCM's e = 0 onset with the held
    test as ``held_set``'s, IMM's rebound (:attr:`switch_rule`) -- and a held pair's release, with the Python impulse
    map's bits; the phase loop's round trip is saved.  A mixin before the method's class (it uses the method's
    ``rough``, ``held_step``, ``log_jump``, ``end_contact``, ``phase``, ``free_phase``)."""

    #: ``kernels.SWITCH_HELD`` (CCM) or ``kernels.SWITCH_REBOUND`` (IMM)
    switch_rule: float

    def switch_coef(self, phase: Phase) -> np.ndarray | None:
        """Without Coulomb friction at any pair: [switch_rule, grazing_speed, gap_tolerance, simultaneity, the
        contacts left under solver.max_contacts, the free and the held phase's step bounds, the first step] (the
        stepper puts in its own bounds and first step) and :meth:`rebound_coef`; with friction the friction
        switches' (none: :meth:`kernel_switches`)."""
        if self.rough:
            return super().switch_coef(phase)
        left = self.case.solver.max_contacts - len(self.contacts)
        return np.array([self.switch_rule, self.grazing_speed, self.gap_tolerance, self.simultaneity, left, np.inf,
                         self.held_step(), np.nan, *self.rebound_coef()])  # fmt: skip

    def rebound_coef(self) -> list[float]:
        """What the rule takes beyond the common coef (IMM's rebound: its rest velocity, rise limit, restitutions)."""
        return []

    def switched_phase(self, phase: Phase, switch: Switch) -> Phase:
        if switch.event not in (EventKind.IMPACT, EventKind.RELEASE):
            return super().switched_phase(phase, switch)
        if switch.event == EventKind.RELEASE or not switch.row[0]:
            return self.free_phase()
        modes = list(phase.modes)
        modes[switch.pair] = ContactMode.CONSTRAINT
        return self.phase(modes, phase.parameters, phase.records)

    def kernel_switched(self, phase: Phase, switch: Switch) -> tuple[Phase, np.ndarray]:
        """A release: the record ends (as ``end_contact``, with the gap's rate the kernel took there).  An impact: the
        jump the kernel took (the compiled map, ``held_impact``'s bits: P, v-, v+, T-, T+ and y+ in the switch's
        record), its record logged, and the pair held (``row[0]``, CCM's onset) or its record ended there
        (:meth:`left_at_once`), as ``on_impact`` does."""
        if switch.event not in (EventKind.IMPACT, EventKind.RELEASE):
            return super().kernel_switched(phase, switch)
        t, k, out = switch.t, switch.pair, switch.record
        if switch.event == EventKind.RELEASE:
            return self.end_contact(phase, k, t, switch.y, float(out[5])), switch.y
        jump = Jump(switch.y_after, out[0:1], out[1:2], out[2:3], float(out[3]), float(out[4]))
        (rec,) = self.log_jump(t, jump, [k])
        modes, records = list(phase.modes), list(phase.records)
        if switch.row[0]:
            modes[k], records[k] = ContactMode.CONSTRAINT, rec
        else:
            rec.end = t
            rec.velocity_after = self.left_at_once(t, jump, k)
        return self.phase(modes, phase.parameters, records), jump.y

    def left_at_once(self, t: float, jump: Jump, pair: int) -> float:
        """The end velocity of a record that ends at its impact: CCM's pair pulling at once leaves with the gap's rate
        after the e = 0 jump (as ``on_impact``)."""
        return self.gap_event(t, jump.y, pair)[1]
