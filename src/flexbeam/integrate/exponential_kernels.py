"""Compiled kernels of the exponential (modal) collocation integrator.

Linearising M(z) z'' = Q + J^T F about the undeformed beam at rest gives
M0 z'' + K0 z = R, with M0 = M(q = 0), K0 = blkdiag(0, K_ff) (free joint) or M0 = M_ff,
K0 = K_ff (theta prescribed), and the remainder

    R(t, z, z', F) = M0 M(z)^-1 (Q + J^T F) + K0 z

which holds the whole rigid-flexible coupling: the mass-matrix variation (a rank-one
update, applied by Sherman-Morrison), centrifugal stiffening, Coriolis and gravity
terms, the drive, the contact force.  In the modal coordinates z = Psi eta of
(K0, M0) (Psi^T M0 Psi = I, Psi^T K0 Psi = Omega^2) each mode obeys

    eta_k'' + w_k^2 eta_k = f_k(t),   f = Psi^T R,

which is propagated *exactly* over a step for a polynomial f (the variation of
constants formula with phi-functions, Hochbruck & Ostermann 2010, Acta Numerica 19,
Sec. 2), so the step is not limited by the highest modal frequency.  f is the
interpolant of its values at the p Gauss-Legendre nodes of the step, which are found
by fixed-point iteration (Gauss collocation); the scalar contact force (CCFM) or
multiplier (CCM) at the nodes is solved by Newton's method inside each iteration,
with its exact linear modal response, so a stiff contact needs no small step.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..contact.laws import law_force
from ..model.kernels import gap_state, generalized_forces, point_kinematics

P_NODES = 4


def gauss_tables(p: int = P_NODES):
    """Nodes c (p) and weights b on (0, 1), Vandermonde inverse, Legendre top values."""
    x, w = np.polynomial.legendre.leggauss(p)
    c = 0.5 * (x + 1.0)
    b = 0.5 * w
    V = np.vander(c, p, increasing=True)
    Vinv = np.linalg.inv(V)  # monomial coefficients in s from nodal values
    top = np.polynomial.legendre.legval(x, [0.0] * (p - 1) + [1.0])
    proj = (2 * p - 1) * b * top  # Legendre top coefficient = proj . f_nodes
    return c, b, Vinv, top, proj


@njit(cache=True)
def _phis(z, p, out):
    """phi_0 .. phi_p of a complex z.

    |z| < 1: phi_p by its Taylor series, then the stable downward recurrence
    phi_{k-1} = z phi_k + 1/(k-1)!; otherwise the upward recurrence
    phi_k = (phi_{k-1} - 1/(k-1)!) / z from phi_0 = e^z.
    """
    if abs(z) < 1.0:
        fact = 1.0
        for k in range(2, p + 1):
            fact *= k
        term = 1.0 / fact + 0j
        acc = term
        for j in range(1, 18):  # |z|^17 / 17! < 3e-15
            term = term * z / (j + p)
            acc += term
        out[p] = acc
        for k in range(p, 0, -1):
            fact /= max(k, 1)
            out[k - 1] = z * out[k] + 1.0 / fact
    else:
        out[0] = np.exp(z)
        fact = 1.0
        for k in range(1, p + 1):
            out[k] = (out[k - 1] - 1.0 / fact) / z
            fact *= k


@njit(cache=True)
def step_weights(omega, h, s, Vinv, C, SW, WS, RE, RV):
    """Propagation weights for the points s (fractions of the step h).

    eta(s) = C eta0 + SW v0 + sum_j RE[:, i, j] f_j,  v(s) = -WS eta0 + C v0 + sum_j RV[:, i, j] f_j
    for f interpolating the nodal values f_j.
    """
    N = omega.size
    m_pts = s.size
    p = Vinv.shape[0]
    ph = np.empty(p + 1, dtype=np.complex128)
    pw = np.empty(p, dtype=np.complex128)
    for k in range(N):
        w = omega[k]
        for i in range(m_pts):
            T = s[i] * h
            if w == 0.0:
                C[k, i] = 1.0
                SW[k, i] = T
                WS[k, i] = 0.0
                for j in range(p):
                    re = 0.0
                    rv = 0.0
                    sp = s[i]
                    for m in range(p):
                        # int_0^T (tau/h)^m dtau = s^(m+1) h/(m+1); twice: s^(m+2) h^2/((m+1)(m+2))
                        rv += sp ** (m + 1) * h / (m + 1) * Vinv[m, j]
                        re += sp ** (m + 2) * h * h / ((m + 1) * (m + 2)) * Vinv[m, j]
                    RE[k, i, j] = re
                    RV[k, i, j] = rv
            else:
                c = math.cos(w * T)
                sn = math.sin(w * T)
                C[k, i] = c
                SW[k, i] = sn / w
                WS[k, i] = w * sn
                _phis(1j * w * T, p, ph)
                fact = 1.0
                for m in range(p):
                    if m > 0:
                        fact *= m
                    pw[m] = fact * s[i] ** (m + 1) * h * ph[m + 1]
                for j in range(p):
                    acc = 0j
                    for m in range(p):
                        acc += pw[m] * Vinv[m, j]
                    RE[k, i, j] = acc.imag / w
                    RV[k, i, j] = acc.real


@njit(cache=True)
def drive_motion(profile, W, Ts, theta0, t):
    """theta, theta', theta'' of a prescribed profile (0: constant rate, 1: Kane spin-up)."""
    if profile == 0:
        return theta0 + W * t, W, 0.0
    if t < Ts:
        a = 2.0 * math.pi / Ts
        th = (W / Ts) * (0.5 * t * t + (math.cos(a * t) - 1.0) / (a * a))
        thd = (W / Ts) * (t - math.sin(a * t) / a)
        thdd = (W / Ts) * (1.0 - math.cos(a * t))
        return theta0 + th, thd, thdd
    return theta0 + W * (t - 0.5 * Ts), W, 0.0


