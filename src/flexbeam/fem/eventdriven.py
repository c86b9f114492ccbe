"""The event-driven run of the finite-element beam: contact phases, located events, step sizes.

Contact
-------
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
impact velocity of the case).  The free-flight factor is kept small because the
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
from ..solution import ContactEvent
from .banded import BAND, fix_first_dof
from .gap import hermite_dip
from .integrator import FemIntegrator, NewtonFailure, State, StepResult
from .model import FemBeam

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
    # dense force on contact steps: (t0, t1, (d, d', d'')_0, (d, d', d'')_1, lawp)
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


def reference_mass(beam: FemBeam, z: np.ndarray) -> float:
    """Effective mass used only to size the contact step (see the module docstring)."""
    case = beam.case
    xP = case.contact.position
    if not beam.prescribed:
        X, _, _ = beam.nodes(z, np.zeros_like(z))
        _, _, _, Jn = beam.gap(z, np.zeros_like(z))
        p = X[beam.pnode]
        J_theta = float(Jn @ np.array([-p[1], p[0], 1.0]))
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


def contact_step(beam: FemBeam, mass: float, speed: float) -> float:
    """h_c = t_c / STEPS_PER_CONTACT from the rigid Hertz impact estimate."""
    law = beam.law
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
    sample: Callable[[State, StepResult, str, np.ndarray | None], None],
    progress: Callable[[float], None] | None = None,
    stop_at_impact: bool = False,
) -> tuple[Record, RunInfo, State]:
    """Integrate from (z0, zd0) at t = 0 to ``t_end``, recording samples.

    ``sample(state, result, phase, lawp)`` is called at every accepted state (twice
    at a phase change, once per phase; ``lawp`` is the contact-law parameter vector
    in a contact phase, else None).  With ``stop_at_impact`` the run ends at the
    first contact onset (status "impact").
    """
    case = beam.case
    rec = Record()
    law = beam.law
    h_fixed = case.fem.time_step
    v_ref = abs(case.initial.impact_velocity)
    m_ref = reference_mass(beam, z0)
    h_c = contact_step(beam, m_ref, v_ref)
    h_free = FREE_STEP_FACTOR * h_c
    if h_fixed is not None:
        h_c = h_free = h_fixed
    h_free = min(h_free, t_end / 20.0)
    h_c = min(h_c, h_free)

    steps = rejected = 0
    status, message = "success", "integration reached t_end"
    in_contact = False
    lawp: np.ndarray | None = None
    event: ContactEvent | None = None
    h_now = h_c
    s = integ.initial(0.0, z0, zd0, None)
    res = integ.evaluate(s, None)
    _warm_up(integ, s, h_c)
    wall0 = time.perf_counter()
    gap_tol_base = 1e-3

    def start_contact(s: State, res: StepResult) -> tuple[np.ndarray, ContactEvent, float]:
        if len(rec.contacts) >= case.solver.max_contacts:
            raise _Stop(
                "max-contacts",
                f"stopped at t = {s.t:.9g} s after {len(rec.contacts)} contacts "
                "(solver.max_contacts); the contacts accumulate (Zeno-like)",
            )
        rate = -res.gap_rate
        m_eff = _effective_mass(beam, s.z) if law.name == "kelvin_voigt" else 1.0
        p = law.parameters(rate, m_eff)
        ev = ContactEvent(index=len(rec.contacts), onset=s.t, velocity_before=res.gap_rate)
        rec.contacts.append(ev)
        h = h_fixed if h_fixed is not None else min(contact_step(beam, m_ref, rate), h_free)
        return p, ev, h

    def gap_of(st: State) -> tuple[float, float]:
        d, vn, _, _ = beam.gap(st.z, st.zd, st.zdd)
        return d, vn

    def locate(
        s0: State, f0: float, s1: State, f1: float, h: float, sign: float, lp: np.ndarray | None, tol: float
    ) -> State:
        """Cut the step back to where f = sign * gap crosses zero downwards (f0 > 0 >= f1)."""
        lo, flo = 0.0, f0
        hi, fhi, shi = h, f1, s1
        side = 0
        for _ in range(100):
            if -fhi <= tol or hi - lo <= 1e-9 * h:
                return shi
            hm = (lo * fhi - hi * flo) / (fhi - flo)
            hm = min(max(hm, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
            sm = _step_with_halving(integ, s0, hm, lp)
            fm = sign * gap_of(sm)[0]
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

    try:
        if res.gap <= 1e-15 and res.gap_rate < -GRAZING_SPEED:
            if stop_at_impact:
                raise _Stop("impact", "impact at t = 0")
            lawp, event, h_c = start_contact(s, res)
            in_contact = True
            res = integ.evaluate(s, lawp)
        sample(s, res, "contact" if in_contact else "free", lawp)
        next_progress = 0.0
        while s.t < t_end * (1.0 - 1e-12):
            h_nom = h_c if in_contact else h_free
            h = min(h_now, h_nom, t_end - s.t)
            try:
                s1 = integ.step(s, h, lawp)
            except NewtonFailure as err:
                rejected += 1
                h_now = 0.5 * h
                if h_now < h_nom * 2.0**-MAX_HALVINGS:
                    raise SolverError(f"fem: step failed ({err}); step size underflow", s.t) from None
                continue
            h_now = h_nom
            d0, v0 = res.gap, res.gap_rate
            d1, v1 = gap_of(s1)
            tol = max(gap_tol_base * max(abs(v0), abs(v1), 1e-6) * h_c, 1e-15)
            if not in_contact:
                crossing = d1 < 0.0 and d0 >= 0.0
                if not crossing and d0 > 0.0 and d1 > 0.0:
                    frac = _hermite_dip(d0, v0, d1, v1, h)
                    if frac is not None:
                        s_dip = _step_with_halving(integ, s, frac * h, None)
                        if gap_of(s_dip)[0] < 0.0:
                            s1, d1, h, crossing = s_dip, gap_of(s_dip)[0], frac * h, True
                if crossing:
                    s1 = locate(s, d0, s1, d1, h, 1.0, None, tol)
                    res1 = integ.evaluate(s1, None)
                    steps += 1
                    s, res = s1, res1
                    if res.gap_rate < -GRAZING_SPEED:
                        sample(s, res, "free", None)
                        if stop_at_impact:
                            raise _Stop("impact", f"impact at t = {s.t:.12g} s")
                        lawp, event, h_c = start_contact(s, res)
                        in_contact = True
                        res = integ.evaluate(s, lawp)
                        sample(s, res, "contact", lawp)
                    else:
                        sample(s, res, "free", None)
                    continue
            else:
                if d1 > 0.0 and d0 <= 0.0:
                    s1 = locate(s, -d0, s1, -d1, h, -1.0, lawp, tol)
                    res1 = integ.evaluate(s1, lawp)
                    _accumulate(rec, beam, s, s1, lawp)
                    steps += 1
                    s, res = s1, res1
                    sample(s, res, "contact", lawp)
                    if event is not None:
                        event.end = s.t
                        event.velocity_after = res.gap_rate
                    in_contact, lawp, event = False, None, None
                    res = integ.evaluate(s, None)
                    sample(s, res, "free", None)
                    continue
            res1 = integ.evaluate(s1, lawp)
            if in_contact:
                _accumulate(rec, beam, s, s1, lawp)
            steps += 1
            s, res = s1, res1
            sample(s, res, "contact" if in_contact else "free", lawp)
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


def _step_with_halving(integ: FemIntegrator, s: State, h: float, lawp: np.ndarray | None) -> State:
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


def _accumulate(rec: Record, beam: FemBeam, s0: State, s1: State, lawp: np.ndarray) -> None:
    """Store the dense-force data of a contact step: the gap's (delta, delta', delta'') at both ends."""
    g0 = beam.gap(s0.z, s0.zd, s0.zdd)[:3]
    g1 = beam.gap(s1.z, s1.zd, s1.zdd)[:3]
    rec.dense.append((s0.t, s1.t, g0, g1, lawp))


def _effective_mass(beam: FemBeam, z: np.ndarray) -> float:
    """1/(J M^-1 J^T) at P with the banded FE mass matrix (theta held if prescribed)."""
    from scipy.linalg import solve_banded

    zero = np.zeros_like(z)
    _, ab, _ = beam.residual(0.0, z, zero, zero, (1.0, 0.0, 0.0))
    J = beam.gap_jacobian(z)
    if beam.prescribed:
        fix_first_dof(ab)
        J[0] = 0.0
    x = solve_banded((BAND, BAND), ab[BAND:], J)
    return float(1.0 / (J @ x))


__all__ = ["Record", "RunInfo", "contact_step", "reference_mass", "run"]
