"""CCM: contact constraint method (Duan, Zhang & Hong 2013, Sec. 3.2).

At contact onset the impulse-momentum map with e = 0 makes the normal velocities of the impacting pairs zero
(generalised velocities jump, coordinates do not; several pairs at once through the impact LCP of
:mod:`flexbeam.methods.impulse`); each closed contact is then a unilateral constraint delta_k(q) = 0 whose
multiplier lambda_k is its contact force, found from the index-1 DAE [M J^T; J 0][z''; -lambda] = [Q; -J'z' -
2 alpha delta' - beta^2 delta] over the held pairs (see :meth:`ImpactMethod.phase`).  The held set is the one
whose multipliers are all compressive (:meth:`ImpactMethod.held_set`); a pair's contact ends when its lambda
crosses zero towards tension (a located event); it is then free until its gap closes again, and every later
contact is treated the same way.

**Coulomb friction** (``contact.friction``, on the exponential integrator).  The onset's e = 0 impulse is frictional
(:func:`~flexbeam.methods.impulse.impulse_jump`: Stronge's process for one pair, the frictional impact LCP for
several), after which the held pair slips or
sticks as under CCFM (:mod:`flexbeam.methods.coulomb`, the same rows, events and switches), its normal force being
the multiplier:

* **slip**: the constraint force acts along (J_n + sigma J_t)^T lambda_n, sigma = -mu_k sign(v_t) fixed for the
  phase -- the non-symmetric DAE [M, (J_n + sigma J_t)^T; J_n, 0] -- until v_t reaches zero (a located STOP);
* **stick**: the tangential constraint v_t = 0 is held too, by a second multiplier lambda_t along J_t, until
  abs(lambda_t) reaches mu_s lambda_n (a located UNSTICK: it slips on in the direction the load pushes) or lambda_n
  turns tensile (RELEASE).  A stop enters the stick unless its ratio abs(lambda_t) / lambda_n already exceeds
  mu_s there; then the slip reverses at once (:mod:`flexbeam.methods.stick_start`).

Friction dissipates -(sigma lambda_n + lambda_t) v_t >= 0, booked with ``dissipated_energy``.  **Painlevé**: a slip
whose effective inverse mass a = W_nn + sigma W_nt is <= 0 -- at a slip phase's start, or reached during the slip
(a located PAINLEVE event) -- is resolved by a tangential impact, which never adds energy, with a warning naming it
(:mod:`flexbeam.methods.painleve`).  IMM's resting contact carries the same friction: the code is one,
:class:`~flexbeam.methods.held_friction.HeldFriction`.
"""

from __future__ import annotations

import numpy as np

from ..integrate.loop import Switch
from ..integrate.phases import ContactMode, EventKind, Phase
from ..kernels import SWITCH_HELD
from .held_friction import HeldFriction
from .impulse import Jump


class CCM(HeldFriction):
    """Contact constraint method."""

    name = "ccm"
    #: (measured: tip-wall with friction lands 253 times within 0.3 s, its undamped modes ringing against the held
    #: pair, then rests held -- a guard of 200 stops it at 0.17 s; CCFM runs it to its end with 65-69 contacts)
    chatter_cause = "its modes ringing against the held contact"

    def on_impact(self, phase: Phase, t: float, y: np.ndarray, pairs: list[int]) -> tuple[Phase, np.ndarray]:
        jump = self.held_impact(phase, t, y, pairs, 0.0)
        events = dict(zip(pairs, self.log_jump(t, jump, pairs)))
        held_before = [k for k, m in enumerate(phase.modes) if m == ContactMode.CONSTRAINT]
        opened = self.opening(t, jump.y, held_before)
        held = self.held_set(t, jump.y, [k for k in [*held_before, *pairs] if k not in opened], phase)
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
        return self.held_phase(phase, t, jump.y, modes, records, [k for k in pairs if k in held])

    # the contacts the compiled stepper takes itself ---------------------------------------------------------------
    def switch_coef(self, phase: Phase) -> np.ndarray | None:
        """Without Coulomb friction at any pair, the compiled stepper takes a single pair's contact itself where
        :meth:`transition` would decide it alone (``kernels/src/held_switch.c``: its e = 0 onset with the Python
        map's bits, the held test as :meth:`held_set`'s, its release), and saves the phase loop's round trip:
        [SWITCH_HELD, grazing_speed, gap_tolerance, simultaneity, the contacts left under solver.max_contacts, the
        free and the held phase's step bounds, the first step] (the stepper puts in its own bounds and first step);
        with friction the friction switches' (none: :meth:`kernel_switches`)."""
        if self.rough:
            return super().switch_coef(phase)
        left = self.case.solver.max_contacts - len(self.contacts)
        return np.array([SWITCH_HELD, self.grazing_speed, self.gap_tolerance, self.simultaneity, left, np.inf,
                         self.held_step(), np.nan])  # fmt: skip

    def switched_phase(self, phase: Phase, switch: Switch) -> Phase:
        if switch.event not in (EventKind.IMPACT, EventKind.RELEASE):
            return super().switched_phase(phase, switch)
        if switch.event == EventKind.RELEASE or not switch.row[0]:
            return self.free_phase()
        modes = list(phase.modes)
        modes[switch.pair] = ContactMode.CONSTRAINT
        return self.phase(modes, phase.parameters, phase.records)

    def kernel_switched(self, phase: Phase, switch: Switch) -> tuple[Phase, np.ndarray]:
        """A release: the record ends (as :meth:`end_contact`, with the gap's rate the kernel took there).  An onset:
        the e = 0 jump the kernel took (the compiled map, :meth:`held_impact`'s bits: P, v-, v+, T-, T+ and y+ in
        the switch's record), its record logged, and the pair held or -- its multiplier pulling at once -- its record
        ended there (as :meth:`on_impact`)."""
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
            rec.velocity_after = self.gap_event(t, jump.y, k)[1]
        return self.phase(modes, phase.parameters, records), jump.y