@njit(cache=True)
def node_forcing(t, z, zd, model, prescribed, drive, point, obstacle, want_gap):
    """Remainder R (modal: f = Psi^T R), contact direction g and the gap at one state.

    Returns (rest, gdir, theta, omega, thdd, delta, vn, J) with rest = M0 M^-1 Q + K0 z and
    gdir = M0 M^-1 J^T in physical coordinates (Sherman-Morrison rank-one update).
    """
    (n, Jc, m1, Mc, Mff, mtf, Kff, sf, G, g, row0, inv00) = model
    (profile, W, Ts, theta0, tau) = drive
    (pbase, pphi, pdphi, pH, pc) = point
    (okind, ocentre, oradius, onormal) = obstacle
    N1 = n + 1
    if prescribed:
        theta, omega, thdd = drive_motion(profile, W, Ts, theta0, t)
        q = z
        qd = zd
    else:
        theta = z[0]
        omega = zd[0]
        thdd = 0.0
        q = z[1:]
        qd = zd[1:]
    Q = np.empty(N1)
    generalized_forces(theta, omega, q, qd, 0.0 if prescribed else tau, g, m1, Mc, Kff, sf, G, Q)
    J = np.zeros(N1)
    delta = 0.0
    vn = 0.0
    if want_gap:
        dr = np.empty((2, N1))
        r, v, a0 = point_kinematics(theta, omega, q, qd, pbase, pphi, pdphi, pH, pc, dr)
        delta, vn, gamma, nx, ny = gap_state(r, v, a0, dr, okind, ocentre, oradius, onormal, J)
    Kq = Kff @ q
    if prescribed:
        rest = np.empty(n)
        gdir = np.empty(n)
        for i in range(n):
            rest[i] = Q[i + 1] - mtf[i] * thdd + Kq[i]
            gdir[i] = J[i + 1]
        return rest, gdir, theta, omega, thdd, delta, vn, J
    s = q @ (Mc @ q)
    den = 1.0 + s * inv00
    a = s * (row0 @ Q) / den
    b = s * (row0 @ J) / den
    rest = Q.copy()
    gdir = J.copy()
    rest[0] -= a
    gdir[0] -= b
    for i in range(n):
        rest[i + 1] += Kq[i]
    return rest, gdir, theta, omega, thdd, delta, vn, J


