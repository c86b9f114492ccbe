"""The co-rotational beam element (Numba): internal force, tangent, exact inertia, points on it.

Element choice
--------------
Two-node planar Euler-Bernoulli elements with three degrees of freedom per node,
the global position (X, Y) and the absolute section rotation psi, in the
co-rotational description of Crisfield (1991), *Non-linear Finite Element Analysis
of Solids and Structures*, Vol. 1 (Wiley), the 2-D co-rotational beam:

* the rigid motion of an element is carried by its chord, from node A to node B,
  d = r_B - r_A, current length l = |d|, chord angle beta, e1 = d/l,
  e2 = (-e1_y, e1_x);
* in the chord frame only three deformation modes remain, the stretch
  u = l - l0 (computed as (l^2 - l0^2)/(l + l0)) and the two local end rotations
  theta_i = psi_i - beta (taken in (-pi, pi]);
* the local element is the linear Euler-Bernoulli element (linear axial, cubic
  Hermite transverse), so that

      N = EA u / l0,   [M1, M2] = (EI / l0) [[4, 2], [2, 4]] [theta_1, theta_2],
      V_e = EA u^2 / (2 l0) + (EI / l0)(2 theta_1^2 + 2 theta_1 theta_2 + 2 theta_2^2).

  The global internal force is f = B^T [N, M1, M2] with
  B = [r; e3 - z/l; e6 - z/l], r = [-e1, 0, e1, 0], z = [-e2, 0, e2, 0], and the
  consistent tangent (Crisfield 1991; checked against finite differences in the tests)

      K = B^T D B + N z z^T / l + (M1 + M2)(r z^T + z r^T) / l^2.

Large rotations and large displacements are therefore exact in the limit of a fine
mesh, while each element stays geometrically linear in its own frame; no modal
truncation and no second-order coupling approximation is made.

Mass: the kinetic energy is evaluated *exactly* for the interpolated field that the
element's strain energy assumes.  In the chord frame the transverse deflection is
v(xi) = l0 [h1(xi) theta_1 + h2(xi) theta_2], h1 = xi (1 - xi)^2, h2 = -xi^2 (1 - xi),
and the axial displacement is linear, so that the position of the material point
xi = x / l0 of the centre line is

    r(xi) = (1 - xi) r_A + xi r_B + v(xi) e2(beta).

With G = dr/dz_e (2 x 6) the inertia force is f_in = int mu G^T r'' dx,
r'' = G z_e'' + a0 where a0 collects the velocity products; this is exactly
d/dt dT/dz' - dT/dz of T = 1/2 int mu |r'|^2 dx (Lagrange's equations of a
holonomic system).  For a straight element it gives the classical consistent mass
matrix (linear axial, Hermite-cubic transverse); the configuration dependence comes
only from v e2, i.e. from the small local deflection, and all velocity-product
(centrifugal, Coriolis) terms are kept in the residual.  Rotary inertia of the
section is neglected (Euler-Bernoulli), as in the modal model.  G and a0 are cubic
in xi (l, beta are constant over the element), so 4-point Gauss quadrature
integrates mu |r'|^2, f_in and the mass exactly.  The construction follows the
idea of a co-rotational inertia from the same cubic interpolation as the stiffness
(cf. T.-N. Le, J.-M. Battini, M. Hjiaj, "Efficient formulation for dynamics of
corotational 2D beams", *Comput. Mech.* 2011), written here directly as Lagrange's
equations of the interpolated field.

Why this element: two nodes with (X, Y, psi) make the hub clamp, the node at the
contact point and its section rotation (for the surface offset c) direct; Hermite
bending gives frequencies converging as h^4 (consistent mass) and nodally exact
linear statics; the co-rotational split keeps every element linear in its own
frame, so large overall rotation and large deflection are exact in the mesh limit;
and the element has a cheap, exactly derivable internal force and tangent.

Gravity is the potential V_g = g int mu r_y dx of the same field.

Newton tangents neglect the configuration and velocity dependence of the inertia
and gravity forces (they are of the order of the local deflection times the rates
squared); the residual is always complete, so only the convergence rate is affected.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import fem_jit

_G4 = np.polynomial.legendre.leggauss(4)
GAUSS_XI = 0.5 * (_G4[0] + 1.0)  # points on [0, 1]
GAUSS_W = 0.5 * _G4[1]  # weights on [0, 1]


@fem_jit
def _local_rotations(c, s, p1, p2):
    t1 = math.atan2(c * math.sin(p1) - s * math.cos(p1), c * math.cos(p1) + s * math.sin(p1))
    t2 = math.atan2(c * math.sin(p2) - s * math.cos(p2), c * math.cos(p2) + s * math.sin(p2))
    return t1, t2


@fem_jit
def gather(X, V, A, e, xe, ve, ae):
    """Element e's coordinates, velocities and accelerations (6 each: its two nodes' X, Y, psi) from the node
    arrays (N + 1) x 3, into ``xe``, ``ve``, ``ae``."""
    for k in range(3):
        xe[k] = X[e, k]
        xe[3 + k] = X[e + 1, k]
        ve[k] = V[e, k]
        ve[3 + k] = V[e + 1, k]
        ae[k] = A[e, k]
        ae[3 + k] = A[e + 1, k]


@fem_jit
def element_chord(xe):
    """The chord of an element from node A to node B: (dx, dy), its length l, its direction (c, s) = (dx, dy)/l
    and the nodes' rotations theta_1, theta_2 relative to it (the co-rotational frame)."""
    dx = xe[3] - xe[0]
    dy = xe[4] - xe[1]
    ell = math.sqrt(dx * dx + dy * dy)
    c = dx / ell
    s = dy / ell
    t1, t2 = _local_rotations(c, s, xe[2], xe[5])
    return dx, dy, ell, c, s, t1, t2


