"""Impulse-momentum map of an instantaneous impact (IMM; Khulief & Shabana 1987).

With generalised mass M, contact Jacobian J (delta' = J z') and restitution e,

    W = J M^-1 J^T,   P = -(1 + e) (J z'^-) / W,   z'^+ = z'^- + M^-1 J^T P,

so that J z'^+ = -e J z'^- and the coordinates do not change.  The contact impulse
does the work W_c = P (v^- + v^+)/2 = -(1 - e^2) (v^-)^2 / (2 W) <= 0.  When theta(t)
is prescribed only the modal velocities jump (M and J restricted to the modal
block) and the joint's impulsive torque does the rest of the kinetic-energy change.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.system import BeamSystem


@dataclass(frozen=True)
class Jump:
    """Result of an impulse-momentum step."""

    y: np.ndarray  # state after the jump (bookkeeping integrals updated)
    impulse: float  # P [N s]
    velocity_before: float  # J z'^- [m/s]
    velocity_after: float  # J z'^+ [m/s]
    kinetic_before: float  # [J]
    kinetic_after: float  # [J]


def impulse_jump(system: BeamSystem, t: float, y: np.ndarray, restitution: float) -> Jump:
    """Apply the impulse-momentum map with coefficient of restitution ``restitution``.

    The energy the impulse removes is added to the dissipated-energy integral and the
    impulsive joint work (prescribed theta only) to the drive-work integral, so that
    the total energy stays continuous across the jump.
    """
    M = system.mass_matrix(t, y)
    J = system.gap(t, y)[3]
    zd = system.velocities(t, y)
    v_minus = float(J @ zd)
    free = slice(1, None) if system.prescribed else slice(None)
    Mr, Jr = M[free, free], J[free]
    T_minus = system.energies(t, y)["kinetic"]
    if Jr.size == 0:
        return Jump(y.copy(), 0.0, v_minus, v_minus, T_minus, T_minus)
    MinvJ = np.linalg.solve(Mr, Jr)
    W = float(Jr @ MinvJ)
    P = -(1.0 + restitution) * v_minus / W
    zd_plus = zd.copy()
    zd_plus[free] += MinvJ * P
    y_plus = system.with_velocities(t, y, zd_plus)
    v_plus = float(J @ zd_plus)
    T_plus = system.energies(t, y_plus)["kinetic"]
    work_contact = 0.5 * P * (v_minus + v_plus)
    y_plus[-2] += -work_contact
    y_plus[-1] += (T_plus - T_minus) - work_contact
    return Jump(y_plus, P, v_minus, v_plus, T_minus, T_plus)
