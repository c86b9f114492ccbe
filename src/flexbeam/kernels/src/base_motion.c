/* A moving base: the revolute joint's point O moves as prescribed, r_O(t) = sum_i A_i sin(w_i t + phi_i) e_axis_i +
 * 1/2 a t^2 + the table's cubic spline T(t) (flexbeam.parameters.joint.Base), and the equations are written in the base frame (origin at O, axes
 * parallel to the inertial ones).  There the base's motion is the uniform inertial field
 *
 *   g_eff(t) = (0, -g) - a_O(t)
 *
 * in place of gravity (Lagrange's equations of the exact inertial kinetic energy, the terms v_O . d/dt(A s) and
 * 1/2 m |v_O|^2 differing from the fixed joint's by a total time derivative: docs/formulation.md, "A moving base";
 * /work/research/moving_base.md with its sympy check).  The base does the work on the beam
 *
 *   W_b = -int a_O . d/dt[A(theta) s] dt = -[a_O . A s] + int j_O . A s dt,
 *
 * s = int mu rho dx = (m1 - 1/2 q^T G q, s_f q) the beam's first moment in the frame, j_O = a_O' the jerk; the
 * kernels book it in that integrated-by-parts form, whose integrand holds the modal coordinates and not their
 * rapidly oscillating rates.  The base's parameters follow the revolute joint's six in jp: [count, a_x, a_y, then per
 * harmonic axis (0 x, 1 y), A, w = 2 pi k f, phi, then the table: rows (0: none), max |T''| along x and y, then per
 * row t, x, y, x'', y''] (the C2 cubic spline through the rows, its second derivatives at the knots from Python:
 * flexbeam.model.joints.revolute); none (njp = 6): a fixed joint, the old code paths bit for bit.  The spline's
 * jerk T''' is constant between knots (it jumps at them); outside the rows it continues the end intervals' cubics
 * (a case must cover [0, t_end] with its rows).
 */
#include <math.h>

#include "detmath.h"
#include "flexbeam.h"
#include "joint.h"

#define REVOLUTE_PARAMS 6

static const double *block(const fb_model *m) {
    return m->joint == FB_JOINT_REVOLUTE && m->njp > REVOLUTE_PARAMS ? m->jp + REVOLUTE_PARAMS : NULL;
}

/* The table's part of the base's parameters: [rows, max |T_x''|, max |T_y''|, rows x (t, x, y, x'', y'')]. */
static const double *table(const double *b) { return b + 3 + 4 * (int)b[0]; }

int fb_base_unpack(const fb_model *m) {
    const double *b = block(m);
    if (!b) return m->joint != FB_JOINT_REVOLUTE || m->njp == REVOLUTE_PARAMS ? 0 : -1;
    int count = (int)b[0];
    if (count < 0 || m->njp < REVOLUTE_PARAMS + 3 + 4 * count + 3) return -1;
    int rows = (int)table(b)[0];
    if (rows < 0 || m->njp != REVOLUTE_PARAMS + 3 + 4 * count + 3 + 5 * rows || rows == 1) return -1;
    for (int i = 1; i < rows; i++)
        if (!(table(b)[3 + 5 * i] > table(b)[3 + 5 * (i - 1)])) return -1;
    return 0;
}

int fb_base_moving(const fb_model *m) { return block(m) != NULL; }

/* The table's spline and its first three derivatives at t, added to R, V, A, J: on the knot interval holding t (the
 * first or last beyond the rows), with u = t - t_i, w = t_i+1 - t, h = t_i+1 - t_i and M the second derivatives,
 * T = M_i w^3 / 6h + M_i+1 u^3 / 6h + (y_i / h - M_i h / 6) w + (y_i+1 / h - M_i+1 h / 6) u. */
