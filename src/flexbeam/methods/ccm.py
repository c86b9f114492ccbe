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
  turns tensile (RELEASE).  A stop enters the stick, which ends at once (the slip reverses) if its ratio
  abs(lambda_t) / lambda_n exceeds mu_s.

Friction dissipates -(sigma lambda_n + lambda_t) v_t >= 0, booked with ``dissipated_energy``.  **Painlevé**: a slip
whose effective inverse mass a = W_nn + sigma W_nt is <= 0 -- at a slip phase's start, or reached during the slip
(a located PAINLEVE event) -- is resolved by a tangential impact, which never adds energy, with a warning naming it
(:mod:`flexbeam.methods.painleve`).
"""

from __future__ import annotations

import numpy as np

from ..integrate.phases import ContactMode, EventKind, Phase
from . import coulomb, painleve
from .base import ImpactMethod


class CCM(ImpactMethod):
    """Contact constraint method."""

    name = "ccm"

    @property
    def rough(self) -> bool:
        """Does some pair carry Coulomb friction?"""
        return any(p.frictional for p in self.system.contact.pairs)

    def on_impact(self, phase: Phase, t: float, y: np.ndarray, pairs: list[int]) -> tuple[Phase, np.ndarray]:
        jump = self.held_impact(phase, t, y, pairs, 0.0)
        events = dict(zip(pairs, self.log_jump(t, jump, pairs)))
        held_before = [k for k, m in enumerate(phase.modes) if m == ContactMode.CONSTRAINT]
        opened = self.opening(t, jump.y, held_before)
        held = self.held_set(t, jump.y, [k for k in [*held_before, *pairs] if k not in opened], phase)
        modes, records = list(phase.modes), list(phase.records)
        friction = coulomb.rows(phase, self.system.pairs)
        for k in set(held_before) | set(pairs):
            rec = events.get(k, records[k])
            if k in held:
                modes[k], records[k] = ContactMode.CONSTRAINT, rec
                if k in pairs:
                    friction[k] = coulomb.onset_row(self.system, t, jump.y, k)
                continue
            # the closed contact would pull: the pair leaves at once with zero normal velocity
            rec.end = t
            rec.velocity_after = self.gap_event(t, jump.y, k)[1]
            modes[k], records[k], friction[k] = ContactMode.NONE, None, 0.0
        if not self.rough:
            return self.phase(modes, phase.parameters, records), jump.y
        friction = coulomb.grouped(self.system, t, jump.y, friction)
        phase, y = self.resolved(self.phase(modes, phase.parameters, records, friction), t, jump.y)
        return self.leaving(phase, t, y), y

    def transition(self, phase: Phase, event: EventKind, t: float, y: np.ndarray, pair: int = 0
                   ) -> tuple[Phase, np.ndarray]:  # fmt: skip
        """As every method's (:meth:`ImpactMethod.transition`); with friction a PAINLEVE event, or a slip starting
        with a <= 0, is resolved by a tangential impact (:meth:`resolved`)."""
        if event == EventKind.PAINLEVE:
            return self.resolved(phase, t, y, pair)
        phase, y = super().transition(phase, event, t, y, pair)
        if phase.friction is None:
            return phase, y
        phase, y = self.resolved(phase, t, y)
        return self.leaving(phase, t, y), y

    def resolved(self, phase: Phase, t: float, y: np.ndarray, pair: int | None = None) -> tuple[Phase, np.ndarray]:
        """The phase and state once every held pair slipping with a <= 0 (and ``pair``, whose a reached zero) has had
        its tangential impact (:mod:`flexbeam.methods.painleve`): it then sticks or slips per mu_s."""
        if phase.friction is None:
            return phase, y
        friction = phase.friction.copy()
        hit = False
        for k, m in enumerate(phase.modes):
            sigma = friction[k, 0]
            if m != ContactMode.CONSTRAINT or sigma == 0.0 or friction[k, 1] != 0.0:
                continue
            a, wnn = painleve.slip_inverse_mass(self.system, t, y, k, sigma)
            if a > painleve.SHARE * wnn and k != pair:
                continue
            painleve.warn(t, k, a)
            y, Pt, Pn = painleve.tangential_impact(self.system, t, y, k)
            rec = phase.records[k]
            if rec is not None:
                rec.tangential_impulse = (0.0 if np.isnan(rec.tangential_impulse) else rec.tangential_impulse) + Pt
                rec.jump_impulse = (0.0 if np.isnan(rec.jump_impulse) else rec.jump_impulse) + Pn
            friction[k] = coulomb.onset_row(self.system, t, y, k)
            hit = True
        if not hit:
            return phase, y
        friction = coulomb.grouped(self.system, t, y, friction)
        return self.leaving(self.phase(phase.modes, phase.parameters, phase.records, friction), t, y), y

    def leaving(self, phase: Phase, t: float, y: np.ndarray) -> Phase:
        """``phase`` without the held pairs that leave the obstacle at (t, y): those moving off it (delta' above
        ``grazing_speed``, as a tangential impact may leave them) or whose multiplier under the phase's friction
        would pull (a stick's lambda_n has no reason to share the frictionless one's sign)."""
        F = self.system.rhs(t, y, phase.buffer)[1]
        for k, m in enumerate(phase.modes):
            if m == ContactMode.CONSTRAINT and (self.gap_event(t, y, k)[1] > self.grazing_speed or F[k] < 0.0):
                phase = self.end_contact(phase, k, t, y)
        return phase
