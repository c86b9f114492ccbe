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
* Contact anywhere (:func:`anywhere_gap`): the beam's surface is the capsule of radius c about
  the deformed centre line r(x) (the co-rotational interpolation of each element), and the gap
  is min_x |r(x) - C| - R - c (sphere) or min_x n . (r(x) - C) - c (half-plane), x in [0, L]
  (the ends' hemispherical caps included), the minimiser found by :func:`nearest_point`.
"""

from __future__ import annotations

import math

import numpy as np

from .element import chord_rates, element_chord, gather, point_kinematics
from .jit import fem_jit

#: obstacle kinds
SPHERE, HALF_PLANE = 0, 1


@fem_jit
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


@fem_jit
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


@fem_jit
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


@fem_jit
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


# ---------------------------------------------------------------------------------------------- contact anywhere
#: samples per element of the coarse search for the nearest point (then safeguarded Newton)
ANYWHERE_SAMPLES = 8


@fem_jit
def _centre_line(xe, l0, xi):
    """Centre-line point of an element and its first two xi-derivatives (nodal coordinates fixed).

    r(xi) = (1 - xi) r_A + xi r_B + v(xi) e2(beta), v = l0 (h1 theta_1 + h2 theta_2) (see
    :mod:`flexbeam.fem.element`), so r_xi = r_B - r_A + v_xi e2 and r_xixi = v_xixi e2 with
    h1' = 1 - 4 xi + 3 xi^2, h2' = -2 xi + 3 xi^2, h1'' = -4 + 6 xi, h2'' = -2 + 6 xi.
    """
    dx, dy, ell, c, s, t1, t2 = element_chord(xe)
    h1 = xi * (1.0 - xi) ** 2
    h2 = -xi * xi * (1.0 - xi)
    v = l0 * (h1 * t1 + h2 * t2)
    vx = l0 * ((1.0 - 4.0 * xi + 3.0 * xi * xi) * t1 + (-2.0 * xi + 3.0 * xi * xi) * t2)
    vxx = l0 * ((-4.0 + 6.0 * xi) * t1 + (-2.0 + 6.0 * xi) * t2)
    r = np.array([(1.0 - xi) * xe[0] + xi * xe[3] - v * s, (1.0 - xi) * xe[1] + xi * xe[4] + v * c])
    rx = np.array([dx - vx * s, dy + vx * c])
    rxx = np.array([-vxx * s, vxx * c])
    return r, rx, rxx


@fem_jit
def _objective(xe, l0, xi, kind, centre, normal):
    """f(xi) minimised by the nearest point and f', f'' in xi: |r - C| for a sphere (f'' = n . r_xixi +
    (|r_xi|^2 - (n . r_xi)^2)/|r - C|), n . (r - C) for a half-plane."""
    r, rx, rxx = _centre_line(xe, l0, xi)
    if kind == SPHERE:
        px = r[0] - centre[0]
        py = r[1] - centre[1]
        dist = math.sqrt(px * px + py * py)
        nx = px / dist
        ny = py / dist
        f1 = nx * rx[0] + ny * rx[1]
        f2 = nx * rxx[0] + ny * rxx[1] + (rx[0] * rx[0] + rx[1] * rx[1] - f1 * f1) / dist
        return dist, f1, f2
    nx = normal[0]
    ny = normal[1]
    f = nx * (r[0] - centre[0]) + ny * (r[1] - centre[1])
    return f, nx * rx[0] + ny * rx[1], nx * rxx[0] + ny * rxx[1]


@fem_jit
def _refine(xe, l0, a, b, kind, centre, normal):
    """Minimiser of f on [a, b] (f unimodal there): an end whose slope points outwards, else the root of f'
    by Newton's method safeguarded by bisection.  Returns (xi, f)."""
    fa, ga, _ = _objective(xe, l0, a, kind, centre, normal)
    if ga >= 0.0:
        return a, fa
    fb, gb, _ = _objective(xe, l0, b, kind, centre, normal)
    if gb <= 0.0:
        return b, fb
    x = 0.5 * (a + b)
    f = fa
    for _ in range(100):
        f, g, h = _objective(xe, l0, x, kind, centre, normal)
        if g > 0.0:
            b = x
        else:
            a = x
        xn = x - g / h if h > 0.0 else 0.5 * (a + b)
        if not (a < xn < b):
            xn = 0.5 * (a + b)
        if abs(xn - x) <= 1e-15 or b - a <= 1e-15:
            break
        x = xn
    return x, f


