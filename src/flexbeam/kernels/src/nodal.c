/* The contact forces at a collocation step's nodes (CCFM's law forces, CCM's multipliers, a sticking pair's tangential
 * multiplier), solved inside each sweep by Newton's method with their exact linear modal response (collocation.c). */
#include "integrator.h"

#define NEWTON_MAX 30 /* Newton iterations for the nodal contact forces */
/* A sticking pair's slip velocity decays from its value at the step's start (the stick's residual: the located stop's
 * and each step end's collocation error) at the rate max(kappa, STICK_DECAY / h0): to 2 % of it at the end of the
 * step first tried, h0 (w->stick_h, phase.c).  Its retries after a rejection decay it at that same rate: a rate
 * steepened by each cut of h made the multiplier (~ STICK_DECAY m_eff v_t / h) grow as 1 / h and its error estimate
 * reject again, down to a step-size underflow (the seed experiment with mu = 0.3 at 0.46 s). */
#define STICK_DECAY 4.0

/* The contact unknowns of a step: (pair, node) for the pairs in contact, pair-major, then the tangential unknowns
 * (row 1: the sticking pairs' multipliers, the regularised law's forces; fb_tangential_unknown). */
void fb_list_unknowns(const fb_phase *ph, fb_unknowns *u) {
    u->count = 0;
    for (int k = 0; k < ph->c.npairs; k++)
        if (ph->c.mode[k] != FB_MODE_NONE)
            for (int i = 0; i < FB_P; i++) {
                u->pair[u->count] = k;
                u->row[u->count] = 0;
                u->node[u->count++] = i;
            }
    for (int k = 0; k < ph->c.npairs; k++)
        if (fb_tangential_unknown(&ph->c, k))
            for (int i = 0; i < FB_P; i++) {
                u->pair[u->count] = k;
                u->row[u->count] = 1;
                u->node[u->count++] = i;
            }
}

#define MAXU FB_MAXU

/* The modal response of unknown a's gap (pair k at node i, seen through jm_k at node i; its slip velocity through
 * jt_k for a tangential row) to unknown b's force (pair l at node j, along b_l at node j; bt_l for a tangential
 * row): A[a][b] (gap) and B[a][b] (gap rate, or slip velocity). */
static void contact_response(const fb_phase *ph, const fb_work *w, const fb_unknowns *u, double *A, double *B) {
    int N = ph->b->N, U = u->count;
    for (int a = 0; a < U; a++) {
        int k = u->pair[a], i = u->node[a];
        const double *jm = u->row[a] ? w->node[i].jt[k] : w->node[i].jm[k];
        for (int c = 0; c < U; c++) {
            int l = u->pair[c], j = u->node[c];
            const double *bj = u->row[c] ? w->node[j].bt[l] : w->node[j].b[l];
            double sa = 0.0, sb = 0.0;
            for (int q = 0; q < N; q++) {
                double x = jm[q] * bj[q];
                sa += x * w->W[q][i].RE[j];
                sb += x * w->W[q][i].RV[j];
            }
            A[a * U + c] = sa;
            B[a * U + c] = sb;
        }
    }
}

/* The contact unknowns, each gap and rate linear in them through (A, B): a FORCE pair's F = law(-delta(F),
 * -rate(F)) and a CONSTRAINT pair's multiplier keeping g = delta' + kappa delta on g(t0) exp(-kappa (t - t0)) at
 * the nodes, by Newton's method (one linear solve when no pair is under a law); a sticking pair's tangential
 * multiplier keeps its slip velocity on g0t exp(-max(kappa, STICK_DECAY / h0) (t - t0)) (friction.c). */
