/* The right-hand side of the reference integrator (scipy's DOP853 on the state vector) and the output columns,
 * from the equations of model.c (docs/formulation.md). */
#include <string.h>

#include "rhs.h"

/* sum over the given coordinates g of M[row][g] acc[g]: the force the given accelerations ask of a row. */
static double given_force(const double *M, int N, int ng, int row, const double *acc) {
    double f = 0.0;
    for (int g = 0; g < ng; g++) f += M[row * N + g] * acc[g];
    return f;
}

/* A (nn x nn, nn = N - off) = the rows and columns of M from off on: the block of the coordinates solved for. */
static void free_block(const double *M, int N, int off, double *A) {
    int nn = N - off;
    for (int i = 0; i < nn; i++)
        for (int j = 0; j < nn; j++) A[i * nn + j] = M[(i + off) * N + j + off];
}

/* The state at t and the equations without the contacts: the mass matrix M, the forces Q with the drive's torque
 * (returned), the given coordinates' accelerations and the support's spring and damper force. */
static double assemble(rhs_eval *e, const fb_model *m, const fb_contacts *c, double t, const double *y) {
    const fb_joint_ops *jt = fb_joint(m);
    int nb = 2 * fb_nz(m);
    e->m = m;
    e->c = c;
    e->jt = jt;
    e->N = fb_nfull(m);
    e->ng = m->ngiven;
    fb_state_split(m, t, y, &e->fr, &e->q, &e->qd);
    jt->given_acc(m, &e->fr, e->ga);
    e->o = m->nobstacles ? &m->obstacles[0] : NULL;
    e->compliant = fb_compliant(m);
    e->s = e->compliant ? y[nb] : 0.0;
    e->sd = e->compliant ? y[nb + 1] : 0.0;
    e->Fsup = e->compliant ? -e->o->ks * e->s - e->o->cs * e->sd : 0.0; /* the force on the support's mass */
    if (e->compliant && fb_base_moving(m)) e->Fsup += fb_support_base_force(m, &e->fr); /* carried by the base */
    double tau = jt->torque(m, t);
    jt->mass(m, e->q, e->M);
    jt->forces(m, &e->fr, e->q, e->qd, tau, 1, e->Q);
    e->damping = fb_damping_force(m, e->qd, e->Q, m->nrigid); /* the beam's structural damping (damped.c) */
    return tau;
}


/* The pairs in contact: their gaps and Jacobians; the law force of each FB_MODE_FORCE pair acts as J_k^T F_k (and
 * Js_k F_k on the support), its damping dissipates, its friction acts (law_friction); the FB_MODE_CONSTRAINT pairs
 * are listed for the solve. */
static void pair_forces(rhs_eval *e) {
    const fb_contacts *c = e->c;
    int N = e->N;
    e->diss = 0.0;
    e->ncon = e->nstick = 0;
    for (int k = 0; k < e->m->npairs; k++) {
        e->F[k] = 0.0;
        if (c->mode[k] == FB_MODE_NONE) continue;
        if (fb_rough(c, k))
            e->gp[k] = fb_pair_tangent(e->m, k, &e->fr, e->q, e->qd, e->s, e->sd, 1, e->J[k], e->Jt[k], &e->vt[k]);
        else
            e->gp[k] = fb_pair_gap(e->m, k, &e->fr, e->q, e->qd, e->s, e->sd, 1, e->J[k]);
        if (c->mode[k] == FB_MODE_CONSTRAINT) {
            e->con[e->ncon++] = k;
            continue;
        }
        const fb_gap *g = &e->gp[k];
        double fk;
        e->F[k] = fb_law_force(c->p[k], -g->delta, -g->rate, &fk, NULL, NULL);
        e->diss += (e->F[k] - fk) * (-g->rate);
        for (int i = 0; i < N; i++) e->Q[i] += e->J[k][i] * e->F[k];
        e->Fsup += g->Js * e->F[k];
        if (fb_rough(c, k)) rhs_law_friction(e, k);
    }
}

/* The constrained pairs' multipliers: [M D^T; J_c 0][z''; -lambda] = [Q; -gamma - 2 alpha delta' - beta^2 delta]
 * on the free rows (the given coordinates' accelerations known), by W = J_c A^-1 D^T over the free block A of M
 * (plus Js Js / m_s with a compliant support); the forces join Q and the support's force.  D = J_c without friction;
 * with Coulomb friction (CCM, friction.c) a slipping pair's force acts along J + sigma Jt (a non-symmetric W) and a
 * sticking pair adds the row Jt z'' = -gamma_t - 2 alpha v_t of its tangential multiplier (rough_rows).  -1 if a
 * system is singular. */
