"""CCFM: continuous contact force method.

While a pair's gap delta is closed the contact force F = L(delta)[F_k + F_d] of its law
(:mod:`flexbeam.contact.laws`) acts on the beam as the generalised force J^T F (Duan, Zhang & Hong 2013,
Sec. 3.1); several pairs in contact add their forces.  A pair's contact starts when its delta crosses zero
downwards and ends when it crosses zero upwards; both instants are located as events.  The damping reference
velocity d'_0 of the hysteresis laws is the approach speed at the onset of each contact, and the linear law's
effective mass 1/(J M^-1 J^T) is taken there too.

While a contact is an impact its step is bounded by t_c / CONTACT_STEPS, t_c the rigid Hertz contact duration at
its onset speed (:meth:`~flexbeam.methods.base.ImpactMethod.contact_time`), so that the force pulse is resolved;
once it has lasted RESTING_DURATIONS = 20 t_c (the impacts of every preset last at most 7.4 t_c) the beam rests
on the obstacle under its law and the bound lifts: the same law, the same state, the step set by the error
control alone.  The force at rest is the static one (the seed beam: F_s = m g L / (2 x_P) and
d_s = (F_s / K)^(1/n), ``tests/validation/test_resting_contact.py``) plus whatever the beam's modes still ring.

With ``contact.friction`` each pair in contact also slips or sticks under Coulomb's law, its switches located as
events (:mod:`flexbeam.methods.coulomb`).
"""

from __future__ import annotations

import numpy as np

from ..integrate.phases import ContactMode, Phase
from ..kernels import SWITCH_FRICTION
from . import coulomb, stick_start
from .base import ImpactMethod


class CCFM(ImpactMethod):
    """Continuous contact force method."""

    name = "ccfm"

    def on_impact(self, phase: Phase, t: float, y: np.ndarray, pairs: list[int]) -> tuple[Phase, np.ndarray]:
        modes, params, records = list(phase.modes), phase.parameters.copy(), list(phase.records)
        friction = coulomb.rows(phase, self.system.pairs)
        for k in pairs:
            ev = self.new_contact(t, y, k)
            m_eff = self.system.effective_mass(t, y, k)
            law = self.system.contact.pairs[k].law
            params[k] = law.parameters(-ev.velocity_before, m_eff)
            ev.time_scale = self.contact_time(-ev.velocity_before, m_eff, float(params[k][0]), float(params[k][1]))
            modes[k], records[k] = ContactMode.FORCE, ev
            friction[k] = coulomb.onset_row(self.system, t, y, k)
        return self.phase(modes, params, records, coulomb.grouped(self.system, t, y, friction)), y

    def kernel_switches(self) -> np.ndarray | None:
        """[SWITCH_FRICTION, band, REST_SPEED, mu_k per pair, mu_s per pair] with Coulomb friction at some pair: the
        compiled stepper takes a stop or the end of a stick itself where :meth:`transition` would decide it alone --
        pairs under their laws, at most one sticking (``kernels/src/friction_switch.c``: the same rows from the same
        numbers, so the run is the same to the bit) -- and saves the phase loop's round trip.  The band is
        :func:`flexbeam.methods.stick_start.band`, the stick test's; None without friction or with Threlfall's
        law."""
        pairs = self.system.contact.pairs
        if not any(p.frictional and p.friction_model != "threlfall" for p in pairs):
            return None
        band = stick_start.band(self.case.solver.fast_rtol)
        mu_k = [p.friction if p.frictional else 0.0 for p in pairs]
        mu_s = [p.friction_static if p.frictional else 0.0 for p in pairs]
        return np.array([SWITCH_FRICTION, band, coulomb.REST_SPEED, *mu_k, *mu_s], float)
