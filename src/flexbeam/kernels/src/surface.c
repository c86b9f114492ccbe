/* A phase that starts on the event surface (a CCM release leaves the pair's point there, a few pm beyond at most):
 * the proof that its gap stays there between two samples, which spares the event search (events.c) its dense
 * searches for a return from above the surface and for sinking in. */
#include <float.h>

#include "surface.h"

/* An evaluated gap's round-off, over eps (|r_P| + |c_x| + |c_y| + R): 4e-15 m on the seed case, 1000x the most the
 * gap of one state differs between two evaluation paths there (3.5e-18 m). */
#define GAP_ULPS 16.0
#define QUIET_PIECES 16 /* pieces the proof that a start on the surface stays there may split an interval into */

/* The gap (with its rate and gamma) at the fraction x of the step, on its exact dense output. */
fb_gap fb_dense_gap(const fb_dense *d, double x) {
    double eta[FB_MAXN], v[FB_MAXN];
    fb_dense_state(d, x, eta, v);
    return fb_gap_at(d->ph, d->pair, d->t0 + x * d->h, eta, v);
}

/* |r_P|: the pair's point's distance from O at most (the tip's for a point anywhere on the beam). */
double fb_pair_reach(const fb_dense *d) {
    const fb_model *m = d->ph->m;
    const fb_point *P = &m->points[m->pairs[d->pair].point];
    return m->pairs[d->pair].anywhere ? m->points[1].base + m->surface : P->base + fabs(P->offset);
}

/* Is the gap between the samples a (at x0) and b (at x0 + dx) provably on the far side of the surface and no more
 * than ``depth`` beyond it?  Then the hump search (golden_min) finds no return and leaves_surface no sinking in, and
 * neither needs its ~110 dense-output evaluations.  On a piece between samples spaced by dx / n the gap stays within
 * the curvature bound of their chord when every mode is resolved at that spacing (fb_dense_bounds, its fast modes'
 * bound B = 0; 2 max|gamma| over the samples for the velocity-product part, as in fb_find_gap_event):
 * -sign g <= max_j (-sign g_j) + curve and sign g <= max_j (sign g_j) + curve.  n is chosen so that curve is at most
 * half the room the ends leave (at most QUIET_PIECES pieces, else no verdict); the margin GAP_ULPS covers the
 * round-off of the samples and of the searches' own evaluations. */
int fb_on_surface_quiet(const fb_dense *d, const double *jb, double gam, double x0, double dx, double a, double b,
                         double sign, double depth) {
    double B, curve = fb_dense_bounds(d, jb, gam, dx, &B);
    double above = fmax(-sign * a, -sign * b), below = fmax(sign * a, sign * b);
    const fb_obstacle *o = &d->ph->m->obstacles[d->ph->m->pairs[d->pair].obstacle];
    double roundoff = GAP_ULPS * DBL_EPSILON * (fb_pair_reach(d) + fabs(o->cx) + fabs(o->cy) + o->radius);
    double room = fmin(-above, depth - below) - roundoff;
    if (B != 0.0 || !(room > 0.0)) return 0;
    double pieces = ceil(sqrt(2.0 * curve / room));
    if (!(pieces <= QUIET_PIECES)) return 0;
    int n = pieces < 1.0 ? 1 : (int)pieces;
    for (int j = 1; j < n; j++) {
        fb_gap g = fb_dense_gap(d, x0 + dx * j / n);
        above = fmax(above, -sign * g.delta);
        below = fmax(below, sign * g.delta);
        gam = fmax(gam, fabs(g.gamma));
    }
    curve = fb_dense_bounds(d, jb, gam, dx / n, &B);
    return B == 0.0 && above + curve + roundoff < 0.0 && below + curve + roundoff <= depth;
}
