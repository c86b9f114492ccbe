/* Elementary functions that give the same bits on every machine (see detmath.h for why).
 *
 * Only IEEE-754 operations that are exact or correctly rounded appear here: + - * / sqrt, fabs, floor, integer
 * and bit operations on the representation.  No libm transcendental function is called (tests/unit/
 * test_detmath.py inspects this file for them), and the build has no contraction (-ffp-contract=off): each
 * result is a function of the argument alone on any IEEE-754 binary64 machine that evaluates double
 * expressions in double (SSE2 on x86-64, AArch64; not the x87 unit, FLT_EVAL_METHOD must be 0).
 *
 * Building blocks.  Double-double arithmetic: a value hi + lo with |lo| <= ulp(hi)/2 carries ~106 bits.
 * two_sum (Knuth, TAOCP vol. 2, 4.2.2, Thm B) and fast_two_sum (Dekker 1971, |a| >= |b|) give the rounding
 * error of a sum exactly; two_prod (Dekker 1971, "A floating-point technique for extending the available
 * precision", Numer. Math. 18, Veltkamp's split by 2^27 + 1) gives the error of a product exactly, without FMA.
 * Every function below evaluates its result as a double-double with a relative error below 2^-62 and rounds it
 * once at the end, so its error is below 0.5 ulp (the final rounding) + 2^-62 / 2^-53 = 0.502 ulp (subnormal
 * results included: they are rounded once too).  tests/unit/test_detmath.py asserts these bounds against mpmath
 * at 200 bits; the measured excess over 0.5 ulp is below 1.2e-4 ulp (5e-4 for Gamma).
 *
 *   fb_exp     Tang's table-driven method (ACM TOMS 15(2), 1989): x = (64 m + j) ln2/64 + r, |r| <= ln2/128,
 *              Cody & Waite reduction with ln2/64 in two parts, 2^(j/64) from a double-double table, a degree-7
 *              Taylor polynomial for e^r - 1; subnormal results rounded once.  Error < 0.502 ulp.
 *   fb_expm1   |x| < 1/16: Taylor series to x^10 with x + x^2/2 in double-double; otherwise e^x (double-double,
 *              as fb_exp, relative error < 2^-66) minus 1 in double-double.  Error < 0.502 ulp.
 *   fb_log     Table-driven (after Tang, ACM TOMS 16(4), 1990): x = 2^e m, m in [sqrt(1/2), sqrt(2)),
 *              u = m c - 1 computed exactly with a 12-bit reciprocal c from a 256-entry table (|u| <= 2^-8),
 *              log x = e ln2 - log c + log1p(u), the series of log1p(u) to u^10.  Error < 0.502 ulp.
 *   fb_log1p   |x| <= 2^-8: the series of log1p; otherwise 1 + x as the exact double-double s + t (two_sum),
 *              log(s) + t/s.  Error < 0.502 ulp.
 *   fb_pow     exp(y log x) with log x and y log x in double-double (absolute error of y log x < 2^-68 for
 *              |y log x| < 745) and e^z evaluated at the double-double z: error < 0.502 ulp for x > 0 over the
 *              whole range of results (subnormal ones included).  Exact cases: pow(x, 0) = 1, pow(x, 1) = x, pow(x, 2) = x*x,
 *              pow(x, -1) = 1/x, pow(x, 0.5) = sqrt(x) for x >= 0 (except -0, +0 per Annex F).  Signed zeros,
 *              infinities, NaNs and x < 0 per C99 Annex F (F.9.4.4).
 *   fb_sin,    x = k pi/2 + r: Cody & Waite reduction with pi/2 in four parts (33+33+33+53 bits, exact products
 *   fb_cos,    for |k| < 2^20) for |x| < 1.6e6, Payne & Hanek's reduction (SIGNUM Newsletter 18(1), 1983) with
 *   fb_sincos  1280 bits of 2/pi in integer arithmetic beyond: r as a double-double, absolute error < 2^-127
 *              (|r| >= 2^-61.5 for every double, 2^-60.5 below 1.6e6: relative error < 2^-65).  Then
 *              a table of sin and cos at a = i/64 in double-double (Gal & Bachelis, ACM TOMS 17(1), 1991, use
 *              the same addition formulas): sin(a + d), cos(a + d) with |d| <= 1/128 from Taylor polynomials,
 *              the leading products exact.  Error < 0.502 ulp for every finite x (no range limit); sin and cos
 *              of fb_sincos are the bits of fb_sin and fb_cos (the same code).
 *   fb_atan2   y/x (or x/y) as an exact double-double quotient t, atan t = atan c + atan((t - c)/(1 + t c))
 *              with c = i/64 and atan c from a double-double table (the classic table-driven arctangent,
 *              J.-M. Muller, Elementary Functions, 3rd ed., 2016, ch. 6), the series of atan to u^11, then
 *              pi/2 - . and pi - . in double-double.  Error < 0.502 ulp; special values per C99 Annex F (F.9.1.4).
 *   fb_tgamma  Stirling's series (Abramowitz & Stegun 6.1.40, 8 terms) for log Gamma(z), z >= 12, in
 *              double-double, then e^(log Gamma); for x < 12, Gamma(x) = Gamma(x + n) / (x (x+1) ... (x+n-1))
 *              (A&S 6.1.15) with x + n and the product in double-double; Gamma(x) = 1/x for x < 2^-960.  log
 *              Gamma is accurate to ~2^-62 absolute: error < 0.516 ulp (0.5 + 2^-6) on (0, 171.62];
 *              +inf beyond, Gamma(+-0) = +-inf, NaN for x < 0 (the function is defined here for x > 0 only).
 */
#include <float.h>
#include <math.h> /* fabs, floor, sqrt, isnan, isinf, INFINITY: exact or correctly rounded only */
#include <stdint.h>
#include <string.h>

#include "detmath.h"

#if defined(__FAST_MATH__)
#error "detmath.c needs IEEE semantics: build without -ffast-math"
#endif
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD != 0
#error "detmath.c needs double expressions evaluated in double (FLT_EVAL_METHOD 0: SSE2, not the x87 unit)"
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

/* ------------------------------------------------------------------------------------------------------ tables
 * Generated with mpmath at 400 bits (the recipe is at the end of this file).  A double-double entry is
 * (nearest double to v, nearest double to v - hi).
 *
 * EXP2_TAB[2j], [2j+1]: 2^(j/64), j = 0..63.
 * LOG_INVC[i]: c_i, 1/(centre of mantissa interval i) rounded to 12 significant bits (1 for i = 0 and 255);
 *   interval i is [1 + i/256, 1 + (i+1)/256), halved for i >= 106.  LOG_LOGC[2i], [2i+1]: -log(c_i).
 * SINCOS_TAB[8i .. 8i+7]: sin(i/64) (hi, its 26-bit split head, tail, lo), cos(i/64) (same), i = 0..52.
 * ATAN_TAB[2i], [2i+1]: atan(i/64), i = 0..64.
 * TWO_OVER_PI[w]: bits 64w+1 .. 64w+64 of the binary expansion of 2/pi (1280 bits).
 */
