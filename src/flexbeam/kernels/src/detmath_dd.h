/* Internal to the detmath*.c files: the build guards, the representation of a double and double-double
 * arithmetic, all static inline (detmath.h is the public interface).
 *
 * Only IEEE-754 operations that are exact or correctly rounded appear in detmath*.c: + - * / sqrt, fabs, floor,
 * integer and bit operations on the representation.  No libm transcendental function is called (tests/unit/
 * test_detmath.py inspects these files for them), and the build has no contraction (-ffp-contract=off): each
 * result is a function of the argument alone on any IEEE-754 binary64 machine that evaluates double
 * expressions in double (SSE2 on x86-64, AArch64; not the x87 unit, FLT_EVAL_METHOD must be 0).  Every file
 * that computes includes this header, so the guards below stop a build that would break that.
 *
 * Double-double arithmetic: a value hi + lo with |lo| <= ulp(hi)/2 carries ~106 bits.  two_sum (Knuth, TAOCP
 * vol. 2, 4.2.2, Thm B) and fast_two_sum (Dekker 1971, |a| >= |b|) give the rounding error of a sum exactly;
 * two_prod (Dekker 1971, "A floating-point technique for extending the available precision", Numer. Math. 18,
 * Veltkamp's split by 2^27 + 1) gives the error of a product exactly, without FMA.
 */
#ifndef FLEXBEAM_DETMATH_DD_H
#define FLEXBEAM_DETMATH_DD_H

#include <float.h>
#include <math.h> /* fabs, floor, sqrt, isnan, isinf, INFINITY: exact or correctly rounded only */
#include <stdint.h>
#include <string.h>

#if defined(__FAST_MATH__)
#error "detmath needs IEEE semantics: build without -ffast-math"
#endif
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD != 0
#error "detmath needs double expressions evaluated in double (FLT_EVAL_METHOD 0: SSE2, not the x87 unit)"
#endif

typedef struct {
    double hi, lo;
} dd;

/* ---------------------------------------------------------------------------------------------- representation */
static inline uint64_t bits_of(double x) {
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static inline double double_of(uint64_t u) {
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

/* 2^k for -1022 <= k <= 1023, exactly */
static inline double pow2i(int k) { return double_of((uint64_t)(k + 1023) << 52); }

static inline int sign_bit(double x) { return (int)(bits_of(x) >> 63); }

/* ------------------------------------------------------------------------------------ double-double arithmetic */
/* s + e = a + b exactly (Knuth's two-sum, no condition on a, b) */
static inline dd two_sum(double a, double b) {
    double s = a + b;
    double bb = s - a;
    dd r = {s, (a - (s - bb)) + (b - bb)};
    return r;
}

/* s + e = a + b exactly if a == 0 or |a| >= |b| (Dekker) */
static inline dd fast_two_sum(double a, double b) {
    double s = a + b;
    dd r = {s, b - (s - a)};
    return r;
}

/* a = hi + lo with hi, lo of at most 26 significant bits each (Veltkamp's split); |a| < 2^995 */
static inline void split(double a, double *hi, double *lo) {
    double c = 134217729.0 * a; /* 2^27 + 1 */
    *hi = c - (c - a);
    *lo = a - *hi;
}

/* p + e = a * b exactly (Dekker's product without FMA), no overflow or underflow in the partial products */
static inline dd two_prod(double a, double b) {
    double ah, al, bh, bl;
    split(a, &ah, &al);
    split(b, &bh, &bl);
    double p = a * b;
    dd r = {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
    return r;
}

static inline dd dd_mul(dd a, dd b) {
    dd p = two_prod(a.hi, b.hi);
    return fast_two_sum(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}

static inline dd dd_div(dd a, dd b) {
    double q = a.hi / b.hi;
    dd p = two_prod(q, b.hi);
    double r = (((a.hi - p.hi) - p.lo) + a.lo) - q * b.lo; /* a.hi - p.hi is exact (Sterbenz) */
    return fast_two_sum(q, r / b.hi);
}

/* nearest integer to x (ties to even) for |x| < 2^51, by the 1.5 2^52 shift (exact in round-to-nearest) */
static inline double round_int(double x) {
    const double shift = 0x1.8p52;
    return (x + shift) - shift;
}

#endif
