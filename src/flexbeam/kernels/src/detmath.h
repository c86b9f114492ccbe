/* Elementary functions that give the same bits on every machine: the public interface of the detmath*.c files.
 *
 * glibc's libm picks an FMA/AVX2 variant of exp, sin, cos, pow at run time by CPU (and numpy its own SIMD
 * loops), so the C library's results differ in the last bit from one x86-64 machine to another; an event-driven
 * impact simulation amplifies such a bit into a different step sequence, a different micro-impact, a different
 * contact count.  These functions use only IEEE-754 +, -, *, / and sqrt (correctly rounded everywhere) and
 * integer operations on the representation, compiled without contraction (-ffp-contract=off): their results
 * are a function of the argument alone, on any IEEE-754 binary64 machine.
 *
 * Each function evaluates its result as a double-double (hi + lo, ~106 bits) with a relative error below 2^-62
 * and rounds it once at the end, so its error is below 0.5 ulp (the final rounding) + 2^-62 / 2^-53 = 0.502 ulp
 * (subnormal results included: they are rounded once too); Gamma's bound is 0.516 ulp.  tests/unit/
 * test_detmath.py asserts these bounds against mpmath at 200 bits; the measured excess over 0.5 ulp is below
 * 1.2e-4 ulp (5e-4 for Gamma).  Each file states its method, its references and its bound:
 *
 *   detmath_exp.c     fb_exp, fb_expm1          detmath_dd.h       double-double arithmetic, the build guards
 *   detmath_log.c     fb_log, fb_log1p          detmath_exp.h      e^x before rounding (exp, expm1, pow, tgamma)
 *   detmath_pow.c     fb_pow                    detmath_log.h      log x before rounding (log, log1p, pow, tgamma)
 *   detmath_trig.c    fb_sin, fb_cos, fb_sincos detmath_tables.h   the tables' layout, the constants
 *   detmath_atan2.c   fb_atan2                  detmath_tab_*.[ch] the generated tables, with their recipes
 *   detmath_tgamma.c  fb_tgamma
 */
#ifndef FLEXBEAM_DETMATH_H
#define FLEXBEAM_DETMATH_H

double fb_sin(double x);
double fb_cos(double x);
void fb_sincos(double x, double *s, double *c);
double fb_exp(double x);
double fb_expm1(double x);
double fb_log(double x);
double fb_log1p(double x);
double fb_pow(double x, double y);
double fb_tgamma(double x); /* Gamma(x) for x > 0 */
double fb_atan2(double y, double x);

#endif