@fem_jit
def nearest_point(X, l0, kind, centre, normal):
    """Element e, local coordinate xi and value f of the centre-line point minimising f (see :func:`_objective`).

    ``X``: node array (N + 1) x 3.  The deformed centre line of every element (its co-rotational
    interpolation) is sampled at xi = i / ANYWHERE_SAMPLES; the best sample's neighbourhood (one sample
    spacing either side, in the adjacent element too at a node) is refined by :func:`_refine`.  Minimising
    over x in [0, L] gives the capsule's hemispherical end caps too.
    """
    nel = l0.size
    xe = np.empty(6)
    best = np.inf
    be = 0
    bi = 0
    m = ANYWHERE_SAMPLES
    for e in range(nel):
        for k in range(3):
            xe[k] = X[e, k]
            xe[3 + k] = X[e + 1, k]
        for i in range(m + 1):
            f = _objective(xe, l0[e], i / m, kind, centre, normal)[0]
            if f < best:
                best = f
                be = e
                bi = i
    rbest = np.inf
    re = be
    rxi = bi / m
    for e in range(max(be - 1, 0), min(be + 2, nel)):
        if e == be:
            a, b = max(bi - 1, 0) / m, min(bi + 1, m) / m
        elif e == be - 1 and bi == 0:
            a, b = (m - 1) / m, 1.0
        elif e == be + 1 and bi == m:
            a, b = 0.0, 1.0 / m
        else:
            continue
        for k in range(3):
            xe[k] = X[e, k]
            xe[3 + k] = X[e + 1, k]
        xi, f = _refine(xe, l0[e], a, b, kind, centre, normal)
        if f < rbest:
            rbest = f
            re = e
            rxi = xi
    return re, rxi, rbest


@fem_jit
def anywhere_gap(X, V, A, l0, tube, kind, centre, radius, normal, Jg):
    """Gap of the beam's capsule surface (radius ``tube`` about the centre line) to an obstacle, contact anywhere.

    delta = min_x |r(x) - C| - R - c (sphere) or min_x n . (r(x) - C) - c (half-plane) over the deformed
    centre line r(x), x in [0, L], at the minimiser x* (element e, xi) with normal n.  By the envelope
    theorem delta' = n . r'(x*) and d delta / dz_e = n^T G(x*) (``Jg``, 6, filled), G = dr/dz_e; and
    delta'' = f_tt - f_xt^2 / f_xx (x* moving) with f_tt = n . r'' (+ (|r'|^2 - (n . r')^2)/|r - C| for a
    sphere), f_xt = n . r_xi' (+ (r_xi . r' - (n . r_xi)(n . r'))/|r - C|), the last term only for x*
    inside (0, L).

    Returns (delta, delta', delta'', e, xi).
    """
    e, xi, _ = nearest_point(X, l0, kind, centre, normal)
    xe = np.empty(6)
    ve = np.empty(6)
    ae = np.empty(6)
    gather(X, V, A, e, xe, ve, ae)
    G = np.empty((2, 6))
    r, v, a = point_kinematics(xe, ve, ae, l0[e], xi, G)
    delta, rate, accel, nx, ny = obstacle_gap(r, v, a, kind, centre, radius + tube, normal)
    if kind != SPHERE:
        delta -= tube
    for b in range(6):
        Jg[b] = nx * G[0, b] + ny * G[1, b]
    inside = not ((e == 0 and xi <= 0.0) or (e == l0.size - 1 and xi >= 1.0))
    if inside:
        _, rx, _ = _centre_line(xe, l0[e], xi)
        f2 = _objective(xe, l0[e], xi, kind, centre, normal)[2]
        # r_xi' = (r_B' - r_A') + v_xi' e2 - v_xi beta' e1
        _, _, ell, c, s, t1, t2 = element_chord(xe)
        ddx, ddy, bdot, _ = chord_rates(ve, ell, c, s)
        d1 = 1.0 - 4.0 * xi + 3.0 * xi * xi
        d2 = -2.0 * xi + 3.0 * xi * xi
        vx = l0[e] * (d1 * t1 + d2 * t2)
        vxd = l0[e] * (d1 * (ve[2] - bdot) + d2 * (ve[5] - bdot))
        rxt0 = ddx - vxd * s - vx * bdot * c
        rxt1 = ddy + vxd * c - vx * bdot * s
        fxt = nx * rxt0 + ny * rxt1
        if kind == SPHERE:
            dist = delta + radius + tube
            fxt += (rx[0] * v[0] + rx[1] * v[1] - (nx * rx[0] + ny * rx[1]) * rate) / dist
        if f2 > 0.0:
            accel -= fxt * fxt / f2
    return delta, rate, accel, e, xi


