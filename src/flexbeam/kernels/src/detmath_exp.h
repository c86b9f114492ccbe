/* Internal to the detmath*.c files: e^x as a double-double before its final rounding (exp_core) and that
 * rounding with the scaling by 2^m (exp_scale), shared by exp, expm1, pow and tgamma.  Static inline: each
 * caller compiles them in place, as in one file. */
#ifndef FLEXBEAM_DETMATH_EXP_H
#define FLEXBEAM_DETMATH_EXP_H

#include "detmath_dd.h"
#include "detmath_tables.h"

/* e^(xh + xl) = (hi + lo) 2^m with hi + lo in [0.994, 1.995), relative error < 2^-66, for |xh| < 746 and
 * |xl| <= ulp(xh).  Tang (1989): k = nearest(x 64/ln2), x = k ln2/64 + r, e^x = 2^(k/64) e^r. */
static inline dd exp_core(double xh, double xl, int *m) {
    double kd = round_int(xh * EXP_INVL);
    int k = (int)kd, j = k & 63;
    *m = (k - j) / 64;
    /* r = xh - k L1 - k L2 + xl: xh - k L1 is exact (k L1 is exact and within a factor 2 of xh, or k = 0) */
    dd r = two_sum(xh - kd * EXP_L1, xl - kd * EXP_L2);
    double z = r.hi;
    /* e^r - 1 - r to r^7 (the r^8 term is < 2^-75 for |r| <= ln2/128) */
    double q = z * z *
               (0.5 + z * (0x1.5555555555555p-3 +
                           z * (0x1.5555555555555p-5 +
                                z * (0x1.1111111111111p-7 + z * (0x1.6c16c16c16c17p-10 + z * 0x1.a01a01a01a01ap-13)))));
    double plo = r.lo + q; /* e^r = 1 + r.hi + plo */
    double th = EXP2_TAB[2 * j], tl = EXP2_TAB[2 * j + 1];
    dd p = two_prod(th, r.hi);
    dd s = fast_two_sum(th, p.hi);
    double t = s.lo + (p.lo + (tl + (th * plo + tl * r.hi)));
    return fast_two_sum(s.hi, t);
}

/* (v.hi + v.lo) 2^m rounded once to a double: overflow to +inf, gradual underflow (v.hi = fl(v.hi + v.lo)) */
static inline double exp_scale(dd v, int m) {
    if (m > 1024) return INFINITY;
    if (m > -1022 || (m == -1022 && v.hi >= 1.0)) {
        if (m == 1024) return v.hi * 0x1p1023 * 2.0;
        return v.hi * pow2i(m);
    }
    if (m < -1080) return 0.0;
    /* a subnormal result: 1 + v 2^(m+1022) has, in [1, 2), the spacing 2^-52 that the subnormals have in
     * units of 2^-1022, so rounding that sum once rounds the result once */
    double sc = pow2i(m + 1022);
    dd t = two_sum(1.0, v.hi * sc);
    double r = t.hi + (t.lo + v.lo * sc);
    return (r - 1.0) * 0x1p-1022;
}

#endif
