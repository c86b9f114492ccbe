"""What the three impact methods share: free flight, the impact event, the contact log.

An impact method (:class:`~flexbeam.integrate.loop.PhaseMethod`) gives the phase loop the first phase and, at
every event a phase ends on, the next phase and the state after it (a velocity jump for CCM's onset and IMM).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import numerics as nm
from ..contact.hertz import rigid_hertz_impact
from ..integrate.loop import Stop
from ..integrate.phases import FRICTION_EVENTS, PAINLEVE_EVENTS, ContactMode, EventKind, Phase
from ..model.system import BeamSystem
from ..parameters.case import Case
from ..results.records import ContactEvent
from . import coulomb, stick_start
from .impulse import Jump, impulse_jump
from .switches import KernelSwitches

#: steps per (estimated) contact duration at least: a contact phase's step is bounded by t_c / CONTACT_STEPS
CONTACT_STEPS = 8
#: a contact under its law that has lasted this many of its impact time scales t_c (the rigid Hertz contact duration
#: at its onset speed, :meth:`ImpactMethod.contact_time`) rests on the obstacle: the step bound t_c / CONTACT_STEPS,
#: which resolves an impact's force pulse, lifts there and the integrator's error control alone sets the step.  The
#: impacts of every preset last at most 7.4 t_c (tip-wall, seed-experiment-calibrated), so their steps keep the bound;
#: math.inf keeps it for the whole contact (``benchmarks/resting.py`` compares both).
RESTING_DURATIONS = 20.0
#: a held pair bounds the step by HELD_STEPS / kappa (kappa = solver.baumgarte_frequency): the Baumgarte terms damp
#: the held gap's drift at the rate kappa (critically, delta'' + 2 kappa delta' + kappa^2 delta = 0), and the Gauss
#: collocation -- A-stable, not L-stable: its stability function |R(z)| -> 1 as z -> -inf -- damps it only on steps
#: that resolve 1 / kappa.  Measured on the rigid beam held on tip-wall (CCM, 1 s): unbounded, its steps grew to
#: 0.78 s and left a drift delta' = -6.9e-8 m/s, the held force 3.5e-5 off at t_end; h <= 4 / kappa (2 ms): drift
#: 1e-16 m/s, the force steady to 2e-12 (500 steps a second); h <= 16 / kappa: 5e-4.  Flexible beams' held steps are
#: shorter: the 29 fingerprints are the same to the bit.
HELD_STEPS = 4.0
#: every phase watches all three kinds of event; each pair is watched for the one its mode can end on
ALL_EVENTS = (EventKind.IMPACT, EventKind.SEPARATION, EventKind.RELEASE)


@dataclass
class ImpactMethod(KernelSwitches):
    """Base of CCFM, CCM and IMM: the phases, the impact events and the transitions back to free flight.

    A phase says, pair by pair, whether the pair is free, under its law or held by its constraint
    (:class:`~flexbeam.integrate.phases.Phase`); subclasses say what an impact of some pairs starts (:meth:`on_impact`).
    """

    system: BeamSystem
    case: Case
    contacts: list[ContactEvent] = field(default_factory=list)

    name = "base"
    #: the name of a phase with held (constrained) pairs and no pair under a law
    held_name = "constrained"
    #: onsets with |delta'| below this are grazing touches, not impacts [m/s]
    grazing_speed = 1e-9
    #: a grazing point is pressed in only by a normal acceleration beyond this [m/s^2] (below: round-off, e.g. a
    #: redundant pair riding on a held one, whose gap follows the held pair's to ~1e-18 m)
    grazing_acceleration = 1e-9
    #: a gap this small counts as closed at the start of a run [m]
    gap_tolerance = 1e-12
    #: another pair closing within this time of a located impact impacts with it [s] (the located time is the root
    #: of the dense output's gap, which the state's own gap matches to ~1e-11 m: ~1e-10 s at 0.1 m/s)
    simultaneity = 1e-9
    #: does the run's integrator locate friction's events (the exponential one; the simulation sets it)?  Without
    #: them no frictional pair can be held: CCM's friction is refused before the run, IMM's run stops where a
    #: frictional pair would come to rest (:meth:`~flexbeam.methods.held_friction.HeldFriction.held_phase`)
    locates_friction = True
    #: why a flexible beam in lasting contact with a stop chatters under the method, which the message of a run
    #: stopped by ``solver.max_contacts`` gives with what carries it on (:meth:`new_contact`; IMM and CCM)
    chatter_cause = ""

    def __post_init__(self) -> None:
        w = self.case.solver.baumgarte_frequency
        self.baumgarte = (w, w)
        self._free: Phase | None = None  # the free phase, built once (a Phase is immutable)
        #: the contacts buffer :meth:`held_set` built last: (modes, parameters, buffer); the phase of those modes and
        #: that parameters array (never changed in place: a new phase copies it) takes it for its own
        self._held_buffer: tuple = ((), None, None)

    # phases -----------------------------------------------------------------
    def free_phase(self) -> Phase:
        """Unimpact motion until a gap closes."""
        if self._free is not None:
            return self._free
        S = self.system.pairs
        self._free = Phase("free", (ContactMode.NONE,) * S, ALL_EVENTS, self.case.sample_steps()[0],
                           np.zeros((S, 4)), (None,) * S, self.baumgarte)  # fmt: skip
        return self._free

    def phase(self, modes, parameters: np.ndarray, records, friction: np.ndarray | None = None) -> Phase:
        """The phase with the pairs in ``modes`` (their law ``parameters``, their contact ``records``; ``friction``:
        CCFM's Coulomb friction rows, :class:`~flexbeam.integrate.phases.Phase`, watched by its events).

        Held pairs are constrained with Baumgarte stabilisation (Baumgarte 1972; Hairer & Wanner, Solving ODEs II,
        Sec. VII.2), alpha = beta = ``solver.baumgarte_frequency``; a held pair starts consistent (delta = 0 at the
        located event, delta' = 0 after the e = 0 jump), so the terms only damp the integration drift.  Contacts are
        sampled at the contact spacing (IMM's resting contact at the free one); a pair under its law bounds the step
        by its contact's time scale t_c over CONTACT_STEPS until it has lasted RESTING_DURATIONS t_c (the bound
        holds while any pair's contact is that young): a contact that outlasts its impact pulse by far is a
        resting one, whose force follows the beam's slow motion and the ringing of its modes, and the error
        control resolves it without the bound.  A held pair bounds the step by HELD_STEPS / alpha to the phase's end,
        so that the collocation damps the held gap's drift as the Baumgarte terms do.
        """
        modes = tuple(m if type(m) is ContactMode else ContactMode(m) for m in modes)  # (the enum's call: ~1 us)
        if not any(modes):
            return self.free_phase()
        force = any(m == ContactMode.FORCE for m in modes)
        name = "contact" if force else self.held_name
        free_step, contact_step = self.case.sample_steps()
        sample = contact_step if force or name == "constrained" else free_step
        young = [r for m, r in zip(modes, records) if m == ContactMode.FORCE and r]
        steps = [r.time_scale / CONTACT_STEPS for r in young]
        until = max((r.onset + RESTING_DURATIONS * r.time_scale for r in young), default=math.inf)
        if self.baumgarte[0] > 0.0 and any(m == ContactMode.CONSTRAINT for m in modes):
            steps.append(self.held_step())  # (with a young contact beside: the smaller, to the end)
            until = math.inf
        rough = friction is not None and np.count_nonzero(friction) > 0  # (np.any costs 5 us a phase)
        events = ALL_EVENTS + FRICTION_EVENTS if rough else ALL_EVENTS
        if (
            rough
            and ContactMode.CONSTRAINT in modes
            and any(m == ContactMode.CONSTRAINT and f[0] != 0.0 for m, f in zip(modes, friction))
        ):
            events += PAINLEVE_EVENTS  # a held pair slips (CCM): its a = W_nn + sigma W_nt is watched
        out = Phase(name, modes, events, sample, np.asarray(parameters, float), tuple(records), self.baumgarte,
                    min(steps, default=math.inf), until, np.array(friction, float) if rough else None)  # fmt: skip
        held_modes, held_params, buffer = self._held_buffer
        if not rough and out.parameters is held_params and modes == held_modes:
            out.__dict__["buffer"] = buffer  # Phase.buffer (a cached property): the same packing, built once
        return out

    # events -----------------------------------------------------------------
    def gap_event(self, t: float, y: np.ndarray, pair: int = 0) -> tuple[float, float]:
        """(delta, delta') of a pair's contact point."""
        delta, vn, _, _ = self.system.gap(t, y, pair)
        return delta, vn

    def gap_acceleration(self, t: float, y: np.ndarray, pair: int = 0, contacts: np.ndarray | None = None) -> float:
        """delta'' of a pair under the ``contacts`` of the current phase (default: free motion) at state y."""
        sysm = self.system
        _, _, gamma, J = sysm.gap(t, y, pair)
        yd = sysm.rhs(t, y, contacts)[0]
        zdd = sysm.joint.full_accelerations(t, yd, sysm.n)
        if sysm.compliant:  # s'' of the support coordinate
            zdd = np.append(zdd, yd[sysm.support_index + 1])
        return nm.dot(J, zdd) + gamma

    def approaching(self, t: float, y: np.ndarray, pair: int = 0, located: bool = False,
                    contacts: np.ndarray | None = None) -> bool:  # fmt: skip
        """Does a pair's contact start here?  Its gap is closed and its point moves into the obstacle, or rests
        on it (|delta'| below ``grazing_speed``) while the motion (under the phase's other ``contacts``) would
        press it in.

        ``located``: the gap's zero was just located as an event, so it is zero to within round-off and only
        the motion decides; another pair counts as closed if it would close within ``simultaneity``.
        """
        delta, vn = self.gap_event(t, y, pair)
        if not (located or delta <= self.gap_tolerance + max(-vn, 0.0) * self.simultaneity):
            return False
        if vn < -self.grazing_speed:
            return True
        return (
            abs(vn) <= self.grazing_speed and self.gap_acceleration(t, y, pair, contacts) < -self.grazing_acceleration
        )

    def held_set(self, t: float, y: np.ndarray, candidates, phase: Phase | None = None) -> list[int]:
        """The candidate pairs whose closed contacts push together (every multiplier >= 0), by the active-set
        method: hold all, release the most tensile, repeat (exact for one pair; for several it finds a set whose
        multipliers are all compressive).  Pairs under a law in ``phase`` keep acting.

        Redundant pairs are not held: a pair whose gap Jacobian depends on those of the pairs kept before it
        (a rigid rod resting on two stops: W = J M^-1 J^T has rank 1) would make the multipliers
        indeterminate; its gap follows the held pairs', so it stays closed without a multiplier of its own.
        """
        S = self.system.pairs
        held = self._independent(t, y, sorted(set(candidates)))
        base = [ContactMode.NONE] * S if phase is None else list(phase.modes)
        params = np.zeros((S, 4)) if phase is None else phase.parameters
        while held:
            modes = [ContactMode.CONSTRAINT if k in held else (m if m == ContactMode.FORCE else ContactMode.NONE)
                     for k, m in enumerate(base)]  # fmt: skip
            buffer = self.system.contacts(modes, params, *self.baumgarte)
            self._held_buffer = (tuple(modes), params, buffer)
            F = self.system.rhs(t, y, buffer)[1]
            worst = min(held, key=lambda k: F[k])
            if F[worst] >= 0.0:
                return held
            held.remove(worst)
        return []

    #: a pair is redundant when the part of its Delassus diagonal not explained by the held pairs is below
    #: this share of the diagonal (W's Schur complement; round-off of W is ~1e-16 of it)
    REDUNDANT = 1e-9

    def _independent(self, t: float, y: np.ndarray, pairs: list[int]) -> list[int]:
        """The pairs, in order, without those whose constraint rows depend on the earlier ones (see
        :meth:`held_set`), by the Schur complement of W on the pairs kept so far."""
        if len(pairs) < 2:
            return pairs
        W = self.system.delassus(t, y, pairs)
        kept: list[int] = []
        for i in range(len(pairs)):
            rows = [pairs.index(k) for k in kept]
            w = W[i, i]
            if rows:
                w -= nm.dot(W[i, rows], nm.solve(W[np.ix_(rows, rows)], W[rows, i]))
            if w > self.REDUNDANT * W[i, i]:
                kept.append(pairs[i])
        return kept

    def holds(self, t: float, y: np.ndarray, pair: int = 0) -> bool:
        """Would the closed contact of ``pair`` (alone) push (multiplier >= 0) at this state?"""
        return self.held_set(t, y, [pair]) == [pair]

    # the contact log -----------------------------------------------------------
    def new_contact(self, t: float, y: np.ndarray, pair: int = 0, velocity_before: float | None = None) -> ContactEvent:
        """Log a contact onset of a pair (its approach speed ``velocity_before``, default: its delta' at y), stopping
        the run past ``solver.max_contacts``."""
        if len(self.contacts) >= self.case.solver.max_contacts:
            advice = (
                f"; a flexible beam in lasting contact with a stop (settling on it, or a rod's impact borne by its "
                f"waves) chatters under {self.name.upper()}, {self.chatter_cause}: CCFM carries a lasting contact, or "
                "raise solver.max_contacts to go on"
                if self.chatter_cause
                else ""
            )
            raise Stop(
                "max-contacts",
                f"stopped at t = {t:.9g} s after {len(self.contacts)} contact{'' if len(self.contacts) == 1 else 's'} "
                f"(solver.max_contacts); the contacts accumulate (Zeno-like){advice}",
            )
        if velocity_before is None:
            velocity_before = self.gap_event(t, y, pair)[1]
        ev = ContactEvent(index=len(self.contacts), onset=t, velocity_before=velocity_before, pair=pair)
        self.contacts.append(ev)
        return ev

    def held_impact(self, phase: Phase, t: float, y: np.ndarray, pairs: list[int], restitution) -> Jump:
        """The impulse map of the impacting ``pairs`` (their ``restitution``) together with the pairs ``phase`` holds,
        these with e = 0: a closed contact takes the impulse that keeps it from sinking in, or opens without one (the
        closed contacts join the impact problem: Pfeiffer & Glocker 1996, Ch. 7).  Alone, the impacting pairs'
        impulses would leave a held pair moving into its obstacle, where its constraint on delta = 0 cannot start.
        A held pair's impulse is added to its record's ``jump_impulse`` (and tangential impulse); the impacting
        pairs come first in the Jump's arrays."""
        held = [k for k, m in enumerate(phase.modes) if m == ContactMode.CONSTRAINT and k not in pairs]
        if not held:
            return impulse_jump(self.system, t, y, restitution, pairs)
        e = np.zeros(len(pairs) + len(held))
        e[: len(pairs)] = restitution
        jump = impulse_jump(self.system, t, y, e, [*pairs, *held])
        for i, k in enumerate(held, start=len(pairs)):
            rec = phase.records[k]
            if rec is None:
                continue
            rec.jump_impulse = (0.0 if math.isnan(rec.jump_impulse) else rec.jump_impulse) + float(jump.impulses[i])
            if jump.tangential is not None:
                tan = 0.0 if math.isnan(rec.tangential_impulse) else rec.tangential_impulse
                rec.tangential_impulse = tan + float(jump.tangential[i])
        return jump

    def opening(self, t: float, y: np.ndarray, pairs) -> list[int]:
        """The ``pairs`` whose points leave their obstacles at (t, y) (delta' above ``grazing_speed``): a held pair
        that an impact elsewhere lifted off, which its constraint would pull back."""
        return [k for k in pairs if self.gap_event(t, y, k)[1] > self.grazing_speed]

    def log_jump(self, t: float, jump: Jump, pairs=(0,)) -> list[ContactEvent]:
        """Log an instantaneous impact (IMM, or the e = 0 onset step of CCM) at each of ``pairs``: its impulse
        and the kinetic energies (the Solution adds the potential energy and a following phase's force integral
        when the record is completed)."""
        out = []
        for i, k in enumerate(pairs):
            ev = self.new_contact(t, jump.y, k, float(jump.velocities_before[i]))
            ev.impulse = ev.jump_impulse = float(jump.impulses[i])
            if jump.tangential is not None:
                ev.tangential_impulse = float(jump.tangential[i])
            ev.energy_before, ev.energy_after = jump.kinetic_before, jump.kinetic_after
            out.append(ev)
        return out

    @staticmethod
    def contact_time(speed: float, m_eff: float, stiffness: float, exponent: float) -> float:
        """Duration of a rigid-body Hertz impact of mass ``m_eff`` at approach ``speed`` [s] (Johnson 1985,
        Sec. 11.4), the time scale of a contact; inf when P does not approach."""
        if abs(speed) <= 1e-9 or not math.isfinite(m_eff):
            return math.inf
        return rigid_hertz_impact(m_eff, abs(speed), stiffness, exponent)[2]

    # phase machine ----------------------------------------------------------------
    def on_impact(self, phase: Phase, t: float, y: np.ndarray, pairs: list[int]) -> tuple[Phase, np.ndarray]:
        """Phase and state right after the impact of ``pairs`` (from ``phase``)."""
        raise NotImplementedError

    def impacting(self, phase: Phase, t: float, y: np.ndarray, first: int | None = None) -> list[int]:
        """The free pairs of ``phase`` whose contacts start now (``first``: just located as an event)."""
        out = []
        for k, m in enumerate(phase.modes):
            if m != ContactMode.NONE:
                continue
            if self.approaching(t, y, k, located=k == first, contacts=phase.buffer):
                out.append(k)
        return out

    def start(self, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        free = self.free_phase()
        pairs = self.impacting(free, t, y)
        return self.on_impact(free, t, y, pairs) if pairs else (free, y)

    def end_contact(self, phase: Phase, pair: int, t: float, y: np.ndarray, rate: float | None = None) -> Phase:
        """Close pair ``pair``'s contact record (its end velocity ``rate``, default the gap's rate at y) and free
        the pair."""
        rec = phase.records[pair]
        if rec is not None:
            rec.end = t
            rec.velocity_after = self.gap_event(t, y, pair)[1] if rate is None else rate
        return self.without(phase, pair)

    def without(self, phase: Phase, pair: int) -> Phase:
        """``phase`` with pair ``pair`` free (its record left as it is)."""
        modes = list(phase.modes)
        modes[pair] = ContactMode.NONE
        records = list(phase.records)
        records[pair] = None
        params = phase.parameters.copy()
        params[pair] = 0.0
        friction = None if phase.friction is None else phase.friction.copy()
        if friction is not None:
            friction[pair] = 0.0
        return self.phase(modes, params, records, friction)

    def transition(self, phase: Phase, event: EventKind, t: float, y: np.ndarray, pair: int = 0
                   ) -> tuple[Phase, np.ndarray]:  # fmt: skip
        """A friction event of a pair (a stop, the end of a stick: :mod:`flexbeam.methods.coulomb`) switches its
        friction row; the others as :meth:`contact_transition`; with friction the sticking pairs are then sorted
        into holders and followers again.  A stop's sticks that cannot hold there slip on at once
        (:func:`~flexbeam.methods.stick_start.holding`)."""
        if event == EventKind.STOP:
            friction = coulomb.grouped(self.system, t, y, coulomb.stop(self.system, phase, t, y, pair), phase.modes)
            return stick_start.holding(self, self.phase(phase.modes, phase.parameters, phase.records, friction), t, y)
        if event in FRICTION_EVENTS:
            friction = coulomb.unstick(self.system, phase, event, pair, t, y)
        else:
            phase, y = self.contact_transition(phase, event, t, y, pair)
            if phase.friction is None:
                return phase, y
            friction = phase.friction
        friction = coulomb.grouped(self.system, t, y, friction, phase.modes)
        return self.phase(phase.modes, phase.parameters, phase.records, friction), y

    def held_step(self) -> float:
        """The step bound of a phase with a held pair: HELD_STEPS / alpha (:meth:`phase`), inf without Baumgarte."""
        return HELD_STEPS / self.baumgarte[0] if self.baumgarte[0] > 0.0 else math.inf

    def settled(self, phase: Phase, t: float, y: np.ndarray) -> tuple[Phase, np.ndarray]:
        """The phase and state after a friction switch at (t, y): as they are (CCFM's law pairs);
        :class:`~flexbeam.methods.held_friction.HeldFriction` resolves its held pairs' Painlevé slips and frees the
        pairs that leave."""
        return phase, y

    def contact_transition(self, phase: Phase, event: EventKind, t: float, y: np.ndarray, pair: int = 0
                           ) -> tuple[Phase, np.ndarray]:  # fmt: skip
        """IMPACT of a pair: the method's contact starts there and at every other free pair closing at this
        instant (a grazing touch keeps the phase); SEPARATION and RELEASE: that pair's contact ends."""
        if event == EventKind.IMPACT:
            if phase.modes[pair] != ContactMode.NONE:
                raise ValueError(f"{self.name}: pair {pair} is in contact in phase '{phase.name}'; it cannot impact")
            pairs = self.impacting(phase, t, y, first=pair)
            if pair in pairs:
                return self.on_impact(phase, t, y, pairs)
            return phase, y
        if event in (EventKind.SEPARATION, EventKind.RELEASE) and phase.modes[pair] != ContactMode.NONE:
            phase = self.end_contact(phase, pair, t, y)
            held = [k for k, m in enumerate(phase.modes) if m == ContactMode.CONSTRAINT]
            if event == EventKind.RELEASE and held:  # another pair whose multiplier the release turns tensile leaves
                for k in set(held) - set(self.held_set(t, y, held, phase)):
                    phase = self.end_contact(phase, k, t, y)
            return phase, y
        raise ValueError(f"{self.name}: phase '{phase.name}' cannot end on {event.name} of pair {pair}")
