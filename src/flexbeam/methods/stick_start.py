"""Does a stick hold where it starts?  Coulomb's stick test at a slip's stop, before the stick phase is entered.

A slip that stops enters a stick (:func:`flexbeam.methods.coulomb.stop`), held by the tangential multiplier lambda_t
of its row J_t z'' = -gamma_t (Pfeiffer & Glocker, Multibody Dynamics with Unilateral Contacts, Wiley 1996, Ch. 5;
Glocker & Pfeiffer, Nonlinear Dynamics 7 (1995) 471-497).  Where the multiplier that would hold it already exceeds
mu_s F there, the stick cannot start: the kernel's unstick event (``kernels/src/friction.c``, fb_find_unstick) would
end the stick phase before its first step, and the pair would slip on against lambda_t with the kinetic force
(:func:`flexbeam.methods.coulomb.unstick`).  :func:`holding` decides this at the stop instead, with the same
multiplier -- that of the constrained accelerations at (t, y) with every sticking holder's row, the law's normal
forces and the slipping pairs' kinetic forces, evaluated by the kernel (``kernels/src/rhs.c`` fb_contact_forces,
:meth:`~flexbeam.model.system.BeamSystem.contact_forces`) -- the same test, mu_s (F + the followers' F) - abs(lambda_t)
against the band of the multiplier's accuracy, and the same switch, so that the run is the one it was without the
stick phase of zero length (a Python transition and a restart of the collocation saved at each).  The compiled
stepper applies the same test to a stop it takes itself (``kernels/src/friction_switch.c``, one sticking pair, the
band of :func:`breaking` (:func:`band`) handed to it by :meth:`flexbeam.methods.ccfm.CCFM.kernel_switches`).
"""

from __future__ import annotations

import numpy as np

from ..integrate.phases import ContactMode, EventKind, Phase
from . import coulomb

#: the stick margin's band, max(UNSTICK_RTOL rtol, UNSTICK_NOISE) of the multipliers' scale: the kernel's unstick
#: event's (``kernels/src/friction.c``), the collocated multiplier's own accuracy
UNSTICK_RTOL = 100.0
UNSTICK_NOISE = 1e-7


def band(rtol: float) -> float:
    """The stick margin's band as a share of the multipliers' scale: max(UNSTICK_RTOL rtol, UNSTICK_NOISE)."""
    return max(UNSTICK_RTOL * rtol, UNSTICK_NOISE)


def breaking(phase: Phase, F: np.ndarray, Ft: np.ndarray, rtol: float) -> tuple[int, EventKind] | None:
    """The first holder of ``phase`` (by pair, as the kernel's earliest event) whose stick cannot hold under the normal
    forces ``F`` and tangential multipliers ``Ft``: abs(lambda_t) beyond mu_s times its and its followers' normal
    forces by more than the band (UNSTICK_*) of the largest of them and of the phase's multipliers; with the event
    the kernel would end its stick on (UNSTICK_PLUS / _MINUS by the sign of lambda_t).  None if every stick holds."""
    held, mus = phase.friction[:, 1].tolist(), phase.friction[:, 2].tolist()
    F, Ft = F.tolist(), Ft.tolist()
    holders = [k for k, h in enumerate(held) if h == 1.0]
    scale = max([abs(Ft[k]) for k in holders] + [abs(f) for f, m in zip(F, phase.modes) if m == ContactMode.CONSTRAINT])
    share = band(rtol)
    for k in holders:
        Fs = F[k] + sum(f for f, h in zip(F, held) if h == 2.0 + k)
        if mus[k] * Fs - abs(Ft[k]) + share * max(scale, mus[k] * Fs, abs(Ft[k])) < 0.0:
            return k, EventKind.UNSTICK_PLUS if Ft[k] > 0.0 else EventKind.UNSTICK_MINUS
    return None


def holding(method, phase: Phase, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
    """The phase and state after ``phase`` is entered at (t, y) with its sticks: settled as every friction switch
    of ``method`` is (:meth:`~flexbeam.methods.base.ImpactMethod.settled`), then each holder whose stick cannot hold
    there slips on (:func:`breaking`, :func:`~flexbeam.methods.coulomb.unstick`), one at a time as the kernel's
    events would end them, settled and its multipliers evaluated anew after each switch.  ``method``: the impact
    method (its system, case, :meth:`~flexbeam.methods.base.ImpactMethod.phase` and ``settled``)."""
    system, rtol = method.system, method.case.solver.fast_rtol
    phase, y = method.settled(phase, t, y)
    while phase.friction is not None and 1.0 in phase.friction[:, 1].tolist():
        forces = system.contact_forces(t, y, phase.buffer)
        broken = None if forces is None else breaking(phase, *forces, rtol)
        if broken is None:
            break
        pair, event = broken
        friction = coulomb.grouped(system, t, y, coulomb.unstick(system, phase, event, pair, t, y), phase.modes)
        phase, y = method.settled(method.phase(phase.modes, phase.parameters, phase.records, friction), t, y)
    return phase, y
