/* Exact propagation of the modal equations eta_k'' + w_k^2 eta_k = f_k(t) over a step for a forcing f that
 * is the polynomial interpolating its values at the FB_P nodes of the step (Gauss-Legendre, or Radau IIA for a
 * resting contact: fb_gauss, fb_radau).
 *
 * Variation of constants (Hochbruck & Ostermann 2010, Acta Numerica 19, Sec. 2): over [0, T], T = s h, for
 * f = sum_m a_m (tau / h)^m,
 *   eta(T) = cos(wT) eta0 + sin(wT)/w v0 + sum_m a_m s^m T^2 Sm(wT),
 *   v(T)   = -w sin(wT) eta0 + cos(wT) v0 + sum_m a_m s^m T Cm(wT),
 * with the moments Cm(th) = int_0^1 cos(th (1 - u)) u^m du and Sm(th) = th^-1 int_0^1 sin(th (1 - u)) u^m du,
 * i.e. J_m = m! phi_(m+1)(i th) = Cm + i th Sm, the phi-functions of exponential integrators on the imaginary
 * axis, computed in real arithmetic.  a = Vinv f_nodes (Vandermonde inverse).  The step is therefore not
 * limited by the highest modal frequency.
 */
#include <string.h>

#include "integrator.h"

#define MOMENT_SERIES 1.0 /* below this th: power series and downward recurrence (else upward) */

/* The tables of a node set given on (-1, 1] by its nodes x and quadrature weights wq, and a bound on its Lebesgue
 * function on [0, 1] (events.c; tests/unit/test_propagation.py). */
static void build_tables(const double *x, const double *wq, double lebesgue, fb_tables *t) {
    t->lebesgue = lebesgue;
    double V[FB_P * FB_P];
    for (int j = 0; j < FB_P; j++) {
        t->c[j] = 0.5 * (x[j] + 1.0);
        t->w[j] = 0.5 * wq[j];
        /* P_3(x) = (5 x^3 - 3 x) / 2: the top Legendre coefficient of the interpolant is
         * (2p - 1) sum_j w_j P_3(x_j) f_j (either quadrature is exact for degree 2p - 2) */
        double P3 = 0.5 * (5.0 * x[j] * x[j] * x[j] - 3.0 * x[j]);
        t->top[j] = (2.0 * FB_P - 1.0) * t->w[j] * P3;
    }
    /* Vandermonde inverse: column j of Vinv holds the monomial coefficients of the Lagrange polynomial l_j */
    for (int j = 0; j < FB_P; j++) {
        double rhs[FB_P];
        for (int i = 0; i < FB_P; i++) {
            double cp = 1.0;
            for (int m = 0; m < FB_P; m++) {
                V[i * FB_P + m] = cp;
                cp *= t->c[i];
            }
            rhs[i] = (i == j) ? 1.0 : 0.0;
        }
        fb_solve(V, rhs, FB_P);
        for (int m = 0; m < FB_P; m++) t->Vinv[m][j] = rhs[m];
    }
    for (int j = 0; j < FB_P; j++) { /* l_j(1): extrapolation of the interpolant to the step end */
        double acc = 0.0;
        for (int m = 0; m < FB_P; m++) acc += t->Vinv[m][j];
        t->lend[j] = acc;
    }
}

static fb_tables GAUSS, RADAU;
static int GAUSS_READY = 0, RADAU_READY = 0;

const fb_tables *fb_gauss(void) {
    if (GAUSS_READY) return &GAUSS;
    /* Gauss-Legendre, 4 nodes on (-1, 1) (Abramowitz & Stegun, Table 25.4) */
    static const double x[FB_P] = {-0.86113631159405257522, -0.33998104358485626480, 0.33998104358485626480,
                                   0.86113631159405257522};
    static const double w[FB_P] = {0.34785484513745385737, 0.65214515486254614263, 0.65214515486254614263,
                                   0.34785484513745385737};
    build_tables(x, w, 3.0, &GAUSS); /* its Lebesgue function's maximum on [0, 1]: 2.856 */
    GAUSS_READY = 1;
    return &GAUSS;
}

