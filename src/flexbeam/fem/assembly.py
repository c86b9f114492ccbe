"""Assembly of the FE equations of motion (Numba): node states, residual, iteration matrix, Newton.

The outputs' kernels (energies, velocities of points) are in :mod:`flexbeam.fem.outputs`.

Degrees of freedom
------------------
z = [theta, X_1, Y_1, psi_1, ..., X_N, Y_N, psi_N]: node 0 is clamped to the hub at
r_h e1(theta) with psi_0 = theta, and maps onto theta with the weights
T0 = dX_0/dtheta = (-r_h sin theta, r_h cos theta, 1).  A free beam (``free``, no joint:
``joint.kind = "free"``) has no hub: z = [X_0, Y_0, psi_0, ..., X_N, Y_N, psi_N], every node
free, node i's DOFs at 3 i + k.  The tangent is assembled in
LAPACK general-band storage (kl = ku = 5, :mod:`flexbeam.fem.banded`) for
:func:`scipy.linalg.lapack.dgbsv`.  The elements are those of :mod:`flexbeam.fem.element`;
the contact force of each contact pair comes from :mod:`flexbeam.fem.contact_law` and its gap from
:mod:`flexbeam.fem.gap`.
"""

from __future__ import annotations

import math

import numpy as np

from .banded import BAND, band_solve, fix_first_dof
from .contact_law import friction_law, law_force
from .damping import kelvin_voigt, viscous
from .element import corotational_element, gather, inertia_element
from .gap import anywhere_gap, anywhere_tangent, gap_at, node_tangent
from .jit import fem_jit

#: per pair, what :func:`assemble` writes: force, its elastic part, gap, gap rate, the contact point's material
#: coordinate x, the friction force along the tangent t = (-n_y, n_x) and the slip velocity along t
POUT_COLUMNS = 7


@fem_jit
def node_states(z, zd, zdd, rh, free, X, V, A):
    """Fill node arrays (nn x 3) from the DOF vectors; node 0 follows the hub angle (``free``: every node is
    its own three DOFs)."""
    nn = X.shape[0]
    if free:
        for i in range(nn):
            for k in range(3):
                X[i, k] = z[3 * i + k]
                V[i, k] = zd[3 * i + k]
                A[i, k] = zdd[3 * i + k]
        return
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
    for i in range(1, nn):
        for k in range(3):
            X[i, k] = z[3 * i + k - 2]
            V[i, k] = zd[3 * i + k - 2]
            A[i, k] = zdd[3 * i + k - 2]


@fem_jit
def _dof_map(e, a, T0, free):
    """(DOF index, weight) of local DOF ``a`` of element ``e``: node 0 onto theta with T0 unless ``free``."""
    node = e + a // 3
    k = a % 3
    if free:
        return 3 * node + k, 1.0
    if node == 0:
        return 0, T0[k]
    return 3 * node + k - 2, 1.0


@fem_jit
def _element_map(e, T0, free, idx, wts):
    """Fill ``idx``/``wts`` with element ``e``'s six (DOF index, weight) pairs (:func:`_dof_map`)."""
    for a in range(6):
        idx[a], wts[a] = _dof_map(e, a, T0, free)


@fem_jit
def _add_block(idx, wts, c, Ke, ab):
    """Add c w_a w_b K_e[a, b] of an element's 6 x 6 block to the band matrix ``ab`` at its DOFs ``idx``."""
    off = 2 * BAND
    for a in range(6):
        for b in range(6):
            i, j = idx[a], idx[b]
            ab[off + i - j, j] += wts[a] * wts[b] * c * Ke[a, b]


