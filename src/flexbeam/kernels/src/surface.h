/* The event search's start on the surface (surface.c). */
#ifndef FLEXBEAM_SURFACE_H
#define FLEXBEAM_SURFACE_H

#include "integrator.h"

fb_gap fb_dense_gap(const fb_dense *d, double x);
double fb_pair_reach(const fb_dense *d);
int fb_on_surface_quiet(const fb_dense *d, const double *jb, double gam, double x0, double dx, double a, double b,
                        double sign, double depth);

#endif