static const double EXP2_TAB[128] = {
    0x1.0000000000000p+0, 0.0,
    0x1.02c9a3e778061p+0, -0x1.19083535b085dp-56,
    0x1.059b0d3158574p+0, 0x1.d73e2a475b465p-55,
    0x1.0874518759bc8p+0, 0x1.186be4bb284ffp-57,
    0x1.0b5586cf9890fp+0, 0x1.8a62e4adc610bp-54,
    0x1.0e3ec32d3d1a2p+0, 0x1.03a1727c57b53p-59,
    0x1.11301d0125b51p+0, -0x1.6c51039449b3ap-54,
    0x1.1429aaea92de0p+0, -0x1.32fbf9af1369ep-54,
    0x1.172b83c7d517bp+0, -0x1.19041b9d78a76p-55,
    0x1.1a35beb6fcb75p+0, 0x1.e5b4c7b4968e4p-55,
    0x1.1d4873168b9aap+0, 0x1.e016e00a2643cp-54,
    0x1.2063b88628cd6p+0, 0x1.dc775814a8495p-55,
    0x1.2387a6e756238p+0, 0x1.9b07eb6c70573p-54,
    0x1.26b4565e27cddp+0, 0x1.2bd339940e9d9p-55,
    0x1.29e9df51fdee1p+0, 0x1.612e8afad1255p-55,
    0x1.2d285a6e4030bp+0, 0x1.0024754db41d5p-54,
    0x1.306fe0a31b715p+0, 0x1.6f46ad23182e4p-55,
    0x1.33c08b26416ffp+0, 0x1.32721843659a6p-54,
    0x1.371a7373aa9cbp+0, -0x1.63aeabf42eae2p-54,
    0x1.3a7db34e59ff7p+0, -0x1.5e436d661f5e3p-56,
    0x1.3dea64c123422p+0, 0x1.ada0911f09ebcp-55,
    0x1.4160a21f72e2ap+0, -0x1.ef3691c309278p-58,
    0x1.44e086061892dp+0, 0x1.89b7a04ef80d0p-59,
    0x1.486a2b5c13cd0p+0, 0x1.3c1a3b69062f0p-56,
    0x1.4bfdad5362a27p+0, 0x1.d4397afec42e2p-56,
    0x1.4f9b2769d2ca7p+0, -0x1.4b309d25957e3p-54,
    0x1.5342b569d4f82p+0, -0x1.07abe1db13cadp-55,
    0x1.56f4736b527dap+0, 0x1.9bb2c011d93adp-54,
    0x1.5ab07dd485429p+0, 0x1.6324c054647adp-54,
    0x1.5e76f15ad2148p+0, 0x1.ba6f93080e65ep-54,
    0x1.6247eb03a5585p+0, -0x1.383c17e40b497p-54,
    0x1.6623882552225p+0, -0x1.bb60987591c34p-54,
    0x1.6a09e667f3bcdp+0, -0x1.bdd3413b26456p-54,
    0x1.6dfb23c651a2fp+0, -0x1.bbe3a683c88abp-57,
    0x1.71f75e8ec5f74p+0, -0x1.16e4786887a99p-55,
    0x1.75feb564267c9p+0, -0x1.0245957316dd3p-54,
    0x1.7a11473eb0187p+0, -0x1.41577ee04992fp-55,
    0x1.7e2f336cf4e62p+0, 0x1.05d02ba15797ep-56,
    0x1.82589994cce13p+0, -0x1.d4c1dd41532d8p-54,
    0x1.868d99b4492edp+0, -0x1.fc6f89bd4f6bap-54,
    0x1.8ace5422aa0dbp+0, 0x1.6e9f156864b27p-54,
    0x1.8f1ae99157736p+0, 0x1.5cc13a2e3976cp-55,
    0x1.93737b0cdc5e5p+0, -0x1.75fc781b57ebcp-57,
    0x1.97d829fde4e50p+0, -0x1.d185b7c1b85d1p-54,
    0x1.9c49182a3f090p+0, 0x1.c7c46b071f2bep-56,
    0x1.a0c667b5de565p+0, -0x1.359495d1cd533p-54,
    0x1.a5503b23e255dp+0, -0x1.d2f6edb8d41e1p-54,
    0x1.a9e6b5579fdbfp+0, 0x1.0fac90ef7fd31p-54,
    0x1.ae89f995ad3adp+0, 0x1.7a1cd345dcc81p-54,
    0x1.b33a2b84f15fbp+0, -0x1.2805e3084d708p-57,
    0x1.b7f76f2fb5e47p+0, -0x1.5584f7e54ac3bp-56,
    0x1.bcc1e904bc1d2p+0, 0x1.23dd07a2d9e84p-55,
    0x1.c199bdd85529cp+0, 0x1.11065895048ddp-55,
    0x1.c67f12e57d14bp+0, 0x1.2884dff483cadp-54,
    0x1.cb720dcef9069p+0, 0x1.503cbd1e949dbp-56,
    0x1.d072d4a07897cp+0, -0x1.cbc3743797a9cp-54,
    0x1.d5818dcfba487p+0, 0x1.2ed02d75b3707p-55,
    0x1.da9e603db3285p+0, 0x1.c2300696db532p-54,
    0x1.dfc97337b9b5fp+0, -0x1.1a5cd4f184b5cp-54,
    0x1.e502ee78b3ff6p+0, 0x1.39e8980a9cc8fp-55,
    0x1.ea4afa2a490dap+0, -0x1.e9c23179c2893p-54,
    0x1.efa1bee615a27p+0, 0x1.dc7f486a4b6b0p-54,
    0x1.f50765b6e4540p+0, 0x1.9d3e12dd8a18bp-54,
    0x1.fa7c1819e90d8p+0, 0x1.74853f3a5931ep-55,
};
static const double LOG_INVC[256] = {
    0x1.0000000000000p+0, 0x1.fd00000000000p-1, 0x1.fb00000000000p-1, 0x1.f920000000000p-1,
    0x1.f720000000000p-1, 0x1.f540000000000p-1, 0x1.f360000000000p-1, 0x1.f160000000000p-1,
    0x1.ef80000000000p-1, 0x1.eda0000000000p-1, 0x1.ebe0000000000p-1, 0x1.ea00000000000p-1,
    0x1.e820000000000p-1, 0x1.e660000000000p-1, 0x1.e480000000000p-1, 0x1.e2c0000000000p-1,
    0x1.e100000000000p-1, 0x1.df40000000000p-1, 0x1.dd80000000000p-1, 0x1.dbc0000000000p-1,
    0x1.da00000000000p-1, 0x1.d860000000000p-1, 0x1.d6a0000000000p-1, 0x1.d500000000000p-1,
    0x1.d340000000000p-1, 0x1.d1a0000000000p-1, 0x1.d000000000000p-1, 0x1.ce60000000000p-1,
    0x1.ccc0000000000p-1, 0x1.cb20000000000p-1, 0x1.c980000000000p-1, 0x1.c7e0000000000p-1,
    0x1.c660000000000p-1, 0x1.c4c0000000000p-1, 0x1.c340000000000p-1, 0x1.c1a0000000000p-1,
    0x1.c020000000000p-1, 0x1.bea0000000000p-1, 0x1.bd20000000000p-1, 0x1.bb80000000000p-1,
    0x1.ba20000000000p-1, 0x1.b8a0000000000p-1, 0x1.b720000000000p-1, 0x1.b5a0000000000p-1,
    0x1.b420000000000p-1, 0x1.b2c0000000000p-1, 0x1.b140000000000p-1, 0x1.afe0000000000p-1,
    0x1.ae80000000000p-1, 0x1.ad00000000000p-1, 0x1.aba0000000000p-1, 0x1.aa40000000000p-1,
    0x1.a8e0000000000p-1, 0x1.a780000000000p-1, 0x1.a620000000000p-1, 0x1.a4c0000000000p-1,
    0x1.a360000000000p-1, 0x1.a220000000000p-1, 0x1.a0c0000000000p-1, 0x1.9f80000000000p-1,
    0x1.9e20000000000p-1, 0x1.9ce0000000000p-1, 0x1.9b80000000000p-1, 0x1.9a40000000000p-1,
    0x1.9900000000000p-1, 0x1.97c0000000000p-1, 0x1.9660000000000p-1, 0x1.9520000000000p-1,
    0x1.93e0000000000p-1, 0x1.92a0000000000p-1, 0x1.9180000000000p-1, 0x1.9040000000000p-1,
    0x1.8f00000000000p-1, 0x1.8dc0000000000p-1, 0x1.8ca0000000000p-1, 0x1.8b60000000000p-1,
    0x1.8a40000000000p-1, 0x1.8900000000000p-1, 0x1.87e0000000000p-1, 0x1.86a0000000000p-1,
    0x1.8580000000000p-1, 0x1.8460000000000p-1, 0x1.8340000000000p-1, 0x1.8220000000000p-1,
    0x1.8100000000000p-1, 0x1.7fe0000000000p-1, 0x1.7ec0000000000p-1, 0x1.7da0000000000p-1,
    0x1.7c80000000000p-1, 0x1.7b60000000000p-1, 0x1.7a40000000000p-1, 0x1.7920000000000p-1,
    0x1.7820000000000p-1, 0x1.7700000000000p-1, 0x1.7600000000000p-1, 0x1.74e0000000000p-1,
    0x1.73e0000000000p-1, 0x1.72c0000000000p-1, 0x1.71c0000000000p-1, 0x1.70c0000000000p-1,
    0x1.6fa0000000000p-1, 0x1.6ea0000000000p-1, 0x1.6da0000000000p-1, 0x1.6ca0000000000p-1,
    0x1.6ba0000000000p-1, 0x1.6aa0000000000p-1, 0x1.69a0000000000p+0, 0x1.68a0000000000p+0,
    0x1.67a0000000000p+0, 0x1.66a0000000000p+0, 0x1.65a0000000000p+0, 0x1.64a0000000000p+0,
    0x1.63c0000000000p+0, 0x1.62c0000000000p+0, 0x1.61c0000000000p+0, 0x1.60e0000000000p+0,
    0x1.5fe0000000000p+0, 0x1.5ee0000000000p+0, 0x1.5e00000000000p+0, 0x1.5d00000000000p+0,
    0x1.5c20000000000p+0, 0x1.5b40000000000p+0, 0x1.5a40000000000p+0, 0x1.5960000000000p+0,
    0x1.5880000000000p+0, 0x1.57a0000000000p+0, 0x1.56a0000000000p+0, 0x1.55c0000000000p+0,
    0x1.54e0000000000p+0, 0x1.5400000000000p+0, 0x1.5320000000000p+0, 0x1.5240000000000p+0,
    0x1.5160000000000p+0, 0x1.5080000000000p+0, 0x1.4fa0000000000p+0, 0x1.4ec0000000000p+0,
    0x1.4e00000000000p+0, 0x1.4d20000000000p+0, 0x1.4c40000000000p+0, 0x1.4b60000000000p+0,
    0x1.4aa0000000000p+0, 0x1.49c0000000000p+0, 0x1.48e0000000000p+0, 0x1.4820000000000p+0,
    0x1.4740000000000p+0, 0x1.4680000000000p+0, 0x1.45a0000000000p+0, 0x1.44e0000000000p+0,
    0x1.4400000000000p+0, 0x1.4340000000000p+0, 0x1.4280000000000p+0, 0x1.41a0000000000p+0,
    0x1.40e0000000000p+0, 0x1.4020000000000p+0, 0x1.3f40000000000p+0, 0x1.3e80000000000p+0,
    0x1.3dc0000000000p+0, 0x1.3d00000000000p+0, 0x1.3c40000000000p+0, 0x1.3b80000000000p+0,
    0x1.3ac0000000000p+0, 0x1.3a00000000000p+0, 0x1.3940000000000p+0, 0x1.3880000000000p+0,
    0x1.37c0000000000p+0, 0x1.3700000000000p+0, 0x1.3640000000000p+0, 0x1.3580000000000p+0,
    0x1.34c0000000000p+0, 0x1.3400000000000p+0, 0x1.3360000000000p+0, 0x1.32a0000000000p+0,
    0x1.31e0000000000p+0, 0x1.3120000000000p+0, 0x1.3080000000000p+0, 0x1.2fc0000000000p+0,
    0x1.2f00000000000p+0, 0x1.2e60000000000p+0, 0x1.2da0000000000p+0, 0x1.2d00000000000p+0,
    0x1.2c40000000000p+0, 0x1.2ba0000000000p+0, 0x1.2ae0000000000p+0, 0x1.2a40000000000p+0,
    0x1.2980000000000p+0, 0x1.28e0000000000p+0, 0x1.2840000000000p+0, 0x1.2780000000000p+0,
    0x1.26e0000000000p+0, 0x1.2640000000000p+0, 0x1.2580000000000p+0, 0x1.24e0000000000p+0,
    0x1.2440000000000p+0, 0x1.23a0000000000p+0, 0x1.2300000000000p+0, 0x1.2240000000000p+0,
    0x1.21a0000000000p+0, 0x1.2100000000000p+0, 0x1.2060000000000p+0, 0x1.1fc0000000000p+0,
    0x1.1f20000000000p+0, 0x1.1e80000000000p+0, 0x1.1de0000000000p+0, 0x1.1d40000000000p+0,
    0x1.1ca0000000000p+0, 0x1.1c00000000000p+0, 0x1.1b60000000000p+0, 0x1.1ac0000000000p+0,
    0x1.1a20000000000p+0, 0x1.19a0000000000p+0, 0x1.1900000000000p+0, 0x1.1860000000000p+0,
    0x1.17c0000000000p+0, 0x1.1720000000000p+0, 0x1.16a0000000000p+0, 0x1.1600000000000p+0,
    0x1.1560000000000p+0, 0x1.14e0000000000p+0, 0x1.1440000000000p+0, 0x1.13a0000000000p+0,
    0x1.1320000000000p+0, 0x1.1280000000000p+0, 0x1.11e0000000000p+0, 0x1.1160000000000p+0,
    0x1.10c0000000000p+0, 0x1.1040000000000p+0, 0x1.0fa0000000000p+0, 0x1.0f20000000000p+0,
    0x1.0e80000000000p+0, 0x1.0e00000000000p+0, 0x1.0d60000000000p+0, 0x1.0ce0000000000p+0,
    0x1.0c60000000000p+0, 0x1.0bc0000000000p+0, 0x1.0b40000000000p+0, 0x1.0aa0000000000p+0,
    0x1.0a20000000000p+0, 0x1.09a0000000000p+0, 0x1.0900000000000p+0, 0x1.0880000000000p+0,
    0x1.0800000000000p+0, 0x1.0780000000000p+0, 0x1.06e0000000000p+0, 0x1.0660000000000p+0,
    0x1.05e0000000000p+0, 0x1.0560000000000p+0, 0x1.04e0000000000p+0, 0x1.0460000000000p+0,
    0x1.03c0000000000p+0, 0x1.0340000000000p+0, 0x1.02c0000000000p+0, 0x1.0240000000000p+0,
    0x1.01c0000000000p+0, 0x1.0140000000000p+0, 0x1.00c0000000000p+0, 0x1.0000000000000p+0,
};
static const double LOG_LOGC[512] = {
    0.0, 0.0,
    0x1.8121214586b54p-8, 0x1.c14b9f9377a1dp-65,
    0x1.41929f96832f0p-7, -0x1.c5517f64bc223p-61,
    0x1.bafb16b74919bp-7, 0x1.8077d52fb696ap-64,
    0x1.1e7d80b1fbf41p-6, 0x1.041a1af666c2ep-62,
    0x1.5ba9a5d9ac039p-6, 0x1.dc27046bc55d7p-60,
    0x1.99107b63b81e1p-6, 0x1.846d971733d21p-61,
    0x1.dad06ca02682fp-6, 0x1.f2b1523f583f1p-60,
    0x1.0c58fa19dfaaap-5, -0x1.d158b17912f05p-59,
    0x1.2b67c571a29d3p-5, -0x1.cd3a8a625a508p-59,
    0x1.487fceb8b26eep-5, -0x1.314ed9fac5e63p-59,
    0x1.67c94f2d4bb58p-5, 0x1.0413e6505e603p-59,
    0x1.873184bc09592p-5, -0x1.6ee2e4edc9fc9p-62,
    0x1.a49da08d3ffa4p-5, -0x1.817dbff460203p-59,
    0x1.c441e06f72a9ep-5, 0x1.f49850d154acap-60,
    0x1.e1e6713606d07p-5, -0x1.86909d7c4a7fap-59,
    0x1.ffa6911ab9301p-5, -0x1.cd9f1f95c2eedp-59,
    0x1.0ec139c5da601p-4, -0x1.b81ab1428cda6p-58,
    0x1.1dbd2643d190bp-4, 0x1.26cbbe249fc08p-59,
    0x1.2cc7284fe5f1cp-4, 0x1.7a1966544f879p-58,
    0x1.3bdf5a7d1ee64p-4, 0x1.7a976d3b5b45fp-59,
    0x1.49f054cd18720p-4, -0x1.33dcfb084e2c8p-59,
    0x1.59242ff043d37p-4, -0x1.40a6c6742cf97p-58,
    0x1.674f089365a7ap-4, -0x1.9acd8b33f8fdcp-58,
    0x1.769ef2c6b568dp-4, 0x1.d8c73b6a54f28p-58,
    0x1.84e40992a480bp-4, -0x1.f1a2a94bc175dp-58,
    0x1.9335e5d594989p-4, -0x1.478a85704ccb7p-58,
    0x1.a1949e8050083p-4, 0x1.d4593857661cdp-61,
    0x1.b0004ac1a86acp-4, -0x1.a3f203532d362p-60,
    0x1.be79020757086p-4, 0x1.98a6fb7b0dba2p-58,
    0x1.ccfedbfee13a8p-4, 0x1.197f3892ad2bap-59,
    0x1.db91f09680dfep-4, 0x1.6102b6bc4a773p-61,
    0x1.e911d663ba274p-4, -0x1.f1cc3363389f0p-59,
    0x1.f7be9fedbfde6p-4, -0x1.74acacef185fbp-61,
    0x1.02ab352ff25f4p-3, -0x1.9ca2a964d5002p-57,
    0x1.0a0ea2164af01p-3, -0x1.5a4f00a6d6cfdp-58,
    0x1.10e6a437247b7p-3, -0x1.4c0e1266b0ad7p-57,
    0x1.17c4862a78dfdp-3, -0x1.e2c7d6808794bp-57,
    0x1.1ea8520e8e6abp-3, 0x1.764657752e7d9p-61,
    0x1.2625d1e6ddf57p-3, -0x1.2c5e13c7b03d6p-57,
    0x1.2c81d0a59878fp-3, -0x1.6689aef246adcp-57,
    0x1.33779819ae5e9p-3, 0x1.6173c35985d85p-62,
    0x1.3a73730182ce0p-3, -0x1.a4904b1c831e1p-58,
    0x1.41756c0220c82p-3, -0x1.b9347cab5fa35p-58,
    0x1.487d8ddca5066p-3, 0x1.31798ee0598a6p-57,
    0x1.4ef51f6466de4p-3, 0x1.e90e466a992d4p-59,
    0x1.56092e02ba516p-3, 0x1.401a26765ec11p-59,
    0x1.5c8bc079d828ap-3, 0x1.ab771f2a4ec63p-57,
    0x1.6313a37335d76p-3, 0x1.05586f0ac97d8p-57,
    0x1.6a399dabbd383p-3, 0x1.96332bd4b341fp-57,
    0x1.70ccb9927bcf7p-3, 0x1.8baae587d9369p-58,
    0x1.77654128f6127p-3, 0x1.2eb7c9a39efdfp-57,
    0x1.7e033d66cd24dp-3, 0x1.52a2de3664f69p-61,
    0x1.84a6b759f512fp-3, -0x1.0055bf0c11f3dp-57,
    0x1.8b4fb826ff293p-3, 0x1.21a7c2fb622c9p-59,
    0x1.91fe49096581bp-3, 0x1.39e61438633bep-57,
    0x1.98b27353d7ce7p-3, -0x1.88f3fcae92c42p-62,
    0x1.9ecf7d8f3142dp-3, 0x1.3f1867a23c90fp-58,
    0x1.a58e729348f43p-3, 0x1.f5411546c2868p-58,
    0x1.abb55c31693adp-3, -0x1.6b2bc53360abap-58,
    0x1.b27f3ee67421cp-3, -0x1.b654063b02b47p-57,
    0x1.b8b027fe249dep-3, 0x1.ad167109c9c07p-58,
    0x1.bf851c067555fp-3, -0x1.c9810a959106ap-61,
    0x1.c5c0254bf23a6p-3, -0x1.55184bd38a145p-59,
    0x1.cc000c9db3c52p-3, 0x1.53d154280394fp-57,
    0x1.d244d99c85674p-3, -0x1.3fcddbe241680p-59,
    0x1.d92fd2b1383b6p-3, 0x1.472d4ee18fee2p-57,
    0x1.df7f018ce7720p-3, -0x1.0ddb409bbbf79p-62,
    0x1.e5d32e2e9ce87p-3, -0x1.5ec7d8dac0adcp-57,
    0x1.ec2c60824fbe9p-3, -0x1.ff33ec69adef7p-57,
    0x1.f1e75fadf9bdep-3, 0x1.d4da27c093199p-57,
    0x1.f84a32ead7c35p-3, 0x1.e3a67b3c6d777p-57,
    0x1.feb2233ea07cdp-3, 0x1.8de00938b4c40p-61,
    0x1.028f9c7035c1cp-2, 0x1.46160cceffeb2p-57,
    0x1.05761cbf25f1fp-2, 0x1.b8639cf256f53p-56,
    0x1.08b196753a123p-2, 0x1.2fe6d2b730bc5p-56,
    0x1.0b9c8e32d1911p-2, 0x1.3a24823e5002fp-57,
    0x1.0edd060b78081p-2, -0x1.92b49ef282b09p-57,
    0x1.11cc830ebd9b4p-2, -0x1.50a7cfa34e2cfp-56,
    0x1.1512088e66669p-2, -0x1.61e6a9ce4df56p-56,
    0x1.180618ef18adfp-2, 0x1.003792c71a980p-56,
    0x1.1afc59297024bp-2, 0x1.afacce1ffe363p-56,
    0x1.1df4cc7cf242dp-2, 0x1.f822afbf1ca5bp-59,
    0x1.20ef7630666d2p-2, -0x1.e65d6ad232b16p-59,
    0x1.23ec5991eba49p-2, 0x1.bb75d1addf870p-60,
    0x1.26eb79f70e869p-2, 0x1.95ee4c513255dp-56,
    0x1.29ecdabcdfa04p-2, -0x1.898847bb7982fp-56,
    0x1.2cf07f480a155p-2, -0x1.4fa89708c2b8fp-59,
    0x1.2ff66b04ea9d4p-2, 0x1.2dabe191d1c94p-56,
    0x1.32fea167a6d71p-2, -0x1.7f4fa572c6e95p-60,
    0x1.360925ec44f5dp-2, -0x1.ac1976885e1d7p-56,
    0x1.3915fc16c3c79p-2, -0x1.34c4e4e8363fep-57,
    0x1.3bce0507acee9p-2, -0x1.e44dcc59f6cf8p-57,
    0x1.3edf463c1683ep-2, 0x1.83d680d3c1084p-56,
    0x1.419b423d5e8c7p-2, 0x1.0dbb243827392p-57,
    0x1.44b0fb5af4f43p-2, -0x1.78c03c16b716dp-60,
    0x1.4770f5f6b9fa6p-2, -0x1.e4932bf3ca2b4p-58,
    0x1.4a8b341552b09p-2, 0x1.f8f437234349dp-57,
    0x1.4d4f3908901a0p-2, -0x1.4362b075df4b9p-57,
    0x1.501528da1f968p-2, -0x1.4e4b582ca5df9p-57,
    0x1.533624b59ca35p-2, -0x1.bc143c89ad43dp-57,
    0x1.560030809c75ap-2, 0x1.6d4c2a8f11536p-57,
    0x1.58cc2f91489f5p-2, -0x1.0602fd8ca6976p-60,
    0x1.5b9a24a3bd662p-2, 0x1.01beceb8baffcp-57,
    0x1.5e6a1279dbb70p-2, -0x1.89d59c1e18f42p-61,
    0x1.613bfbdb596a0p-2, 0x1.83c5841e04943p-56,
    -0x1.61b87c49757dcp-2, 0x1.9b9f366b9d573p-61,
    -0x1.5ee293627122bp-2, 0x1.332a8ab3835a3p-56,
    -0x1.5c0aa675484c6p-2, -0x1.edaaf6da03dd6p-57,
    -0x1.5930b2a24a406p-2, 0x1.2950383e2a278p-56,
    -0x1.5654b5039c926p-2, 0x1.f68491379ef38p-57,
    -0x1.5376aaad2978cp-2, 0x1.3901791f4ef46p-56,
    -0x1.50f2b0e1e0682p-2, -0x1.408c47b8d7e11p-56,
    -0x1.4e10c6bc8a061p-2, 0x1.7c0e9c90f9f07p-56,
    -0x1.4b2cc755559fcp-2, -0x1.a1c3a02dab12cp-59,
    -0x1.48a3900b8e0c3p-2, 0x1.a9c435205ae99p-56,
    -0x1.45bba0a07571bp-2, -0x1.8b2746c61d23cp-56,
    -0x1.42d193339888cp-2, -0x1.caa56557e6476p-59,
    -0x1.404308686a7e4p-2, 0x1.0bcfb6082ce6dp-56,
    -0x1.3d54fa5c1f710p-2, 0x1.e3265c6a1c98dp-56,
    -0x1.3ac2ea349541bp-2, 0x1.6174b459c0952p-58,
    -0x1.382f3216c4efap-2, 0x1.d21d1a7f6ca47p-58,
    -0x1.353b31376decdp-2, 0x1.afe6c26d9b4bfp-58,
    -0x1.32a3e562ad88cp-2, 0x1.055cf3157e69ap-57,
    -0x1.300aead06350cp-2, 0x1.52e91406a8a04p-57,
    -0x1.2d703f4fb2488p-2, 0x1.a1f71f9e24b2fp-56,
    -0x1.2a7441c8bf99fp-2, -0x1.4f7897c1af0ecp-57,
    -0x1.27d5ef1db5f37p-2, 0x1.ba3c6564f9e80p-58,
    -0x1.2535e4856ccfcp-2, -0x1.9075fd55b69f6p-56,
    -0x1.22941fbcf7966p-2, 0x1.76f5eb09628afp-56,
    -0x1.1ff09e7ceffa7p-2, -0x1.49513eacc12cbp-56,
    -0x1.1d4b5e796a245p-2, -0x1.2de8cbdd6118dp-56,
    -0x1.1aa45d61e8b2fp-2, 0x1.f8d5d4f34675bp-58,
    -0x1.17fb98e15095dp-2, -0x1.7458b5d97ba9dp-56,
    -0x1.15510e9ddcbebp-2, 0x1.36392273bea28p-56,
    -0x1.12a4bc3911a96p-2, -0x1.5f3d719b4eba0p-57,
    -0x1.1058bf9ae4ad5p-2, -0x1.89fa0ab4cb31dp-58,
    -0x1.0da917c36ff34p-2, -0x1.949e682709990p-56,
    -0x1.0af7a0eb6c27ap-2, 0x1.835b5d2929663p-56,
    -0x1.084458a1b87b3p-2, -0x1.bf7e6063c5ea6p-60,
    -0x1.05f25d3507940p-2, 0x1.6c6bd0d5db650p-56,
    -0x1.033badfa740e2p-2, 0x1.e87d6f48401a1p-56,
    -0x1.008326389b70cp-2, -0x1.fdf1e6fd54780p-57,
    -0x1.fc594b23e32c4p-3, -0x1.ae31316f7857dp-58,
    -0x1.f6e15321531b3p-3, 0x1.2ef589d8e8fcbp-57,
    -0x1.f22e5e72f105dp-3, -0x1.61d7d037c1899p-57,
    -0x1.ecaf6c50e779fp-3, 0x1.ecaa9de806dd1p-57,
    -0x1.e7f675089b55ap-3, -0x1.bd6203aad33c1p-57,
    -0x1.e27076e2af2e6p-3, 0x1.61578001e0162p-59,
    -0x1.ddb16d8ce9c22p-3, -0x1.0d1df68e8837ap-59,
    -0x1.d8ef91af31d5ep-3, 0x1.7f0d931e0e2cap-60,
    -0x1.d35f2626d50b6p-3, 0x1.74777f7511582p-57,
    -0x1.ce97213a60ce1p-3, -0x1.da19a199fc2f3p-58,
    -0x1.c9cc3f09b4813p-3, -0x1.0fcde09db0584p-57,
    -0x1.c4313e754e93dp-3, 0x1.062cd4a0a8294p-58,
    -0x1.bf601bb0e44e2p-3, 0x1.56b83c874aaf4p-57,
    -0x1.ba8c10ae46d19p-3, -0x1.c53ddd3b097acp-57,
    -0x1.b5b519e8fb5a4p-3, -0x1.ba27fdc19e1a0p-57,
    -0x1.b0db33d620ff7p-3, -0x1.438eab9063d0bp-60,
    -0x1.abfe5ae46124cp-3, 0x1.ea72be27390f0p-57,
    -0x1.a71e8b7bdfbbdp-3, -0x1.35910facdd138p-57,
    -0x1.a23bc1fe2b563p-3, -0x1.93711b07a998cp-59,
    -0x1.9d55fac62d05dp-3, 0x1.a7f0ed6f0a140p-58,
    -0x1.986d3228180cap-3, 0x1.2a6c8af000189p-58,
    -0x1.938164715959dp-3, 0x1.eb51d1cec565cp-59,
    -0x1.8e928de886d41p-3, 0x1.569d851a56770p-57,
    -0x1.89a0aacd4e703p-3, 0x1.095c29638284bp-63,
    -0x1.84abb75865139p-3, -0x1.5482c750b9638p-58,
    -0x1.7fb3afbb75412p-3, -0x1.5b73ec551633ep-61,
    -0x1.7ab890210d909p-3, -0x1.be36b2d6a0608p-59,
    -0x1.768f9603f56b5p-3, -0x1.e1ed62bae6091p-57,
    -0x1.718ec0614c65bp-3, -0x1.685e849196865p-59,
    -0x1.6c8ac7bd32dcdp-3, 0x1.ceb7efed75cdcp-57,
    -0x1.6783a82650b9ap-3, -0x1.d70474dcd1ee9p-58,
    -0x1.6350a28aaa758p-3, 0x1.3f547e9c51633p-57,
    -0x1.5e43b135bd5e3p-3, 0x1.699ddb38620bfp-57,
    -0x1.59338d9982086p-3, 0x1.65d22aa8ad7cfp-58,
    -0x1.54f8fbecdfed4p-3, -0x1.7a05784d1c3cfp-57,
    -0x1.4fe2f194f05edp-3, 0x1.2863a941ef62ep-57,
    -0x1.4ba36f39a55e5p-3, -0x1.68981bcc36756p-57,
    -0x1.468770542f13fp-3, -0x1.740e55ef03f34p-57,
    -0x1.4242f1b1d263ap-3, -0x1.3358c718eb1a2p-59,
    -0x1.3d20f03c3e7b1p-3, -0x1.eb8d51dd2ac56p-59,
    -0x1.38d7699164309p-3, 0x1.ad30e32247c95p-57,
    -0x1.33af575770e4fp-3, -0x1.9945fce5491eap-57,
    -0x1.2f60bcb8e7a7cp-3, 0x1.1ff0ee5d7c352p-60,
    -0x1.2b0fcf3b1a2f0p-3, 0x1.ae0e7ad30ad29p-57,
    -0x1.25ded0abc6ad2p-3, 0x1.eac3a26edd19cp-58,
    -0x1.2188bd9806263p-3, 0x1.f29fb75abd153p-60,
    -0x1.1d304f8c352c9p-3, -0x1.764175df7b4a6p-57,
    -0x1.17f6458fca611p-3, 0x1.4bdb0dc8fdffap-63,
    -0x1.13989fef47112p-3, 0x1.0f6bdda0e3ac7p-57,
    -0x1.0f3897134b12ep-3, -0x1.4c2ed85273cd7p-57,
    -0x1.0ad6285dd9861p-3, -0x1.8181bb32c5a5dp-60,
    -0x1.0671512ca596ep-3, -0x1.50c647eb86499p-58,
    -0x1.012850a6dfcafp-3, -0x1.e6b7fa406c718p-58,
    -0x1.f97c47ae59b3dp-4, 0x1.202bda7825aefp-58,
    -0x1.f0a30c01162a6p-4, -0x1.85f325c5bbacdp-58,
    -0x1.e7c4e8dc50612p-4, -0x1.406519872abacp-58,
    -0x1.dee1d8cd5ed72p-4, -0x1.7e358401dccebp-58,
    -0x1.d5f9d6587f0e4p-4, -0x1.fcbb1d08062d6p-60,
    -0x1.cd0cdbf8c13e1p-4, -0x1.36d4375d0c271p-58,
    -0x1.c41ae41ff3ce4p-4, -0x1.4ff2a60b06187p-58,
    -0x1.bb23e9368e975p-4, 0x1.83559db8ad559p-60,
    -0x1.b227e59b9de91p-4, 0x1.68a0f613f70f2p-58,
    -0x1.a926d3a4ad563p-4, -0x1.942f48aa70ea9p-58,
    -0x1.a020ad9db2443p-4, 0x1.e6fd21f501558p-59,
    -0x1.97156dc8f63e0p-4, -0x1.f328123425204p-59,
    -0x1.8e050e5f010a5p-4, 0x1.40184a2e5a240p-63,
    -0x1.86c10dcacaa46p-4, -0x1.1df08eb1d94f3p-61,
    -0x1.7da766d7b12cdp-4, 0x1.eeedfcdd94131p-58,
    -0x1.74888fec3505dp-4, 0x1.ffa5f1262e0fbp-60,
    -0x1.6b64831afe40dp-4, 0x1.426efbd2408d9p-61,
    -0x1.623b3a6c8688ap-4, 0x1.d95a212463045p-58,
    -0x1.5ae3378a8436ep-4, -0x1.293d8e75db4e1p-60,
    -0x1.51b073f06183fp-4, -0x1.a49e39a1a8be4p-58,
    -0x1.4878638cfa251p-4, -0x1.056742e6b13a3p-59,
    -0x1.411481711dcfap-4, -0x1.42c3a75ff2ff8p-61,
    -0x1.37d2d762831d0p-4, 0x1.5536ffe2b86c4p-58,
    -0x1.2e8bcf4c0953ap-4, 0x1.b4bfa6514e6b4p-59,
    -0x1.271be75573341p-4, -0x1.68019f7d8e730p-59,
    -0x1.1dcb263db1944p-4, -0x1.3d7a7a2605718p-58,
    -0x1.1474f58ac2e0fp-4, 0x1.0b7fd8bf6f55cp-60,
    -0x1.0cf8e05ad6a68p-4, 0x1.1980aed1a8368p-59,
    -0x1.0398d6b62254fp-4, 0x1.37f2ff33ff795p-58,
    -0x1.f829b0e783300p-5, -0x1.33e3f04f1ef23p-59,
    -0x1.e555c203269a3p-5, -0x1.1e1fa086732d8p-59,
    -0x1.d63dd1c4f2d50p-5, -0x1.1b48127516b77p-60,
    -0x1.c355dd0921f2dp-5, 0x1.9b2a03e3be3a7p-60,
    -0x1.b42dd711971bfp-5, 0x1.eb9759c130499p-60,
    -0x1.a131b1ba816afp-5, -0x1.78a9c9afd0290p-59,
    -0x1.91f9739c93afep-5, -0x1.8958ecf2f588ap-60,
    -0x1.82b9f4ee6a484p-5, 0x1.f835b339b7b57p-63,
    -0x1.6fa0593c7b683p-5, 0x1.0df14e5afb8c3p-59,
    -0x1.60506fe98da8bp-5, -0x1.fbf358fe4f25fp-59,
    -0x1.4d2238cb20903p-5, -0x1.d4bcd2c3b4af0p-59,
    -0x1.3dc1c153c612cp-5, -0x1.65a7ff7f900d0p-62,
    -0x1.2e59e2bacfd47p-5, -0x1.baf237da2e001p-61,
    -0x1.1b0d98923d980p-5, 0x1.e9ae889bac481p-60,
    -0x1.0b94f7c196176p-5, -0x1.da43f761f4dc4p-59,
    -0x1.f829b0e783300p-6, -0x1.33e3f04f1ef23p-60,
    -0x1.d91a66c543cc4p-6, 0x1.d34e608cbdaabp-62,
    -0x1.b2320b99305bep-6, -0x1.df8dbccb8d964p-61,
    -0x1.9300b1e9340f5p-6, -0x1.53cab292ca3f7p-60,
    -0x1.73c01cd777f49p-6, -0x1.e0cb17a563b7fp-60,
    -0x1.54703d7c6fd7ap-6, 0x1.586bc48b4636bp-60,
    -0x1.351104daa4849p-6, -0x1.917d19aae8095p-60,
    -0x1.15a263de88b93p-6, 0x1.62e289ea83a5fp-60,
    -0x1.dc84b19123815p-7, 0x1.5f0e2d267d821p-61,
    -0x1.9d61aadc6bd8dp-7, 0x1.39b097b525947p-61,
    -0x1.5e1f703ecbe50p-7, -0x1.3eb0bb43693b9p-61,
    -0x1.1ebde2d1997e6p-7, 0x1.ffa46e1b2ec81p-64,
    -0x1.be79c70058ec9p-8, 0x1.964fefef02b62p-66,
    -0x1.3f38a60f06489p-8, -0x1.693c937494046p-62,
    -0x1.7f7047d7983dap-9, -0x1.a275a19204e80p-63,
    0.0, 0.0,
};
static const double SINCOS_TAB[424] = {
    0.0, 0.0, 0.0, 0.0,
    0x1.0000000000000p+0, 0x1.0000000000000p+0, 0.0, 0.0,
    0x1.fffaaaaeeeed5p-7, 0x1.fffaaa8000000p-7, 0x1.77776a8000000p-34, -0x1.2ab639a9f0776p-63,
    0x1.fff000155549fp-1, 0x1.fff0000000000p-1, 0x1.55549f0000000p-29, 0x1.28a28a03a5ef3p-55,
    0x1.ffeaaaeeee86fp-6, 0x1.ffeaab0000000p-6, -0x1.1117910000000p-34, -0x1.cd406fb224ae2p-60,
    0x1.ffc00155527d3p-1, 0x1.ffc0018000000p-1, -0x1.556c168000000p-28, -0x1.3b54492d89b5bp-55,
    0x1.7fdc01032fba9p-5, 0x1.7fdc010000000p-5, 0x1.97dd480000000p-36, -0x1.599bdf46e997ap-59,
    0x1.ff7006bfdf99fp-1, 0x1.ff70068000000p-1, 0x1.fefccf8000000p-28, -0x1.8b3b560648d5fp-56,
    0x1.ffaaaeeed4edbp-5, 0x1.ffaaaf0000000p-5, -0x1.12b1250000000p-33, -0x1.2d16d32684b69p-59,
    0x1.ff0015549f4d3p-1, 0x1.ff00158000000p-1, -0x1.5b05968000000p-28, 0x1.328387b99426fp-55,
    0x1.3facb12d1755bp-4, 0x1.3facb10000000p-4, 0x1.68baad8000000p-31, -0x1.921915299468bp-58,
    0x1.fe7034129ef6fp-1, 0x1.fe70340000000p-1, 0x1.29ef6f0000000p-29, -0x1.cbf4337c96f97p-57,
    0x1.7f701032550e4p-4, 0x1.7f70100000000p-4, 0x1.92a8720000000p-31, 0x1.afc2d1800501ap-60,
    0x1.fdc06bf7e6b9bp-1, 0x1.fdc06c0000000p-1, -0x1.0328ca0000000p-30, 0x1.31902b535f8dbp-55,
    0x1.bf1b78568391dp-4, 0x1.bf1b788000000p-4, -0x1.4be3718000000p-31, 0x1.e91841dea4cc8p-58,
    0x1.fcf0c800e99b1p-1, 0x1.fcf0c80000000p-1, 0x1.d336200000000p-34, 0x1.ea3d786d186acp-57,
    0x1.feaaeee86ee36p-4, 0x1.feaaef0000000p-4, -0x1.7911ca0000000p-32, -0x1.afcb2bcc6f03bp-59,
    0x1.fc015527d5bd3p-1, 0x1.fc01550000000p-1, 0x1.3eade98000000p-28, 0x1.b68f35094efb8p-55,
    0x1.1f0d3d7afceafp-3, 0x1.1f0d3d8000000p-3, -0x1.40c5440000000p-33, -0x1.6ef95099769a5p-57,
    0x1.faf22263c4bd3p-1, 0x1.faf2228000000p-1, -0x1.c3b42d0000000p-29, -0x1.52ace133a2769p-58,
    0x1.3eb312c5d66cbp-3, 0x1.3eb3130000000p-3, -0x1.d14c9a8000000p-30, 0x1.47d666b66cb91p-57,
    0x1.f9c340a7cc428p-1, 0x1.f9c3408000000p-1, 0x1.3e62140000000p-28, 0x1.c5b6b063b7462p-55,
    0x1.5e44fcfa126f3p-3, 0x1.5e44fd0000000p-3, -0x1.7b64340000000p-33, -0x1.6f443063f89b6p-57,
    0x1.f874c2e1eecf6p-1, 0x1.f874c30000000p-1, -0x1.e1130a0000000p-29, -0x1.c6514e1332b16p-55,
    0x1.7dc102fbaf2b5p-3, 0x1.7dc1030000000p-3, -0x1.14352c0000000p-33, 0x1.5ab50e23c97c3p-59,
    0x1.f706bdf9ece1cp-1, 0x1.f706be0000000p-1, -0x1.84c7900000000p-31, -0x1.698c80c36dcb4p-55,
    0x1.9d252d0cec312p-3, 0x1.9d252d0000000p-3, 0x1.9d86240000000p-32, 0x1.9c43d80b1137dp-58,
    0x1.f57948cff6797p-1, 0x1.f579490000000p-1, -0x1.804c348000000p-28, 0x1.e3a0d3e03b1d4p-57,
    0x1.bc6f84edc6199p-3, 0x1.bc6f850000000p-3, -0x1.239e670000000p-31, 0x1.9c1a56a7b0cabp-57,
    0x1.f3cc7c3b3d16ep-1, 0x1.f3cc7c0000000p-1, 0x1.d9e8b70000000p-28, -0x1.21a3ad28a3494p-57,
    0x1.db9e15fb5a5d0p-3, 0x1.db9e160000000p-3, -0x1.2968c00000000p-33, -0x1.32e20d6cc6fc2p-57,
    0x1.f20073086649fp-1, 0x1.f200730000000p-1, 0x1.0cc93e0000000p-30, 0x1.b940416c1984bp-56,
    0x1.faaeed4f31577p-3, 0x1.faaeed8000000p-3, -0x1.8675448000000p-30, -0x1.15d88508e32b8p-57,
    0x1.f01549f7deea1p-1, 0x1.f0154a0000000p-1, -0x1.0422be0000000p-30, 0x1.d3c1e99e5cafdp-55,
    0x1.0cd00cef36436p-2, 0x1.0cd00d0000000p-2, -0x1.0c9bca0000000p-30, -0x1.9fb0a0c93e2b4p-56,
    0x1.ee0b1fbc0f11cp-1, 0x1.ee0b1f8000000p-1, 0x1.e0788e0000000p-28, -0x1.bfd2380bbc3b1p-59,
    0x1.1c37d64c6b876p-2, 0x1.1c37d68000000p-2, -0x1.9ca3c50000000p-29, 0x1.46076fe0dcff4p-56,
    0x1.ebe214f76efa8p-1, 0x1.ebe2150000000p-1, -0x1.1220b00000000p-30, -0x1.02f9f12ba543ep-55,
    0x1.2b8ddc43eb49fp-2, 0x1.2b8ddc8000000p-2, -0x1.e0a5b08000000p-29, 0x1.1553899f2d807p-57,
    0x1.e99a4c3a7cd83p-1, 0x1.e99a4c0000000p-1, 0x1.d3e6c18000000p-28, -0x1.2264b1bc53ce8p-55,
    0x1.3ad129769d3d8p-2, 0x1.3ad1298000000p-2, -0x1.2c58500000000p-31, 0x1.03d550487839ap-63,
    0x1.e733ea0193d40p-1, 0x1.e733ea0000000p-1, 0x1.93d4000000000p-33, -0x1.6428b3546ce13p-55,
    0x1.4a00c9b0f3d20p-2, 0x1.4a00c98000000p-2, 0x1.879e900000000p-29, 0x1.823ba6bb08eadp-56,
    0x1.e4af14b2a449cp-1, 0x1.e4af148000000p-1, 0x1.95224e0000000p-28, -0x1.68ca02e8a6833p-55,
    0x1.591bc9fa2f597p-2, 0x1.591bca0000000p-2, -0x1.7429a40000000p-32, 0x1.7c74bac3fe0cbp-57,
    0x1.e20bf49acd6c1p-1, 0x1.e20bf48000000p-1, 0x1.acd6c10000000p-29, -0x1.660aec7ef636bp-58,
    0x1.682138a38d7f7p-2, 0x1.6821388000000p-2, 0x1.1c6bfb8000000p-29, -0x1.d889202444aadp-56,
    0x1.df4ab3ebd875ep-1, 0x1.df4ab40000000p-1, -0x1.4278a20000000p-29, -0x1.e2d8a7e6736c4p-55,
    0x1.7710255764214p-2, 0x1.7710258000000p-2, -0x1.44def60000000p-29, -0x1.6ead7314bb6cep-57,
    0x1.dc6b7eb995912p-1, 0x1.dc6b7e8000000p-1, 0x1.ccac890000000p-28, 0x1.4b364776dcd35p-58,
    0x1.85e7a12826949p-2, 0x1.85e7a10000000p-2, 0x1.4134a48000000p-29, 0x1.8a40e9b5face0p-56,
    0x1.d96e82f71a9dcp-1, 0x1.d96e830000000p-1, -0x1.1cac480000000p-30, 0x1.ff61bd5d2039dp-55,
    0x1.94a6be9f546c5p-2, 0x1.94a6be8000000p-2, 0x1.f546c50000000p-30, -0x1.69ce13e683f58p-56,
    0x1.d653f073e4040p-1, 0x1.d653f08000000p-1, -0x1.837f800000000p-30, -0x1.76236434bec37p-55,
    0x1.a34c91cc50ccap-2, 0x1.a34c920000000p-2, -0x1.9d799b0000000p-29, -0x1.a310e3b50cecdp-58,
    0x1.d31bf8d8d7c06p-1, 0x1.d31bf90000000p-1, -0x1.3941fd0000000p-28, 0x1.e60dd3089cbddp-56,
    0x1.b1d8305321617p-2, 0x1.b1d8308000000p-2, -0x1.66f4f48000000p-29, -0x1.ae242cb99f519p-56,
    0x1.cfc6cfa52ad9fp-1, 0x1.cfc6cf8000000p-1, 0x1.2956cf8000000p-28, 0x1.8b5b5508f2a0dp-55,
    0x1.c048b17b140a3p-2, 0x1.c048b18000000p-2, -0x1.3afd740000000p-32, 0x1.19fe6757e9fa7p-57,
    0x1.cc54aa2b2972ep-1, 0x1.cc54aa0000000p-1, 0x1.594b970000000p-28, 0x1.4ee162ba83a98p-57,
    0x1.ce9d2e3d4a51fp-2, 0x1.ce9d2e0000000p-2, 0x1.ea528f8000000p-29, -0x1.2fc8a12dae298p-57,
    0x1.c8c5bf8ce1a84p-1, 0x1.c8c5bf8000000p-1, 0x1.9c35080000000p-30, 0x1.ab3d1a1590123p-56,
    0x1.dcd4c15329c9ap-2, 0x1.dcd4c18000000p-2, -0x1.66b1b30000000p-29, 0x1.0d4c6e171fd9ap-56,
    0x1.c51a48b8b175ep-1, 0x1.c51a488000000p-1, 0x1.c58baf0000000p-28, -0x1.1bbb43b9aa880p-57,
    0x1.eaee8744b05f0p-2, 0x1.eaee878000000p-2, -0x1.da7d080000000p-29, -0x1.789b43c9b027dp-58,
    0x1.c1528065b7d50p-1, 0x1.c152808000000p-1, -0x1.a482b00000000p-29, -0x1.892111312e828p-55,
    0x1.f8e99e76abc97p-2, 0x1.f8e99e8000000p-2, -0x1.2a86d20000000p-31, 0x1.9d950af2d00a3p-58,
    0x1.bd6ea310294f5p-1, 0x1.bd6ea30000000p-1, 0x1.0294f50000000p-29, 0x1.31bbcc88c109dp-56,
    0x1.0362939c69955p-1, 0x1.0362938000000p-1, 0x1.c699550000000p-29, -0x1.2d8cd78397b01p-55,
    0x1.b96eeef58840ep-1, 0x1.b96eef0000000p-1, -0x1.4ef7e40000000p-30, 0x1.45a3cc78fade0p-58,
    0x1.0a4021e9e1001p-1, 0x1.0a40220000000p-1, -0x1.61efff0000000p-29, -0x1.6f643a13914f6p-55,
    0x1.b553a410c104ep-1, 0x1.b553a40000000p-1, 0x1.0c104e0000000p-29, 0x1.8ff7947027a15p-58,
    0x1.110d0c4b69c3bp-1, 0x1.110d0c8000000p-1, -0x1.a4b1e28000000p-28, 0x1.d918998809981p-55,
    0x1.b11d04162a4c6p-1, 0x1.b11d040000000p-1, 0x1.62a4c60000000p-29, 0x1.1dd561efbc0c2p-56,
    0x1.17c8e5f2eedb0p-1, 0x1.17c8e60000000p-1, -0x1.a224a00000000p-30, 0x1.35e57102e2488p-57,
    0x1.accb526f69de5p-1, 0x1.accb528000000p-1, -0x1.09621b0000000p-29, 0x1.8fb6a8dd6b6ccp-55,
    0x1.1e7343236574cp-1, 0x1.1e73430000000p-1, 0x1.1b2ba60000000p-28, 0x1.22a3fa4f41d5ap-56,
    0x1.a85ed4373e02dp-1, 0x1.a85ed40000000p-1, 0x1.b9f0168000000p-28, 0x1.9be06385ec792p-57,
    0x1.250bb93788bbbp-1, 0x1.250bb90000000p-1, 0x1.bc45dd8000000p-28, 0x1.ea3d02457bccep-56,
    0x1.a3d7d0352bdcfp-1, 0x1.a3d7d00000000p-1, 0x1.a95ee78000000p-28, -0x1.68dbaeca19669p-55,
    0x1.2b91dea88421ep-1, 0x1.2b91de8000000p-1, 0x1.44210f0000000p-28, -0x1.fa371db216ab0p-55,
    0x1.9f368ed912f85p-1, 0x1.9f368f0000000p-1, -0x1.37683d8000000p-28, -0x1.1d200c5791606p-55,
    0x1.32054b148bc4fp-1, 0x1.32054b0000000p-1, 0x1.48bc4f0000000p-29, 0x1.f6b42095a135bp-55,
    0x1.9a7b5a36a6514p-1, 0x1.9a7b5a0000000p-1, 0x1.b5328a0000000p-28, 0x1.722cfcc9fa7a9p-55,
    0x1.386597456282bp-1, 0x1.3865978000000p-1, -0x1.d4ebea8000000p-28, -0x1.10fada93b07a8p-56,
    0x1.95a67e00cb1fdp-1, 0x1.95a67e0000000p-1, 0x1.963fa00000000p-34, -0x1.0befda21f862dp-55,
    0x1.3eb25d36cd53ap-1, 0x1.3eb25d0000000p-1, 0x1.b66a9d0000000p-28, -0x1.be570e1570fc0p-58,
    0x1.90b84784ddaf7p-1, 0x1.90b8478000000p-1, 0x1.376bdc0000000p-31, -0x1.0feb10ab93b87p-56,
    0x1.44eb381cf386bp-1, 0x1.44eb380000000p-1, 0x1.cf386b0000000p-29, -0x1.3ed6c1e6a5505p-55,
    0x1.8bb105a5dc900p-1, 0x1.8bb1058000000p-1, 0x1.2ee4800000000p-28, 0x1.863e03e9474c1p-55,
    0x1.4b0fc46aab761p-1, 0x1.4b0fc48000000p-1, -0x1.55489f0000000p-29, 0x1.0da05738cc59cp-61,
    0x1.869108d77a6c6p-1, 0x1.8691090000000p-1, -0x1.442c9d0000000p-28, 0x1.338ffe2bfe9ddp-56,
    0x1.511f9fd7b351cp-1, 0x1.511fa00000000p-1, -0x1.4265720000000p-28, -0x1.5c0e861c48831p-55,
    0x1.8158a31916d5dp-1, 0x1.8158a30000000p-1, 0x1.916d5d0000000p-29, -0x1.de8b90b8228dep-57,
    0x1.571a6966d59b3p-1, 0x1.571a698000000p-1, -0x1.92a64d0000000p-29, 0x1.c843b4d0fb197p-58,
    0x1.7c0827f09e54fp-1, 0x1.7c08280000000p-1, -0x1.ec35620000000p-30, -0x1.c73d6d72aee68p-57,
    0x1.5cffc16bf8f0dp-1, 0x1.5cffc18000000p-1, -0x1.4070f30000000p-29, 0x1.96cb370eb578ap-55,
    0x1.769fec655211fp-1, 0x1.769fec8000000p-1, -0x1.aadee10000000p-29, -0x1.827d5cf8c68c5p-57,
    0x1.62cf49921ac79p-1, 0x1.62cf498000000p-1, 0x1.21ac790000000p-29, -0x1.edd9855b6241ap-55,
    0x1.712046fa77678p-1, 0x1.7120470000000p-1, -0x1.6226200000000p-31, 0x1.425b0a5029c81p-55,
    0x1.6888a4e134b2fp-1, 0x1.6888a50000000p-1, -0x1.ecb4d10000000p-29, -0x1.6b7d37644d5e6p-55,
    0x1.6b898fa9efb5dp-1, 0x1.6b898f8000000p-1, 0x1.4f7dae8000000p-28, 0x1.15ac786ccf4b2p-56,
    0x1.6e2b77c40bde1p-1, 0x1.6e2b780000000p-1, -0x1.dfa10f8000000p-28, -0x1.0e729857fad53p-56,
    0x1.65dc1fdeb8cbap-1, 0x1.65dc200000000p-1, -0x1.0a39a30000000p-28, -0x1.97c1b47337c77p-58,
    0x1.73b7680dea578p-1, 0x1.73b7680000000p-1, 0x1.bd4af00000000p-30, -0x1.2248306dc12a2p-56,
    0x1.6018526f563dfp-1, 0x1.6018528000000p-1, -0x1.0a9c210000000p-29, 0x1.46ca5e0e432d0p-55,
};
static const double ATAN_TAB[130] = {
    0.0, 0.0,
    0x1.fff555bbb729bp-7, -0x1.220c39d4dff50p-61,
    0x1.ffd55bba97625p-6, -0x1.5ec431444912cp-60,
    0x1.7fb818430da2ap-5, -0x1.86ef8f794f105p-63,
    0x1.ff55bb72cfdeap-5, -0x1.c934d86d23f1dp-60,
    0x1.3f59f0e7c559dp-4, 0x1.ac4ce285df847p-58,
    0x1.7ee182602f10fp-4, -0x1.cfb654c0c3d98p-58,
    0x1.be39ebe6f07c3p-4, 0x1.f7b8f29a05987p-58,
    0x1.fd5ba9aac2f6ep-4, -0x1.cd37686760c17p-59,
    0x1.1e1fafb043727p-3, -0x1.b485914dacf8cp-59,
    0x1.3d6eee8c6626cp-3, 0x1.61a3b0ce9281bp-57,
    0x1.5c9811e3ec26ap-3, -0x1.054ab2c010f3dp-58,
    0x1.7b97b4bce5b02p-3, 0x1.347b0b4f881cap-58,
    0x1.9a6a8e96c8626p-3, 0x1.cf601e7b4348ep-59,
    0x1.b90d7529260a2p-3, 0x1.17b10d2e0e5abp-61,
    0x1.d77d5df205736p-3, 0x1.c648d1534597ep-57,
    0x1.f5b75f92c80ddp-3, 0x1.8ab6e3cf7afbdp-57,
    0x1.09dc597d86362p-2, 0x1.62e47390cb865p-56,
    0x1.18bf5a30bf178p-2, 0x1.30ca4748b1bf9p-57,
    0x1.278372057ef46p-2, -0x1.077cdd36dfc81p-56,
    0x1.362773707ebccp-2, -0x1.963a544b672d8p-57,
    0x1.44aa436c2af0ap-2, -0x1.5d5e43c55b3bap-56,
    0x1.530ad9951cd4ap-2, -0x1.2566480884082p-57,
    0x1.614840309cfe2p-2, -0x1.a725715711f00p-56,
    0x1.6f61941e4def1p-2, -0x1.c63aae6f6e918p-56,
    0x1.7d5604b63b3f7p-2, 0x1.69c885c2b249ap-56,
    0x1.8b24d394a1b25p-2, 0x1.b6d0ba3748fa8p-56,
    0x1.98cd5454d6b18p-2, 0x1.9e6c988fd0a77p-56,
    0x1.a64eec3cc23fdp-2, -0x1.24dec1b50b7ffp-56,
    0x1.b3a911da65c6cp-2, 0x1.ae187b1ca5040p-56,
    0x1.c0db4c94ec9f0p-2, -0x1.cc1ce70934c34p-56,
    0x1.cde53432c1351p-2, -0x1.a2cfa4418f1adp-56,
    0x1.dac670561bb4fp-2, 0x1.a2b7f222f65e2p-56,
    0x1.e77eb7f175a34p-2, 0x1.0e53dc1bf3435p-56,
    0x1.f40dd0b541418p-2, -0x1.a3992dc382a23p-57,
    0x1.0039c73c1a40cp-1, -0x1.b32c949c9d593p-55,
    0x1.0657e94db30d0p-1, -0x1.d5b495f6349e6p-56,
    0x1.0c6145b5b43dap-1, 0x1.974fa13b5404fp-58,
    0x1.1255d9bfbd2a9p-1, -0x1.2bdaee1c0ee35p-58,
    0x1.1835a88be7c13p-1, 0x1.c621cec00c301p-55,
    0x1.1e00babdefeb4p-1, -0x1.928df287a668fp-58,
    0x1.23b71e2cc9e6ap-1, 0x1.c421c9f38224ep-57,
    0x1.2958e59308e31p-1, -0x1.09e73b0c6c087p-56,
    0x1.2ee628406cbcap-1, 0x1.c5d5e9ff0cf8dp-55,
    0x1.345f01cce37bbp-1, 0x1.1021137c71102p-55,
    0x1.39c391cd4171ap-1, -0x1.2304331d8bf46p-55,
    0x1.3f13fb89e96f4p-1, 0x1.ecf8b492644f0p-56,
    0x1.445065b795b56p-1, -0x1.f76d0163f79c8p-56,
    0x1.4978fa3269ee1p-1, 0x1.2419a87f2a458p-56,
    0x1.4e8de5bb6ec04p-1, 0x1.4a33dbeb3796cp-55,
    0x1.538f57b89061fp-1, -0x1.1bb74abda520cp-55,
    0x1.587d81f732fbbp-1, -0x1.5e5c9d8c5a950p-56,
    0x1.5d58987169b18p-1, 0x1.0028e4bc5e7cap-57,
    0x1.6220d115d7b8ep-1, -0x1.2b785350ee8c1p-57,
    0x1.66d663923e087p-1, -0x1.6ea6febe8bbbap-56,
    0x1.6b798920b3d99p-1, -0x1.a80386188c50ep-55,
    0x1.700a7c5784634p-1, -0x1.8c34d25aadef6p-56,
    0x1.748978fba8e0fp-1, 0x1.7b2a6165884a1p-59,
    0x1.78f6bbd5d315ep-1, 0x1.406a089803740p-55,
    0x1.7d528289fa093p-1, 0x1.560821e2f3aa9p-55,
    0x1.819d0b7158a4dp-1, -0x1.bf76229d3b917p-56,
    0x1.85d69576cc2c5p-1, 0x1.6b66e7fc8b8c3p-57,
    0x1.89ff5ff57f1f8p-1, -0x1.55b9a5e177a1bp-55,
    0x1.8e17aa99cc05ep-1, -0x1.ec182ab042f61p-56,
    0x1.921fb54442d18p-1, 0x1.1a62633145c07p-55,
};
static const uint64_t TWO_OVER_PI[20] = {
    0xa2f9836e4e441529u, 0xfc2757d1f534ddc0u, 0xdb6295993c439041u,
    0xfe5163abdebbc561u, 0xb7246e3a424dd2e0u, 0x06492eea09d1921cu,
    0xfe1deb1cb129a73eu, 0xe88235f52ebb4484u, 0xe99c7026b45f7e41u,
    0x3991d639835339f4u, 0x9c845f8bbdf9283bu, 0x1ff897ffde05980fu,
    0xef2f118b5a0a6d1fu, 0x6d367ecf27cb09b7u, 0x4f463f669e5fea2du,
    0x7527bac7ebe5f17bu, 0x3d0739f78a5292eau, 0x6bfb5fb11f8d5d08u,
    0x56033046fc7b6babu, 0xf0cfbc209af4361du,
};