@fem_jit
def assemble(
    z, zd, zdd, t_tau, rh, Jh, free, l0, mu, EA, EI, field, gxi, gw, damp,
    cM, cC, cK, want_S,
    pnodes, cPs, okinds, ocentres, oradii, onormals, anyw, active, lawps, pout,
    R, ab,
):  # fmt: skip
    """Residual R(z, z', z'') of the equations of motion and the iteration matrix.

    R = f_in + f_int + f_d - f_g - sum_k J_k^T F_k (+ J_h theta'' - tau on theta), with f_d the beam's structural
    damping (``damp`` = [c, eta / mu], :mod:`flexbeam.fem.damping`) and
    S = cM M + cC C + cK K in LAPACK band storage ``ab`` (kl = ku = BAND; row
    offset 2 BAND) if ``want_S``.  ``t_tau`` is the joint torque tau; a ``free`` beam has no hub (no theta, no
    J_h, no torque: every node's DOFs are unknowns).

    The contact pairs k = 0 .. S-1 are given by arrays: the node ``pnodes[k]`` of
    the contact point, its signed offset ``cPs[k]`` below the centre line, the
    obstacle (``okinds[k]``, ``ocentres[k]``, ``oradii[k]``, ``onormals[k]``, see
    :func:`flexbeam.fem.gap.gap_at`), whether the pair is in its contact phase
    (``active[k]`` != 0) and its law's parameters ``lawps[k]``
    (:func:`flexbeam.fem.contact_law.law_force`); F_k = 0 for an inactive pair.
    A pair with ``anyw[k]`` != 0 has its contact point anywhere: the point of the capsule of
    radius ``cPs[k]`` about the deformed centre line nearest its obstacle
    (:func:`flexbeam.fem.gap.anywhere_gap`, element e, local xi); its force acts there,
    distributed by the element's own interpolation, -G^T n F_k (the virtual work of F_k n at
    the point), with the tangent (cK dF/dd + cC dF/dd') J^T J, J = n^T G (the gap Hessian --
    obstacle curvature, the change of G and the motion of the point -- neglected, as for the
    fixed pairs); its material coordinate x* is written to ``pout[k, 4]``.

    Returns
    -------
    F, F_k, delta, delta'
        Contact force, its elastic part, gap and gap rate of pair 0; every pair's
        are written to ``pout[k, :4]`` (S x 5).
    """
    nel = l0.size
    nn = nel + 1
    X = np.empty((nn, 3))
    V = np.empty((nn, 3))
    A = np.empty((nn, 3))
    node_states(z, zd, zdd, rh, free, X, V, A)
    th = 0.0 if free else z[0]
    T0 = np.array([-rh * math.sin(th), rh * math.cos(th), 1.0])
    d2X0 = np.array([-rh * math.cos(th), -rh * math.sin(th), 0.0])
    R[:] = 0.0
    if want_S:
        ab[:, :] = 0.0
    R0node = np.zeros(3)
    _add_elements(X, V, A, T0, free, l0, mu, EA, EI, field, gxi, gw, cM, cK, want_S, R, ab, R0node)
    if damp[0] > 0.0 or damp[1] > 0.0:
        _add_damping(X, V, free, l0, mu, EA, EI, gxi, gw, damp, cC, want_S, R, ab, T0, R0node)
    # contact of each pair at its node or, anywhere, at its nearest point
    Jp = np.empty(3)
    Jg = np.empty(6)
    for q in range(pnodes.size):
        if anyw[q] != 0:
            _anywhere_pair(q, X, V, A, l0, T0, free, cPs, okinds, ocentres, oradii, onormals, active, lawps, pout,
                           cK, cC, want_S, R, ab, R0node, Jg)  # fmt: skip
        else:
            _node_pair(q, pnodes[q], X, V, A, T0, free, cPs, okinds, ocentres, oradii, onormals, active, lawps, pout,
                       cK, cC, want_S, R, ab, R0node, Jp)  # fmt: skip
    if free:
        return pout[0, 0], pout[0, 1], pout[0, 2], pout[0, 3]
    # hub
    R[0] += Jh * zdd[0] - t_tau
    if want_S:
        ab[2 * BAND, 0] += cM * Jh + cK * (R0node[0] * d2X0[0] + R0node[1] * d2X0[1])
    return pout[0, 0], pout[0, 1], pout[0, 2], pout[0, 3]


@fem_jit
def _add_elements(X, V, A, T0, free, l0, mu, EA, EI, field, gxi, gw, cM, cK, want_S, R, ab, R0node):
    """Add each element's f_in + f_int - f_g to R and cM M_e + cK K_e to the band matrix ``ab`` (if ``want_S``),
    node 0's mapped onto theta with the weights T0; node 0's unmapped forces are summed into ``R0node``
    (:func:`assemble`)."""
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
    for e in range(l0.size):
        gather(X, V, A, e, xe, ve, ae)
        corotational_element(xe, l0[e], EA, EI, fe, Ke, want_S)
        inertia_element(xe, ve, ae, l0[e], mu, field, gxi, gw, fin, Me, fg, G)
        _element_map(e, T0, free, idx, wts)
        for a in range(6):
            fa = fin[a] + fe[a] - fg[a]
            R[idx[a]] += wts[a] * fa
            if e == 0 and a < 3:
                R0node[a] += fa
        if want_S:
            for a in range(6):
                for b in range(6):
                    Ke[a, b] = cM * Me[a, b] + cK * Ke[a, b]
            _add_block(idx, wts, 1.0, Ke, ab)


