/* atan2(y, x) with the same bits on every machine (detmath.h).
 *
 *   fb_atan2   y/x (or x/y) as an exact double-double quotient t, atan t = atan c + atan((t - c)/(1 + t c))
 *              with c = i/64 and atan c from a double-double table (the classic table-driven arctangent,
 *              J.-M. Muller, Elementary Functions, 3rd ed., 2016, ch. 6), the series of atan to u^11, then
 *              pi/2 - . and pi - . in double-double.  Error < 0.502 ulp; special values per C99 Annex F (F.9.1.4).
 */
#include "detmath.h"
#include "detmath_dd.h"
#include "detmath_tables.h"

/* atan(t) for t = th + tl in [0, 1] (|tl| <= ulp(th)), as a double-double */
static inline dd atan_core(double th, double tl) {
    int i = (int)(th * 64.0 + 0.5);
    double c = (double)i * 0x1p-6;
    /* u = (t - c) / (1 + t c), |u| <= 2^-7, as a double-double */
    dd n = two_sum(th - c, tl); /* th - c exact (Sterbenz for i >= 1) */
    dd tc = two_prod(th, c);
    dd den = fast_two_sum(1.0, tc.hi);
    den.lo += tc.lo + tl * c;
    dd u = dd_div(n, den);
    double z = u.hi, z2 = z * z;
    /* atan u - u to u^11 (the u^13 term is < 2^-85 |u|) */
    double p = z * z2 *
               (-0x1.5555555555555p-2 +
                z2 * (0x1.999999999999ap-3 +
                      z2 * (-0x1.2492492492492p-3 + z2 * (0x1.c71c71c71c71cp-4 + z2 * -0x1.745d1745d1746p-4))));
    dd s = two_sum(ATAN_TAB[2 * i], z);
    return fast_two_sum(s.hi, s.lo + (ATAN_TAB[2 * i + 1] + (u.lo + p)));
}

double fb_atan2(double y, double x) {
    if (isnan(x) || isnan(y)) return x + y;
    double ax = fabs(x), ay = fabs(y), th;
    int xneg = sign_bit(x);
    if (isinf(ax) || isinf(ay)) {
        if (isinf(ax) && isinf(ay))
            th = xneg ? PI3O4 : PIO4;
        else if (isinf(ax))
            th = xneg ? PI_HI : 0.0;
        else
            th = PIO2_HI;
        return sign_bit(y) ? -th : th;
    }
    if (ay == 0.0) {
        th = xneg ? PI_HI : 0.0; /* atan2(+-0, -0) = +-pi, atan2(+-0, +0) = +-0 */
        return sign_bit(y) ? -th : th;
    }
    if (ax == 0.0) return sign_bit(y) ? -PIO2_HI : PIO2_HI;
    int swap = ay > ax;
    double num = swap ? ax : ay, den = swap ? ay : ax;
    dd a; /* atan(num/den) in [0, pi/4] */
    double t = num / den;
    if (t < 0x1p-60) { /* atan t = t (1 - t^2/3 ...) rounds to the correctly rounded t */
        a.hi = t;
        a.lo = 0.0;
    } else {
        /* scale both by a power of 2 (exactly: num >= 2^-61 den) into a range where Dekker's product holds */
        if (den > 0x1p500) {
            num *= 0x1p-600;
            den *= 0x1p-600;
        } else if (den < 0x1p-500) {
            num *= 0x1p600;
            den *= 0x1p600;
        }
        t = num / den;
        dd pr = two_prod(t, den);
        double tl = ((num - pr.hi) - pr.lo) / den; /* num/den = t + tl */
        a = atan_core(t, tl);
    }
    if (swap) { /* pi/2 - a */
        dd b = two_sum(PIO2_HI, -a.hi);
        a = fast_two_sum(b.hi, b.lo + (PIO2_LO - a.lo));
    }
    if (xneg) { /* pi - a */
        dd b = two_sum(PI_HI, -a.hi);
        a = fast_two_sum(b.hi, b.lo + (PI_LO - a.lo));
    }
    th = a.hi + a.lo;
    return sign_bit(y) ? -th : th;
}
