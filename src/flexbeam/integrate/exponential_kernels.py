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

Each step propagates the mass-matrix change frozen at its start exactly
(:func:`_step_basis`): its diagonal as shifted frequencies, or, when the coupling is strong,
the whole rank-one change in the step's own modal basis from the secular equation.
:func:`advance` runs a phase's whole step loop (steps, step control, event search and
location, output sampling) in compiled code.

Performance: a call between compiled functions passes every array of its tuple arguments
(the model ``sysd``, the modal model ``mm``: ~25 arrays) field by field with reference
counting, ~0.2 us per call, measured -- more than the work of a node at n = 12.  The
helpers called per node or per sample with those tuples (:func:`_node_modal`, :func:`_rigid`,
:func:`_gap_at`, :func:`_modal_at`) are therefore inlined (``inline="always"``): 42 -> 17.5 us
per collocation step at n = 12, for ~20 s more cold compilation.  Inlining the rest as well
cost another ~30 s of compilation for no measurable gain.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..contact.laws import law_force
from ..model.kernels import dot as _dot
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


MOMENT_SERIES = 1.0  # theta below this: power series and downward recurrence (else upward)


@njit(cache=True, inline="always")
def _osc_moments(theta, cos_t, sin_t, p, Cm, Sm):
    """Moments of the harmonic kernel over the unit interval, real arithmetic.

    Cm[m] = int_0^1 cos(theta (1 - u)) u^m du and Sm[m] = theta^-1 int_0^1 sin(theta (1 - u))
    u^m du for m = 0 .. p - 1 (theta >= 0; Sm -> 1 / ((m + 1) (m + 2)) as theta -> 0).  They
    are J_m = m! phi_(m+1)(i theta) = Cm + i theta Sm, the phi-functions of exponential
    integrators (Hochbruck & Ostermann 2010, Acta Numerica 19, Sec. 2.1) on the imaginary
    axis.  theta < MOMENT_SERIES: the power series of J_(p-1) and the stable downward
    recurrence J_(m-1) = (i theta J_m + 1) / m; otherwise J_0 = (e^(i theta) - 1) / (i theta)
    and the upward recurrence J_m = (m J_(m-1) - 1) / (i theta).  ``cos_t``, ``sin_t``: cos and sin
    of theta, which the callers have already.
    """
    if theta < MOMENT_SERIES:
        m = p - 1
        t2 = theta * theta
        fact = 1.0  # (m + 1)!
        for k in range(2, m + 2):
            fact *= k
        mf = fact / (m + 1)  # m!
        # Cm = m! sum_j (-1)^j theta^2j / (2j + m + 1)!,  Sm = m! sum_j (-1)^j theta^2j / (2j + m + 2)!
        c_term = mf / fact
        s_term = c_term / (m + 2)
        c_acc = c_term
        s_acc = s_term
        for j in range(1, 12):  # theta^22 / 24! < 2e-24
            c_term = -c_term * t2 / ((2 * j + m) * (2 * j + m + 1))
            s_term = -s_term * t2 / ((2 * j + m + 1) * (2 * j + m + 2))
            c_acc += c_term
            s_acc += s_term
        Cm[m] = c_acc
        Sm[m] = s_acc
        for k in range(m, 0, -1):
            Cm[k - 1] = (1.0 - t2 * Sm[k]) / k
            Sm[k - 1] = Cm[k] / k
    else:
        t2 = theta * theta
        Cm[0] = sin_t / theta
        Sm[0] = (1.0 - cos_t) / t2
        for k in range(1, p):
            Cm[k] = k * Sm[k - 1]
            Sm[k] = (1.0 - k * Cm[k - 1]) / t2


@njit(cache=True, inline="always")
def _free_response(w, T, Cm, Sm):
    """cos(w T), sin(w T) / w, w sin(w T) of one mode over the time T, and its moments into Cm, Sm.

    The free-oscillation part and (:func:`_osc_moments`) the monomial-forcing part of the
    variation-of-constants solution, shared by :func:`step_weights` and :func:`_hop_weights`.
    """
    th = w * T
    c = math.cos(th)
    sn = math.sin(th)
    _osc_moments(th, c, sn, Cm.size, Cm, Sm)
    return c, (sn / w if w != 0.0 else T), w * sn


@njit(cache=True)
def step_weights(omega, h, s, Vinv, C, SW, WS, RE, RV):
    """Propagation weights for the points s (fractions of the step h).

    eta(s) = C eta0 + SW v0 + sum_j RE[:, i, j] f_j,  v(s) = -WS eta0 + C v0 + sum_j RV[:, i, j] f_j
    for f interpolating the nodal values f_j: the variation-of-constants integral of
    eta'' + w^2 eta = f(tau), with f = sum_m a_m (tau / h)^m, over [0, T = s h] is
    T^2 s^m Sm(w T) (position) and T s^m Cm(w T) (velocity) per monomial (:func:`_osc_moments`).
    """
    N = omega.size
    m_pts = s.size
    p = Vinv.shape[0]
    Cm = np.empty(p)
    Sm = np.empty(p)
    for k in range(N):
        w = omega[k]
        for i in range(m_pts):
            T = s[i] * h
            C[k, i], SW[k, i], WS[k, i] = _free_response(w, T, Cm, Sm)
            spm = 1.0
            for m in range(p):
                Cm[m] *= T * spm
                Sm[m] *= T * T * spm
                spm *= s[i]
            for j in range(p):
                re = 0.0
                rv = 0.0
                for m in range(p):
                    re += Sm[m] * Vinv[m, j]
                    rv += Cm[m] * Vinv[m, j]
                RE[k, i, j] = re
                RV[k, i, j] = rv


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


# ------------------------------------------------- the model in modal coordinates
#
# The hot loop works on the modal state (eta, v) alone: with Psi_q the rows of Psi that
# map eta to q (all of them for a prescribed theta, else rows 1..n) every quadratic form
# and projection it needs is precomputed once per phase (:func:`_modal_model`), so a
# node costs three N x N products (M_c, G and H in modal form) and no allocation.


@njit(cache=True)
def _mv(AT, x, out):
    """out = A x from AT = A^T (column sweeps, contiguous and vectorisable, no temporaries)."""
    m = out.size
    for i in range(m):
        out[i] = 0.0
    for j in range(x.size):
        xj = x[j]
        for i in range(m):
            out[i] += xj * AT[j, i]


@njit(cache=True)
def _congruence_T(A, Psi, off):
    """Psi_q^T A^T Psi_q (N x N), Psi_q = Psi[off:off + A.shape[0]]."""
    n = A.shape[0]
    N = Psi.shape[1]
    T1 = np.zeros((n, N))  # A^T Psi_q
    for i in range(n):
        for j in range(n):
            a = A[j, i]
            for j2 in range(N):
                T1[i, j2] += a * Psi[j + off, j2]
    out = np.zeros((N, N))
    for k in range(N):
        for i in range(n):
            pk = Psi[i + off, k]
            for j2 in range(N):
                out[k, j2] += pk * T1[i, j2]
    return out


@njit(cache=True)
def _project(vec, Psi, off):
    """Psi_q^T vec."""
    N = Psi.shape[1]
    out = np.zeros(N)
    for i in range(vec.size):
        for k in range(N):
            out[k] += Psi[i + off, k] * vec[i]
    return out


@njit(cache=True)
def _t_times(A, x):
    """A^T x."""
    n = A.shape[0]
    out = np.zeros(A.shape[1])
    for i in range(n):
        for j in range(A.shape[1]):
            out[j] += A[i, j] * x[i]
    return out


@njit(cache=True)
def _modal_model(lin, sysd):
    """Per-phase modal data: (psi0, Mcm^T, Gm^T, Hm^T, sf, m_tf, Phi, Phi', the row-0 vectors
    mr, gr, kr, hr, scalars) with Xm = Psi_q^T X Psi_q and psi0 the theta row of Psi (zero
    for a prescribed theta)."""
    omega, Psi, PsiT, toM, row0, inv00, sref = lin
    model, prescribed, drive, point, obstacle = sysd
    (n, Jc, m1, Mc, Mff, mtf, Kff, sf, G, g) = model
    phi, dphi, H = point[1], point[2], point[3]
    N = omega.size
    off = 0 if prescribed else 1
    psi0 = np.zeros(N)
    mr = np.zeros(N)
    gr = np.zeros(N)
    kr = np.zeros(N)
    hr = np.zeros(N)
    sc = np.zeros(4)
    if not prescribed:
        for k in range(N):
            psi0[k] = Psi[0, k]
        r0f = row0[1:].copy()
        mr = _project(_t_times(Mc, r0f), Psi, off)
        gr = _project(_t_times(G, r0f), Psi, off)
        kr = _project(_t_times(Kff, r0f), Psi, off)
        hr = _project(_t_times(H, r0f), Psi, off)
        sc[0] = row0[0]
        sc[1] = _dot(r0f, sf)
        sc[2] = _dot(r0f, phi)
        sc[3] = _dot(r0f, dphi)
    return (psi0, _congruence_T(Mc, Psi, off), _congruence_T(G, Psi, off), _congruence_T(H, Psi, off),
            _project(sf, Psi, off), _project(mtf, Psi, off), _project(phi, Psi, off), _project(dphi, Psi, off),
            mr, gr, kr, hr, sc)


