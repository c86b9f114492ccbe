/* Contact anywhere: the point of the beam's surface nearest an obstacle, on the deformed beam.
 *
 * The beam's surface is taken as a capsule: the tube of radius c (the surface offset) around the deformed centre
 * line rho(x), x in [0, L], closed by hemispherical caps.  Its point nearest a sphere of centre C is rho(x*) + c u
 * with x* the centre-line point nearest C and u = (C - rho(x*)) / |C - rho(x*)|; nearest a half-plane of outward
 * normal n_o it is rho(x*) - c n_o with x* minimising n_o . rho.  In the body frame rho(x) = (r_h + x + s(x) + u_x(x),
 * w(x)), w = Psi(x) q, u_x = -1/2 q^T H(x) q (zero in the zeroth-order model), s = Phi_a(x) p the axial modes'
 * stretch (model.axial_modes; the flexible coordinates are [q, p]), interpolated between the stations by cubic
 * Hermite polynomials (Psi with Psi', Psi' with Psi'', u_x with u_x' = -1/2 (Psi' q)^2, H with H' = Psi' Psi'^T,
 * Phi_a with Phi_a'; s' and s'' are the derivatives of s's interpolant).
 * The search: a scan of the stations (with s, without u_x, second order), then Newton's method on
 * f = (rho - C) . rho' (sphere) or n_o . rho' (plane), safeguarded by bisection, in the two intervals around the
 * best station.
 * With flat end faces (``flat``) instead of the caps, a minimiser at an end is moved to the end face's point nearest
 * the obstacle: across the section, the corner on the obstacle's side (half-plane) or the face's point nearest the
 * sphere's centre; the tube between the ends is the same.
 * The result is a material point (x*, offsets along the deformed section's normal and tangent), so that the pair's gap,
 * rate and Jacobian follow from the point kinematics of model.c: by the envelope theorem the derivative of the
 * minimum over x is the partial derivative at x*.
 */
#include <string.h>

#include "nearest_line.h"

#define NEWTON_ITERS 60

/* Cubic Hermite basis on [0, 1] at s, its first and second derivatives (d/ds). */
static void hermite(double s, double h[4], double d1[4], double d2[4]) {
    double s2 = s * s, s3 = s2 * s;
    h[0] = 2 * s3 - 3 * s2 + 1, h[1] = s3 - 2 * s2 + s, h[2] = -2 * s3 + 3 * s2, h[3] = s3 - s2;
    d1[0] = 6 * s2 - 6 * s, d1[1] = 3 * s2 - 4 * s + 1, d1[2] = -6 * s2 + 6 * s, d1[3] = 3 * s2 - 2 * s;
    d2[0] = 12 * s - 6, d2[1] = 6 * s - 4, d2[2] = -12 * s + 6, d2[3] = 6 * s - 2;
}

static double station_u(line_t *ln, int j) {
    if (!line_known(ln, KNOWN_U, j)) {
        const double *H = ln->m->st_H + (size_t)j * ln->n * ln->n;
        ln->u[j] = -0.5 * fb_quad(H, ln->q, ln->n);
    }
    return ln->u[j];
}

/* Psi' q and Psi'' q at station j, computed on first use (the scan needs Psi q alone). */
static void station_slopes(line_t *ln, int j) {
    if (!line_known(ln, KNOWN_SLOPES, j)) {
        ln->w1[j] = line_dot(ln->m->st_dphi + (size_t)j * ln->n, ln->q, ln->n);
        ln->w2[j] = line_dot(ln->m->st_ddphi + (size_t)j * ln->n, ln->q, ln->n);
    }
}

static int interval(const line_t *ln, double x, double *s) {
    int j = (int)(x / ln->dx);
    if (j < 0) j = 0;
    if (j > ln->M - 2) j = ln->M - 2;
    *s = (x - ln->m->st_x[j]) / ln->dx;
    return j;
}