static int constraint_forces(rhs_eval *e) {
    const fb_contacts *c = e->c;
    const double *M = e->M, *ga = e->ga;
    int N = e->N, ng = e->ng, off = ng, nn = N - off, nr = e->ncon;
    double a[MAXZ], B[2 * FB_MAX_PAIRS][MAXZ], W[4 * FB_MAX_PAIRS * FB_MAX_PAIRS], r[2 * FB_MAX_PAIRS];
    double A[MAXZ * MAXZ];
    fb_row rows[2 * FB_MAX_PAIRS];
    for (int ia = 0; ia < e->ncon; ia++) {
        int k = e->con[ia];
        const fb_gap *g = &e->gp[k];
        rows[ia] = (fb_row){k, 0, e->J[k], e->J[k], g->Js, g->Js,
                            -g->gamma - 2.0 * c->alpha * g->rate - c->beta * c->beta * g->delta};
    }
    if (c->friction) nr = rhs_rough_rows(e, rows);
    for (int i = 0; i < nn; i++) a[i] = e->Q[i + off] - given_force(M, N, ng, i + off, ga);
    free_block(M, N, off, A);
    if (nn > 0 && fb_solve(A, a, nn)) return -1;
    for (int ia = 0; ia < nr; ia++) {
        for (int i = 0; i < nn; i++) B[ia][i] = rows[ia].col[i + off];
        free_block(M, N, off, A);
        if (nn > 0 && fb_solve(A, B[ia], nn)) return -1;
    }
    for (int ia = 0; ia < nr; ia++) {
        const double *Jk = rows[ia].row;
        r[ia] = rows[ia].target - fb_dot(Jk + off, a, nn);
        for (int g = 0; g < ng; g++) r[ia] -= Jk[g] * ga[g];
        if (e->compliant) r[ia] -= rows[ia].row_s * e->Fsup / e->o->ms;
        for (int ib = 0; ib < nr; ib++) {
            double wab = fb_dot(Jk + off, B[ib], nn);
            if (e->compliant) wab += rows[ia].row_s * rows[ib].col_s / e->o->ms;
            W[ia * nr + ib] = wab;
        }
    }
    if (fb_solve(W, r, nr)) return -1;
    for (int ia = 0; ia < nr; ia++) {
        int k = rows[ia].pair;
        if (rows[ia].tangential)
            e->Ft[k] = r[ia];
        else
            e->F[k] = r[ia];
        for (int i = 0; i < N; i++) e->Q[i] += rows[ia].col[i] * r[ia];
        e->Fsup += rows[ia].col_s * r[ia];
    }
    if (c->friction) rhs_rough_dissipation(e);
    return 0;
}

/* The coordinates' rates and accelerations (dy's first rows) from M z'' = Q with the contact forces, the joint's
 * torque and the energy balance's rates (dy's last two).  With given coordinates the free rows are solved with the
 * given accelerations, and the joint's reaction torque is the given rows' residual; otherwise the torque is the
 * drive's tau.  -1 if M is singular. */
static int accelerations(rhs_eval *e, double tau, const double *y, double *dy, double *torque) {
    const fb_model *m = e->m;
    int N = e->N, ng = e->ng, size = fb_state_size(m);
    double *M = e->M, *Q = e->Q;
    if (ng) { /* the free rows with the given accelerations; the reaction is the given rows' residual */
        int nn = N - ng;
        double rhs[MAXZ], A[MAXZ * MAXZ];
        for (int i = 0; i < nn; i++) rhs[i] = Q[i + ng] - given_force(M, N, ng, i + ng, e->ga);
        free_block(M, N, ng, A);
        if (nn > 0 && fb_solve(A, rhs, nn)) return -1;
        double reaction = given_force(M, N, ng, 0, e->ga) - Q[0];
        for (int i = 0; i < nn; i++) {
            reaction += M[i + ng] * rhs[i];
            dy[i] = y[nn + i];
            dy[nn + i] = rhs[i];
        }
        dy[size - 2] = e->diss;
        dy[size - 1] = e->jt->power(m, &e->fr, e->q, e->qd, reaction);
        *torque = reaction;
    } else {
        if (fb_solve(M, Q, N)) return -1;
        for (int i = 0; i < N; i++) dy[i] = y[N + i];
        for (int i = 0; i < N; i++) dy[N + i] = Q[i];
        dy[size - 2] = e->diss;
        *torque = tau;
        dy[size - 1] = e->jt->power(m, &e->fr, e->q, e->qd, tau);
    }
    return 0;
}

