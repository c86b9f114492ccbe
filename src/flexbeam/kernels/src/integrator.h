/* The exponential collocation integrator: types shared by collocation.c, events.c, stepcontrol.c, phase.c. */
#ifndef FLEXBEAM_INTEGRATOR_H
#define FLEXBEAM_INTEGRATOR_H

#include "flexbeam.h"

#define FB_MAXN 66 /* modal coordinates: n <= 64 modes, theta, a support coordinate */

/* What a phase integrates: the model in its modal basis, the contact mode and its parameters. */
typedef struct {
    const fb_model *m;
    const fb_basis *b;
    int mode;        /* FB_MODE_NONE, FB_MODE_FORCE (law p = [K, n, chi/d'_0, C]), FB_MODE_CONSTRAINT */
    double p[4];     /* law parameters, or [kappa, ...]: the constraint's Baumgarte decay rate */
    double rtol, atol;
    double omega_rigid; /* the frequency that weighs a rigid-mode angle error in the energy norm [rad/s] */
    int row0_q;         /* (M0^-1)_0q != 0: the Sherman-Morrison correction needs K0 z (hub frame) */
} fb_phase;

/* The model evaluated at one modal state: the smooth modal forcing, the contact direction and the gap. */
typedef struct {
    double t, th, thd, thdd;
    double smooth[FB_MAXN]; /* Psi^T R without the contact force */
    double b[FB_MAXN];      /* Psi^T M0 M^-1 J^T: modal forcing per unit contact force */
    double jm[FB_MAXN];     /* Psi^T J^T: d delta / d eta */
    double delta, rate;     /* gap and its rate */
    double gamma;           /* the gap's acceleration at z'' = 0 (velocity-product terms) */
    fb_gap gap;             /* all of the gap state */
    double z[FB_MAXN], zd[FB_MAXN];
} fb_node;

void fb_eval_node(const fb_phase *ph, double t, const double *eta, const double *v, int want_gap, fb_node *out);
void fb_eval_node_acc(const fb_phase *ph, double t, const double *eta, const double *v, int want_gap, int want_acc,
                      fb_node *out);
fb_gap fb_gap_at(const fb_phase *ph, double t, const double *eta, const double *v);

/* Work space of one phase: the step's weights (cached for its length h), the node evaluations. */
typedef struct {
    double h;                      /* weights are for this step length */
    fb_weight W[FB_MAXN][FB_NPTS]; /* per mode: the FB_P nodes and the end */
    fb_node node[FB_P];
    fb_node end;                   /* the model at the step end (error estimate, events) */
    double F[FB_P];                /* contact force (or multiplier) at the nodes */
    double Fk[FB_P];               /* its elastic part (CCFM) */
    double lambda_scale;           /* the largest multiplier of the phase so far (CCM) */
    int iterations;
} fb_work;

/* Result of one collocation step. */
typedef struct {
    double eta1[FB_MAXN], v1[FB_MAXN];
    double err;     /* error estimate in units of the tolerance (accept <= 1) */
    int converged;
} fb_step;

int fb_collocate(const fb_phase *ph, fb_work *w, double t0, double h, const double *eta0, const double *v0,
                 double *f, fb_step *out);

/* Energy-norm helpers (stepcontrol.c) */
double fb_energy_norm(const fb_phase *ph, const double *eta, const double *v);
double fb_tolerance(const fb_phase *ph, const double *eta0, const double *v0, const double *eta1, const double *v1);
double fb_next_step(double h, double err, int accepted);

/* Events (events.c) */
#define FB_NO_EVENT 2.0
#define FB_UNDECIDED -1.0
enum { FB_EVENT_IMPACT = 1, FB_EVENT_SEPARATION = 2, FB_EVENT_RELEASE = 3 };

typedef struct { /* a step's dense output, for the event search */
    const fb_phase *ph;
    double t0, h;
    const double *eta0, *v0, *f; /* f: FB_P x N nodal forcing */
} fb_dense;

void fb_dense_state(const fb_dense *d, double x, double *eta, double *v);
double fb_find_gap_event(const fb_dense *d, int direction, const double *kx, const fb_gap *known,
                         const double *eta_known, const double *jm, double *beyond);
double fb_find_release(const double *lam);
double fb_find_kink(const fb_dense *d, const double *kx, const fb_gap *known, int count);

#endif
