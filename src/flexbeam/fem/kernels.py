"""Compiled (Numba) kernels of the co-rotational beam finite elements.

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

Degrees of freedom
------------------
z = [theta, X_1, Y_1, psi_1, ..., X_N, Y_N, psi_N]: node 0 is clamped to the hub at
r_h e1(theta) with psi_0 = theta, and maps onto theta with the weights
T0 = dX_0/dtheta = (-r_h sin theta, r_h cos theta, 1).  The tangent is assembled in
LAPACK general-band storage (kl = ku = 5) for :func:`scipy.linalg.lapack.dgbsv`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..contact.laws import law_force
from ..model.kernels import gap_state

#: half-bandwidth of the assembled matrices
BAND = 5

_G4 = np.polynomial.legendre.leggauss(4)
GAUSS_XI = 0.5 * (_G4[0] + 1.0)  # points on [0, 1]
GAUSS_W = 0.5 * _G4[1]  # weights on [0, 1]


@njit(cache=True)
def _local_rotations(c, s, p1, p2):
    t1 = math.atan2(c * math.sin(p1) - s * math.cos(p1), c * math.cos(p1) + s * math.sin(p1))
    t2 = math.atan2(c * math.sin(p2) - s * math.cos(p2), c * math.cos(p2) + s * math.sin(p2))
    return t1, t2


@njit(cache=True)
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


@njit(cache=True)
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


@njit(cache=True)
def inertia_element(xe, ve, ae, l0, mu, g, gxi, gw, fin, Me, fg, G):
    """Inertia force, mass matrix, gravity force and energies of one element.

    Parameters
    ----------
    xe, ve, ae
        Element coordinates, velocities and accelerations (6 each).
    l0, mu, g
        Initial length [m], line density [kg/m], gravity [m/s^2] (along -Y).
    gxi, gw
        Gauss points and weights on [0, 1].
    fin, Me, fg
        Output (filled): inertia force int mu G^T r'', mass int mu G^T G,
        generalised gravity force -g int mu G^T e_Y.
    G
        Work array (2 x 6).

    Returns
    -------
    T, V_g
        Kinetic and gravitational energy [J].
    """
    dx = xe[3] - xe[0]
    dy = xe[4] - xe[1]
    ell = math.sqrt(dx * dx + dy * dy)
    c = dx / ell
    s = dy / ell
    t1, t2 = _local_rotations(c, s, xe[2], xe[5])
    ddx = ve[3] - ve[0]
    ddy = ve[4] - ve[1]
    bdot = (-s * ddx + c * ddy) / ell
    ldot = c * ddx + s * ddy
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
        for a in range(6):
            fin[a] += wq * (G[0, a] * ax + G[1, a] * ay)
            fg[a] -= wq * g * G[1, a]
            for b in range(6):
                Me[a, b] += wq * (G[0, a] * G[0, b] + G[1, a] * G[1, b])
    return T, Vg


@njit(cache=True)
def point_on_element(xe, ve, l0, xi):
    """Position and velocity of the centre-line point xi in [0, 1] of an element."""
    dx = xe[3] - xe[0]
    dy = xe[4] - xe[1]
    ell = math.sqrt(dx * dx + dy * dy)
    c = dx / ell
    s = dy / ell
    t1, t2 = _local_rotations(c, s, xe[2], xe[5])
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


@njit(cache=True)
def node_states(z, zd, zdd, rh, X, V, A):
    """Fill node arrays (nn x 3) from the DOF vectors; node 0 follows the hub angle."""
    th, w, al = z[0], zd[0], zdd[0]
    ct, st = math.cos(th), math.sin(th)
    X[0, 0] = rh * ct
    X[0, 1] = rh * st
    X[0, 2] = th
    V[0, 0] = -rh * st * w
    V[0, 1] = rh * ct * w
    V[0, 2] = w
    A[0, 0] = rh * (-st * al - ct * w * w)
    A[0, 1] = rh * (ct * al - st * w * w)
    A[0, 2] = al
    nn = X.shape[0]
    for i in range(1, nn):
        for k in range(3):
            X[i, k] = z[3 * i + k - 2]
            V[i, k] = zd[3 * i + k - 2]
            A[i, k] = zdd[3 * i + k - 2]


@njit(cache=True)
def contact_point(xp, vp, c):
    """Surface point P at offset c below the centre line along the section normal.

    r_P = X - c n(psi), n = (-sin psi, cos psi).  Returns (r_P, r_P', dr_P/dpsi, a0)
    with a0 = c psi'^2 (-sin psi, cos psi), the velocity-product part of r_P''.
    """
    sp, cp = math.sin(xp[2]), math.cos(xp[2])
    r = np.array([xp[0] + c * sp, xp[1] - c * cp])
    dpsi = np.array([c * cp, c * sp])
    v = np.array([vp[0] + dpsi[0] * vp[2], vp[1] + dpsi[1] * vp[2]])
    a0 = np.array([-c * sp * vp[2] * vp[2], c * cp * vp[2] * vp[2]])
    return r, v, dpsi, a0


@njit(cache=True)
def gap_at(xp, vp, ap, c, kind, centre, radius, normal, J):
    """Gap delta, rate delta', acceleration delta'' and Jacobian d delta/d(X, Y, psi) of P.

    Sphere (kind 0): delta = |r_P - C| - R, n = (r_P - C)/|r_P - C|,
    delta'' = n . r_P'' + (|r_P'|^2 - (n . r_P')^2)/|r_P - C|.  Half-plane (kind 1):
    delta = n . (r_P - C).
    """
    r, v, dpsi, a0 = contact_point(xp, vp, c)
    acc = np.array([ap[0] + dpsi[0] * ap[2] + a0[0], ap[1] + dpsi[1] * ap[2] + a0[1]])
    dr = np.array([[1.0, 0.0, dpsi[0]], [0.0, 1.0, dpsi[1]]])  # d r_P / d(X, Y, psi)
    delta, vn, dd, nx, ny = gap_state(r, v, acc, dr, kind, centre, radius, normal, J)
    return delta, vn, dd


@njit(cache=True)
def _dof_map(e, a, T0):
    node = e + a // 3
    k = a % 3
    if node == 0:
        return 0, T0[k]
    return 3 * node + k - 2, 1.0


@njit(cache=True)
def assemble(
    z, zd, zdd, t_tau, rh, Jh, l0, mu, EA, EI, g, gxi, gw,
    cM, cC, cK, want_S,
    pnode, cP, okind, ocentre, oradius, onormal, in_contact, lawp,
    R, ab,
):  # fmt: skip
    """Residual R(z, z', z'') of the equations of motion and the iteration matrix.

    R = f_in + f_int - f_g - J^T F (+ J_h theta'' - tau on theta), with
    S = cM M + cC C + cK K in LAPACK band storage ``ab`` (kl = ku = BAND; row
    offset 2 BAND) if ``want_S``.  ``t_tau`` is the joint torque tau.

    Returns
    -------
    F, F_k, delta, delta'
        Contact force, its elastic part, gap and gap rate at P (F = 0 when not
        ``in_contact``).
    """
    nel = l0.size
    nn = nel + 1
    X = np.empty((nn, 3))
    V = np.empty((nn, 3))
    A = np.empty((nn, 3))
    node_states(z, zd, zdd, rh, X, V, A)
    th = z[0]
    T0 = np.array([-rh * math.sin(th), rh * math.cos(th), 1.0])
    d2X0 = np.array([-rh * math.cos(th), -rh * math.sin(th), 0.0])
    R[:] = 0.0
    if want_S:
        ab[:, :] = 0.0
    off = 2 * BAND
    xe = np.empty(6)
    ve = np.empty(6)
    ae = np.empty(6)
    fe = np.empty(6)
    Ke = np.empty((6, 6))
    fin = np.empty(6)
    Me = np.empty((6, 6))
    fg = np.empty(6)
    G = np.empty((2, 6))
    idx = np.empty(6, np.int64)
    wts = np.empty(6)
    R0node = np.zeros(3)
    for e in range(nel):
        for k in range(3):
            xe[k] = X[e, k]
            xe[3 + k] = X[e + 1, k]
            ve[k] = V[e, k]
            ve[3 + k] = V[e + 1, k]
            ae[k] = A[e, k]
            ae[3 + k] = A[e + 1, k]
        corotational_element(xe, l0[e], EA, EI, fe, Ke, want_S)
        inertia_element(xe, ve, ae, l0[e], mu, g, gxi, gw, fin, Me, fg, G)
        for a in range(6):
            i, w = _dof_map(e, a, T0)
            idx[a] = i
            wts[a] = w
            fa = fin[a] + fe[a] - fg[a]
            R[i] += w * fa
            if e == 0 and a < 3:
                R0node[a] += fa
        if want_S:
            for a in range(6):
                for b in range(6):
                    i, j = idx[a], idx[b]
                    ab[off + i - j, j] += wts[a] * wts[b] * (cM * Me[a, b] + cK * Ke[a, b])
    # contact at node pnode
    F = 0.0
    Fk = 0.0
    Jp = np.empty(3)
    delta, vn, _ = gap_at(X[pnode], V[pnode], A[pnode], cP, okind, ocentre, oradius, onormal, Jp)
    if in_contact:
        d = -delta
        dd = -vn
        F, Fk = law_force(lawp, d, dd)
        dFd = 0.0
        dFdd = 0.0
        if F > 0.0 and d > 0.0:
            dFd = lawp[1] * lawp[0] * d ** (lawp[1] - 1.0) * (1.0 + lawp[2] * dd)
            dFdd = Fk * lawp[2] + lawp[3]
        # R -= J^T F; dF/dz = -dFd J - dFdd J (dz'/dz) (the gap Hessian is neglected)
        pidx = np.empty(3, np.int64)
        pw = np.empty(3)
        for k in range(3):
            if pnode == 0:
                pidx[k] = 0
                pw[k] = T0[k]
                R0node[k] -= Jp[k] * F
            else:
                pidx[k] = 3 * pnode + k - 2
                pw[k] = 1.0
            R[pidx[k]] -= pw[k] * Jp[k] * F
        if want_S and F > 0.0:
            coef = cK * dFd + cC * dFdd
            for a in range(3):
                for b in range(3):
                    i, j = pidx[a], pidx[b]
                    ab[off + i - j, j] += pw[a] * pw[b] * coef * Jp[a] * Jp[b]
    # hub
    R[0] += Jh * zdd[0] - t_tau
    if want_S:
        ab[off, 0] += cM * Jh + cK * (R0node[0] * d2X0[0] + R0node[1] * d2X0[1])
    return F, Fk, delta, vn


@njit(cache=True)
def energies(z, zd, rh, Jh, l0, mu, EA, EI, g, gxi, gw):
    """(kinetic, elastic, gravitational) energy [J] of the mesh and hub."""
    nel = l0.size
    nn = nel + 1
    X = np.empty((nn, 3))
    V = np.empty((nn, 3))
    A = np.empty((nn, 3))
    node_states(z, zd, np.zeros(z.size), rh, X, V, A)
    xe = np.empty(6)
    ve = np.empty(6)
    fe = np.empty(6)
    Ke = np.empty((6, 6))
    fin = np.empty(6)
    Me = np.empty((6, 6))
    fg = np.empty(6)
    G = np.empty((2, 6))
    T = 0.5 * Jh * zd[0] * zd[0]
    Ve = 0.0
    Vg = 0.0
    for e in range(nel):
        for k in range(3):
            xe[k] = X[e, k]
            xe[3 + k] = X[e + 1, k]
            ve[k] = V[e, k]
            ve[3 + k] = V[e + 1, k]
        Ve += corotational_element(xe, l0[e], EA, EI, fe, Ke, False)
        Te, Vge = inertia_element(xe, ve, ve, l0[e], mu, g, gxi, gw, fin, Me, fg, G)
        T += Te
        Vg += Vge
    return T, Ve, Vg


@njit(cache=True)
def fix_first_dof(ab):
    """Replace row and column 0 of a band matrix by the identity (theta held)."""
    off = 2 * BAND
    n = ab.shape[1]
    for j in range(min(n, BAND + 1)):
        ab[off - j, j] = 0.0
    for i in range(min(n, BAND + 1)):
        ab[off + i, 0] = 0.0
    ab[off, 0] = 1.0


@njit(cache=True)
def band_solve(ab, x):
    """Solve A x = b in place (b given in x) by band LU *without* pivoting.

    ``ab`` is in LAPACK general-band layout (offset 2 BAND) and is overwritten.  The
    iteration matrices here are symmetric and, for a dynamic step, dominated by the
    positive definite c_M M, so no pivoting is needed; a pivot smaller than 1e-13
    times the largest diagonal entry returns False and the caller falls back to
    LAPACK ``dgbsv`` (partial pivoting).
    """
    n = ab.shape[1]
    off = 2 * BAND
    big = 0.0
    for k in range(n):
        big = max(big, abs(ab[off, k]))
    small = 1e-13 * big
    for k in range(n):
        piv = ab[off, k]
        if not abs(piv) > small:
            return False
        iend = min(n, k + BAND + 1)
        for i in range(k + 1, iend):
            lik = ab[off + i - k, k] / piv
            if lik != 0.0:
                for j in range(k + 1, iend):
                    ab[off + i - j, j] -= lik * ab[off + k - j, j]
                x[i] -= lik * x[k]
    for k in range(n - 1, -1, -1):
        acc = x[k]
        for j in range(k + 1, min(n, k + BAND + 1)):
            acc -= ab[off + k - j, j] * x[j]
        x[k] = acc / ab[off, k]
    return True


@njit(cache=True)
def newton(
    z, zd, zdd, a, cM, cC, ca, scale, tol, max_iter, prescribed,
    t_tau, rh, Jh, l0, mu, EA, EI, g, gxi, gw,
    pnode, cP, okind, ocentre, oradius, onormal, in_contact, lawp,
    R, ab,
):  # fmt: skip
    """Newton iterations of one generalized-alpha step, updating z, z', z'', a in place.

    Returns (iterations, code): code 0 converged, 1 not converged, 2 pivot too
    small (retry with pivoting), 3 non-finite increment.
    """
    for it in range(1, max_iter + 1):
        assemble(
            z, zd, zdd, t_tau, rh, Jh, l0, mu, EA, EI, g, gxi, gw, cM, cC, 1.0, True,
            pnode, cP, okind, ocentre, oradius, onormal, in_contact, lawp, R, ab,
        )  # fmt: skip
        if prescribed:
            fix_first_dof(ab)
            R[0] = 0.0
        for i in range(R.size):
            R[i] = -R[i]
        if not band_solve(ab, R):
            return it, 2
        err = 0.0
        for i in range(R.size):
            d = R[i]
            if not math.isfinite(d):
                return it, 3
            z[i] += d
            zd[i] += cC * d
            zdd[i] += cM * d
            a[i] += ca * d
            err = max(err, abs(d) / scale[i])
        if err < tol:
            return it, 0
    return max_iter, 1


@njit(cache=True)
def hermite_dip(g0, v0, g1, v1, h):
    """Fraction s in (0, 1) at which the cubic Hermite of the gap is lowest if < 0, else -1."""
    best = 0.0
    sbest = -1.0
    for i in range(1, 64):
        s = i / 64.0
        s2 = s * s
        s3 = s2 * s
        p = (
            (2 * s3 - 3 * s2 + 1) * g0
            + (s3 - 2 * s2 + s) * h * v0
            + (-2 * s3 + 3 * s2) * g1
            + (s3 - s2) * h * v1
        )
        if p < best:
            best = p
            sbest = s
    return sbest


@njit(cache=True)
def normal_velocities(z, zd, rh, l0, elems, xis):
    """Velocities along e2(theta) of centre-line points (element, xi) [m/s]."""
    nn = l0.size + 1
    X = np.empty((nn, 3))
    V = np.empty((nn, 3))
    A = np.empty((nn, 3))
    node_states(z, zd, zd, rh, X, V, A)
    out = np.empty(elems.size)
    xe = np.empty(6)
    ve = np.empty(6)
    st, ct = math.sin(z[0]), math.cos(z[0])
    for p in range(elems.size):
        e = elems[p]
        for k in range(3):
            xe[k] = X[e, k]
            xe[3 + k] = X[e + 1, k]
            ve[k] = V[e, k]
            ve[3 + k] = V[e + 1, k]
        _, v = point_on_element(xe, ve, l0[e], xis[p])
        out[p] = -st * v[0] + ct * v[1]
    return out
