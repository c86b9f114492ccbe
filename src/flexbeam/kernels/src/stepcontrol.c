/* Step-size control of the collocation integrator.
 *
 * Errors are measured in the energy norm of the modes, |e|^2 = sum_k (w_k^2 de_k^2 + dv_k^2) (mass-normalised
 * modal coordinates: twice the energy of the error), a rigid mode's angle weighed by omega_rigid (the lowest
 * flexible frequency), against the tolerance atol + rtol |state| in the same norm.  The estimate
 * (collocation.c) propagates the defect of the forcing interpolant at the step end (~h^p) as a forcing error:
 * of order ORDER = p + 1 in h for the velocities.
 */
#include "integrator.h"

#define ORDER 5.0       /* order in h of the error estimate (velocity: h times the forcing defect ~ h^p) */
#define SAFETY 0.9      /* aim below the tolerance */
#define FAC_MIN 0.2     /* largest reduction after a rejected step */
#define FAC_MAX 5.0     /* largest growth after an accepted step */
#define KEEP_LOW 0.9    /* an accepted step proposing a factor in [KEEP_LOW, KEEP_HIGH] keeps its length, */
#define KEEP_HIGH 1.25  /* so the next step reuses its propagation weights (a sine and cosine per mode and node) */

double fb_energy_norm(const fb_phase *ph, const double *eta, const double *v) {
    int N = ph->b->N;
    double acc = 0.0;
    for (int k = 0; k < N; k++) {
        double om = ph->b->omega[k];
        if (om > 0.0) acc += om * om * eta[k] * eta[k];
        acc += v[k] * v[k];
    }
    return sqrt(acc);
}

/* The step's tolerance in the energy norm: atol + rtol times the larger of the state's norm at both ends (the
 * rigid angle, whose value has no physical scale, does not enter the state's norm). */
double fb_tolerance(const fb_phase *ph, const double *eta0, const double *v0, const double *eta1, const double *v1) {
    double a = fb_energy_norm(ph, eta0, v0), b = fb_energy_norm(ph, eta1, v1);
    return ph->atol + ph->rtol * (a > b ? a : b);
}

/* The next step length from the error estimate err (in units of the tolerance) of a step of length h: the
 * elementary controller h (SAFETY / err)^(1/ORDER), its factor bounded to [FAC_MIN, FAC_MAX] (to [0.5, ...] after an
 * accepted step), and kept at 1 near 1 (hysteresis: unchanged weights are reused). */
double fb_next_step(double h, double err, int accepted) {
    double fac = err > 0.0 ? SAFETY * fb_pow(err, -1.0 / ORDER) : FAC_MAX;
    if (fac > FAC_MAX) fac = FAC_MAX;
    if (fac < FAC_MIN) fac = FAC_MIN;
    if (accepted && fac < 1.0) fac = fac > 0.5 ? fac : 0.5;
    if (accepted && fac >= KEEP_LOW && fac <= KEEP_HIGH) fac = 1.0;
    return h * fac;
}
