/* Coulomb friction in the reference-layout right-hand side (rhs.c): a law pair's kinetic force or its stick's row
 * (CCFM), a constrained pair's slip column and stick row (CCM), and friction's dissipation (friction.c for the
 * compiled integrator's own rows). */
#include "rhs.h"

/* d v_t / d s' of pair k: its slip velocity's share of the compliant support's rate (fb_node_friction). */
double rhs_tangent_support(const rhs_eval *e, int k) {
    const fb_gap *g = &e->gp[k];
    const fb_obstacle *o = &e->m->obstacles[e->m->pairs[k].obstacle];
    return o->ms > 0.0 ? -(-g->ny * o->ux + g->nx * o->uy) : 0.0;
}

/* Coulomb friction of a law pair k (CCFM, friction.c): slipping (or under the regularised law) its force sigma F
 * acts along Jt and dissipates -sigma F v_t; sticking, its tangential multiplier is solved with the constrained
 * pairs' (rhs.c's constraint_forces). */
void rhs_law_friction(rhs_eval *e, int k) {
    e->Ft[k] = 0.0;
    if (e->c->stick[k]) {
        e->stick[e->nstick++] = k;
        return;
    }
    double f = fb_slip_coefficient(e->c, k, e->vt[k]) * e->F[k];
    for (int i = 0; i < e->N; i++) e->Q[i] += e->Jt[k][i] * f;
    e->Fsup += rhs_tangent_support(e, k) * f;
    e->diss -= f * e->vt[k];
}

/* The rows of the constrained pairs with friction (CCM, friction.c): a slipping pair's force column J + sigma Jt
 * (sigma = fb_slip_coefficient), a sticking pair's tangential row Jt z'' = -gamma_t - 2 alpha v_t (its multiplier
 * along Jt; the Baumgarte term damps the slip velocity's drift).  Returns the number of rows. */
int rhs_rough_rows(rhs_eval *e, fb_row *rows) {
    const fb_contacts *c = e->c;
    int n = e->ncon, N = e->N;
    for (int ia = 0; ia < e->ncon; ia++) {
        int k = e->con[ia];
        e->Ft[k] = 0.0;
        if (!fb_rough(c, k)) continue;
        const fb_gap *g = &e->gp[k];
        double sigma = fb_slip_coefficient(c, k, e->vt[k]), Jts = rhs_tangent_support(e, k);
        if (sigma != 0.0) {
            for (int i = 0; i < N; i++) e->D[k][i] = e->J[k][i] + sigma * e->Jt[k][i];
            rows[ia].col = e->D[k];
            rows[ia].col_s = g->Js + sigma * Jts;
        }
        if (c->stick[k])
            rows[n++] = (fb_row){k, 1, e->Jt[k], e->Jt[k], Jts, Jts, -g->tgamma - 2.0 * c->alpha * e->vt[k]};
    }
    for (int j = 0; j < e->nstick; j++) { /* the sticking law pairs' tangential rows */
        int k = e->stick[j];
        double Jts = rhs_tangent_support(e, k);
        rows[n++] = (fb_row){k, 1, e->Jt[k], e->Jt[k], Jts, Jts, -e->gp[k].tgamma - 2.0 * c->alpha * e->vt[k]};
    }
    return n;
}

/* Friction's dissipation -(sigma F + lambda_t) v_t of the constrained pairs (CCM) and -lambda_t v_t of the sticking
 * law pairs, added to the dissipated power. */
void rhs_rough_dissipation(rhs_eval *e) {
    for (int ia = 0; ia < e->ncon; ia++) {
        int k = e->con[ia];
        if (fb_rough(e->c, k)) e->diss -= (fb_slip_coefficient(e->c, k, e->vt[k]) * e->F[k] + e->Ft[k]) * e->vt[k];
    }
    for (int j = 0; j < e->nstick; j++) e->diss -= e->Ft[e->stick[j]] * e->vt[e->stick[j]];
}