@fem_jit
def _add_damping(X, V, free, l0, mu, EA, EI, gxi, gw, damp, cC, want_S, R, ab, T0, R0node):
    """Add the structural damping (:mod:`flexbeam.fem.damping`) to R and cC C_e to ``ab``: Kelvin-Voigt's through the
    DOF map as the elastic force; the viscous on the nodes but the hub's, its reaction -w . f on theta."""
    off = 2 * BAND
    xe = np.empty(6)
    ve = np.empty(6)
    ae = np.zeros(6)
    fd = np.empty(6)
    Cd = np.empty((6, 6))
    fin = np.empty(6)
    Me = np.empty((6, 6))
    fg = np.empty(6)
    G = np.empty((2, 6))
    idx = np.empty(6, np.int64)
    wts = np.empty(6)
    zero = np.zeros(2)
    thd = 0.0 if free else V[0, 2]
    for e in range(l0.size):
        gather(X, V, V, e, xe, ve, ae)
        _element_map(e, T0, free, idx, wts)
        if damp[0] > 0.0:
            kelvin_voigt(xe, ve, l0[e], EA, EI, damp[0], fd, Cd)
            for a in range(6):
                R[idx[a]] += wts[a] * fd[a]
                if e == 0 and a < 3:
                    R0node[a] += fd[a]
            if want_S:
                _add_block(idx, wts, cC, Cd, ab)
        if damp[1] > 0.0:
            inertia_element(xe, ve, ae, l0[e], mu, zero, gxi, gw, fin, Me, fg, G)
            viscous(xe, ve, thd, free, damp[1], Me, fd)
            for a in range(6):
                if not free and e == 0 and a < 3:
                    continue  # the hub's node moves with the frame: its share and the reaction's cancel
                R[idx[a]] += fd[a]
                if not free:  # the reaction on the frame: -w . f, w = (-Y, X, 1) per node
                    R[0] -= (-xe[a + 1] if a % 3 == 0 else xe[a - 1] if a % 3 == 1 else 1.0) * fd[a]
            if want_S:
                for a in range(6):
                    for b in range(6):
                        if not free and e == 0 and (a < 3 or b < 3):
                            continue
                        ab[off + idx[a] - idx[b], idx[b]] += cC * damp[1] * Me[a, b]


@fem_jit
def _node_pair(
    q, pnode, X, V, A, T0, free, cPs, okinds, ocentres, oradii, onormals, active, lawps, pout, cK, cC, want_S, R, ab,
    R0node, Jp,
):  # fmt: skip
    """Contact pair q at mesh node ``pnode``: R -= J^T F, S += (cK dF/dd + cC dF/dd') J^T J (:func:`assemble`)."""
    off = 2 * BAND
    pidx = np.empty(3, np.int64)
    pw = np.empty(3)
    F = 0.0
    Fk = 0.0
    delta, vn, _ = gap_at(X[pnode], V[pnode], A[pnode], cPs[q], okinds[q], ocentres[q], oradii[q], onormals[q], Jp)
    Ft = 0.0
    vt = 0.0
    if active[q] != 0:
        d = -delta
        dd = -vn
        F, Fk, dFd, dFdd = law_force(lawps[q], d, dd)
        # R -= J^T F; dF/dz = -dFd J - dFdd J (dz'/dz) (the gap Hessian is neglected)
        for k in range(3):
            if free:
                pidx[k] = 3 * pnode + k
                pw[k] = 1.0
            elif pnode == 0:
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
        if lawps[q, 5] > 0.0 and F > 0.0:  # Coulomb friction (regularised) at the point
            Jt = np.empty(3)
            vt = node_tangent(X[pnode], V[pnode], cPs[q], Jp[0], Jp[1], Jt)
            Ft = _friction(q, F, dFd, dFdd, vt, Jp, Jt, pidx, pw, lawps, cK, cC, want_S, R, ab)
            if not free and pnode == 0:
                for k in range(3):
                    R0node[k] -= Jt[k] * Ft
    pout[q, 0] = F
    pout[q, 1] = Fk
    pout[q, 2] = delta
    pout[q, 3] = vn
    pout[q, 5] = Ft
    pout[q, 6] = vt


