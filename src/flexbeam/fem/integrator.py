"""Generalized-alpha time stepping of the finite-element beam (one step, Newton on z_{n+1}).

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


The contact events and the step sizes are handled by :mod:`flexbeam.fem.eventdriven`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.linalg.lapack import dgbsv

from ..errors import SolverError
from .assembly import POUT_COLUMNS, newton
from .banded import BAND, fix_first_dof
from .beam import FemBeam
from .contact_law import law_force
from .pairs import ContactState

#: Newton: scaled increment tolerance and iteration limit
NEWTON_TOL = 1e-10
NEWTON_MAX_ITER = 30


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
    """Output quantities at an accepted state: pair 0's contact force, its elastic part, gap and gap rate,
    the joint torque, and the same per pair (arrays over the pairs; forces zero for free pairs), with each pair's
    contact point's material coordinate x (it moves for a pair anywhere)."""

    force: float
    elastic_force: float
    gap: float
    gap_rate: float
    torque: float
    pair_force: np.ndarray | None = None
    pair_elastic_force: np.ndarray | None = None
    pair_gap: np.ndarray | None = None
    pair_gap_rate: np.ndarray | None = None
    pair_position: np.ndarray | None = None
    pair_friction: np.ndarray | None = None  #: friction force along the tangent t = (-n_y, n_x) [N] (frictional)
    pair_slip: np.ndarray | None = None  #: slip velocity along t [m/s] (frictional runs)


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
        self._ab = np.zeros((3 * BAND + 1, n))
        self._scale = beam.increment_scale()
        self._pout = np.zeros((beam.npairs, POUT_COLUMNS))
        self.iterations = 0

    # ------------------------------------------------------------- helpers
    def _drive(self, t: float, z: np.ndarray, zd: np.ndarray, zdd: np.ndarray) -> None:
        if self.beam.prescribed:
            z[0], zd[0], zdd[0] = self.beam.drive.motion(t)

    def _solve(self, ab: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        if self.beam.prescribed:
            fix_first_dof(ab)
            rhs[0] = 0.0
        _, _, x, info = dgbsv(BAND, BAND, ab, rhs, overwrite_ab=1, overwrite_b=1)
        if info != 0:
            raise NewtonFailure(f"singular iteration matrix (dgbsv info = {info})")
        return x

    def initial(self, t: float, z: np.ndarray, zd: np.ndarray, lawp: ContactState | np.ndarray | None) -> State:
        """Consistent initial accelerations z''(t0) = -M^-1 R(z, z', 0); a_0 = z''_0."""
        z, zd = z.copy(), zd.copy()
        zdd = np.zeros_like(z)
        self._drive(t, z, zd, zdd)
        R, ab, _ = self.beam.residual(t, z, zd, zdd, (1.0, 0.0, 0.0), True, lawp, (self._R, self._ab))
        zdd += self._solve(ab, -R)
        if not np.all(np.isfinite(zdd)):
            raise SolverError("fem: non-finite initial acceleration", t)
        return State(t, z, zd, zdd, zdd.copy())

    def evaluate(self, s: State, lawp: ContactState | np.ndarray | None) -> StepResult:
        """Contact forces F_k = law_force(p_k, -delta_k, -delta_k') of the pairs in contact, gaps and joint
        torque at an accepted state."""
        beam = self.beam
        cs = beam.contact_state(lawp)
        S = beam.npairs
        Fs, Fks, ds, vns = np.zeros(S), np.zeros(S), np.empty(S), np.empty(S)
        for k, (d, vn, _, _) in enumerate(beam.gaps(s.z, s.zd, s.zdd)):
            ds[k], vns[k] = d, vn
            p = cs.laws[k]
            if p is not None:
                F, Fk, _, _ = law_force(p, -d, -vn)
                Fs[k], Fks[k] = F, Fk
        frictional = beam.frictional
        if beam.prescribed or frictional:  # the residual's pass also writes each pair's friction and slip
            R, _, _ = beam.residual(s.t, s.z, s.zd, s.zdd, (0.0, 0.0, 0.0), False, cs, (self._R, self._ab))
        torque = float(R[0]) if beam.prescribed else beam.torque(s.t)
        pos = np.array([beam.contact_point(s.z, k)[2] for k in range(S)]) if S > 1 or beam.any_anywhere else None
        out = StepResult(float(Fs[0]), float(Fks[0]), float(ds[0]), float(vns[0]), torque, Fs, Fks, ds, vns, pos)
        if frictional:
            out.pair_friction, out.pair_slip = beam.pair_outputs[:, 5].copy(), beam.pair_outputs[:, 6].copy()
        return out

    # ---------------------------------------------------------------- step
    def step(self, s: State, h: float, lawp: ContactState | np.ndarray | None) -> State:
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
        cs = beam.contact_state(lawp)
        backup = (z.copy(), zd.copy(), zdd.copy(), a.copy())
        its, code = newton(
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
            *beam.model_args(t1),
            beam.damping,
            *beam.contact_args(),
            cs.active,
            cs.params,
            self._pout,
            self._R,
            self._ab,
        )
        self.iterations += its
        if code == 2:  # a tiny pivot: redo with LAPACK's partial pivoting
            z, zd, zdd, a = backup
            self._newton_pivoting(t1, z, zd, zdd, a, cM, cC, ca, cs)
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


__all__ = ["FemIntegrator", "GeneralizedAlpha", "NewtonFailure", "State", "StepResult"]