/* Radau IIA, 4 nodes on (-1, 1]: the zeros of P_4(x) - P_3(x), weights (1 + x_i) / (16 P_3(x_i)^2) and 2 / 16 at
 * x = 1 (Hairer & Wanner, Solving ODEs II, Sec. IV.5; computed to 30 digits with mpmath).  The step's end is a node,
 * so the collocation is stiffly accurate and L-stable: a stiff mode in the collocated remainder that the step does
 * not resolve -- a resting contact's spring -- is damped in the end state, where Gauss's nodes (|R(inf)| = 1) carry
 * it on undamped and the error estimate sees it at every step whatever the tolerance (docs/performance.md, "A
 * resting contact").  Order 2p - 1 = 7 at the step's end (Gauss: 2p = 8). */
const fb_tables *fb_radau(void) {
    if (RADAU_READY) return &RADAU;
    static const double x[FB_P] = {-0.82282408097459210521, -0.18106627111853057827, 0.57531892352169411205, 1.0};
    static const double w[FB_P] = {0.44092442235353675055, 0.77638693768634376156, 0.65768863996011948789, 0.125};
    build_tables(x, w, 3.5, &RADAU); /* its Lebesgue function's maximum on [0, 1]: 3.447, at 0 */
    RADAU_READY = 1;
    return &RADAU;
}

/* Moments Cm[0..p-1], Sm[0..p-1] of the harmonic kernel at th >= 0 (cos th, sin th given). */
static void osc_moments(double th, double cos_t, double sin_t, double *Cm, double *Sm) {
    const int p = FB_P;
    if (th < MOMENT_SERIES) {
        int m = p - 1;
        double t2 = th * th, fact = 1.0;
        for (int k = 2; k < m + 2; k++) fact *= k; /* (m + 1)! */
        double mf = fact / (m + 1);                  /* m! */
        double c_term = mf / fact, s_term = c_term / (m + 2), c_acc = c_term, s_acc = s_term;
        for (int j = 1; j < 12; j++) { /* th^22 / 24! < 2e-24: at most 11 terms, fewer for a small th */
            c_term = -c_term * t2 / ((2.0 * j + m) * (2.0 * j + m + 1));
            s_term = -s_term * t2 / ((2.0 * j + m + 1) * (2.0 * j + m + 2));
            c_acc += c_term;
            s_acc += s_term;
            if (fabs(c_term) <= 1e-17 * fabs(c_acc) && fabs(s_term) <= 1e-17 * fabs(s_acc)) break;
        }
        Cm[m] = c_acc;
        Sm[m] = s_acc;
        for (int k = m; k > 0; k--) {
            Cm[k - 1] = (1.0 - t2 * Sm[k]) / k;
            Sm[k - 1] = Cm[k] / k;
        }
    } else {
        double t2 = th * th;
        Cm[0] = sin_t / th;
        Sm[0] = (1.0 - cos_t) / t2;
        for (int k = 1; k < p; k++) {
            Cm[k] = k * Sm[k - 1];
            Sm[k] = (1.0 - k * Cm[k - 1]) / t2;
        }
    }
}

void fb_moments(double th, double *Cm, double *Sm) {
    double s, c;
    fb_sincos(th, &s, &c);
    osc_moments(th, c, s, Cm, Sm);
}

void fb_weights(const fb_tables *tb, double w, double h, double s, fb_weight *out) {
    double T = s * h, th = w * T, c, sn, Cm[FB_P], Sm[FB_P];
    fb_sincos(th, &sn, &c);
    osc_moments(th, c, sn, Cm, Sm);
    out->C = out->CV = c;
    out->SW = w != 0.0 ? sn / w : T;
    out->WS = w * sn;
    fb_weight_nodes(tb, T, s, Sm, Cm, out);
}

