/* The right-hand side of the reference integrator (scipy's DOP853 on the state vector) and the output columns,
 * from the equations of model.c (docs/formulation.md). */
#include <string.h>

#include "flexbeam.h"

#define MAXZ 66 /* n <= 64 modes, theta, and a support coordinate */

/* sum over the given coordinates g of M[row][g] acc[g]: the force the given accelerations ask of a row. */
static double given_force(const double *M, int N, int ng, int row, const double *acc) {
    double f = 0.0;
    for (int g = 0; g < ng; g++) f += M[row * N + g] * acc[g];
    return f;
}

/* Right-hand side dy/dt of the reference-layout state with the contacts c (see flexbeam.kernels.rhs), pair k:
 * FB_MODE_FORCE: the law force F_k(d_k, d_k') of p_k acts as J_k^T F_k;
 * FB_MODE_CONSTRAINT: the multipliers of [M J_c^T; J_c 0][z''; -lambda] = [Q; -gamma - 2 alpha delta' - beta^2 delta]
 * over the constrained pairs c (Baumgarte).  A compliant support (obstacle 0) adds m_s s'' = -k_s s - c_s s' +
 * sum_k Js_k F_k over the pairs on it.  The coordinates the joint gives as functions of time (theta(t) prescribed)
 * are not solved for: the other rows are, and the joint's reaction is the given rows' residual.  F (npairs) returns each pair's force.  Returns 0, or -1 for a non-finite state or a
 * singular system (dy then NaN). */