@fem_jit
def chord_rates(ve, ell, c, s):
    """Rates of an element's chord: (dx', dy'), its rotation beta' = (-s dx' + c dy')/l and stretching
    l' = c dx' + s dy'."""
    ddx = ve[3] - ve[0]
    ddy = ve[4] - ve[1]
    return ddx, ddy, (-s * ddx + c * ddy) / ell, c * ddx + s * ddy


@fem_jit
def corotational_element(xe, l0, EA, EI, fe, Ke, want_K):
    """Internal force, tangent and strain energy of one co-rotational element.

    Parameters
    ----------
    xe
        Element coordinates [X_A, Y_A, psi_A, X_B, Y_B, psi_B].
    l0
        Initial length [m].
    EA, EI
        Axial and bending stiffness.
    fe, Ke
        Output: internal force (6) and tangent (6 x 6); filled (not added to).
    want_K
        Compute Ke.

    Returns
    -------
    float
        Strain energy V_e [J].
    """
    dx = xe[3] - xe[0]
    dy = xe[4] - xe[1]
    l2 = dx * dx + dy * dy
    ell = math.sqrt(l2)
    c = dx / ell
    s = dy / ell
    t1, t2 = _local_rotations(c, s, xe[2], xe[5])
    u = (l2 - l0 * l0) / (ell + l0)
    k = EI / l0
    N = EA * u / l0
    M1 = k * (4.0 * t1 + 2.0 * t2)
    M2 = k * (2.0 * t1 + 4.0 * t2)
    # r = [-e1, 0, e1, 0], z = [-e2, 0, e2, 0], b_i = e_(3i) - z / l
    r0, r1, r3, r4 = -c, -s, c, s
    z0, z1, z3, z4 = s, -c, -s, c
    fe[0] = r0 * N - z0 / ell * (M1 + M2)
    fe[1] = r1 * N - z1 / ell * (M1 + M2)
    fe[2] = M1
    fe[3] = r3 * N - z3 / ell * (M1 + M2)
    fe[4] = r4 * N - z4 / ell * (M1 + M2)
    fe[5] = M2
    if want_K:
        r = (r0, r1, 0.0, r3, r4, 0.0)
        z = (z0, z1, 0.0, z3, z4, 0.0)
        ka = EA / l0
        gN = N / ell
        gM = (M1 + M2) / (ell * ell)
        for a in range(6):
            b1a = -z[a] / ell + (1.0 if a == 2 else 0.0)
            b2a = -z[a] / ell + (1.0 if a == 5 else 0.0)
            for b in range(6):
                b1b = -z[b] / ell + (1.0 if b == 2 else 0.0)
                b2b = -z[b] / ell + (1.0 if b == 5 else 0.0)
                Ke[a, b] = (
                    ka * r[a] * r[b]
                    + k * (4.0 * b1a * b1b + 2.0 * (b1a * b2b + b2a * b1b) + 4.0 * b2a * b2b)
                    + gN * z[a] * z[b]
                    + gM * (r[a] * z[b] + z[a] * r[b])
                )
    return 0.5 * N * u + k * (2.0 * t1 * t1 + 2.0 * t1 * t2 + 2.0 * t2 * t2)


