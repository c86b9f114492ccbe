/* One step of collocation (Gauss's nodes, Radau IIA's at rest: ph->tb) on the exactly propagated modal equations.
 *
 * Linearising M(z) z'' = Q + J^T F about the undeformed beam at rest gives M0 z'' + K0 z = R with
 *   R = M0 M(z)^-1 (Q + J^T F) + K0 z,
 * which the joint evaluates (joint.h, remainder and correct): for a revolute joint with theta free
 * M(z) = M0 + ds e0 e0^T (ds = q^T Mc q), so by Sherman-Morrison
 *   M0 M^-1 x = x - c e0 (row0 . x),  c = ds / (1 + ds (M0^-1)_00),  row0 = e0^T M0^-1.
 * In modal coordinates z = Psi eta: eta'' + diag(w^2) eta = f = Psi^T R (exact propagation, propagation.c)
 * with f the interpolant of its values at the FB_P nodes, found by fixed-point iteration; the contact
 * forces (CCFM) or multipliers (CCM) of the pairs in contact at the nodes are solved inside each sweep by Newton's
 * method with their exact linear modal response (pairs and nodes together), so a stiff contact needs no small
 * step.  With theta(t) prescribed, z = q and M = M_qq is constant: R = Q_q - m_tq theta''.  A compliant support is
 * one more mode sqrt(m_s) s.
 */
#include <float.h>
#include <string.h>

#include "integrator.h"

#define ITER_MAX 12     /* fixed-point sweeps per step before the step is rejected */
#define ITER_TOL 1e-3   /* converged when the last sweep moved the step end by this much of the tolerance */
#define STAGNATION 1e-2 /* ... or it stops contracting within this much of the tolerance */
#define ROUNDOFF 1e-13  /* ... or it moves the end by less than this of the forcing's own effect (round-off) */
/* The collocated multiplier (CCM) is an algebraic variable the state's error estimate does not see: its
 * interpolant's top Legendre term is held to MULTIPLIER_RTOL rtol of the phase's largest multiplier so far, but not
 * below MULTIPLIER_NOISE, its round-off (the multiplier is a velocity defect divided by the step's response
 * h / m_eff: ~1e-9 relative measured at h ~ 1e-7 s; 1e-7 leaves a margin of 100). */
#define MULTIPLIER_RTOL 100.0
#define MULTIPLIER_NOISE 1e-7
/* A multiplier's term whose effect on the state is below this many ulps of the state's energy norm is its round-off
 * (measured: 500-2500 on a flexible bar held on two stops at steps below 3e-7 s; multiplier_error). */
#define MULTIPLIER_ROUNDOFF 1e4

void fb_phase_init(fb_phase *ph, const fb_model *m, const fb_basis *b, const fb_contacts *c, double rtol,
                   double atol, double omega_rigid) {
    ph->m = m;
    ph->b = b;
    ph->c = *c;
    ph->contact = ph->force = ph->held = 0;
    for (int k = 0; k < c->npairs; k++) {
        ph->force |= c->mode[k] == FB_MODE_FORCE;
        ph->held |= c->mode[k] == FB_MODE_CONSTRAINT;
    }
    ph->contact = ph->force || ph->held;
    ph->rtol = rtol;
    ph->atol = atol;
    ph->omega_rigid = omega_rigid;
    ph->row0_q = fb_joint(m)->row0_coupled(m, b);
    ph->tb = fb_gauss();
}

void fb_eval_node(const fb_phase *ph, double t, const double *eta, const double *v, int want, fb_node *out) {
    fb_eval_node_acc(ph, t, eta, v, want, 0, out);
}