@njit(cache=True)
def _gap_kin(th, om, e, v, He, point, obstacle, mm, want_pj, prescribed, PJ):
    """Gap delta and rate at the modal state (e, v) with He = Hm e; with ``want_pj`` the modal
    contact Jacobian PJ = Psi^T J (J[1:] for a prescribed theta).  Returns (delta, delta', J_0,
    row0 . J) -- the point kinematics of :func:`~flexbeam.model.kernels.point_kinematics` and
    :func:`~flexbeam.model.kernels.gap_state` in modal form."""
    psi0, McmT, GmT, HmT, sfm, mtfm, phim, dphim, mr, gr, kr, hr, sc = mm
    base, c_off = point[0], point[4]
    N = e.size
    qHq = 0.0
    ang = 0.0
    angd = 0.0
    phq = 0.0
    hqd = 0.0
    phqd = 0.0
    for k in range(N):
        qHq += e[k] * He[k]
        ang += dphim[k] * e[k]
        angd += dphim[k] * v[k]
        phq += phim[k] * e[k]
        hqd += He[k] * v[k]
        phqd += phim[k] * v[k]
    sa, ca = math.sin(ang), math.cos(ang)
    rx = base - 0.5 * qHq + c_off * sa
    ry = phq - c_off * ca
    rhod_x = -hqd + c_off * ca * angd
    rhod_y = phqd + c_off * sa * angd
    ct, st = math.cos(th), math.sin(th)
    r0 = ct * rx - st * ry
    r1 = st * rx + ct * ry
    vlx = rhod_x - om * ry
    vly = rhod_y + om * rx
    w0 = ct * vlx - st * vly
    w1 = st * vlx + ct * vly
    kind, centre, radius, normal, sup = obstacle
    cx, cy = centre[0], centre[1]
    rs = 0.0
    if sup[0] > 0.0:  # compliant support: the obstacle moved by s along u, P's velocity relative to it
        rs = 1.0 / math.sqrt(sup[0])  # the last modal coordinate is sqrt(m_s) s
        s_ob = e[N - 1] * rs
        sd_ob = v[N - 1] * rs
        cx += s_ob * sup[3]
        cy += s_ob * sup[4]
        w0 -= sd_ob * sup[3]
        w1 -= sd_ob * sup[4]
    if kind == 0:
        dx = r0 - cx
        dy = r1 - cy
        dist = math.sqrt(dx * dx + dy * dy)
        nx, ny = dx / dist, dy / dist
        delta = dist - radius
    else:
        nx, ny = normal[0], normal[1]
        delta = nx * (r0 - cx) + ny * (r1 - cy)
    vn = nx * w0 + ny * w1
    J0 = 0.0
    r0J = 0.0
    if want_pj:
        J0 = nx * (ct * (-ry) - st * rx) + ny * (st * (-ry) + ct * rx)
        a = nx * ct + ny * st
        bb = -nx * st + ny * ct
        for k in range(N):
            PJ[k] = a * (-He[k] + c_off * ca * dphim[k]) + bb * (phim[k] + c_off * sa * dphim[k])
        if not prescribed:
            for k in range(N):
                PJ[k] += psi0[k] * J0
            r0J = sc[0] * J0 + a * (-_dot(hr, e) + c_off * ca * sc[3]) + bb * (sc[2] + c_off * sa * sc[3])
        if rs > 0.0:  # d delta / d(sqrt(m_s) s) = -(n . u) / sqrt(m_s)
            PJ[N - 1] = -(nx * sup[3] + ny * sup[4]) * rs
    return delta, vn, J0, r0J


@njit(cache=True, inline="always")
def _rigid(t, e, v, sysd, psi0):
    """theta, theta', theta'' at the modal state (the drive's for a prescribed theta)."""
    if sysd[1]:
        profile, W, Ts, theta0, tau = sysd[2]
        return drive_motion(profile, W, Ts, theta0, t)
    return _dot(psi0, e), _dot(psi0, v), 0.0


@njit(cache=True, inline="always")
def _gap_at(t, e, v, sysd, mm, He, want_pj, PJ):
    """Gap and rate (and the modal Jacobian) at the modal state (e, v) at time t."""
    th, om, thdd = _rigid(t, e, v, sysd, mm[0])
    _mv(mm[3], e, He)
    return _gap_kin(th, om, e, v, He, sysd[3], sysd[4], mm, want_pj, sysd[1], PJ)


@njit(cache=True, inline="always")
def _node_modal(t, e, v, sysd, mm, inv00, sref, want_gap, Ae, Be, He, rest, PJ):
    """Modal remainder rest = Psi^T R at (e, v) and, with ``want_gap``, the gap and PJ = Psi^T J.

    R = M_ref M^-1 Q + K0 z as in the module docstring, with the elastic force K q (which
    K0 z cancels) left out of both.  Returns (theta, theta', theta'', delta, delta', gcorr):
    the modal contact direction Psi^T M_ref M^-1 J^T is PJ - gcorr psi0.
    """
    model, prescribed, drive, point, obstacle = sysd
    (n, Jc, m1, Mc, Mff, mtf, Kff, sf, G, g) = model
    tau = drive[4]
    psi0, McmT, GmT, HmT, sfm, mtfm, phim, dphim, mr, gr, kr, hr, sc = mm
    N = e.size
    th, om, thdd = _rigid(t, e, v, sysd, psi0)
    _mv(McmT, e, Ae)
    qMq = _dot(e, Ae)
    om2 = om * om
    cth, sth = math.cos(th), math.sin(th)
    qGq = 0.0
    sfq = 0.0
    if g != 0.0:
        _mv(GmT, e, Be)
        qGq = _dot(e, Be)
        sfq = _dot(sfm, e)
        for k in range(N):
            rest[k] = om2 * Ae[k] - g * (cth * sfm[k] - sth * Be[k])
    else:
        for k in range(N):
            rest[k] = om2 * Ae[k]
    ds = 0.0
    den = 1.0
    if prescribed:
        for k in range(N):
            rest[k] -= thdd * mtfm[k]
    else:
        Q0 = tau - 2.0 * om * _dot(v, Ae) - g * (cth * (m1 - 0.5 * qGq) - sth * sfq)
        ds = qMq - sref
        den = 1.0 + ds * inv00
        row0Q = sc[0] * Q0 + om2 * _dot(mr, e) - g * (cth * sc[1] - sth * _dot(gr, e)) - _dot(kr, e)
        rest0 = Q0 - ds * row0Q / den
        for k in range(N):
            rest[k] += psi0[k] * rest0
    sup = obstacle[4]
    if sup[0] > 0.0:  # the support's dashpot, -c_s s' / m_s in the coordinate sqrt(m_s) s
        rest[N - 1] -= sup[2] / sup[0] * v[N - 1]
    delta = 0.0
    vn = 0.0
    gcorr = 0.0
    if want_gap:
        _mv(HmT, e, He)
        delta, vn, J0, r0J = _gap_kin(th, om, e, v, He, point, obstacle, mm, True, prescribed, PJ)
        if not prescribed:
            gcorr = ds * r0J / den
    return th, om, thdd, delta, vn, gcorr


@njit(cache=True, inline="always")
def _modal_at(eta0, v0, f, C, SW, WS, RE, RV, i, e, v):
    """Modal state at point i of the step weights (into e, v)."""
    N = eta0.size
    p = f.shape[0]
    for k in range(N):
        e[k] = C[k, i] * eta0[k] + SW[k, i] * v0[k]
        v[k] = -WS[k, i] * eta0[k] + C[k, i] * v0[k]
    for j in range(p):
        for k in range(N):
            e[k] += RE[k, i, j] * f[j, k]
            v[k] += RV[k, i, j] * f[j, k]


@njit(cache=True)
def _hop_weights(omega, T, Cm, Sm, Wt):
    """Weights of one hop of length T for monomial forcing u^m (u = tau / T in [0, 1]).

    Rows of ``Wt`` (N x (3 + 2p)): cos(w T), sin(w T)/w, w sin(w T), then the position and
    velocity responses T^2 Sm(w T), T Cm(w T) (:func:`_osc_moments`; ``Cm``, ``Sm`` work
    arrays of size p), as :func:`step_weights` for the single point s = 1.
    """
    N = omega.size
    p = (Wt.shape[1] - 3) // 2
    for k in range(N):
        Wt[k, 0], Wt[k, 1], Wt[k, 2] = _free_response(omega[k], T, Cm, Sm)
        for m in range(p):
            Wt[k, 3 + m] = T * T * Sm[m]
            Wt[k, 3 + p + m] = T * Cm[m]


@njit(cache=True)
def _hop(A, sa, L, Wt, e, v, b):
    """Advance the modal state (e, v) from the fraction sa of the step to sa + L (in place).

    ``A`` (p x N): monomial coefficients in s of the step's forcing; ``Wt``: the hop
    weights (:func:`_hop_weights`) of the length L h.  The forcing on the hop, a polynomial
    in u = (s - sa) / L, is obtained by a Taylor shift: the propagation stays exact.
    """
    p = A.shape[0]
    N = A.shape[1]
    for k in range(N):
        for m in range(p):
            b[m] = A[m, k]
        if sa != 0.0:
            for i in range(p - 1):
                for j in range(p - 2, i - 1, -1):
                    b[j] += sa * b[j + 1]
        sc = 1.0
        fe = 0.0
        fv = 0.0
        for m in range(p):
            bm = b[m] * sc
            fe += Wt[k, 3 + m] * bm
            fv += Wt[k, 3 + p + m] * bm
            sc *= L
        e0 = e[k]
        v0 = v[k]
        e[k] = Wt[k, 0] * e0 + Wt[k, 1] * v0 + fe
        v[k] = -Wt[k, 2] * e0 + Wt[k, 0] * v0 + fv


