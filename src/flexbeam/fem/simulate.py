"""Case -> finite-element model -> initial state -> generalized-alpha run -> Solution."""

from __future__ import annotations

import math
import platform
import warnings
from collections.abc import Callable

import numpy as np

from ..errors import FlexbeamWarning, ParameterError
from ..parameters.case import Case
from ..results.records import FRICTION_VARIABLES, PAIR_VARIABLES
from ..results.solution import Solution
from .beam import FemBeam
from .contact_law import law_potential
from .dense_force import dense_force, pair_force
from .eventdriven import run
from .initial import initial_state
from .integrator import FemIntegrator, State, StepResult
from .pairs import ContactState
from .rigid_motion import FemMotion
from .run_record import Record, RunInfo

SCHEME = "generalized-alpha (Chung & Hulbert 1993; Arnold & Bruls 2007 form), Newton"
ELEMENT = "2-node co-rotational Euler-Bernoulli (Crisfield 1991), exact-kinetic-energy consistent mass"


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
        # frictional runs: (F_t, v_t, state) per pair, the state 0 (no frictional contact), 1 slip, 2 stick (within
        # the regularised law's band |v_t| <= v_s), as CCFM's pair_friction_state
        self.friction_rows: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        # a free beam: (x_G, y_G, v_Gx, v_Gy, a_Gx, a_Gy, H_G, H_G') per sample, and the pairs' (n_x, n_y, lever)
        # where the contact state changes (flexbeam.fem.rigid_motion)
        self.rigid_rows: list[tuple[float, ...]] = []
        self.strikes: list[tuple[float, np.ndarray]] = []
        self._active: tuple[int, ...] | None = None
        self._angle = 0.0

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
        if res.pair_friction is not None:  # Coulomb friction dissipates -F_t v_t >= 0 per pair
            mu_s, vs = b.free_state.friction[:, 1], b.free_state.friction[:, 2]
            touching = (mu_s > 0.0) & (res.pair_force > 0.0)
            state = np.where(touching, np.where(np.abs(res.pair_slip) <= vs, 2.0, 1.0), 0.0)
            self.friction_rows.append((res.pair_friction, res.pair_slip, state))
            p_diss += float(np.sum(-res.pair_friction * res.pair_slip))
        p_diss += b.damping_power(s.z, s.zd)  # the beam's structural damping (flexbeam.fem.damping)
        p_drive = 0.0 if b.free else res.torque * float(s.zd[0]) + b.base_power(s.t, s.z, s.zd)
        if self._prev is not None:
            t0, pd0, pw0 = self._prev
            dt = s.t - t0
            self.dissipated += 0.5 * dt * (pd0 + p_diss)
            self.work += 0.5 * dt * (pw0 + p_drive)
        self._prev = (s.t, p_diss, p_drive)
        if b.free:
            theta, rate, tip, mv = self._free(s, cs)
        else:
            theta, rate, tip = float(s.z[0]), float(s.zd[0]), b.tip_deflection(s.z)
            mv = b.measuring_velocities(s.z, s.zd)
        self.times.append(s.t)
        self.phases.append(phase)
        self.rows.append((theta, rate, F, res.gap, res.gap_rate, T, Ve, Vg, Uc, self.dissipated, self.work,
                          res.torque, tip, mv))  # fmt: skip

    def _free(self, s: State, cs: ContactState) -> tuple[float, float, float, np.ndarray]:
        """A free beam's sample: its rigid-body motion recorded, the pairs' normals and lever arms where the contact
        state changes; (theta, theta', tip deflection, measuring velocities) in its mean-axis frame, theta
        unwrapped."""
        b = self.beam
        rg = b.rigid(s.z, s.zd, s.zdd)
        self.rigid_rows.append((*rg.position, *rg.velocity, *rg.acceleration, rg.momentum, rg.torque))
        active = tuple(int(a) for a in cs.active)
        if active != self._active:
            self.strikes.append((s.t, np.array([b.rigid_jacobian(s.z, k) for k in range(b.npairs)])))
            self._active = active
        theta = rg.angle + 2.0 * math.pi * round((self._angle - rg.angle) / (2.0 * math.pi))
        self._angle = theta
        mv = b.measuring_velocities(s.z, s.zd, rg.angle)
        return theta, rg.angle_rate, b.tip_deflection(s.z, rg), mv


_SCALARS = (
    "theta", "theta_rate", "contact_force", "gap", "normal_velocity", "kinetic_energy",
    "elastic_energy", "gravitational_energy", "contact_energy", "dissipated_energy",
    "drive_work", "joint_torque", "tip_deflection",
)  # fmt: skip


