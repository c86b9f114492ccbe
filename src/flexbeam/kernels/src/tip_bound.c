/* The tip's deflection on a phase's dense output: its exact linear part in the modal coordinates, and a bound on
 * how far it can exceed the larger of two samples T apart (the pruned search of the tip's extremes, extremes.c).
 *
 * The tip's kinematics.  The tip is the material point x = L on the centre line (offset 0; system.py packs it as
 * points[1]).  In the floating frame it sits at rho = (X, Y) (fb_point_kinematics, model.c), with
 *     X = base - S + P,   S = 1/2 q^T H(L) q,   P = Phi_a(L) p,   Y = Psi(L) q,   base = r_h + L,
 * and in the plane at r = R + A(theta) rho.  Its deflection (fb_tip_deflection) is its distance from the hub's
 * radial line through the frame's origin, D = e2(phi) . (r - R), e2(phi) = (-sin phi, cos phi), the hub angle
 * phi = theta + alpha with alpha = d q (d = Psi'(0): nonzero in the system frame, zero in the hub frame; a free
 * beam's phi = theta, alpha = 0).  Since A(theta)^T e2(phi) = e2(phi - theta) = e2(alpha),
 *     D = Y cos(alpha) - X sin(alpha),
 * whatever theta and R.  Linear part l = Y - base alpha = sum_k g_k eta_k, g_k = sum_i (Psi_i(L) - base d_i)
 * Psi_{q_i, k} over the bending rows q_i of the basis Psi; the rest
 *     N = D - l = Y (cos alpha - 1) - base (sin alpha - alpha) + (S - P) sin alpha
 * is of third order in the deformation and vanishes when d = 0 (then D = Y exactly).  With |cos a - 1| <= a^2/2,
 * |sin a - a| <= |a|^3/6 and |sin a| <= |a|:
 *     |N|  <= Y^ a^2/2 + base a^3/6 + (S^ + P^) a,
 *     |N'| <= Y^ a a' + Y'^ a^2/2 + base a' a^2/2 + (S'^ + P'^) a + (S^ + P^) a',
 * a, a' bounding |alpha|, |alpha'|; Y^, S^, P^ and their rates' bounds likewise (sums of |coefficient| x the modes'
 * bounds below; S through |Psi_q^T H Psi_q|).
 *
 * Each mode's bounds over a step of length h: eta'' + c eta' + w^2 eta = f(u), c >= 0 (damped.c), f the step's
 * forcing polynomial sum_m a_m u^m (u in [0, 1]; a = Vinv f_nodes, as the propagation uses it), |f| <= F = sum |a_m|.
 *  - Energy: d/dt sqrt(v^2 + w^2 eta^2) <= |f|, so |v| <= V = sqrt(v0^2 + w^2 eta0^2) + h F and
 *    |eta| <= amp + h F / w (amp = sqrt(eta0^2 + (v0 / w)^2)); also |eta| <= |eta0| + h V.
 *  - By parts: the forced response int K'(t - s) f(s) ds = K(t) f(0) + int K(t - s) f'(s) ds, K the step response,
 *    0 <= K <= 2 / w^2 for any c >= 0, int |f'| <= sum_{m >= 1} |a_m|: |eta| <= amp + 2 F / w^2.
 *  - The equation: |eta''| <= w^2 A + F + c V (A the smaller bound on |eta|).
 * Over a bracket the bounds are the largest over the steps it touches (each also holds across a step's end: the
 * state is continuous there).
 *
 * The slack.  For t between samples t_a < t < t_b = t_a + T and lambda = (t_b - t) / T,
 *     D(t) - max(D_a, D_b) <= D(t) - lambda D_a - (1 - lambda) D_b = dl + dN,
 *     dl <= sum_k |g_k| min(2 A_k, T^2/8 max|eta_k''|)          (a mode's range; the linear interpolant's error)
 *     dN <= min(2 N^, T/2 N'^)    (lambda (N(t) - N_a) + (1 - lambda)(N(t) - N_b) <= 2 N'^ (t - t_a)(t_b - t) / T),
 * plus twice the rounding of the computed deflection, 8 ulp of (1 + |theta|) |rho| (the frame's angle at the phase's
 * ends: the rotations' and the hub angle's rounding grows with |theta|; r - R is formed as A(theta) rho, never as a
 * difference of positions, so the frame's distance from the origin R adds none).  No factor of safety: the bound is the derivation's. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "tip_bound.h"

void fb_tip_model_init(const fb_model *m, const fb_basis *b, fb_tip_model *tm) {
    const fb_point *tip = &m->points[1];
    int N = b->N, nb = fb_nb(m), na = m->na, off = m->nrigid - m->ngiven;
    memset(tm, 0, sizeof *tm);
    tm->N = N;
    tm->base = tip->base;
    for (int k = 0; k < N; k++) {
        double y = 0.0, al = 0.0, pa = 0.0;
        for (int i = 0; i < nb; i++) {
            double psi = b->Psi[(off + i) * N + k];
            y += tip->phi[i] * psi;
            if (m->joint == FB_JOINT_REVOLUTE) al += m->d[i] * psi;
        }
        for (int i = 0; i < na; i++) pa += tip->aphi[i] * b->Psi[(off + nb + i) * N + k];
        tm->y[k] = y, tm->alpha[k] = al, tm->p[k] = pa;
        tm->g[k] = y - tm->base * al;
        if (al != 0.0) tm->nonlinear = 1;
    }
    if (!tm->nonlinear) return;
    double HPsi[FB_MAXN * FB_MAXN]; /* H Psi_q (nb x N), formed once: O(nb^2 N + nb N^2), not O(nb^2 N^2) */
    for (int i = 0; i < nb; i++)
        for (int k = 0; k < N; k++) {
            double row = 0.0;
            for (int l = 0; l < nb; l++) row += tip->H[i * nb + l] * b->Psi[(off + l) * N + k];
            HPsi[i * N + k] = row;
        }
    for (int j = 0; j < N; j++) /* |Psi_q^T H Psi_q| */
        for (int k = 0; k < N; k++) {
            double acc = 0.0;
            for (int i = 0; i < nb; i++) acc += b->Psi[(off + i) * N + j] * HPsi[i * N + k];
            tm->Habs[j * N + k] = fabs(acc);
        }
}

