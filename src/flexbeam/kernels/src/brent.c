/* Roots of a scalar function on a step's dense output by Brent's method (Brent, Algorithms for Minimization
 * without Derivatives, Prentice-Hall 1973, ch. 4): the event searches' root finder (events.c: a gap's crossing, a
 * law's kink; friction.c: a slip's stop).
 */
#include "integrator.h"

/* Root of fn on [a, b] (fa fb <= 0) by Brent's method (Brent 1973, ch. 4), to 1e-15 of the step; ``past``: the end
 * of the final bracket where fn <= 0 (the root passed, as bisection keeps it), else Brent's best estimate. */
static double brent_side(const fb_dense *d, double a, double b, double fa, double fb, fb_scalar fn, int past) {
    if (fa == 0.0) return a;
    if (fb == 0.0) return b;
    double c = a, fc = fa, e = b - a, dd = e;
    for (int it = 0; it < 200; it++) {
        if (fb * fc > 0.0) {
            c = a;
            fc = fa;
            dd = e = b - a;
        }
        if (fabs(fc) < fabs(fb)) {
            a = b; b = c; c = a;
            fa = fb; fb = fc; fc = fa;
        }
        double tol = 2.0 * 2.2e-16 * fabs(b) + 0.5e-15, m = 0.5 * (c - b);
        if (fabs(m) <= tol || fb == 0.0) return past && fb > 0.0 ? c : b;
        if (fabs(e) >= tol && fabs(fa) > fabs(fb)) {
            double s = fb / fa, p, q;
            if (a == c) {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                double qq = fa / fc, r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if (p > 0.0)
                q = -q;
            else
                p = -p;
            if (2.0 * p < fmin(3.0 * m * q - fabs(tol * q), fabs(e * q))) {
                e = dd;
                dd = p / q;
            } else {
                dd = e = m;
            }
        } else {
            dd = e = m;
        }
        a = b;
        fa = fb;
        b += fabs(dd) > tol ? dd : (m > 0.0 ? tol : -tol);
        fb = fn(d, b);
    }
    return b;
}

double fb_brent(const fb_dense *d, double a, double b, double fa, double fb, fb_scalar fn) {
    return brent_side(d, a, b, fa, fb, fn, 0);
}

double fb_brent_past(const fb_dense *d, double a, double b, double fa, double fb, fb_scalar fn) {
    return brent_side(d, a, b, fa, fb, fn, 1);
}
