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

from ..integrate.phases import ContactMode, Phase
from ..kernels import SWITCH_HELD
from .held_friction import HeldFriction
from .switches import PairSwitches


class CCM(PairSwitches, HeldFriction):
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

    # the contacts the compiled stepper takes itself (methods/switches.py PairSwitches) -----------------------------
    switch_rule = SWITCH_HELD