static void solve_contacts(const fb_phase *ph, fb_work *w, const fb_unknowns *u, const double *A, const double *B,
                           double h, const double *g0, const double *g0t) {
    const fb_tables *tb = ph->tb;
    int U = u->count;
    double kappa = ph->c.alpha, F0[MAXU], F[MAXU], d0[MAXU], r0[MAXU];
    double hd = w->stick_h > 0.0 ? w->stick_h : h; /* h0: the step first tried (phase.c), else this one */
    for (int a = 0; a < U; a++) {
        int k = u->pair[a], i = u->node[a];
        F0[a] = F[a] = u->row[a] ? w->Ft[k][i] : w->F[k][i];
        d0[a] = w->node[i].gap[k].delta;
        r0[a] = u->row[a] ? w->node[i].vt[k] : w->node[i].gap[k].rate;
    }
    int normal[MAXU], regularised = 0; /* a regularised tangential unknown's normal force (the same pair and node) */
    for (int a = 0; a < U; a++) {
        normal[a] = -1;
        if (!u->row[a] || !(ph->c.regv[u->pair[a]] > 0.0)) continue;
        regularised = 1;
        for (int c = 0; c < U; c++)
            if (!u->row[c] && u->pair[c] == u->pair[a] && u->node[c] == u->node[a]) normal[a] = c;
    }
    if (!ph->force && !regularised) { /* only constraints: linear, M F = target - g(F0) + M F0 in one solve */
        double M[MAXU * MAXU], rhs[MAXU];
        for (int a = 0; a < U; a++) {
            int k = u->pair[a], i = u->node[a];
            if (u->row[a]) { /* a sticking pair's slip velocity (CCM with friction) */
                rhs[a] = g0t[k] * fb_exp(-fmax(kappa, STICK_DECAY / hd) * tb->c[i] * h) - r0[a];
                for (int c = 0; c < U; c++) {
                    M[a * U + c] = B[a * U + c];
                    rhs[a] += M[a * U + c] * F0[c];
                }
                continue;
            }
            rhs[a] = g0[k] * fb_exp(-kappa * tb->c[i] * h) - (r0[a] + kappa * d0[a]);
            for (int c = 0; c < U; c++) {
                M[a * U + c] = B[a * U + c] + kappa * A[a * U + c];
                rhs[a] += M[a * U + c] * F0[c];
            }
            w->Fk[k][i] = 0.0;
        }
        if (fb_solve(M, rhs, U) == 0)
            for (int a = 0; a < U; a++) {
                if (u->row[a])
                    w->Ft[u->pair[a]][u->node[a]] = rhs[a];
                else
                    w->F[u->pair[a]][u->node[a]] = rhs[a];
            }
        return;
    }
    for (int it = 0; it < NEWTON_MAX; it++) {
        double Jac[MAXU * MAXU], res[MAXU], big = 0.0, step = 0.0;
        for (int a = 0; a < U; a++) {
            int k = u->pair[a], i = u->node[a];
            double d = d0[a], r = r0[a];
            for (int c = 0; c < U; c++) {
                d += A[a * U + c] * (F[c] - F0[c]);
                r += B[a * U + c] * (F[c] - F0[c]);
            }
            if (normal[a] >= 0) { /* the regularised law: F_t = sigma(v_t) F, F its normal force (not below 0) */
                int n = normal[a], pos = F[n] > 0.0 || ph->c.mode[k] != FB_MODE_FORCE;
                double Fn = pos ? F[n] : 0.0, s = fb_slip_coefficient(&ph->c, k, r);
                double ds = fb_slip_slope(&ph->c, k, r) * Fn;
                res[a] = -(F[a] - s * Fn);
                for (int c = 0; c < U; c++) Jac[a * U + c] = (a == c ? 1.0 : 0.0) - ds * B[a * U + c];
                if (pos) Jac[a * U + n] -= s;
                big = fmax(big, fabs(F[a]));
            } else if (u->row[a]) {
                res[a] = g0t[k] * fb_exp(-fmax(kappa, STICK_DECAY / hd) * tb->c[i] * h) - r;
                for (int c = 0; c < U; c++) Jac[a * U + c] = B[a * U + c];
                big = fmax(big, fabs(F[a]));
            } else if (ph->c.mode[k] == FB_MODE_FORCE) {
                double gd, gr, fk;
                double law = fb_law_force(ph->c.p[k], -d, -r, &fk, &gd, &gr);
                w->Fk[k][i] = fk;
                res[a] = -(F[a] - law);
                for (int c = 0; c < U; c++)
                    Jac[a * U + c] = (a == c ? 1.0 : 0.0) + gd * A[a * U + c] + gr * B[a * U + c];
                big = fmax(big, fabs(law));
            } else {
                res[a] = g0[k] * fb_exp(-kappa * tb->c[i] * h) - (r + kappa * d);
                for (int c = 0; c < U; c++) Jac[a * U + c] = B[a * U + c] + kappa * A[a * U + c];
                w->Fk[k][i] = 0.0;
            }
        }
        if (fb_solve(Jac, res, U)) break;
        for (int a = 0; a < U; a++) {
            F[a] += res[a];
            step = fmax(step, fabs(res[a]));
        }
        if (step <= 1e-13 * big || big == 0.0) break;
    }
    for (int a = 0; a < U; a++) {
        int k = u->pair[a];
        if (u->row[a])
            w->Ft[k][u->node[a]] = F[a];
        else
            w->F[k][u->node[a]] = ph->c.mode[k] == FB_MODE_FORCE && F[a] < 0.0 ? 0.0 : F[a];
    }
}

/* The nodal contact forces of a sweep (w->F, w->Ft) from the nodes' evaluations in w. */
void fb_nodal_contacts(const fb_phase *ph, fb_work *w, const fb_unknowns *u, double h, const double *g0,
                       const double *g0t) {
    double A[MAXU * MAXU], B[MAXU * MAXU];
    contact_response(ph, w, u, A, B);
    solve_contacts(ph, w, u, A, B, h, g0, g0t);
}