@fem_jit
def _shape_G(xi, l0, ell, c, s, vb, G):
    """Fill G = dr/dz_e (2 x 6) at xi; returns (h1, h2)."""
    h1 = xi * (1.0 - xi) ** 2
    h2 = -xi * xi * (1.0 - xi)
    # w = d(v e2)/d beta = -l0 (h1 + h2) e2 - v e1
    hs = -l0 * (h1 + h2)
    wx = hs * (-s) - vb * c
    wy = hs * c - vb * s
    e2x, e2y = -s, c
    # d beta / d r_A = -e2 / l,  d beta / d r_B = e2 / l
    G[0, 0] = (1.0 - xi) - wx * e2x / ell
    G[0, 1] = -wx * e2y / ell
    G[1, 0] = -wy * e2x / ell
    G[1, 1] = (1.0 - xi) - wy * e2y / ell
    G[0, 3] = xi + wx * e2x / ell
    G[0, 4] = wx * e2y / ell
    G[1, 3] = wy * e2x / ell
    G[1, 4] = xi + wy * e2y / ell
    G[0, 2] = l0 * h1 * e2x
    G[1, 2] = l0 * h1 * e2y
    G[0, 5] = l0 * h2 * e2x
    G[1, 5] = l0 * h2 * e2y
    return h1, h2


@fem_jit
def inertia_element(xe, ve, ae, l0, mu, field, gxi, gw, fin, Me, fg, G):
    """Inertia force, mass matrix, gravity force and energies of one element.

    Parameters
    ----------
    xe, ve, ae
        Element coordinates, velocities and accelerations (6 each).
    l0, mu, field
        Initial length [m], line density [kg/m], the uniform field (g_x, g_y) [m/s^2]: gravity (0, -g), or on a
        moving base in its frame (0, -g) - a_O(t).
    gxi, gw
        Gauss points and weights on [0, 1].
    fin, Me, fg
        Output (filled): inertia force int mu G^T r'', mass int mu G^T G,
        generalised gravity force int mu G^T (g_x, g_y).
    G
        Work array (2 x 6).

    Returns
    -------
    T, V_g
        Kinetic and gravitational energy [J] (the field's potential -int mu (g_x x + g_y y)).
    """
    g, gx = -field[1], field[0]  # (0, -g): the fixed joint's operations, bit for bit
    dx, dy, ell, c, s, t1, t2 = element_chord(xe)
    ddx, ddy, bdot, ldot = chord_rates(ve, ell, c, s)
    t1d = ve[2] - bdot
    t2d = ve[5] - bdot
    bdd0 = -2.0 * bdot * ldot / ell
    for a in range(6):
        fin[a] = 0.0
        fg[a] = 0.0
        for b in range(6):
            Me[a, b] = 0.0
    T = 0.0
    Vg = 0.0
    for q in range(gxi.size):
        xi = gxi[q]
        wq = gw[q] * mu * l0
        h1 = xi * (1.0 - xi) ** 2
        h2 = -xi * xi * (1.0 - xi)
        vb = l0 * (h1 * t1 + h2 * t2)
        vbd = l0 * (h1 * t1d + h2 * t2d)
        vbdd0 = -l0 * (h1 + h2) * bdd0
        _shape_G(xi, l0, ell, c, s, vb, G)
        # velocity-product acceleration: vbdd0 e2 - 2 vbd bdot e1 - vb bdd0 e1 - vb bdot^2 e2
        a0x = (vbdd0 - vb * bdot * bdot) * (-s) + (-2.0 * vbd * bdot - vb * bdd0) * c
        a0y = (vbdd0 - vb * bdot * bdot) * c + (-2.0 * vbd * bdot - vb * bdd0) * s
        vx = 0.0
        vy = 0.0
        ax = a0x
        ay = a0y
        for b in range(6):
            vx += G[0, b] * ve[b]
            vy += G[1, b] * ve[b]
            ax += G[0, b] * ae[b]
            ay += G[1, b] * ae[b]
        T += 0.5 * wq * (vx * vx + vy * vy)
        ry = (1.0 - xi) * xe[1] + xi * xe[4] + vb * c
        Vg += wq * g * ry
        if gx != 0.0:
            Vg -= wq * gx * ((1.0 - xi) * xe[0] + xi * xe[3] - vb * s)
        for a in range(6):
            fin[a] += wq * (G[0, a] * ax + G[1, a] * ay)
            fg[a] -= wq * g * G[1, a]
            if gx != 0.0:
                fg[a] += wq * gx * G[0, a]
            for b in range(6):
                Me[a, b] += wq * (G[0, a] * G[0, b] + G[1, a] * G[1, b])
    return T, Vg