/* The state's equations and the contact forces at (t, y) into e (assemble, pair_forces, constraint_forces), the
 * drive's torque in *tau.  -1 for a non-finite state or a singular system. */
static int contact_state(rhs_eval *e, const fb_model *m, double t, const double *y, const fb_contacts *c,
                         double *tau) {
    for (int i = 0; i < fb_state_size(m); i++)
        if (!isfinite(y[i])) return -1;
    *tau = assemble(e, m, c, t, y);
    pair_forces(e);
    if (m->Cd) e->diss += e->damping;
    return (e->ncon || e->nstick) && constraint_forces(e) ? -1 : 0;
}

/* Right-hand side dy/dt of the reference-layout state with the contacts c (see flexbeam.kernels.rhs), pair k:
 * FB_MODE_FORCE: the law force F_k(d_k, d_k') of p_k acts as J_k^T F_k;
 * FB_MODE_CONSTRAINT: the multipliers of [M J_c^T; J_c 0][z''; -lambda] = [Q; -gamma - 2 alpha delta' - beta^2 delta]
 * over the constrained pairs c (Baumgarte).  A compliant support (obstacle 0) adds m_s s'' = -k_s s - c_s s' +
 * sum_k Js_k F_k over the pairs on it.  The coordinates the joint gives as functions of time (theta(t) prescribed)
 * are not solved for: the other rows are, and the joint's reaction is the given rows' residual.  F (npairs) returns
 * each pair's force.  Returns 0, or -1 for a non-finite state or a singular system (dy then NaN). */
int fb_rhs(const fb_model *m, double t, const double *y, const fb_contacts *c, double *dy, double *F_out,
           double *torque_out) {
    int size = fb_state_size(m), nb = 2 * fb_nz(m), S = m->npairs;
    rhs_eval e;
    double tau, torque;
    if (contact_state(&e, m, t, y, c, &tau)) goto fail;
    if (e.compliant) {
        dy[nb] = e.sd;
        dy[nb + 1] = e.Fsup / e.o->ms;
        e.diss += e.o->cs * e.sd * e.sd;
    }
    if (accelerations(&e, tau, y, dy, &torque)) goto fail;
    if (fb_base_moving(m)) /* the base's work and the ground obstacles' (base_motion.c) */
        dy[size - 1] += fb_base_power(m, t, &e.fr, e.q, e.qd, e.sd) + fb_ground_rate(m, &e.fr, c->mode, e.F, e.gp);
    if (F_out)
        for (int k = 0; k < S; k++) F_out[k] = e.F[k];
    if (torque_out) *torque_out = torque;
    return 0;
fail:
    for (int i = 0; i < size; i++) dy[i] = NAN;
    if (F_out)
        for (int k = 0; k < S; k++) F_out[k] = NAN;
    if (torque_out) *torque_out = NAN;
    return -1;
}

/* The contact forces at (t, y) under the contacts c, as fb_rhs solves them: F (npairs) the normal forces -- a law
 * pair's force, a held pair's multiplier -- and Ft (npairs) the sticking pairs' tangential multipliers lambda_t, of
 * their rows Jt z'' = -gamma_t - 2 alpha v_t (0 for the other pairs): the multipliers a stick phase starts with at
 * (t, y) (methods/stick_start.py).  Returns 0, or -1 for a non-finite state or a singular system. */
int fb_contact_forces(const fb_model *m, double t, const double *y, const fb_contacts *c, double *F, double *Ft) {
    rhs_eval e;
    double tau;
    if (contact_state(&e, m, t, y, c, &tau)) return -1;
    for (int k = 0; k < m->npairs; k++) {
        F[k] = e.F[k];
        Ft[k] = c->friction && c->stick[k] && c->mode[k] != FB_MODE_NONE ? e.Ft[k] : 0.0;
    }
    return 0;
}

double fb_tip_deflection_at(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double sphi,
                            double cphi) {
    fb_kin tip = {.want_acc = 0};
    fb_point_kinematics(m, &m->points[1], f, q, qd, &tip, NULL);
    return -sphi * tip.rel[0] + cphi * tip.rel[1]; /* the tip from the frame's origin, in the hub's normal */
}

