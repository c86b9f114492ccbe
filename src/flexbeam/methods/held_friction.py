"""Coulomb friction at held contacts: CCM's constrained phase and IMM's resting phase share it.

A pair held on its obstacle by its unilateral constraint (its normal force the multiplier lambda_n: CCM's contact
after its e = 0 onset, IMM's resting contact once its impacts have died out below ``solver.rest_velocity``) slips
or sticks with the rows, events and switches of :mod:`flexbeam.methods.coulomb` (Pfeiffer & Glocker, Multibody
Dynamics with Unilateral Contacts, Wiley 1996, Ch. 5; Glocker & Pfeiffer, Nonlinear Dynamics 7 (1995) 471-497):

* **slip**: the constraint force acts along (J_n + sigma J_t)^T lambda_n, sigma = -mu_k sign(v_t), until v_t
  reaches zero (a located STOP);
* **stick**: v_t = 0 held by a second multiplier lambda_t along J_t until abs(lambda_t) reaches mu_s lambda_n (a
  located UNSTICK: it slips on in the direction the load pushes) or lambda_n turns tensile (RELEASE);
* **Painlevé**: a slip whose effective inverse mass a = W_nn + sigma W_nt is <= 0 at its start, or falls to
  :data:`~flexbeam.methods.painleve.SHARE` W_nn during it (a located PAINLEVE event), is resolved by a tangential
  impact that never adds energy, with a warning naming it (:mod:`flexbeam.methods.painleve`).

A pair whose held contact starts gets the friction row of its state right after the onset's (frictional) impulse
(:func:`~flexbeam.methods.coulomb.onset_row`); a pair held before keeps its row.  After every switch a held pair whose
multiplier would pull under the phase's friction leaves it, and after an impulse one that moves off its obstacle
(:meth:`leaving`).
"""

from __future__ import annotations

import numpy as np

from ..contact.laws import threlfall
from ..integrate.loop import Stop
from ..integrate.phases import ContactMode, EventKind, Phase
from . import coulomb, painleve
from .base import ImpactMethod


