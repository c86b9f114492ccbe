/* The tip's deflection on a phase's dense output: its exact linear part and the bound of the tip's pruned search
 * (tip_bound.c holds the derivation). */
#ifndef FLEXBEAM_TIP_BOUND_H
#define FLEXBEAM_TIP_BOUND_H

#include "integrator.h"
#include "joint.h"

typedef struct {
    int N, nonlinear; /* nonlinear: alpha = d q is not identically zero (the system frame) */
    double base;      /* r_h + L */
    /* per unit eta_k: the linear part g = y - base alpha; Y = Psi(L) q, alpha = d q, P = Phi_a(L) p */
    double g[FB_MAXN], y[FB_MAXN], alpha[FB_MAXN], p[FB_MAXN];
    double Habs[FB_MAXN * FB_MAXN]; /* |Psi_q^T H(L) Psi_q| (only when nonlinear) */
} fb_tip_model;

/* A bracket's bounds: per mode |eta| <= A, |eta''| <= E; |N| <= N0, |N'| <= N1; the deflection's rounding. */
typedef struct {
    double A[FB_MAXN], E[FB_MAXN], N0, N1, rounding;
} fb_tip_bracket;

void fb_tip_model_init(const fb_model *m, const fb_basis *b, fb_tip_model *tm);
/* Each mode's bounds over one step (its record): |eta| <= A, |eta'| <= V, |eta''| <= E. */
void fb_tip_step_bounds(const fb_tip_model *tm, const fb_basis *b, const double *rec, int R, double *A, double *V,
                        double *E);
/* A bracket's bounds from its modes' bounds (the largest over its steps). */
void fb_tip_combine(const fb_tip_model *tm, const double *A, const double *V, const double *E, double theta_max,
                    fb_tip_bracket *out);
/* The bounds over records r0 .. r1 (record size R); theta_max: |theta| of the frame. */
void fb_tip_reach(const fb_tip_model *tm, const fb_basis *b, const double *records, int R, int r0, int r1,
                  double theta_max, fb_tip_bracket *out);
/* How far the deflection can exceed the larger of two samples T apart within the bracket: the linear part's,
 * the rest's and the rounding's shares (parts), and their sum. */
void fb_tip_slack_parts(const fb_tip_model *tm, const fb_tip_bracket *br, double T, double parts[3]);
double fb_tip_slack(const fb_tip_model *tm, const fb_tip_bracket *br, double T);

#endif
