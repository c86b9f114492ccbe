/* The revolute joint at a fixed point O: the floating frame turns by theta about O (docs/formulation.md).
 *
 * Coordinates [theta, q]; the drive leaves theta free, applies a constant torque tau (on the hub angle
 * phi = theta + d q) or prescribes theta(t) (then theta is given: the state holds q only, and the joint torque is
 * an output).  First-order approximation model (zeroth order: D = G = H = 0, so Mc = M_ff):
 *
 *   M(q) = [[Jc + q^T Mc q, m_tq^T], [m_tq, M_qq]]
 *   Q_theta = tau - 2 theta' q^T Mc q' - g [cos(theta)(m1 - 1/2 q^T G q) - sin(theta) s_f q]
 *   Q_q     = -K q + theta'^2 Mc q - g [cos(theta) s_f - sin(theta) G q] + tau d
 *
 * so that M z'' = Q + J^T F.  Energies T = 1/2 z'^T M z', V_e = 1/2 q^T K q,
 * V_g = g [sin(theta)(m1 - 1/2 q^T G q) + cos(theta) s_f q].  A point at rho in the frame is at r = A(theta) rho.
 *
 * With axial modes (m->na > 0; the flexible coordinates [q, p]) axial.c adds their terms: the fixed-free modes'
 * centrifugal forcing and stiffening, the theta row's S^T p and -S q, gravity through s_a p.
 *
 * Parameters jp: [drive (0 free, 1 torque, 2 prescribed), profile (0 constant rate, 1 Kane's spin-up), torque,
 * spin rate, spin-up time, theta0] (flexbeam.model.joints.revolute packs them).
 */
#include <string.h>

#include "flexbeam.h"

#define MAXZ 66 /* n <= 64 modes, theta, and a support coordinate */

enum { DRIVE_FREE = 0, DRIVE_TORQUE = 1, DRIVE_PRESCRIBED = 2 };
enum { PROFILE_CONSTANT = 0, PROFILE_KANE = 1 };
#define DRIVE(m) ((int)(m)->jp[0])
#define PROFILE(m) ((int)(m)->jp[1])
#define TORQUE(m) ((m)->jp[2])
#define SPIN_RATE(m) ((m)->jp[3])
#define SPIN_UP_TIME(m) ((m)->jp[4])
#define THETA0(m) ((m)->jp[5])

static int rev_unpack(fb_model *m) {
    if (m->njp < 6 || fb_base_unpack(m) || DRIVE(m) < DRIVE_FREE || DRIVE(m) > DRIVE_PRESCRIBED || PROFILE(m) < PROFILE_CONSTANT ||
        PROFILE(m) > PROFILE_KANE)
        return -1;
    m->nrigid = 1;
    m->ngiven = DRIVE(m) == DRIVE_PRESCRIBED;
    return 0;
}

/* theta, theta', theta'' of a prescribed profile: constant rate, or Kane, Ryan & Banerjee (1987) eq. 57. */
static void rev_motion(const fb_model *m, double t, double *th, double *thd, double *thdd) {
    double W = SPIN_RATE(m);
    if (PROFILE(m) == PROFILE_CONSTANT) {
        *th = THETA0(m) + W * t; *thd = W; *thdd = 0.0;
        return;
    }
    double Ts = SPIN_UP_TIME(m);
    if (t < Ts) {
        double a = 2.0 * FB_PI / Ts;
        double sa, ca;
        fb_sincos(a * t, &sa, &ca);
        *th = THETA0(m) + (W / Ts) * (0.5 * t * t + (ca - 1.0) / (a * a));
        *thd = (W / Ts) * (t - sa / a);
        *thdd = (W / Ts) * (1.0 - ca);
        return;
    }
    *th = THETA0(m) + W * (t - 0.5 * Ts); *thd = W; *thdd = 0.0;
}

static void rev_split(const fb_model *m, double t, const double *z, const double *zd, fb_frame *f, const double **q,
                  const double **qd) {
    f->R[0] = f->R[1] = f->Rd[0] = f->Rd[1] = 0.0; /* the frame turns about O, the origin */
    if (fb_base_moving(m)) { /* the base frame: O's acceleration as an inertial field */
        fb_base_motion(m, t, f->rO, f->vO, f->aO, NULL);
        f->field[0] = -f->aO[0];
        f->field[1] = -m->g - f->aO[1];
    } else {
        f->field[0] = 0.0;
        f->field[1] = -m->g;
        f->rO[0] = f->rO[1] = f->vO[0] = f->vO[1] = f->aO[0] = f->aO[1] = 0.0;
    }
    if (m->ngiven) {
        rev_motion(m, t, &f->th, &f->thd, &f->thdd);
        *q = z;
        *qd = zd;
    } else {
        f->th = z[0];
        f->thd = zd[0];
        f->thdd = 0.0;
        *q = z + 1;
        *qd = zd + 1;
    }
}

