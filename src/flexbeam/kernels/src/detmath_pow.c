/* x^y with the same bits on every machine (detmath.h).
 *
 *   fb_pow     exp(y log x) with log x and y log x in double-double (absolute error of y log x < 2^-68 for
 *              |y log x| < 745) and e^z evaluated at the double-double z: error < 0.502 ulp for x > 0 over the
 *              whole range of results (subnormal ones included).  Exact cases: pow(x, 0) = 1, pow(x, 1) = x,
 *              pow(x, 2) = x*x, pow(x, -1) = 1/x, pow(x, 0.5) = sqrt(x) for x >= 0 (except -0, +0 per Annex F).
 *              pow(x, 1.5) and pow(x, 2.5) for 2^-300 < x < 2^300 -- the Hertz-type contact laws' K d^(3/2) and
 *              their potential, a tenth of a contact run's compiled time -- as x sqrt(x) in double-double
 *              (pow_odd_half): error < 0.5 + 2^-50 ulp, correctly rounded where exp(y log x) was not (~5e-6
 *              of arguments).
 *              Signed zeros, infinities, NaNs and x < 0 per C99 Annex F (F.9.4.4).
 */
#include "detmath.h"
#include "detmath_dd.h"
#include "detmath_exp.h"
#include "detmath_log.h"

static inline int is_integer(double y) { return floor(y) == y; } /* y finite */

static inline int is_odd_integer(double y) { /* y finite */
    return fabs(y) < 0x1p53 && floor(y) == y && floor(0.5 * y) != 0.5 * y;
}

/* x^1.5 = x sqrt(x) and x^2.5 = x^2 sqrt(x) for 2^-300 < x < 2^300 (the contact laws' exponent n = 3/2 and their
 * potential's n + 1), at a fifth of exp(y log x)'s cost.  s = sqrt(x) rounded; e = x - s^2 is a double (the remainder
 * of a correctly rounded square root), so (x - hi) - lo of two_prod(s, s) is e exactly (x - hi by Sterbenz); then
 * sqrt(x) = s + c, c = e / (2 s), to (e / s^2)^2 / 8 <= 2^-107 relative, c rounded to 2^-53 of itself <= 2^-106 of s.
 * The product with x (or x^2 = two_prod(x, x)) in double-double: x c and the sum of the low parts round to 2^-106 and
 * 2^-105 of the result (x^2's low part times c, ~2^-106, is dropped), so before the final rounding the relative error
 * is below 2^-103: < 0.5 + 2^-50 ulp. */
static double pow_odd_half(double x, double y) {
    double s = sqrt(x);
    dd ss = two_prod(s, s);
    double c = ((x - ss.hi) - ss.lo) / (2.0 * s);
    if (y == 1.5) {
        dd p = two_prod(x, s);
        return p.hi + (p.lo + x * c);
    }
    dd x2 = two_prod(x, x);
    dd p = two_prod(x2.hi, s);
    return p.hi + (p.lo + (x2.hi * c + x2.lo * s));
}

double fb_pow(double x, double y) {
    if (y == 0.0 || x == 1.0) return 1.0; /* even for a NaN in the other argument (F.9.4.4) */
    if (isnan(x) || isnan(y)) return x + y;
    if (y == 1.0) return x;
    if (y == 2.0) return x * x;
    if (y == -1.0) return 1.0 / x;
    double ax = fabs(x);
    if (isinf(y)) {
        if (ax == 1.0) return 1.0; /* (-1)^+-inf */
        return (ax > 1.0) == (y > 0.0) ? INFINITY : 0.0;
    }
    int odd = is_odd_integer(y);
    if (x == 0.0) {
        if (y < 0.0) return odd ? 1.0 / x : INFINITY; /* +-inf for odd y, like 1/+-0 */
        return odd ? x : 0.0;
    }
    if (isinf(x)) {
        if (x > 0.0) return y < 0.0 ? 0.0 : INFINITY;
        if (y < 0.0) return odd ? -0.0 : 0.0;
        return odd ? -INFINITY : INFINITY;
    }
    double sign = 1.0;
    if (x < 0.0) {
        if (!is_integer(y)) return (x - x) / (x - x); /* NaN */
        if (odd) sign = -1.0;
    }
    if (ax == 1.0) return sign;
    if (y == 0.5) return sqrt(x);
    if ((y == 1.5 || y == 2.5) && x > 0x1p-300 && x < 0x1p300) return pow_odd_half(x, y);
    if (fabs(y) > 0x1p63) /* |y log x| >= 2^63 2^-53 > 745 for x != 1 */
        return (ax > 1.0) == (y > 0.0) ? sign * INFINITY : sign * 0.0;
    dd l = log_core(ax);
    dd p = two_prod(y, l.hi);
    dd z = fast_two_sum(p.hi, p.lo + y * l.lo); /* y log x, relative error < 2^-69 */
    if (z.hi > 709.79) return sign * INFINITY;
    if (z.hi < -745.14) return sign * 0.0;
    int m;
    dd v = exp_core(z.hi, z.lo, &m);
    return sign * exp_scale(v, m);
}