def check_supported(case: Case) -> None:
    """Raise a one-line :class:`~flexbeam.errors.ParameterError` (a ValueError) naming the first field of
    ``case`` that the FE reference does not model, instead of ignoring it.

    The FE reference has contact pairs at fixed material points or anywhere (``[contact]`` and each
    ``[[obstacles]]`` entry's) on rigidly held obstacles: no compliant ``obstacle.support``; a free beam starts
    straight (it has no modes for ``initial.modal_displacement`` or ``initial.modal_velocity``).
    """
    if case.obstacle.support.compliant:
        raise ParameterError("obstacle.support: the FE reference supports rigidly held obstacles only")
    if case.joint.kind == "free":
        for name in ("modal_displacement", "modal_velocity"):
            if any(v != 0.0 for v in getattr(case.initial, name)):
                raise ParameterError(
                    f"initial.{name}: the FE reference has no modes; its free beam starts straight (leave it empty)"
                )


def simulate_fem(
    case: Case, progress: Callable[[float], None] | None = None, stop: Callable[[], str] | None = None
) -> Solution:
    """Run ``case`` with the finite-element reference model and return its Solution.

    Parameters
    ----------
    case
        The validated case; ``case.fem`` sets the mesh (``elements``), the step
        (``time_step``, omitted = automatic) and the numerical dissipation (``rho_inf``).
    progress
        Called with the current time now and then (for progress bars).
    stop
        Asked after each step for a cause that ends the run there, keeping what was computed (status
        "interrupted"; :func:`flexbeam.fem.eventdriven.run`).

    Returns
    -------
    Solution
        The same arrays as the modal methods (``q``, ``q_rate`` have no columns);
        a numerical failure gives ``status = "failed"`` with what was computed.

    Raises
    ------
    ParameterError
        For a case field the FE reference does not model (see :func:`check_supported`).
    ModelError
        For a joint kind the FE reference does not model (:func:`flexbeam.fem.beam.joint_drive`).
    """
    from ..parameters.io import dump_case
    from ..version import __version__

    check_supported(case)
    beam = FemBeam.from_case(case)
    z0, zd0, info = initial_state(beam)
    integ = FemIntegrator(beam, case.fem.rho_inf)
    sampler = _Sampler(beam)
    rec, run_info, _ = run(beam, integ, z0, zd0, case.solver.t_end, sampler, progress, stop=stop)
    sol = build_solution(case, beam, sampler, rec, run_info, info, __version__, dump_case(case))
    warn_coarse_step(case, sol)
    return sol


#: a contact that a fixed ``fem.time_step`` resolves in fewer steps than this is warned of: the seed's first contact
#: (0.60 ms) in 20 steps reads its peak 1.4 % above the converged one, in 6 steps 10 % (1084 against 986 N), each a
#: "success" (measured 2026-11-28; the automatic step gives ~200)
MIN_CONTACT_STEPS = 20


def warn_coarse_step(case: Case, sol: Solution) -> None:
    """A :class:`~flexbeam.errors.FlexbeamWarning` naming ``fem.time_step`` when the step the case fixes resolves a
    contact of the run (its first such one named) in fewer than :data:`MIN_CONTACT_STEPS` steps."""
    h = case.fem.time_step
    if h is None:
        return
    for ev in sol.contacts:
        if math.isfinite(ev.duration) and 0.0 < ev.duration < MIN_CONTACT_STEPS * h:
            warnings.warn(
                f"fem.time_step: {h:g} s resolves the contact at t = {ev.onset:.6g} s, {ev.duration:.3g} s long, in "
                f"{ev.duration / h:.1f} steps (fewer than {MIN_CONTACT_STEPS}: its force is not converged); a smaller "
                "step, or omit fem.time_step for the automatic one (~200 steps a contact)",
                FlexbeamWarning,
                stacklevel=2,
            )
            return


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
    """Assemble the :class:`~flexbeam.results.solution.Solution` from the recorded samples.

    Parameters
    ----------
    case, beam
        The case and its FE model.
    sampler
        The samples of the run (:class:`_Sampler`).
    rec, run_info
        The run's contact log and dense data, its status and statistics (:func:`flexbeam.fem.eventdriven.run`).
    info
        Values derived for the initial state (the impact rate, the release angle), added to the provenance.
    version, case_toml
        The package version and the case as TOML, for the provenance.

    Returns
    -------
    Solution
        The samples as the modal methods' arrays, the contacts with their impulse, energies and force peak.
    """
    t = np.asarray(sampler.times, float)
    phase = np.asarray(sampler.phases, dtype=object)
    out = sample_arrays(beam, sampler)
    contact_balances(rec, beam, t, phase, out)
    dense = [dense_force(rec, k) for k in range(beam.npairs)]
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
        provenance=provenance(case, beam, run_info, info, version, case_toml),
        measuring_points=np.asarray(case.output.measuring_points, float),
        force_at=pair_force(dense) if any(f is not None for f in dense) else None,
        motion=FemMotion.of_run(beam, t, sampler, rec, out) if beam.free else None,
    )
    for ev in rec.contacts:  # the peaks of a pair's contact on that pair's force
        peaks = sol.force_peaks(ev.index, threshold=0.0)
        if peaks:
            ev.peak_time, ev.peak_force = max(peaks, key=lambda p: p[1])
    return sol


