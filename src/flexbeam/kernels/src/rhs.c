/* The right-hand side of the reference integrator (scipy's DOP853 on the state vector) and the output columns,
 * from the equations of model.c (docs/formulation.md). */
#include <string.h>

#include "flexbeam.h"

#define MAXZ 66 /* n <= 64 modes, theta, and a support coordinate */

static double dot(const double *a, const double *b, int n) {
    double acc = 0.0;
    for (int i = 0; i < n; i++) acc += a[i] * b[i];
    return acc;
}

/* Right-hand side dy/dt of the reference-layout state in a contact mode (see flexbeam.kernels.rhs):
 * FB_MODE_FORCE: the law force F(d, d') of p = [K, n, chi/d'_0, C] acts as J^T F;
 * FB_MODE_CONSTRAINT: the multiplier of [M J^T; J 0][z''; -lambda] = [Q; -gamma - 2 alpha delta' - beta^2 delta]
 * with p = [alpha, beta, ., .] (Baumgarte).  A compliant support adds m_s s'' = -k_s s - c_s s' + Js F.
 * With theta(t) prescribed only the modal rows are solved and the joint torque is the theta row's residual.
 * Returns 0, or -1 for a non-finite state or a singular system (dy then NaN). */
int fb_rhs(const fb_model *m, double t, const double *y, int mode, const double *p, double *dy, double *F_out,
           double *torque_out) {
    int n = m->n, N = n + 1, size = fb_state_size(m), nb = 2 * fb_nz(m);
    for (int i = 0; i < size; i++)
        if (!isfinite(y[i])) goto fail;
    double th, thd, thdd;
    const double *q, *qd;
    fb_state_split(m, t, y, &th, &thd, &thdd, &q, &qd);
    const fb_obstacle *o = m->nobstacles ? &m->obstacles[0] : NULL;
    int compliant = fb_compliant(m);
    double s = compliant ? y[nb] : 0.0, sd = compliant ? y[nb + 1] : 0.0;
    double Fs = compliant ? -o->ks * s - o->cs * sd : 0.0;
    double tau = m->prescribed ? 0.0 : fb_drive_torque(m, t);
    double M[MAXZ * MAXZ], Q[MAXZ], J[MAXZ], dr[2 * MAXZ];
    fb_mass_matrix(m, q, M);
    fb_forces(m, th, thd, q, qd, tau, 1, Q);
    double F = 0.0, diss = 0.0, Js = 0.0;
    memset(J, 0, sizeof(double) * N);
    if (mode != FB_MODE_NONE && o) {
        fb_kin k = {.want_acc = 1};
        fb_point_kinematics(m, &m->points[0], th, thd, q, qd, &k, dr);
        fb_gap gp = fb_gap_state(o, &k, dr, N, s, sd, J);
        Js = gp.Js;
        if (mode == FB_MODE_FORCE) {
            double fk;
            F = fb_law_force(p, -gp.delta, -gp.rate, &fk, NULL, NULL);
            diss = (F - fk) * (-gp.rate);
        } else {
            double rhs_c = -gp.gamma - 2.0 * p[0] * gp.rate - p[1] * p[1] * gp.delta, inv_mass = 0.0;
            if (compliant) {
                rhs_c -= Js * Fs / o->ms;
                inv_mass = Js * Js / o->ms;
            }
            double A[MAXZ * MAXZ], a[MAXZ], b[MAXZ];
            int off = m->prescribed ? 1 : 0, nn = N - off;
            if (m->prescribed) rhs_c -= J[0] * thdd;
            for (int i = 0; i < nn; i++) {
                a[i] = Q[i + off] - (m->prescribed ? M[(i + 1) * N] * thdd : 0.0);
                b[i] = J[i + off];
            }
            double A2[MAXZ * MAXZ];
            for (int i = 0; i < nn; i++)
                for (int j = 0; j < nn; j++) A[i * nn + j] = A2[i * nn + j] = M[(i + off) * N + j + off];
            if (nn > 0) {
                if (fb_solve(A, a, nn) || fb_solve(A2, b, nn)) goto fail;
                rhs_c -= dot(J + off, a, nn);
                inv_mass += dot(J + off, b, nn);
            }
            if (inv_mass > 0.0) F = rhs_c / inv_mass;
        }
        for (int i = 0; i < N; i++) Q[i] += J[i] * F;
    }
    if (compliant) {
        dy[nb] = sd;
        dy[nb + 1] = (Fs + Js * F) / o->ms;
        diss += o->cs * sd * sd;
    }
    double torque;
    if (m->prescribed) {
        double rhs[MAXZ], A[MAXZ * MAXZ];
        for (int i = 0; i < n; i++) {
            rhs[i] = Q[i + 1] - M[(i + 1) * N] * thdd;
            for (int j = 0; j < n; j++) A[i * n + j] = M[(i + 1) * N + j + 1];
        }
        if (n > 0 && fb_solve(A, rhs, n)) goto fail;
        torque = M[0] * thdd - Q[0];
        for (int i = 0; i < n; i++) {
            torque += M[i + 1] * rhs[i];
            dy[i] = qd[i];
            dy[n + i] = rhs[i];
        }
        dy[size - 2] = diss;
        dy[size - 1] = torque * thd;
    } else {
        if (fb_solve(M, Q, N)) goto fail;
        dy[0] = thd;
        for (int i = 0; i < n; i++) dy[i + 1] = qd[i];
        for (int i = 0; i < N; i++) dy[N + i] = Q[i];
        dy[size - 2] = diss;
        torque = tau;
        dy[size - 1] = tau * (thd + dot(m->d, qd, n));
    }
    if (F_out) *F_out = F;
    if (torque_out) *torque_out = torque;
    return 0;
fail:
    for (int i = 0; i < size; i++) dy[i] = NAN;
    if (F_out) *F_out = NAN;
    if (torque_out) *torque_out = NAN;
    return -1;
}