static double rev_torque(const fb_model *m, double t) {
    (void)t;
    return DRIVE(m) == DRIVE_TORQUE ? TORQUE(m) : 0.0;
}

static void rev_mass(const fb_model *m, const double *q, double *M) {
    int n = m->n, nb = fb_nb(m), N = n + 1;
    M[0] = m->Jc + fb_quad(m->Mc, q, nb);
    for (int i = 0; i < nb; i++) {
        M[i + 1] = m->mtq[i];
        M[(i + 1) * N] = m->mtq[i];
        for (int j = 0; j < nb; j++) M[(i + 1) * N + j + 1] = m->Mqq[i * nb + j];
    }
    if (m->na) fb_axial_mass(m, q, 0, M);
}

/* rev_forces on a moving base: gravity replaced by the uniform field (g_x, g_y) = f->field through its components in
 * the frame, g1 = g_x cos theta + g_y sin theta, g2 = -g_x sin theta + g_y cos theta (docs/formulation.md, "A moving
 * base"): Q_theta = tau - 2 theta' q^T Mc q' + g2 s_x - g1 s_y, Q_q = theta'^2 Mc q - g1 G q + g2 s_f + tau d (- K q),
 * s_x = m1 - 1/2 q^T G q, s_y = s_f q; with (0, -g) these are the fixed joint's terms. */
static double field_forces(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double tau,
                           int elastic, double *Q) {
    int n = m->n; /* no axial modes on a moving base (flexbeam.parameters.case refuses them) */
    double c, s, thd = f->thd;
    fb_sincos(f->th, &s, &c);
    double g1 = f->field[0] * c + f->field[1] * s, g2 = -f->field[0] * s + f->field[1] * c;
    double qMcqd = 0.0, qMcq = 0.0, qGq = 0.0, sfq = 0.0, mcq[MAXZ], gq[MAXZ], kq[MAXZ];
    fb_symv(m->Mc, q, n, mcq);
    fb_symv(m->G, q, n, gq);
    if (elastic) fb_symv(m->K, q, n, kq);
    for (int i = 0; i < n; i++) {
        qMcqd += mcq[i] * qd[i];
        qMcq += mcq[i] * q[i];
        qGq += q[i] * gq[i];
        sfq += m->sf[i] * q[i];
        Q[i + 1] = thd * thd * mcq[i] + tau * m->d[i] - g1 * gq[i] + g2 * m->sf[i] - (elastic ? kq[i] : 0.0);
    }
    Q[0] = tau - 2.0 * thd * qMcqd + g2 * (m->m1 - 0.5 * qGq) - g1 * sfq;
    return qMcq;
}

/* Q of the equations (elastic: with the elastic force -K q); returns q^T Mc q (the theta-theta mass change). */
static double rev_forces(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double tau, int elastic,
                     double *Q) {
    if (fb_base_moving(m)) return field_forces(m, f, q, qd, tau, elastic, Q);
    int n = fb_nb(m);
    double c, s, g = m->g, thd = f->thd;
    fb_sincos(f->th, &s, &c);
    double qMcqd = 0.0, qMcq = 0.0, qGq = 0.0, sfq = 0.0, mcq[MAXZ], gq[MAXZ];
    fb_symv(m->Mc, q, n, mcq);
    for (int i = 0; i < n; i++) {
        qMcqd += mcq[i] * qd[i];
        qMcq += mcq[i] * q[i];
        Q[i + 1] = thd * thd * mcq[i] + tau * m->d[i];
    }
    if (g != 0.0) {
        fb_symv(m->G, q, n, gq);
        for (int i = 0; i < n; i++) {
            qGq += q[i] * gq[i];
            sfq += m->sf[i] * q[i];
            Q[i + 1] -= g * (c * m->sf[i] - s * gq[i]);
        }
    }
    if (elastic) {
        double kq[MAXZ];
        fb_symv(m->K, q, n, kq);
        for (int i = 0; i < n; i++) Q[i + 1] -= kq[i];
    }
    Q[0] = tau - 2.0 * thd * qMcqd - g * (c * (m->m1 - 0.5 * qGq) - s * sfq);
    if (m->na) { /* axial.c; gravity through s_a p: V_g += g sin(theta) s_a p */
        double dJ = 0.0, sap = 0.0;
        Q[0] += fb_axial_forces(m, thd, q, qd, elastic, Q + 1);
        for (int k = 0; k < m->na; k++) {
            const double pk = q[n + k];
            dJ += (2.0 * m->mta[k] + m->Maa[k] * pk) * pk;
            sap += m->sa[k] * pk;
            Q[n + k + 1] -= g * s * m->sa[k];
        }
        Q[0] -= g * c * sap;
        qMcq += dJ;
    }
    return qMcq;
}

