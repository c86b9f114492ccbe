"""Compiled (Numba) kernels of the rigid-flexible coupling equations.

Generalised coordinates z = [theta, q_1..q_n].  First-order approximation model
(PHYSICS.md, verified there by Lagrange's equations; Mc = M_ff - D):

    M(q) = [[J_h + J0 + q^T Mc q,  m_tf],
            [m_tf^T,               M_ff]]

    Q_theta = tau - 2 theta' q^T Mc q' - g [cos(theta)(m1 - 1/2 q^T G q) - sin(theta) s_f q]
    Q_f     = -K_ff q + theta'^2 Mc q - g [cos(theta) s_f^T - sin(theta) G q]

so that M z'' = Q (+ J^T F for a contact force F).  The zeroth-order model has
D = G = 0.  Energies: T = 1/2 z'^T M z', V_e = 1/2 q^T K_ff q,
V_g = g [sin(theta)(m1 - 1/2 q^T G q) + cos(theta) s_f q].

Point kinematics of a material point at x, offset c below the centre line along the
deformed section normal (section rotation phi = Phi'(x) q):

    rho(q) = (r_h + x - 1/2 q^T H q + c sin(phi),  Phi q - c cos(phi)),   r = A(theta) rho.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def mass_matrix(q, Jc, Mc, Mff, mtf, out):
    """Fill ``out`` (N x N, N = n + 1) with M(q); ``Jc = J_h + J0``."""
    n = q.size
    Mcq = Mc @ q
    out[0, 0] = Jc + q @ Mcq
    for i in range(n):
        out[0, i + 1] = mtf[i]
        out[i + 1, 0] = mtf[i]
        for j in range(n):
            out[i + 1, j + 1] = Mff[i, j]


@njit(cache=True)
def generalized_forces(theta, omega, q, qd, tau, g, m1, Mc, Kff, sf, G, out):
    """Fill ``out`` (N) with Q(z, z', t) of the unimpact equations (no contact)."""
    n = q.size
    Mcq = Mc @ q
    Gq = G @ q
    c, s = math.cos(theta), math.sin(theta)
    out[0] = tau - 2.0 * omega * (Mcq @ qd) - g * (c * (m1 - 0.5 * (q @ Gq)) - s * (sf @ q))
    Kq = Kff @ q
    for i in range(n):
        out[i + 1] = -Kq[i] + omega * omega * Mcq[i] - g * (c * sf[i] - s * Gq[i])


@njit(cache=True)
def energies(theta, omega, q, qd, Jc, Mc, Mff, mtf, Kff, m1, sf, G, g):
    """Return (kinetic, elastic, gravitational) energy [J]."""
    T = 0.5 * omega * omega * (Jc + q @ (Mc @ q)) + omega * (mtf @ qd) + 0.5 * (qd @ (Mff @ qd))
    Ve = 0.5 * (q @ (Kff @ q))
    Vg = g * (math.sin(theta) * (m1 - 0.5 * (q @ (G @ q))) + math.cos(theta) * (sf @ q))
    return T, Ve, Vg


@njit(cache=True)
def point_kinematics(theta, omega, q, qd, base, phi, dphi, H, c, dr):
    """Position, velocity and velocity-product acceleration of a beam point.

    Parameters
    ----------
    theta, omega
        Hub angle [rad] and rate [rad/s].
    q, qd
        Modal coordinates and rates.
    base, phi, dphi, H, c
        Point data: r_h + x, Phi(x), Phi'(x), H(x), offset c [m].
    dr
        Output (2 x N): dr/dz, the Jacobian of the global position.

    Returns
    -------
    r, v, a0
        Global position, velocity, and the acceleration for z'' = 0 (the
        velocity-product terms, needed for J' z' in the contact constraint).
    """
    n = q.size
    Hq = H @ q
    ang = dphi @ q
    angd = dphi @ qd
    sa, ca = math.sin(ang), math.cos(ang)
    rx = base - 0.5 * (q @ Hq) + c * sa
    ry = phi @ q - c * ca
    # d rho / d q (2 x n)
    drho_x = -Hq + c * ca * dphi
    drho_y = phi + c * sa * dphi
    rhod_x = drho_x @ qd
    rhod_y = drho_y @ qd
    # velocity-product part of rho''
    acc_x = -(qd @ (H @ qd)) - c * sa * angd * angd
    acc_y = c * ca * angd * angd
    ct, st = math.cos(theta), math.sin(theta)
    # floating-frame quantities -> global via A(theta) = [[ct, -st], [st, ct]]
    # dr/dtheta = A S rho, S rho = (-ry, rx)
    dr[0, 0] = ct * (-ry) - st * rx
    dr[1, 0] = st * (-ry) + ct * rx
    for i in range(n):
        dr[0, i + 1] = ct * drho_x[i] - st * drho_y[i]
        dr[1, i + 1] = st * drho_x[i] + ct * drho_y[i]
    r = np.empty(2)
    r[0] = ct * rx - st * ry
    r[1] = st * rx + ct * ry
    # local velocity rho' + omega S rho
    vlx = rhod_x - omega * ry
    vly = rhod_y + omega * rx
    v = np.empty(2)
    v[0] = ct * vlx - st * vly
    v[1] = st * vlx + ct * vly
    # local acceleration for z'' = 0: rho''_0 + 2 omega S rho' - omega^2 rho
    alx = acc_x - 2.0 * omega * rhod_y - omega * omega * rx
    aly = acc_y + 2.0 * omega * rhod_x - omega * omega * ry
    a0 = np.empty(2)
    a0[0] = ct * alx - st * aly
    a0[1] = st * alx + ct * aly
    return r, v, a0


@njit(cache=True)
def gap_state(r, v, a0, dr, kind, centre, radius, normal, J):
    """Gap delta, its rate, its velocity-product acceleration and Jacobian J.

    ``kind = 0``: sphere (or point, radius 0) at ``centre``: delta = |r - c| - r_s,
    n = (r - c)/|r - c|, delta'' = n . r'' + (|r'|^2 - (n . r')^2)/|r - c|.
    ``kind = 1``: half-plane through ``centre`` with unit outward ``normal``:
    delta = n . (r - c).  ``J`` (N) is filled with d delta / dz = n^T dr/dz.
    Returns (delta, delta', gamma, nx, ny) where gamma is delta'' at z'' = 0.
    """
    if kind == 0:
        dx = r[0] - centre[0]
        dy = r[1] - centre[1]
        dist = math.sqrt(dx * dx + dy * dy)
        nx, ny = dx / dist, dy / dist
        delta = dist - radius
        vn = nx * v[0] + ny * v[1]
        gamma = nx * a0[0] + ny * a0[1] + (v[0] * v[0] + v[1] * v[1] - vn * vn) / dist
    else:
        nx, ny = normal[0], normal[1]
        delta = nx * (r[0] - centre[0]) + ny * (r[1] - centre[1])
        vn = nx * v[0] + ny * v[1]
        gamma = nx * a0[0] + ny * a0[1]
    for i in range(J.size):
        J[i] = nx * dr[0, i] + ny * dr[1, i]
    return delta, vn, gamma, nx, ny
