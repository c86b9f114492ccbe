/* The exponential collocation integrator: types shared by collocation.c, events.c, stepcontrol.c, phase.c. */
#ifndef FLEXBEAM_INTEGRATOR_H
#define FLEXBEAM_INTEGRATOR_H

#include "flexbeam.h"

#define FB_MAXN 66 /* modal coordinates: n <= 64 modes, theta, a support coordinate */

typedef struct { /* the hop weights of every mode, mode-innermost */
    double C[FB_MAXN], SW[FB_MAXN], WS[FB_MAXN], CV[FB_MAXN], pe[FB_P][FB_MAXN], pv[FB_P][FB_MAXN];
} fb_hops;

void fb_hops_fill(const fb_basis *b, double T, fb_hops *H);
void fb_hop_advance(const fb_basis *b, const fb_hops *H, const double *A, double sa, double L, double *eta,
                    double *v);

/* What a phase integrates: the model in its modal basis and how each contact pair acts. */
typedef struct {
    const fb_model *m;
    const fb_basis *b;
    fb_contacts c;      /* per pair: FB_MODE_*, the law (FORCE); c.alpha: the constraints' decay rate kappa */
    int contact;        /* some pair is in contact (FORCE or CONSTRAINT) */
    int force, held;    /* some pair is under its law / held by its constraint */
    double rtol, atol;
    double omega_rigid; /* the frequency that weighs a rigid-mode angle error in the energy norm [rad/s] */
    int row0_q;         /* (M0^-1)_0q != 0: the Sherman-Morrison correction needs K0 z (hub frame) */
    const fb_tables *tb; /* the collocation's nodes: Gauss's, Radau's for a resting contact (FB_CTRL_RADAU) */
} fb_phase;

void fb_phase_init(fb_phase *ph, const fb_model *m, const fb_basis *b, const fb_contacts *c, double rtol,
                   double atol, double omega_rigid);

/* What fb_eval_node evaluates besides the smooth forcing: */
enum {
    FB_WANT_NONE = 0,
    FB_WANT_GAP = 1, /* every pair's gap, and J (jm, b) of the pairs in contact */
    FB_WANT_JM = 2,  /* ... and jm of every pair (the event search's bounds at a free step's first node) */
    FB_WANT_ACTIVE = 3, /* the gap and J of the pairs in contact only (a collocation sweep: the free pairs' gaps
                         * are evaluated once per accepted step, by the event search, and not at all when far) */
};

/* The model evaluated at one modal state: the smooth modal forcing, the contact directions and the gaps. */
typedef struct {
    double t;
    fb_frame frame;                   /* the floating frame's motion */
    double smooth[FB_MAXN];           /* Psi^T R without the contact forces */
    double b[FB_MAX_PAIRS][FB_MAXN];  /* Psi^T M0 M^-1 J_k^T: modal forcing per unit force of pair k (in contact) */
    double jm[FB_MAX_PAIRS][FB_MAXN]; /* Psi^T J_k^T: d delta_k / d eta (in contact; every pair with FB_WANT_JM) */
    double jb[FB_MAX_PAIRS][FB_MAXN]; /* a bound on |jm_k| wherever the pair's point may be (|jm| for a fixed one) */
    fb_gap gap[FB_MAX_PAIRS];         /* every pair's gap state (delta, rate, gamma = delta'' at z'' = 0, ...) */
    double z[FB_MAXN], zd[FB_MAXN];
    /* a frictional pair in contact (friction.c): Psi^T Jt_k^T, Psi^T M0 M^-1 Jt_k^T (b above then holds the slip's
     * force direction Psi^T M0 M^-1 (J_k + sigma_k Jt_k)^T) and the slip velocity v_t */
    double jt[FB_MAX_PAIRS][FB_MAXN], bt[FB_MAX_PAIRS][FB_MAXN], vt[FB_MAX_PAIRS];
} fb_node;

void fb_eval_node(const fb_phase *ph, double t, const double *eta, const double *v, int want, fb_node *out);
void fb_eval_node_acc(const fb_phase *ph, double t, const double *eta, const double *v, int want, int want_acc,
                      fb_node *out);
fb_gap fb_gap_at(const fb_phase *ph, int pair, double t, const double *eta, const double *v);

/* Work space of one phase: the step's weights (cached for its length h), the node evaluations. */
typedef struct {
    double h;                      /* weights are for this step length */
    const fb_tables *tb;           /* ... and these nodes */
    fb_weight W[FB_MAXN][FB_NPTS]; /* per mode: the FB_P nodes and the end */
    fb_node node[FB_P];
    fb_node *end;                  /* the model at the step end (error estimate, events) */
    fb_node *start;                /* the model at the step start (a Radau step's error estimate), when start_ok */
    fb_node ends[2];               /* end and start point here: an accepted Radau step's end becomes the next start */
    int start_ok;                  /* *start holds the model at the state of time start->t */
    double F[FB_MAX_PAIRS][FB_P];  /* contact force (or multiplier) of each pair at the nodes */
    double Fk[FB_MAX_PAIRS][FB_P]; /* its elastic part (FORCE) */
    double Ft[FB_MAX_PAIRS][FB_P]; /* a sticking pair's tangential multiplier lambda_t (friction.c) */
    double lambda_scale;           /* the largest multiplier of the phase so far (CONSTRAINT) */
    double stick_h;                /* the step a stick's residual slip decays over (nodal.c; 0: the step's own) */
    int iterations;
} fb_work;

/* Result of one collocation step. */
typedef struct {
    double eta1[FB_MAXN], v1[FB_MAXN];
    double err;     /* error estimate in units of the tolerance (accept <= 1) */
    int converged;
} fb_step;

