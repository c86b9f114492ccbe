"""What the three impact methods share: free flight, the impact event, the contact log.

An impact method (:class:`~flexbeam.integrate.loop.PhaseMethod`) gives the phase loop the first phase and, at
every event a phase ends on, the next phase and the state after it (a velocity jump for CCM's onset and IMM).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..contact.hertz import rigid_hertz_impact
from ..integrate.loop import Stop
from ..model.system import BeamSystem
from ..parameters.case import Case
from ..phases import ContactMode, EventKind, Phase
from ..solution import ContactEvent
from .impulse import Jump

#: steps per (estimated) contact duration at least: a contact phase's step is bounded by t_c / CONTACT_STEPS
CONTACT_STEPS = 8


@dataclass
class ImpactMethod:
    """Base of CCFM, CCM and IMM: the free phase, the impact event and the transitions back to free flight.

    Subclasses say what an impact starts (:meth:`on_impact`).
    """

    system: BeamSystem
    case: Case
    contacts: list[ContactEvent] = field(default_factory=list)

    name = "base"
    #: onsets with |delta'| below this are grazing touches, not impacts [m/s]
    grazing_speed = 1e-9
    #: a gap this small counts as closed at the start of a run [m]
    gap_tolerance = 1e-12

    def __post_init__(self) -> None:
        w = self.case.solver.baumgarte_frequency
        self.baumgarte = np.array([w, w, 0.0, 0.0])

    # phases -----------------------------------------------------------------
    def free_phase(self) -> Phase:
        """Unimpact motion until the gap closes."""
        return Phase("free", ContactMode.NONE, (EventKind.IMPACT,), self.case.solver.sample_step)

    def constrained_phase(self, contact: ContactEvent, name: str = "constrained") -> Phase:
        """Contact held closed by the unilateral constraint until its multiplier turns tensile.

        Baumgarte stabilisation (Baumgarte 1972; Hairer & Wanner, Solving ODEs II, Sec. VII.2) with
        alpha = beta = ``solver.baumgarte_frequency``.  A CCM contact is sampled at the contact spacing, IMM's
        resting contact at the free one.  The phase starts consistent (delta = 0 at the located event,
        delta' = 0 after the e = 0 jump), so the terms only damp the integration drift.
        """
        s = self.case.solver
        step = s.contact_sample_step if name == "constrained" else s.sample_step
        return Phase(name, ContactMode.CONSTRAINT, (EventKind.RELEASE,), step, self.baumgarte, contact)

    # events -----------------------------------------------------------------
    def gap_event(self, t: float, y: np.ndarray) -> tuple[float, float]:
        """(delta, delta') of the contact point."""
        delta, vn, _, _ = self.system.gap(t, y)
        return delta, vn

    def gap_acceleration(self, t: float, y: np.ndarray) -> float:
        """delta'' under free motion (no contact force) at state y."""
        sysm = self.system
        _, _, gamma, J = sysm.gap(t, y)
        yd = sysm.rhs(t, y)[0]
        n = sysm.n
        if sysm.prescribed:
            zdd = np.concatenate(([sysm.drive.motion(t)[2]], yd[n : 2 * n]))
        else:
            zdd = yd[n + 1 : 2 * n + 2]
        if sysm.compliant:  # s'' of the support coordinate
            zdd = np.append(zdd, yd[sysm.support_index + 1])
        return float(J @ zdd + gamma)

    def approaching(self, t: float, y: np.ndarray, located: bool = False) -> bool:
        """Does a contact start here?  The gap is closed and P moves into the obstacle, or rests on it
        (|delta'| below ``grazing_speed``) while free motion would press it in.

        ``located``: the gap's zero was just located as an event, so it is zero to within round-off and only
        the motion decides.
        """
        delta, vn = self.gap_event(t, y)
        if not (located or delta <= self.gap_tolerance):
            return False
        if vn < -self.grazing_speed:
            return True
        return abs(vn) <= self.grazing_speed and self.gap_acceleration(t, y) < 0.0

    def holds(self, t: float, y: np.ndarray) -> bool:
        """Would the closed contact push (multiplier >= 0) at this state?"""
        return self.system.rhs(t, y, ContactMode.CONSTRAINT, self.baumgarte)[1] >= 0.0

    # the contact log -----------------------------------------------------------
    def new_contact(self, t: float, y: np.ndarray) -> ContactEvent:
        """Log a contact onset, stopping the run past ``solver.max_contacts``."""
        if len(self.contacts) >= self.case.solver.max_contacts:
            raise Stop(
                "max-contacts",
                f"stopped at t = {t:.9g} s after {len(self.contacts)} contacts "
                f"(solver.max_contacts); the contacts accumulate (Zeno-like)",
            )
        ev = ContactEvent(index=len(self.contacts), onset=t, velocity_before=self.gap_event(t, y)[1])
        self.contacts.append(ev)
        return ev

    def log_jump(self, t: float, jump: Jump) -> ContactEvent:
        """Log an instantaneous impact (IMM, or the e = 0 onset step of CCM): its impulse and kinetic energies (the
        Solution adds the potential energy and a following phase's force integral when the record is completed)."""
        ev = self.new_contact(t, jump.y)
        ev.velocity_before = jump.velocity_before
        ev.impulse = ev.jump_impulse = jump.impulse
        ev.energy_before, ev.energy_after = jump.kinetic_before, jump.kinetic_after
        return ev

    @staticmethod
    def contact_time(speed: float, m_eff: float, stiffness: float, exponent: float) -> float:
        """Duration of a rigid-body Hertz impact of mass ``m_eff`` at approach ``speed`` [s] (Johnson 1985,
        Sec. 11.4), the time scale of a contact; inf when P does not approach."""
        if abs(speed) <= 1e-9 or not math.isfinite(m_eff):
            return math.inf
        return rigid_hertz_impact(m_eff, abs(speed), stiffness, exponent)[2]

    # phase machine ----------------------------------------------------------------
    def on_impact(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        """Phase and state right after an impact."""
        raise NotImplementedError

    def start(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        if self.approaching(t, y):
            return self.on_impact(t, y)
        return self.free_phase(), y

    def transition(self, phase: Phase, event: EventKind, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        """IMPACT: the method's contact starts (a grazing touch keeps flying); SEPARATION and RELEASE: the
        contact ends and free flight resumes."""
        if event == EventKind.IMPACT:
            if self.approaching(t, y, located=True):
                return self.on_impact(t, y)
            return self.free_phase(), y
        if event in (EventKind.SEPARATION, EventKind.RELEASE) and phase.contact is not None:
            phase.contact.end = t
            phase.contact.velocity_after = self.gap_event(t, y)[1]
            return self.free_phase(), y
        raise ValueError(f"{self.name}: phase '{phase.name}' cannot end on {event.name}")
