"""Case -> finite-element model -> initial state -> generalized-alpha run -> Solution."""

from __future__ import annotations

import math
import platform
from collections.abc import Callable

import numpy as np
from scipy.optimize import brentq

from ..errors import ParameterError
from ..parameters.case import Case
from ..results.records import PAIR_VARIABLES
from ..results.solution import Solution
from .contact_law import law_force, law_potential
from .eventdriven import Record, RunInfo, run
from .integrator import FemIntegrator, State, StepResult
from .model import ContactState, FemBeam

SCHEME = "generalized-alpha (Chung & Hulbert 1993; Arnold & Bruls 2007 form), Newton"
ELEMENT = "2-node co-rotational Euler-Bernoulli (Crisfield 1991), exact-kinetic-energy consistent mass"


def _impact_rate(beam: FemBeam, theta: float, velocity: float) -> float:
    """Rigid rotation rate of the straight beam giving P the normal velocity ``velocity``."""
    z, _ = beam.straight(theta, 0.0)
    return beam.case.initial.impact_rate(beam.rotation_jacobian(z), velocity)


def release_state(beam: FemBeam, angle: float) -> tuple[np.ndarray, np.ndarray]:
    """At rest in the static equilibrium under gravity with the hub held at ``angle``."""
    z = beam.static_equilibrium(angle, steps=1)
    return z, np.zeros_like(z)


def _first_impact_velocity(beam: FemBeam, angle: float) -> float:
    integ = FemIntegrator(beam, beam.case.fem.rho_inf)
    z, zd = release_state(beam, angle)
    out: list[StepResult] = []

    def sample(s: State, res: StepResult, phase: str, lawp) -> None:
        out.append(res)

    _, info, _ = run(beam, integ, z, zd, 10.0, sample, stop_at_impact=True)
    if info.status != "impact":
        raise ParameterError(f"initial.release_angle: released at {angle:.6g} rad the beam does not reach the obstacle")
    last = out[-1]
    pair = int(np.argmin(last.pair_gap))  # the pair whose gap closed (the others are open)
    return float(last.pair_gap_rate[pair])


def solve_release_angle(beam: FemBeam) -> float:
    """Release angle from rest at which P reaches the obstacle at the impact velocity.

    Shooting on the finite-element free flight (:func:`scipy.optimize.brentq`), started
    from the rigid-rod estimate g m1 (sin th_r - sin th_i) = 1/2 J rate^2.
    """
    case = beam.case
    init = case.initial
    th_i = init.impact_angle
    rate = _impact_rate(beam, th_i, init.impact_velocity)
    L, rh, mu, g = case.beam.length, beam.hub_radius, beam.mu, beam.gravity
    m1 = mu * ((rh + L) ** 2 - rh**2) / 2.0
    J = beam.hub_inertia + mu * ((rh + L) ** 3 - rh**3) / 3.0
    if g <= 0.0:
        raise ParameterError("initial.kind: 'release' needs gravity (model.gravity > 0)")
    s = math.sin(th_i) + 0.5 * J * rate**2 / (g * m1)
    if s >= 1.0:
        raise ParameterError(
            f"initial.impact_velocity: {init.impact_velocity:g} m/s cannot be reached by release "
            "from rest under gravity"
        )
    guess = math.asin(s)
    lo, hi = th_i + 0.8 * (guess - th_i), min(th_i + 1.25 * (guess - th_i), 0.5 * math.pi)
    try:
        return float(
            brentq(
                lambda a: _first_impact_velocity(beam, a) - init.impact_velocity,
                lo,
                hi,
                xtol=1e-10,
                rtol=1e-8,
            )
        )
    except ValueError:
        raise ParameterError(
            "initial.release_angle: no release angle near the rigid estimate "
            f"{guess:.6g} rad gives the impact velocity; give initial.release_angle"
        ) from None


