/* Exact propagation of a damped mode eta'' + d eta' + w^2 eta = f(t) (d = 2 zeta w: the beam's structural damping,
 * beam.kelvin_voigt and beam.viscous_damping) over [0, T], T = s h, for the polynomial forcing
 * f = sum_m a_m (tau / h)^m, generalising propagation.c's moments to the damped oscillator.
 *
 * With alpha = d T / 2 and S = (w T)^2 - alpha^2 (= (nu T)^2, nu the damped frequency), the roots of the
 * characteristic polynomial (in units of 1 / T) are z = -alpha +- sqrt(-S).  Everything is a function of the
 * ring element z = -alpha + e, e^2 = -S (e = i nu T underdamped, e = kappa overdamped, a dual number at critical
 * damping): each analytic function F of the 2 x 2 system is F(z) = A + e B with A, B entire functions of S, so the
 * formulation passes through critical damping (S = 0) with no case of its own.  With
 *   e^{-alpha} C = e^{-alpha} cos(nu T),  e^{-alpha} Sn = e^{-alpha} sin(nu T) / (nu T)   (cosh, sinh when S < 0),
 * the free response is (variation of constants; Hochbruck & Ostermann 2010, Acta Numerica 19, Sec. 2)
 *   eta(T) = e^{-alpha} [(C + alpha Sn) eta0 + T Sn v0],  v(T) = e^{-alpha} [-w^2 T Sn eta0 + (C - alpha Sn) v0],
 * and the forced one
 *   eta(T) += sum_m a_m s^m T^2 B_m,  v(T) += sum_m a_m s^m T V_m,
 * with P_m(z) = int_0^1 e^{z (1 - u)} u^m du = m! phi_(m+1)(z) = A_m + e B_m, the phi-functions of exponential
 * integrators, B_m = int_0^1 e^{-alpha (1 - u)} Sn(1 - u) u^m du and V_m = A_m - alpha B_m = m B_(m-1)
 * (V_0 = e^{-alpha} Sn).  P_m is evaluated (rho_min <= rho_max the roots' moduli) by its power series and the
 * downward recurrence P_(m-1) = (1 + z P_m) / m in the ring when rho_max < 3; by the upward one
 * P_m = (m P_(m-1) - 1) / z from P_0 = (e^z - 1) / z when the roots are within a factor 3 of each other
 * (1 / z = (-alpha - e) / (w T)^2); and when they are farther apart (strongly overdamped: a fast and a slow real
 * root) as the divided difference B_m = (P_m(z1) - P_m(z2)) / (z1 - z2) of the real phi-functions at the two roots,
 * z1 = -(w T)^2 / rho_max computed without cancellation.  Each of these is well conditioned where it is used; none
 * divides by sqrt(S).  Checked against scipy's solve_ivp at zeta = 0, 0.01, 0.999, 1, 1.001, 50, the augmented
 * matrix exponential and closed forms (tests/unit/test_damped_propagation.py).
 */
#include <string.h>

#include "integrator.h"

#define SERIES_RHO 3.0 /* the ring's power series below this root modulus */
#define SPREAD 3.0     /* roots farther apart than this ratio: the divided difference of the real roots */

typedef struct {
    double a, b; /* a + e b, e^2 = -S */
} ring;

static ring rmul(ring x, ring y, double S) {
    ring r = {x.a * y.a - S * x.b * y.b, x.a * y.b + x.b * y.a};
    return r;
}

/* The mode's step constants: alpha, S, the roots' moduli, e^{-alpha} C, e^{-alpha} Sn and the free response. */
typedef struct {
    double alpha, wT, S, kappa, rmin, rmax, eC, eS, EE, VV;
    int split; /* overdamped with kappa >= 1: the real roots' exponentials */
} damped_step;

