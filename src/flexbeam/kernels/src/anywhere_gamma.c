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
 *
 * The slip velocity's rate (Coulomb friction's sticking row, rhs.c).  The slip velocity of an anywhere pair is that of
 * the surface's material point at the nearest point, v_t(q, q') = T(x*(q), off*(q); q, q') with T(x, off) = t . w, w
 * the velocity relative to the obstacle of the material point at x with offsets off from the centre line (along the
 * section's normal and tangent, nearest.c) and t = (-n_y, n_x) its gap's tangent (on a sphere t turns with the point).
 * So v_t' = Jt z'' + [the material point's rate, model.c] + T_x x*' + T_off off*': the contact point moving along the
 * beam meets material points that move differently (T_x = t . w_x + t_x . w, t . w_x the surface fibre's stretching
 * rate where the pair sticks, w = 0), and it moves across the section where the centre line's tangent turns against the
 * section's (their angle ~ w'^3 / 6 - w' s') or, x* at an end, around the end cap (T_off off*', off*' by
 * fb_nearest_rate; on a sphere ~ (n . w) / |P - C| per metre).  The stick holds the contact point's slip v_t(q, q') = 0
 * -- the relative velocity of the bodies' coincident points at the current contact point (Pfeiffer & Glocker, Multibody
 * Dynamics with Unilateral Contacts, Wiley 1996, Ch. 4-5: the tangential constraint g_T' = 0 and its time derivative
 * along the moving contact point; Montana, Int. J. Robotics Research 7 (1988) 17-32, for the contact point's motion) --
 * the function the collocation holds at its nodes, so its acceleration-level row takes the whole rate.  A rigid
 * straight bar has t . w_x = 0 (w_x = omega x rho_x is along the normal) and, sticking, w = 0: T_x x*' vanishes there.
 * P_x and v_x are central differences at x -+ h along the surface fibre of the contact point's offsets (``offsets``),
 * with the same h and errors as above; the terms are added to *tgamma where the normal correction applies (an interior
 * proper minimum) and, on an end cap, T_off off*' alone (x* stays); a flat end face keeps the material point's rate.
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

/* The kinematics of the surface's material point at x with the contact point's ``offsets``. */
static void fibre_kin(const fb_model *m, const fb_frame *f, const double *q, const double *qd, const double *offsets,
                      double x, fb_kin *k) {
    fb_surface_point sp;
    fb_centre_point(m, x, &sp);
    sp.P.offset = offsets[0], sp.P.offset_t = offsets[1];
    k->want_acc = 0;
    fb_point_kinematics(m, &sp.P, f, q, qd, k, NULL);
}

/* T at x of the surface's material point with offsets off + e doff. */
static double offset_slip(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, const double *qd,
                          double s, double sd, const double *off, const double *doff, double e, double x) {
    double oe[2] = {off[0] + e * doff[0], off[1] + e * doff[1]}, vx, vy;
    fb_kin k;
    fibre_kin(m, f, q, qd, oe, x, &k);
    fb_gap g = fb_gap_state(o, f, &k, NULL, 0, s, sd, NULL);
    return fb_slip_velocity(o, f, &k, &g, sd, &vx, &vy);
}

/* The slip velocity's rate along the contact point's motion over the beam at x: T_x x*' + T_off off' (header).
 * T_x = t . w_x + t_x . w, with w_x = v_x (the obstacle's velocity is the same all along the beam) and P_x the
 * central differences at xc -+ h along the fibre of ``offsets``; on a sphere t_x = (-n_y,x, n_x,x),
 * n_x = (P_x - (n . P_x) n) / |P - C| (on a half-plane t is fixed).  T_off off' by the central difference of T over
 * the offsets' motion -+ EPS_OFF off' (T is smooth in the offsets: truncation EPS_OFF^2). */
#define EPS_OFF 1e-6 /* [s] */
static double contact_motion(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q,
                             const double *qd, double s, double sd, const double *offsets, double x, double xc,
                             double h) {
    int end = h == 0.0; /* at an end: x* stays, the contact point moves over the cap alone */
    double doff[2], xd = fb_nearest_rate(m, o, f, q, qd, s, sd, x, end, doff);
    double Tp = offset_slip(m, o, f, q, qd, s, sd, offsets, doff, EPS_OFF, x);
    double Toff = (Tp - offset_slip(m, o, f, q, qd, s, sd, offsets, doff, -EPS_OFF, x)) / (2.0 * EPS_OFF);
    if (end) return Toff;
    fb_kin k, km, kp;
    fibre_kin(m, f, q, qd, offsets, x, &k);
    fibre_kin(m, f, q, qd, offsets, xc - h, &km);
    fibre_kin(m, f, q, qd, offsets, xc + h, &kp);
    fb_gap g = fb_gap_state(o, f, &k, NULL, 0, s, sd, NULL);
    double w[2], Px[2], vx[2];
    fb_slip_velocity(o, f, &k, &g, sd, &w[0], &w[1]);
    for (int i = 0; i < 2; i++) Px[i] = (kp.r[i] - km.r[i]) / (2.0 * h), vx[i] = (kp.v[i] - km.v[i]) / (2.0 * h);
    double Tx = -g.ny * vx[0] + g.nx * vx[1];
    if (o->kind == FB_SPHERE) {
        double dist = g.delta + o->radius, pn = g.nx * Px[0] + g.ny * Px[1];
        double nxx = (Px[0] - pn * g.nx) / dist, nyx = (Px[1] - pn * g.ny) / dist;
        Tx += -nyx * w[0] + nxx * w[1];
    }
    return Tx * xd + Toff;
}

/* D'' at z'' = 0 of an anywhere pair whose nearest point is at material coordinate x (``gamma``: the material surface
 * point's, model.c's fb_gap_state), obstacle o displaced by s (rate sd) along its support axis; with ``tgamma`` (the
 * material point's slip rate, its surface offsets in ``offsets``) the contact point's motion's T_x x*' + T_off off'
 * is added to it (on an end cap T_off off' alone). */
double fb_anywhere_gamma(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, const double *qd,
                         double s, double sd, int flat, double x, double gamma, const double *offsets,
                         double *tgamma) {
    double x0 = m->st_x[0], L = m->st_x[m->nst - 1];
    int interior = x > x0 && x < L;
    if (!interior && flat) return gamma;
    fb_kin kc;
    centre_kin(m, f, q, qd, x, 1, &kc);
    fb_gap gc = fb_gap_state(o, f, &kc, NULL, 0, s, sd, NULL);
    if (!interior) {
        if (tgamma) *tgamma += contact_motion(m, o, f, q, qd, s, sd, offsets, x, x, 0.0);
        return gc.gamma;
    }
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
    if (!(dxx > round)) return gc.gamma;
    if (tgamma) *tgamma += contact_motion(m, o, f, q, qd, s, sd, offsets, x, xc, h);
    return gc.gamma - b * b / dxx;
}