@njit(cache=True)
def _monomial(Vinv, f, A):
    """A = Vinv f: monomial coefficients (in s) of the interpolant through the nodal rows f."""
    p = Vinv.shape[0]
    N = f.shape[1]
    for m in range(p):
        for k in range(N):
            acc = 0.0
            for j in range(p):
                acc += Vinv[m, j] * f[j, k]
            A[m, k] = acc


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
def _lagrange_end(c, j):
    """l_j(1) of the Lagrange basis on the nodes c."""
    lj = 1.0
    for m in range(c.size):
        if m != j:
            lj *= (1.0 - c[m]) / (c[j] - c[m])
    return lj



ENERGY_NORM = True
# fixed-point iteration: converged at |df| <= ITERATION_TOL rtol max|f|.  The iteration contracts by
# 1e-3 (n = 12) to ~0.1 (n = 32) per sweep, so the forcing left is <~ 1e-3 rtol of its size: its
# effect on the state is far below the step's error tolerance (1e-5 cost 1-2 more sweeps a step).
ITERATION_TOL = 1e-3
STAGNATION_TOL = 1e-2  # ... or at |df| <= STAGNATION_TOL rtol max|f| once it stops contracting


@njit(cache=True)
def _error_norm(deta, dv, eta0, v0, eta1, v1, omega, Psi, atol, rtol):
    """Scaled error of a step from the modal error bounds ``deta``, ``dv``.

    Energy norm (ENERGY_NORM): the modal error vector (w_k deta_k, dv_k) -- whose square
    is twice the energy of the error -- against atol + rtol sqrt(2 E_lin), E_lin the
    linearised energy of the state, plus the position of every zero-frequency (rigid)
    mode against atol + rtol |eta_k|.  The spurious top mode of a hub without inertia
    moves theta' strongly but holds almost no energy and barely moves the contact point,
    so the energy norm does not let it dictate the step.  Otherwise: componentwise in
    the physical coordinates z, z'.
    """
    N = omega.size
    err = 0.0
    if ENERGY_NORM:
        e2 = 0.0
        s0 = 0.0
        s1 = 0.0
        for k in range(N):
            w = omega[k]
            e2 += (w * deta[k]) ** 2 + dv[k] ** 2
            s0 += (w * eta0[k]) ** 2 + v0[k] ** 2
            s1 += (w * eta1[k]) ** 2 + v1[k] ** 2
            if w == 0.0:
                err = max(err, deta[k] / (atol + rtol * max(abs(eta0[k]), abs(eta1[k]))))
        return max(err, math.sqrt(e2) / (atol + rtol * math.sqrt(max(s0, s1))))
    z0 = Psi @ eta0
    zd0 = Psi @ v0
    z1 = Psi @ eta1
    zd1 = Psi @ v1
    for i in range(N):
        dz = 0.0
        dzd = 0.0
        for k in range(N):
            a = abs(Psi[i, k])
            dz += a * deta[k]
            dzd += a * dv[k]
        e1 = dz / (atol + rtol * max(abs(z0[i]), abs(z1[i])))
        e2 = dzd / (atol + rtol * max(abs(zd0[i]), abs(zd1[i])))
        err = max(err, e1, e2)
    return err


@njit(cache=True)
def _solve_into(A, rhs, M, x):
    """x = A^-1 rhs for a small dense A (Gaussian elimination, partial pivoting, work array M)."""
    n = rhs.size
    for i in range(n):
        x[i] = rhs[i]
        for j in range(n):
            M[i, j] = A[i, j]
    for k in range(n):
        piv = k
        for i in range(k + 1, n):
            if abs(M[i, k]) > abs(M[piv, k]):
                piv = i
        if piv != k:
            for j in range(n):
                M[k, j], M[piv, j] = M[piv, j], M[k, j]
            x[k], x[piv] = x[piv], x[k]
        for i in range(k + 1, n):
            m = M[i, k] / M[k, k]
            for j in range(k, n):
                M[i, j] -= m * M[k, j]
            x[i] -= m * x[k]
    for k in range(n - 1, -1, -1):
        acc = x[k]
        for j in range(k + 1, n):
            acc -= M[k, j] * x[j]
        x[k] = acc / M[k, k]


@njit(cache=True)
def _colloc_buffers(N, p):
    """Work arrays of :func:`collocation_step` (allocated once per phase)."""
    return (np.empty((p, N)), np.empty((p, N)), np.empty(p), np.empty(p), np.empty(p), np.empty(p), np.empty(p),
            np.empty((p, N)), np.empty((p, p)), np.empty((p, p)), np.empty(p), np.empty(p), np.empty(p),
            np.empty((p, p)), np.empty(p), np.empty((p, p)), np.empty(p + 1), np.empty(N), np.empty(N),
            np.empty(N), np.empty(N), np.empty(N), np.empty(N), np.empty(N), np.empty(N), np.empty(N),
            np.empty(N), np.empty(N), np.empty(N), np.empty(N))


@njit(cache=True)
def _step_out(N, p):
    """Outputs of :func:`collocation_step`: (eta1, v1, f, F, diss, power)."""
    return (np.empty(N), np.empty(N), np.empty((p, N)), np.empty(p), np.empty(p), np.empty(p))