static void setup(double w, double d, double T, damped_step *ds) {
    double alpha = 0.5 * d * T, wT = w * T, S = (wT - alpha) * (wT + alpha);
    ds->alpha = alpha, ds->wT = wT, ds->S = S;
    ds->kappa = S < 0.0 ? sqrt(-S) : 0.0;
    ds->rmax = S < 0.0 ? alpha + ds->kappa : wT;
    ds->rmin = S < 0.0 ? wT * wT / ds->rmax : wT;
    ds->split = S < 0.0 && ds->kappa >= 1.0;
    if (ds->split) { /* e^{z1}, e^{z2} of the real roots: no overflow of cosh kappa against e^{-alpha} */
        double e1 = fb_exp(-ds->rmin), e2 = fb_exp(-ds->rmax), k2 = 2.0 * ds->kappa;
        ds->eC = 0.5 * (e1 + e2);
        ds->eS = (e1 - e2) / k2;
        ds->EE = (ds->rmax * e1 - ds->rmin * e2) / k2;
        ds->VV = (ds->rmax * e2 - ds->rmin * e1) / k2;
        return;
    }
    double E = fb_exp(-alpha), C, Sn;
    if (S >= 0.0) {
        double th = sqrt(S), sn;
        fb_sincos(th, &sn, &C);
        Sn = th > 0.0 ? sn / th : 1.0;
    } else { /* cosh kappa, sinh kappa / kappa by their series, kappa < 1 */
        double k2 = -S, tc = 1.0, ts = 1.0;
        C = Sn = 1.0;
        for (int j = 1; j < 12; j++) {
            tc *= k2 / ((2.0 * j - 1.0) * (2.0 * j));
            ts *= k2 / ((2.0 * j) * (2.0 * j + 1.0));
            C += tc;
            Sn += ts;
        }
    }
    ds->eC = E * C;
    ds->eS = E * Sn;
    ds->EE = ds->eC + alpha * ds->eS;
    ds->VV = ds->eC - alpha * ds->eS;
}

/* P_m(z), m < FB_P, of a real z <= 0 (the overdamped roots): series below |z| = 1, else the upward recurrence. */
static void real_moments(double z, double *P) {
    const int p = FB_P;
    if (fabs(z) < 1.0) {
        int m = p - 1;
        double term = 1.0 / (m + 1), acc = term;
        for (int j = 1; j < 30; j++) {
            term *= z / (m + j + 1);
            acc += term;
            if (fabs(term) <= 1e-17 * fabs(acc)) break;
        }
        P[m] = acc;
        for (int k = m; k > 0; k--) P[k - 1] = (1.0 + z * P[k]) / k;
    } else {
        P[0] = fb_expm1(z) / z;
        for (int k = 1; k < p; k++) P[k] = (k * P[k - 1] - 1.0) / z;
    }
}

/* The moments B_m, V_m (m < FB_P) of the step (see the file's comment). */
static void moments(const damped_step *ds, double *B, double *V) {
    const int p = FB_P;
    double S = ds->S;
    ring z = {-ds->alpha, 1.0}, P[FB_P];
    if (ds->rmax < SERIES_RHO) {
        int m = p - 1;
        ring term = {1.0 / (m + 1), 0.0}, acc = term;
        for (int j = 1; j < 60; j++) {
            term = rmul(term, z, S);
            term.a /= (m + j + 1), term.b /= (m + j + 1);
            acc.a += term.a, acc.b += term.b;
            if (fabs(term.a) <= 1e-17 * fabs(acc.a) && fabs(term.b) <= 1e-17 * fabs(acc.b)) break;
        }
        P[m] = acc;
        for (int k = m; k > 0; k--) {
            ring zp = rmul(z, P[k], S);
            P[k - 1].a = (1.0 + zp.a) / k, P[k - 1].b = zp.b / k;
        }
    } else if (S >= 0.0 || ds->rmax < SPREAD * ds->rmin) {
        double n2 = ds->wT * ds->wT;
        ring zinv = {-ds->alpha / n2, -1.0 / n2}, x = {ds->eC - 1.0, ds->eS};
        P[0] = rmul(x, zinv, S);
        for (int k = 1; k < p; k++) {
            ring y = {k * P[k - 1].a - 1.0, k * P[k - 1].b};
            P[k] = rmul(y, zinv, S);
        }
    } else {
        double P1[FB_P], P2[FB_P], dz = ds->rmax - ds->rmin;
        real_moments(-ds->rmin, P1);
        real_moments(-ds->rmax, P2);
        for (int k = 0; k < p; k++) P[k].b = (P1[k] - P2[k]) / dz, P[k].a = 0.0;
    }
    for (int k = 0; k < p; k++) B[k] = P[k].b;
    V[0] = ds->eS;
    for (int k = 1; k < p; k++) V[k] = k * B[k - 1];
}