def initial_state(beam: FemBeam) -> tuple[np.ndarray, np.ndarray, dict[str, float]]:
    """(z, z', info) for ``case.initial`` (see :func:`flexbeam.simulation.initial_state`)."""
    init = beam.case.initial
    if beam.prescribed:
        th, thd, _ = beam.drive.motion(0.0)
        z, zd = beam.straight(th, thd)
        return z, zd, {}
    if init.kind == "state":
        z, zd = beam.straight(init.angle, init.rate)
        return z, zd, {}
    if init.kind == "impact":
        rate = _impact_rate(beam, init.impact_angle, init.impact_velocity)
        z, zd = beam.straight(init.impact_angle, rate)
        return z, zd, {"impact_rate": rate}
    angle = init.release_angle
    if angle is None:
        angle = solve_release_angle(beam)
    z, zd = release_state(beam, angle)
    return z, zd, {"release_angle": float(angle)}


class _Sampler:
    """Evaluates the output variables at each accepted state."""

    def __init__(self, beam: FemBeam) -> None:
        self.beam = beam
        self.rows: list[tuple] = []
        self.times: list[float] = []
        self.phases: list[str] = []
        self._prev: tuple[float, float, float] | None = None
        self.dissipated = 0.0
        self.work = 0.0
        self.pair_rows: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []

    def __call__(self, s: State, res: StepResult, phase: str, lawp: ContactState | np.ndarray | None) -> None:
        """Record the outputs at ``s``: pair 0's force, gap and rate (as the modal model's columns), the
        contact potential U_c = sum_k K_k d_k^(n_k+1)/(n_k+1) and the dissipated power
        sum_k (F_k - F_k,elastic)(-delta_k') of the pairs in contact, and per pair (several pairs or a pair
        anywhere) the gap, normal velocity, force and contact point's material coordinate x."""
        b = self.beam
        cs = b.contact_state(lawp)
        T, Ve, Vg = b.energies(s.z, s.zd)
        if b.npairs == 1:
            lawp = cs.laws[0]
            F, Fk = (res.force, res.elastic_force) if lawp is not None else (0.0, 0.0)
            Uc = float(law_potential(lawp, -res.gap)) if lawp is not None else 0.0
            p_diss = (F - Fk) * (-res.gap_rate)
            if b.any_anywhere:
                self.pair_rows.append((res.pair_gap.copy(), res.pair_gap_rate.copy(), res.pair_force.copy(),
                                       res.pair_position.copy()))  # fmt: skip
        else:
            F = res.force if cs.laws[0] is not None else 0.0
            Uc = p_diss = 0.0
            for k, p in enumerate(cs.laws):
                if p is not None:
                    Uc += float(law_potential(p, -res.pair_gap[k]))
                    p_diss += float(res.pair_force[k] - res.pair_elastic_force[k]) * float(-res.pair_gap_rate[k])
            self.pair_rows.append(
                (res.pair_gap.copy(), res.pair_gap_rate.copy(), res.pair_force.copy(), res.pair_position.copy())
            )
        p_drive = res.torque * float(s.zd[0])
        if self._prev is not None:
            t0, pd0, pw0 = self._prev
            dt = s.t - t0
            self.dissipated += 0.5 * dt * (pd0 + p_diss)
            self.work += 0.5 * dt * (pw0 + p_drive)
        self._prev = (s.t, p_diss, p_drive)
        mv = b.measuring_velocities(s.z, s.zd)
        self.times.append(s.t)
        self.phases.append(phase)
        self.rows.append((
            float(s.z[0]), float(s.zd[0]), F, res.gap, res.gap_rate, T, Ve, Vg, Uc,
            self.dissipated, self.work, res.torque, b.tip_deflection(s.z), mv,
        ))  # fmt: skip


_SCALARS = (
    "theta", "theta_rate", "contact_force", "gap", "normal_velocity", "kinetic_energy",
    "elastic_energy", "gravitational_energy", "contact_energy", "dissipated_energy",
    "drive_work", "joint_torque", "tip_deflection",
)  # fmt: skip