/* Mode k's bounds over the step of record rec (see above): |eta| <= *A, |eta'| <= *V, |eta''| <= *E. */
static void mode_bounds(const fb_basis *b, const double *rec, int R, int k, double *A, double *V, double *E) {
    int N = b->N;
    const double *eta0 = rec + 4, *v0 = eta0 + N, *f = v0 + N;
    double a[FB_P], F = fb_forcing_coefficients(fb_record_tables(rec, R), f, N, k, a, NULL);
    double h = rec[1], w = b->omega[k], c = b->damp ? b->damp[k] : 0.0;
    *V = sqrt(v0[k] * v0[k] + w * w * eta0[k] * eta0[k]) + h * F;
    *A = fabs(eta0[k]) + h * *V;
    if (w > 0.0) {
        double amp = sqrt(eta0[k] * eta0[k] + (v0[k] / w) * (v0[k] / w));
        *A = fmin(*A, amp + fmin(h * F / w, 2.0 * F / (w * w)));
    }
    *E = w * w * *A + F + c * *V;
}

void fb_tip_step_bounds(const fb_tip_model *tm, const fb_basis *b, const double *rec, int R, double *A, double *V,
                        double *E) {
    for (int k = 0; k < tm->N; k++) mode_bounds(b, rec, R, k, &A[k], &V[k], &E[k]);
}

void fb_tip_combine(const fb_tip_model *tm, const double *A, const double *V, const double *E, double theta_max,
                    fb_tip_bracket *out) {
    int N = tm->N;
    double Y = 0.0, Yd = 0.0, a = 0.0, ad = 0.0, P = 0.0, Pd = 0.0, S = 0.0, Sd = 0.0;
    for (int k = 0; k < N; k++) {
        out->A[k] = A[k], out->E[k] = E[k];
        Y += fabs(tm->y[k]) * A[k], Yd += fabs(tm->y[k]) * V[k];
        a += fabs(tm->alpha[k]) * A[k], ad += fabs(tm->alpha[k]) * V[k];
        P += fabs(tm->p[k]) * A[k], Pd += fabs(tm->p[k]) * V[k];
    }
    if (tm->nonlinear)
        for (int j = 0; j < N; j++)
            for (int k = 0; k < N; k++) {
                S += 0.5 * tm->Habs[j * N + k] * A[j] * A[k];
                Sd += tm->Habs[j * N + k] * A[j] * V[k];
            }
    double base = tm->base;
    out->N0 = Y * a * a / 2.0 + base * a * a * a / 6.0 + (S + P) * a;
    out->N1 = Y * a * ad + Yd * a * a / 2.0 + base * ad * a * a / 2.0 + (Sd + Pd) * a + (S + P) * ad;
    out->rounding = 8.0 * DBL_EPSILON * (1.0 + theta_max) * (fabs(base) + S + P + Y);
}

void fb_tip_reach(const fb_tip_model *tm, const fb_basis *b, const double *records, int R, int r0, int r1,
                  double theta_max, fb_tip_bracket *out) {
    int N = tm->N;
    double A[FB_MAXN] = {0}, V[FB_MAXN] = {0}, E[FB_MAXN] = {0}, a[FB_MAXN], v[FB_MAXN], e[FB_MAXN];
    for (int r = r0; r <= r1; r++) {
        fb_tip_step_bounds(tm, b, records + (size_t)r * R, R, a, v, e);
        for (int k = 0; k < N; k++) A[k] = fmax(A[k], a[k]), V[k] = fmax(V[k], v[k]), E[k] = fmax(E[k], e[k]);
    }
    fb_tip_combine(tm, A, V, E, theta_max, out);
}

void fb_tip_slack_parts(const fb_tip_model *tm, const fb_tip_bracket *br, double T, double parts[3]) {
    double lin = 0.0;
    for (int k = 0; k < tm->N; k++) lin += fabs(tm->g[k]) * fmin(2.0 * br->A[k], 0.125 * T * T * br->E[k]);
    parts[0] = lin;
    parts[1] = fmin(2.0 * br->N0, 0.5 * T * br->N1);
    parts[2] = 2.0 * br->rounding;
}

double fb_tip_slack(const fb_tip_model *tm, const fb_tip_bracket *br, double T) {
    double parts[3];
    fb_tip_slack_parts(tm, br, T, parts);
    return parts[0] + parts[1] + parts[2];
}
