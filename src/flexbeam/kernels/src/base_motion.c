/* A moving base: the revolute joint's point O moves as prescribed, r_O(t) = sum_i A_i sin(w_i t + phi_i) e_axis_i +
 * 1/2 a t^2 (flexbeam.parameters.joint.Base), and the equations are written in the base frame (origin at O, axes
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
 * harmonic axis (0 x, 1 y), A, w = 2 pi k f, phi]; none (njp = 6): a fixed joint, the old code paths bit for bit.
 */
#include <math.h>

#include "detmath.h"
#include "flexbeam.h"
#include "joint.h"

#define REVOLUTE_PARAMS 6

static const double *block(const fb_model *m) {
    return m->joint == FB_JOINT_REVOLUTE && m->njp > REVOLUTE_PARAMS ? m->jp + REVOLUTE_PARAMS : NULL;
}

int fb_base_unpack(const fb_model *m) {
    const double *b = block(m);
    if (!b) return m->joint != FB_JOINT_REVOLUTE || m->njp == REVOLUTE_PARAMS ? 0 : -1;
    int count = (int)b[0];
    return count >= 0 && m->njp == REVOLUTE_PARAMS + 3 + 4 * count ? 0 : -1;
}

int fb_base_moving(const fb_model *m) { return block(m) != NULL; }

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
    }
    for (int k = 0; k < 2; k++) {
        if (r) r[k] = R[k];
        if (v) v[k] = V[k];
        if (a) a[k] = A[k];
        if (j) j[k] = J[k];
    }
}

/* The field the beam feels in the base frame at t: (0, -g) - a_O(t). */
void fb_base_field(const fb_model *m, double t, double *field) {
    double a[2];
    fb_base_motion(m, t, NULL, NULL, a, NULL);
    field[0] = -a[0];
    field[1] = -m->g - a[1];
}

/* A(theta) s(q): the beam's first moment int mu r dx about O in the plane's axes. */
static void moment(const fb_model *m, const fb_frame *f, const double *q, double out[2]) {
    int n = m->n;
    double sx = m->m1 - 0.5 * fb_quad(m->G, q, n), sy = fb_dot(m->sf, q, n), s, c;
    fb_sincos(f->th, &s, &c);
    out[0] = c * sx - s * sy;
    out[1] = s * sx + c * sy;
}

/* The integrand of the base's work, j_O(t) . A s (W_b' less the boundary term's rate). */
double fb_base_work_rate(const fb_model *m, double t, const fb_frame *f, const double *q) {
    double j[2], As[2];
    fb_base_motion(m, t, NULL, NULL, NULL, j);
    moment(m, f, q, As);
    return j[0] * As[0] + j[1] * As[1];
}

/* The boundary term of the base's work at t, -a_O(t) . A s. */
double fb_base_boundary(const fb_model *m, double t, const fb_frame *f, const double *q) {
    double a[2], As[2];
    fb_base_motion(m, t, NULL, NULL, a, NULL);
    moment(m, f, q, As);
    return -(a[0] * As[0] + a[1] * As[1]);
}
