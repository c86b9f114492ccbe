/* Internal to the detmath*.c files: log1p of a small argument and log x as double-doubles before their final
 * rounding, shared by log, log1p, pow and tgamma.  Static inline: each caller compiles them in place, as in
 * one file. */
#ifndef FLEXBEAM_DETMATH_LOG_H
#define FLEXBEAM_DETMATH_LOG_H

#include "detmath_dd.h"
#include "detmath_tables.h"

/* log1p(z + zl) = hi + lo for |z| <= 2^-8, |zl| <= ulp(z): the series
 * z - z^2/2 + z^3 (1/3 - z/4 + ... - z^7/10) with z^2/2 exact (the z^11 term is < 2^-80 |z|), absolute error
 * < 2^-78 |z| */
static inline dd log1p_small(double z, double zl) {
    dd sq = two_prod(z, z);
    double t =
        z * sq.hi *
        (0x1.5555555555555p-2 +
         z * (-0.25 + z * (0x1.999999999999ap-3 +
                           z * (-0x1.5555555555555p-3 +
                                z * (0x1.2492492492492p-3 +
                                     z * (-0.125 + z * (0x1.c71c71c71c71cp-4 + z * -0x1.999999999999ap-4)))))));
    dd b = fast_two_sum(z, -0.5 * sq.hi); /* |z| >= z^2/2 */
    return fast_two_sum(b.hi, b.lo + (zl + ((t - z * zl) - 0.5 * sq.lo)));
}

/* log x = hi + lo for finite x > 0 (subnormals included): absolute error < 2^-78 |log1p(u)| + 2^-86 */
static inline dd log_core(double x) {
    uint64_t ix = bits_of(x);
    int e = (int)(ix >> 52) - 1023;
    if (e == -1023) { /* subnormal: scale by 2^54 exactly */
        ix = bits_of(x * 0x1p54);
        e = (int)(ix >> 52) - 1023 - 54;
    }
    uint64_t frac = ix & 0x000fffffffffffffULL;
    int i = (int)(frac >> 44); /* the mantissa's top 8 bits */
    uint64_t mb = frac | 0x3ff0000000000000ULL;
    double m = double_of(mb);              /* x = 2^e m, m in [1, 2) */
    double mh = double_of(mb & ~0xfffULL); /* m to 40 fraction bits: mh c exact for a 12-bit c */
    if (i >= 106) {                        /* m >= 1.4140625: use m/2 in [0.707, 1) */
        m *= 0.5;
        mh *= 0.5;
        e += 1;
    }
    double c = LOG_INVC[i];
    /* u = m c - 1 exactly: mh c - 1 (53-bit product near 1) and (m - mh) c are exact; |u| <= 2^-8 */
    dd u = two_sum(mh * c - 1.0, (m - mh) * c);
    dd b = log1p_small(u.hi, u.lo);
    double ed = (double)e;
    dd a = two_sum(ed * LN2_HI, LOG_LOGC[2 * i]); /* e log2 - log c */
    dd s = two_sum(a.hi, b.hi);
    return fast_two_sum(s.hi, s.lo + (b.lo + (a.lo + (ed * LN2_LO + LOG_LOGC[2 * i + 1]))));
}

#endif
