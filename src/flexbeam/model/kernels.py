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

# Small dense products as plain loops: at n <= 64 a BLAS call (and the temporary it
# allocates) costs more than the arithmetic, and these kernels run per sample and per stage.


@njit(cache=True)
def dot(a, b):
    """a . b of two vectors."""
    acc = 0.0
    for i in range(a.size):
        acc += a[i] * b[i]
    return acc


@njit(cache=True)
def row_dot(A, i, x):
    """(A x)_i."""
    acc = 0.0
    for j in range(x.size):
        acc += A[i, j] * x[j]
    return acc


@njit(cache=True)
def quad(A, x):
    """x^T A x."""
    acc = 0.0
    for i in range(x.size):
        acc += x[i] * row_dot(A, i, x)
    return acc


@njit(cache=True)
def mass_matrix(q, Jc, Mc, Mff, mtf, out):
    """Fill ``out`` (N x N, N = n + 1) with M(q); ``Jc = J_h + J0``."""
    n = q.size
    out[0, 0] = Jc + quad(Mc, q)
    for i in range(n):
        out[0, i + 1] = mtf[i]
        out[i + 1, 0] = mtf[i]
        for j in range(n):
            out[i + 1, j + 1] = Mff[i, j]


@njit(cache=True)
def generalized_forces(theta, omega, q, qd, tau, g, m1, Mc, Kff, sf, G, out):
    """Fill ``out`` (N) with Q(z, z', t) of the unimpact equations (no contact)."""
    n = q.size
    c, s = math.cos(theta), math.sin(theta)
    qMcqd = 0.0
    qGq = 0.0
    for i in range(n):
        mcq = row_dot(Mc, i, q)
        gq = row_dot(G, i, q)
        qMcqd += mcq * qd[i]
        qGq += q[i] * gq
        out[i + 1] = -row_dot(Kff, i, q) + omega * omega * mcq - g * (c * sf[i] - s * gq)
    out[0] = tau - 2.0 * omega * qMcqd - g * (c * (m1 - 0.5 * qGq) - s * dot(sf, q))


@njit(cache=True)
def energies(theta, omega, q, qd, Jc, Mc, Mff, mtf, Kff, m1, sf, G, g):
    """Return (kinetic, elastic, gravitational) energy [J]."""
    T = 0.5 * omega * omega * (Jc + quad(Mc, q)) + omega * dot(mtf, qd) + 0.5 * quad(Mff, qd)
    Ve = 0.5 * quad(Kff, q)
    Vg = g * (math.sin(theta) * (m1 - 0.5 * quad(G, q)) + math.cos(theta) * dot(sf, q))
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
    ang = dot(dphi, q)
    angd = dot(dphi, qd)
    sa, ca = math.sin(ang), math.cos(ang)
    ct, st = math.cos(theta), math.sin(theta)
    # d rho / d q (2 x n): (-H q + c ca Phi', Phi + c sa Phi'), and its products with q, q'
    qHq = 0.0
    rhod_x = 0.0
    rhod_y = 0.0
    for i in range(n):
        hq = row_dot(H, i, q)
        qHq += q[i] * hq
        dx = -hq + c * ca * dphi[i]
        dy = phi[i] + c * sa * dphi[i]
        rhod_x += dx * qd[i]
        rhod_y += dy * qd[i]
        dr[0, i + 1] = ct * dx - st * dy
        dr[1, i + 1] = st * dx + ct * dy
    rx = base - 0.5 * qHq + c * sa
    ry = dot(phi, q) - c * ca
    # velocity-product part of rho''
    acc_x = -quad(H, qd) - c * sa * angd * angd
    acc_y = c * ca * angd * angd
    # floating-frame quantities -> global via A(theta) = [[ct, -st], [st, ct]]
    # dr/dtheta = A S rho, S rho = (-ry, rx)
    dr[0, 0] = ct * (-ry) - st * rx
    dr[1, 0] = st * (-ry) + ct * rx
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
def transverse_velocity(omega, q, qd, base, phi, H):
    """Velocity of a beam-axis point (offset c = 0) normal to the rotated beam axis [m/s].

    The y-component in the rotating frame of :func:`point_kinematics`'s velocity,
    rho_y' + theta' rho_x = Phi q' + theta' (r_h + x - q^T H q / 2), without its Jacobian and
    acceleration terms (what the measuring points record).
    """
    return dot(phi, qd) + omega * (base - 0.5 * quad(H, q))


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
