"""Generalized-alpha time integration of the finite-element beam with contact events.

Scheme
------
Chung & Hulbert (1993), *J. Appl. Mech.* 60, 371-375, in the form of Arnold & Brüls
(2007), *Multibody Syst. Dyn.* 18, 185-202, which evaluates the equations of motion
at the end of the step (so the contact force, a prescribed theta(t) and the outputs
all live at t_{n+1}) and carries an algorithmic acceleration a:

    R(z_{n+1}, z'_{n+1}, z''_{n+1}, t_{n+1}) = 0,
    (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) z''_{n+1} + alpha_f z''_n,
    z_{n+1}  = z_n + h z'_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1},
    z'_{n+1} = z'_n + h (1 - gamma) a_n + h gamma a_{n+1},

    alpha_m = (2 rho_inf - 1)/(rho_inf + 1),  alpha_f = rho_inf/(rho_inf + 1),
    gamma = 1/2 - alpha_m + alpha_f,          beta = (1 - alpha_m + alpha_f)^2 / 4,

second-order accurate, unconditionally stable, with spectral radius rho_inf at
infinite frequency (rho_inf = 1: the trapezoidal rule, no numerical dissipation).
Each step is solved by Newton's method on z_{n+1} with the iteration matrix
S = c_M M + c_C C + K, c_M = (1 - alpha_m)/((1 - alpha_f) beta h^2),
c_C = gamma/(beta h), assembled in band storage and factorised by LAPACK ``dgbsv``.

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
from scipy.linalg.lapack import dgbsv

from ..contact.hertz import rigid_hertz_impact
from ..contact.laws import law_force
from ..errors import SolverError
from ..methods.base import ContactEvent
from . import kernels as kn
from .model import NO_LAW, FemBeam

#: contact onsets with |delta'| below this are grazing touches, not impacts [m/s]
GRAZING_SPEED = 1e-9
#: Newton: scaled increment tolerance and iteration limit
NEWTON_TOL = 1e-10
NEWTON_MAX_ITER = 30
#: how many halvings of a failing step before giving up
MAX_HALVINGS = 30
#: steps per estimated contact duration, and free/contact step ratio
STEPS_PER_CONTACT = 200
FREE_STEP_FACTOR = 2.0


@dataclass
class State:
    """Accepted state at time t: coordinates, rates, accelerations, algorithmic a."""

    t: float
    z: np.ndarray
    zd: np.ndarray
    zdd: np.ndarray
    a: np.ndarray


class NewtonFailure(Exception):
    """Newton's method did not converge for one step."""


@dataclass
class GeneralizedAlpha:
    """Chung-Hulbert generalized-alpha parameters for a given rho_inf."""

    rho_inf: float
    alpha_m: float = field(init=False)
    alpha_f: float = field(init=False)
    gamma: float = field(init=False)
    beta: float = field(init=False)

    def __post_init__(self) -> None:
        r = self.rho_inf
        self.alpha_m = (2.0 * r - 1.0) / (r + 1.0)
        self.alpha_f = r / (r + 1.0)
        self.gamma = 0.5 - self.alpha_m + self.alpha_f
        self.beta = 0.25 * (1.0 - self.alpha_m + self.alpha_f) ** 2


@dataclass
class StepResult:
    """Output quantities at an accepted state."""

    force: float
    elastic_force: float
    gap: float
    gap_rate: float
    torque: float