static void spline(const double *tab, double t, double *R, double *V, double *A, double *J) {
    int rows = (int)tab[0], lo = 0, hi = rows - 1;
    const double *row = tab + 3;
    while (hi - lo > 1) { /* the last knot at or before t (the first interval before the rows) */
        int mid = (lo + hi) / 2;
        if (row[5 * mid] <= t) lo = mid;
        else hi = mid;
    }
    const double *a = row + 5 * lo, *b = a + 5;
    double h = b[0] - a[0], u = t - a[0], w = b[0] - t;
    for (int k = 0; k < 2; k++) {
        double y0 = a[1 + k], y1 = b[1 + k], M0 = a[3 + k], M1 = b[3 + k];
        double c0 = y0 / h - M0 * h / 6.0, c1 = y1 / h - M1 * h / 6.0;
        R[k] += (M0 * w * w * w + M1 * u * u * u) / (6.0 * h) + c0 * w + c1 * u;
        V[k] += (M1 * u * u - M0 * w * w) / (2.0 * h) + c1 - c0;
        A[k] += (M0 * w + M1 * u) / h;
        J[k] += (M1 - M0) / h;
    }
}

/* r_O, v_O, a_O and the jerk j_O at t (any of them NULL: not wanted). */
void fb_base_motion(const fb_model *m, double t, double *r, double *v, double *a, double *j) {
    double R[2] = {0.0, 0.0}, V[2] = {0.0, 0.0}, A[2] = {0.0, 0.0}, J[2] = {0.0, 0.0};
    const double *b = block(m);
    if (b) {
        int count = (int)b[0];
        R[0] = 0.5 * b[1] * t * t, R[1] = 0.5 * b[2] * t * t;
        V[0] = b[1] * t, V[1] = b[2] * t;
        A[0] = b[1], A[1] = b[2];
        for (int i = 0; i < count; i++) {
            const double *h = b + 3 + 4 * i;
            int k = h[0] != 0.0;
            double amp = h[1], w = h[2], s, c;
            fb_sincos(w * t + h[3], &s, &c);
            R[k] += amp * s;
            V[k] += amp * w * c;
            A[k] -= amp * w * w * s;
            J[k] -= amp * w * w * w * c;
        }
        if (table(b)[0] > 0.0) spline(table(b), t, R, V, A, J);
    }
    for (int k = 0; k < 2; k++) {
        if (r) r[k] = R[k];
        if (v) v[k] = V[k];
        if (a) a[k] = A[k];
        if (j) j[k] = J[k];
    }
}

/* The first knot of a base table after t + tol (INFINITY without a table): a step of the exponential integrator
 * ends there, so that within a step a_O is linear and the jerk constant (fb_advance's plan_step). */
double fb_base_next_knot(const fb_model *m, double t, double tol) {
    const double *b = block(m);
    if (!b || table(b)[0] <= 0.0) return INFINITY;
    const double *tab = table(b), *row = tab + 3;
    int lo = 0, hi = (int)tab[0]; /* the first row with t_i > t + tol is in [lo, hi] (hi: none) */
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (row[5 * mid] > t + tol) hi = mid;
        else lo = mid + 1;
    }
    return lo < (int)tab[0] ? row[5 * lo] : INFINITY;
}

/* A bound on |v_O| over [t0, t1] (the event search's reach of an obstacle fixed to the ground): per axis |v_O(t0)|
 * plus (t1 - t0) times a bound on |a_O|, sum_i |A_i| w_i^2 + |a| + max |T''|. */
double fb_base_speed_bound(const fb_model *m, double t0, double t1) {
    const double *b = block(m);
    if (!b) return 0.0;
    double v[2], acc[2] = {fabs(b[1]), fabs(b[2])};
    fb_base_motion(m, t0, NULL, v, NULL, NULL);
    for (int i = 0; i < (int)b[0]; i++) {
        const double *h = b + 3 + 4 * i;
        acc[h[0] != 0.0] += fabs(h[1]) * h[2] * h[2];
    }
    acc[0] += table(b)[1], acc[1] += table(b)[2]; /* max |T''| (T'' is linear between knots) */
    double dt = fabs(t1 - t0), vx = fabs(v[0]) + dt * acc[0], vy = fabs(v[1]) + dt * acc[1];
    return sqrt(vx * vx + vy * vy);
}

