"""IMM: impulse-momentum method with a coefficient of restitution.

Each impact is instantaneous: M (z'^+ - z'^-) = J^T P with J z'^+ = -e J z'^-, the coordinates unchanged
(:func:`flexbeam.methods.impulse.impulse_jump`; pairs impacting at the same instant share one impact LCP, Newton's
restitution per pair); no force history exists.  Every contact of the run is treated the same way.

Accumulating impacts (e < 1 with gravity pressing P onto the obstacle: a Zeno sequence whose impact speeds
shrink geometrically) are ended deliberately: once an impact's rebound speed ``e |delta'^-|`` falls below
``solver.rest_velocity`` (always for e = 0: a plastic impact leaves P on the surface) the velocity is cancelled
(e = 0) and P rests on the obstacle if the contact would push -- the contact is then held by the unilateral
constraint of the CCM phase (phase "resting", the force is its multiplier) until that force would turn tensile,
when free motion resumes.  Pairs impacting together come to rest together, once the fastest rebound among them
is below ``solver.rest_velocity`` (a pair with e = 0 always rests), or once each one's rebound flight would rise less
than its gap can resolve (:meth:`IMM.unresolvable`: a pair pressed back hard, as by a flexible beam's vibration, whose
landings would be lost in the gap's round-off while its rebounds are still faster than ``solver.rest_velocity``).

**Coulomb friction** (``contact.friction``).  An impact is frictional (Stronge's process for one pair, the frictional
impact LCP for several: :func:`~flexbeam.methods.impulse.impulse_jump`), and so is the resting contact, with CCM's
code (:class:`~flexbeam.methods.held_friction.HeldFriction`): a resting pair slips with its normal force the
multiplier lambda_n and the tangential force sigma lambda_n, sigma = -mu_k sign(v_t), until v_t reaches zero (a
located STOP), then sticks, held tangentially by a second multiplier lambda_t, until abs(lambda_t) reaches
mu_s lambda_n (a located UNSTICK: it slips on) or lambda_n turns tensile (it leaves); a slip with Painlevé's
a = W_nn + sigma W_nt <= 0 is resolved by a tangential impact, with a warning (:mod:`flexbeam.methods.painleve`).
The resting phase's friction needs the exponential integrator's located events: on the reference path (solver.
integrator = "reference", a compliant support) the run stops where a frictional pair would come to rest.
"""

from __future__ import annotations

import math

import numpy as np

from ..integrate.phases import ContactMode, Phase
from ..kernels import SWITCH_REBOUND
from .held_friction import HeldFriction
from .impulse import Jump
from .switches import PairSwitches

#: a rebound flight lower than this many eps of its gap's scale cannot be located (:meth:`IMM.unresolvable`): 4x the
#: gap's round-off GAP_ULPS of ``kernels/src/surface.c``
RISE_ULPS = 64.0
EPS = float(np.finfo(float).eps)
#: [m/s^2] the largest acceleration pressing a pair back that :meth:`IMM.unresolvable` provides for (a 1 kHz vibration
#: of 25 mm amplitude), and [m] the largest gap scale (1 km): a rebound that rises higher against both is not checked
PRESSING_MAX = 1e6
RISE_SCALE_MAX = RISE_ULPS * EPS * 1e3


