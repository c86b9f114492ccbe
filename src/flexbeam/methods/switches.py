"""The switches the compiled stepper takes inside a phase (``kernels/src/switching.c``), as an impact method offers
and books them: which rules apply to a phase (:meth:`KernelSwitches.switch_coef`), and the phase -- with its contact
records, or without (what a failure names) -- after each switch the stepper reports.  CCFM's Coulomb switches are
these defaults; CCM's single-pair onsets and releases are :class:`~flexbeam.methods.ccm.CCM`'s."""

from __future__ import annotations

import numpy as np

from ..integrate.loop import Switch
from ..integrate.phases import Phase


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
