"""Wiring: case -> system -> initial state -> impact method -> integrator -> Solution."""

from __future__ import annotations

import math
import platform
from collections.abc import Callable

import numpy as np

from . import __version__
from .errors import ParameterError, closest
from .integrate.eventdriven import RunResult, Stop, integrate
from .methods.base import ImpactMethod
from .methods.ccfm import CCFM
from .model.outputs import COLUMNS, SUPPORT_COLUMNS, evaluate
from .model.system import _NO_LAW, CONTACT_NONE, BeamSystem
from .parameters.case import Case
from .parameters.io import dump_case
from .solution import Solution


def _methods() -> dict[str, type[ImpactMethod]]:
    from .methods.ccm import CCM
    from .methods.imm import IMM

    return {"ccfm": CCFM, "ccm": CCM, "imm": IMM}


METHOD_NAMES = ("ccfm", "ccm", "imm", "fem")


def initial_state(system: BeamSystem, case: Case) -> tuple[np.ndarray, dict[str, float]]:
    """Initial state vector for ``case.initial`` and a dict of derived values.

    * ``impact``: theta = impact angle, beam straight and at rest in the floating frame,
      theta' chosen so that P's normal velocity delta' = J_theta theta' equals the
      impact velocity.
    * ``state``: theta, theta' as given.
    * ``release``: at rest, in the static equilibrium of the cantilever under gravity
      at the release angle, (K_ff - g sin(theta) G) q = -g cos(theta) s_f^T; the release
      angle, when not given, is solved for (shooting with :func:`scipy.optimize.brentq`
      on the free flight) so that P reaches the obstacle at the impact velocity.
    """
    init = case.initial
    if system.prescribed:
        th, thd, _ = system.drive.motion(0.0)
        return system.state(th, thd), {}
    if init.kind == "state":
        return system.state(init.angle, init.rate), {}
    if init.kind == "impact":
        y = system.state(init.impact_angle, 0.0)
        J_theta = system.gap(0.0, y)[3][0]
        if J_theta == 0.0:
            raise ParameterError("initial.impact_velocity: P cannot move along the contact normal")
        y = system.state(init.impact_angle, init.impact_velocity / J_theta)
        return y, {"impact_rate": float(y[system.n + 1])}
    angle = init.release_angle
    info: dict[str, float] = {}
    if angle is None:
        angle = solve_release_angle(system, case)
    info["release_angle"] = float(angle)
    return release_state(system, angle), info


def release_state(system: BeamSystem, angle: float) -> np.ndarray:
    """At rest in static equilibrium under gravity at hub angle ``angle``."""
    b, g = system.beam, system.g
    q = np.zeros(b.n)
    if b.n:
        q = np.linalg.solve(b.Kff - g * math.sin(angle) * b.G, -g * math.cos(angle) * b.sf)
    return system.state(angle, 0.0, q)


class _UntilImpact(CCFM):
    """Free flight that stops at the first impact, reporting P's normal velocity."""

    def transition(self, phase, event, t, y):
        raise Stop("impact", repr(self.gap_event(t, y)[1]))


def _first_impact_velocity(system: BeamSystem, case: Case, angle: float) -> float:
    run = integrate(_UntilImpact(system, case), release_state(system, angle), 10.0,
                    rtol=1e-10, atol=1e-13)
    if run.status != "impact":
        raise ParameterError(
            f"initial.release_angle: released at {angle:.6g} rad the beam does not reach the obstacle"
        )
    return float(run.message)