@fem_jit
def node_tangent(xp, vp, c, nx, ny, Jt):
    """Slip velocity v_t = t . r_P' of P at a node along the contact's tangent t = (-n_y, n_x) (the obstacle's
    outward normal n turned by +90 degrees, as the modal model's), and ``Jt`` (3) = t^T dr_P/d(X, Y, psi)."""
    _, v, dpsi, _ = surface_point(xp, vp, c)
    tx, ty = -ny, nx
    Jt[0] = tx
    Jt[1] = ty
    Jt[2] = tx * dpsi[0] + ty * dpsi[1]
    return tx * v[0] + ty * v[1]


@fem_jit
def anywhere_tangent(X, V, l0, tube, e, xi, kind, centre, normal, Jt):
    """Slip velocity and ``Jt`` (6, over element e's DOFs) of the capsule's surface point in contact, at x* (e, xi),
    against a sphere (its normal n = (r(x*) - C) / |r(x*) - C|) or a half-plane (its normal).

    The point lies at -c n from the centre line's r(x*), c = ``tube``, a material point of the section there, which
    turns with the section's angle psi(xi) = beta + d1 theta_1 + d2 theta_2 (the chord's angle and the cubic's slope,
    d1 = 1 - 4 xi + 3 xi^2, d2 = 3 xi^2 - 2 xi: the nodal angles at the ends): its velocity is r' - c psi' (n_y, -n_x),
    so along t = (-n_y, n_x) v_t = t . r' - c psi' and Jt = t^T G - c d psi / dz_e, with
    d psi / dz_e = (1 - d1 - d2) d beta / dz_e + d1 e_psi_A + d2 e_psi_B and d beta / dz_e = (s, -c, 0, -s, c, 0) / l.
    """
    xe = np.empty(6)
    ve = np.empty(6)
    ae = np.zeros(6)
    gather(X, V, V, e, xe, ve, ae)  # (the accelerations are not needed: V stands in, ae is scratch)
    G = np.empty((2, 6))
    r, v, _ = point_kinematics(xe, ve, ae, l0[e], xi, G)
    nx, ny = normal[0], normal[1]
    if kind == SPHERE:
        dist = math.sqrt((r[0] - centre[0]) ** 2 + (r[1] - centre[1]) ** 2)
        nx, ny = (r[0] - centre[0]) / dist, (r[1] - centre[1]) / dist
    _, _, ell, cb, sb, _, _ = element_chord(xe)
    d1 = 1.0 - 4.0 * xi + 3.0 * xi * xi
    d2 = 3.0 * xi * xi - 2.0 * xi
    db = np.array([sb, -cb, 0.0, -sb, cb, 0.0]) / ell
    tx, ty = -ny, nx
    psid = 0.0
    for b in range(6):
        dpsi = (1.0 - d1 - d2) * db[b] + (d1 if b == 2 else 0.0) + (d2 if b == 5 else 0.0)
        Jt[b] = tx * G[0, b] + ty * G[1, b] - tube * dpsi
        psid += dpsi * ve[b]
    return tx * v[0] + ty * v[1] - tube * psid