/* As fb_eval_node; ``want_acc``: also the gaps' velocity-product accelerations gamma (an n x n product more each). */
void fb_eval_node_acc(const fb_phase *ph, double t, const double *eta, const double *v, int want, int want_acc,
                      fb_node *out) {
    const fb_model *m = ph->m;
    const fb_basis *b = ph->b;
    const fb_joint_ops *jt = fb_joint(m);
    int N = b->N, nz = b->nz, ng = m->ngiven, compliant = fb_compliant(m);
    double *z = out->z, *zd = out->zd;
    fb_to_physical(b, eta, z);
    fb_to_physical(b, v, zd);
    const double *q, *qd;
    jt->split(m, t, z, zd, &out->frame, &q, &qd);
    out->t = t;
    double Q[FB_MAXN], R[FB_MAXN];
    double ds = jt->forces(m, &out->frame, q, qd, jt->torque(m, t), 0, Q); /* no elastic force */
    fb_damping_force(m, qd, Q, m->nrigid); /* the beam's structural damping, partly given back below */
    fb_update up;
    jt->remainder(m, b, ph->row0_q, &out->frame, q, Q, ds, &up, R);
    double s = 0.0, sd = 0.0;
    if (compliant) {
        const fb_obstacle *o = &m->obstacles[0];
        s = z[N - 1];
        sd = zd[N - 1];
        R[N - 1] = -o->cs * sd; /* the support's dashpot (its spring is in the linear part) */
        if (fb_base_moving(m)) R[N - 1] += fb_support_base_force(m, &out->frame); /* a moving base's -m_s a_O . u */
    }
    fb_damping_return(b, v, R); /* the modes' damping d v is in the propagation's linear part */
    fb_project(b, R, out->smooth);
    if (want == FB_WANT_NONE) return;
    for (int k = 0; k < m->npairs; k++) {
        int active = ph->c.mode[k] != FB_MODE_NONE, jac = active || want == FB_WANT_JM;
        if (!active && want == FB_WANT_ACTIVE) continue;
        int rough = active && fb_rough(&ph->c, k);
        double J[FB_MAXN], Jx[FB_MAXN], Jt[FB_MAXN], vt = 0.0;
        out->gap[k] = rough ? fb_pair_tangent(m, k, &out->frame, q, qd, s, sd, want_acc, J, Jt, &vt)
                            : fb_pair_gap(m, k, &out->frame, q, qd, s, sd, want_acc, jac ? J : NULL);
        if (!jac) continue;
        /* J in the integrator's coordinates: the full ones without the given ([theta, q] or q), then the support */
        for (int i = 0; i < nz; i++) Jx[i] = J[i + ng];
        if (compliant) Jx[N - 1] = out->gap[k].Js;
        fb_project(b, Jx, out->jm[k]);
        if (m->pairs[k].anywhere) { /* its point moves: bound over all surface points, |Psi|^T env */
            double env[FB_MAXN], ez[FB_MAXN];
            fb_anywhere_bound(m, q, env);
            for (int i = 0; i < nz; i++) ez[i] = env[i + ng];
            if (compliant) ez[N - 1] = 1.0;
            fb_project_abs(b, ez, out->jb[k]);
        } else {
            for (int i = 0; i < N; i++) out->jb[k][i] = fabs(out->jm[k][i]);
        }
        if (!active) continue;
        if (up.active) {
            jt->correct(m, b, &up, Jx);
            fb_project(b, Jx, out->b[k]);
        } else {
            memcpy(out->b[k], out->jm[k], sizeof(double) * N);
        }
        if (rough) fb_node_friction(ph, k, Jt, vt, &up, out);
    }
}

/* The gap of pair ``pair`` at a modal state (the point kinematics alone, no forces). */
fb_gap fb_gap_at(const fb_phase *ph, int pair, double t, const double *eta, const double *v) {
    const fb_model *m = ph->m;
    const fb_basis *b = ph->b;
    int N = b->N, compliant = fb_compliant(m);
    double z[FB_MAXN], zd[FB_MAXN];
    fb_frame fr;
    const double *q, *qd;
    fb_to_physical(b, eta, z);
    fb_to_physical(b, v, zd);
    fb_joint(m)->split(m, t, z, zd, &fr, &q, &qd);
    return fb_pair_gap(m, pair, &fr, q, qd, compliant ? z[N - 1] : 0.0, compliant ? zd[N - 1] : 0.0, 0, NULL);
}

static void ensure_weights(const fb_phase *ph, fb_work *w, double h) {
    const fb_tables *tb = ph->tb;
    if (w->h == h && w->tb == tb) return;
    int N = ph->b->N;
    for (int k = 0; k < N; k++) {
        for (int i = 0; i < FB_P; i++) fb_mode_weights(tb, ph->b, k, h, tb->c[i], &w->W[k][i]);
        fb_mode_weights(tb, ph->b, k, h, 1.0, &w->W[k][FB_P]);
    }
    w->h = h;
    w->tb = tb;
}