/* Is obstacle 0 a mass on a support carried by the base (its anchor moves with O: the mass feels -m_s a_O)? */
static int carried_support(const fb_model *m) { return fb_compliant(m) && !m->obstacles[0].ground; }

/* A(theta) s(q): the beam's first moment int mu r dx about O in the plane's axes; with a support carried by the
 * base, plus its mass's m_s s_u u (s_u its displacement along u from the static equilibrium: the constant part of
 * its moment does no work). */
static void moment(const fb_model *m, const fb_frame *f, const double *q, double su, double out[2]) {
    int n = m->n;
    double sx = m->m1 - 0.5 * fb_quad(m->G, q, n), sy = fb_dot(m->sf, q, n), s, c;
    fb_sincos(f->th, &s, &c);
    out[0] = c * sx - s * sy;
    out[1] = s * sx + c * sy;
    if (carried_support(m)) {
        const fb_obstacle *o = &m->obstacles[0];
        out[0] += o->ms * su * o->ux;
        out[1] += o->ms * su * o->uy;
    }
}

double fb_support_base_force(const fb_model *m, const fb_frame *f) {
    if (!carried_support(m) || !fb_base_moving(m)) return 0.0;
    const fb_obstacle *o = &m->obstacles[0];
    return -o->ms * (f->aO[0] * o->ux + f->aO[1] * o->uy);
}

/* The integrand of the base's work, j_O(t) . A s (W_b' less the boundary term's rate). */
double fb_base_work_rate(const fb_model *m, double t, const fb_frame *f, const double *q, double su) {
    double j[2], As[2];
    fb_base_motion(m, t, NULL, NULL, NULL, j);
    moment(m, f, q, su, As);
    return j[0] * As[0] + j[1] * As[1];
}

/* The rate of the base's work in its direct form, -a_O(t) . d/dt[A s] (the reference integrator's W rate),
 * d/dt[A s] = A (s_x' - theta' s_y, s_y' + theta' s_x), s_x' = -q^T G q', s_y' = s_f q'. */
double fb_base_power(const fb_model *m, double t, const fb_frame *f, const double *q, const double *qd, double sud) {
    int n = m->n;
    double a[2], gq[64], sxd = 0.0, s, c;
    fb_base_motion(m, t, NULL, NULL, a, NULL);
    fb_symv(m->G, q, n, gq);
    for (int i = 0; i < n; i++) sxd -= gq[i] * qd[i];
    double sx = m->m1 - 0.5 * fb_dot(gq, q, n), sy = fb_dot(m->sf, q, n), syd = fb_dot(m->sf, qd, n);
    double lx = sxd - f->thd * sy, ly = syd + f->thd * sx;
    fb_sincos(f->th, &s, &c);
    double p = -(a[0] * (c * lx - s * ly) + a[1] * (s * lx + c * ly));
    if (carried_support(m)) p -= m->obstacles[0].ms * sud * (a[0] * m->obstacles[0].ux + a[1] * m->obstacles[0].uy);
    return p;
}

/* The work rate of the obstacles fixed to the ground on the beam, -sum_k F_k n_k . v_O over the pairs touching one
 * (F the pairs' forces, or multipliers, g their gaps, f the frame with v_O): the contact power F J z' on the beam is
 * F delta' - F n . v_O, and F delta' = -U_c' - E_d' (docs/formulation.md, "A moving base"). */
double fb_ground_rate(const fb_model *m, const fb_frame *f, const int *mode, const double *F, const fb_gap *g) {
    double acc = 0.0;
    for (int k = 0; k < m->npairs; k++)
        if (mode[k] != FB_MODE_NONE && m->obstacles[m->pairs[k].obstacle].ground)
            acc -= F[k] * (g[k].nx * f->vO[0] + g[k].ny * f->vO[1]);
    return acc;
}

/* The boundary term of the base's work at t, -a_O(t) . A s. */
double fb_base_boundary(const fb_model *m, double t, const fb_frame *f, const double *q, double su) {
    double a[2], As[2];
    fb_base_motion(m, t, NULL, NULL, a, NULL);
    moment(m, f, q, su, As);
    return -(a[0] * As[0] + a[1] * As[1]);
}
