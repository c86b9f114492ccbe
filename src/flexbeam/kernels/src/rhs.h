/* The reference-layout right-hand side's evaluation, shared by rhs.c (the equations, the contact forces, the
 * outputs) and rhs_friction.c (Coulomb friction's rows and forces in it).  Private to those two files. */
#ifndef FLEXBEAM_RHS_H
#define FLEXBEAM_RHS_H

#include "flexbeam.h"

#define MAXZ 66 /* n <= 64 modes, theta, and a support coordinate */

/* One evaluation of the right-hand side, shared by its pieces: the state, the equations M z'' = Q of the full
 * coordinates z, the pairs' gaps, Jacobians and forces, the force on the support's mass and the dissipated power. */
typedef struct {
    const fb_model *m;
    const fb_contacts *c;
    const fb_joint_ops *jt;
    const fb_obstacle *o; /* the support (obstacle 0), or NULL */
    fb_frame fr;
    const double *q, *qd;
    int N, ng, compliant;
    double s, sd;                   /* the support's coordinate and rate (0 without a compliant support) */
    double ga[FB_MAX_JOINT_PARAMS]; /* the given coordinates' accelerations */
    double M[MAXZ * MAXZ], Q[MAXZ], J[FB_MAX_PAIRS][MAXZ];
    fb_gap gp[FB_MAX_PAIRS];
    double F[FB_MAX_PAIRS], Fsup, diss, damping;
    int con[FB_MAX_PAIRS], ncon;     /* the constrained pairs */
    int stick[FB_MAX_PAIRS], nstick; /* the law pairs (CCFM) sticking: their tangential multipliers */
    /* a pair with Coulomb friction: its tangent Jacobian, slip velocity, force direction J + sigma Jt (a constrained
     * pair's slip) and tangential multiplier (stick) */
    double Jt[FB_MAX_PAIRS][MAXZ], vt[FB_MAX_PAIRS], D[FB_MAX_PAIRS][MAXZ], Ft[FB_MAX_PAIRS];
} rhs_eval;

/* One row of the constrained pairs' system: the pair, normal (0) or tangential (1), the constraint's row and the
 * force's column over the full coordinates, their support entries, and the row's target acceleration. */
typedef struct {
    int pair, tangential;
    const double *row, *col;
    double row_s, col_s, target;
} fb_row;

/* Coulomb friction in the right-hand side (rhs_friction.c). */
double rhs_tangent_support(const rhs_eval *e, int k);
void rhs_law_friction(rhs_eval *e, int k);
int rhs_rough_rows(rhs_eval *e, fb_row *rows);
void rhs_rough_dissipation(rhs_eval *e);

#endif