/* ------------------------------------------------------------------------------------------------- constants */
static const double EXP_INVL = 0x1.71547652b82fep+6; /* 64/ln2 */
static const double EXP_L1 = 0x1.62e42fefa0000p-7;   /* ln2/64, 36 bits: k L1 exact for |k| < 2^17 */
static const double EXP_L2 = 0x1.cf79abc9e3b3ap-46;  /* ln2/64 - L1 */
static const double LN2_HI = 0x1.62e42fefa3800p-1;   /* ln2, 42 bits: e LN2_HI exact for |e| < 2^11 */
static const double LN2_LO = 0x1.ef35793c76730p-45;  /* ln2 - LN2_HI */
static const double INV_PIO2 = 0x1.45f306dc9c883p-1; /* 2/pi */
static const double PIO2_1 = 0x1.921fb54400000p+0;   /* pi/2 = P1 + P2 + P3 + P4: 33-bit parts, k Pn exact */
static const double PIO2_2 = 0x1.0b4611a600000p-34;  /*   for |k| < 2^20 */
static const double PIO2_3 = 0x1.3198a2e000000p-69;
static const double PIO2_4 = 0x1.b839a252049c1p-104;
static const double PIO2_HI = 0x1.921fb54442d18p+0, PIO2_LO = 0x1.1a62633145c07p-54;
static const double PI_HI = 0x1.921fb54442d18p+1, PI_LO = 0x1.1a62633145c07p-53;
static const double PIO4 = 0x1.921fb54442d18p-1, PI3O4 = 0x1.2d97c7f3321d2p+1; /* nearest to pi/4, 3pi/4 */
static const double LNSQRT2PI_HI = 0x1.d67f1c864beb5p-1, LNSQRT2PI_LO = -0x1.65b5a1b7ff5dfp-55;