double fb_tip_deflection(const fb_model *m, const fb_frame *f, const double *q, const double *qd) {
    double phi, phid, sphi, cphi;
    fb_joint(m)->hub(m, f, q, qd, &phi, &phid);
    fb_sincos(phi, &sphi, &cphi);
    return fb_tip_deflection_at(m, f, q, qd, sphi, cphi);
}

/* Output columns (FB_NCOLS per sample, see flexbeam.kernels.OUTPUT_COLUMNS: gap, normal velocity and contact
 * force are the first pair's, the contact energy all pairs'), the normal velocities of the measuring points
 * (points[2:]) and per pair [gap, rate, force] (pcols, FB_PAIR_COLS x npairs per sample) for reference-layout
 * states Y at times T, all with the contacts c. */
void fb_outputs(const fb_model *m, const double *T, const double *Y, int count, const fb_contacts *c, double *cols,
                double *mv, double *pcols) {
    const fb_joint_ops *jt = fb_joint(m);
    int size = fb_state_size(m), nb = 2 * fb_nz(m), nmeas = m->nmeasure, S = m->npairs;
    int compliant = fb_compliant(m), held = 0;
    const fb_obstacle *o = m->nobstacles ? &m->obstacles[0] : NULL;
    for (int k = 0; k < S; k++) held |= c->mode[k] == FB_MODE_CONSTRAINT;
    double dy[2 * MAXZ + 4], F[FB_MAX_PAIRS];
    for (int i = 0; i < count; i++) {
        const double *y = Y + (size_t)i * size;
        double *out = cols + (size_t)i * FB_NCOLS, *pc = pcols + (size_t)i * S * FB_PAIR_COLS;
        double t = T[i];
        fb_frame fr;
        const double *q, *qd;
        fb_state_split(m, t, y, &fr, &q, &qd);
        double s = compliant ? y[nb] : 0.0, sd = compliant ? y[nb + 1] : 0.0;
        double Uc = 0.0, torque = jt->torque(m, t);
        fb_gap gp[FB_MAX_PAIRS];
        for (int k = 0; k < S; k++) {
            gp[k] = fb_pair_gap(m, k, &fr, q, qd, s, sd, 0, NULL);
            F[k] = 0.0;
            if (c->mode[k] == FB_MODE_FORCE) {
                F[k] = fb_law_force(c->p[k], -gp[k].delta, -gp[k].rate, NULL, NULL, NULL);
                Uc += fb_law_potential(c->p[k], -gp[k].delta);
            }
        }
        if (m->ngiven || held) fb_rhs(m, t, y, c, dy, F, &torque);
        double Tk, Ve, Vg;
        jt->energies(m, &fr, q, qd, &Tk, &Ve, &Vg);
        if (compliant) {
            Tk += 0.5 * o->ms * sd * sd;
            Ve += 0.5 * o->ks * s * s;
        }
        double phi, phid;
        jt->hub(m, &fr, q, qd, &phi, &phid);
        double sphi, cphi;
        fb_sincos(phi, &sphi, &cphi);
        double e2x = -sphi, e2y = cphi; /* the hub's normal */
        out[0] = phi;
        out[1] = phid;
        out[2] = S ? gp[0].delta : INFINITY;
        out[3] = S ? gp[0].rate : 0.0;
        out[4] = S ? F[0] : 0.0;
        out[5] = Uc;
        out[6] = Tk;
        out[7] = Ve;
        out[8] = Vg;
        out[9] = y[size - 2];
        out[10] = y[size - 1];
        out[11] = torque;
        out[FB_COL_TIP] = fb_tip_deflection_at(m, &fr, q, qd, sphi, cphi);
        out[13] = s;
        out[14] = compliant ? -(o->ks * s + o->cs * sd) : 0.0;
        for (int k = 0; k < S; k++) {
            pc[FB_PAIR_COLS * k] = gp[k].delta;
            pc[FB_PAIR_COLS * k + 1] = gp[k].rate;
            pc[FB_PAIR_COLS * k + 2] = F[k];
            pc[FB_PAIR_COLS * k + 3] = gp[k].x;
        }
        for (int j = 0; j < nmeas; j++) {
            fb_kin kin = {.want_acc = 0};
            fb_point_kinematics(m, &m->points[2 + j], &fr, q, qd, &kin, NULL);
            mv[(size_t)i * nmeas + j] = e2x * kin.v[0] + e2y * kin.v[1];
        }
    }
}
