/* e^x and e^x - 1 with the same bits on every machine (detmath.h).
 *
 *   fb_exp     Tang's table-driven method (ACM TOMS 15(2), 1989): x = (64 m + j) ln2/64 + r, |r| <= ln2/128,
 *              Cody & Waite reduction with ln2/64 in two parts, 2^(j/64) from a double-double table, a degree-7
 *              Taylor polynomial for e^r - 1; subnormal results rounded once.  Error < 0.502 ulp.
 *   fb_expm1   |x| < 1/16: Taylor series to x^10 with x + x^2/2 in double-double; otherwise e^x (double-double,
 *              as fb_exp, relative error < 2^-66) minus 1 in double-double.  Error < 0.502 ulp.
 */
#include "detmath.h"
#include "detmath_dd.h"
#include "detmath_exp.h"

double fb_exp(double x) {
    if (!(x <= 709.79)) return isnan(x) ? x + x : INFINITY; /* e^709.79 > DBL_MAX */
    if (x < -745.14) return 0.0;                             /* e^-745.14 < 2^-1075: rounds to 0 */
    int m;
    dd v = exp_core(x, 0.0, &m);
    return exp_scale(v, m);
}

double fb_expm1(double x) {
    double ax = fabs(x);
    if (ax < 0.0625) {
        if (ax < 0x1p-60) return x; /* x + x^2/2 rounds to x; keeps -0 */
        /* x + x^2/2 (double-double) + x^3 (1/3! + x/4! + ... + x^7/10!); the x^11 term is < 2^-65 |x| */
        dd sq = two_prod(x, x);
        double p =
            0x1.5555555555555p-3 +
            x * (0x1.5555555555555p-5 +
                 x * (0x1.1111111111111p-7 +
                      x * (0x1.6c16c16c16c17p-10 +
                           x * (0x1.a01a01a01a01ap-13 +
                                x * (0x1.a01a01a01a01ap-16 + x * (0x1.71de3a556c734p-19 + x * 0x1.27e4fb7789f5cp-22))))));
        dd s = fast_two_sum(x, 0.5 * sq.hi);
        return s.hi + (s.lo + (0.5 * sq.lo + x * sq.hi * p));
    }
    /* e^x - 1 from e^x in double-double: the relative error 2^-66 of e^x grows by e^x / |e^x - 1| <= 16.5 */
    if (!(x <= 709.79)) return isnan(x) ? x + x : INFINITY;
    if (x < -38.0) return -1.0; /* -1 + e^x with e^x < 2^-54: rounds to -1 (also x = -inf) */
    int m;
    dd v = exp_core(x, 0.0, &m);
    if (m > 1000) return exp_scale(v, m); /* the 1 is below 2^-900 ulp */
    double sc = pow2i(m);                 /* -55 <= m <= 1000: v 2^m is exact */
    dd a = two_sum(v.hi * sc, -1.0);
    return a.hi + (a.lo + v.lo * sc);
}
