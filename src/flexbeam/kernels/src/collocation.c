/* One step of Gauss collocation on the exactly propagated modal equations.
 *
 * Linearising M(z) z'' = Q + J^T F about the undeformed beam at rest gives M0 z'' + K0 z = R with
 *   R = M0 M(z)^-1 (Q + J^T F) + K0 z,
 * M(z) = M0 + ds e0 e0^T (ds = q^T Mc q, free joint), so by Sherman-Morrison
 *   M0 M^-1 x = x - c e0 (row0 . x),  c = ds / (1 + ds (M0^-1)_00),  row0 = e0^T M0^-1.
 * In modal coordinates z = Psi eta: eta'' + diag(w^2) eta = f = Psi^T R (exact propagation, propagation.c)
 * with f the interpolant of its values at the FB_P Gauss nodes, found by fixed-point iteration; the contact
 * force (CCFM) or multiplier (CCM) at the nodes is solved inside each sweep by Newton's method with its exact
 * linear modal response, so a stiff contact needs no small step.  With theta(t) prescribed, z = q and
 * M = M_qq is constant: R = Q_q - m_tq theta'' + K q.  A compliant support is one more mode sqrt(m_s) s.
 */
#include <string.h>

#include "integrator.h"

#define ITER_MAX 12     /* fixed-point sweeps per step before the step is rejected */
#define ITER_TOL 1e-3   /* converged when the last sweep moved the step end by this much of the tolerance */
#define STAGNATION 1e-2 /* ... or it stops contracting within this much of the tolerance */
#define ROUNDOFF 1e-13  /* ... or it moves the end by less than this of the forcing's own effect (round-off) */
#define NEWTON_MAX 30   /* Newton iterations for the nodal contact forces */
/* The collocated multiplier (CCM) is an algebraic variable the state's error estimate does not see: its
 * interpolant's top Legendre term is held to MULTIPLIER_RTOL rtol of the phase's largest multiplier so far, but not
 * below MULTIPLIER_NOISE, its round-off (the multiplier is a velocity defect divided by the step's response
 * h / m_eff: ~1e-9 relative measured at h ~ 1e-7 s; 1e-7 leaves a margin of 100). */
#define MULTIPLIER_RTOL 100.0
#define MULTIPLIER_NOISE 1e-7

void fb_eval_node(const fb_phase *ph, double t, const double *eta, const double *v, int want_gap, fb_node *out) {
    fb_eval_node_acc(ph, t, eta, v, want_gap, 0, out);
}

/* As fb_eval_node; ``want_acc``: also the gap's velocity-product acceleration gamma (an n x n product more). */
void fb_eval_node_acc(const fb_phase *ph, double t, const double *eta, const double *v, int want_gap, int want_acc,
                      fb_node *out) {
    const fb_model *m = ph->m;
    const fb_basis *b = ph->b;
    int n = m->n, N = b->N, nz = b->nz, pre = m->prescribed, compliant = fb_compliant(m);
    double *z = out->z, *zd = out->zd;
    fb_to_physical(b, eta, z);
    fb_to_physical(b, v, zd);
    const double *q = pre ? z : z + 1, *qd = pre ? zd : zd + 1;
    double th, thd, thdd;
    if (pre) {
        fb_drive_motion(m, t, &th, &thd, &thdd);
    } else {
        th = z[0];
        thd = zd[0];
        thdd = 0.0;
    }
    out->t = t;
    out->th = th;
    out->thd = thd;
    out->thdd = thdd;
    double Q[FB_MAXN], R[FB_MAXN];
    double ds = fb_forces(m, th, thd, q, qd, pre ? 0.0 : fb_drive_torque(m, t), 0, Q); /* no elastic force */
    double c = 0.0;
    if (pre) {
        for (int i = 0; i < n; i++) R[i] = Q[i + 1] - m->mtq[i] * thdd;
    } else {
        c = ds / (1.0 + ds * b->inv00);
        double r0 = 0.0;
        for (int i = 0; i < nz; i++) r0 += b->row0[i] * Q[i];
        if (ph->row0_q) { /* row0 . (-K0 z): the elastic force is not in Q */
            for (int i = 0; i < n; i++) {
                double kq = 0.0;
                for (int j = 0; j < n; j++) kq += m->K[i * n + j] * q[j];
                r0 -= b->row0[i + 1] * kq;
            }
        }
        for (int i = 0; i < nz; i++) R[i] = Q[i];
        R[0] -= c * r0;
    }
    const fb_obstacle *o = m->nobstacles ? &m->obstacles[0] : NULL;
    double s = 0.0, sd = 0.0;
    if (compliant) {
        s = z[N - 1];
        sd = zd[N - 1];
        R[N - 1] = -o->cs * sd; /* the support's dashpot (its spring is in the linear part) */
    }
    fb_project(b, R, out->smooth);
    out->delta = out->rate = out->gamma = 0.0;
    out->gap.delta = INFINITY;
    if (!want_gap || !o) return;
    double dr[2 * FB_MAXN], J[FB_MAXN], Jx[FB_MAXN];
    fb_kin k = {.want_acc = want_acc};
    fb_point_kinematics(m, &m->points[0], th, thd, q, qd, &k, dr);
    fb_gap gp = fb_gap_state(o, &k, dr, n + 1, s, sd, J);
    out->gap = gp;
    out->delta = gp.delta;
    out->rate = gp.rate;
    out->gamma = gp.gamma;
    /* J in the integrator's coordinates: [theta, q] or q, then the support */
    for (int i = 0; i < nz; i++) Jx[i] = J[i + (pre ? 1 : 0)];
    if (compliant) Jx[N - 1] = gp.Js;
    fb_project(b, Jx, out->jm);
    if (!pre && c != 0.0) {
        double r0 = 0.0;
        for (int i = 0; i < nz; i++) r0 += b->row0[i] * Jx[i];
        Jx[0] -= c * r0;
        fb_project(b, Jx, out->b);
    } else {
        memcpy(out->b, out->jm, sizeof(double) * N);
    }
}

