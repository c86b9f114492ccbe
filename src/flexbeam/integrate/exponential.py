"""Production integrator: exact modal propagation + Gauss collocation (see the kernels).

Same contract as :func:`flexbeam.integrate.eventdriven.integrate` (the scipy reference
path): it drives an impact method's phases, locates the impact and separation
events, and returns a :class:`~flexbeam.integrate.eventdriven.RunResult` whose
samples :func:`flexbeam.simulation.collect` turns into a Solution.

The whole step loop of a phase -- collocation steps, step-size control, the event
search and location, and the sampling of the output grid -- is one compiled call,
:func:`~flexbeam.integrate.exponential_kernels.advance`; Python only sets up the
arrays, asks the impact method for the next phase at each event, and wraps the
samples (and, for contact phases, the step records as dense output) into
:class:`~flexbeam.integrate.eventdriven.Segment` objects.

Step control uses the end-state response to the defect of the collocated forcing as
error estimate (order p of the interpolant, while the collocation solution itself is
superconvergent, order 2p at the step end), measured in the energy norm of the modes
(plus the rigid mode's angle).

Hub without inertia (J_h = 0): the Schur complement of M_00 is tiny (~5e-6 kg m^2 at 12
modes), so the linearisation has a spurious top mode (the pinned-versus-clamped root
region) whose frequency moves with q^T M_c q by several per cent (by tens of per cent at 32
modes).  Each step freezes that change at its start and propagates it exactly
(:func:`~flexbeam.integrate.exponential_kernels._step_basis`): as shifted frequencies when it
is weak, and above FULL_FREEZE_MIN as the whole rank-one coupling, diagonalised per step
through the secular equation in O(N^2), so that the forcing keeps only the change of
q^T M_c q over the step (2.4x faster at 32 modes).  The energy norm keeps the mode -- which
carries large theta' oscillations but almost no energy and barely moves the contact point --
from dictating the step.

Bookkeeping: a constant joint torque's work is tau (theta1 - theta0), exact (Gauss
quadrature of tau theta' over steps much longer than the fast modes' periods drifted);
with theta(t) prescribed, the modal-acceleration part of the joint work is integrated by
parts.

Events (:func:`~flexbeam.integrate.exponential_kernels.find_event`):

* *impact* (free flight): the gap over an accepted step is sampled on the exact
  dense output.  Modal content too fast for the sampling is bounded by
  B = sum_k |(Psi^T J)_k| (|free amplitude_k| + 2 max|f_k| / w_k^2); the step is
  declared contact-free only if min(samples) - 2B > 0, otherwise the sampling is
  refined until every mode that can reach the obstacle is resolved (or the step is
  shortened).  Crossings, excursions from zero and Hermite-predicted dips are then
  located by Brent's method on the dense output, and the step is retaken to end at
  the event.
* *separation* (CCFM): the gap's upward crossing, likewise.
* *release* (CCM / resting contact): the collocated multiplier turning tensile.

Compliant obstacle support (CCFM): the support's coordinate sqrt(m_s) s is one more mode
of frequency sqrt(k_s / m_s), propagated exactly; its dashpot -c_s s' / m_s is collocated
like the coupling terms (and booked in E_d), and the gap sees the obstacle moved by s.
The kernel works on [z, s, z', s', E_d, W]; :class:`ModalIntegrator` maps to and from the
reference layout [z, z', s, s', E_d, W].

Constrained phases (CCM, IMM's resting contact): the multiplier lambda is collocated at
the nodes so that g = delta' + kappa delta decays as g(t0) exp(-kappa (t - t0)) over the
step -- the reference path's Baumgarte-stabilised delta'' + 2 alpha delta' + alpha^2 delta
= 0 with kappa = alpha -- and, lambda being an algebraic variable the state's error
estimate does not see, its interpolant's top term is held to MULTIPLIER_RTOL rtol of the
phase's largest lambda (:func:`~flexbeam.integrate.exponential_kernels._multiplier_error`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from ..errors import SolverError
from ..model.system import BeamSystem
from .eventdriven import MAX_STALLED, PhaseMethod, RunResult, Segment, Stop, start_run
from .exponential_kernels import (
    ADVANCE_EVENT,
    ADVANCE_NONFINITE,
    ADVANCE_UNDERFLOW,
    P_NODES,
    advance,
    dense_eval,
    gauss_tables,
)

_PROFILES = {"constant-rate": 0, "kane-spinup": 1}


class ModalIntegrator:
    """Linearisation, modal basis and compiled-kernel arguments for one :class:`BeamSystem`."""

    def __init__(self, system: BeamSystem, rtol: float = 1e-7, atol: float = 1e-12) -> None:
        self.system = system
        self.rtol, self.atol = rtol, atol
        b = system.beam
        n = b.n
        Mc = np.ascontiguousarray(b.Mff - b.D)
        if system.prescribed:
            M0 = np.ascontiguousarray(b.Mff)
            K0 = np.ascontiguousarray(b.Kff)
        else:
            M0 = system.mass_matrix(0.0, system.state(0.0, 0.0))[: n + 1, : n + 1]  # the beam block
            K0 = np.zeros((n + 1, n + 1))
            K0[1:, 1:] = b.Kff
        # (K0, M0) eigenproblem through the Cholesky factor M0 = L L^T (no scipy at start-up)
        Linv = np.linalg.inv(np.linalg.cholesky(M0))
        w2, Y = np.linalg.eigh(Linv @ K0 @ Linv.T)
        Psi = Linv.T @ Y
        w2 = np.where(w2 < 1e-10 * max(float(np.max(w2, initial=0.0)), 1.0), 0.0, w2)
        omega = np.sqrt(w2)
        toM = Psi.T @ M0
        M0inv = np.linalg.inv(M0)
        row0 = M0inv[0] if not system.prescribed else np.zeros(omega.size)
        inv00 = float(M0inv[0, 0]) if not system.prescribed else 0.0
        self.nb = omega.size  # the beam's coordinates (theta and q, or q alone)
        if system.compliant:  # the support's sqrt(m_s) s as one more mode, frequency sqrt(k_s / m_s)
            ms, ks = float(system.contact.support[0]), float(system.contact.support[1])
            nb = self.nb
            omega = np.append(omega, math.sqrt(ks / ms))
            Psi = np.block([[Psi, np.zeros((nb, 1))], [np.zeros((1, nb)), np.full((1, 1), 1.0 / math.sqrt(ms))]])
            toM = np.block([[toM, np.zeros((nb, 1))], [np.zeros((1, nb)), np.full((1, 1), math.sqrt(ms))]])
            row0 = np.append(row0, 0.0)
        self.N = omega.size
        Psi = np.ascontiguousarray(Psi)
        self.lin = (omega, Psi, np.ascontiguousarray(Psi.T), np.ascontiguousarray(toM), np.ascontiguousarray(row0),
                    inv00, 0.0)
        # kernel state layout [z, s, z', s', E_d, W] -> reference layout [z, z', s, s', E_d, W]
        # (the same without a compliant support)
        nb, N = self.nb, self.N
        self.to_reference = None
        if system.compliant:
            self.to_reference = np.concatenate([np.arange(nb), N + np.arange(nb), [nb, 2 * N - 1],
                                                [2 * N, 2 * N + 1]])
        model = (n, b.hub_inertia + b.J0, b.m1, Mc, b.Mff, b.mtf, b.Kff, b.sf, b.G, float(system.g))
        spec = system.drive.spec
        drive = (
            _PROFILES[spec.profile], float(spec.spin_rate), float(spec.spin_up_time),
            float(system.drive.theta0), float(spec.torque if spec.kind == "torque" else 0.0),
        )  # fmt: skip
        P, o = system.contact.point, system.contact
        point = (P.base, P.phi, P.dphi, P.H, P.offset)
        obstacle = (o.kind, o.centre, o.radius, o.normal, np.ascontiguousarray(o.support, dtype=float))
        self.sysd = (model, bool(system.prescribed), drive, point, obstacle)
        c, bw, Vinv, _, _ = gauss_tables(P_NODES)
        self.tab = (c, bw, Vinv)

    def split(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, float]:
        """(z, z', E_d, W) of a reference-layout state (z and z' end with s and s' for a compliant support)."""
        k = y
        if self.to_reference is not None:
            k = np.empty_like(y)
            k[self.to_reference] = y
        N = self.N
        return (np.ascontiguousarray(k[:N]), np.ascontiguousarray(k[N : 2 * N]), float(k[2 * N]),
                float(k[2 * N + 1]))

    def reference_layout(self, Y: np.ndarray) -> np.ndarray:
        """Rows of kernel-layout states in the reference layout."""
        return Y if self.to_reference is None else np.ascontiguousarray(Y[..., self.to_reference])

    def advance(self, t, t_end, y, mode, lawp, h, hcap, sample_step, keep_dense):
        z, zd, Ed, W = self.split(y)
        out = advance(t, t_end, z, zd, Ed, W, mode, lawp, h, hcap, sample_step, keep_dense, self.lin,
                      self.tab, self.sysd, self.atol, self.rtol)
        return (*out[:6], self.reference_layout(out[6]), *out[7:])


class _SegmentDense:
    """Dense output of a whole phase from its step records, in the reference state layout.

    Called like scipy's ``DenseOutput``: y(t) for a scalar t, columns y(t_i) for an array.
    """

    def __init__(self, integ: ModalIntegrator, records: tuple) -> None:
        r_t, r_h = records[0], records[1]
        self.t_min, self.t_max = float(r_t[0]), float(r_t[-1] + r_h[-1])
        self.t_old, self.t = self.t_min, self.t_max
        self.args = (*records, integ.lin[1], integ.tab[2], integ.sysd)
        self.integ = integ

    def __call__(self, t):
        tt = np.atleast_1d(np.asarray(t, float))
        Y = self.integ.reference_layout(dense_eval(tt, *self.args))
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
    wall0 = time.perf_counter()
    integ = ModalIntegrator(system, rtol, atol)
    # a zero-length call loads the compiled kernels (from numba's cache: ~0.25 s in a fresh
    # process) outside the reported wall time, which is the integration alone
    t_load = time.perf_counter()
    integ.advance(0.0, 0.0, np.asarray(y0, float), 0, np.zeros(4), 1e-6, math.inf, 1e-5, False)
    wall0 += time.perf_counter() - t_load
    t = 0.0
    segments: list[Segment] = []
    steps = nfev = 0
    status, message = "success", "integration reached t_end"
    started = start_run(method, y0, segments)
    if isinstance(started, RunResult):
        started.integrator = INTEGRATOR
        return started
    phase, y = started
    h = min(1e-4, t_end)
    cap = max_step or math.inf
    stalled = 0
    while t < t_end:
        mode = int(phase.data.get("mode", 0))
        lawp = np.asarray(phase.data.get("p", np.zeros(4)), float)
        phase_cap = cap
        if mode == 1:
            phase_cap = min(cap, _contact_step_cap(system, t, y, lawp))
        (code, t1, h, n_steps, n_fev, ts, ys, *records) = integ.advance(
            t, t_end, y, mode, lawp, h, phase_cap, phase.sample_step, phase.keep_dense)
        steps += n_steps
        nfev += n_fev
        seg = Segment(phase, t, t1, [np.array([t]), ts], [y[None, :].copy(), ys])
        segments.append(seg)
        if phase.keep_dense and records[0].size:
            seg.dense_ts = [float(records[0][0]), float(records[0][-1] + records[1][-1])]
            seg.dense = [_SegmentDense(integ, tuple(records))]
        if ys.shape[0]:
            y = ys[-1].copy()
        t = t1
        if progress is not None:
            progress(t)
        if code == ADVANCE_UNDERFLOW:
            status, message = "failed", f"step size underflow at t = {t:.9g} s"
            break
        if code == ADVANCE_NONFINITE:
            status, message = "failed", f"non-finite state at t = {t:.9g} s"
            break
        if code != ADVANCE_EVENT:
            break
        try:
            phase, y = method.transition(phase, phase.events[0], t, y)
        except Stop as stop:
            status, message = stop.status, stop.message
            break
        except SolverError as err:
            status, message = "failed", str(err)
            break
        stalled = stalled + 1 if seg.t1 == seg.t0 else 0
        if stalled > MAX_STALLED:
            status, message = "failed", f"events keep recurring without progress at t = {t:.9g} s"
            break
        h = min(h, 1e-5)
    wall = time.perf_counter() - wall0
    return RunResult(segments, status, message, t, wall, steps, nfev, INTEGRATOR)


INTEGRATOR = f"exponential modal Gauss collocation (p = {P_NODES}), compiled, event-driven"


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


__all__ = ["ModalIntegrator", "integrate_modal"]