def _dense_force(rec: Record, pair: int = 0) -> Callable[[float], float] | None:
    """t -> contact force of ``pair`` on its contact steps, from the quintic Hermite interpolant
    of its gap through (delta, delta', delta'') at both ends of each step."""
    dense = [d for d in rec.dense if d[5] == pair]
    if not dense:
        return None
    t0 = np.array([d[0] for d in dense])
    t1 = np.array([d[1] for d in dense])

    def force_at(t: float) -> float:
        i = int(np.searchsorted(t1, t, side="left"))
        if i >= t1.size or t < t0[i]:
            return 0.0
        a, b, g0, g1, lawp, _ = dense[i]
        h = b - a
        if h <= 0.0:
            return float(law_force(lawp, -g0[0], -g0[1])[0])
        s = (t - a) / h
        d, dd = _quintic(s, h, g0, g1)
        return float(law_force(lawp, -d, -dd)[0])

    return force_at


def _quintic(s: float, h: float, g0, g1) -> tuple[float, float]:
    """Quintic Hermite value and derivative at s in [0, 1] from (f, f', f'') at the ends."""
    f0, v0, a0 = g0[0], g0[1] * h, g0[2] * h * h
    f1, v1, a1 = g1[0], g1[1] * h, g1[2] * h * h
    s2, s3, s4, s5 = s * s, s**3, s**4, s**5
    H = (
        1 - 10 * s3 + 15 * s4 - 6 * s5,
        s - 6 * s3 + 8 * s4 - 3 * s5,
        0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5,
        10 * s3 - 15 * s4 + 6 * s5,
        -4 * s3 + 7 * s4 - 3 * s5,
        0.5 * s3 - s4 + 0.5 * s5,
    )
    dH = (
        -30 * s2 + 60 * s3 - 30 * s4,
        1 - 18 * s2 + 32 * s3 - 15 * s4,
        s - 4.5 * s2 + 6 * s3 - 2.5 * s4,
        30 * s2 - 60 * s3 + 30 * s4,
        -12 * s2 + 28 * s3 - 15 * s4,
        1.5 * s2 - 4 * s3 + 2.5 * s4,
    )
    c = (f0, v0, a0, f1, v1, a1)
    val = sum(hk * ck for hk, ck in zip(H, c, strict=True))
    der = sum(hk * ck for hk, ck in zip(dH, c, strict=True)) / h
    return float(val), float(der)


def check_supported(case: Case) -> None:
    """Raise a one-line :class:`~flexbeam.errors.ParameterError` (a ValueError) naming the first field of
    ``case`` that the FE reference does not model, instead of ignoring it.

    The FE reference has contact pairs at fixed material points or anywhere (``[contact]`` and each
    ``[[obstacles]]`` entry's) on rigidly held obstacles: no compliant ``obstacle.support``.
    """
    if case.obstacle.support.compliant:
        raise ParameterError("obstacle.support: the FE reference supports rigidly held obstacles only")


def simulate_fem(case: Case, progress: Callable[[float], None] | None = None) -> Solution:
    """Run ``case`` with the finite-element reference model and return its Solution.

    Parameters
    ----------
    case
        The validated case; ``case.fem`` sets the mesh (``elements``), the step
        (``time_step``, omitted = automatic) and the numerical dissipation (``rho_inf``).
    progress
        Called with the current time now and then (for progress bars).

    Returns
    -------
    Solution
        The same arrays as the modal methods (``q``, ``q_rate`` have no columns);
        a numerical failure gives ``status = "failed"`` with what was computed.

    Raises
    ------
    ParameterError
        For a case field the FE reference does not model (see :func:`check_supported`).
    """
    from ..parameters.io import dump_case
    from ..version import __version__

    check_supported(case)
    beam = FemBeam.from_case(case)
    z0, zd0, info = initial_state(beam)
    integ = FemIntegrator(beam, case.fem.rho_inf)
    sampler = _Sampler(beam)
    rec, run_info, _ = run(beam, integ, z0, zd0, case.solver.t_end, sampler, progress)
    return build_solution(case, beam, sampler, rec, run_info, info, __version__, dump_case(case))


