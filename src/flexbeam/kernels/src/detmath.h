/* Elementary functions that give the same bits on every machine (detmath.c).
 *
 * glibc's libm picks an FMA/AVX2 variant of exp, sin, cos, pow at run time by CPU (and numpy its own SIMD
 * loops), so the C library's results differ in the last bit from one x86-64 machine to another; an event-driven
 * impact simulation amplifies such a bit into a different step sequence, a different micro-impact, a different
 * contact count.  These functions use only IEEE-754 +, -, *, / and sqrt (correctly rounded everywhere) and
 * integer operations on the representation, compiled without contraction (-ffp-contract=off): their results
 * are a function of the argument alone, on any IEEE-754 binary64 machine.
 *
 * Accuracy (tests/unit/test_detmath.py, against mpmath): see detmath.c for each function's bound.
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