/* rho(x) and its first two x-derivatives in the body frame. */
static void centre_line(line_t *ln, double x, double r[2], double r1[2], double r2[2]) {
    double s, h[4], d1[4], d2[4];
    int j = interval(ln, x, &s);
    station_w(ln, j), station_w(ln, j + 1);
    station_slopes(ln, j);
    station_slopes(ln, j + 1);
    double D = ln->dx;
    hermite(s, h, d1, d2);
    double w = h[0] * ln->w[j] + D * h[1] * ln->w1[j] + h[2] * ln->w[j + 1] + D * h[3] * ln->w1[j + 1];
    double w1 = h[0] * ln->w1[j] + D * h[1] * ln->w2[j] + h[2] * ln->w1[j + 1] + D * h[3] * ln->w2[j + 1];
    double w2 = (d1[0] * ln->w1[j] + d1[2] * ln->w1[j + 1]) / D + d1[1] * ln->w2[j] + d1[3] * ln->w2[j + 1];
    double u = 0.0;
    if (ln->m->first_order) {
        double ua = station_u(ln, j), ub = station_u(ln, j + 1);
        u = h[0] * ua + D * h[1] * (-0.5 * ln->w1[j] * ln->w1[j]) + h[2] * ub +
            D * h[3] * (-0.5 * ln->w1[j + 1] * ln->w1[j + 1]);
    }
    double u1 = ln->m->first_order ? -0.5 * w1 * w1 : 0.0, u2 = ln->m->first_order ? -w1 * w2 : 0.0;
    r[0] = ln->rh + x + u, r[1] = w;
    r1[0] = 1.0 + u1, r1[1] = w1;
    r2[0] = u2, r2[1] = w2;
    if (ln->s) { /* the stretch's interpolant and its derivatives */
        double sa1, sb1, sa = station_s(ln, j, &sa1), sb = station_s(ln, j + 1, &sb1);
        r[0] += h[0] * sa + D * h[1] * sa1 + h[2] * sb + D * h[3] * sb1;
        r1[0] += (d1[0] * sa + d1[2] * sb) / D + d1[1] * sa1 + d1[3] * sb1;
        r2[0] += (d2[0] * sa + d2[2] * sb) / (D * D) + (d2[1] * sa1 + d2[3] * sb1) / D;
    }
}

/* f = (1/2) d/dx of the search's objective: (rho - C) . rho' (sphere) or n . rho' (plane); and df/dx. */
static double objective_slope(line_t *ln, int sphere, const double c[2], double x, double *df) {
    double r[2], r1[2], r2[2];
    centre_line(ln, x, r, r1, r2);
    if (sphere) {
        double ex = r[0] - c[0], ey = r[1] - c[1];
        *df = r1[0] * r1[0] + r1[1] * r1[1] + ex * r2[0] + ey * r2[1];
        return ex * r1[0] + ey * r1[1];
    }
    *df = c[0] * r2[0] + c[1] * r2[1];
    return c[0] * r1[0] + c[1] * r1[1];
}

/* The minimiser of the objective on [a, b]: an end if the slope does not change sign there, else the root of the
 * slope by Newton's method kept inside the shrinking bracket. */
static double minimise(line_t *ln, int sphere, const double c[2], double a, double b) {
    double dfa, dfb, fa = objective_slope(ln, sphere, c, a, &dfa), fb = objective_slope(ln, sphere, c, b, &dfb);
    if (fa >= 0.0) return a;
    if (fb <= 0.0) return b;
    double x = 0.5 * (a + b), tol = 1e-13 * (ln->rh + ln->m->st_x[ln->M - 1]);
    for (int it = 0; it < NEWTON_ITERS; it++) {
        double df, f = objective_slope(ln, sphere, c, x, &df);
        if (f < 0.0) a = x;
        else b = x;
        double xn = df > 0.0 ? x - f / df : 0.5 * (a + b);
        /* a converged Newton step may land on the bracket's end x itself (f = 0 exactly, or a step below the ulp,
         * as at a straight beam's point abreast of a sphere's centre): that is the root, not a reason to bisect on
         * down to tol off it */
        if (df > 0.0 && xn >= a && xn <= b && fabs(xn - x) <= tol) return xn;
        if (!(xn > a && xn < b)) xn = 0.5 * (a + b);
        if (fabs(xn - x) <= tol || b - a <= tol) return xn;
        x = xn;
    }
    return x;
}