/* The state error (in units of ``tol``) a multiplier error ``L`` of pair ``l`` makes when it acts over the step as a
 * forcing error along its column b (the end node's): propagated as the forcing interpolant's defect is. */
static double multiplier_effect(const fb_phase *ph, const fb_node *end, int l, int tang, double L, double h,
                                double tol) {
    int N = ph->b->N;
    double e2 = 0.0, lim0 = h * h / ((FB_P + 1.0) * (FB_P + 2.0));
    for (int k = 0; k < N; k++) {
        double d = fabs((tang ? end->bt[l][k] : end->b[l][k]) * L);
        double om = ph->b->omega[k], lim = om > 0.0 ? fmin(lim0, 2.0 / (om * om)) : lim0;
        double dv = h * d / (FB_P + 1.0), de = d * lim, ow = om > 0.0 ? om : ph->omega_rigid;
        e2 += ow * ow * de * de + dv * dv;
    }
    return sqrt(e2) / tol;
}

/* A multiplier is algebraic, unseen by the state's error estimate: the step's error ``err`` raised to its
 * interpolant's top Legendre term L over MULTIPLIER_* of its scale, for each held pair's (CCM) and each sticking
 * pair's tangential one (friction.c) -- unless L moves the step's end state by less than ``noise`` (in units of the
 * tolerance: MULTIPLIER_ROUNDOFF ulps of the state's energy norm; :func:`multiplier_effect`).  Against a compliant
 * support a held pair's L is also held to its effect on the state (multiplier_effect <= 1): the multiplier drives
 * the support's mass, so its error is the support's motion's, where against a rigid obstacle MULTIPLIER_RTOL alone
 * holds the motion within its tolerance (not whatever the multiplier's error: uncontrolled, the seed's onsets moved
 * by 2.7e-6 s, docs/performance.md) (under MULTIPLIER_RTOL alone the calibrated sensor's first contact under CCM
 * dissipated 1.1e-4 more than the reference integrator's, its duration 2.3e-6 longer; with it 1.7e-5 and 2.4e-7,
 * converging with fast_rtol as the rigid stop's CCM does).  A multiplier is a
 * velocity defect over the step's response ~ h / m_eff, so the state's round-off puts ~ m_eff eps |x| / h into its
 * nodal values, which no relative tolerance can hold as the step shrinks: held to it, every step was rejected down
 * to an underflow (a flexible bar held on two stops, fast_rtol 1e-9 and below). */
static double multiplier_error(const fb_phase *ph, const fb_work *w, const fb_node *end, double h, double tol,
                               double xnorm, double err) {
    const fb_tables *tb = ph->tb;
    double noise = MULTIPLIER_ROUNDOFF * DBL_EPSILON * xnorm / tol;
    for (int l = 0; l < ph->c.npairs; l++) {
        if (ph->c.friction && ph->c.stick[l]) {
            double L = 0.0, big = 0.0;
            for (int j = 0; j < FB_P; j++) {
                L += tb->top[j] * w->Ft[l][j];
                big = fmax(big, fmax(fabs(w->Ft[l][j]), w->F[l][j]));
            }
            double e = fabs(L) / (ph->atol + fmax(MULTIPLIER_RTOL * ph->rtol, MULTIPLIER_NOISE) * big);
            if (e > err && multiplier_effect(ph, end, l, 1, L, h, tol) > noise) err = e;
        }
        if (ph->c.mode[l] != FB_MODE_CONSTRAINT) continue;
        double L = 0.0, big = w->lambda_scale;
        for (int j = 0; j < FB_P; j++) {
            L += tb->top[j] * w->F[l][j];
            big = fmax(big, fabs(w->F[l][j]));
        }
        double e = fabs(L) / (ph->atol + fmax(MULTIPLIER_RTOL * ph->rtol, MULTIPLIER_NOISE) * big);
        int compliant = fb_compliant(ph->m);
        double eff = e > err || compliant ? multiplier_effect(ph, end, l, 0, L, h, tol) : 0.0;
        if (e > err && eff > noise) err = e;
        if (compliant && eff > err) err = eff; /* (the support's mass moves under it: held to its effect too) */
    }
    return err;
}