@njit(cache=True)
def collocation_step(t0, h, eta0, v0, f_guess, F_guess, mode, lawp, lin, basis, tab, sysd, atol, rtol, work, fresh,
                     mm, cb, out):
    """One exponential Gauss-collocation step.

    ``mode``: 0 free, 1 CCFM (law parameters ``lawp``), 2 CCM (multiplier with
    delta' + lawp[0] delta = 0 at the nodes).  The state ``eta0``, ``v0``, the forcing and
    the outputs are in the step's coordinates zeta of :func:`_step_basis` (``basis``, whose
    frequencies w~ are ``lin[0]``): the model is evaluated at eta = X zeta, and the
    collocated forcing is X^-1 (rest - c0 u u^T W^2 eta), so that the coupling frozen at the
    step start is propagated exactly.  ``fresh``: recompute the propagation weights
    in ``work`` (else they are those of the same h).  ``mm``: :func:`_modal_model`; ``cb``:
    :func:`_colloc_buffers`.  Fills ``out`` = (eta1, v1, f (p x N), F (p), diss_rates (p),
    power (p)) and returns (ok, err, iterations); ``ok`` is False when the iteration did not
    converge.  ``f_guess``, ``F_guess`` must not be arrays of ``out``.
    """
    omega, Psi, PsiT, toM, row0, inv00, sref = lin
    c, b, Vinv = tab
    C, SW, WS, RE, RV = work
    eta1, v1, f, F, diss, power = out
    (gvec, PJ, delta, vn, omega_n, thdd_n, theta_n, f_new, D, Dv, base_d, base_v, res, Jac, dF, Msol, s_all,
     ei, vi, Ae, Be, He, rest, defect, deta, dvv, PJe, ez, vz, tz) = cb
    X, XT, XiT, cu, w2u, shift = basis[1], basis[2], basis[3], basis[4], basis[5], basis[6]
    full = basis[7][0] != 0.0
    psi0 = mm[0]
    model = sysd[0]
    prescribed = sysd[1]
    p = c.size
    N = eta0.size
    n = model[0]
    if fresh:
        for i in range(p):
            s_all[i] = c[i]
        s_all[p] = 1.0
        step_weights(omega, h, s_all, Vinv, C, SW, WS, RE, RV)
    for j in range(p):
        F[j] = F_guess[j]
        for k in range(N):
            f[j, k] = f_guess[j, k]
    ok = False
    want_gap = mode != 0
    g0 = 0.0
    if mode == 2:
        _map(full, XT, eta0, ei)
        _map(full, XT, v0, vi)
        d0, vn0, _, _ = _gap_at(t0, ei, vi, sysd, mm, He, False, PJe)
        g0 = vn0 + lawp[0] * d0
    iters = 0
    diff_prev = math.inf
    for _it in range(40):
        iters += 1
        for i in range(p):
            _modal_at(eta0, v0, f, C, SW, WS, RE, RV, i, ez, vz)
            _map(full, XT, ez, ei)
            _map(full, XT, vz, vi)
            th, om, thdd, d_i, vn_i, gcorr = _node_modal(
                t0 + c[i] * h, ei, vi, sysd, mm, inv00, sref, want_gap, Ae, Be, He, rest, PJ[i])
            _frozen_out(full, cu, w2u, shift, ei, rest)
            _map(full, XiT, rest, f_new[i])
            theta_n[i], omega_n[i], thdd_n[i] = th, om, thdd
            if want_gap:
                for k in range(N):
                    tz[k] = PJ[i, k] - gcorr * psi0[k]
                _map(full, XiT, tz, gvec[i])
                if full:  # the gap's modal Jacobian in zeta: X^T PJ
                    for k in range(N):
                        tz[k] = PJ[i, k]
                    _map(full, X, tz, PJ[i])
                delta[i], vn[i] = d_i, vn_i
        if mode != 0:
            # linear response of delta, delta' at node i to the force at node j (J frozen)
            for i in range(p):
                for j in range(p):
                    acc = 0.0
                    accv = 0.0
                    for k in range(N):
                        acc += PJ[i, k] * RE[k, i, j] * gvec[j, k]
                        accv += PJ[i, k] * RV[k, i, j] * gvec[j, k]
                    D[i, j] = acc
                    Dv[i, j] = accv
            for i in range(p):
                cd = 0.0
                cv = 0.0
                for j in range(p):
                    cd += D[i, j] * F[j]
                    cv += Dv[i, j] * F[j]
                base_d[i] = delta[i] - cd
                base_v[i] = vn[i] - cv
            if mode == 2:
                # g = delta' + kappa delta decays as g0 exp(-kappa t) from its value at the
                # step start (kappa = the Baumgarte frequency lawp[0] = alpha = beta): the
                # reference path's delta'' + 2 alpha delta' + beta^2 delta = 0, imposed at the
                # nodes.  (g = 0 at the nodes would demand a force ~ g0 / h from the residual
                # the previous step leaves at its end, unbounded as the step shrinks.)
                kappa = lawp[0]
                for i in range(p):
                    res[i] = -base_v[i] - kappa * base_d[i] + g0 * math.exp(-kappa * c[i] * h)
                    for j in range(p):
                        Jac[i, j] = Dv[i, j] + kappa * D[i, j]
                _solve_into(Jac, res, Msol, F)
            else:
                for _newton in range(30):
                    for i in range(p):
                        for j in range(p):
                            Jac[i, j] = 0.0
                    for i in range(p):
                        di = base_d[i]
                        vi_ = base_v[i]
                        for j in range(p):
                            di += D[i, j] * F[j]
                            vi_ += Dv[i, j] * F[j]
                        dpen = -di
                        dd = -vi_
                        fi, fk = law_force(lawp, dpen, dd)
                        res[i] = fi - F[i]  # -(F - fi)
                        Jac[i, i] = 1.0
                        if fi > 0.0:
                            dF_dd = lawp[1] * lawp[0] * dpen ** (lawp[1] - 1.0) * (1.0 + lawp[2] * dd)
                            dF_dv = lawp[0] * dpen ** lawp[1] * lawp[2] + lawp[3]
                            for j in range(p):
                                Jac[i, j] += dF_dd * D[i, j] + dF_dv * Dv[i, j]
                    _solve_into(Jac, res, Msol, dF)
                    scale = 1e-300
                    big = 0.0
                    for i in range(p):
                        F[i] += dF[i]
                        scale = max(scale, abs(F[i]))
                        big = max(big, abs(dF[i]))
                    if big <= 1e-13 * scale:
                        break
        # the convergence scale: the forcing's terms (a resting contact's force cancels the
        # load, so the sum alone would be pure round-off)
        scale = 1e-300
        for j in range(p):
            for k in range(N):
                scale = max(scale, abs(f_new[j, k]))
        if mode != 0:
            for j in range(p):
                for k in range(N):
                    fc = gvec[j, k] * F[j]
                    scale = max(scale, abs(fc))
                    f_new[j, k] += fc
        diff = 0.0
        for j in range(p):
            for k in range(N):
                diff = max(diff, abs(f_new[j, k] - f[j, k]))
                scale = max(scale, abs(f_new[j, k]))
                f[j, k] = f_new[j, k]
        if not (diff < math.inf):
            break
        if diff <= ITERATION_TOL * rtol * scale:
            ok = True
            break
        # stagnation at round-off: a CCM multiplier solved from velocities over a short step
        # (lambda ~ velocity defect / h) carries relative noise ~1e-9 that no iteration removes
        if diff <= STAGNATION_TOL * rtol * scale and diff >= 0.5 * diff_prev:
            ok = True
            break
        diff_prev = diff
    _modal_at(eta0, v0, f, C, SW, WS, RE, RV, p, eta1, v1)
    _map(full, XT, eta1, ei)
    _map(full, XT, v1, vi)
    # error estimate: defect of the forcing interpolant at the step end (one extra
    # evaluation), f(t0 + h) - sum_j l_j(1) f_j ~ f^(p) h^p / p!, propagated as a forcing
    # error: velocity ~ h d / (p + 1), displacement ~ d min(h^2 / ((p+1)(p+2)), 2 / w^2).
    # The collocation end state itself is superconvergent, so this order-p estimate is
    # conservative.
    th_e, om_e, thdd_e, d_e, vn_e, gcorr_e = _node_modal(
        t0 + h, ei, vi, sysd, mm, inv00, sref, want_gap, Ae, Be, He, rest, PJe)
    _frozen_out(full, cu, w2u, shift, ei, rest)
    if mode != 0:
        if mode == 1:
            fe, fke = law_force(lawp, -d_e, -vn_e)
        else:
            fe = 0.0
            for j in range(p):
                fe += _lagrange_end(c, j) * F[j]
        for k in range(N):
            rest[k] += (PJe[k] - gcorr_e * psi0[k]) * fe
    _map(full, XiT, rest, defect)
    for j in range(p):
        lj = _lagrange_end(c, j)
        for k in range(N):
            defect[k] -= lj * f[j, k]
    lim0 = h * h / ((p + 1) * (p + 2))
    for k in range(N):
        dk = abs(defect[k])
        dvv[k] = h * dk / (p + 1)
        lim = lim0
        if omega[k] > 0.0:
            lim = min(lim, 2.0 / (omega[k] * omega[k]))
        deta[k] = dk * lim
    err = _error_norm(deta, dvv, eta0, v0, eta1, v1, omega, Psi, atol, rtol)
    if not ok:
        err = math.inf
    # bookkeeping rates at the nodes: contact dissipation and drive power
    tau = sysd[2][4]
    for i in range(p):
        diss[i] = 0.0
        if mode == 1:
            fi, fk = law_force(lawp, -delta[i], -vn[i])
            diss[i] = (fi - fk) * (-vn[i])
        sup = sysd[4][4]
        if sup[0] > 0.0:  # the support's dashpot, c_s s'^2
            _modal_at(eta0, v0, f, C, SW, WS, RE, RV, i, ez, vz)
            _map(full, XT, vz, vi)
            diss[i] += sup[2] / sup[0] * vi[N - 1] * vi[N - 1]
        if prescribed:
            # joint torque = M[0,:] z'' - Q[0] - J[0] F, z'' = [theta'', Psi (f - w^2 eta)]
            # (a prescribed theta has the identity basis: zeta = eta)
            eta, v, z, zd = _states(eta0, v0, f, C, SW, WS, RE, RV, i, Psi)
            th, om = theta_n[i], omega_n[i]
            Qf = np.empty(n + 1)
            (nn, Jc, m1, Mc, Mff, mtf, Kff, sf, G, g) = model
            generalized_forces(th, om, z, zd, 0.0, g, m1, Mc, Kff, sf, G, Qf)
            # the modal-acceleration part th' m_tf q'' (fast oscillation) is booked exactly by
            # parts, [th' m_tf q'] - int th'' m_tf q' dt: the rate here omits it
            torque = (Jc + z @ (Mc @ z)) * thdd_n[i] - Qf[0]
            if mode != 0:
                point, obstacle = sysd[3], sysd[4]
                dr = np.empty((2, n + 1))
                Jb = np.empty(n + 1)
                r, vv, a0 = point_kinematics(th, om, z, zd, point[0], point[1], point[2], point[3], point[4], dr)
                gap_state(r, vv, a0, dr, obstacle[0], obstacle[1], obstacle[2], obstacle[3], Jb)
                torque -= Jb[0] * F[i]
            power[i] = torque * om - thdd_n[i] * (mtf @ zd)
        else:
            power[i] = tau * omega_n[i]
    return ok, err, iters


@njit(cache=True)
def dense_states(h, eta0, v0, f, s, Psi, omega, Vinv):
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



# ------------------------------------------------------------------ events

NO_EVENT = 2.0  # find_event: the step is free of the event
UNDECIDED = -1.0  # find_event: too long a step to decide, shorten it


@njit(cache=True)
def _event_buffers(N, p):
    """Work arrays of :func:`find_event` (allocated once per phase)."""
    ns = 4 * SAMPLES + 1
    return (np.empty(ns), np.empty(ns), np.empty(ns), np.empty(ns), np.empty((p, N)), np.empty((N, 3 + 2 * p)),
            np.empty((N, 3 + 2 * p)), np.empty(N), np.empty(N), np.empty(N), np.empty(N), np.empty(p),
            np.empty((2, p)), np.empty(N), np.empty(N))


@njit(cache=True)
def _gap1(x, ctx):
    """Gap at the fraction x of the step (exact modal propagation from its start)."""
    return _gap_rate1(x, ctx)[0]


@njit(cache=True)
def _gap_rate1(x, ctx):
    """Gap and its rate at the fraction x of the step."""
    t0, h, eta0, v0, omega, sysd, mm, eb, full, XT = ctx
    s, d, dv, rate, A, Wu, W1, ec, vc, He, PJ, bb, ph, ee, ve = eb
    _hop_weights(omega, x * h, ph[0], ph[1], W1)
    for k in range(eta0.size):
        ec[k] = eta0[k]
        vc[k] = v0[k]
    _hop(A, 0.0, x, W1, ec, vc, bb)
    _map(full, XT, ec, ee)
    _map(full, XT, vc, ve)
    g = _gap_at(t0 + x * h, ee, ve, sysd, mm, He, False, PJ)
    return g[0], g[1]


@njit(cache=True)
def _leaves_surface(a, b, ga, gb, sign, ctx):
    """Event fraction in [a, b] when the gap starts on its surface at rest and ends beyond it.

    As the reference path's ``_leaves_surface``: a phase that starts on the event surface
    with (almost) zero rate -- P left on the obstacle by a CCM release at lambda = 0 just
    after the e = 0 jump -- can cross inside an excursion far below round-off.  The first
    point of a geometric grid from a where the gap is beyond the surface by more than
    1e-6 |g(b)| and still moving that way is reported (Brent-refined if the gap is seen on
    the near side just before), so the method decides there and the contact is not lost;
    ``ga``, ``gb`` are the gap at a and b, known to the caller.
    NO_EVENT if none: the gap is beyond the surface only by the constraint's drift and P is
    on its way back (a CCM release from a gap of round-off size).
    """
    noise = 1e-6 * abs(gb)
    prev_x = a
    prev_g = ga
    for k in range(48, -1, -1):
        x = a + (b - a) * 2.0 ** (-k)
        gx, rx = _gap_rate1(x, ctx)
        if sign * gx > noise and sign * rx > 0.0:
            if -sign * prev_g > 0.0:
                return _brent(prev_x, x, prev_g, gx, ctx)
            return x
        prev_x, prev_g = x, gx
    return NO_EVENT