/* The contact unknowns of a step (nodal.c): (pair, node, row) -- row 0 the normal force or multiplier, row 1 a
 * sticking pair's tangential multiplier */
#define FB_MAXU (2 * FB_MAX_PAIRS * FB_P)
typedef struct {
    int count, pair[FB_MAXU], node[FB_MAXU], row[FB_MAXU];
} fb_unknowns;
void fb_list_unknowns(const fb_phase *ph, fb_unknowns *u);
void fb_nodal_contacts(const fb_phase *ph, fb_work *w, const fb_unknowns *u, double h, const double *g0,
                       const double *g0t);

int fb_collocate(const fb_phase *ph, fb_work *w, double t0, double h, const double *eta0, const double *v0,
                 double *f, fb_step *out);
void fb_next_start(const fb_phase *ph, fb_work *w);
/* The next step's first guess from the nodal values of the last (collocation.c) */
void fb_extrapolate(const fb_tables *tb, int N, int S, double ratio, double *f, double F[][FB_P]);

/* Energy-norm helpers (stepcontrol.c) */
double fb_energy_norm(const fb_phase *ph, const double *eta, const double *v);
double fb_tolerance(const fb_phase *ph, const double *eta0, const double *v0, const double *eta1, const double *v1);
double fb_next_step(double h, double err, int accepted);
double fb_balance_error(const fb_phase *ph, double r, double scale, double load, double size);
double fb_rigid_load(const fb_phase *ph, const fb_node *nd);

/* Events (events.c) */
#define FB_NO_EVENT 2.0
#define FB_UNDECIDED -1.0
enum { FB_EVENT_IMPACT = 1, FB_EVENT_SEPARATION = 2, FB_EVENT_RELEASE = 3 };
/* Coulomb friction's events (friction.c): the slip velocity reaches zero; a stick ends with lambda_t = +mu_s F
 * (PLUS) or -mu_s F (MINUS) */
enum { FB_EVENT_STOP = 4, FB_EVENT_UNSTICK_PLUS = 5, FB_EVENT_UNSTICK_MINUS = 6 };
/* a held (CCM) slipping pair's a = W_nn + sigma W_nt reaches zero: Painlevé (friction.c) */
enum { FB_EVENT_PAINLEVE = 7 };

typedef struct { /* a step's dense output, for the event search of one pair */
    const fb_phase *ph;
    double t0, h;
    const double *eta0, *v0, *f; /* f: FB_P x N nodal forcing */
    int pair;
    const fb_tables *tb; /* the step's nodes (a record's: fb_record_tables) */
} fb_dense;

/* A step's forcing polynomial of one mode and the bound on the forced response (forcing_bound.c) */
typedef struct {
    double max, start, variation; /* max|f| over the step, |f(0)|, int |f'|: each rounded up */
} fb_forcing;
/* a = the monomial coefficients of mode k's forcing (Vinv f_nodes); returns sum |a_m|; *mag (if not NULL):
 * sum_m sum_j |Vinv_mj f_jk| */
/* The node set a step record of R floats was taken with (phase.c: its flag before the summary). */
const fb_tables *fb_record_tables(const double *rec, int R);
double fb_forcing_coefficients(const fb_tables *tb, const double *f, int N, int k, double *a, double *mag);
void fb_forcing_bound(const fb_tables *tb, const double *f, int N, int k, fb_forcing *out);
/* (max|f| + |f(0)| + V) / w^2: bounds the forced response from rest over the step, damped or not */
double fb_forced_amplitude(const fb_forcing *fc, double w);
void fb_dense_state(const fb_dense *d, double x, double *eta, double *v);
/* a scalar function of the fraction x of a step (its dense output d) */
typedef double (*fb_scalar)(const fb_dense *d, double x);
/* Root of fn on [a, b] (fa fb <= 0) by Brent's method (Brent 1973, ch. 4), to 1e-15 of the step (events.c). */
double fb_brent(const fb_dense *d, double a, double b, double fa, double fb, fb_scalar fn);
/* ... its end of the final bracket where fn <= 0 (fa > 0 >= fb: the root passed, as a bisection keeps it) */
double fb_brent_past(const fb_dense *d, double a, double b, double fa, double fb, fb_scalar fn);
int fb_gap_far(const fb_dense *d, const double *jb, double gap0);
/* Bounds on sum_k jm_k eta_k (+ a part of curvature <= gamma) between samples spaced by the fraction dx of the step:
 * returns the resolved modes' deviation from the linear interpolant, *fast the faster modes' amplitude. */
double fb_dense_bounds(const fb_dense *d, const double *jm, double gamma, double dx, double *fast);
double fb_find_gap_event(const fb_dense *d, int direction, const double *kx, const fb_gap *known,
                         const double *eta_known, const double *jm, const double *jb, double *beyond);
double fb_find_release(const fb_tables *tb, const double *lam, int later);
double fb_find_kink(const fb_dense *d, const double *kx, const fb_gap *known, int count);

/* Coulomb friction (friction.c) */
fb_gap fb_tangent_at(const fb_phase *ph, int pair, double t, const double *eta, const double *v, double *vt);
void fb_node_friction(const fb_phase *ph, int k, const double *Jt, double vt, const fb_update *up, fb_node *out);
double fb_friction_event(const fb_dense *d, const fb_work *w, int events, int *kind);
double fb_find_unstick(const fb_phase *ph, int k, const double *F, const double *Ft, double scale, int *kind);
double fb_friction_rate(const fb_phase *ph, const fb_node *nd, int k, double F, double Ft);
/* The regularised law's tangential force sigma(v_t) max(F, 0) of pair k at an evaluated node (its nodal unknown's
 * value there, normal force F); 0 for any other pair (friction.c). */
double fb_regularised_force(const fb_phase *ph, const fb_node *nd, int k, double F);

#endif
