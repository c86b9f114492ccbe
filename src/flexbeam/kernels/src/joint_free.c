/* A free-flying beam: no joint.  The floating frame sits at the centre of mass G with the mean-axis conditions of
 * the free-free modes (docs/formulation.md, "A free-flying beam").
 *
 * Coordinates [x_G, y_G, theta, q]; the foreshortening is measured from its mean, u_x = -1/2 q^T H(x) q with
 * H(x) = int_0^x Psi'^T Psi' - H_bar, so that G stays at the frame's origin to second order, and the free-free
 * modes satisfy int mu Psi = int mu (x - L/2) Psi = 0.  First-order approximation model (zeroth order: D = H = 0):
 *
 *   M(q) = diag(m, m, J_G + q^T Mc q, M_qq),   Mc = M_qq - D,   M_qq = mu L I
 *   Q    = (0, -m g, -2 theta' q^T Mc q', -K q + theta'^2 Mc q)
 *
 * so that M z'' = Q + J^T F.  Energies T = 1/2 m |R_G'|^2 + 1/2 theta'^2 (J_G + q^T Mc q) + 1/2 q'^T M_qq q',
 * V_e = 1/2 q^T K q, V_g = m g y_G.  A point at rho in the frame is at r = R_G + A(theta) rho; its material
 * coordinate is x = rho_x - r_h with r_h = -L/2 (the model buffer's hub radius): rho_x = x - L/2 on the straight beam.
 * The model buffer's Jc is J_G, m1, s_f, G, d and m_tq are zero (the frame at G, the mean-axis conditions).
 *
 * With axial modes (m->na > 0; the flexible coordinates [q, p]) axial.c adds their terms (free-free modes: s_a = 0).
 *
 * Parameters jp: [m] (the beam's mass; flexbeam.model.joints.free packs it).
 */
#include <string.h>

#include "flexbeam.h"

#define MAXZ 66 /* n <= 62 modes, x_G, y_G, theta, and a support coordinate */
#define MASS(m) ((m)->jp[0])

static int free_unpack(fb_model *m) {
    if (m->njp != 1 || !(MASS(m) > 0.0) || m->n > 62) return -1;
    m->nrigid = 3;
    m->ngiven = 0;
    return 0;
}

static void free_split(const fb_model *m, double t, const double *z, const double *zd, fb_frame *f, const double **q,
                       const double **qd) {
    (void)t;
    f->R[0] = z[0];
    f->R[1] = z[1];
    f->th = z[2];
    f->Rd[0] = zd[0];
    f->Rd[1] = zd[1];
    f->thd = zd[2];
    f->thdd = 0.0;
    f->field[0] = 0.0;
    f->field[1] = -m->g;
    f->rO[0] = f->rO[1] = f->vO[0] = f->vO[1] = f->aO[0] = f->aO[1] = 0.0;
    *q = z + 3;
    *qd = zd + 3;
}

static double free_torque(const fb_model *m, double t) {
    (void)m;
    (void)t;
    return 0.0;
}

static void free_mass(const fb_model *m, const double *q, double *M) {
    int n = m->n, nb = fb_nb(m), N = n + 3;
    memset(M, 0, sizeof(double) * (size_t)N * N);
    M[0] = MASS(m);
    M[N + 1] = MASS(m);
    M[2 * N + 2] = m->Jc + fb_quad(m->Mc, q, nb);
    for (int i = 0; i < nb; i++)
        for (int j = 0; j < nb; j++) M[(i + 3) * N + j + 3] = m->Mqq[i * nb + j];
    if (m->na) fb_axial_mass(m, q, 2, M);
}

/* Q of the equations (elastic: with the elastic force -K q); returns q^T Mc q (the theta-theta mass change).  The
 * drive's tau does not exist (a free beam has no joint): it is ignored. */
static double free_forces(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double tau,
                          int elastic, double *Q) {
    (void)tau;
    int n = fb_nb(m);
    double thd = f->thd, qMcqd = 0.0, qMcq = 0.0, mcq[MAXZ];
    fb_symv(m->Mc, q, n, mcq);
    for (int i = 0; i < n; i++) {
        qMcqd += mcq[i] * qd[i];
        qMcq += mcq[i] * q[i];
        Q[i + 3] = thd * thd * mcq[i];
    }
    if (elastic) {
        double kq[MAXZ];
        fb_symv(m->K, q, n, kq);
        for (int i = 0; i < n; i++) Q[i + 3] -= kq[i];
    }
    Q[0] = 0.0;
    Q[1] = -MASS(m) * m->g;
    Q[2] = -2.0 * thd * qMcqd;
    if (m->na) { /* axial.c (free-free modes: s_a = 0, gravity acts on y_G alone) */
        Q[2] += fb_axial_forces(m, thd, q, qd, elastic, Q + 3);
        for (int k = 0; k < m->na; k++) qMcq += (2.0 * m->mta[k] + m->Maa[k] * q[n + k]) * q[n + k];
    }
    return qMcq;
}

static void free_energies(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double *T,
                          double *Ve, double *Vg) {
    int n = fb_nb(m);
    double thd = f->thd;
    *T = 0.5 * MASS(m) * (f->Rd[0] * f->Rd[0] + f->Rd[1] * f->Rd[1]) +
         0.5 * thd * thd * (m->Jc + fb_quad(m->Mc, q, n)) + 0.5 * fb_quad(m->Mqq, qd, n);
    *Ve = 0.5 * fb_quad(m->K, q, n);
    *Vg = MASS(m) * m->g * f->R[1];
    if (m->na) fb_axial_energies(m, thd, q, qd, T, Ve);
}