void fb_weights_damped(const fb_tables *tb, double w, double d, double h, double s, fb_weight *out) {
    double T = s * h, B[FB_P], V[FB_P];
    damped_step ds;
    setup(w, d, T, &ds);
    moments(&ds, B, V);
    out->C = ds.EE;
    out->CV = ds.VV;
    out->SW = T * ds.eS;
    out->WS = w * w * T * ds.eS;
    fb_weight_nodes(tb, T, s, B, V, out);
}

void fb_hop_weights_damped(double w, double d, double T, fb_hop *out) {
    double B[FB_P], V[FB_P];
    damped_step ds;
    setup(w, d, T, &ds);
    moments(&ds, B, V);
    out->C = ds.EE;
    out->CV = ds.VV;
    out->SW = T * ds.eS;
    out->WS = w * w * T * ds.eS;
    for (int m = 0; m < FB_P; m++) {
        out->pe[m] = T * T * B[m];
        out->pv[m] = T * V[m];
    }
}

/* Mode k's weights: damped when the basis has a damping coefficient for it, else propagation.c's. */
void fb_mode_weights(const fb_tables *tb, const fb_basis *b, int k, double h, double s, fb_weight *out) {
    if (b->damp && b->damp[k] > 0.0 && b->omega[k] > 0.0)
        fb_weights_damped(tb, b->omega[k], b->damp[k], h, s, out);
    else
        fb_weights(tb, b->omega[k], h, s, out);
}

void fb_mode_hop(const fb_basis *b, int k, double T, fb_hop *out) {
    if (b->damp && b->damp[k] > 0.0 && b->omega[k] > 0.0)
        fb_hop_weights_damped(b->omega[k], b->damp[k], T, out);
    else
        fb_hop_weights(b->omega[k], T, out);
}

/* The structural damping force -C q' of the flexible coordinates (C = m->Cd, n x n) added to Q from ``off`` on;
 * returns the dissipated power q'^T C q' (0 without damping). */
double fb_damping_force(const fb_model *m, const double *qd, double *Q, int off) {
    if (!m->Cd) return 0.0;
    int n = m->n;
    double power = 0.0;
    for (int i = 0; i < n; i++) {
        double acc = 0.0;
        for (int j = 0; j < n; j++) acc += m->Cd[i * n + j] * qd[j];
        if (Q) Q[off + i] -= acc;
        power += qd[i] * acc;
    }
    return power;
}

/* R += M0 Psi diag(d) v (= toM^T (d v)): the damping the modal propagation takes in its linear part, given back to
 * the remainder, whose Q holds the physical damping force (Psi^T of it is then d v exactly). */
void fb_damping_return(const fb_basis *b, const double *v, double *R) {
    if (!b->damp) return;
    int N = b->N;
    for (int k = 0; k < N; k++) {
        double dv = b->damp[k] * v[k];
        if (dv == 0.0) continue;
        if (b->diagonal) {
            R[k] += b->toM[k * N + k] * dv;
            continue;
        }
        for (int i = 0; i < N; i++) R[i] += b->toM[k * N + i] * dv;
    }
}

/* The exact dissipation d int_0^h v^2 dt of a damped mode over a step whose forcing is the cubic f (monomial
 * coefficients a in u = t / h), from its energy E = (v^2 + w^2 eta^2) / 2: d int v^2 = E(0) - E(h) + int f v, and
 * int f v = Y(f) by the exact recursions over f's derivatives D_j (D_4 = 0), with X(p) = int p eta, Y(p) = int p v:
 *   Y(p) = [p eta] - X(p'),   w^2 X(p) = int p f - [p v] + Y(p') - d Y(p)   (w^2 eta = f - v' - d v).
 * Exact for any w > 0; used where w h >= 1 (a mode too fast for the Gauss nodes to integrate v^2) and the recursion's
 * factor d / (w^2 h) stays below 4. */
