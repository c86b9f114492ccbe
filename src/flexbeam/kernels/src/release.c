/* Event search for a held constraint (events.c does the gaps): the collocated multiplier turning tensile. */
#include "integrator.h"

/* Fraction of the step where the collocated multiplier lambda(s) (interpolant of the nodal values) turns
 * tensile, or FB_NO_EVENT.  ``later``: not the phase's first step -- a multiplier already tensile at such a step's
 * start turned so where the last step ended (its interpolant ended at zero or a hair above, this one's starts a
 * hair below: no crossing inside either step), and is released there, x = 0 (before, the release was missed and
 * the constraint pulled on: a shaken cantilever's held tip, CCM with friction, at up to 7 % of the contact's peak
 * for 1.4e-4 s).  At a phase's first step the start's sign is the transition's, which has just tested it. */
double fb_find_release(const fb_tables *tb, const double *lam, int later) {
    double prev = 0.0;
    for (int j = 0; j < FB_P; j++) prev += lam[j] * fb_lagrange(tb, j, 0.0);
    if (later && prev < 0.0) return 0.0;
    for (int i = 1; i <= 32; i++) {
        double x = i / 32.0, val = 0.0;
        for (int j = 0; j < FB_P; j++) val += lam[j] * fb_lagrange(tb, j, x);
        if (prev >= 0.0 && val < 0.0) {
            if (prev == 0.0) return (i - 1) / 32.0;
            double lo = (i - 1) / 32.0, hi = x;
            for (int it = 0; it < 60; it++) {
                double mid = 0.5 * (lo + hi), vm = 0.0;
                for (int j = 0; j < FB_P; j++) vm += lam[j] * fb_lagrange(tb, j, mid);
                if (vm >= 0.0)
                    lo = mid;
                else
                    hi = mid;
            }
            return hi;
        }
        prev = val;
    }
    return FB_NO_EVENT;
}