@fem_jit
def _anywhere_pair(
    q, X, V, A, l0, T0, free, cPs, okinds, ocentres, oradii, onormals, active, lawps, pout, cK, cC, want_S, R, ab,
    R0node, Jg,
):  # fmt: skip
    """Contact pair q anywhere: R -= G^T n F at the nearest point (element e), S += coef J^T J (:func:`assemble`)."""
    delta, vn, _, e, xi = anywhere_gap(X, V, A, l0, cPs[q], okinds[q], ocentres[q], oradii[q], onormals[q], Jg)
    F = 0.0
    Fk = 0.0
    Ft = 0.0
    vt = 0.0
    if active[q] != 0:
        F, Fk, dFd, dFdd = law_force(lawps[q], -delta, -vn)
        idx = np.empty(6, np.int64)
        wts = np.empty(6)
        for a in range(6):
            i, w = _dof_map(e, a, T0, free)
            idx[a] = i
            wts[a] = w
            R[i] -= w * Jg[a] * F
            if e == 0 and a < 3:
                R0node[a] -= Jg[a] * F
        if want_S and F > 0.0:
            coef = cK * dFd + cC * dFdd
            off = 2 * BAND
            for a in range(6):
                for b in range(6):
                    ab[off + idx[a] - idx[b], idx[b]] += wts[a] * wts[b] * coef * Jg[a] * Jg[b]
        if lawps[q, 5] > 0.0 and F > 0.0:  # Coulomb friction (regularised) at the surface point
            Jt = np.empty(6)
            vt = anywhere_tangent(X, V, l0, cPs[q], e, xi, okinds[q], ocentres[q], onormals[q], Jt)
            Ft = _friction(q, F, dFd, dFdd, vt, Jg, Jt, idx, wts, lawps, cK, cC, want_S, R, ab)
            if e == 0:
                for a in range(3):
                    R0node[a] -= Jt[a] * Ft
    x = xi * l0[e]
    for k in range(e):
        x += l0[k]
    pout[q, 0] = F
    pout[q, 1] = Fk
    pout[q, 2] = delta
    pout[q, 3] = vn
    pout[q, 4] = x
    pout[q, 5] = Ft
    pout[q, 6] = vt


@fem_jit
def _friction(q, F, dFd, dFdd, vt, J, Jt, idx, wts, lawps, cK, cC, want_S, R, ab):
    """Pair q's friction force Ft = -F phi(v_t) along the tangent (:func:`~flexbeam.fem.contact_law.friction_law`,
    its parameters lawps[q, 4:8]): R -= Jt^T Ft over the DOFs ``idx`` (weights ``wts``), and the iteration matrix
    += Jt^T (phi dF/dz + F phi' dv_t/dz) = Jt^T (-phi (cK dF/dd + cC dF/dd') J + F phi' cC Jt), not symmetric (the
    normal force's dependence on the state; the tangent's own change neglected, as the gap Hessian is).  Returns Ft."""
    phi, dphi = friction_law(lawps[q, 4], lawps[q, 5], lawps[q, 6], vt, lawps[q, 7])
    Ft = -F * phi
    m = idx.size
    for a in range(m):
        R[idx[a]] -= wts[a] * Jt[a] * Ft
    if want_S:
        coef = cK * dFd + cC * dFdd
        off = 2 * BAND
        for a in range(m):
            for b in range(m):
                dFt = F * dphi * cC * Jt[b] - phi * coef * J[b]
                ab[off + idx[a] - idx[b], idx[b]] += wts[a] * wts[b] * Jt[a] * dFt
    return Ft


@fem_jit
def newton(
    z, zd, zdd, a, cM, cC, ca, scale, tol, max_iter, prescribed,
    t_tau, rh, Jh, free, l0, mu, EA, EI, field, gxi, gw, damp,
    pnodes, cPs, okinds, ocentres, oradii, onormals, anyw, active, lawps, pout,
    R, ab,
):  # fmt: skip
    """Newton iterations of one generalized-alpha step, updating z, z', z'', a in place.

    Returns (iterations, code): code 0 converged, 1 not converged, 2 pivot too
    small (retry with pivoting), 3 non-finite increment.
    """
    for it in range(1, max_iter + 1):
        assemble(
            z, zd, zdd, t_tau, rh, Jh, free, l0, mu, EA, EI, field, gxi, gw, damp, cM, cC, 1.0, True,
            pnodes, cPs, okinds, ocentres, oradii, onormals, anyw, active, lawps, pout, R, ab,
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