@njit(cache=True)
def _states(eta0, v0, f, C, SW, WS, RE, RV, i, Psi):
    N = eta0.size
    p = f.shape[0]
    eta = C[:, i] * eta0 + SW[:, i] * v0
    v = -WS[:, i] * eta0 + C[:, i] * v0
    for j in range(p):
        for k in range(N):
            eta[k] += RE[k, i, j] * f[j, k]
            v[k] += RV[k, i, j] * f[j, k]
    return eta, v, Psi @ eta, Psi @ v


@njit(cache=True)
def collocation_step(
    t0, h, eta0, v0, f_guess, F_guess, mode, lawp, omega, Psi, PsiT, c, b, Vinv, proj, top,
    model, prescribed, drive, point, obstacle, atol, rtol, C, SW, WS, RE, RV,
):  # fmt: skip
    """One exponential Gauss-collocation step.

    ``mode``: 0 free, 1 CCFM (law parameters ``lawp``), 2 CCM (multiplier with
    delta' = 0 at the nodes).  Returns (ok, eta1, v1, f (p x N), F (p), err,
    diss_rates (p), power (p)); ``ok`` is False when the iteration did not converge.
    """
    p = c.size
    N = eta0.size
    n = model[0]
    s_all = np.empty(p + 1)
    s_all[:p] = c
    s_all[p] = 1.0
    step_weights(omega, h, s_all, Vinv, C, SW, WS, RE, RV)
    f = f_guess.copy()
    F = F_guess.copy()
    rest = np.empty((p, N))
    gvec = np.empty((p, N))
    PJ = np.empty((p, N))
    delta = np.empty(p)
    vn = np.empty(p)
    theta_n = np.empty(p)
    omega_n = np.empty(p)
    thdd_n = np.empty(p)
    ok = False
    want_gap = mode != 0
    for _it in range(40):
        for i in range(p):
            eta, v, z, zd = _states(eta0, v0, f, C, SW, WS, RE, RV, i, Psi)
            r_i, g_i, th, om, thdd, d_i, vn_i, J = node_forcing(
                t0 + c[i] * h, z, zd, model, prescribed, drive, point, obstacle, want_gap)
            rest[i] = PsiT @ r_i
            gvec[i] = PsiT @ g_i
            theta_n[i], omega_n[i], thdd_n[i] = th, om, thdd
            delta[i], vn[i] = d_i, vn_i
            if prescribed:
                PJ[i] = PsiT @ J[1:]
            else:
                PJ[i] = PsiT @ J
        if mode != 0:
            # linear response of delta, delta' at node i to the force at node j (J frozen)
            D = np.zeros((p, p))
            Dv = np.zeros((p, p))
            for i in range(p):
                for j in range(p):
                    acc = 0.0
                    accv = 0.0
                    for k in range(N):
                        acc += PJ[i, k] * RE[k, i, j] * gvec[j, k]
                        accv += PJ[i, k] * RV[k, i, j] * gvec[j, k]
                    D[i, j] = acc
                    Dv[i, j] = accv
            # gap and rate at the nodes without the contact force
            base_d = np.empty(p)
            base_v = np.empty(p)
            for i in range(p):
                cd = 0.0
                cv = 0.0
                for j in range(p):
                    cd += D[i, j] * F[j]
                    cv += Dv[i, j] * F[j]
                base_d[i] = delta[i] - cd
                base_v[i] = vn[i] - cv
            if mode == 2:
                # CCM: delta' + delta / h = 0 at the nodes (velocity-level constraint with a
                # drift correction that removes any gap offset over about one step)
                kappa = 1.0 / h
                F = np.linalg.solve(Dv + kappa * D, -base_v - kappa * base_d)
            else:
                for _newton in range(30):
                    res = np.empty(p)
                    Jac = np.zeros((p, p))
                    for i in range(p):
                        di = base_d[i]
                        vi = base_v[i]
                        for j in range(p):
                            di += D[i, j] * F[j]
                            vi += Dv[i, j] * F[j]
                        dpen = -di
                        dd = -vi
                        fi, fk = law_force(lawp, dpen, dd)
                        res[i] = F[i] - fi
                        Jac[i, i] = 1.0
                        if fi > 0.0:
                            dF_dd = lawp[1] * lawp[0] * dpen ** (lawp[1] - 1.0) * (1.0 + lawp[2] * dd)
                            dF_dv = lawp[0] * dpen ** lawp[1] * lawp[2] + lawp[3]
                            for j in range(p):
                                Jac[i, j] += dF_dd * D[i, j] + dF_dv * Dv[i, j]
                    dF = np.linalg.solve(Jac, -res)
                    F = F + dF
                    scale = 1e-300
                    for i in range(p):
                        scale = max(scale, abs(F[i]))
                    if np.max(np.abs(dF)) <= 1e-13 * scale:
                        break
        f_new = rest.copy()
        if mode != 0:
            for j in range(p):
                f_new[j] += gvec[j] * F[j]
        diff = np.max(np.abs(f_new - f))
        scale = np.max(np.abs(f_new)) + 1e-300
        f = f_new
        if diff <= 1e-11 * scale:
            ok = True
            break
    eta1, v1, z1, zd1 = _states(eta0, v0, f, C, SW, WS, RE, RV, p, Psi)
    # error estimate: defect of the forcing interpolant at the step end (one extra
    # evaluation), f(t0 + h) - sum_j l_j(1) f_j ~ f^(p) h^p / p!, propagated as a forcing
    # error: velocity ~ h d / (p + 1), displacement ~ d min(h^2 / ((p+1)(p+2)), 2 / w^2).
    # The collocation end state itself is superconvergent, so this order-p estimate is
    # conservative.
    r_e, g_e, th_e, om_e, thdd_e, d_e, vn_e, J_e = node_forcing(
        t0 + h, z1, zd1, model, prescribed, drive, point, obstacle, want_gap)
    f_end = PsiT @ r_e
    if mode == 1:
        fe, fke = law_force(lawp, -d_e, -vn_e)
        f_end = f_end + (PsiT @ g_e) * fe
    elif mode == 2:
        lam_end = 0.0
        for j in range(p):
            lj = 1.0
            for m in range(p):
                if m != j:
                    lj *= (1.0 - c[m]) / (c[j] - c[m])
            lam_end += lj * F[j]
        f_end = f_end + (PsiT @ g_e) * lam_end
    defect = f_end.copy()
    for j in range(p):
        lj = 1.0
        for m in range(p):
            if m != j:
                lj *= (1.0 - c[m]) / (c[j] - c[m])
        defect -= lj * f[j]
    deta = np.empty(N)
    dv = np.empty(N)
    for k in range(N):
        dk = abs(defect[k])
        dv[k] = h * dk / (p + 1)
        lim = h * h / ((p + 1) * (p + 2))
        if omega[k] > 0.0:
            lim = min(lim, 2.0 / (omega[k] * omega[k]))
        deta[k] = dk * lim
    z0 = Psi @ eta0
    zd0 = Psi @ v0
    absPsi = np.abs(Psi)
    dz = absPsi @ deta
    dzd = absPsi @ dv
    err = 0.0
    for k in range(N):
        e1 = abs(dz[k]) / (atol + rtol * max(abs(z0[k]), abs(z1[k])))
        e2 = abs(dzd[k]) / (atol + rtol * max(abs(zd0[k]), abs(zd1[k])))
        err = max(err, e1, e2)
    # bookkeeping rates at the nodes: contact dissipation and drive power
    diss = np.zeros(p)
    power = np.zeros(p)
    tau = drive[4]
    for i in range(p):
        if mode == 1:
            fi, fk = law_force(lawp, -delta[i], -vn[i])
            diss[i] = (fi - fk) * (-vn[i])
        if prescribed:
            # joint torque = M[0,:] z'' - Q[0] - J[0] F, z'' = [theta'', Psi (f - w^2 eta)]
            eta, v, z, zd = _states(eta0, v0, f, C, SW, WS, RE, RV, i, Psi)
            acc_m = f[i] - omega * omega * eta
            qdd = Psi @ acc_m
            th, om = theta_n[i], omega_n[i]
            Qf = np.empty(n + 1)
            (nn, Jc, m1, Mc, Mff, mtf, Kff, sf, G, g, row0, inv00) = model
            generalized_forces(th, om, z, zd, 0.0, g, m1, Mc, Kff, sf, G, Qf)
            Jf = np.zeros(n + 1)
            if mode != 0:
                dr = np.empty((2, n + 1))
                r, vv, a0 = point_kinematics(th, om, z, zd, point[0], point[1], point[2], point[3], point[4], dr)
                gap_state(r, vv, a0, dr, obstacle[0], obstacle[1], obstacle[2], obstacle[3], Jf)
            torque = (Jc + z @ (Mc @ z)) * thdd_n[i] + mtf @ qdd - Qf[0]
            if mode != 0:
                torque -= Jf[0] * F[i]
            power[i] = torque * om
        else:
            power[i] = tau * omega_n[i]
    return ok, eta1, v1, f, F, err, diss, power