def build_solution(
    case: Case,
    beam: FemBeam,
    sampler: _Sampler,
    rec: Record,
    run_info: RunInfo,
    info: dict[str, float],
    version: str,
    case_toml: str,
) -> Solution:
    """Assemble the :class:`~flexbeam.results.solution.Solution` from the recorded samples."""
    m = len(sampler.times)
    t = np.asarray(sampler.times, float)
    phase = np.asarray(sampler.phases, dtype=object)
    out: dict[str, np.ndarray] = {}
    for k, name in enumerate(_SCALARS):
        out[name] = np.array([r[k] for r in sampler.rows], float).reshape(m)
    npts = len(beam.measuring)
    out["measuring_velocity"] = np.array([r[-1] for r in sampler.rows], float).reshape(m, npts)
    S = beam.npairs
    if S > 1 or beam.any_anywhere:  # per pair (samples x pairs), as the modal model's pair_* variables
        for j, name in enumerate(PAIR_VARIABLES):
            out[name] = np.array([r[j] for r in sampler.pair_rows], float).reshape(m, S)
    out["q"] = np.empty((m, 0))
    out["q_rate"] = np.empty((m, 0))
    out["total_energy"] = (
        out["kinetic_energy"]
        + out["elastic_energy"]
        + out["gravitational_energy"]
        + out["contact_energy"]
        + out["dissipated_energy"]
        - out["drive_work"]
    )
    mech = out["kinetic_energy"] + out["elastic_energy"] + out["gravitational_energy"]
    for ev in rec.contacts:
        end = ev.end if math.isfinite(ev.end) else (t[-1] if m else ev.onset)
        sel = (t >= ev.onset) & (t <= end) & (phase == "contact")
        if np.count_nonzero(sel) > 1:
            force = out["contact_force"] if S == 1 else out["pair_contact_force"][:, ev.pair]
            ev.impulse = float(np.trapezoid(force[sel], t[sel]))
            ev.energy_before, ev.energy_after = float(mech[sel][0]), float(mech[sel][-1])
    law = beam.law
    provenance = {
        "flexbeam_version": version,
        "python": platform.python_version(),
        "case_name": case.name,
        "case_toml": case_toml,
        "method": "fem",
        "elements": beam.elements,
        "nodes": beam.elements + 1,
        "contact_node": beam.pnode,
        "element": ELEMENT,
        "scheme": SCHEME,
        "integrator": SCHEME,
        "rho_inf": case.fem.rho_inf,
        "time_step": case.fem.time_step if case.fem.time_step is not None else "automatic",
        "contact_time_step": run_info.h_contact,
        "free_time_step": run_info.h_free,
        "contact_law": law.name,
        "contact_stiffness": law.stiffness,
        "contact_exponent": law.exponent,
        "contact_pairs": [p.label for p in beam.pairs],
        **info,
    }
    if S > 1:
        provenance["contact_nodes"] = [p.node for p in beam.pairs]
    dense = [_dense_force(rec, k) for k in range(S)]
    sol = Solution(
        time=t,
        phase=phase,
        arrays=out,
        contacts=rec.contacts,
        status=run_info.status,
        message=run_info.message,
        stats={
            "steps": run_info.steps,
            "nfev": run_info.iterations,
            "wall_time": run_info.wall_time,
            "rejected": run_info.rejected,
        },
        provenance=provenance,
        measuring_points=np.asarray(case.output.measuring_points, float),
        force_at=_pair_force(dense) if any(f is not None for f in dense) else None,
    )
    for ev in rec.contacts:  # the peaks of a pair's contact on that pair's force
        peaks = sol.force_peaks(ev.index, threshold=0.0)
        if peaks:
            ev.peak_time, ev.peak_force = max(peaks, key=lambda p: p[1])
    return sol


def _pair_force(dense: list[Callable[[float], float] | None]) -> Callable[[float, int], float]:
    """(t, pair) -> F_k(t), pair k's force on its dense output (0 for a pair that has no contact): the
    ``force_at`` of :class:`~flexbeam.results.solution.Solution`."""

    def force_at(t: float, pair: int = 0) -> float:
        f = dense[pair]
        return 0.0 if f is None else f(t)

    return force_at
