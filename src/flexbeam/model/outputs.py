"""Output variables at many samples in one compiled loop.

Evaluates, for every sample of one phase, the quantities a :class:`~flexbeam.solution.Solution`
stores (gap, contact force, energies, joint torque, velocities of measuring points),
with the same kernels the equations of motion use, so that outputs and dynamics
cannot disagree.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..contact.laws import law_force, law_potential
from .kernels import energies, point_kinematics, transverse_velocity
from .system import BeamSystem, _state_split, contact_gap, rhs_kernel, support_slot

#: column order of :func:`sample_outputs`
COLUMNS = (
    "theta", "theta_rate", "gap", "normal_velocity", "contact_force", "contact_energy",
    "kinetic_energy", "elastic_energy", "gravitational_energy", "dissipated_energy", "drive_work",
    "joint_torque", "tip_deflection", "support_displacement", "sensor_force",
)  # fmt: skip

#: columns that exist only for a compliant obstacle support
SUPPORT_COLUMNS = ("support_displacement", "sensor_force")


@njit(cache=True)
def sample_outputs(
    Y, n, prescribed, TH, THD, THDD, TAU, g,
    Jc, m1, Mc, Mff, mtf, Kff, sf, G,
    pbase, pphi, pdphi, pH, pc, okind, ocentre, oradius, onormal, osup,
    mode, p, tip_phi, mbase, mphi, mH,
):  # fmt: skip
    """Rows of :data:`COLUMNS` and measuring-point normal velocities for states ``Y``."""
    m = Y.shape[0]
    N = n + 1
    out = np.empty((m, len(COLUMNS)))
    mv = np.empty((m, mbase.size))
    dr = np.empty((2, N))
    J = np.empty(N)
    for k in range(m):
        y = Y[k]
        theta, omega, q, qd = _state_split(y, n, prescribed, TH[k], THD[k])
        q = np.ascontiguousarray(q)
        qd = np.ascontiguousarray(qd)
        r, v, a0 = point_kinematics(theta, omega, q, qd, pbase, pphi, pdphi, pH, pc, dr)
        s_ob, sd_ob = 0.0, 0.0
        if osup[0] > 0.0:
            k_ob = support_slot(n, prescribed)
            s_ob, sd_ob = y[k_ob], y[k_ob + 1]
        delta, vn, gamma, nx, ny, Js = contact_gap(
            r, v, a0, dr, okind, ocentre, oradius, onormal, osup, s_ob, sd_ob, J
        )
        if prescribed or mode == 2:  # the force (CCM) or the joint torque needs the equations solved
            dy, F, torque = rhs_kernel(
                y, n, prescribed, TH[k], THD[k], THDD[k], TAU[k], g, Jc, m1, Mc, Mff, mtf, Kff, sf, G,
                pbase, pphi, pdphi, pH, pc, okind, ocentre, oradius, onormal, osup, mode, p,
            )  # fmt: skip
        else:  # free joint: the torque is the applied one; the CCFM force is the law's (as in rhs_kernel)
            F = law_force(p, -delta, -vn)[0] if mode == 1 else 0.0
            torque = TAU[k]
        T, Ve, Vg = energies(theta, omega, q, qd, Jc, Mc, Mff, mtf, Kff, m1, sf, G, g)
        T += 0.5 * osup[0] * sd_ob * sd_ob
        Ve += 0.5 * osup[1] * s_ob * s_ob
        out[k, 0] = theta
        out[k, 1] = omega
        out[k, 2] = delta
        out[k, 3] = vn
        out[k, 4] = F
        out[k, 5] = law_potential(p, -delta) if mode == 1 else 0.0
        out[k, 6] = T
        out[k, 7] = Ve
        out[k, 8] = Vg
        out[k, 9] = y[y.size - 2]
        out[k, 10] = y[y.size - 1]
        out[k, 11] = torque
        out[k, 12] = tip_phi @ q if n > 0 else 0.0
        out[k, 13] = s_ob
        out[k, 14] = -(osup[1] * s_ob + osup[2] * sd_ob)
        for j in range(mbase.size):
            mv[k, j] = transverse_velocity(omega, q, qd, mbase[j], mphi[j], mH[j])
    return out, mv


def evaluate(system: BeamSystem, times: np.ndarray, states: np.ndarray, mode: int,
             p: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Output columns (dict) and measuring-point velocities for samples of one phase."""
    b, P, o = system.beam, system.contact.point, system.contact
    m = times.size
    TH, THD, THDD = np.zeros(m), np.zeros(m), np.zeros(m)
    if system.prescribed:
        for k, t in enumerate(times):
            TH[k], THD[k], THDD[k] = system.drive.motion(float(t))
    TAU = np.array([system.drive.torque(float(t)) for t in times]) if system.drive.spec.kind == "torque" \
        else np.zeros(m)
    tip = system.tip
    pts = system.measuring
    n = b.n
    mbase = np.array([pt.base for pt in pts], float)
    mphi = np.array([pt.phi for pt in pts], float).reshape(len(pts), n)
    mH = np.array([pt.H for pt in pts], float).reshape(len(pts), n, n)
    out, mv = sample_outputs(
        np.ascontiguousarray(states), n, system.prescribed, TH, THD, THDD, TAU, system.g,
        b.hub_inertia + b.J0, b.m1, np.ascontiguousarray(b.Mff - b.D), b.Mff, b.mtf, b.Kff, b.sf, b.G,
        P.base, P.phi, P.dphi, P.H, P.offset, o.kind, o.centre, o.radius, o.normal, o.support,
        mode, p, tip.phi if tip is not None else np.zeros(0), mbase, mphi, mH,
    )  # fmt: skip
    return {name: out[:, i] for i, name in enumerate(COLUMNS)}, mv