/* The step's error estimate, squared (energy norm): the defect of the forcing interpolant at the step end (w->end,
 * evaluated), d = f(t0 + h) - sum_j l_j(1) f_j ~ f^(p) h^p / p!, propagated as a forcing error: velocity
 * h d / (p + 1), displacement d min(h^2 / ((p + 1)(p + 2)), 2 / w^2).  The collocation end state itself is
 * superconvergent (order 2p), so this estimate is conservative.  Radau's nodes end at the step's end, where the
 * collocation leaves no defect: theirs is taken at the step's start (the last step's end, fb_next_start),
 * d = f(t0) - sum_j l_j(0) f_j, of the same order (the node polynomial's |prod_j c_j| = 0.0286 there against
 * Gauss's 0.0143 at the end; their end state is of order 2p - 1). */
static double defect_error2(const fb_phase *ph, fb_work *w, double t0, double h, const double *eta0, const double *v0,
                            const double *f) {
    const fb_tables *tb = ph->tb;
    int N = ph->b->N, S = ph->c.npairs;
    fb_node *at = w->end;
    const double *ld = tb->lend; /* l_j at the defect's point */
    if (tb->c[FB_P - 1] == 1.0) {
        at = w->start;
        if (!w->start_ok || at->t != t0) /* (else a retry from the same start, or the last step's end: fb_advance) */
            fb_eval_node_acc(ph, t0, eta0, v0, FB_WANT_GAP, 1, at);
        w->start_ok = 1;
        ld = tb->Vinv[0];
    }
    double Fe[FB_MAX_PAIRS], Fte[FB_MAX_PAIRS];
    for (int l = 0; l < S; l++) {
        Fe[l] = Fte[l] = 0.0;
        if (ph->c.friction && ph->c.stick[l])
            for (int j = 0; j < FB_P; j++) Fte[l] += ld[j] * w->Ft[l][j];
        if (ph->c.mode[l] == FB_MODE_FORCE) {
            Fe[l] = fb_law_force(ph->c.p[l], -at->gap[l].delta, -at->gap[l].rate, NULL, NULL, NULL);
        } else if (ph->c.mode[l] == FB_MODE_CONSTRAINT) {
            for (int j = 0; j < FB_P; j++) Fe[l] += ld[j] * w->F[l][j];
        }
        if (!ph->c.stick[l]) Fte[l] = fb_regularised_force(ph, at, l, Fe[l]); /* the regularised law's there */
    }
    double e2 = 0.0, lim0 = h * h / ((FB_P + 1.0) * (FB_P + 2.0));
    for (int k = 0; k < N; k++) {
        double d = at->smooth[k];
        for (int l = 0; l < S; l++) {
            if (ph->c.mode[l] != FB_MODE_NONE) d += at->b[l][k] * Fe[l];
            if (fb_tangential_unknown(&ph->c, l)) d += at->bt[l][k] * Fte[l];
        }
        for (int j = 0; j < FB_P; j++) d -= ld[j] * f[j * N + k];
        double om = ph->b->omega[k], lim = om > 0.0 ? fmin(lim0, 2.0 / (om * om)) : lim0;
        double dv = h * fabs(d) / (FB_P + 1.0), de = fabs(d) * lim;
        double ow = om > 0.0 ? om : ph->omega_rigid;
        e2 += ow * ow * de * de + dv * dv;
    }
    return e2;
}

/* After an accepted step (fb_advance): at Radau's nodes, the model at its end (w->end, evaluated for its error
 * estimate and events) becomes the next step's start, which defect_error2 evaluates -- with the same arguments
 * (t0 + h, the end state), so the same bits -- without evaluating it again (a resting run: -4 % of the kernel).  */
void fb_next_start(const fb_phase *ph, fb_work *w) {
    if (ph->tb->c[FB_P - 1] != 1.0) return;
    fb_node *end = w->end;
    w->end = w->start, w->start = end;
}

/* One step from (eta0, v0) over [t0, t0 + h].  f (FB_P x N) holds the guess of the nodal forcing and returns the
 * converged one, w->F the nodal contact forces.  Returns 0, or -1 for a non-finite state. */