double fb_mode_dissipation(double w, double d, double h, const double *a, double e0, double v0, double e1,
                           double v1) {
    double D[FB_P + 1][FB_P], X = 0.0, Y = 0.0, w2 = w * w;
    memcpy(D[0], a, sizeof(double) * FB_P);
    for (int j = 0; j < FB_P; j++) {
        for (int k = 0; k < FB_P - 1; k++) D[j + 1][k] = (k + 1) * D[j][k + 1] / h;
        D[j + 1][FB_P - 1] = 0.0;
    }
    for (int j = FB_P - 1; j >= 0; j--) {
        double end = 0.0, pf = 0.0;
        for (int k = 0; k < FB_P; k++) {
            end += D[j][k];
            for (int l = 0; l < FB_P; l++) pf += D[j][k] * a[l] / (k + l + 1);
        }
        double Yj = end * e1 - D[j][0] * e0 - X;
        if (j == 0) return 0.5 * (v0 * v0 + w2 * e0 * e0) - 0.5 * (v1 * v1 + w2 * e1 * e1) + Yj;
        X = (h * pf - (end * v1 - D[j][0] * v0) + Y - d * Yj) / w2;
        Y = Yj;
    }
    return 0.0;
}

/* The step's nodal dissipation rates red (Gauss quadrature of q'^T C q' at the nodes) corrected so that their
 * quadrature books each damped mode's dissipation d int v^2 as its energy balance gives it, E(0) - E(h) + int f v:
 * the Gauss nodes cannot integrate the v^2 of a mode that turns many times in a step (which the exact propagation
 * allows) nor of an overdamped mode's fast transient (d h > 1).  int f v is exact by the recursion of
 * fb_mode_dissipation when w h >= 1 and d <= 4 w^2 h, else [f eta] - int f' eta with the smooth eta at the nodes
 * (d h > 1; the quadrature is kept when d h <= 1 and w h < 1, where it resolves v).  As the base's work is
 * integrated by parts (base_motion.c).  The correction is spread as a constant rate over the step. */
void fb_damping_books(const fb_phase *ph, const fb_work *w, double h, const double *eta, const double *v,
                      const double *eta1, const double *v1, const double *f, double *red) {
    const fb_basis *b = ph->b;
    if (!b->damp) return;
    const fb_tables *tb = ph->tb;
    int N = b->N;
    double corr = 0.0;
    for (int k = 0; k < N; k++) {
        double d = b->damp[k], om = b->omega[k];
        int exact = om * h >= 1.0 && d <= 4.0 * om * om * h;
        if (!(d > 0.0) || !(exact || d * h > 1.0)) continue;
        double a[FB_P], quad = 0.0, parts = 0.0, fe = 0.0;
        for (int m = 0; m < FB_P; m++) {
            a[m] = 0.0;
            for (int j = 0; j < FB_P; j++) a[m] += tb->Vinv[m][j] * f[j * N + k];
            fe += a[m];
        }
        for (int j = 0; j < FB_P; j++) { /* the mode at node j: eta = Psi^-1 z = toM z, v = toM z' */
            const double *z = w->node[j].z, *zd = w->node[j].zd;
            double ek = 0.0, vk = 0.0, fd = 0.0, cp = 1.0;
            for (int i = 0; i < N; i++) {
                if (b->diagonal && i != k) continue;
                ek += b->toM[k * N + i] * z[i];
                vk += b->toM[k * N + i] * zd[i];
            }
            for (int m = 1; m < FB_P; m++, cp *= tb->c[j]) fd += m * a[m] * cp / h; /* f'(t_j) */
            quad += tb->w[j] * d * vk * vk;
            parts += tb->w[j] * fd * ek;
        }
        double E0 = 0.5 * (v[k] * v[k] + om * om * eta[k] * eta[k]);
        double E1 = 0.5 * (v1[k] * v1[k] + om * om * eta1[k] * eta1[k]);
        double D = exact ? fb_mode_dissipation(om, d, h, a, eta[k], v[k], eta1[k], v1[k])
                         : E0 - E1 + fe * eta1[k] - a[0] * eta[k] - h * parts;
        corr += D - h * quad;
    }
    for (int j = 0; j < FB_P; j++) red[j] += corr / h;
}