@fem_jit
def point_on_element(xe, ve, l0, xi):
    """Position and velocity of the centre-line point xi in [0, 1] of an element."""
    dx, dy, ell, c, s, t1, t2 = element_chord(xe)
    h1 = xi * (1.0 - xi) ** 2
    h2 = -xi * xi * (1.0 - xi)
    vb = l0 * (h1 * t1 + h2 * t2)
    G = np.empty((2, 6))
    _shape_G(xi, l0, ell, c, s, vb, G)
    r = np.empty(2)
    r[0] = (1.0 - xi) * xe[0] + xi * xe[3] - vb * s
    r[1] = (1.0 - xi) * xe[1] + xi * xe[4] + vb * c
    v = np.zeros(2)
    for b in range(6):
        v[0] += G[0, b] * ve[b]
        v[1] += G[1, b] * ve[b]
    return r, v


@fem_jit
def point_kinematics(xe, ve, ae, l0, xi, G):
    """Position r, velocity r' and acceleration r'' of the centre-line point xi of an element.

    r(xi) = (1 - xi) r_A + xi r_B + v(xi) e2(beta), r' = G z_e', r'' = G z_e'' + a0, with
    G = dr/dz_e (filled, 2 x 6) and a0 the velocity products of :func:`inertia_element`.
    """
    dx, dy, ell, c, s, t1, t2 = element_chord(xe)
    ddx, ddy, bdot, ldot = chord_rates(ve, ell, c, s)
    t1d = ve[2] - bdot
    t2d = ve[5] - bdot
    bdd0 = -2.0 * bdot * ldot / ell
    h1 = xi * (1.0 - xi) ** 2
    h2 = -xi * xi * (1.0 - xi)
    vb = l0 * (h1 * t1 + h2 * t2)
    vbd = l0 * (h1 * t1d + h2 * t2d)
    vbdd0 = -l0 * (h1 + h2) * bdd0
    _shape_G(xi, l0, ell, c, s, vb, G)
    r = np.empty(2)
    r[0] = (1.0 - xi) * xe[0] + xi * xe[3] - vb * s
    r[1] = (1.0 - xi) * xe[1] + xi * xe[4] + vb * c
    v = np.zeros(2)
    a = np.empty(2)
    a[0] = (vbdd0 - vb * bdot * bdot) * (-s) + (-2.0 * vbd * bdot - vb * bdd0) * c
    a[1] = (vbdd0 - vb * bdot * bdot) * c + (-2.0 * vbd * bdot - vb * bdd0) * s
    for b in range(6):
        v[0] += G[0, b] * ve[b]
        v[1] += G[1, b] * ve[b]
        a[0] += G[0, b] * ae[b]
        a[1] += G[1, b] * ae[b]
    return r, v, a