int fb_rhs(const fb_model *m, double t, const double *y, const fb_contacts *c, double *dy, double *F_out,
           double *torque_out) {
    const fb_joint_ops *jt = fb_joint(m);
    int N = fb_nfull(m), size = fb_state_size(m), nb = 2 * fb_nz(m), S = m->npairs, ng = m->ngiven;
    for (int i = 0; i < size; i++)
        if (!isfinite(y[i])) goto fail;
    fb_frame fr;
    const double *q, *qd;
    fb_state_split(m, t, y, &fr, &q, &qd);
    double ga[FB_MAX_JOINT_PARAMS]; /* the given coordinates' accelerations */
    jt->given_acc(m, &fr, ga);
    const fb_obstacle *o = m->nobstacles ? &m->obstacles[0] : NULL;
    int compliant = fb_compliant(m);
    double s = compliant ? y[nb] : 0.0, sd = compliant ? y[nb + 1] : 0.0;
    double Fsup = compliant ? -o->ks * s - o->cs * sd : 0.0; /* the force on the support's mass */
    double tau = jt->torque(m, t);
    double M[MAXZ * MAXZ], Q[MAXZ], J[FB_MAX_PAIRS][MAXZ];
    jt->mass(m, q, M);
    jt->forces(m, &fr, q, qd, tau, 1, Q);
    double F[FB_MAX_PAIRS], diss = 0.0;
    fb_gap gp[FB_MAX_PAIRS];
    int con[FB_MAX_PAIRS], ncon = 0;
    for (int k = 0; k < S; k++) {
        F[k] = 0.0;
        if (c->mode[k] == FB_MODE_NONE) continue;
        gp[k] = fb_pair_gap(m, k, &fr, q, qd, s, sd, 1, J[k]);
        if (c->mode[k] == FB_MODE_CONSTRAINT) {
            con[ncon++] = k;
            continue;
        }
        double fk;
        F[k] = fb_law_force(c->p[k], -gp[k].delta, -gp[k].rate, &fk, NULL, NULL);
        diss += (F[k] - fk) * (-gp[k].rate);
        for (int i = 0; i < N; i++) Q[i] += J[k][i] * F[k];
        Fsup += gp[k].Js * F[k];
    }
    if (ncon) {
        int off = ng, nn = N - off;
        double a[MAXZ], B[FB_MAX_PAIRS][MAXZ], W[FB_MAX_PAIRS * FB_MAX_PAIRS], r[FB_MAX_PAIRS];
        double A[MAXZ * MAXZ];
        for (int i = 0; i < nn; i++) a[i] = Q[i + off] - given_force(M, N, ng, i + off, ga);
        for (int i = 0; i < nn; i++)
            for (int j = 0; j < nn; j++) A[i * nn + j] = M[(i + off) * N + j + off];
        if (nn > 0 && fb_solve(A, a, nn)) goto fail;
        for (int ia = 0; ia < ncon; ia++) {
            for (int i = 0; i < nn; i++) B[ia][i] = J[con[ia]][i + off];
            for (int i = 0; i < nn; i++)
                for (int j = 0; j < nn; j++) A[i * nn + j] = M[(i + off) * N + j + off];
            if (nn > 0 && fb_solve(A, B[ia], nn)) goto fail;
        }
        for (int ia = 0; ia < ncon; ia++) {
            int k = con[ia];
            r[ia] = -gp[k].gamma - 2.0 * c->alpha * gp[k].rate - c->beta * c->beta * gp[k].delta -
                    fb_dot(J[k] + off, a, nn);
            for (int g = 0; g < ng; g++) r[ia] -= J[k][g] * ga[g];
            if (compliant) r[ia] -= gp[k].Js * Fsup / o->ms;
            for (int ib = 0; ib < ncon; ib++) {
                double wab = fb_dot(J[k] + off, B[ib], nn);
                if (compliant) wab += gp[k].Js * gp[con[ib]].Js / o->ms;
                W[ia * ncon + ib] = wab;
            }
        }
        if (fb_solve(W, r, ncon)) goto fail;
        for (int ia = 0; ia < ncon; ia++) {
            int k = con[ia];
            F[k] = r[ia];
            for (int i = 0; i < N; i++) Q[i] += J[k][i] * F[k];
            Fsup += gp[k].Js * F[k];
        }
    }
    if (compliant) {
        dy[nb] = sd;
        dy[nb + 1] = Fsup / o->ms;
        diss += o->cs * sd * sd;
    }
    double torque;
    if (ng) { /* the free rows with the given accelerations; the reaction is the given rows' residual */
        int nn = N - ng;
        double rhs[MAXZ], A[MAXZ * MAXZ];
        for (int i = 0; i < nn; i++) {
            rhs[i] = Q[i + ng] - given_force(M, N, ng, i + ng, ga);
            for (int j = 0; j < nn; j++) A[i * nn + j] = M[(i + ng) * N + j + ng];
        }
        if (nn > 0 && fb_solve(A, rhs, nn)) goto fail;
        torque = given_force(M, N, ng, 0, ga) - Q[0];
        for (int i = 0; i < nn; i++) {
            torque += M[i + ng] * rhs[i];
            dy[i] = y[nn + i];
            dy[nn + i] = rhs[i];
        }
        dy[size - 2] = diss;
        dy[size - 1] = jt->power(m, &fr, q, qd, torque);
    } else {
        if (fb_solve(M, Q, N)) goto fail;
        for (int i = 0; i < N; i++) dy[i] = y[N + i];
        for (int i = 0; i < N; i++) dy[N + i] = Q[i];
        dy[size - 2] = diss;
        torque = tau;
        dy[size - 1] = jt->power(m, &fr, q, qd, tau);
    }
    if (F_out)
        for (int k = 0; k < S; k++) F_out[k] = F[k];
    if (torque_out) *torque_out = torque;
    return 0;
fail:
    for (int i = 0; i < size; i++) dy[i] = NAN;
    if (F_out)
        for (int k = 0; k < S; k++) F_out[k] = NAN;
    if (torque_out) *torque_out = NAN;
    return -1;
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
        fb_kin tip = {.want_acc = 0};
        fb_point_kinematics(m, &m->points[1], &fr, q, qd, &tip, NULL);
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
        out[FB_COL_TIP] = e2x * (tip.r[0] - fr.R[0]) + e2y * (tip.r[1] - fr.R[1]);
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