/* The material point at x: Psi, Psi', H and (with axial modes) Phi_a at x by the search's Hermite interpolation.  On
 * a station (s = 0 or 1: an end cap's minimiser, or a point met exactly) the basis is (1, 0, 0, 0) or (0, 0, 1, 0) and
 * the interpolant sums the station's value with zeros: that value itself, to the bit, unless it is a zero (whose sign
 * the sum decides), so a nonzero one is copied and a zero summed as elsewhere. */
static void material_shapes(const line_t *ln, double x, fb_surface_point *out) {
    const fb_model *m = ln->m;
    int n = ln->n, na = m->na;
    double sj, h[4], d1[4], d2[4];
    int j = interval(ln, x, &sj), at = sj == 0.0 || sj == 1.0;
    hermite(sj, h, d1, d2);
    double D = ln->dx;
    const double *P0 = m->st_phi + (size_t)j * n, *P1 = P0 + n, *Q0 = m->st_dphi + (size_t)j * n, *Q1 = Q0 + n;
    const double *R0 = m->st_ddphi + (size_t)j * n, *R1 = R0 + n;
    const double *H0 = m->st_H + (size_t)j * n * n, *H1 = H0 + (size_t)n * n;
    const double *Ps = sj == 0.0 ? P0 : P1, *Qs = sj == 0.0 ? Q0 : Q1, *Hs = sj == 0.0 ? H0 : H1;
    for (int k = 0; k < n; k++) {
        double p = at ? Ps[k] : 0.0, dp = at ? Qs[k] : 0.0;
        out->phi[k] = p != 0.0 ? p : h[0] * P0[k] + D * h[1] * Q0[k] + h[2] * P1[k] + D * h[3] * Q1[k];
        out->dphi[k] = dp != 0.0 ? dp : h[0] * Q0[k] + D * h[1] * R0[k] + h[2] * Q1[k] + D * h[3] * R1[k];
    }
    for (int r = 0; r < n; r++)
        for (int k = 0; k < n; k++) {
            double v = at ? Hs[r * n + k] : 0.0;
            out->H[r * n + k] = v != 0.0 ? v
                                         : h[0] * H0[r * n + k] + h[2] * H1[r * n + k] +
                                               D * (h[1] * Q0[r] * Q0[k] + h[3] * Q1[r] * Q1[k]);
        }
    out->P.phi = out->phi;
    out->P.dphi = out->dphi;
    out->P.H = out->H;
    out->P.aphi = NULL;
    if (na) { /* Phi_a at x by the same Hermite interpolation as the search's stretch */
        const double *A0 = m->st_aphi + (size_t)j * na, *A1 = A0 + na, *B0 = m->st_daphi + (size_t)j * na, *B1 = B0 + na;
        const double *As = sj == 0.0 ? A0 : A1;
        for (int k = 0; k < na; k++) {
            double a = at ? As[k] : 0.0;
            out->aphi[k] = a != 0.0 ? a : h[0] * A0[k] + D * h[1] * B0[k] + h[2] * A1[k] + D * h[3] * B1[k];
        }
        out->P.aphi = out->aphi;
    }
}

/* The centre line's material point at x (no offsets): Psi, Psi', H, Phi_a interpolated as the search's (the kinematics
 * of the true gap's second derivative, anywhere_gamma.c). */