/* ---------------------------------------------------------------------------------------------- exp, expm1 */
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

/* ------------------------------------------------------------------------------------------------ log, log1p */
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

/* ------------------------------------------------------------------------------------------------------- pow */
static inline int is_integer(double y) { return floor(y) == y; } /* y finite */

static inline int is_odd_integer(double y) { /* y finite */
    return fabs(y) < 0x1p53 && floor(y) == y && floor(0.5 * y) != 0.5 * y;
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

/* --------------------------------------------------------------------------------------------- sin, cos, sincos */
/* the bits of 2/pi from offset o (0 = the first bit after the binary point), 64 of them */
static inline uint64_t two_over_pi_bits(int o) {
    int w = o >> 6, b = o & 63;
    uint64_t v = TWO_OVER_PI[w] << b;
    if (b) v |= TWO_OVER_PI[w + 1] >> (64 - b);
    return v;
}

/* the 128-bit product a b = hi 2^64 + lo (32-bit limbs: portable C99) */
static inline void mul64(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo) {
    uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
    *lo = (mid << 32) | (p00 & 0xffffffffu);
    *hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
}

/* bits pos .. pos+63 of the 320-bit integer p[0] + p[1] 2^64 + ... */
static inline uint64_t bits_at(const uint64_t p[5], int pos) {
    int w = pos >> 6, b = pos & 63;
    uint64_t v = p[w] >> b;
    if (b) v |= p[w + 1] << (64 - b);
    return v;
}

/* Payne & Hanek: x = M 2^e (M a 53-bit integer, x >= 2^20) times 2/pi modulo 4, in integer arithmetic.  The
 * bits b_i 2^-i of 2/pi with i <= e - 2 give multiples of 4 and are skipped; 192 bits from i0 = max(1, e - 1)
 * give the product P = M W with s = i0 + 191 - e >= 190 fraction bits, truncation error < 2^(53 - s).  The
 * fraction f in [-1/2, 1/2) (128 bits) times pi/2 is r; the quadrant is the integer part mod 4. */
static int reduce_large(double ax, double *rh, double *rl) {
    uint64_t ix = bits_of(ax);
    int e = (int)(ix >> 52) - 1075;
    uint64_t M = (ix & 0x000fffffffffffffULL) | (1ULL << 52);
    int i0 = e - 1 > 1 ? e - 1 : 1;
    int s = i0 + 191 - e, o = i0 - 1;
    uint64_t w2 = two_over_pi_bits(o), w1 = two_over_pi_bits(o + 64), w0 = two_over_pi_bits(o + 128);
    uint64_t h0, l0, h1, l1, h2, l2, p[5];
    mul64(M, w0, &h0, &l0);
    mul64(M, w1, &h1, &l1);
    mul64(M, w2, &h2, &l2);
    p[0] = l0;
    p[1] = h0 + l1;
    uint64_t c1 = p[1] < l1;
    p[2] = h1 + l2;
    uint64_t c2 = p[2] < l2;
    p[2] += c1;
    c2 += p[2] < c1;
    p[3] = h2 + c2;
    p[4] = 0;
    uint64_t fh = bits_at(p, s - 64), fl = bits_at(p, s - 128);
    int q = (int)(bits_at(p, s) & 3);
    double sg = 1.0;
    if (fh >> 63) { /* f >= 1/2: the next quadrant, f - 1 = -(2^128 - F) 2^-128 */
        q = (q + 1) & 3;
        sg = -1.0;
        fl = ~fl + 1;
        fh = ~fh + (fl == 0);
    }
    int sh = 0; /* normalize F (|f| >= 2^-62 for every double x, so fh != 0 in practice) */
    if (fh == 0) {
        fh = fl;
        fl = 0;
        sh = 64;
        if (fh == 0) {
            *rh = *rl = 0.0;
            return q;
        }
    }
    while (!(fh >> 63)) {
        fh = (fh << 1) | (fl >> 63);
        fl <<= 1;
        sh++;
    }
    /* f = fh 2^(-64-sh) + fl 2^(-128-sh): the top 53 bits and the next 53 as an exact double-double */
    double f1 = (double)(fh >> 11) * pow2i(-53 - sh);
    double f2 = (double)(((fh & 0x7ffu) << 42) | (fl >> 22)) * pow2i(-106 - sh);
    dd r = two_prod(f1, PIO2_HI);
    r = fast_two_sum(r.hi, r.lo + (f1 * PIO2_LO + f2 * PIO2_HI));
    *rh = sg * r.hi;
    *rl = sg * r.lo;
    return q;
}

/* ax = |x| finite: the quadrant q (k mod 4) and r = ax - k pi/2 = rh + rl, |r| <= pi/4 + 2^-30, absolute error
 * < 2^-134 (k P4's rounding; |r| >= 2^-60.5 for every double below 1.6e6: the doubles nearest to k pi/2, all
 * k < 2^20, were checked); k = 0 gives r = ax */
static inline int reduce_pio2(double ax, double *rh, double *rl) {
    if (ax < 1.6e6) { /* |k| < 2^20: Cody & Waite, k P1, k P2, k P3 exact */
        double kd = round_int(ax * INV_PIO2);
        double a = ax - kd * PIO2_1; /* exact: kd P1 is within a factor 2 of ax, or kd = 0 */
        double b = kd * PIO2_2, c = kd * PIO2_3, d = kd * PIO2_4;
        double h = a - b;
        if (fabs(h) >= 0x1p-13) { /* |a| >= |b| (< 2^-14) and |h| >= |c| (< 2^-49): fast_two_sum for both */
            double e1 = (a - h) - b;
            double g = h - c;
            double e2 = (h - g) - c;
            *rh = g;
            *rl = (e1 + e2) - d;
        } else { /* r near 0 (rare): the exact sums of two_sum */
            dd hh = two_sum(a, -b);
            dd gg = two_sum(hh.hi, -c);
            dd r = fast_two_sum(gg.hi, (hh.lo + gg.lo) - d); /* |r| >= 2^-61 >> the tail */
            *rh = r.hi;
            *rl = r.lo;
        }
        return (int)kd & 3;
    }
    return reduce_large(ax, rh, rl);
}

/* sin and cos of r = rh + rl, |r| <= pi/4 + 2^-30, |rl| <= 2 ulp(rh): r = a + d with a = i/64, |d| <= 1/128,
 * sin(a + d) = sin a + cos a d + [cos a (sin d - d) + sin a (cos d - 1)],
 * cos(a + d) = cos a - sin a d + [cos a (cos d - 1) - sin a (sin d - d)],
 * sin a d and cos a d exact (Dekker's product with the table's split of sin a, cos a).  Computed for |r|, the
 * sign of sin r returned in *neg (a sign bit); no branch (the signs of r are random in a simulation), the
 * sums ordered as shallow trees (the kernel is latency-bound). */
static inline void sincos_kernel(double rh, double rl, double *sr, double *cr, uint64_t *neg) {
    uint64_t sgn = bits_of(rh) & 0x8000000000000000ULL;
    rh = double_of(bits_of(rh) ^ sgn);
    rl = double_of(bits_of(rl) ^ sgn);
    double ta = rh + 0x1.8p46; /* rh rounded to a multiple of 2^-6 (ulp of 1.5 2^46), exactly */
    double a = ta - 0x1.8p46;
    int i = (int)(bits_of(ta) & 0xff);
    const double *t = SINCOS_TAB + 8 * i;
    double d = rh - a; /* exact (Sterbenz for i >= 1) */
    double z = d * d, z2 = z * z;
    /* sin d - d to d^7 and cos d - 1 to d^8 (the next terms are < 2^-81 |d| and < 2^-91) */
    double ps = (d * z) * (-0x1.5555555555555p-3 + z * 0x1.1111111111111p-7) + (d * z2) * (z * -0x1.a01a01a01a01ap-13);
    double pc = (z * (-0.5 + z * 0x1.5555555555555p-5) + (z * z2) * (-0x1.6c16c16c16c17p-10 + z * 0x1.a01a01a01a01ap-16)) -
                d * rl;
    double ds = rl + ps; /* sin(d + rl) = d + ds, cos(d + rl) = 1 + pc */
    double dh, dl;
    split(d, &dh, &dl);
    double S = t[0], Sh = t[1], St = t[2], Sl = t[3], C = t[4], Ch = t[5], Ct = t[6], Cl = t[7];
    double pC = C * d, eC = ((Ch * dh - pC) + Ch * dl + Ct * dh) + Ct * dl; /* C d = pC + eC */
    double pS = S * d, eS = ((Sh * dh - pS) + Sh * dl + St * dh) + St * dl; /* S d = pS + eS */
    dd s = fast_two_sum(S, pC); /* |S| >= sin(1/64) > |pC| or S = 0 */
    dd c = fast_two_sum(C, -pS);
    *sr = s.hi + ((s.lo + eC) + ((C * ds + S * pc) + (Sl + Cl * d)));
    *cr = c.hi + ((c.lo - eS) + ((C * pc - S * ds) + (Cl - Sl * d)));
    *neg = sgn;
}

/* sin x and cos x: x = k pi/2 + r, q = k mod 4; sin x = (sin r, cos r, -sin r, -cos r)[q] and
 * cos x = (cos r, -sin r, -cos r, sin r)[q], selected and signed with bit masks (no branch on q) */
static inline void sincos_core(double x, double *s, double *c) {
    double ax = fabs(x);
    if (!(ax < INFINITY)) { /* +-inf, NaN */
        *s = *c = x - x;
        return;
    }
    double rh, rl, sr, cr;
    uint64_t neg;
    int q = reduce_pio2(ax, &rh, &rl);
    sincos_kernel(rh, rl, &sr, &cr, &neg);
    uint64_t us = bits_of(sr) ^ neg, uc = bits_of(cr); /* sin r, cos r with their signs */
    uint64_t swap = -(uint64_t)(q & 1);
    uint64_t vs = (us & ~swap) | (uc & swap), vc = (uc & ~swap) | (us & swap);
    uint64_t ns = (uint64_t)((q >> 1) & 1) << 63, nc = (uint64_t)(((q + 1) >> 1) & 1) << 63;
    *s = double_of(vs ^ ns ^ (bits_of(x) & 0x8000000000000000ULL));
    *c = double_of(vc ^ nc);
}

double fb_sin(double x) {
    double s, c;
    sincos_core(x, &s, &c);
    return s;
}

double fb_cos(double x) {
    double s, c;
    sincos_core(x, &s, &c);
    return c;
}

void fb_sincos(double x, double *s, double *c) { sincos_core(x, s, c); }

/* ----------------------------------------------------------------------------------------------------- atan2 */
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

/* ---------------------------------------------------------------------------------------------------- tgamma */
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

/* Recipe of the tables (Python, mpmath), run once and pasted above:
 *
 *   import mpmath as mp; mp.mp.prec = 400                                   # 1600 for TWO_OVER_PI
 *   d = lambda v: float(mp.mpf(v)); dd = lambda v: (d(v), d(mp.mpf(v) - d(v)))
 *   def round_bits(v, n): m, e = mp.frexp(mp.mpf(v)); return float(mp.ldexp(mp.nint(mp.ldexp(m, n)), e - n))
 *   def split(a): c = 134217729.0 * a; h = c - (c - a); return h, a - h       # as split() above
 *   EXP2_TAB   = [dd(mp.mpf(2) ** (mp.mpf(j) / 64)) for j in range(64)]
 *   for i in range(256):                                                      # LOG_INVC, LOG_LOGC
 *       a, b = 1 + mp.mpf(i) / 256, 1 + mp.mpf(i + 1) / 256
 *       if i >= 106: a, b = a / 2, b / 2
 *       c = 1.0 if i in (0, 255) else round_bits(2 / (a + b), 12); LOG_INVC[i] = c; LOG_LOGC[i] = dd(-mp.log(c))
 *   SINCOS_TAB = [(sh, *split(sh), sl, ch, *split(ch), cl) for (sh, sl), (ch, cl) in
 *                 ((dd(mp.sin(mp.mpf(i) / 64)), dd(mp.cos(mp.mpf(i) / 64))) for i in range(53))]
 *   ATAN_TAB   = [dd(mp.atan(mp.mpf(i) / 64)) for i in range(65)]
 *   TWO_OVER_PI: the 20 successive 64-bit integer parts of frac(2/pi * 2^64), frac(... * 2^64), ...
 *   constants: EXP_L1 = round_bits(ln2/64, 36), LN2_HI = round_bits(ln2, 42), PIO2_1..3 = 33-bit roundings of
 *   pi/2 minus the previous parts, the polynomial coefficients the nearest doubles to 1/n!, 1/n and
 *   B_2k / (2k (2k-1)).
 */
