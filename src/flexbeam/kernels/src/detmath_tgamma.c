/* Gamma(x) for x > 0 with the same bits on every machine (detmath.h).
 *
 *   fb_tgamma  Stirling's series (Abramowitz & Stegun 6.1.40, 8 terms) for log Gamma(z), z >= 12, in
 *              double-double, then e^(log Gamma); for x < 12, Gamma(x) = Gamma(x + n) / (x (x+1) ... (x+n-1))
 *              (A&S 6.1.15) with x + n and the product in double-double; Gamma(x) = 1/x for x < 2^-960.  log
 *              Gamma is accurate to ~2^-62 absolute: error < 0.516 ulp (0.5 + 2^-6) on (0, 171.62];
 *              +inf beyond, Gamma(+-0) = +-inf, NaN for x < 0 (the function is defined here for x > 0 only).
 */
#include "detmath.h"
#include "detmath_dd.h"
#include "detmath_exp.h"
#include "detmath_log.h"
#include "detmath_tables.h"

/* log Gamma(z) for z = zh + zl >= 12 by Stirling's series (A&S 6.1.40):
 * (z - 1/2) log z - z + log sqrt(2 pi) + sum_k B_2k / (2k (2k-1) z^(2k-1)), k = 1..8, remainder < 2^-63. */
static inline dd lgamma_stirling(double zh, double zl) {
    dd l = log_core(zh);
    l.lo += zl / zh; /* log(zh + zl) */
    dd zm = two_sum(zh, -0.5);
    zm.lo += zl;
    dd p = two_prod(zm.hi, l.hi);
    p.lo += zm.hi * l.lo + zm.lo * l.hi;
    /* the first term 1/(12 z) in double-double (up to 0.007: its rounding would be 2^-60), the rest in double */
    dd twelve_z = two_prod(12.0, zh);
    dd one = {1.0, 0.0};
    dd s1 = dd_div(one, twelve_z);
    double w = 1.0 / zh, w2 = w * w;
    s1.lo -= s1.hi * (zl * w); /* 1/(12 (zh + zl)) */
    double S = w * w2 *
               (-0x1.6c16c16c16c17p-9 +
                w2 * (0x1.a01a01a01a01ap-11 +
                      w2 * (-0x1.3813813813814p-11 +
                            w2 * (0x1.b951e2b18ff23p-11 +
                                  w2 * (-0x1.f6ab0d9993c7dp-10 + w2 * (0x1.a41a41a41a41ap-8 + w2 * -0x1.e4286cb0f5398p-6))))));
    dd a = two_sum(p.hi, -zh);
    dd b = two_sum(a.hi, LNSQRT2PI_HI);
    dd c = two_sum(b.hi, s1.hi);
    return fast_two_sum(c.hi, (((S + s1.lo) + LNSQRT2PI_LO) - zl) + p.lo + a.lo + b.lo + c.lo);
}

double fb_tgamma(double x) {
    if (isnan(x)) return x + x;
    if (x == 0.0) return 1.0 / x;                 /* +-inf */
    if (x < 0.0) return (x - x) / (x - x);        /* outside the domain of this function (and -inf): NaN */
    if (x > 171.7) return INFINITY;               /* Gamma(171.625) > DBL_MAX; also +inf */
    if (x < 0x1p-960) return 1.0 / x;             /* Gamma(x) = 1/x - gamma + O(x), the gamma x below 2^-960 */
    int m;
    if (x >= 12.0) {
        dd E = lgamma_stirling(x, 0.0);
        if (E.hi > 709.79) return INFINITY;
        dd v = exp_core(E.hi, E.lo, &m);
        return exp_scale(v, m);
    }
    /* Gamma(x) = Gamma(x + n) / (x (x+1) ... (x+n-1)), x + n in [12, 13) */
    int n = 12 - (int)floor(x);
    dd z = two_sum(x, (double)n), prod = {x, 0.0};
    for (int j = 1; j < n; j++) prod = dd_mul(prod, two_sum(x, (double)j));
    dd E = lgamma_stirling(z.hi, z.lo);
    dd v = exp_core(E.hi, E.lo, &m); /* Gamma(z) = v 2^m, m <= 29 */
    double sc = pow2i(m);
    v.hi *= sc;
    v.lo *= sc;
    dd g = dd_div(v, prod);
    return g.hi + g.lo;
}