@njit(cache=True)
def dense_states(t0, h, eta0, v0, f, s, Psi, omega, Vinv):
    """z and z' at fractions ``s`` of a step (exact modal propagation of the step's f)."""
    p = Vinv.shape[0]
    N = eta0.size
    m = s.size
    C = np.empty((N, m))
    SW = np.empty((N, m))
    WS = np.empty((N, m))
    RE = np.empty((N, m, p))
    RV = np.empty((N, m, p))
    step_weights(omega, h, s, Vinv, C, SW, WS, RE, RV)
    Z = np.empty((m, N))
    ZD = np.empty((m, N))
    for i in range(m):
        eta, v, z, zd = _states(eta0, v0, f, C, SW, WS, RE, RV, i, Psi)
        Z[i] = z
        ZD[i] = zd
    return Z, ZD


@njit(cache=True)
def integrate_rates(rates, s, Vinv, h):
    """int_0^{s h} of the interpolant of nodal rates (for the bookkeeping integrals)."""
    p = Vinv.shape[0]
    out = np.empty(s.size)
    coef = Vinv @ rates
    for i in range(s.size):
        acc = 0.0
        for m in range(p):
            acc += coef[m] * s[i] ** (m + 1) / (m + 1)
        out[i] = acc * h
    return out


@njit(cache=True)
def gaps_at(times, Z, ZD, prescribed, drive, point, obstacle, n):
    """Gap delta and rate delta' at dense states (rows of Z, ZD)."""
    m = times.size
    d = np.empty(m)
    dv = np.empty(m)
    N1 = n + 1
    dr = np.empty((2, N1))
    J = np.empty(N1)
    (profile, W, Ts, theta0, tau) = drive
    for i in range(m):
        if prescribed:
            th, om, thdd = drive_motion(profile, W, Ts, theta0, times[i])
            q = Z[i]
            qd = ZD[i]
        else:
            th = Z[i, 0]
            om = ZD[i, 0]
            q = Z[i, 1:]
            qd = ZD[i, 1:]
        r, v, a0 = point_kinematics(th, om, np.ascontiguousarray(q), np.ascontiguousarray(qd),
                                    point[0], point[1], point[2], point[3], point[4], dr)
        delta, vn, gamma, nx, ny = gap_state(r, v, a0, dr, obstacle[0], obstacle[1], obstacle[2], obstacle[3], J)
        d[i] = delta
        dv[i] = vn
    return d, dv