/* Output columns (FB_NCOLS per sample, see flexbeam.kernels.OUTPUT_COLUMNS) and the normal velocities of
 * the measuring points (points[2:]) for reference-layout states Y at times T, all in one contact mode. */
void fb_outputs(const fb_model *m, const double *T, const double *Y, int count, int mode, const double *p,
                double *cols, double *mv) {
    int n = m->n, N = n + 1, size = fb_state_size(m), nb = 2 * fb_nz(m), nmeas = m->npoints - 2;
    int compliant = fb_compliant(m);
    const fb_obstacle *o = m->nobstacles ? &m->obstacles[0] : NULL;
    double dr[2 * MAXZ], J[MAXZ], dy[2 * MAXZ + 4];
    for (int k = 0; k < count; k++) {
        const double *y = Y + (size_t)k * size;
        double *out = cols + (size_t)k * FB_NCOLS;
        double t = T[k], th, thd, thdd;
        const double *q, *qd;
        fb_state_split(m, t, y, &th, &thd, &thdd, &q, &qd);
        double s = compliant ? y[nb] : 0.0, sd = compliant ? y[nb + 1] : 0.0;
        double F = 0.0, Uc = 0.0, torque = m->prescribed ? 0.0 : fb_drive_torque(m, t);
        fb_gap gp = {0};
        if (o) {
            fb_kin kin = {.want_acc = 1};
            fb_point_kinematics(m, &m->points[0], th, thd, q, qd, &kin, dr);
            gp = fb_gap_state(o, &kin, dr, N, s, sd, J);
        }
        if (m->prescribed || mode == FB_MODE_CONSTRAINT) {
            fb_rhs(m, t, y, mode, p, dy, &F, &torque);
        } else if (mode == FB_MODE_FORCE) {
            F = fb_law_force(p, -gp.delta, -gp.rate, NULL, NULL, NULL);
        }
        if (mode == FB_MODE_FORCE) Uc = fb_law_potential(p, -gp.delta);
        double Tk, Ve, Vg;
        fb_energies(m, th, thd, q, qd, &Tk, &Ve, &Vg);
        if (compliant) {
            Tk += 0.5 * o->ms * sd * sd;
            Ve += 0.5 * o->ks * s * s;
        }
        double phi = th + dot(m->d, q, n), phid = thd + dot(m->d, qd, n);
        double e2x = -sin(phi), e2y = cos(phi); /* the hub's normal */
        fb_kin tip = {.want_acc = 0};
        fb_point_kinematics(m, &m->points[1], th, thd, q, qd, &tip, NULL);
        out[0] = phi;
        out[1] = phid;
        out[2] = gp.delta;
        out[3] = gp.rate;
        out[4] = F;
        out[5] = Uc;
        out[6] = Tk;
        out[7] = Ve;
        out[8] = Vg;
        out[9] = y[size - 2];
        out[10] = y[size - 1];
        out[11] = torque;
        out[12] = e2x * tip.r[0] + e2y * tip.r[1];
        out[13] = s;
        out[14] = compliant ? -(o->ks * s + o->cs * sd) : 0.0;
        for (int j = 0; j < nmeas; j++) {
            fb_kin kin = {.want_acc = 0};
            fb_point_kinematics(m, &m->points[2 + j], th, thd, q, qd, &kin, NULL);
            mv[(size_t)k * nmeas + j] = e2x * kin.v[0] + e2y * kin.v[1];
        }
    }
}