@njit(cache=True)
def _brent(a, b, fa, fb, ctx):
    """Root of the gap on [a, b] (fa fb <= 0), Brent's method (xtol 1e-15, rtol 1e-14)."""
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    c, fc = a, fa
    d = e = b - a
    for _ in range(200):
        if fb * fc > 0.0:
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 2.0 * 2.2e-16 * abs(b) + 0.5 * (1e-15 + 1e-14 * abs(b))
        m = 0.5 * (c - b)
        if abs(m) <= tol or fb == 0.0:
            return b
        if abs(e) >= tol and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:
                p = 2.0 * m * s
                q = 1.0 - s
            else:
                q = fa / fc
                r = fb / fc
                p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0.0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * m * q - abs(tol * q), abs(e * q)):
                e = d
                d = p / q
            else:
                d = m
                e = m
        else:
            d = m
            e = m
        a, fa = b, fb
        if abs(d) > tol:
            b += d
        else:
            b += tol if m > 0 else -tol
        fb = _gap1(b, ctx)
    return b


@njit(cache=True)
def _golden_min(ctx, lo, hi, sign):
    """Argmin of sign * gap on [lo, hi] (golden-section search to 1e-14)."""
    gr = 0.5 * (math.sqrt(5.0) - 1.0)
    a, b = lo, hi
    x1 = b - gr * (b - a)
    x2 = a + gr * (b - a)
    f1 = sign * _gap1(x1, ctx)
    f2 = sign * _gap1(x2, ctx)
    while b - a > 1e-14:
        if f1 < f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - gr * (b - a)
            f1 = sign * _gap1(x1, ctx)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + gr * (b - a)
            f2 = sign * _gap1(x2, ctx)
    return 0.5 * (a + b)


@njit(cache=True)
def _scan(s, d, rate, direction, ctx):
    """Earliest root (fraction s) of sampled (d, rate) in ``direction``, refined on the gap.

    Checks, per interval: a sign change; an excursion that starts on (or just behind)
    zero, leaves, and comes back; and a dip predicted by the cubic Hermite interpolant
    through (d, rate) at both ends, searched on 16 sub-intervals.  NO_EVENT if none.
    """
    sign = -1.0 if direction < 0 else 1.0
    for i in range(s.size - 1):
        a, b = d[i], d[i + 1]
        ra, rb = rate[i], rate[i + 1]
        hh = s[i + 1] - s[i]
        cross = (a > 0.0 and b <= 0.0) if sign < 0 else (a < 0.0 and b >= 0.0)
        if cross:
            if b == 0.0:
                return s[i + 1]
            return _brent(s[i], s[i + 1], a, b, ctx)
        if -sign * a <= 0.0 and -sign * b < 0.0:  # starts on (or just behind) zero, ends beyond it
            if -sign * ra > 0.0:  # leaving at first: a hump
                x = _golden_min(ctx, s[i], s[i + 1], sign)
                gx = _gap1(x, ctx)
                if -sign * gx > 0.0:
                    return _brent(x, s[i + 1], gx, b, ctx)
                if i == 0:  # the phase starts on the surface (an excursion below round-off)
                    x = _leaves_surface(s[i], s[i + 1], a, b, sign, ctx)
                    if x <= 1.0:
                        return x
            continue
        same = (a > 0.0 and b > 0.0) if sign < 0 else (a < 0.0 and b < 0.0)
        if not same:
            continue
        dip = False
        for k in range(17):
            x = k / 16.0
            poly = ((2 * x**3 - 3 * x**2 + 1) * a + (x**3 - 2 * x**2 + x) * hh * ra
                    + (-2 * x**3 + 3 * x**2) * b + (x**3 - x**2) * hh * rb)
            if (sign < 0 and poly < 0.0) or (sign > 0 and poly > 0.0):
                dip = True
                break
        if not dip:
            continue
        prev_x = s[i]
        prev_g = a
        for k in range(1, 17):
            x = s[i] + k / 16.0 * hh
            gx = b if k == 16 else _gap1(x, ctx)
            if (sign < 0 and prev_g > 0.0 >= gx) or (sign > 0 and prev_g < 0.0 <= gx):
                return _brent(prev_x, x, prev_g, gx, ctx)
            prev_x, prev_g = x, gx
    return NO_EVENT


@njit(cache=True)
def _fast_bound(h, eta0, v0, f, m, omega, PJ):
    """Bound on the gap contribution of modes too fast for m samples per step.

    B = sum over modes with w h / m > pi/4 of |(Psi^T J)_k| (free amplitude_k + 2 max|f_k| / w_k^2),
    ``PJ`` = Psi^T J at the step start.
    """
    N = omega.size
    B = 0.0
    for k in range(N):
        w = omega[k]
        if w * h / m > 0.25 * math.pi:
            amp = math.sqrt(eta0[k] ** 2 + (v0[k] / w) ** 2)
            fmax = 0.0
            for j in range(f.shape[0]):
                fmax = max(fmax, abs(f[j, k]))
            B += abs(PJ[k]) * (amp + 2.0 * fmax / (w * w))
    return B


@njit(cache=True)
def _far(t0, h, f, eta0, v0, d0, PJ, J0, omega, sysd):
    """Is the obstacle provably out of reach within the step (no sampling needed)?

    Each mode's velocity stays below its free amplitude sqrt(v_k^2 + w_k^2 eta_k^2) plus
    h LEBESGUE max_j |f_jk| (the interpolated forcing's bound), so the gap's rate stays
    below R = sum_k |(Psi^T J)_k| (that bound) (+ |J_theta| max|theta'| for a prescribed
    theta(t), whose profiles have monotone rates); the step is declared far if the gap at its
    start (``d0``; ``PJ``, ``J0`` its Jacobian) exceeds 2 R h (a factor 2 for the variation of
    J over the step).
    """
    if d0 <= 0.0:
        return False
    R = 0.0
    for k in range(omega.size):
        fmax = 0.0
        for j in range(f.shape[0]):
            fmax = max(fmax, abs(f[j, k]))
        R += abs(PJ[k]) * (math.sqrt(v0[k] ** 2 + (omega[k] * eta0[k]) ** 2) + h * LEBESGUE * fmax)
    if sysd[1]:  # prescribed theta: its (monotone) rate moves P too
        profile, W, Ts, theta0, tau = sysd[2]
        rate = max(abs(drive_motion(profile, W, Ts, theta0, t0)[1]),
                   abs(drive_motion(profile, W, Ts, theta0, t0 + h)[1]))
        R += abs(J0) * rate
    return d0 > 2.0 * R * h


SAMPLES = 16  # gap samples per step in the event search (refined x4 once if modes are unresolved)
LEBESGUE = 3.0  # > max over [0, 1] of sum_j |l_j(s)| for the Gauss nodes (2.0 for p = 4)


@njit(cache=True)
def find_event(t0, h, eta0, v0, f, direction, lin, basis, tab, sysd, mm, eb):
    """First crossing of the gap in ``direction`` inside the step, as a fraction s.

    NO_EVENT when the step is provably free of it, a fraction in (0, 1] at a located
    crossing, UNDECIDED when the step is too long to decide cheaply (modes that could
    reach the obstacle are not resolved by 4 SAMPLES samples): the caller shortens the step.
    A step is declared free of an impact only if min(samples) - 2B > 0 with B the
    bound of :func:`_fast_bound` on the unresolved modes, or, all modes resolved, if
    no sign change, excursion or Hermite-predicted dip is found.  The samples are exact
    modal propagations hop by hop (:func:`_hop`) in the step's coordinates zeta
    (``basis``, :func:`_step_basis`), the gap evaluated in modal form at eta = X zeta.
    """
    omega = lin[0]
    X, XT = basis[1], basis[2]
    full = basis[7][0] != 0.0
    s, d, dv, rate, A, Wu, W1, ec, vc, He, PJ, bb, ph, ee, ve = eb
    N = omega.size
    _map(full, XT, eta0, ee)
    _map(full, XT, v0, ve)
    d0, vn0, J0, r0J = _gap_at(t0, ee, ve, sysd, mm, He, True, PJ)
    if full:  # X^T Psi^T J: the contact direction in zeta
        for k in range(N):
            ee[k] = PJ[k]
        _map(full, X, ee, PJ)
    if direction < 0 and _far(t0, h, f, eta0, v0, d0, PJ, J0, omega, sysd):
        return NO_EVENT
    _monomial(tab[2], f, A)
    ctx = (t0, h, eta0, v0, omega, sysd, mm, eb, full, XT)
    m = SAMPLES
    while True:
        _hop_weights(omega, h / m, ph[0], ph[1], Wu)
        for k in range(N):
            ec[k] = eta0[k]
            vc[k] = v0[k]
        s[0] = 0.0
        d[0] = d0
        dv[0] = vn0
        for i in range(1, m + 1):
            _hop(A, (i - 1) / m, 1.0 / m, Wu, ec, vc, bb)
            s[i] = i / m
            _map(full, XT, ec, ee)
            _map(full, XT, vc, ve)
            gi = _gap_at(t0 + s[i] * h, ee, ve, sysd, mm, He, False, PJ)
            d[i] = gi[0]
            dv[i] = gi[1]
        B = _fast_bound(h, eta0, v0, f, m, omega, PJ)
        leaving = d[0] > 0.0 or dv[0] > 0.0
        if direction < 0 and leaving and np.min(d[1 : m + 1]) - 2.0 * B > 0.0:
            return NO_EVENT
        if B == 0.0:
            for i in range(m + 1):
                rate[i] = dv[i] * h
            return _scan(s[: m + 1], d[: m + 1], rate[: m + 1], direction, ctx)
        if m >= 4 * SAMPLES:
            return UNDECIDED
        m *= 4


