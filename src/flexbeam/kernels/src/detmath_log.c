/* log x and log(1 + x) with the same bits on every machine (detmath.h).
 *
 *   fb_log     Table-driven (after Tang, ACM TOMS 16(4), 1990): x = 2^e m, m in [sqrt(1/2), sqrt(2)),
 *              u = m c - 1 computed exactly with a 12-bit reciprocal c from a 256-entry table (|u| <= 2^-8),
 *              log x = e ln2 - log c + log1p(u), the series of log1p(u) to u^10.  Error < 0.502 ulp.
 *   fb_log1p   |x| <= 2^-8: the series of log1p; otherwise 1 + x as the exact double-double s + t (two_sum),
 *              log(s) + t/s.  Error < 0.502 ulp.
 */
#include "detmath.h"
#include "detmath_dd.h"
#include "detmath_log.h"

double fb_log(double x) {
    if (!(x > 0.0)) return x == 0.0 ? -INFINITY : (x - x) / (x - x); /* log(+-0) = -inf; x < 0, NaN: NaN */
    if (isinf(x)) return x;
    return log_core(x).hi;
}

double fb_log1p(double x) {
    if (!(x > -1.0)) return x == -1.0 ? -INFINITY : (x - x) / (x - x);
    if (isinf(x)) return x;
    double ax = fabs(x);
    if (ax < 0x1p-60) return x; /* x - x^2/2 rounds to x; keeps -0 */
    if (ax <= 0x1p-8) {
        dd l = log1p_small(x, 0.0);
        return l.hi;
    }
    dd s = two_sum(1.0, x); /* 1 + x = s.hi + s.lo exactly, |s.lo / s.hi| <= 2^-53 << |log s.hi| */
    dd l = log_core(s.hi);
    return l.hi + (l.lo + s.lo / s.hi); /* log(s.hi + s.lo) = log s.hi + s.lo/s.hi - O(2^-106) */
}
