/* PLACEHOLDER: libm wrappers until the deterministic implementations land (see detmath.h). */
#include <math.h>

#include "detmath.h"

double fb_sin(double x) { return sin(x); }
double fb_cos(double x) { return cos(x); }
void fb_sincos(double x, double *s, double *c) {
    *s = sin(x);
    *c = cos(x);
}
double fb_exp(double x) { return exp(x); }
double fb_expm1(double x) { return expm1(x); }
double fb_log(double x) { return log(x); }
double fb_log1p(double x) { return log1p(x); }
double fb_pow(double x, double y) { return pow(x, y); }
double fb_tgamma(double x) { return tgamma(x); }
double fb_atan2(double y, double x) { return atan2(y, x); }