class IMM(PairSwitches, HeldFriction):
    """Impulse-momentum method."""

    name = "imm"
    #: (measured: seed-experiment, tip-wall and two-stops reach 1000 contacts by 0.26-0.46 s, and sooner with friction
    #: or beam damping; CCFM runs each to its end)
    chatter_cause = "its modes throwing the struck point back after each impulse"
    held_name = "resting"

    def on_impact(self, phase: Phase, t: float, y: np.ndarray, pairs: list[int]) -> tuple[Phase, np.ndarray]:
        rest = self.case.solver.rest_velocity
        e = np.array([self.system.contact.pairs[k].restitution for k in pairs])
        speed = np.array([-self.gap_event(t, y, k)[1] for k in pairs])
        # the pairs of one impact rest together (or none of them): a pair alone at rest beside one that rebounds
        # asks the impact problem for both at once when their constraints are dependent (a rigid rod on two stops)
        resting = (e == 0.0) | bool(np.max(e * speed) < rest) | self.unresolvable(phase, t, y, pairs, e * speed)
        jump = self.held_impact(phase, t, y, pairs, np.where(resting, 0.0, e))
        events = self.log_jump(t, jump, pairs)
        opened = self.opening(t, jump.y, [k for k, m in enumerate(phase.modes) if m == ContactMode.CONSTRAINT])
        held_before = [k for k, m in enumerate(phase.modes) if m == ContactMode.CONSTRAINT and k not in opened]
        candidates = [k for k, r in zip(pairs, resting) if r]
        held = self.held_set(t, jump.y, [*held_before, *candidates], phase) if candidates or held_before else []
        modes, records = list(phase.modes), list(phase.records)
        for k, ev in zip(pairs, events):
            if k in held:
                modes[k], records[k] = ContactMode.CONSTRAINT, ev
            else:
                ev.end = t
                ev.velocity_after = float(jump.velocities_after[pairs.index(k)])
                modes[k], records[k] = ContactMode.NONE, None
        for k in [*held_before, *opened]:
            if k not in held:
                self.end_contact(phase, k, t, jump.y)
                modes[k], records[k] = ContactMode.NONE, None
        return self.held_phase(phase, t, jump.y, modes, records, [k for k in pairs if k in held])

    # the rebounds the compiled stepper takes itself (methods/switches.py PairSwitches) -----------------------------
    switch_rule = SWITCH_REBOUND

    def rebound_coef(self) -> list[float]:
        """[solver.rest_velocity, the rise limit of :meth:`unresolvable`'s first test, each pair's restitution]: the
        kernel rebounds where :meth:`on_impact` would (a rebound above both), else the phase loop decides."""
        e = [float(p.restitution) for p in self.system.contact.pairs]
        return [self.case.solver.rest_velocity, 2.0 * RISE_SCALE_MAX * PRESSING_MAX, *e]

    def left_at_once(self, t: float, jump: Jump, pair: int) -> float:
        """A rebound's end velocity: the jump's v+ (as :meth:`on_impact`)."""
        return float(jump.velocities_after[0])

    def unresolvable(self, phase: Phase, t: float, y: np.ndarray, pairs: list[int], rebound: np.ndarray) -> bool:
        """Would every pair's rebound flight stay lower than its gap can resolve?  A flight's height is w^2 / (2 a)
        (rebound speed w, a = -delta'' the acceleration pressing the pair back under the phase's other contacts,
        uniform over a flight that short); below :data:`RISE_ULPS` eps (abs(r_P) + abs(c) + R) -- the gap's round-off is
        GAP_ULPS = 16 of them (``kernels/src/surface.c``) -- its landing cannot be located, and the rest of the Zeno
        sequence moves the pair by less than that.  (A flexible bar's end pressed back at 1.5e4 m/s^2 by the
        bar's vibration failed at a flight of 5e-17 m, its rebounds at 1.2e-6 m/s above ``solver.rest_velocity``.)"""
        if not np.all(rebound**2 < 2.0 * RISE_SCALE_MAX * PRESSING_MAX):  # no acceleration we look for holds them
            return False
        for k, w in zip(pairs, rebound):
            press = -self.gap_acceleration(t, y, k, phase.buffer)
            obstacle = self.system.contact.obstacles[self.system.contact.pairs[k].obstacle]
            reach = math.hypot(*self.system.point_state(t, y, self.system.pair_point(k))[0])
            floor = RISE_ULPS * EPS * (reach + math.hypot(*obstacle.centre) + obstacle.radius)
            if not (press > 0.0 and w * w <= 2.0 * floor * press):
                return False
        return True