@njit(cache=True)
def _lagrange_at(c, lam, x):
    out = 0.0
    for j in range(c.size):
        lj = 1.0
        for m in range(c.size):
            if m != j:
                lj *= (x - c[m]) / (c[j] - c[m])
        out += lj * lam[j]
    return out


@njit(cache=True)
def multiplier_release(c, lam):
    """Fraction of the step where the collocated multiplier lambda(s) turns tensile, or NO_EVENT."""
    prev = _lagrange_at(c, lam, 0.0)
    for i in range(1, 33):
        x = i / 32.0
        val = _lagrange_at(c, lam, x)
        if prev >= 0.0 > val:
            if prev == 0.0:
                return (i - 1) / 32.0
            lo, hi = (i - 1) / 32.0, x
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if _lagrange_at(c, lam, mid) >= 0.0:
                    lo = mid
                else:
                    hi = mid
            return hi
        prev = val
    return NO_EVENT


# ---------------------------------------------------------------- the loop

@njit(cache=True)
def _grow(a, need):
    """``a`` with room for ``need`` rows along its first axis (doubling), contents kept."""
    if need <= a.shape[0]:
        return a
    out = np.empty((max(need, 2 * a.shape[0]),) + a.shape[1:])
    out[: a.shape[0]] = a
    return out


@njit(cache=True)
def _extrapolate_into(c, f, ratio, out):
    """Values at the next step's nodes (1 + ratio c_i) of the interpolant through f (rows)."""
    p = c.size
    N = f.shape[1]
    for i in range(p):
        for k in range(N):
            out[i, k] = 0.0
        x = 1.0 + ratio * c[i]
        for j in range(p):
            lj = 1.0
            for m in range(p):
                if m != j:
                    lj *= (x - c[m]) / (c[j] - c[m])
            for k in range(N):
                out[i, k] += lj * f[j, k]


@njit(cache=True)
def _extrapolate1_into(c, F, ratio, out):
    for i in range(c.size):
        out[i] = _lagrange_at(c, F, 1.0 + ratio * c[i])


@njit(cache=True)
def _boundary_work(t, qd, sysd):
    """theta'(t) m_tf q' of a prescribed theta(t): the integrated part of the joint work."""
    profile, W, Ts, theta0, tau = sysd[2]
    return drive_motion(profile, W, Ts, theta0, t)[1] * (sysd[0][5] @ qd)


FREEZE = True  # propagate the mass-matrix variation frozen at each step's start exactly
# |ds (M_ref^-1)_00| (the relative change of the top mode's mass) from which a step freezes the
# whole rank-one coupling in its own basis, below which only its diagonal.  Measured on the seed
# case (CCFM, 0.1 s; diagonal only / full basis always / this threshold, ms; n = 8-16 medians of
# three interleaved runs): n = 8 (|.| median 0.002) 67 / 82 / 67, n = 12 (0.008) 139 / 144 / 141,
# n = 16 (0.017) 215 / 210 / 195, n = 24 (0.12) 794 / 486 / 448, n = 32 (0.19) 1660 / 668 / 719.
FULL_FREEZE_MIN = 0.05


@njit(cache=True)
def _basis_buffers(N):
    """(w~, X, X^T, X^-T, c0 u, W^2 u, shift, full) of :func:`_step_basis` (allocated once per
    phase, as the identity basis)."""
    return (np.empty(N), np.eye(N), np.eye(N), np.eye(N), np.zeros(N), np.zeros(N), np.zeros(N), np.zeros(1))


@njit(cache=True)
def _map(full, AT, x, out):
    """out = A x from AT = A^T (:func:`_mv`) in the step's full basis, a copy for the identity basis.

    With the basis (X, X^T, X^-T) of :func:`_step_basis`: ``AT`` = X^T maps zeta to eta,
    X^-T maps eta to zeta, X gives X^T y."""
    if full:
        _mv(AT, x, out)
    else:
        for k in range(x.size):
            out[k] = x[k]


@njit(cache=True)
def _map_rows(AT, F, tmp):
    """Each row of F replaced by A row (in the full basis; ``tmp`` a work vector)."""
    for j in range(F.shape[0]):
        _mv(AT, F[j], tmp)
        for k in range(tmp.size):
            F[j, k] = tmp[k]


@njit(cache=True)
def _frozen_out(full, cu, w2u, shift, e, rest):
    """rest -= the coupling frozen in the step's propagation: c0 u u^T W^2 e (full) or its diagonal."""
    if full:
        fr = _dot(w2u, e)
        for k in range(e.size):
            rest[k] -= cu[k] * fr
    else:
        for k in range(e.size):
            rest[k] -= shift[k] * e[k]


@njit(cache=True)
def _identity_basis(omega, basis):
    """The identity basis with the frequencies ``omega`` (the matrices are reset only when
    the previous step's basis was a full one)."""
    wt, X, XT, XiT, cu, w2u, sh, full = basis
    N = omega.size
    if full[0] != 0.0:
        for j in range(N):
            for k in range(N):
                X[j, k] = 0.0
                XT[j, k] = 0.0
                XiT[j, k] = 0.0
            X[j, j] = 1.0
            XT[j, j] = 1.0
            XiT[j, j] = 1.0
        full[0] = 0.0
    for k in range(N):
        wt[k] = omega[k]
        sh[k] = 0.0


SECULAR_MAXIT = 60  # safeguarded Newton iterations per root of the secular equation (2-4 taken)


@njit(cache=True)
def _secular_sums(i, dA, v2, tau):
    """R = sum_(k != i) v_k^2 / (d_k - lambda) and dR / dtau at lambda = dA[i] + tau."""
    R = 0.0
    Rp = 0.0
    do = dA[i]
    for k in range(dA.size):
        if k != i:
            inv = 1.0 / ((dA[k] - do) - tau)
            r = v2[k] * inv
            R += r
            Rp += r * inv
    return R, Rp


@njit(cache=True)
def _secular_root(i, dA, v2, c, vsum):
    """tau = lambda - dA[i] of the eigenvalue of D - c v v^T that continues from the pole dA[i].

    ``dA`` (ascending) and ``v2`` = v^2 over the m active modes (v != 0), ``vsum`` = sum v2.  For
    c < 0 the root lies in (dA[i], dA[i + 1]) (above the top pole: within -c vsum), for c > 0
    in (dA[i - 1], dA[i]).  Newton's method on G(tau) = tau (1 - c R(tau)) + c v_i^2, the secular
    equation f = 1 - c sum_k v_k^2 / (d_k - lambda) times tau, which has no pole at the origin,
    so tau comes out to full relative accuracy however weak the coupling (Golub 1973; the
    shifted form as in LAPACK's dlaed4), safeguarded by bisection on the sign of f (monotone
    between the poles).  Started from the one-pole estimate, 1-3 iterations.
    """
    m = dA.size
    do = dA[i]
    vo2 = v2[i]
    if c < 0.0:
        lo = 0.0
        hi = dA[i + 1] - do if i < m - 1 else -c * vsum
    else:
        hi = 0.0
        lo = dA[i - 1] - do if i > 0 else -c * vsum
    R, Rp = _secular_sums(i, dA, v2, 0.0)
    den = 1.0 - c * R
    tau = -c * vo2 / den if den != 0.0 else 0.5 * (lo + hi)  # the one-pole estimate
    if not (lo < tau < hi):
        tau = 0.5 * (lo + hi)
    for _ in range(SECULAR_MAXIT):
        R, Rp = _secular_sums(i, dA, v2, tau)
        G = tau * (1.0 - c * R) + c * vo2
        Gp = 1.0 - c * R - tau * c * Rp
        step = -G / Gp if Gp != 0.0 else math.inf
        if abs(step) <= 4.0 * 2.2e-16 * abs(tau):  # converged (the start is often this close already)
            return tau + step
        if (G / tau < 0.0) == (c < 0.0):  # f = G / tau is monotone: keep the root bracketed
            lo = tau
        else:
            hi = tau
        t_new = tau + step
        if not (lo < t_new < hi):
            t_new = 0.5 * (lo + hi)
        if t_new == tau:
            return tau
        tau = t_new
    return tau