def sample_arrays(beam: FemBeam, sampler: _Sampler) -> dict[str, np.ndarray]:
    """The output arrays of the samples, named as the modal model's: the scalars, the measuring points'
    velocities, per pair (several pairs or a pair anywhere) its ``pair_*`` columns, empty ``q`` and ``q_rate``
    and the total energy balance."""
    m = len(sampler.times)
    out: dict[str, np.ndarray] = {}
    for k, name in enumerate(_SCALARS):
        out[name] = np.array([r[k] for r in sampler.rows], float).reshape(m)
    npts = len(beam.measuring)
    out["measuring_velocity"] = np.array([r[-1] for r in sampler.rows], float).reshape(m, npts)
    S = beam.npairs
    if S > 1 or beam.any_anywhere:  # per pair (samples x pairs), as the modal model's pair_* variables
        for j, name in enumerate(PAIR_VARIABLES):
            out[name] = np.array([r[j] for r in sampler.pair_rows], float).reshape(m, S)
    if sampler.friction_rows:  # a frictional run: the friction force along each pair's tangent, the slip, the state
        for j, name in enumerate(FRICTION_VARIABLES):
            out[name] = np.array([r[j] for r in sampler.friction_rows], float).reshape(m, S)
    out["q"] = np.empty((m, 0))
    out["q_rate"] = np.empty((m, 0))
    if beam.free:  # G's position and velocity, as the modal model's centre_of_mass variables
        rigid = np.asarray(sampler.rigid_rows, float).reshape(m, 8)
        out["centre_of_mass"], out["centre_of_mass_velocity"] = rigid[:, 0:2].copy(), rigid[:, 2:4].copy()
    out["total_energy"] = (
        out["kinetic_energy"]
        + out["elastic_energy"]
        + out["gravitational_energy"]
        + out["contact_energy"]
        + out["dissipated_energy"]
        - out["drive_work"]
    )
    return out


def contact_balances(rec: Record, beam: FemBeam, t: np.ndarray, phase: np.ndarray, out: dict[str, np.ndarray]) -> None:
    """Each recorded contact's impulse (the trapezoidal integral of its pair's force over its contact samples; with
    friction also the tangential impulse) and the mechanical energy at its first and last contact sample, set on the
    contact events of ``rec``."""
    m = t.size
    mech = out["kinetic_energy"] + out["elastic_energy"] + out["gravitational_energy"]
    for ev in rec.contacts:
        end = ev.end if math.isfinite(ev.end) else (t[-1] if m else ev.onset)
        sel = (t >= ev.onset) & (t <= end) & (phase == "contact")
        if np.count_nonzero(sel) > 1:
            force = out["contact_force"] if beam.npairs == 1 else out["pair_contact_force"][:, ev.pair]
            ev.impulse = float(np.trapezoid(force[sel], t[sel]))
            if FRICTION_VARIABLES[0] in out:  # along the pair's tangent t = (-n_y, n_x), as IMM's
                ev.tangential_impulse = float(np.trapezoid(out[FRICTION_VARIABLES[0]][sel, ev.pair], t[sel]))
            ev.energy_before, ev.energy_after = float(mech[sel][0]), float(mech[sel][-1])


def provenance(
    case: Case, beam: FemBeam, run_info: RunInfo, info: dict[str, float], version: str, case_toml: str
) -> dict[str, object]:
    """What produced an FE Solution: versions, the case, the mesh, element and scheme, the step sizes, the
    contact law and pairs, and the values ``info`` derived for the initial state."""
    law = beam.law
    out = {
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
        **case.base.drive,
        **info,
    }
    if beam.npairs > 1:
        out["contact_nodes"] = [p.node for p in beam.pairs]
    return out
