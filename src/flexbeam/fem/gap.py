"""Gap geometry of the FE reference (Numba): the contact point P on the beam surface and its obstacle.

Written for the finite-element model on its own (it shares no code with the modal model's
contact kinematics); ``tests/fem/test_gap.py`` checks it against the distance of a point
to a circle and a line, finite differences and a sampled trajectory.

* P lies at the signed distance c below the centre line of the contact node, along the section
  normal: r_P = X - c n(psi), n(psi) = (-sin psi, cos psi) (c = the surface offset for
  ``contact.side`` "below", its negative "above", 0 on the centre line).
* Sphere (``kind`` 0, a point for radius 0) with centre C and radius R: the gap is the
  signed distance delta = |r_P - C| - R, with the outward normal n = (r_P - C)/|r_P - C|,
  delta' = n . r_P' and delta'' = n . r_P'' + (|r_P'|^2 - (n . r_P')^2)/|r_P - C|
  (the second term from dn/dt = (r_P' - n (n . r_P'))/|r_P - C|).
* Half-plane (``kind`` 1) through C with unit outward normal n: delta = n . (r_P - C),
  delta' = n . r_P', delta'' = n . r_P''.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

#: obstacle kinds
SPHERE, HALF_PLANE = 0, 1


@njit(cache=True)
def surface_point(xp, vp, c):
    """Surface point P at offset c below the centre line along the section normal.

    ``xp``, ``vp``: the node's (X, Y, psi) and their rates.  Returns
    (r_P, r_P', dr_P/dpsi, a0) with a0 = c psi'^2 (-sin psi, cos psi), the
    velocity-product part of r_P''.
    """
    sp, cp = math.sin(xp[2]), math.cos(xp[2])
    r = np.array([xp[0] + c * sp, xp[1] - c * cp])
    dpsi = np.array([c * cp, c * sp])
    v = np.array([vp[0] + dpsi[0] * vp[2], vp[1] + dpsi[1] * vp[2]])
    a0 = np.array([-c * sp * vp[2] * vp[2], c * cp * vp[2] * vp[2]])
    return r, v, dpsi, a0


@njit(cache=True)
def obstacle_gap(r, v, a, kind, centre, radius, normal):
    """Gap of a point at ``r`` moving with ``v``, ``a`` to a sphere or half-plane.

    Returns (delta, delta', delta'', n_x, n_y): the signed distance, its first two time
    derivatives and the unit outward normal of the obstacle at the closest point.
    """
    if kind == SPHERE:
        rx = r[0] - centre[0]
        ry = r[1] - centre[1]
        dist = math.sqrt(rx * rx + ry * ry)
        nx = rx / dist
        ny = ry / dist
        rate = nx * v[0] + ny * v[1]
        curvature = (v[0] * v[0] + v[1] * v[1] - rate * rate) / dist
        return dist - radius, rate, nx * a[0] + ny * a[1] + curvature, nx, ny
    nx = normal[0]
    ny = normal[1]
    delta = nx * (r[0] - centre[0]) + ny * (r[1] - centre[1])
    return delta, nx * v[0] + ny * v[1], nx * a[0] + ny * a[1], nx, ny


@njit(cache=True)
def gap_at(xp, vp, ap, c, kind, centre, radius, normal, J):
    """Gap delta, rate delta', acceleration delta'' of P at a node and d delta/d(X, Y, psi).

    ``xp``, ``vp``, ``ap``: the node's (X, Y, psi) and their first and second rates;
    ``J`` (3) is filled with the Jacobian n^T dr_P/d(X, Y, psi) = (n_x, n_y, n . dr_P/dpsi).
    """
    r, v, dpsi, a0 = surface_point(xp, vp, c)
    acc = np.array([ap[0] + dpsi[0] * ap[2] + a0[0], ap[1] + dpsi[1] * ap[2] + a0[1]])
    delta, rate, accel, nx, ny = obstacle_gap(r, v, acc, kind, centre, radius, normal)
    J[0] = nx
    J[1] = ny
    J[2] = nx * dpsi[0] + ny * dpsi[1]
    return delta, rate, accel


@njit(cache=True)
def hermite_dip(g0, v0, g1, v1, h):
    """Fraction s in (0, 1) at which the cubic Hermite of the gap is lowest if < 0, else -1.

    The cubic through (delta, delta') = (g0, v0) and (g1, v1) at the ends of a step of
    length h is sampled at s = i/64 (a grazing contact inside a free step).
    """
    best = 0.0
    sbest = -1.0
    for i in range(1, 64):
        s = i / 64.0
        s2 = s * s
        s3 = s2 * s
        p = (2 * s3 - 3 * s2 + 1) * g0 + (s3 - 2 * s2 + s) * h * v0 + (-2 * s3 + 3 * s2) * g1 + (s3 - s2) * h * v1
        if p < best:
            best = p
            sbest = s
    return sbest