/* The forcing weights RE, RV of a step fraction s (T = s h) from the moments Sm (position) and Cm (velocity) of
 * the step's kernel: the monomial coefficients' weights projected onto the nodal values (Vandermonde inverse).
 * Shared by the undamped and the damped modes (damped.c). */
void fb_weight_nodes(const fb_tables *tb, double T, double s, const double *Sm, const double *Cm, fb_weight *out) {
    double spm = 1.0, pe[FB_P], pv[FB_P];
    for (int m = 0; m < FB_P; m++) {
        pe[m] = T * T * spm * Sm[m];
        pv[m] = T * spm * Cm[m];
        spm *= s;
    }
    for (int j = 0; j < FB_P; j++) {
        double re = 0.0, rv = 0.0;
        for (int m = 0; m < FB_P; m++) {
            re += pe[m] * tb->Vinv[m][j];
            rv += pv[m] * tb->Vinv[m][j];
        }
        out->RE[j] = re;
        out->RV[j] = rv;
    }
}

void fb_hop_weights(double w, double T, fb_hop *out) {
    double th = w * T, c, sn, Cm[FB_P], Sm[FB_P];
    fb_sincos(th, &sn, &c);
    osc_moments(th, c, sn, Cm, Sm);
    out->C = out->CV = c;
    out->SW = w != 0.0 ? sn / w : T;
    out->WS = w * sn;
    for (int m = 0; m < FB_P; m++) {
        out->pe[m] = T * T * Sm[m];
        out->pv[m] = T * Cm[m];
    }
}

void fb_monomial(const fb_tables *tb, const double *f, int N, double *A) {
    for (int m = 0; m < FB_P; m++)
        for (int k = 0; k < N; k++) {
            double acc = 0.0;
            for (int j = 0; j < FB_P; j++) acc += tb->Vinv[m][j] * f[j * N + k];
            A[m * N + k] = acc;
        }
}

/* The hop weights of every mode, stored mode-innermost (fb_hops) for fb_hop_advance. */
void fb_hops_fill(const fb_basis *b, double T, fb_hops *H) {
    for (int k = 0; k < b->N; k++) {
        fb_hop one;
        fb_mode_hop(b, k, T, &one);
        H->C[k] = one.C;
        H->CV[k] = one.CV;
        H->SW[k] = one.SW;
        H->WS[k] = one.WS;
        for (int m = 0; m < FB_P; m++) {
            H->pe[m][k] = one.pe[m];
            H->pv[m][k] = one.pv[m];
        }
    }
}

/* Advance (eta, v) in place from the step fraction sa by the fraction L with the hop weights H (of length L h):
 * the forcing, a polynomial in the step fraction with monomial coefficients A, is Taylor-shifted to the hop's
 * own variable u = (s - sa) / L, so the propagation stays exact.  Each mode's arithmetic is its own and in a fixed
 * order; the loops run over the modes innermost (contiguous, independent: vectorised without reassociation). */
void fb_hop_advance(const fb_basis *b, const fb_hops *H, const double *A, double sa, double L, double *eta,
                    double *v) {
    int N = b->N;
    double c[FB_P][FB_MAXN], fe[FB_MAXN], fv[FB_MAXN], sc[FB_P];
    for (int m = 0; m < FB_P; m++) memcpy(c[m], A + (size_t)m * N, sizeof(double) * N);
    if (sa != 0.0)
        for (int i = 0; i < FB_P - 1; i++)
            for (int j = FB_P - 2; j >= i; j--)
                for (int k = 0; k < N; k++) c[j][k] += sa * c[j + 1][k];
    sc[0] = 1.0;
    for (int m = 1; m < FB_P; m++) sc[m] = sc[m - 1] * L;
    for (int k = 0; k < N; k++) fe[k] = fv[k] = 0.0;
    for (int m = 0; m < FB_P; m++)
        for (int k = 0; k < N; k++) {
            fe[k] += H->pe[m][k] * c[m][k] * sc[m];
            fv[k] += H->pv[m][k] * c[m][k] * sc[m];
        }
    for (int k = 0; k < N; k++) {
        double e0 = eta[k], v0 = v[k];
        eta[k] = H->C[k] * e0 + H->SW[k] * v0 + fe[k];
        v[k] = -H->WS[k] * e0 + H->CV[k] * v0 + fv[k];
    }
}