class FemIntegrator:
    """Steps a :class:`FemBeam` with the generalized-alpha scheme.

    Parameters
    ----------
    beam
        The finite-element model.
    rho_inf
        Spectral radius at infinite frequency.
    """

    def __init__(self, beam: FemBeam, rho_inf: float) -> None:
        self.beam = beam
        self.scheme = GeneralizedAlpha(rho_inf)
        n = beam.size
        self._R = np.empty(n)
        self._ab = np.zeros((3 * kn.BAND + 1, n))
        self._scale = beam._increment_scale()
        self.iterations = 0

    # ------------------------------------------------------------- helpers
    def _drive(self, t: float, z: np.ndarray, zd: np.ndarray, zdd: np.ndarray) -> None:
        if self.beam.prescribed:
            z[0], zd[0], zdd[0] = self.beam.drive.motion(t)

    def _solve(self, ab: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        if self.beam.prescribed:
            kn.fix_first_dof(ab)
            rhs[0] = 0.0
        _, _, x, info = dgbsv(kn.BAND, kn.BAND, ab, rhs, overwrite_ab=1, overwrite_b=1)
        if info != 0:
            raise NewtonFailure(f"singular iteration matrix (dgbsv info = {info})")
        return x

    def initial(self, t: float, z: np.ndarray, zd: np.ndarray, lawp: np.ndarray | None) -> State:
        """Consistent initial accelerations z''(t0) = -M^-1 R(z, z', 0); a_0 = z''_0."""
        z, zd = z.copy(), zd.copy()
        zdd = np.zeros_like(z)
        self._drive(t, z, zd, zdd)
        R, ab, _ = self.beam.residual(t, z, zd, zdd, (1.0, 0.0, 0.0), True, lawp, (self._R, self._ab))
        zdd += self._solve(ab, -R)
        if not np.all(np.isfinite(zdd)):
            raise SolverError("fem: non-finite initial acceleration", t)
        return State(t, z, zd, zdd, zdd.copy())

    def evaluate(self, s: State, lawp: np.ndarray | None) -> StepResult:
        """Contact force, gap and joint torque at an accepted state."""
        beam = self.beam
        d, vn, _, _ = beam.gap(s.z, s.zd, s.zdd)
        F = Fk = 0.0
        if lawp is not None:
            F, Fk = law_force(lawp, -d, -vn)
        if beam.prescribed:
            R, _, _ = beam.residual(s.t, s.z, s.zd, s.zdd, (0.0, 0.0, 0.0), False, lawp, (self._R, self._ab))
            torque = float(R[0])
        else:
            torque = beam.torque(s.t)
        return StepResult(float(F), float(Fk), d, vn, torque)

    # ---------------------------------------------------------------- step
    def step(self, s: State, h: float, lawp: np.ndarray | None) -> State:
        """One generalized-alpha step of size h from s (Newton on z_{n+1}).

        Raises
        ------
        NewtonFailure
            When Newton does not converge or the state becomes non-finite.
        """
        p = self.scheme
        am, af, g, b = p.alpha_m, p.alpha_f, p.gamma, p.beta
        t1 = s.t + h
        # predictor: a_{n+1} = a_n
        a = s.a.copy()
        z = s.z + h * s.zd + h * h * (0.5 - b) * s.a + h * h * b * a
        zd = s.zd + h * (1.0 - g) * s.a + h * g * a
        zdd = ((1.0 - am) * a + am * s.a - af * s.zdd) / (1.0 - af)
        self._drive(t1, z, zd, zdd)
        cM = (1.0 - am) / ((1.0 - af) * b * h * h)
        cC = g / (b * h)
        ca = 1.0 / (b * h * h)
        beam = self.beam
        in_contact = lawp is not None
        backup = (z.copy(), zd.copy(), zdd.copy(), a.copy())
        its, code = kn.newton(
            z,
            zd,
            zdd,
            a,
            cM,
            cC,
            ca,
            self._scale,
            NEWTON_TOL,
            NEWTON_MAX_ITER,
            beam.prescribed,
            beam.torque(t1),
            *beam.model_args(),
            *beam.contact_args(),
            in_contact,
            lawp if in_contact else NO_LAW,
            self._R,
            self._ab,
        )
        self.iterations += its
        if code == 2:  # a tiny pivot: redo with LAPACK's partial pivoting
            z, zd, zdd, a = backup
            self._newton_pivoting(t1, z, zd, zdd, a, cM, cC, ca, lawp)
        elif code == 1:
            raise NewtonFailure(f"Newton did not converge in {NEWTON_MAX_ITER} iterations")
        elif code == 3:
            raise NewtonFailure("non-finite Newton increment")
        if beam.prescribed:
            a[0] = zdd[0]
        return State(t1, z, zd, zdd, a)

    def _newton_pivoting(self, t1, z, zd, zdd, a, cM, cC, ca, lawp) -> None:
        for _ in range(NEWTON_MAX_ITER):
            self.iterations += 1
            R, ab, _ = self.beam.residual(t1, z, zd, zdd, (cM, cC, 1.0), True, lawp, (self._R, self._ab))
            dz = self._solve(ab, -R)
            if not np.all(np.isfinite(dz)):
                raise NewtonFailure("non-finite Newton increment")
            z += dz
            zd += cC * dz
            zdd += cM * dz
            a += ca * dz
            if np.max(np.abs(dz) / self._scale) < NEWTON_TOL:
                return
        raise NewtonFailure(f"Newton did not converge in {NEWTON_MAX_ITER} iterations")


# ---------------------------------------------------------------------------
# the event-driven run


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
    s = kn.hermite_dip(g0, v0, g1, v1, h)
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
    kn.hermite_dip(1.0, 0.0, 1.0, 0.0, 1.0)
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
        kn.fix_first_dof(ab)
        J[0] = 0.0
    x = solve_banded((kn.BAND, kn.BAND), ab[kn.BAND :], J)
    return float(1.0 / (J @ x))


__all__ = ["FemIntegrator", "GeneralizedAlpha", "State", "run"]