static void rev_energies(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double *T, double *Ve,
                     double *Vg) {
    int n = fb_nb(m);
    double thd = f->thd;
    *T = 0.5 * thd * thd * (m->Jc + fb_quad(m->Mc, q, n)) + thd * fb_dot(m->mtq, qd, n) +
         0.5 * fb_quad(m->Mqq, qd, n);
    *Ve = 0.5 * fb_quad(m->K, q, n);
    double s, c;
    fb_sincos(f->th, &s, &c);
    *Vg = m->g * (s * (m->m1 - 0.5 * fb_quad(m->G, q, n)) + c * fb_dot(m->sf, q, n));
    if (m->na) {
        fb_axial_energies(m, thd, q, qd, T, Ve);
        *Vg += m->g * s * fb_dot(m->sa, q + n, m->na);
    }
}

/* r = A(theta) rho, v = A (rho' + theta' e3 x rho), a0 = A (acc + 2 theta' e3 x rho' - theta'^2 rho); dr/dtheta =
 * A e3 x rho, dr/dq = A drho. */
static void rev_place(const fb_model *m, const fb_frame *f, const fb_body_kin *bk, const double *drho, fb_kin *out,
                  double *dr) {
    int n = m->n, N = n + 1;
    double ct, st, thd = f->thd, rx = bk->rho[0], ry = bk->rho[1];
    fb_sincos(f->th, &st, &ct);
    if (dr) {
        for (int i = 0; i < n; i++) {
            double dx = drho[i], dy = drho[n + i];
            dr[i + 1] = ct * dx - st * dy;
            dr[N + i + 1] = st * dx + ct * dy;
        }
        dr[0] = ct * (-ry) - st * rx;
        dr[N] = st * (-ry) + ct * rx;
    }
    out->r[0] = out->rel[0] = ct * rx - st * ry; /* R = 0: the frame turns about O */
    out->r[1] = out->rel[1] = st * rx + ct * ry;
    double vlx = bk->rhod[0] - thd * ry, vly = bk->rhod[1] + thd * rx;
    out->v[0] = ct * vlx - st * vly;
    out->v[1] = st * vlx + ct * vly;
    double alx = bk->acc[0] - 2.0 * thd * bk->rhod[1] - thd * thd * rx;
    double aly = bk->acc[1] + 2.0 * thd * bk->rhod[0] - thd * thd * ry;
    out->a0[0] = ct * alx - st * aly;
    out->a0[1] = st * alx + ct * aly;
}

/* A(theta)^T p: O is the origin, so a point and a direction turn alike. */
static void rev_to_body(const fb_model *m, const fb_frame *f, const double *p, int direction, double *out) {
    (void)m;
    (void)direction;
    double ct, st;
    fb_sincos(f->th, &st, &ct);
    out[0] = ct * p[0] + st * p[1];
    out[1] = -st * p[0] + ct * p[1];
}

static void rev_hub(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double *phi, double *phid) {
    *phi = f->th + fb_dot(m->d, q, fb_nb(m));
    *phid = f->thd + fb_dot(m->d, qd, fb_nb(m));
}

/* phi = theta + d q accumulated from theta (the order the step bookkeeping has always used). */
static double rev_work_angle(const fb_model *m, const double *z) {
    double acc = z[0];
    for (int i = 0; i < fb_nb(m); i++) acc += m->d[i] * z[i + 1];
    return acc;
}