@njit(cache=True)
def _step_basis(eta, lin, sysd, mm, Ae, basis):
    """The step's coordinates zeta (eta = X zeta) and frequencies w~ with the mass matrix frozen at eta.

    M(q) = M_ref + ds e0 e0^T makes the modal equations (I + ds u u^T) eta'' + W^2 eta = ...
    (u = Psi^T e0, the theta row of Psi), i.e. eta'' + (I - c u u^T) W^2 eta = ... with
    c = ds / (1 + ds |u|^2), |u|^2 = (M_ref^-1)_00.  With ds frozen at the step start (c0) the
    pencil (W^2, M_s = I + ds u u^T) is diagonalised, X^T W^2 X = diag(w~^2), X^T M_s X = I, so
    X^-1 = X^T M_s, and the step propagates zeta'' + w~^2 zeta = X^-1 (rest - c0 u u^T W^2 eta)
    exactly: what the forcing keeps of the coupling is (c - c0) u u^T W^2 eta, the change of
    ds over the step.  (For a hub without inertia the coupling is strong -- the spurious top
    mode's mass is the small Schur complement of M_00, its frequency moves by per cent with
    q^T M_c q -- and, left in the forcing, oscillates with every mode.)

    The pencil is a rank-one modification: its nonzero eigenvalues are those of
    D - c0 v v^T with D = W^2, v = W u (Golub 1973, SIAM Rev. 15; Bunch, Nielsen & Sorensen
    1978, Numer. Math. 31), the roots of the secular equation 1 = c0 sum_k v_k^2 / (w_k^2 -
    lambda), one between each pair of poles (:func:`_secular_root`), and the eigenvectors
    x_j = (W^2 - lambda_j)^-1 u, M_s-normalised; the rigid mode stays e0 / sqrt(1 + ds u_0^2)
    and modes with u_k = 0 stay e_k.  O(N^2) per step.

    Weak coupling (|ds (M_ref^-1)_00| < FULL_FREEZE_MIN): the basis stays the identity and only
    the diagonal of the frozen coupling, the frequency change c0 u_k^2 w_k^2 of each mode, is
    propagated (``shift``); the off-diagonal part stays in the forcing.  This spares the
    transformations (five N x N products per node), which cost more than the steps they save
    when the coupling is weak (measured: see FULL_FREEZE_MIN).

    Fills ``basis`` = (w~, X, X^T, X^-T, c0 u, W^2 u, shift, full); the identity for a
    prescribed theta.
    """
    omega, Psi, PsiT, toM, row0, inv00, sref = lin
    wt, X, XT, XiT, cu, w2u, sh, full = basis
    N = omega.size
    ds = 0.0
    if not sysd[1] and FREEZE:
        _mv(mm[1], eta, Ae)
        ds = _dot(eta, Ae) - sref
    den = 1.0 + ds * inv00
    if ds == 0.0 or not den > 0.0 or abs(ds * inv00) < FULL_FREEZE_MIN:
        _identity_basis(omega, basis)
        if ds != 0.0 and den > 0.0:  # weak coupling: the diagonal as shifted frequencies
            c0 = ds / den
            u = mm[0]
            for k in range(N):
                w2 = omega[k] * omega[k]
                sh[k] = min(c0 * u[k] * u[k] * w2, w2)
                wt[k] = math.sqrt(w2 - sh[k])
        return
    u = mm[0]
    c0 = ds / den
    full[0] = 1.0
    # the active poles (v = w u != 0), ascending as the modes come from eigh; the rigid mode
    # and a support mode (u = 0) are not coupled
    order = np.empty(N, dtype=np.int64)
    m = 0
    for k in range(N):
        w2u[k] = omega[k] * omega[k] * u[k]
        cu[k] = c0 * u[k]
        if omega[k] * u[k] != 0.0:
            order[m] = k
            m += 1
    dA = np.empty(m)
    v2 = np.empty(m)
    vsum = 0.0
    for a in range(m):
        k = order[a]
        dA[a] = omega[k] * omega[k]
        v2[a] = dA[a] * u[k] * u[k]
        vsum += v2[a]
    for k in range(N):
        if omega[k] * u[k] == 0.0:  # e_k, M_s-normalised, at its own frequency
            wt[k] = omega[k]
            for j in range(N):
                X[j, k] = 0.0
            X[k, k] = 1.0 / math.sqrt(1.0 + ds * u[k] * u[k])
    for a in range(m):
        o = order[a]
        tau = _secular_root(a, dA, v2, c0, vsum)
        lam = dA[a] + tau
        wt[o] = math.sqrt(lam) if lam > 0.0 else 0.0
        ux = 0.0
        nrm = 0.0
        for k in range(N):
            w = omega[k]
            if w * u[k] != 0.0:
                xk = u[k] / ((w * w - dA[a]) - tau)
            elif u[k] != 0.0:  # the rigid mode (w = 0)
                xk = -u[k] / lam
            else:
                xk = 0.0
            X[k, o] = xk
            ux += u[k] * xk
            nrm += xk * xk
        sc = 1.0 / math.sqrt(nrm + ds * ux * ux)
        for k in range(N):
            X[k, o] *= sc
    for k in range(N):
        ux = 0.0
        for j in range(N):
            ux += u[j] * X[j, k]
        for j in range(N):
            XT[k, j] = X[j, k]
            XiT[j, k] = X[j, k] + ds * u[j] * ux


ADVANCE_END, ADVANCE_EVENT, ADVANCE_UNDERFLOW, ADVANCE_NONFINITE = 0, 1, 2, 3
MULTIPLIER_RTOL = 100.0  # the multiplier's tolerance in units of rtol (relative to the phase's peak)


@njit(cache=True)
def _multiplier_error(Vinv, F, f_scale, atol, rtol):
    """Scaled interpolation error of a CCM step's multiplier (an algebraic variable).

    The state's error estimate does not see lambda, whose nodal values are interpolated
    by a polynomial of degree p - 1; the size of its top Legendre term on (0, 1),
    |a_(p-1)| / binom(2p - 2, p - 1) with a_(p-1) the leading monomial coefficient, is
    taken as its error, against atol + MULTIPLIER_RTOL rtol max(|lambda|) over the phase.
    """
    p = F.size
    binom = 1.0  # binom(2p - 2, p - 1)
    for k in range(1, p):
        binom = binom * (p - 1 + k) / k
    lead = 0.0
    big = f_scale
    for j in range(p):
        lead += Vinv[p - 1, j] * F[j]
        big = max(big, abs(F[j]))
    return abs(lead) / binom / (atol + MULTIPLIER_RTOL * rtol * big)


