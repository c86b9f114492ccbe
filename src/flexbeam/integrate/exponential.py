"""Production integrator: exact modal propagation + Gauss collocation (see the kernels).

Same contract as :func:`flexbeam.integrate.eventdriven.integrate` (the scipy reference
path): it drives an impact method's phases, locates the impact and separation
events, and returns a :class:`~flexbeam.integrate.eventdriven.RunResult` whose
samples :func:`flexbeam.simulation.collect` turns into a Solution.

Step control uses the end-state response to the top Legendre component of the
collocated forcing as error estimate (order p of the interpolant, while the
collocation solution itself is superconvergent, order 2p at the step end).

Events:

* *impact* (free flight): the gap over an accepted step is sampled on the exact
  dense output.  Modal content too fast for the sampling is bounded by
  B = sum_k |(Psi^T J)_k| (|free amplitude_k| + 2 max|f_k| / w_k^2); the step is
  declared contact-free only if min(samples) - 2B > 0, otherwise the sampling is
  refined until every mode that can reach the obstacle is resolved.  Crossings and
  Hermite-predicted dips are then located by :func:`scipy.optimize.brentq` on the
  dense output, and the step is retaken to end at the event.
* *separation* (CCFM): the gap's upward crossing, likewise.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
from scipy.integrate import DenseOutput
from scipy.linalg import eigh
from scipy.optimize import brentq

from ..model.system import BeamSystem
from .eventdriven import MAX_STALLED, Phase, PhaseMethod, RunResult, Segment, Stop, _sample_grid, start_run
from .exponential_kernels import (
    P_NODES,
    collocation_step,
    dense_states,
    gaps_at,
    gauss_tables,
    integrate_rates,
    node_forcing,
)

_PROFILES = {"constant-rate": 0, "kane-spinup": 1}


class ModalIntegrator:
    """Exponential collocation integrator for one :class:`BeamSystem`."""

    def __init__(self, system: BeamSystem, rtol: float = 1e-7, atol: float = 1e-12) -> None:
        self.system = system
        self.rtol, self.atol = rtol, atol
        b = system.beam
        n = b.n
        M0 = system.mass_matrix(0.0, system.state(0.0, 0.0))
        if system.prescribed:
            M0 = np.ascontiguousarray(b.Mff)
            K0 = np.ascontiguousarray(b.Kff)
        else:
            K0 = np.zeros((n + 1, n + 1))
            K0[1:, 1:] = b.Kff
        w2, Psi = eigh(K0, M0)
        w2 = np.where(w2 < 1e-10 * max(float(np.max(w2, initial=0.0)), 1.0), 0.0, w2)
        self.omega = np.sqrt(w2)
        self.Psi = np.ascontiguousarray(Psi)
        self.PsiT = np.ascontiguousarray(Psi.T)
        self.to_modal = np.ascontiguousarray(Psi.T @ M0)  # eta = Psi^T M0 z
        self.N = self.omega.size
        M0inv = np.linalg.inv(system.mass_matrix(0.0, system.state(0.0, 0.0)))
        self.model = (
            n, b.hub_inertia + b.J0, b.m1, np.ascontiguousarray(b.Mff - b.D), b.Mff, b.mtf, b.Kff, b.sf, b.G,
            system.g, np.ascontiguousarray(M0inv[0]), float(M0inv[0, 0]),
        )  # fmt: skip
        spec = system.drive.spec
        self.drive = (
            _PROFILES[spec.profile], float(spec.spin_rate), float(spec.spin_up_time),
            float(system.drive.theta0), float(spec.torque if spec.kind == "torque" else 0.0),
        )  # fmt: skip
        P, o = system.contact.point, system.contact
        self.point = (P.base, P.phi, P.dphi, P.H, P.offset)
        self.obstacle = (o.kind, o.centre, o.radius, o.normal)
        self.c, self.b, self.Vinv, self.top, self.proj = gauss_tables(P_NODES)
        p = P_NODES
        self.work = tuple(np.empty(shape) for shape in ((self.N, p + 1),) * 3 + ((self.N, p + 1, p),) * 2)
        self.h = None

    # ----------------------------------------------------------- conversions
    def split(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, float]:
        N = self.N
        z, zd = y[:N], y[N : 2 * N]
        return self.to_modal @ z, self.to_modal @ zd, float(y[-2]), float(y[-1])

    def assemble(self, Z: np.ndarray, ZD: np.ndarray, Ed: np.ndarray, W: np.ndarray) -> np.ndarray:
        return np.concatenate((Z, ZD, Ed[:, None], W[:, None]), axis=1)

    # ------------------------------------------------------------------ step
    def step(self, t0, h, eta0, v0, mode, lawp, f_guess, F_guess):
        return collocation_step(
            t0, h, eta0, v0, f_guess, F_guess, mode, lawp, self.omega, self.Psi, self.PsiT, self.c, self.b,
            self.Vinv, self.proj, self.top, self.model, self.system.prescribed, self.drive, self.point,
            self.obstacle, self.atol, self.rtol, *self.work,
        )  # fmt: skip

    def dense(self, t0, h, eta0, v0, f, s):
        return dense_states(t0, h, eta0, v0, f, np.atleast_1d(np.asarray(s, float)), self.Psi, self.omega,
                            self.Vinv)

    def gaps(self, t0, h, eta0, v0, f, s):
        s = np.atleast_1d(np.asarray(s, float))
        Z, ZD = self.dense(t0, h, eta0, v0, f, s)
        return gaps_at(t0 + s * h, Z, ZD, self.system.prescribed, self.drive, self.point, self.obstacle,
                       self.system.n)

    def initial_forcing(self, t, eta, v, mode):
        z, zd = self.Psi @ eta, self.Psi @ v
        rest, g, *_ = node_forcing(t, z, zd, self.model, self.system.prescribed, self.drive, self.point,
                                   self.obstacle, mode != 0)
        f = self.PsiT @ rest
        return np.tile(f, (P_NODES, 1))

    # ------------------------------------------------------------ events
    def _fast_bound(self, t0, h, eta0, v0, f, m):
        """Bound on the gap contribution of modes too fast for m samples per step."""
        w = self.omega
        unresolved = w * h / m > math.pi / 4
        if not unresolved.any():
            return 0.0, None
        z0, zd0 = self.Psi @ eta0, self.Psi @ v0
        _, _, _, _, _, _, _, J = node_forcing(t0, z0, zd0, self.model, self.system.prescribed, self.drive,
                                              self.point, self.obstacle, True)
        PJ = self.PsiT @ (J[1:] if self.system.prescribed else J)
        amp = np.sqrt(eta0**2 + (v0 / np.where(w > 0, w, 1.0)) ** 2)
        forced = 2.0 * np.max(np.abs(f), axis=0) / np.where(w > 0, w**2, 1.0)
        contrib = np.abs(PJ) * (amp + forced)
        return float(np.sum(contrib[unresolved])), contrib

    def find_event(self, t0, h, eta0, v0, f, direction):
        """First crossing of the gap in ``direction`` inside the step, as a fraction s.

        Returns None when the step is provably free of it, a fraction in (0, 1] at a
        located crossing, or -1.0 when the step is too long to decide cheaply (modes
        that could reach the obstacle are not resolved by 64 samples): the caller then
        shortens the step.
        """
        g = lambda x: float(self.gaps(t0, h, eta0, v0, f, [x])[0][0])  # noqa: E731
        m = 16
        while True:
            s = np.linspace(0.0, 1.0, m + 1)
            d, dv = self.gaps(t0, h, eta0, v0, f, s)
            B, _ = self._fast_bound(t0, h, eta0, v0, f, m)
            leaving = d[0] > 0.0 or dv[0] > 0.0
            if direction < 0 and leaving and np.min(d[1:]) - 2.0 * B > 0.0:
                return None
            if B == 0.0:
                return _scan_arrays(s, d, dv * h, direction, g)
            if m >= 64:
                return -1.0
            m *= 4


def _scan_arrays(s, d, rate, direction, g) -> float | None:
    """Earliest root (fraction s) of sampled (d, rate) in ``direction``, refined on g.

    Checks, per interval: a sign change; an excursion that starts on (or just behind)
    zero, leaves, and comes back; and a dip predicted by the cubic Hermite interpolant
    through (d, rate) at both ends.  Vectorised: only flagged intervals are refined.
    """
    sign = -1.0 if direction < 0 else 1.0  # crossing towards this sign
    a, b = d[:-1], d[1:]
    ra, rb = rate[:-1], rate[1:]
    hh = np.diff(s)
    cross = (a > 0.0) & (b <= 0.0) if sign < 0 else (a < 0.0) & (b >= 0.0)
    hump = (-sign * a <= 0.0) & (-sign * ra > 0.0) & (-sign * b < 0.0)
    same = (a > 0) & (b > 0) if sign < 0 else (a < 0) & (b < 0)
    x = np.linspace(0.0, 1.0, 17)[:, None]
    h00, h10 = 2 * x**3 - 3 * x**2 + 1, x**3 - 2 * x**2 + x
    h01, h11 = -2 * x**3 + 3 * x**2, x**3 - x**2
    poly = h00 * a + h10 * hh * ra + h01 * b + h11 * hh * rb
    dip = same & ((poly.min(axis=0) < 0.0) if sign < 0 else (poly.max(axis=0) > 0.0))
    flagged = np.nonzero(cross | hump | dip)[0]
    for i in flagged:
        if cross[i]:
            if b[i] == 0.0:
                return float(s[i + 1])
            return float(brentq(g, s[i], s[i + 1], xtol=1e-15, rtol=1e-14))
        if hump[i]:
            from scipy.optimize import minimize_scalar

            res = minimize_scalar(lambda v: sign * g(v), bounds=(s[i], s[i + 1]), method="bounded",
                                  options={"xatol": 1e-14})
            if -sign * g(float(res.x)) > 0.0:
                return float(brentq(g, float(res.x), s[i + 1], xtol=1e-15, rtol=1e-14))
            continue
        xs = s[i] + x[:, 0] * hh[i]
        vals = np.array([g(v) for v in xs])
        for k in range(xs.size - 1):
            if (sign < 0 and vals[k] > 0.0 >= vals[k + 1]) or (sign > 0 and vals[k] < 0.0 <= vals[k + 1]):
                return float(brentq(g, xs[k], xs[k + 1], xtol=1e-15, rtol=1e-14))
    return None


class _StepDense(DenseOutput):
    """Dense output of one accepted step in the reference state layout."""

    def __init__(self, integ: ModalIntegrator, t0, h, eta0, v0, f, Ed0, W0, diss, power):
        super().__init__(t0, t0 + h)
        self.args = (integ, t0, h, eta0, v0, f, Ed0, W0, diss, power)

    def _call_impl(self, t):
        integ, t0, h, eta0, v0, f, Ed0, W0, diss, power = self.args
        tt = np.atleast_1d(t)
        s = (tt - t0) / h
        Z, ZD = integ.dense(t0, h, eta0, v0, f, s)
        Ed = Ed0 + integrate_rates(diss, s, integ.Vinv, h)
        W = W0 + integrate_rates(power, s, integ.Vinv, h)
        Y = integ.assemble(Z, ZD, Ed, W)
        return Y[0] if np.ndim(t) == 0 else Y.T


def integrate_modal(
    method: PhaseMethod,
    system: BeamSystem,
    y0: np.ndarray,
    t_end: float,
    rtol: float = 1e-7,
    atol: float = 1e-12,
    max_step: float | None = None,
    progress: Callable[[float], None] | None = None,
) -> RunResult:
    """Integrate from 0 to ``t_end`` with the exponential collocation integrator."""
    integ = ModalIntegrator(system, rtol, atol)
    t = 0.0
    segments: list[Segment] = []
    steps = nfev = 0
    status, message = "success", "integration reached t_end"
    wall0 = time.perf_counter()
    started = start_run(method, y0, segments)
    if isinstance(started, RunResult):
        return started
    phase, y = started
    h = min(1e-4, t_end)
    cap = max_step or math.inf
    records: list[tuple[Segment, _StepDense]] = []
    stalled = 0
    while t < t_end and status == "success":
        mode = phase.data.get("mode", 0)
        lawp = phase.data.get("p", np.zeros(4))
        seg = Segment(phase, t, t, [np.array([t])], [y[None, :].copy()])
        segments.append(seg)
        eta, v, Ed, W = integ.split(y)
        f_guess = integ.initial_forcing(t, eta, v, mode)
        F_guess = np.zeros(P_NODES)
        direction = -1 if mode == 0 else +1
        event_hit = False
        phase_cap = cap
        if mode == 1:
            phase_cap = min(cap, _contact_step_cap(system, t, y, lawp))
        while t < t_end:
            h = min(h, t_end - t, phase_cap)
            ok, eta1, v1, f, F, err, diss, power = integ.step(t, h, eta, v, mode, lawp, f_guess, F_guess)
            steps += 1
            nfev += P_NODES
            if not ok or not np.isfinite(err) or err > 1.0:
                if not ok or not np.isfinite(err):
                    h *= 0.25
                else:
                    h *= max(0.2, 0.9 * err ** (-1.0 / P_NODES))
                if h < 1e-15 * max(1.0, t):
                    status, message = "failed", f"step size underflow at t = {t:.9g} s"
                    break
                continue
            if mode == 2:
                s_ev = _multiplier_release(integ.c, F)
            else:
                s_ev = integ.find_event(t, h, eta, v, f, direction)
            if s_ev is not None and s_ev < 0.0:  # undecided: too long a step near the obstacle
                h *= 0.25
                continue
            if s_ev is not None:
                h_ev = s_ev * h
                if h_ev <= 0.0:
                    event_hit = True
                else:
                    ok2, eta1, v1, f2, F2, err2, diss2, power2 = integ.step(t, h_ev, eta, v, mode, lawp, f, F)
                    if ok2:
                        h_taken, f, F, diss, power = h_ev, f2, F2, diss2, power2
                        event_hit = True
                    else:
                        h *= 0.5
                        continue
            else:
                h_taken = h
            if event_hit and h_ev <= 0.0:
                break
            records.append((seg, _StepDense(integ, t, h_taken, eta, v, f, Ed, W, diss, power)))
            Ed = Ed + h_taken * float(integ.b @ diss)
            W = W + h_taken * float(integ.b @ power)
            t = t + h_taken
            eta, v = eta1, v1
            f_guess, F_guess = f, F
            y = integ.assemble((integ.Psi @ eta)[None, :], (integ.Psi @ v)[None, :], np.array([Ed]),
                               np.array([W]))[0]
            seg.times.append(np.array([t]))
            seg.states.append(y[None, :].copy())
            seg.t1 = t
            if progress is not None:
                progress(t)
            if not event_hit:
                h = h_taken * min(4.0, max(0.2, 0.9 * max(err, 1e-10) ** (-1.0 / (P_NODES + 1))))
            if event_hit:
                break
        if status != "success":
            break
        if event_hit:
            try:
                phase, y = method.transition(phase, phase.events[0], t, y)
            except Stop as stop:
                status, message = stop.status, stop.message
                break
            stalled = stalled + 1 if seg.t1 == seg.t0 else 0
            if stalled > MAX_STALLED:
                status, message = "failed", f"events keep recurring without progress at t = {t:.9g} s"
                break
            h = min(h, 1e-5)
    wall = time.perf_counter() - wall0
    _sample(records)
    return RunResult(segments, status, message, t, wall, steps, nfev)


def _lagrange(c: np.ndarray, values: np.ndarray, s: np.ndarray) -> np.ndarray:
    out = np.zeros_like(s)
    for j in range(c.size):
        lj = np.ones_like(s)
        for m in range(c.size):
            if m != j:
                lj *= (s - c[m]) / (c[j] - c[m])
        out += lj * values[j]
    return out


def _multiplier_release(c: np.ndarray, lam: np.ndarray) -> float | None:
    """Fraction of the step where the collocated multiplier lambda(s) turns tensile, or None."""
    s = np.linspace(0.0, 1.0, 33)
    vals = _lagrange(c, lam, s)
    for i in range(s.size - 1):
        if vals[i] >= 0.0 > vals[i + 1]:
            fn = lambda x: float(_lagrange(c, lam, np.array([x]))[0])  # noqa: E731
            return float(brentq(fn, s[i], s[i + 1], xtol=1e-15)) if vals[i] > 0.0 else float(s[i])
    return None


CONTACT_STEPS = 40  # at least this many steps per (estimated) contact duration


def _contact_step_cap(system: BeamSystem, t: float, y: np.ndarray, lawp: np.ndarray) -> float:
    """t_c / CONTACT_STEPS with t_c the rigid-body Hertz duration at the onset's effective mass.

    The collocation is exact at the step ends but its dense output (used for the peak
    force) is of order p only, so the contact is resolved by enough steps.
    """
    from ..contact.hertz import rigid_hertz_impact

    speed = abs(system.gap(t, y)[1])
    m_eff = system.effective_mass(t, y)
    if speed <= 1e-9 or not math.isfinite(m_eff):
        return math.inf
    return rigid_hertz_impact(m_eff, speed, float(lawp[0]), float(lawp[1]))[2] / CONTACT_STEPS


def _sample(records: list[tuple[Segment, _StepDense]]) -> None:
    """Output samples and dense segments from the accepted steps (after the timed loop)."""
    pending: dict[int, list] = {}
    for seg, dense in records:
        grid = _sample_grid(dense.t_old, dense.t, seg.phase.sample_step)
        lst = pending.setdefault(id(seg), [seg, [], []])
        if grid.size:
            lst[1].append(grid)
            lst[2].append(dense(grid).T)
        if seg.phase.keep_dense:
            if not seg.dense_ts:
                seg.dense_ts.append(dense.t_old)
            seg.dense_ts.append(dense.t)
            seg.dense.append(dense)
    for seg, times, states in pending.values():
        if not times:
            continue
        t_all = np.concatenate(seg.times + times)
        y_all = np.concatenate(seg.states + states)
        order = np.argsort(t_all, kind="stable")
        seg.times, seg.states = [t_all[order]], [y_all[order]]


__all__ = ["ModalIntegrator", "Phase", "integrate_modal"]