def solve_release_angle(system: BeamSystem, case: Case) -> float:
    """Release angle from rest that gives P the impact velocity at first contact."""
    init = case.initial
    th_i = init.impact_angle
    y = system.state(th_i, 0.0)
    J_theta = system.gap(0.0, y)[3][0]
    rate = init.impact_velocity / J_theta
    b = system.beam
    if system.g <= 0.0 or b.m1 <= 0.0:
        raise ParameterError("initial.kind: 'release' needs gravity (model.gravity > 0)")
    # rigid estimate: g m1 (sin th_r - sin th_i) = 1/2 (J_h + J0) rate^2 (falling towards -theta)
    s = math.sin(th_i) + 0.5 * (b.hub_inertia + b.J0) * rate**2 / (system.g * b.m1)
    if s >= 1.0:
        raise ParameterError(
            f"initial.impact_velocity: {init.impact_velocity:g} m/s cannot be reached by release "
            "from rest under gravity"
        )
    guess = math.asin(s)
    target = init.impact_velocity

    def miss(angle: float) -> float:
        return _first_impact_velocity(system, case, angle) - target

    from scipy.optimize import brentq

    lo, hi = th_i + 0.8 * (guess - th_i), min(th_i + 1.25 * (guess - th_i), 0.5 * math.pi)
    try:
        return float(brentq(miss, lo, hi, xtol=1e-12, rtol=1e-10))
    except ValueError:
        raise ParameterError(
            "initial.release_angle: no release angle near the rigid estimate "
            f"{guess:.6g} rad gives the impact velocity; give initial.release_angle"
        ) from None


def simulate(
    case: Case,
    method: str = "ccfm",
    progress: Callable[[float], None] | None = None,
) -> Solution:
    """Run ``case`` with an impact method and return the :class:`Solution`."""
    if method == "fem":
        if case.obstacle.support.compliant:
            raise ParameterError("obstacle.support: the finite-element reference (method 'fem') takes a rigidly "
                                 "fixed obstacle only; omit obstacle.support.stiffness")
        try:
            from .fem import simulate_fem
        except ImportError:
            raise ParameterError("method: 'fem' (the finite-element reference) is not available yet") from None
        return simulate_fem(case, progress=progress)
    methods = _methods()
    if method not in methods:
        raise ParameterError(
            f"method: unknown impact method '{method}'; allowed: {', '.join(METHOD_NAMES)}"
            f"{closest(method, METHOD_NAMES)}"
        )
    system = BeamSystem.from_case(case)
    y0, info = initial_state(system, case)
    impact = methods[method](system, case)
    system.rhs(0.0, y0)  # compile (or load from cache) before the timed integration
    s = case.solver
    if uses_exponential(case, method, system):
        from .integrate.exponential import integrate_modal

        run = integrate_modal(impact, system, y0, s.t_end, s.fast_rtol, s.fast_atol, s.max_step, progress)
    else:
        run = integrate(impact, y0, s.t_end, s.rtol, s.atol, s.max_step, progress)
    return collect(run, impact, system, case, info)


def uses_exponential(case: Case, method: str, system: BeamSystem) -> bool:
    """Does ``solver.integrator = "exponential"`` apply to this run?

    Every impact method on a rigid obstacle, and CCFM on a compliant support (its s as
    one more exactly propagated mode).  Constrained phases against a compliant support
    (CCM, IMM's resting contact) take the reference path: the multiplier collocated at the
    nodes lets the constraint do work ~5e-6 of the energy over a contact against the stiff
    support, above the 1e-6 the energy tests demand; so does a compliant support with
    theta(t) prescribed (the joint torque's bookkeeping does not see the moving obstacle).
    The Solution's provenance names the integrator that ran.
    """
    if case.solver.integrator != "exponential":
        return False
    return not system.compliant or (method == "ccfm" and not system.prescribed)