/* The drive's power: the reaction ``torque`` times theta' (theta prescribed), else the applied torque on phi'. */
static double rev_power(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double torque) {
    (void)q;
    if (m->ngiven) return torque * f->thd;
    return torque * (f->thd + fb_dot(m->d, qd, fb_nb(m)));
}

/* max |theta'| over [t0, t1] of a prescribed theta (its profiles have monotone rates), else 0. */
static double rev_rate_bound(const fb_model *m, double t0, double t1) {
    if (!m->ngiven) return 0.0;
    double th, thd0, thd1, thdd;
    rev_motion(m, t0, &th, &thd0, &thdd);
    rev_motion(m, t1, &th, &thd1, &thdd);
    return fmax(fabs(thd0), fabs(thd1));
}

static void rev_given_acc(const fb_model *m, const fb_frame *f, double *acc) {
    if (m->ngiven) acc[0] = f->thdd;
}

static void rev_rigid_bound(const fb_model *m, double reach, double *env) {
    (void)m;
    env[0] = reach;
}

/* The hub frame's M0^-1 couples theta to q (row0_q): the Sherman-Morrison correction then needs K0 z. */
static int rev_row0_coupled(const fb_model *m, const fb_basis *b) {
    if (m->ngiven) return 0;
    for (int i = 1; i < b->nz; i++)
        if (b->row0[i] != 0.0) return 1;
    return 0;
}

/* R = M0 M^-1 Q (+ K0 z): theta prescribed, M = M_qq = M0 and R = Q_q - m_tq theta''; theta free, M(q) = M0 +
 * ds e0 e0^T and by Sherman-Morrison M0 M^-1 x = x - c e0 (row0 . x), c = ds / (1 + ds (M0^-1)_00). */
static double rev_remainder(const fb_model *m, const fb_basis *b, int row0_q, const fb_frame *f, const double *q,
                        const double *Q, double ds, fb_update *up, double *R) {
    int n = fb_nb(m), nz = b->nz;
    up->active = up->rank2 = up->row = 0;
    up->c = 0.0;
    if (m->ngiven) { /* M = blockdiag(M_qq, M_aa): R = Q - M_(q,p)theta theta'' */
        for (int i = 0; i < n; i++) R[i] = Q[i + 1] - m->mtq[i] * f->thdd;
        if (m->na) {
            double u[FB_JOINT_MAXZ];
            fb_axial_row(m, q, u);
            for (int i = 0; i < n; i++) R[i] -= u[i] * f->thdd;
            for (int k = 0; k < m->na; k++) R[n + k] = Q[n + k + 1] - u[n + k] * f->thdd;
        }
        return 0.0;
    }
    if (m->na) return fb_axial_remainder(m, b, 0, q, Q, ds, up, R);
    double c = ds / (1.0 + ds * b->inv00);
    up->c = c;
    up->active = c != 0.0;
    double r0 = 0.0;
    for (int i = 0; i < nz; i++) r0 += b->row0[i] * Q[i];
    if (row0_q) { /* row0 . (-K0 z): the elastic force is not in Q */
        for (int i = 0; i < n; i++) {
            double kq = 0.0;
            for (int j = 0; j < n; j++) kq += m->K[i * n + j] * q[j];
            r0 -= b->row0[i + 1] * kq;
        }
    }
    for (int i = 0; i < nz; i++) R[i] = Q[i];
    R[0] -= c * r0;
    return c;
}

static void rev_correct(const fb_model *m, const fb_basis *b, const fb_update *up, double *x) {
    (void)m;
    if (up->rank2) {
        fb_axial_correct(b, up, x);
        return;
    }
    double c = up->c, r0 = 0.0;
    for (int i = 0; i < b->nz; i++) r0 += b->row0[i] * x[i];
    x[0] -= c * r0;
}

const fb_joint_ops fb_joint_revolute = {
    .unpack = rev_unpack,
    .split = rev_split,
    .torque = rev_torque,
    .mass = rev_mass,
    .forces = rev_forces,
    .energies = rev_energies,
    .place = rev_place,
    .to_body = rev_to_body,
    .work_angle = rev_work_angle,
    .hub = rev_hub,
    .power = rev_power,
    .rate_bound = rev_rate_bound,
    .given_acc = rev_given_acc,
    .rigid_bound = rev_rigid_bound,
    .row0_coupled = rev_row0_coupled,
    .remainder = rev_remainder,
    .correct = rev_correct,
};