/* r = R + A(theta) rho, v = R' + A (rho' + theta' e3 x rho), a0 = A (acc + 2 theta' e3 x rho' - theta'^2 rho) (R''
 * is a coordinate acceleration, not a velocity product); dr/dR = I, dr/dtheta = A e3 x rho, dr/dq = A drho. */
static void free_place(const fb_model *m, const fb_frame *f, const fb_body_kin *bk, const double *drho, fb_kin *out,
                       double *dr) {
    int n = m->n, N = n + 3;
    double ct, st, thd = f->thd, rx = bk->rho[0], ry = bk->rho[1];
    fb_sincos(f->th, &st, &ct);
    if (dr) {
        for (int i = 0; i < n; i++) {
            double dx = drho[i], dy = drho[n + i];
            dr[i + 3] = ct * dx - st * dy;
            dr[N + i + 3] = st * dx + ct * dy;
        }
        dr[0] = 1.0;
        dr[1] = 0.0;
        dr[N] = 0.0;
        dr[N + 1] = 1.0;
        dr[2] = ct * (-ry) - st * rx;
        dr[N + 2] = st * (-ry) + ct * rx;
    }
    out->rel[0] = ct * rx - st * ry;
    out->rel[1] = st * rx + ct * ry;
    out->r[0] = f->R[0] + out->rel[0];
    out->r[1] = f->R[1] + out->rel[1];
    double vlx = bk->rhod[0] - thd * ry, vly = bk->rhod[1] + thd * rx;
    out->v[0] = f->Rd[0] + (ct * vlx - st * vly);
    out->v[1] = f->Rd[1] + (st * vlx + ct * vly);
    double alx = bk->acc[0] - 2.0 * thd * bk->rhod[1] - thd * thd * rx;
    double aly = bk->acc[1] + 2.0 * thd * bk->rhod[0] - thd * thd * ry;
    out->a0[0] = ct * alx - st * aly;
    out->a0[1] = st * alx + ct * aly;
}

/* A(theta)^T (p - R) for a point, A(theta)^T p for a direction. */
static void free_to_body(const fb_model *m, const fb_frame *f, const double *p, int direction, double *out) {
    (void)m;
    double ct, st, px = p[0], py = p[1];
    fb_sincos(f->th, &st, &ct);
    if (!direction) {
        px -= f->R[0];
        py -= f->R[1];
    }
    out[0] = ct * px + st * py;
    out[1] = -st * px + ct * py;
}

/* No hub: the frame's angle (the outputs' theta columns). */
static void free_hub(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double *phi,
                     double *phid) {
    (void)m;
    (void)q;
    (void)qd;
    *phi = f->th;
    *phid = f->thd;
}

static double free_work_angle(const fb_model *m, const double *z) {
    (void)m;
    return z[2];
}

static double free_power(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double torque) {
    (void)m;
    (void)q;
    (void)qd;
    return torque * f->thd;
}

static double free_rate_bound(const fb_model *m, double t0, double t1) {
    (void)m;
    (void)t0;
    (void)t1;
    return 0.0;
}

static void free_given_acc(const fb_model *m, const fb_frame *f, double *acc) {
    (void)m;
    (void)f;
    (void)acc;
}

/* |dr/dx_G| = |dr/dy_G| = 1, |dr/dtheta| = |rho| <= reach (the reach about G: half the length and more). */
static void free_rigid_bound(const fb_model *m, double reach, double *env) {
    (void)m;
    env[0] = 1.0;
    env[1] = 1.0;
    env[2] = reach;
}

/* M0 = diag(m, m, J_G, mu L I) is diagonal: row0 = e_theta^T M0^-1 has no modal part. */
static int free_row0_coupled(const fb_model *m, const fb_basis *b) {
    (void)m;
    (void)b;
    return 0;
}

/* R = M0 M^-1 Q with M(q) = M0 + ds e2 e2^T (e2: theta's row): M0 M^-1 x = x - c e2 (row0 . x),
 * c = ds / (1 + ds (M0^-1)_22); row0 = e2^T M0^-1 and (M0^-1)_22 are the basis buffer's row0 and inv00. */
static double free_remainder(const fb_model *m, const fb_basis *b, int row0_q, const fb_frame *f, const double *q,
                             const double *Q, double ds, fb_update *up, double *R) {
    (void)row0_q;
    (void)f;
    if (m->na) return fb_axial_remainder(m, b, 2, q, Q, ds, up, R);
    int nz = b->nz;
    double c = ds / (1.0 + ds * b->inv00);
    up->c = c;
    up->active = c != 0.0;
    up->rank2 = 0;
    up->row = 2;
    double r0 = 0.0;
    for (int i = 0; i < nz; i++) r0 += b->row0[i] * Q[i];
    for (int i = 0; i < nz; i++) R[i] = Q[i];
    R[2] -= c * r0;
    return c;
}

static void free_correct(const fb_model *m, const fb_basis *b, const fb_update *up, double *x) {
    (void)m;
    if (up->rank2) {
        fb_axial_correct(b, up, x);
        return;
    }
    double c = up->c, r0 = 0.0;
    for (int i = 0; i < b->nz; i++) r0 += b->row0[i] * x[i];
    x[2] -= c * r0;
}

const fb_joint_ops fb_joint_free = {
    .unpack = free_unpack,
    .split = free_split,
    .torque = free_torque,
    .mass = free_mass,
    .forces = free_forces,
    .energies = free_energies,
    .place = free_place,
    .to_body = free_to_body,
    .work_angle = free_work_angle,
    .hub = free_hub,
    .power = free_power,
    .rate_bound = free_rate_bound,
    .given_acc = free_given_acc,
    .rigid_bound = free_rigid_bound,
    .row0_coupled = free_row0_coupled,
    .remainder = free_remainder,
    .correct = free_correct,
};