/* eta, v at one point from the per-mode weights W[k * stride] and the nodal forcing f (FB_P x N). */
void fb_propagate(const fb_basis *b, const fb_weight *W, int stride, const double *eta0, const double *v0,
                  const double *f, double *eta, double *v) {
    int N = b->N;
    for (int k = 0; k < N; k++) {
        const fb_weight *wk = W + (size_t)k * stride;
        double e = wk->C * eta0[k] + wk->SW * v0[k], u = -wk->WS * eta0[k] + wk->CV * v0[k];
        for (int j = 0; j < FB_P; j++) {
            e += wk->RE[j] * f[j * N + k];
            u += wk->RV[j] * f[j * N + k];
        }
        eta[k] = e;
        v[k] = u;
    }
}

double fb_lagrange(const fb_tables *tb, int j, double s) {
    double acc = 0.0, sp = 1.0;
    for (int m = 0; m < FB_P; m++) {
        acc += tb->Vinv[m][j] * sp;
        sp *= s;
    }
    return acc;
}

double fb_lagrange_integral(const fb_tables *tb, int j, double s) {
    double acc = 0.0, sp = s;
    for (int m = 0; m < FB_P; m++) {
        acc += tb->Vinv[m][j] * sp / (m + 1);
        sp *= s;
    }
    return acc;
}

/* Basis buffer: [version, N, nz, diagonal, inv00, omega (N), Psi (N x N), toM (N x N), row0 (nz), (damp (N))]. */
int fb_basis_unpack(fb_basis *b, const double *buf, size_t nbuf) {
    if (nbuf < 5 || (int)buf[0] != FB_LAYOUT_VERSION) return -1;
    b->N = (int)buf[1];
    b->nz = (int)buf[2];
    b->diagonal = (int)buf[3];
    b->inv00 = buf[4];
    size_t N = (size_t)b->N;
    size_t base = 5 + N + 2 * N * N + (size_t)b->nz;
    if (nbuf != base && nbuf != base + N) return -2; /* + damp (N) with structural damping */
    b->omega = buf + 5;
    b->Psi = b->omega + N;
    b->toM = b->Psi + N * N;
    b->row0 = b->toM + N * N;
    b->K0 = NULL;
    b->damp = nbuf == base + N ? b->row0 + b->nz : NULL;
    return 0;
}

void fb_to_physical(const fb_basis *b, const double *eta, double *z) {
    int N = b->N;
    if (b->diagonal) {
        for (int k = 0; k < N; k++) z[k] = b->Psi[k * N + k] * eta[k];
        return;
    }
    fb_matvec(b->Psi, eta, N, z);
}

/* out = |Psi|^T x for x >= 0: a bound on |Psi^T y| for |y| <= x elementwise. */
void fb_project_abs(const fb_basis *b, const double *x, double *out) {
    int N = b->N;
    for (int k = 0; k < N; k++) {
        double acc = 0.0;
        for (int i = 0; i < N; i++) acc += fabs(b->Psi[i * N + k]) * x[i];
        out[k] = acc;
    }
}

void fb_project(const fb_basis *b, const double *x, double *out) {
    int N = b->N;
    if (b->diagonal) {
        for (int k = 0; k < N; k++) out[k] = b->Psi[k * N + k] * x[k];
        return;
    }
    for (int k = 0; k < N; k++) {
        double acc = 0.0;
        for (int i = 0; i < N; i++) acc += b->Psi[i * N + k] * x[i];
        out[k] = acc;
    }
}
