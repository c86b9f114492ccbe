/* The gap acceleration of a contact anywhere: the second derivative of the true gap D(q) = min over x of delta(x, q).
 *
 * nearest.c finds the beam's surface point nearest the obstacle and model.c treats it as a material point: right for
 * D and D' (envelope theorem), not for D''.  On the capsule surface D = |rho(x*) - C| - c - r_s (sphere) or
 * n_o . (rho(x*) - C) - c (half-plane), rho the deformed centre line and x* its point nearest the obstacle, where
 * delta_x = n . rho_x = 0.  With x*' = -(delta_xq q') / delta_xx (the derivative of delta_x(x*, q) = 0):
 *     D'' = [the centre line's material point's delta''] - (delta_xq q')^2 / delta_xx,
 *     sphere:     delta_xq q' = (rho_x . v_perp) / dist + n . v_x,  delta_xx = (|rho_x|^2 - (n . rho_x)^2) / dist + n . rho_xx,
 *     half-plane: delta_xq q' = n . v_x,                            delta_xx = n . rho_xx,
 * v(x) the centre line's material velocity relative to the obstacle (v_perp = v - (n . v) n), dist = |rho - C|.
 * A rigid straight bar sliding along itself over a sphere: the correction -v_t^2 / dist cancels the material point's
 * v_t^2 / dist (D'' = 0).  The material point is the centre line's (the offset c u to the surface turns with the
 * section, the true surface point does not).  rho_x, rho_xx and v_x are central differences of the kinematics of
 * fb_point_kinematics at x -+ h, h = (station spacing) / 64: the Hermite interpolant is cubic within an interval,
 * so the second difference is exact there but for round-off, ~eps |rho| / h^2 (1e-9 / m for |rho| ~ 1 m and 40
 * stations a metre), and the first differences carry h^2 rho''' / 6 (rho''' the interval's constant third
 * derivative; 4e-5 of rho''' dx^2) and round-off eps |rho| / h; the stencil is moved inside [0, L] at the ends.  With delta_xx below 1e3 times the second difference's round-off (a straight beam parallel to a
 * half-plane: no proper minimum) the centre line's material value is kept.  A minimiser at an end (x* = 0 or L) of
 * the capsule (its cap: a sphere around rho(L)) takes the centre line's material value; on a flat end face
 * (``flat``) the material surface point's ``gamma`` is kept.
 */
#include <float.h>

#include "flexbeam.h"

/* The kinematics of the centre line's material point at x. */
static void centre_kin(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double x, int acc,
                       fb_kin *k) {
    fb_surface_point sp;
    fb_centre_point(m, x, &sp);
    k->want_acc = acc;
    fb_point_kinematics(m, &sp.P, f, q, qd, k, NULL);
}

/* D'' at z'' = 0 of an anywhere pair whose nearest point is at material coordinate x (``gamma``: the material surface
 * point's, model.c's fb_gap_state), obstacle o displaced by s (rate sd) along its support axis. */
double fb_anywhere_gamma(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, const double *qd,
                         double s, double sd, int flat, double x, double gamma) {
    double x0 = m->st_x[0], L = m->st_x[m->nst - 1];
    int interior = x > x0 && x < L;
    if (!interior && flat) return gamma;
    fb_kin kc;
    centre_kin(m, f, q, qd, x, 1, &kc);
    fb_gap gc = fb_gap_state(o, f, &kc, NULL, 0, s, sd, NULL);
    if (!interior) return gc.gamma;
    double h = (L - x0) / (m->nst - 1) / 64.0, xc = fmin(fmax(x, x0 + h), L - h);
    fb_kin km, k0 = kc, kp;
    if (xc != x) centre_kin(m, f, q, qd, xc, 0, &k0);
    centre_kin(m, f, q, qd, xc - h, 0, &km);
    centre_kin(m, f, q, qd, xc + h, 0, &kp);
    double rx[2], rxx[2], vx[2];
    for (int i = 0; i < 2; i++) {
        rx[i] = (kp.r[i] - km.r[i]) / (2.0 * h);
        rxx[i] = (kp.r[i] - 2.0 * k0.r[i] + km.r[i]) / (h * h);
        vx[i] = (kp.v[i] - km.v[i]) / (2.0 * h);
    }
    double nx = gc.nx, ny = gc.ny, b = nx * vx[0] + ny * vx[1], dxx = nx * rxx[0] + ny * rxx[1];
    if (o->kind == FB_SPHERE) {
        double dist = gc.delta + o->radius, v[2] = {kc.v[0] - sd * o->ux, kc.v[1] - sd * o->uy};
        if (o->ground) v[0] += f->vO[0], v[1] += f->vO[1];
        double vn = nx * v[0] + ny * v[1], rn = nx * rx[0] + ny * rx[1];
        b += (rx[0] * (v[0] - vn * nx) + rx[1] * (v[1] - vn * ny)) / dist;
        dxx += (rx[0] * rx[0] + rx[1] * rx[1] - rn * rn) / dist;
    }
    double round = 1e3 * DBL_EPSILON * (fabs(k0.r[0]) + fabs(k0.r[1])) / (h * h);
    return dxx > round ? gc.gamma - b * b / dxx : gc.gamma;
}