/* The gap at a modal state (the point kinematics alone, no forces); no obstacle: an infinite gap. */
fb_gap fb_gap_at(const fb_phase *ph, double t, const double *eta, const double *v) {
    const fb_model *m = ph->m;
    const fb_basis *b = ph->b;
    int n = m->n, N = b->N, pre = m->prescribed, compliant = fb_compliant(m);
    fb_gap none = {INFINITY, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    if (!m->nobstacles) return none;
    double z[FB_MAXN], zd[FB_MAXN], th, thd, thdd;
    fb_to_physical(b, eta, z);
    fb_to_physical(b, v, zd);
    const double *q = pre ? z : z + 1, *qd = pre ? zd : zd + 1;
    if (pre) {
        fb_drive_motion(m, t, &th, &thd, &thdd);
    } else {
        th = z[0];
        thd = zd[0];
    }
    fb_kin k = {.want_acc = 0};
    fb_point_kinematics(m, &m->points[0], th, thd, q, qd, &k, NULL);
    return fb_gap_state(&m->obstacles[0], &k, NULL, n + 1, compliant ? z[N - 1] : 0.0, compliant ? zd[N - 1] : 0.0,
                        NULL);
}

static void ensure_weights(const fb_phase *ph, fb_work *w, double h) {
    if (w->h == h) return;
    const fb_tables *tb = fb_gauss();
    int N = ph->b->N;
    for (int k = 0; k < N; k++) {
        double om = ph->b->omega[k];
        for (int i = 0; i < FB_P; i++) fb_weights(om, h, tb->c[i], &w->W[k][i]);
        fb_weights(om, h, 1.0, &w->W[k][FB_P]);
    }
    w->h = h;
}

/* The modal response at node i to the nodal values of a scalar force F_j along the directions b_j, seen through
 * jm_i: A[i][j] (gap) and B[i][j] (gap rate). */
static void contact_response(const fb_phase *ph, const fb_work *w, double A[FB_P][FB_P], double B[FB_P][FB_P]) {
    int N = ph->b->N;
    for (int i = 0; i < FB_P; i++)
        for (int j = 0; j < FB_P; j++) {
            double a = 0.0, bb = 0.0;
            const double *jm = w->node[i].jm, *bj = w->node[j].b;
            for (int k = 0; k < N; k++) {
                double x = jm[k] * bj[k];
                a += x * w->W[k][i].RE[j];
                bb += x * w->W[k][i].RV[j];
            }
            A[i][j] = a;
            B[i][j] = bb;
        }
}

/* CCFM: Newton's method on F_i = law(-delta_i(F), -rate_i(F)) with delta and its rate linear in F. */
static void solve_law(const fb_phase *ph, fb_work *w, double A[FB_P][FB_P], double B[FB_P][FB_P]) {
    double F0[FB_P], F[FB_P], d0[FB_P], r0[FB_P];
    for (int i = 0; i < FB_P; i++) {
        F0[i] = F[i] = w->F[i];
        d0[i] = w->node[i].delta;
        r0[i] = w->node[i].rate;
    }
    for (int it = 0; it < NEWTON_MAX; it++) {
        double Jac[FB_P * FB_P], res[FB_P], big = 0.0, step = 0.0;
        for (int i = 0; i < FB_P; i++) {
            double d = d0[i], r = r0[i];
            for (int j = 0; j < FB_P; j++) {
                d += A[i][j] * (F[j] - F0[j]);
                r += B[i][j] * (F[j] - F0[j]);
            }
            double gd, gr, fk;
            double law = fb_law_force(ph->p, -d, -r, &fk, &gd, &gr);
            w->Fk[i] = fk;
            res[i] = -(F[i] - law);
            for (int j = 0; j < FB_P; j++) Jac[i * FB_P + j] = (i == j ? 1.0 : 0.0) + gd * A[i][j] + gr * B[i][j];
            big = fmax(big, fabs(law));
        }
        if (fb_solve(Jac, res, FB_P)) break;
        for (int i = 0; i < FB_P; i++) {
            F[i] += res[i];
            step = fmax(step, fabs(res[i]));
        }
        if (step <= 1e-13 * big || big == 0.0) break;
    }
    for (int i = 0; i < FB_P; i++) w->F[i] = F[i] > 0.0 ? F[i] : 0.0;
}

/* CCM: the multiplier keeping g = delta' + kappa delta on g(t0) exp(-kappa (t - t0)) at the nodes (linear). */
static void solve_constraint(const fb_phase *ph, fb_work *w, double A[FB_P][FB_P], double B[FB_P][FB_P], double h,
                             double g0) {
    const fb_tables *tb = fb_gauss();
    double kappa = ph->p[0], M[FB_P * FB_P], rhs[FB_P];
    for (int i = 0; i < FB_P; i++) {
        double g = w->node[i].rate + kappa * w->node[i].delta, target = g0 * exp(-kappa * tb->c[i] * h);
        rhs[i] = target - g;
        for (int j = 0; j < FB_P; j++) {
            M[i * FB_P + j] = B[i][j] + kappa * A[i][j];
            rhs[i] += M[i * FB_P + j] * w->F[j];
        }
    }
    if (fb_solve(M, rhs, FB_P) == 0)
        for (int i = 0; i < FB_P; i++) w->F[i] = rhs[i];
}

/* One step from (eta0, v0) over [t0, t0 + h].  f (FB_P x N) holds the guess of the nodal forcing and returns the
 * converged one, w->F the nodal contact forces.  Returns 0, or -1 for a non-finite state. */
int fb_collocate(const fb_phase *ph, fb_work *w, double t0, double h, const double *eta0, const double *v0,
                 double *f, fb_step *out) {
    const fb_tables *tb = fb_gauss();
    int N = ph->b->N, contact = ph->mode != FB_MODE_NONE;
    ensure_weights(ph, w, h);
    double g0 = 0.0;
    if (ph->mode == FB_MODE_CONSTRAINT) {
        fb_gap gp = fb_gap_at(ph, t0, eta0, v0);
        g0 = gp.rate + ph->p[0] * gp.delta;
    }
    double tol = fb_tolerance(ph, eta0, v0, eta0, v0), prev = INFINITY;
    out->converged = 0;
    for (int it = 0; it < ITER_MAX; it++) {
        w->iterations = it + 1;
        for (int i = 0; i < FB_P; i++) {
            double eta[FB_MAXN], v[FB_MAXN];
            fb_propagate(ph->b, &w->W[0][i], FB_NPTS, eta0, v0, f, eta, v);
            fb_eval_node(ph, t0 + tb->c[i] * h, eta, v, contact, &w->node[i]);
        }
        if (contact) {
            double A[FB_P][FB_P], B[FB_P][FB_P];
            contact_response(ph, w, A, B);
            if (ph->mode == FB_MODE_FORCE)
                solve_law(ph, w, A, B);
            else
                solve_constraint(ph, w, A, B, h, g0);
        }
        /* new forcing, how far it moves the step end and how far the forcing itself does (energy norm) */
        double change = 0.0, size = 0.0;
        for (int k = 0; k < N; k++) {
            double de = 0.0, dv = 0.0, fe = 0.0, fv = 0.0;
            for (int j = 0; j < FB_P; j++) {
                double fn = w->node[j].smooth[k] + (contact ? w->node[j].b[k] * w->F[j] : 0.0);
                double df = fn - f[j * N + k];
                f[j * N + k] = fn;
                de += w->W[k][FB_P].RE[j] * df;
                dv += w->W[k][FB_P].RV[j] * df;
                fe += fabs(w->W[k][FB_P].RE[j] * fn);
                fv += fabs(w->W[k][FB_P].RV[j] * fn);
            }
            double om = ph->b->omega[k] > 0.0 ? ph->b->omega[k] : ph->omega_rigid;
            change += om * om * de * de + dv * dv;
            size += om * om * fe * fe + fv * fv;
        }
        if (!isfinite(change)) return -1;
        change = sqrt(change);
        /* converged: the last sweep moved the end by ITER_TOL of the tolerance; or it stagnates at round-off
         * (ROUNDOFF of the forcing's own effect); or it stopped contracting within STAGNATION of the tolerance */
        if (change <= ITER_TOL * tol || change <= ROUNDOFF * sqrt(size) ||
            (it > 0 && change > 0.5 * prev && change <= STAGNATION * tol)) {
            out->converged = 1;
            break;
        }
        prev = change;
    }
    fb_propagate(ph->b, &w->W[0][FB_P], FB_NPTS, eta0, v0, f, out->eta1, out->v1);
    for (int k = 0; k < N; k++)
        if (!isfinite(out->eta1[k]) || !isfinite(out->v1[k])) return -1;
    /* error estimate: the defect of the forcing interpolant at the step end, d = f(t0 + h) - sum_j l_j(1) f_j
     * ~ f^(p) h^p / p! (one more evaluation), propagated as a forcing error: velocity h d / (p + 1), displacement
     * d min(h^2 / ((p + 1)(p + 2)), 2 / w^2).  The collocation end state itself is superconvergent (order 2p),
     * so this estimate is conservative. */
    fb_node *end = &w->end;
    fb_eval_node_acc(ph, t0 + h, out->eta1, out->v1, 1, 1, end);
    double Fe = 0.0;
    if (ph->mode == FB_MODE_FORCE) {
        Fe = fb_law_force(ph->p, -end->delta, -end->rate, NULL, NULL, NULL);
    } else if (ph->mode == FB_MODE_CONSTRAINT) {
        for (int j = 0; j < FB_P; j++) Fe += fb_lagrange(j, 1.0) * w->F[j];
    }
    double e2 = 0.0, lim0 = h * h / ((FB_P + 1.0) * (FB_P + 2.0));
    for (int k = 0; k < N; k++) {
        double d = end->smooth[k] + (contact ? end->b[k] * Fe : 0.0);
        for (int j = 0; j < FB_P; j++) d -= tb->lend[j] * f[j * N + k];
        double om = ph->b->omega[k], lim = om > 0.0 ? fmin(lim0, 2.0 / (om * om)) : lim0;
        double dv = h * fabs(d) / (FB_P + 1.0), de = fabs(d) * lim;
        double ow = om > 0.0 ? om : ph->omega_rigid;
        e2 += ow * ow * de * de + dv * dv;
    }
    tol = fb_tolerance(ph, eta0, v0, out->eta1, out->v1);
    out->err = sqrt(e2) / tol;
    if (ph->mode == FB_MODE_CONSTRAINT) { /* the multiplier is algebraic: hold its interpolant's top term too */
        double L = 0.0, big = w->lambda_scale;
        for (int j = 0; j < FB_P; j++) {
            L += tb->top[j] * w->F[j];
            big = fmax(big, fabs(w->F[j]));
        }
        out->err = fmax(out->err, fabs(L) / (ph->atol + fmax(MULTIPLIER_RTOL * ph->rtol, MULTIPLIER_NOISE) * big));
    }
    return 0;
}