int fb_collocate(const fb_phase *ph, fb_work *w, double t0, double h, const double *eta0, const double *v0,
                 double *f, fb_step *out) {
    const fb_tables *tb = ph->tb;
    int N = ph->b->N, S = ph->c.npairs;
    ensure_weights(ph, w, h);
    double g0[FB_MAX_PAIRS], g0t[FB_MAX_PAIRS];
    for (int k = 0; k < S; k++) {
        if (ph->c.mode[k] == FB_MODE_CONSTRAINT) {
            fb_gap gp = fb_gap_at(ph, k, t0, eta0, v0);
            g0[k] = gp.rate + ph->c.alpha * gp.delta;
        }
        if (ph->c.friction && ph->c.stick[k]) fb_tangent_at(ph, k, t0, eta0, v0, &g0t[k]);
    }
    fb_unknowns u;
    fb_list_unknowns(ph, &u);
    double tol = fb_tolerance(ph, eta0, v0, eta0, v0), prev = INFINITY;
    out->converged = 0;
    for (int it = 0; it < ITER_MAX; it++) {
        w->iterations = it + 1;
        for (int i = 0; i < FB_P; i++) {
            double eta[FB_MAXN], v[FB_MAXN];
            fb_propagate(ph->b, &w->W[0][i], FB_NPTS, eta0, v0, f, eta, v);
            fb_eval_node(ph, t0 + tb->c[i] * h, eta, v, ph->contact ? FB_WANT_ACTIVE : FB_WANT_NONE, &w->node[i]);
        }
        if (u.count) fb_nodal_contacts(ph, w, &u, h, g0, g0t);
        /* new forcing, how far it moves the step end and how far the forcing itself does (energy norm) */
        double change = 0.0, size = 0.0;
        for (int k = 0; k < N; k++) {
            double de = 0.0, dv = 0.0, fe = 0.0, fv = 0.0;
            for (int j = 0; j < FB_P; j++) {
                double fn = w->node[j].smooth[k];
                for (int l = 0; l < S; l++) {
                    if (ph->c.mode[l] != FB_MODE_NONE) fn += w->node[j].b[l][k] * w->F[l][j];
                    if (fb_tangential_unknown(&ph->c, l)) fn += w->node[j].bt[l][k] * w->Ft[l][j];
                }
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
    fb_node *end = w->end;
    fb_eval_node_acc(ph, t0 + h, out->eta1, out->v1, FB_WANT_GAP, 1, end);
    double e2 = defect_error2(ph, w, t0, h, eta0, v0, f);
    tol = fb_tolerance(ph, eta0, v0, out->eta1, out->v1);
    out->err = sqrt(e2) / tol;
    double xnorm = fmax(fb_energy_norm(ph, eta0, v0), fb_energy_norm(ph, out->eta1, out->v1));
    out->err = multiplier_error(ph, w, end, h, tol, xnorm, out->err);
    return 0;
}

/* Values at the next step's nodes (1 + ratio c_i) of the interpolant through the nodal rows of f (N per node)
 * and of each pair's F. */
void fb_extrapolate(const fb_tables *tb, int N, int S, double ratio, double *f, double F[][FB_P]) {
    double L[FB_P][FB_P], g[FB_P * FB_MAXN], G[FB_MAX_PAIRS][FB_P];
    for (int i = 0; i < FB_P; i++)
        for (int j = 0; j < FB_P; j++) L[i][j] = fb_lagrange(tb, j, 1.0 + ratio * tb->c[i]);
    for (int i = 0; i < FB_P; i++) {
        for (int k = 0; k < S; k++) G[k][i] = 0.0;
        for (int q = 0; q < N; q++) g[i * N + q] = 0.0;
        for (int j = 0; j < FB_P; j++) {
            for (int k = 0; k < S; k++) G[k][i] += L[i][j] * F[k][j];
            for (int q = 0; q < N; q++) g[i * N + q] += L[i][j] * f[j * N + q];
        }
    }
    memcpy(f, g, sizeof(double) * FB_P * N);
    for (int k = 0; k < S; k++) memcpy(F[k], G[k], sizeof(double) * FB_P);
}