@njit(cache=True)
def advance(t, t_end, z, zd, Ed, W, mode, lawp, h, hcap, sample_step, keep_dense, lin, tab, sysd, atol, rtol):
    """Integrate one phase from (t, z, z', E_d, W) until ``t_end`` or its event.

    ``mode`` 0 (free flight, event: the gap closes), 1 (CCFM, the gap opens), 2 (CCM, the
    multiplier turns tensile).  Returns (code, t, h_next, steps, nfev, sample times,
    sample states (reference layout [z, z', E_d, W]; every step end and the points of the
    ``sample_step`` grid), and when ``keep_dense`` the accepted steps' records (t0, h,
    eta0, v0, f, E_d0, W0, dissipation and power rates at the nodes, X) for dense output, each
    in its step's coordinates (:func:`_step_basis`).
    ``code``: ADVANCE_END, ADVANCE_EVENT, ADVANCE_UNDERFLOW (step size underflow) or
    ADVANCE_NONFINITE.  All work arrays are allocated here, once per phase; the output grid
    inside a step is sampled hop by hop (:func:`_hop`, one set of weights per step).
    """
    omega, Psi, PsiT, toM, row0, inv00, sref = lin
    c, b, Vinv = tab
    N = omega.size
    p = c.size
    size = 2 * N + 2
    mm = _modal_model(lin, sysd)
    cb = _colloc_buffers(N, p)
    eb = _event_buffers(N, p)
    out1 = _step_out(N, p)
    out2 = _step_out(N, p)
    Ae, Be, He, rest, PJb = cb[19], cb[20], cb[21], cb[22], cb[26]
    eta = toM @ z
    v = toM @ zd
    _node_modal(t, eta, v, sysd, mm, inv00, sref, mode != 0, Ae, Be, He, rest, PJb)
    f_guess = np.empty((p, N))
    for j in range(p):
        f_guess[j] = rest
    F_guess = np.zeros(p)
    work = (np.empty((N, p + 1)), np.empty((N, p + 1)), np.empty((N, p + 1)),
            np.empty((N, p + 1, p)), np.empty((N, p + 1, p)))
    h_w = -1.0
    new_lin = True
    full = False
    basis = _basis_buffers(N)
    wt, X, XT, XiT = basis[0], basis[1], basis[2], basis[3]
    lin_s = (wt, Psi, PsiT, toM, row0, inv00, sref)
    zeta = np.empty(N)  # the state in the step's coordinates (eta = X zeta)
    zetad = np.empty(N)
    en = np.empty(N)
    vn_ = np.empty(N)
    # sampling work arrays
    A = np.empty((p, N))
    W1 = np.empty((N, 3 + 2 * p))
    Wu = np.empty((N, 3 + 2 * p))
    ec = np.empty(N)
    vc = np.empty(N)
    bb = np.empty(p)
    ph = np.empty((2, p))
    cd = np.empty(p)
    cw = np.empty(p)
    zb = np.empty(N)
    ts = np.empty(256)
    ys = np.empty((256, size))
    ns = 0
    cap_r = 64 if keep_dense else 0
    r_t = np.empty(cap_r)
    r_w = np.empty((cap_r, N))
    r_h = np.empty(cap_r)
    r_eta = np.empty((cap_r, N))
    r_v = np.empty((cap_r, N))
    r_f = np.empty((cap_r, p, N))
    r_X = np.empty((cap_r if keep_dense else 0, N, N))
    r_E = np.empty((cap_r, 2))
    r_rates = np.empty((cap_r, 2, p))
    nr = 0
    steps = 0
    nfev = 0
    code = ADVANCE_END
    direction = -1 if mode == 0 else 1
    f_scale = 0.0  # largest contact force of the phase so far
    prescribed = sysd[1]
    tau = sysd[2][4]
    while t < t_end:
        h = min(h, t_end - t, hcap)
        if new_lin:  # the step's coordinates; the state and the forcing's guess (eta) moved to them
            _step_basis(eta, lin, sysd, mm, Ae, basis)
            full = basis[7][0] != 0.0
            _map(full, XiT, eta, zeta)
            _map(full, XiT, v, zetad)
            if full:
                _map_rows(XiT, f_guess, en)
            new_lin = False
            h_w = -1.0
        ok, err, iters = collocation_step(
            t, h, zeta, zetad, f_guess, F_guess, mode, lawp, lin_s, basis, tab, sysd, atol, rtol, work, h != h_w,
            mm, cb, out1)
        h_w = h
        steps += 1
        nfev += iters * p + 1
        if mode == 2 and err <= 1.0:
            err = max(err, _multiplier_error(Vinv, out1[3], f_scale, atol, rtol))
        if not (err <= 1.0):
            if not (err < math.inf):
                h *= 0.25
            else:
                h *= max(0.2, 0.9 * err ** (-1.0 / p))
            if h < 1e-15 * max(1.0, t):
                code = ADVANCE_UNDERFLOW
                break
            continue
        eta1, v1, f, F, diss, power = out1
        for j in range(p):
            f_scale = max(f_scale, abs(F[j]))
        if mode == 2:
            s_ev = multiplier_release(c, F)
        else:
            s_ev = find_event(t, h, zeta, zetad, f, direction, lin_s, basis, tab, sysd, mm, eb)
        if s_ev < 0.0:  # undecided: too long a step near the obstacle
            h *= 0.25
            continue
        event = s_ev <= 1.0
        h_taken = h
        if event:
            h_ev = s_ev * h
            if h_ev <= 0.0:
                code = ADVANCE_EVENT
                break
            ok2, err2, iters2 = collocation_step(
                t, h_ev, zeta, zetad, f, F, mode, lawp, lin_s, basis, tab, sysd, atol, rtol, work, True, mm, cb, out2)
            h_w = h_ev
            nfev += iters2 * p + 1
            if not ok2:
                h *= 0.5
                continue
            h_taken = h_ev
            eta1, v1, f, F, diss, power = out2
        if keep_dense:
            if nr == r_t.shape[0]:
                r_t = _grow(r_t, nr + 1)
                r_w = _grow(r_w, nr + 1)
                r_h = _grow(r_h, nr + 1)
                r_eta = _grow(r_eta, nr + 1)
                r_v = _grow(r_v, nr + 1)
                r_f = _grow(r_f, nr + 1)
                r_X = _grow(r_X, nr + 1)
                r_E = _grow(r_E, nr + 1)
                r_rates = _grow(r_rates, nr + 1)
            r_t[nr] = t
            r_w[nr] = wt
            r_h[nr] = h_taken
            r_eta[nr] = zeta
            r_v[nr] = zetad
            r_f[nr] = f
            r_X[nr] = X
            r_E[nr, 0] = Ed
            r_E[nr, 1] = W
            r_rates[nr, 0] = diss
            r_rates[nr, 1] = power
            nr += 1
        # output samples on the grid strictly inside the step, then the step end
        theta_start = 0.0
        for k in range(N):
            theta_start += Psi[0, k] * eta[k]
        b_start = 0.0
        if prescribed:
            _mv(PsiT, v, zb)
            b_start = _boundary_work(t, zb, sysd)
        t1 = t + h_taken
        k0 = math.floor(t / sample_step) + 1
        k1 = math.floor(t1 / sample_step)
        cnt = 0
        kf = k1 + 1
        for k in range(k0, k1 + 1):
            tk = k * sample_step
            if t < tk < t1:
                cnt += 1
                kf = min(kf, k)
        ts = _grow(ts, ns + cnt + 1)
        ys = _grow(ys, ns + cnt + 1)
        if cnt:
            _monomial(Vinv, f, A)
            for m in range(p):
                acc_d = 0.0
                acc_w = 0.0
                for j in range(p):
                    acc_d += Vinv[m, j] * diss[j]
                    acc_w += Vinv[m, j] * power[j]
                cd[m] = acc_d
                cw[m] = acc_w
            s0 = (kf * sample_step - t) / h_taken
            ds_ = sample_step / h_taken
            _hop_weights(wt, s0 * h_taken, ph[0], ph[1], W1)
            if cnt > 1:
                _hop_weights(wt, ds_ * h_taken, ph[0], ph[1], Wu)
            for k in range(N):
                ec[k] = zeta[k]
                vc[k] = zetad[k]
            for i in range(cnt):
                tk = (kf + i) * sample_step
                if i == 0:
                    _hop(A, 0.0, s0, W1, ec, vc, bb)
                else:
                    _hop(A, s0 + (i - 1) * ds_, ds_, Wu, ec, vc, bb)
                row = ys[ns + i]
                _map(full, XT, ec, en)
                _map(full, XT, vc, vn_)
                _mv(PsiT, en, row[:N])
                _mv(PsiT, vn_, row[N : 2 * N])
                sg = (tk - t) / h_taken
                eds = 0.0
                wsm = 0.0
                spm = sg
                for m in range(p):
                    eds += cd[m] * spm / (m + 1)
                    wsm += cw[m] * spm / (m + 1)
                    spm *= sg
                ts[ns + i] = tk
                row[2 * N] = Ed + eds * h_taken
                if prescribed:
                    row[2 * N + 1] = W + (wsm * h_taken + _boundary_work(tk, row[N : 2 * N], sysd) - b_start)
                else:  # constant torque: W = tau (theta - theta_0), exactly
                    row[2 * N + 1] = W + tau * (row[0] - theta_start)
            ns += cnt
        _map(full, XT, eta1, en)  # the step end back in eta
        _map(full, XT, v1, vn_)
        ed_inc = 0.0
        for j in range(p):
            ed_inc += b[j] * diss[j]
        Ed += h_taken * ed_inc
        if prescribed:
            pw_inc = 0.0
            for j in range(p):
                pw_inc += b[j] * power[j]
            _mv(PsiT, vn_, zb)
            W += h_taken * pw_inc + _boundary_work(t1, zb, sysd) - b_start
        else:
            # tau theta' holds the fast modes' oscillation, which Gauss quadrature over a
            # long step would miss; for a constant torque the work is tau (theta1 - theta0)
            th1 = 0.0
            for k in range(N):
                th1 += Psi[0, k] * en[k]
            W += tau * (th1 - theta_start)
        t = t1
        for k in range(N):
            eta[k] = en[k]
            v[k] = vn_[k]
        new_lin = True
        h_next = h
        if event:
            for j in range(p):
                F_guess[j] = F[j]
                for k in range(N):
                    f_guess[j, k] = f[j, k]
        else:
            h_next = h_taken * min(4.0, max(0.2, 0.9 * max(err, 1e-10) ** (-1.0 / (p + 1))))
            _extrapolate_into(c, f, h_next / h_taken, f_guess)
            _extrapolate1_into(c, F, h_next / h_taken, F_guess)
            if full:  # the guess back in eta
                _map_rows(XT, f_guess, en)
        ts[ns] = t
        row = ys[ns]
        _mv(PsiT, eta, row[:N])
        _mv(PsiT, v, row[N : 2 * N])
        row[2 * N] = Ed
        row[2 * N + 1] = W
        ns += 1
        finite = True
        for k in range(size):
            if not np.isfinite(row[k]):
                finite = False
        if not finite:
            code = ADVANCE_NONFINITE
            break
        if event:
            code = ADVANCE_EVENT
            break
        h = h_next
    return (code, t, h, steps, nfev, ts[:ns].copy(), ys[:ns].copy(),
            r_t[:nr].copy(), r_h[:nr].copy(), r_w[:nr].copy(), r_eta[:nr].copy(), r_v[:nr].copy(), r_f[:nr].copy(),
            r_E[:nr].copy(), r_rates[:nr].copy(), r_X[:nr].copy())


@njit(cache=True)
def dense_eval(tt, r_t, r_h, r_w, r_eta, r_v, r_f, r_E, r_rates, r_X, Psi, Vinv, sysd):
    """States [z, z', E_d, W] at times ``tt`` from the step records (rows; each step in its own
    coordinates zeta, eta = X zeta, so z = Psi X zeta)."""
    N = Psi.shape[0]
    out = np.empty((tt.size, 2 * N + 2))
    s = np.empty(1)
    k_prev = -1
    PX = np.empty((N, N))
    for i in range(tt.size):
        k = np.searchsorted(r_t, tt[i], side="right") - 1
        k = min(max(k, 0), r_t.size - 1)
        h = r_h[k]
        s[0] = (tt[i] - r_t[k]) / h
        if k != k_prev:
            PX = Psi @ r_X[k]
            k_prev = k
        Z, ZD = dense_states(h, r_eta[k], r_v[k], r_f[k], s, PX, r_w[k], Vinv)
        out[i, :N] = Z[0]
        out[i, N : 2 * N] = ZD[0]
        out[i, 2 * N] = r_E[k, 0] + integrate_rates(r_rates[k, 0], s, Vinv, h)[0]
        if sysd[1]:
            out[i, 2 * N + 1] = (r_E[k, 1] + integrate_rates(r_rates[k, 1], s, Vinv, h)[0]
                                 + _boundary_work(tt[i], ZD[0], sysd) - _boundary_work(r_t[k], PX @ r_v[k], sysd))
        else:
            out[i, 2 * N + 1] = r_E[k, 1] + sysd[2][4] * (Z[0, 0] - PX[0] @ r_eta[k])
    return out

