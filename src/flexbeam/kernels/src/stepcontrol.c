/* Step-size control of the collocation integrator.
 *
 * Errors are measured in the energy norm of the modes, |e|^2 = sum_k (w_k^2 de_k^2 + dv_k^2) (mass-normalised
 * modal coordinates: twice the energy of the error), a rigid mode's angle weighed by omega_rigid (the lowest
 * flexible frequency), against the tolerance atol + rtol |state| in the same norm.  The estimate
 * (collocation.c) propagates the defect of the forcing interpolant at the step end (~h^p) as a forcing error:
 * of order ORDER = p + 1 in h for the velocities.
 */
#include "integrator.h"

/* A step's energy-balance residual may use this share of the energy error its state tolerance admits: the state's
 * error estimate is conservative, but its energy errors add up over the ~100 free-flight steps of a 0.1 s run
 * (measured on the seed case: drift 1.9e-6 at fast_rtol 1e-6 without this check, <= 6.4e-7 with it, at 0-8 %
 * more steps). */
#define BALANCE_SHARE 0.1
#define BALANCE_ROUNDOFF 1e-13 /* the residual's round-off, relative to its terms (a few hundred ulps) */

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

/* The step's energy-balance residual r = E(t + h) - E(t) + dE_d - dW against BALANCE_SHARE of the energy error the
 * state tolerance admits: a state error e in the error norm (above: |x|^2 = 2 (T + V_e) = 2 scale, a rigid
 * mode's angle weighed by omega_rigid) moves the energy by at most |grad E| |e| + |e|^2 / 2, and |e| <= tol =
 * atol + rtol |x|.  The gradient's kinetic and elastic part has the norm |x|; a rigid mode's generalised force Q_k
 * (``load`` = |Q_k / omega_rigid| over the rigid modes' rows of the smooth forcing: the drive torque, gravity, and
 * the inertial terms, nil at rest) moves the potential or the work by Q_k e_k / omega_rigid, which no elastic energy
 * measures, as a rigid mode stores none -- a rigid beam at rest on a contact or a held constraint: |x| -> 0 while
 * the contact holds the load, r the round-off of that load's work (its force times an ulp of the gap: 1.3e-17 J on
 * the rigid seed beam, against the 2e-18 J |x| admitted).  The larger of the two parts stands for |grad E|: where
 * the vibration's part is the larger the budget is the former one (a flexible beam at rest keeps |x| from its
 * static deflection, |Q_k / omega_k| over the flexible modes; every fingerprinted run is the same to the bit).
 * Never below the round-off of the residual's terms (``size``: the sum of their magnitudes).  Returns |r| over
 * that (> 1: reject). */
double fb_balance_error(const fb_phase *ph, double r, double scale, double load, double size) {
    double x = sqrt(2.0 * scale), tol = ph->atol + ph->rtol * x, g = fmax(x, load);
    return fabs(r) / fmax(BALANCE_SHARE * (g * tol + 0.5 * tol * tol), BALANCE_ROUNDOFF * size);
}

/* |Q_k / omega_rigid| over the rigid modes (omega_k = 0) of the smooth forcing at node nd (fb_balance_error's load). */
double fb_rigid_load(const fb_phase *ph, const fb_node *nd) {
    double acc = 0.0;
    for (int k = 0; k < ph->b->N; k++)
        if (ph->b->omega[k] <= 0.0) acc += nd->smooth[k] * nd->smooth[k];
    return sqrt(acc) / ph->omega_rigid;
}