def collect(run: RunResult, method: ImpactMethod, system: BeamSystem, case: Case,
            info: dict[str, float]) -> Solution:
    """Evaluate the output variables at every sample and build the Solution."""
    n, npts = system.n, len(system.measuring)
    times, phases, rows = [], [], []
    for seg in run.segments:
        t_seg = np.concatenate(seg.times)
        y_seg = np.concatenate(seg.states)
        times.append(t_seg)
        phases.append(np.full(t_seg.size, seg.phase.name, dtype=object))
        rows.append((seg.phase, t_seg, y_seg))
    t_all = np.concatenate(times) if times else np.empty(0)
    columns: dict[str, list[np.ndarray]] = {}
    qs, qds, mvs = [], [], []
    for phase, t_seg, y_seg in rows:
        cols, mv = evaluate(system, t_seg, y_seg, phase.data.get("mode", CONTACT_NONE),
                            phase.data.get("p", _NO_LAW))
        for name, arr in cols.items():
            columns.setdefault(name, []).append(arr)
        mvs.append(mv)
        if system.prescribed:
            qs.append(y_seg[:, :n])
            qds.append(y_seg[:, n : 2 * n])
        else:
            qs.append(y_seg[:, 1 : n + 1])
            qds.append(y_seg[:, n + 2 : 2 * n + 2])
    names = [c for c in COLUMNS if system.compliant or c not in SUPPORT_COLUMNS]
    out = {name: np.concatenate(columns[name]) if name in columns else np.empty(0) for name in names}
    out["q"] = np.concatenate(qs) if qs else np.empty((0, n))
    out["q_rate"] = np.concatenate(qds) if qds else np.empty((0, n))
    out["measuring_velocity"] = np.concatenate(mvs) if mvs else np.empty((0, npts))
    out["total_energy"] = (out["kinetic_energy"] + out["elastic_energy"] + out["gravitational_energy"]
                           + out["contact_energy"] + out["dissipated_energy"] - out["drive_work"])
    _fill_contact_log(method, t_all, out, np.concatenate(phases) if phases else np.empty(0))
    force_at = _dense_force(run, method, system)
    provenance = {
        "flexbeam_version": __version__,
        "python": platform.python_version(),
        "case_name": case.name,
        "case_toml": dump_case(case),
        "method": method.name,
        "integrator": run.integrator,
        "rtol": case.solver.rtol if run.integrator.startswith("scipy") else case.solver.fast_rtol,
        "atol": case.solver.atol if run.integrator.startswith("scipy") else case.solver.fast_atol,
        "contact_law": system.law.name,
        "contact_stiffness": system.law.stiffness,
        "contact_exponent": system.law.exponent,
        **info,
    }
    sol = Solution(
        time=t_all,
        phase=np.concatenate(phases) if phases else np.empty(0, dtype=object),
        arrays=out,
        contacts=method.contacts,
        status=run.status,
        message=run.message,
        stats={"steps": run.steps, "nfev": run.nfev, "wall_time": run.wall_time},
        provenance=provenance,
        measuring_points=np.asarray(case.output.measuring_points, float),
        _force_at=force_at,
    )
    for ev in method.contacts:
        peaks = sol.force_peaks(ev.index, threshold=0.0)
        if peaks:
            ev.peak_time, ev.peak_force = max(peaks, key=lambda p: p[1])
    return sol


def _fill_contact_log(method: ImpactMethod, t: np.ndarray, out: dict[str, np.ndarray],
                      phase: np.ndarray) -> None:
    """Impulse (trapezoid on the samples) and energies before/after for force-based methods."""
    E = out["total_energy"] - out["dissipated_energy"]
    for ev in method.contacts:
        if not math.isnan(ev.impulse):
            continue
        end = ev.end if math.isfinite(ev.end) else (t[-1] if t.size else ev.onset)
        sel = (t >= ev.onset) & (t <= end) & (phase != "free")
        if np.count_nonzero(sel) > 1:
            ev.impulse = float(np.trapezoid(out["contact_force"][sel], t[sel]))
            mech = E[sel] - out["contact_energy"][sel]
            ev.energy_before, ev.energy_after = float(mech[0]), float(mech[-1])


def _dense_force(run: RunResult, method: ImpactMethod, system: BeamSystem):
    """t -> contact force on the dense output of the contact phases (for peak refinement)."""
    parts = [(seg.t0, seg.t1, seg.phase, seg.interpolant()) for seg in run.segments
             if seg.phase.keep_dense and seg.dense]
    if not parts:
        return None

    def force_at(t: float) -> float:
        for t0, t1, phase, sol in parts:
            if t0 <= t <= t1:
                return method.force(phase, t, sol(t))[0]
        return 0.0

    return force_at