void fb_centre_point(const fb_model *m, double x, fb_surface_point *out) {
    int M = m->nst;
    line_t ln = {m, NULL, fb_nb(m), M, m->hub_radius, m->st_x[M - 1] / (M - 1), NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    material_shapes(&ln, x, out);
    out->x = x;
    out->P.base = ln.rh + x;
    out->P.offset = out->P.offset_t = 0.0;
}

/* The unit direction from the centre line's point r to the obstacle c (obstacle_in_body). */
static void obstacle_direction(int sphere, const double c[2], const double r[2], double dir[2]) {
    if (sphere) {
        double ex = c[0] - r[0], ey = c[1] - r[1], d = sqrt(ex * ex + ey * ey);
        dir[0] = d > 0.0 ? ex / d : 0.0, dir[1] = d > 0.0 ? ey / d : -1.0;
    } else {
        dir[0] = -c[0], dir[1] = -c[1];
    }
}

/* The surface point's offsets off = [-c u . n, c u . t] along the normal and tangent of the section at angle ang (u =
 * dir, c the surface offset; sa, ca: sin and cos of ang). */
static void section_offsets(double cs, const double dir[2], double sa, double ca, double off[2]) {
    off[1] = cs * (dir[0] * ca + dir[1] * sa);  /* c u . t */
    off[0] = -cs * (-dir[0] * sa + dir[1] * ca); /* -c u . n */
}

/* The obstacle in the body frame: a sphere's centre, or a plane's outward normal (the objective's direction), into
 * c; returns whether it is a sphere. */
static int obstacle_in_body(const fb_model *m, const fb_obstacle *o, const fb_frame *f, double s, double c[2]) {
    double p[2] = {o->cx + s * o->ux, o->cy + s * o->uy}, nrm[2] = {o->nx, o->ny};
    if (o->ground) p[0] -= f->rO[0], p[1] -= f->rO[1]; /* fixed to the ground: at C - r_O in the base frame */
    int sphere = o->kind == FB_SPHERE;
    fb_joint(m)->to_body(m, f, sphere ? p : nrm, !sphere, c);
    return sphere;
}

/* The search's line at q + e q' and the obstacle in the body frame with the frame advanced by e (theta', R', v_O)
 * and its support (s'), into ln (its station arrays in st, 6 M doubles, and known, LINE_KNOWN LINE_WORDS(M) words)
 * and c; returns whether it is a sphere. */
static int advanced(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, const double *qd,
                    double s, double sd, double e, double *qe, double *st, unsigned long long *known, line_t *ln,
                    double c[2]) {
    int n = fb_nb(m), na = m->na, M = m->nst;
    fb_frame g = *f;
    g.th += e * f->thd, g.R[0] += e * f->Rd[0], g.R[1] += e * f->Rd[1];
    g.rO[0] += e * f->vO[0], g.rO[1] += e * f->vO[1];
    for (int k = 0; k < n + na; k++) qe[k] = q[k] + e * qd[k];
    double *w = st, *w1 = st + M, *w2 = st + 2 * M, *u = st + 3 * M, *sx = st + 4 * M, *sx1 = st + 5 * M;
    *ln = (line_t){m, qe, n, M, m->hub_radius, m->st_x[M - 1] / (M - 1), w, w1, w2, u, na ? sx : NULL, na ? sx1 : NULL,
                   known};
    memset(known, 0, sizeof(unsigned long long) * LINE_KNOWN * LINE_WORDS(M));
    return obstacle_in_body(m, o, &g, s + e * sd, c);
}

/* The rate x*' of the search's minimiser x (an interior root of objective_slope's f(x; q, C)): -f_t / f_x, f_t the
 * rate of f at fixed x as q moves at q' and the obstacle in the body frame with the frame and its support; and the
 * rate of the surface point's offsets doff (the point of the section facing the obstacle turns against the section
 * where the centre line's tangent is not the section's: a relative angle ~ w'^3 / 6 - w' s'; on an end cap (``end``:
 * x* stays there, x*' = 0) the point turns around the cap).  Central differences
 * over -+ EPS_T (f and the offsets are smooth in q and the frame: truncation EPS_T^2 f''' / 6, round-off
 * eps |f| / EPS_T).  The search's own minimiser and offsets, so that the slip velocity taken there has these rates
 * (anywhere_gamma.c). */
#define EPS_T 1e-6 /* [s] */
double fb_nearest_rate(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, const double *qd,
                       double s, double sd, double x, int end, double *doff) {
    int M = m->nst;
    unsigned long long known[LINE_KNOWN * LINE_WORDS(M)];
    double st[6 * M], qe[m->n], fe[2], fx = 0.0, c[2], df, r[2], r1[2], r2[2], dir[2], off[2][2];
    line_t ln;
    for (int side = 0; side < 2 && !end; side++) {
        int sphere = advanced(m, o, f, q, qd, s, sd, side ? EPS_T : -EPS_T, qe, st, known, &ln, c);
        fe[side] = objective_slope(&ln, sphere, c, x, &df);
        fx += 0.5 * df;
    }
    double xd = !end && fx != 0.0 ? -(fe[1] - fe[0]) / (2.0 * EPS_T) / fx : 0.0; /* an end's x* stays */
    for (int side = 0; side < 2; side++) {
        double e = side ? EPS_T : -EPS_T;
        int sphere = advanced(m, o, f, q, qd, s, sd, e, qe, st, known, &ln, c);
        centre_line(&ln, x + e * xd, r, r1, r2);
        obstacle_direction(sphere, c, r, dir);
        double sa, ca;
        fb_sincos(r1[1], &sa, &ca); /* the section's angle: the slope Psi' q */
        section_offsets(m->surface, dir, sa, ca, off[side]);
    }
    for (int i = 0; i < 2; i++) doff[i] = (off[1][i] - off[0][i]) / (2.0 * EPS_T);
    return xd;
}

void fb_nearest_point(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, double s,
                      int flat, fb_surface_point *out) {
    int n = fb_nb(m), na = m->na, M = m->nst;
    double w[M], w1[M], w2[M], u[M], sx[na ? M : 1], sx1[na ? M : 1];
    double L = m->st_x[M - 1];
    unsigned long long known[LINE_KNOWN * LINE_WORDS(M)];
    memset(known, 0, sizeof known);
    line_t ln = {m, q, n, M, m->hub_radius, L / (M - 1), w, w1, w2, u, na ? sx : NULL, na ? sx1 : NULL, known};
    double c[2];
    int sphere = obstacle_in_body(m, o, f, s, c);
    int best = fb_nearest_station(&ln, sphere, c, (int)(o - m->obstacles));
    double a = m->st_x[best > 0 ? best - 1 : 0], b = m->st_x[best < M - 1 ? best + 1 : M - 1];
    double x = minimise(&ln, sphere, c, a, b);
    material_shapes(&ln, x, out);
    /* the direction from the centre line to the obstacle, and the offsets along the section's normal and tangent */
    double r[2], r1[2], r2[2], dir[2], off[2];
    centre_line(&ln, x, r, r1, r2);
    obstacle_direction(sphere, c, r, dir);
    double ang = line_dot(out->dphi, q, n), sa, ca, cs = m->surface;
    fb_sincos(ang, &sa, &ca);
    section_offsets(cs, dir, sa, ca, off);
    out->x = x;
    out->P.base = ln.rh + x;
    out->P.offset_t = off[1];
    out->P.offset = off[0];
    if (flat && (x == m->st_x[0] || x == L)) { /* an end face: its point nearest the obstacle, along the section */
        double across = -dir[0] * sa + dir[1] * ca, t; /* u . n */
        if (sphere) {
            double ex = c[0] - r[0], ey = c[1] - r[1], along = -ex * sa + ey * ca; /* (C - rho) . n */
            t = along > cs ? cs : (along < -cs ? -cs : along);
        } else {
            t = across > 0.0 ? cs : (across < 0.0 ? -cs : 0.0); /* the corner on the obstacle's side */
        }
        out->P.offset_t = 0.0;
        out->P.offset = -t;
    }
}

/* Per generalised coordinate [rigid, q, p] a bound on |d delta / dz| of an anywhere pair over all the beam's
 * surface points: the joint's from the reach |r| for the frame's; max|Psi_k| + c max|Psi'_k| + |(H q)_k| for q_k,
 * with |(H(x) q)_k| <= sqrt(H_kk(L) q^T H(L) q) (H(L) - H(x) is positive semi-definite); max|Phi_a,k| for p_k. */
void fb_anywhere_bound(const fb_model *m, const double *q, double *env) {
    int n = fb_nb(m), na = m->na, M = m->nst;
    const double *HL = m->st_H + (size_t)(M - 1) * n * n;
    double qHq = fb_quad(HL, q, n), reach = m->points[1].base + m->surface;
    for (int k = 0; k < n; k++) reach += m->st_maxphi[k] * fabs(q[k]);
    for (int k = 0; k < na; k++) reach += m->st_maxaphi[k] * fabs(q[n + k]);
    fb_joint(m)->rigid_bound(m, reach, env);
    for (int k = 0; k < n; k++)
        env[m->nrigid + k] = m->st_maxphi[k] + m->surface * m->st_maxdphi[k] + sqrt(fmax(HL[k * n + k], 0.0) * fmax(qHq, 0.0));
    for (int k = 0; k < na; k++) env[m->nrigid + n + k] = m->st_maxaphi[k];
}