class HeldFriction(ImpactMethod):
    """An impact method whose held (CONSTRAINT) pairs carry Coulomb friction: CCM and IMM."""

    @property
    def rough(self) -> bool:
        """Does some pair carry Coulomb friction?"""
        return any(p.frictional for p in self.system.contact.pairs)

    def held_phase(self, phase: Phase, t: float, y: np.ndarray, modes, records, onsets
                   ) -> tuple[Phase, np.ndarray]:  # fmt: skip
        """The phase after an impact from ``phase`` with the pairs in ``modes`` (their contact ``records``), and the
        state: without friction the plain phase at (t, y); with friction the pairs held from ``onsets`` on get their
        onset rows, those held before keep theirs, the others none; then the Painlevé slips are resolved
        (:meth:`resolved`) and the pairs that leave are freed (:meth:`leaving`)."""
        if not self.rough:
            return self.phase(modes, phase.parameters, records), y
        stuck = [k for k in onsets if self.system.contact.pairs[k].frictional]
        if stuck and not self.locates_friction:
            raise Stop(
                "failed",
                f"contact.friction: pair {stuck[0]} comes to rest at t = {t:.9g} s, and a resting contact's Coulomb "
                "friction runs on the exponential integrator only (rigid obstacle, solver.integrator = "
                "'exponential'); or friction = 0",
            )
        friction = coulomb.rows(phase, self.system.pairs)
        for k, m in enumerate(modes):
            if m != ContactMode.CONSTRAINT:
                friction[k] = 0.0
            elif k in onsets:
                friction[k] = coulomb.onset_row(self.system, t, y, k)
        friction = coulomb.grouped(self.system, t, y, friction, modes)
        phase, y = self.resolved(self.phase(modes, phase.parameters, records, friction), t, y)
        return self.leaving(phase, t, y), y

    def transition(self, phase: Phase, event: EventKind, t: float, y: np.ndarray, pair: int = 0
                   ) -> tuple[Phase, np.ndarray]:  # fmt: skip
        """As every method's (:meth:`ImpactMethod.transition`); with friction a PAINLEVE event, or a slip starting
        with a <= 0, is resolved by a tangential impact, and the pairs that leave are freed (:meth:`settled`; a
        stop's phase is settled already, before its sticks are tested)."""
        if event == EventKind.PAINLEVE:
            return self.resolved(phase, t, y, pair)
        phase, y = super().transition(phase, event, t, y, pair)
        if event == EventKind.STOP:
            return phase, y
        phase, y = self.settled(phase, t, y)
        if event in (EventKind.UNSTICK_PLUS, EventKind.UNSTICK_MINUS) and coulomb.state(phase, pair) == 2:
            phase = self.lifted(phase, t, y, pair, event)  # stuck again where its stick just ended
        return phase, y

    def settled(self, phase: Phase, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        """``phase`` at (t, y) with its Painlevé slips resolved (:meth:`resolved`) and the pairs whose multiplier
        would pull under the switched friction freed (:meth:`leaving`, ``moved=False``: a switch leaves the velocities
        as they are, and a tangential impact's are tested where it is resolved); as it is without friction."""
        if phase.friction is None:
            return phase, y
        phase, y = self.resolved(phase, t, y)
        return self.leaving(phase, t, y, moved=False), y

    def resolved(self, phase: Phase, t: float, y: np.ndarray, pair: int | None = None) -> tuple[Phase, np.ndarray]:
        """The phase and state once every held pair slipping with a <= 0 (and ``pair``, whose a reached zero) has had
        its tangential impact (:mod:`flexbeam.methods.painleve`): it then sticks or slips per mu_s."""
        if phase.friction is None:
            return phase, y
        friction = phase.friction.copy()
        hit = False
        for k, m in enumerate(phase.modes):
            sigma = friction[k, 0]
            if m != ContactMode.CONSTRAINT or sigma == 0.0:
                continue
            if friction[k, 1] == -1.0:  # Threlfall's regularised law: its coefficient at the slip velocity now
                sigma = float(threlfall(sigma, friction[k, 2], self.system.tangent(t, y, k)[2]))
            elif friction[k, 1] != 0.0:  # (sticking)
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
        friction = coulomb.grouped(self.system, t, y, friction, phase.modes)
        return self.leaving(self.phase(phase.modes, phase.parameters, phase.records, friction), t, y), y

    def lifted(self, phase: Phase, t: float, y: np.ndarray, pair: int, event: EventKind) -> Phase:
        """``phase`` after the stick of ``pair`` ended at (t, y) (``event``, the kernel's UNSTICK) and the slip it
        began, a Painlevé slip (a <= SHARE W_nn the way the load drives it), was stuck again by its tangential impact:
        the pair lifts off where its free normal acceleration separates it (a warning), and the run stops where it
        presses it in (:mod:`flexbeam.methods.painleve`, *Neither stick nor slip*); as it is when the slip was not a
        Painlevé one.  (Before, the kernel ended such a stick at once and the slip's resolution stuck it again, until
        "events keep recurring without progress".)"""
        direction = -1.0 if event == EventKind.UNSTICK_PLUS else 1.0
        mu_k = self.system.contact.pairs[pair].friction
        a, wnn = painleve.slip_inverse_mass(self.system, t, y, pair, -mu_k * direction)
        if a > painleve.SHARE * wnn:
            return phase
        bn = self.gap_acceleration(t, y, pair, self.without(phase, pair).buffer)
        if bn <= 0.0:
            raise Stop("failed", painleve.inconsistent(t, pair, a, bn))
        painleve.warn_lift(t, pair, bn)
        return self.end_contact(phase, pair, t, y)

    def leaving(self, phase: Phase, t: float, y: np.ndarray, moved: bool = True) -> Phase:
        """``phase`` without the held pairs that leave the obstacle at (t, y): those moving off it (delta' above
        ``grazing_speed``, as a tangential impact may leave them: tested only if the velocities ``moved``) or whose
        multiplier under the phase's friction would pull (a stick's lambda_n has no reason to share the frictionless
        one's sign).  A held pair's delta' is the constraint's drift where no impulse moved it (its Baumgarte
        recovery of a penetration, ~alpha delta, the collocation's 1e-8 m/s): taken for a lift-off after a friction
        switch, it freed both ends of a bar resting on a floor, which fell back at once, a contact per switch."""
        F = self.system.rhs(t, y, phase.buffer)[1]
        for k, m in enumerate(phase.modes):
            if m != ContactMode.CONSTRAINT:
                continue
            if F[k] < 0.0 or (moved and self.gap_event(t, y, k)[1] > self.grazing_speed):
                phase = self.end_contact(phase, k, t, y)
        return phase
