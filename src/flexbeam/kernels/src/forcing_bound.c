/* Bounds on a step's polynomial forcing and on a mode's forced response to it (events.c, tip_bound.c).
 *
 * Over a step of length h a mode's forcing is the interpolant of its nodal values, f(u) = sum_m a_m u^m, u = t / h
 * in [0, 1] (a = Vinv f_nodes, as the propagation uses it; degree FB_P - 1 = 3).  The forced response of
 * eta'' + c eta' + w^2 eta = f, c >= 0, from rest is int_0^t K'(t - s) f(s) ds with K the step response,
 * K = (1 - x) / w^2, x the free response from eta = 1, v = 0.  By parts, with K(0) = 0,
 *     eta(t) = K(t) f(0) + int_0^t K(t - s) f'(s) ds = [f(t) - f(0) x(t) - int_0^t x(t - s) f'(s) ds] / w^2,
 * and |x| <= 1 (its energy x'^2 + w^2 x^2 starts at w^2 and only decreases, for c = 0 x = cos w t), so
 *     |eta_forced(t)| <= (max|f| + |f(0)| + V) / w^2,     V = int_0^1 |f'(u)| du, the total variation of f
 * (undamped, damped and overdamped alike).  The familiar 2 max|f| / w^2 holds only for a forcing of one sign
 * varying slowly: f = T_3(2u - 1), max|f| = 1, reaches 3.35 / w^2 at w h = 8.26 (tests/unit/test_event_bound.py).
 * (events.c's former 2 x 3 max_j |f_j| / w^2 held at FB_P = 4 only through the slack of its Lebesgue factor 3:
 * over nodal values |f_j| <= 1 the forced response reaches 2 x 2.855 / w^2, as w h grows.)
 *
 * max|f| and V are computed from the polynomial: f' = a_1 + 2 a_2 u + 3 a_3 u^2 has at most two real roots in
 * (0, 1) (by the quadratic formula without cancellation); with the partition 0 = u_0 < roots < u_n = 1,
 * max|f| = max_i |f(u_i)| and V = sum_i |f(u_i) - f(u_(i-1))| exactly (f is monotone between the u_i).  A root
 * off by delta changes f there by O(f'' delta^2), far below the evaluation's rounding; the rounding -- the
 * coefficients' (4 ulp of sum_j |Vinv_mj f_j| each) and Horner's on [0, 1] (6 ulp of sum |a_m|) -- is added:
 * each value of f is raised by ROUNDING ulp of sum_m sum_j |Vinv_mj f_j| (>= sum |a_m|), V by twice that per piece.
 */
#include <float.h>

#include "integrator.h"

#if FB_P != 4
#error "forcing_bound.c finds the extrema of a cubic: FB_P = 4 collocation nodes"
#endif

#define ROUNDING 16.0 /* ulp of sum_m sum_j |Vinv_mj f_j| covering the coefficients' and Horner's rounding */

double fb_forcing_coefficients(const fb_tables *tb, const double *f, int N, int k, double *a, double *mag) {
    double F = 0.0, G = 0.0;
    for (int m = 0; m < FB_P; m++) {
        double s = 0.0;
        for (int j = 0; j < FB_P; j++) {
            s += tb->Vinv[m][j] * f[j * N + k];
            G += fabs(tb->Vinv[m][j] * f[j * N + k]);
        }
        a[m] = s;
        F += fabs(s);
    }
    if (mag) *mag = G;
    return F;
}

static double horner(const double *a, double u) {
    double s = a[FB_P - 1];
    for (int m = FB_P - 2; m >= 0; m--) s = s * u + a[m];
    return s;
}

/* The roots of f' = a_1 + 2 a_2 u + 3 a_3 u^2 inside (0, 1), ascending, into r; returns their count. */
static int turning_points(const double *a, double *r) {
    double A = 3.0 * a[3], B = 2.0 * a[2], C = a[1], x[2];
    int n = 0, count = 0;
    if (A != 0.0) {
        double disc = B * B - 4.0 * A * C;
        if (disc < 0.0) return 0;
        double q = -0.5 * (B + copysign(sqrt(disc), B));
        x[n++] = q / A;
        if (q != 0.0) x[n++] = C / q;
    } else if (B != 0.0) {
        x[n++] = -C / B;
    }
    for (int i = 0; i < n; i++)
        if (x[i] > 0.0 && x[i] < 1.0) r[count++] = x[i];
    if (count == 2 && r[0] > r[1]) {
        double t = r[0];
        r[0] = r[1], r[1] = t;
    }
    return count;
}

void fb_forcing_bound(const fb_tables *tb, const double *f, int N, int k, fb_forcing *out) {
    double a[FB_P], mag, u[4], val[4];
    fb_forcing_coefficients(tb, f, N, k, a, &mag);
    int n = 1 + turning_points(a, u + 1);
    u[0] = 0.0, u[n] = 1.0;
    double err = ROUNDING * DBL_EPSILON * mag, top = 0.0, var = 0.0;
    for (int i = 0; i <= n; i++) {
        val[i] = horner(a, u[i]);
        top = fmax(top, fabs(val[i]));
        if (i) var += fabs(val[i] - val[i - 1]);
    }
    out->max = top + err;
    out->start = fabs(a[0]) + err;
    out->variation = var + 2.0 * n * err;
}

double fb_forced_amplitude(const fb_forcing *fc, double w) {
    return (fc->max + fc->start + fc->variation) / (w * w);
}
