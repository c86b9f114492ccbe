"""The event-driven run of the finite-element beam: contact phases, located events, step sizes.

Contact
-------
Each contact pair (a point of the beam against an obstacle under its law; pair 0 is P
against ``[obstacle]``, one more per ``[[obstacles]]`` entry) has its own phases.
As in the modal CCFM path the contact force acts only in a contact phase, which
starts when the gap delta of P crosses zero downwards with P approaching, and ends
when it crosses zero upwards.  A step whose end state has crossed is cut back: the
crossing is located by the Illinois variant of regula falsi on the step size (each
trial is a complete implicit step from the last accepted state) until |delta| is
below a tolerance on the penetrated side (onset) or the open side (separation).  A
free step whose ends both have delta > 0 is also checked for a dip below zero by the
cubic Hermite interpolant of (delta, delta') at its ends, so that a grazing impact
inside a step is not missed.

Step size
---------
``fem.time_step`` fixes the step.  Otherwise, during contact h_c = t_c / 200 with t_c
the Hertz duration 2 delta_max / v int_0^1 (1 - s^(n+1))^(-1/2) ds of the approach
speed v and a reference effective mass (the rigid-body one, (J_h + J_beam)/J_theta^2
for a free or torque-driven joint; the first clamped mode's mu L / phi_1(x_P)^2 when
theta(t) is prescribed), and in free flight h_f = 2 h_c (t_c estimated with the
impact velocity of the case; with several pairs each pair's own estimate with its
law and J_theta at its point, the smallest of them for h_f, and while several pairs
are in contact the smallest of theirs).  The free-flight factor is kept small because the
vibration that an impact excites has the contact's own time scale, and the phase of
that vibration decides the next contact: later contacts converge slowly with the
step, so set ``fem.time_step`` for converged multi-contact histories.  A step whose
Newton iteration fails is halved and retried (down to 2^-30 of the nominal step).
The onset/separation tolerance on |delta| is 1e-3 |delta'| h_c, i.e. the contact
instants are located to ~1e-3 of a contact step.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..contact.hertz import rigid_hertz_impact
from ..errors import SolverError
from ..results.records import ContactEvent
from .banded import BAND, fix_first_dof
from .gap import hermite_dip
from .integrator import FemIntegrator, NewtonFailure, State, StepResult
from .model import ContactState, FemBeam

#: contact onsets with |delta'| below this are grazing touches, not impacts [m/s]
GRAZING_SPEED = 1e-9
#: how many halvings of a failing step before giving up
MAX_HALVINGS = 30
#: steps per estimated contact duration, and free/contact step ratio
STEPS_PER_CONTACT = 200
FREE_STEP_FACTOR = 2.0


@dataclass
class Record:
    """Contact log and dense contact data of one run (the samples go to ``sample``)."""

    contacts: list[ContactEvent] = field(default_factory=list)
    # dense force on contact steps, per pair in contact: (t0, t1, (d, d', d'')_0, (d, d', d'')_1, lawp, pair)
    dense: list[tuple] = field(default_factory=list)


@dataclass
class RunInfo:
    """Status, statistics and the step sizes used by :func:`run`."""

    status: str
    message: str
    steps: int
    rejected: int
    iterations: int
    wall_time: float
    h_contact: float
    h_free: float


def reference_mass(beam: FemBeam, z: np.ndarray, pair: int = 0) -> float:
    """Effective mass used only to size the contact step of ``pair`` (see the module docstring)."""
    case = beam.case
    xP = beam.pairs[pair].position
    if not beam.prescribed:
        J_theta = beam.rotation_jacobian(z, pair)
        L, rh, mu = case.beam.length, beam.hub_radius, beam.mu
        inertia = beam.hub_inertia + mu * ((rh + L) ** 3 - rh**3) / 3.0
        if abs(J_theta) > 0.0:
            return inertia / J_theta**2
        return math.inf
    bl = 1.8751040687119611
    L = case.beam.length
    s = (math.cosh(bl) + math.cos(bl)) / (math.sinh(bl) + math.sin(bl))
    x = bl * xP / L
    phi = math.cosh(x) - math.cos(x) - s * (math.sinh(x) - math.sin(x))
    return beam.mu * L / max(phi * phi, 1e-12)


def contact_step(beam: FemBeam, mass: float, speed: float, pair: int = 0) -> float:
    """h_c = t_c / STEPS_PER_CONTACT from the rigid Hertz impact estimate with the law of ``pair``."""
    law = beam.pairs[pair].law
    mass = min(mass, 1e6 * beam.mu * beam.case.beam.length)
    speed = max(abs(speed), 1e-6)
    _, _, tc = rigid_hertz_impact(mass, speed, law.stiffness, law.exponent)
    return tc / STEPS_PER_CONTACT


def _hermite_dip(g0: float, v0: float, g1: float, v1: float, h: float) -> float | None:
    """Fraction s in (0, 1) where the cubic Hermite of the gap dips below zero, if any."""
    s = hermite_dip(g0, v0, g1, v1, h)
    return s if s > 0.0 else None


def run(
    beam: FemBeam,
    integ: FemIntegrator,
    z0: np.ndarray,
    zd0: np.ndarray,
    t_end: float,
    sample: Callable[[State, StepResult, str, ContactState], None],
    progress: Callable[[float], None] | None = None,
    stop_at_impact: bool = False,
) -> tuple[Record, RunInfo, State]:
    """Integrate from (z0, zd0) at t = 0 to ``t_end``, recording samples.

    ``sample(state, result, phase, contacts)`` is called at every accepted state (twice
    at a change of the contact state, once before and once after; ``contacts`` is the
    :class:`~flexbeam.fem.model.ContactState` -- which pairs are in contact, under which
    law parameters; the phase is "contact" while some pair is).  With ``stop_at_impact``
    the run ends at the first contact onset of any pair (status "impact").

    Each pair k has its own contact phase, which starts when its gap delta_k crosses zero
    downwards with its point approaching and ends when delta_k crosses zero upwards.
    When several pairs have an event within one step, the step is cut back to the one
    whose linear (or, for a dip, Hermite) estimate of the crossing comes first; a pair
    found already past its crossing at a located event is switched there too.  The step
    is the contact step h_c while any pair is in contact (the smallest of the open
    pairs' estimates), else h_f.
    """
    case = beam.case
    rec = Record()
    S = beam.npairs
    h_fixed = case.fem.time_step
    v_ref = abs(case.initial.impact_velocity)
    m_ref = [reference_mass(beam, z0, k) for k in range(S)]
    h_c = contact_step(beam, m_ref[0], v_ref)
    for k in range(1, S):
        h_c = min(h_c, contact_step(beam, m_ref[k], v_ref, k))
    h_free = FREE_STEP_FACTOR * h_c
    if h_fixed is not None:
        h_c = h_free = h_fixed
    h_free = min(h_free, t_end / 20.0)
    h_c = min(h_c, h_free)

    steps = rejected = 0
    status, message = "success", "integration reached t_end"
    cs = beam.free_state
    events: list[ContactEvent | None] = [None] * S
    h_now = h_c
    s = integ.initial(0.0, z0, zd0, None)
    res = integ.evaluate(s, None)
    _warm_up(integ, s, h_c)
    wall0 = time.perf_counter()
    gap_tol_base = 1e-3

    def phase_of(c: ContactState) -> str:
        return "contact" if c.any else "free"

    def open_pair(k: int) -> None:
        """Pair k starts its contact at the current state (s, res)."""
        nonlocal cs, h_c
        if stop_at_impact:
            raise _Stop("impact", "impact at t = 0" if s.t == 0.0 else f"impact at t = {s.t:.12g} s")
        if len(rec.contacts) >= case.solver.max_contacts:
            raise _Stop(
                "max-contacts",
                f"stopped at t = {s.t:.9g} s after {len(rec.contacts)} contacts "
                "(solver.max_contacts); the contacts accumulate (Zeno-like)",
            )
        rate = -float(res.pair_gap_rate[k])
        law = beam.pairs[k].law
        m_eff = _effective_mass(beam, s.z, k) if law.name == "kelvin_voigt" else 1.0
        p = law.parameters(rate, m_eff)
        ev = ContactEvent(index=len(rec.contacts), onset=s.t, velocity_before=float(res.pair_gap_rate[k]), pair=k)
        rec.contacts.append(ev)
        h = h_fixed if h_fixed is not None else min(contact_step(beam, m_ref[k], rate, k), h_free)
        h_c = min(h_c, h) if cs.any else h
        cs = cs.with_pair(k, p)
        events[k] = ev

    def close_pair(k: int) -> None:
        """Pair k ends its contact at the current state (s, res)."""
        nonlocal cs
        ev = events[k]
        if ev is not None:
            ev.end = s.t
            ev.velocity_after = float(res.pair_gap_rate[k])
        cs = cs.with_pair(k, None)
        events[k] = None

    def gaps_of(st: State) -> list[tuple[float, float]]:
        return [(d, vn) for d, vn, _, _ in beam.gaps(st.z, st.zd, st.zdd)]

    def locate(
        s0: State, f0: float, s1: State, f1: float, h: float, sign: float, c: ContactState, tol: float, k: int
    ) -> State:
        """Cut the step back to where f = sign * gap of pair k crosses zero downwards (f0 > 0 >= f1)."""
        lo, flo = 0.0, f0
        hi, fhi, shi = h, f1, s1
        side = 0
        for _ in range(100):
            if -fhi <= tol or hi - lo <= 1e-9 * h:
                return shi
            hm = (lo * fhi - hi * flo) / (fhi - flo)
            hm = min(max(hm, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
            sm = _step_with_halving(integ, s0, hm, c)
            fm = sign * beam.gap(sm.z, sm.zd, sm.zdd, pair=k)[0]
            if fm <= 0.0:
                hi, fhi, shi = hm, fm, sm
                if side == -1:
                    flo *= 0.5
                side = -1
            else:
                lo, flo = hm, fm
                if side == 1:
                    fhi *= 0.5
                side = 1
        return shi

    def switch_others(k: int) -> None:
        """At a located event of pair k: another pair already penetrating and approaching starts its contact,
        another pair in contact found open ends it (two events closer than the location tolerance)."""
        nonlocal res
        for j in range(S):
            if j == k:
                continue
            d, vn = float(res.pair_gap[j]), float(res.pair_gap_rate[j])
            if cs.laws[j] is None and d < 0.0 and vn < -GRAZING_SPEED:
                open_pair(j)
            elif cs.laws[j] is not None and d > 0.0:
                close_pair(j)
            else:
                continue
            res = integ.evaluate(s, cs)
            sample(s, res, phase_of(cs), cs)

    try:
        started = False
        for k in range(S):
            if res.pair_gap[k] <= 1e-15 and res.pair_gap_rate[k] < -GRAZING_SPEED:
                open_pair(k)
                started = True
        if started:
            res = integ.evaluate(s, cs)
        sample(s, res, phase_of(cs), cs)
        next_progress = 0.0
        while s.t < t_end * (1.0 - 1e-12):
            h_nom = h_c if cs.any else h_free
            h = min(h_now, h_nom, t_end - s.t)
            try:
                s1 = integ.step(s, h, cs)
            except NewtonFailure as err:
                rejected += 1
                h_now = 0.5 * h
                if h_now < h_nom * 2.0**-MAX_HALVINGS:
                    raise SolverError(f"fem: step failed ({err}); step size underflow", s.t) from None
                continue
            h_now = h_nom
            g1 = gaps_of(s1)
            candidates = []  # (estimated fraction of the step, pair, a Hermite dip?)
            for k in range(S):
                d0, v0 = float(res.pair_gap[k]), float(res.pair_gap_rate[k])
                d1, v1 = g1[k]
                if cs.laws[k] is None:
                    if d1 < 0.0 and d0 >= 0.0:
                        candidates.append((d0 / (d0 - d1), k, False))
                    elif d0 > 0.0 and d1 > 0.0:
                        frac = _hermite_dip(d0, v0, d1, v1, h)
                        if frac is not None:
                            candidates.append((frac, k, True))
                elif d1 > 0.0 and d0 <= 0.0:
                    candidates.append((d0 / (d0 - d1), k, False))
            hit = None
            for frac, k, dip in sorted(candidates):
                if not dip:
                    hit = (k, s1, g1[k][0], h)
                    break
                s_dip = _step_with_halving(integ, s, frac * h, cs)
                d_dip = beam.gap(s_dip.z, s_dip.zd, s_dip.zdd, pair=k)[0]
                if d_dip < 0.0:
                    hit = (k, s_dip, d_dip, frac * h)
                    break
            if hit is not None:
                k, s_hit, d1, h_hit = hit
                d0, v0 = float(res.pair_gap[k]), float(res.pair_gap_rate[k])
                tol = max(gap_tol_base * max(abs(v0), abs(g1[k][1]), 1e-6) * h_c, 1e-15)
                if cs.laws[k] is None:
                    s1 = locate(s, d0, s_hit, d1, h_hit, 1.0, cs, tol, k)
                    res1 = integ.evaluate(s1, cs)
                    if cs.any:
                        _accumulate(rec, beam, s, s1, cs)
                    steps += 1
                    s, res = s1, res1
                    sample(s, res, phase_of(cs), cs)
                    if res.pair_gap_rate[k] < -GRAZING_SPEED:
                        open_pair(k)
                        res = integ.evaluate(s, cs)
                        sample(s, res, "contact", cs)
                else:
                    s1 = locate(s, -d0, s_hit, -d1, h_hit, -1.0, cs, tol, k)
                    res1 = integ.evaluate(s1, cs)
                    _accumulate(rec, beam, s, s1, cs)
                    steps += 1
                    s, res = s1, res1
                    sample(s, res, "contact", cs)
                    close_pair(k)
                    res = integ.evaluate(s, cs)
                    sample(s, res, phase_of(cs), cs)
                switch_others(k)
                continue
            res1 = integ.evaluate(s1, cs)
            if cs.any:
                _accumulate(rec, beam, s, s1, cs)
            steps += 1
            s, res = s1, res1
            sample(s, res, phase_of(cs), cs)
            if progress is not None and s.t >= next_progress:
                progress(s.t)
                next_progress = s.t + t_end / 200.0
    except _Stop as stop:
        status, message = stop.status, stop.message
    except SolverError as err:
        status, message = "failed", str(err)
    wall = time.perf_counter() - wall0
    return rec, RunInfo(status, message, steps, rejected, integ.iterations, wall, h_c, h_free), s


def _warm_up(integ: FemIntegrator, s: State, h: float) -> None:
    """Compile (or load from Numba's cache) every kernel before the clock starts."""
    its = integ.iterations
    try:
        integ.step(s, 1e-3 * h, None)
    except NewtonFailure:
        pass
    integ.iterations = its
    hermite_dip(1.0, 0.0, 1.0, 0.0, 1.0)
    integ.beam.energies(s.z, s.zd)
    integ.beam.measuring_velocities(s.z, s.zd)


class _Stop(Exception):
    def __init__(self, status: str, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


def _step_with_halving(integ: FemIntegrator, s: State, h: float, lawp: ContactState | np.ndarray | None) -> State:
    """A step of exactly h, taken as 2^k sub-steps if Newton fails."""
    for k in range(12):
        n = 2**k
        try:
            st = s
            for _ in range(n):
                st = integ.step(st, h / n, lawp)
            return st
        except NewtonFailure:
            continue
    raise SolverError("fem: Newton failed while locating a contact event", s.t)


def _accumulate(rec: Record, beam: FemBeam, s0: State, s1: State, cs: ContactState) -> None:
    """Store the dense-force data of a contact step for each pair in contact: its gap's (delta, delta',
    delta'') at both ends."""
    if beam.npairs == 1:
        g0 = beam.gap(s0.z, s0.zd, s0.zdd)[:3]
        g1 = beam.gap(s1.z, s1.zd, s1.zdd)[:3]
        rec.dense.append((s0.t, s1.t, g0, g1, cs.laws[0], 0))
        return
    gaps0 = beam.gaps(s0.z, s0.zd, s0.zdd)
    gaps1 = beam.gaps(s1.z, s1.zd, s1.zdd)
    for k, p in enumerate(cs.laws):
        if p is not None:
            rec.dense.append((s0.t, s1.t, gaps0[k][:3], gaps1[k][:3], p, k))


def _effective_mass(beam: FemBeam, z: np.ndarray, pair: int = 0) -> float:
    """1/(J M^-1 J^T) at a pair's point with the banded FE mass matrix (theta held if prescribed)."""
    from scipy.linalg import solve_banded

    zero = np.zeros_like(z)
    _, ab, _ = beam.residual(0.0, z, zero, zero, (1.0, 0.0, 0.0))
    J = beam.gap_jacobian(z, pair)
    if beam.prescribed:
        fix_first_dof(ab)
        J[0] = 0.0
    x = solve_banded((BAND, BAND), ab[BAND:], J)
    return float(1.0 / (J @ x))


__all__ = ["Record", "RunInfo", "contact_step", "reference_mass", "run"]
