"""What the three impact methods share: free flight, the gap event, the contact log."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..contact.impulse import Jump
from ..contact.laws import law_potential
from ..integrate.eventdriven import Event, Phase, Stop
from ..model.system import CONTACT_CONSTRAINT, CONTACT_FORCE, BeamSystem
from ..parameters.case import Case


@dataclass
class ContactEvent:
    """One contact (or, for IMM, one instantaneous impact).

    Times in s; velocities are P's normal velocity delta' [m/s] (negative = approaching)
    just before the contact and at its end (IMM: right after the jump).
    """

    index: int
    onset: float
    end: float = float("nan")
    velocity_before: float = float("nan")
    velocity_after: float = float("nan")
    impulse: float = float("nan")
    peak_force: float = float("nan")
    peak_time: float = float("nan")
    energy_before: float = float("nan")
    energy_after: float = float("nan")

    @property
    def duration(self) -> float:
        return self.end - self.onset


@dataclass
class ImpactMethod:
    """Base of CCFM, CCM and IMM: the free phase and the impact event.

    Subclasses add their contact phase(s) and transitions.
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
        self._free_fun = self.system.rhs_function()
        self.impact_event = Event("impact", self.gap_event, -1)
        self.release_event = Event("release", self.multiplier_event, -1)
        w = self.case.solver.baumgarte_frequency
        self.baumgarte = np.array([w, w, 0.0, 0.0])

    # events ---------------------------------------------------------------
    def gap_event(self, t: float, y: np.ndarray) -> tuple[float, float]:
        """(delta, delta') of the contact point: the impact/separation event function."""
        delta, vn, _, _ = self.system.gap(t, y)
        return delta, vn

    def free_phase(self) -> Phase:
        """Unimpact motion until the gap closes."""
        return Phase("free", self._free_fun, [self.impact_event], self.case.solver.sample_step,
                     step_limit=self.safe_step)

    def safe_step(self, t: float, y: np.ndarray) -> float:
        """Largest free-flight step that cannot carry P through the obstacle.

        P moves at most |v_P| h (to first order) in a step h; allowing a quarter of the
        obstacle's size (sphere radius; 1 mm for a point) or half the current gap keeps
        at least one event check point inside the obstacle, and the Hermite check on
        (delta, delta') catches a shallower dip.  A half-plane cannot be passed through.
        """
        if self.system.contact.kind != 0:
            return math.inf
        r, v, _, _ = self.system.point_state(t, y, self.system.contact.point)
        speed = math.hypot(v[0], v[1])
        if speed == 0.0:
            return math.inf
        size = self.system.contact.radius or 1e-3
        gap = self.gap_event(t, y)[0]
        return max(0.25 * size, 0.5 * gap) / speed

    def gap_acceleration(self, t: float, y: np.ndarray) -> float:
        """delta'' under free motion (no contact force) at state y."""
        _, _, gamma, J = self.system.gap(t, y)
        yd = self.system.rhs(t, y)[0]
        n1 = self.system.n + 1
        if self.system.prescribed:
            thdd = self.system.drive.motion(t)[2]
            zdd = np.concatenate(([thdd], yd[self.system.n : 2 * self.system.n]))
        else:
            zdd = yd[n1 : 2 * n1]
        if self.system.compliant:  # s'' of the support coordinate
            zdd = np.append(zdd, yd[self.system.support_index + 1])
        return float(J @ zdd + gamma)

    def approaching(self, t: float, y: np.ndarray, located: bool = False) -> bool:
        """Does a contact start here?  The gap is closed and P moves into the obstacle,
        or rests on it (|delta'| below ``grazing_speed``) while free motion would press it in.

        ``located``: the gap's zero was just located as an event, so it is zero to
        within round-off and only the motion decides.
        """
        delta, vn = self.gap_event(t, y)
        if not (located or delta <= self.gap_tolerance):
            return False
        if vn < -self.grazing_speed:
            return True
        return abs(vn) <= self.grazing_speed and self.gap_acceleration(t, y) < 0.0

    def new_contact(self, t: float, y: np.ndarray) -> ContactEvent:
        """Log a contact onset, stopping the run past ``solver.max_contacts``."""
        if len(self.contacts) >= self.case.solver.max_contacts:
            raise Stop(
                "max-contacts",
                f"stopped at t = {t:.9g} s after {len(self.contacts)} contacts "
                f"(solver.max_contacts); the contacts accumulate (Zeno-like)",
            )
        vn = self.gap_event(t, y)[1]
        ev = ContactEvent(index=len(self.contacts), onset=t, velocity_before=vn)
        self.contacts.append(ev)
        return ev

    def log_jump(self, t: float, jump: Jump) -> ContactEvent:
        """Log an instantaneous impact (IMM, or the e = 0 onset step of CCM)."""
        ev = self.new_contact(t, jump.y)
        ev.velocity_before = jump.velocity_before
        ev.impulse = jump.impulse
        ev.energy_before, ev.energy_after = jump.kinetic_before, jump.kinetic_after
        return ev

    # constrained (sticking) contact ----------------------------------------
    def multiplier_event(self, t: float, y: np.ndarray) -> tuple[float, float]:
        """Contact multiplier lambda of the constrained phase (separation when < 0)."""
        return float(self.system.rhs(t, y, CONTACT_CONSTRAINT, self.baumgarte)[1]), float("nan")

    def holds(self, t: float, y: np.ndarray) -> bool:
        """Would the closed contact push (lambda >= 0) at this state?"""
        return self.multiplier_event(t, y)[0] >= 0.0

    def constrained_phase(self, contact: ContactEvent, name: str = "constrained") -> Phase:
        """Contact held closed by the unilateral constraint until lambda turns tensile.

        Baumgarte stabilisation (Baumgarte 1972; Hairer & Wanner, Solving ODEs II,
        Sec. VII.2) with alpha = beta = ``solver.baumgarte_frequency``.  A CCM contact is
        sampled at the contact spacing, IMM's resting contact at the free one.  The phase starts
        consistent (delta = 0 at the located event, delta' = 0 after the e = 0 jump),
        so the terms only damp the integration drift, critically, on a time scale far
        slower than the beam's modes (no added stiffness for the explicit solver).
        """
        step = self.case.solver.contact_sample_step if name == "constrained" else self.case.solver.sample_step
        return Phase(
            name,
            self.system.rhs_function(CONTACT_CONSTRAINT, self.baumgarte),
            [self.release_event],
            step,
            data={"mode": CONTACT_CONSTRAINT, "p": self.baumgarte, "contact": contact},
            keep_dense=True,
        )

    # phase machine of the methods whose contacts start with a velocity jump ----
    def on_impact(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        """Phase and state right after an impact (CCM, IMM override this)."""
        raise NotImplementedError

    def start(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        if self.approaching(t, y):
            return self.on_impact(t, y)
        return self.free_phase(), y

    def transition(self, phase: Phase, event: Event, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        """Free flight -> impact at a located gap closure; any contact phase -> free at its end."""
        if phase.name == "free":
            if self.approaching(t, y, located=True):
                return self.on_impact(t, y)
            return self.free_phase(), y  # grazing touch: keep flying
        ev = phase.data["contact"]
        ev.end = t
        ev.velocity_after = self.gap_event(t, y)[1]
        return self.free_phase(), y

    # outputs --------------------------------------------------------------
    def force(self, phase: Phase, t: float, y: np.ndarray) -> tuple[float, float]:
        """(contact force F [N], contact potential U_c [J]) at a sample of ``phase``."""
        mode = phase.data.get("mode", 0)
        if mode == 0:
            return 0.0, 0.0
        p = phase.data["p"]
        F = float(self.system.rhs(t, y, mode, p)[1])
        if mode == CONTACT_FORCE:
            return F, law_potential(p, -self.gap_event(t, y)[0])
        return F, 0.0

    def joint_torque(self, phase: Phase, t: float, y: np.ndarray) -> float:
        """Joint torque [N m] at a sample (the reaction when theta(t) is prescribed)."""
        return self.system.joint_torque(t, y, phase.data.get("mode", 0), phase.data.get("p"))
