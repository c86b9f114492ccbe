/* Coulomb friction at a contact under its law (CCFM, docs/methods.md "Friction in CCFM").
 *
 * Along the contact's tangent t = (-n_y, n_x) the point P slips with velocity v_t = t . (r_P' - the obstacle's
 * velocity) = Jt z' (fb_pair_tangent).  A slipping pair adds the tangential force F_t = sigma F, sigma = -mu_k
 * sign(v_t) fixed over the phase, to its law's normal force F: the generalised force (J + sigma Jt)^T F, so the
 * collocation's force direction b of the pair is Psi^T M0 M^-1 (J + sigma Jt)^T.  The slip ends where v_t reaches
 * zero (FB_EVENT_STOP, located on the step's dense output).  A sticking pair is held tangentially by a multiplier
 * lambda_t along Jt (Glocker & Pfeiffer 1992; Pfeiffer & Glocker, Multibody Dynamics with Unilateral Contacts, 1996,
 * Ch. 5), its normal force still from the law: the collocation keeps v_t on v_t(t0) exp(-kappa (t - t0)) at its
 * nodes, as CCM keeps a held gap; the stick ends where |lambda_t| reaches mu_s F (FB_EVENT_UNSTICK_PLUS/MINUS by the
 * sign of lambda_t, located on the nodal interpolants).  Friction dissipates -(sigma F + lambda_t) v_t >= 0.
 */
#include <string.h>

#include "integrator.h"

#define EV_STOP 8                 /* event bits of the friction events (flexbeam.integrate.modal._EVENT_BITS) */
#define EV_UNSTICK (16 | 32)
#define EV_PAINLEVE 64
/* Painlevé's event fires where a = W_nn + sigma W_nt falls to this share of W_nn (methods/painleve.py SHARE): at
 * a -> 0 the collocation's multiplier system turns singular (the step size underflows at a ~ 1e-5 W_nn on the
 * sliding rod of tests/validation/test_friction_ccm.py) */
#define PAINLEVE_SHARE 1e-3
#define VT_NOISE 1e-9 /* [m/s] a slip that starts at rest counts as reversed only this far beyond it (a stick holds v_t
                       * to ~3e-11 m/s, measured on the rough bar of tests/validation/test_friction_ccfm.py) */
#define STOP_SAMPLES 16           /* slip-velocity samples per step */
#define STOP_CLEAR 2.0            /* no samples where the known slip velocities clear zero by this times their spread */
#define UNSTICK_SAMPLES 32        /* samples of the stick margin mu_s F - |lambda_t| per step */
/* The stick margin's band: the collocated multiplier's own accuracy, which its error control holds to
 * max(MULTIPLIER_RTOL rtol, MULTIPLIER_NOISE) of its scale (collocation.c) */
#define UNSTICK_RTOL 100.0
#define UNSTICK_NOISE 1e-7

/* The gap of pair ``pair`` at a modal state and its slip velocity *vt. */
fb_gap fb_tangent_at(const fb_phase *ph, int pair, double t, const double *eta, const double *v, double *vt) {
    const fb_model *m = ph->m;
    const fb_basis *b = ph->b;
    int N = b->N, compliant = fb_compliant(m);
    double z[FB_MAXN], zd[FB_MAXN], J[FB_MAXN], Jt[FB_MAXN];
    fb_frame fr;
    const double *q, *qd;
    fb_to_physical(b, eta, z);
    fb_to_physical(b, v, zd);
    fb_joint(m)->split(m, t, z, zd, &fr, &q, &qd);
    return fb_pair_tangent(m, pair, &fr, q, qd, compliant ? z[N - 1] : 0.0, compliant ? zd[N - 1] : 0.0, 0, J, Jt, vt);
}

/* A frictional pair k in contact at an evaluated node (its b[k] already the normal force's direction), its tangent
 * Jacobian Jt and slip velocity vt (fb_pair_tangent): jt = Psi^T Jt^T, bt = Psi^T M0 M^-1 Jt^T (the update up of the
 * node's mass matrix), and a slipping pair's force direction b[k] += sigma bt (not the regularised law's, whose
 * tangential force is an unknown of its own: fb_tangential_unknown). */
void fb_node_friction(const fb_phase *ph, int k, const double *Jt, double vt, const fb_update *up, fb_node *out) {
    const fb_model *m = ph->m;
    const fb_basis *b = ph->b;
    const fb_obstacle *o = &m->obstacles[m->pairs[k].obstacle];
    const fb_gap *g = &out->gap[k];
    int N = b->N, nz = b->nz, ng = m->ngiven;
    double Jx[FB_MAXN];
    out->vt[k] = vt;
    for (int i = 0; i < nz; i++) Jx[i] = Jt[i + ng];
    if (fb_compliant(m)) Jx[N - 1] = o->ms > 0.0 ? -(-g->ny * o->ux + g->nx * o->uy) : 0.0;
    fb_project(b, Jx, out->jt[k]);
    if (up->active) {
        fb_joint(m)->correct(m, b, up, Jx);
        fb_project(b, Jx, out->bt[k]);
    } else {
        memcpy(out->bt[k], out->jt[k], sizeof(double) * N);
    }
    double sigma = ph->c.regv[k] > 0.0 ? 0.0 : fb_slip_coefficient(&ph->c, k, vt);
    if (sigma != 0.0)
        for (int i = 0; i < N; i++) out->b[k][i] += sigma * out->bt[k][i];
}

/* sigma_k of a slipping pair, or Threlfall's regularised coefficient -mu_k (1 - exp(-3 |v_t| / v_0)) sign(v_t)
 * (Threlfall, Mechanism and Machine Theory 13 (1978) 475-483), 0 at v_t = 0. */
double fb_slip_coefficient(const fb_contacts *c, int k, double vt) {
    if (!(c->regv[k] > 0.0)) return c->slip[k];
    double s = c->regmu[k] * fb_expm1(-3.0 * fabs(vt) / c->regv[k]);
    return vt > 0.0 ? s : (vt < 0.0 ? -s : 0.0);
}

double fb_regularised_force(const fb_phase *ph, const fb_node *nd, int k, double F) {
    const fb_contacts *c = &ph->c;
    return fb_tangential_unknown(c, k) && !c->stick[k] ? fb_slip_coefficient(c, k, nd->vt[k]) * fmax(F, 0.0) : 0.0;
}

/* d sigma / d v_t of fb_slip_coefficient: -3 mu_k / v_0 exp(-3 |v_t| / v_0) under the regularised law (the same from
 * either side of v_t = 0), 0 for a slipping pair's constant sigma. */
double fb_slip_slope(const fb_contacts *c, int k, double vt) {
    if (!(c->regv[k] > 0.0)) return 0.0;
    return -3.0 * c->regmu[k] / c->regv[k] * fb_exp(-3.0 * fabs(vt) / c->regv[k]);
}

/* sign(v_t) of the slip (sdir) times v_t at the state (eta, v) at the fraction x of the step (> 0 while the pair
 * slips its way). */
static double slip_state(const fb_dense *d, double x, const double *eta, const double *v) {
    double vt;
    fb_tangent_at(d->ph, d->pair, d->t0 + x * d->h, eta, v, &vt);
    return d->ph->c.sdir[d->pair] > 0.0 ? vt : -vt;
}

/* slip_state at the fraction x of the step, by the step's dense output. */
static double slip_x(const fb_dense *d, double x) {
    double eta[FB_MAXN], v[FB_MAXN];
    fb_dense_state(d, x, eta, v);
    return slip_state(d, x, eta, v);
}

/* The residual slip speed a slip that started at rest may run back by before it counts as reversed. */
static double rest_noise(const fb_dense *d) { return fmax(VT_NOISE, d->ph->c.vrest[d->pair]); }

/* slip_x beyond the run back of a slip that started at rest (zero where it counts as reversed). */
static double reversed_x(const fb_dense *d, double x) { return slip_x(d, x) + rest_noise(d); }

/* Where the slip of pair d->pair stops -- its slip velocity, positive along its direction, reaches zero -- or, for a
 * slip that started at rest, where it runs backwards beyond VT_NOISE or the stick's residual v_rest it started from
 * (the pair's vrest); FB_NO_EVENT if neither.  The slip velocity is sampled at STOP_SAMPLES points by exact hops
 * between them (one set of propagation weights for all, as the gap's samples in events.c); a sign change seen there
 * is located on the step's dense output.  start: slip_state at the step's start (the caller has it). */
static double fb_find_stop(const fb_dense *d, double start) {
    const fb_basis *b = d->ph->b;
    int N = b->N;
    double noise = rest_noise(d), prev = start;
    int forward = start > 0.0;
    if (start < -noise) return 0.0;
    fb_hops H;
    double A[FB_P * FB_MAXN], eta[FB_MAXN], v[FB_MAXN];
    fb_hops_fill(b, d->h / STOP_SAMPLES, &H);
    fb_monomial(d->tb, d->f, N, A);
    memcpy(eta, d->eta0, sizeof(double) * N);
    memcpy(v, d->v0, sizeof(double) * N);
    for (int i = 1; i <= STOP_SAMPLES; i++) {
        double x = (double)i / STOP_SAMPLES, a = (i - 1.0) / STOP_SAMPLES;
        fb_hop_advance(b, &H, A, a, 1.0 / STOP_SAMPLES, eta, v);
        double cur = slip_state(d, x, eta, v), shift = forward ? 0.0 : noise;
        if (cur + shift <= 0.0 && (forward || cur + shift < 0.0)) { /* seen passed: confirmed by the dense output */
            cur = slip_x(d, x);
            if (cur + shift <= 0.0 && (forward || cur + shift < 0.0))
                return fb_brent_past(d, a, x, prev + shift, cur + shift, forward ? slip_x : reversed_x);
        }
        forward |= cur > 0.0;
        prev = cur;
    }
    return FB_NO_EVENT;
}

/* mu_s F - |lambda_t| of the nodal interpolants at x plus the band ``noise``, and lambda_t in *lam. */
static double stick_margin(const fb_tables *tb, double mus, const double *F, const double *Ft, double noise, double x,
                           double *lam) {
    double f = 0.0, l = 0.0;
    for (int j = 0; j < FB_P; j++) {
        double w = fb_lagrange(tb, j, x);
        f += w * F[j];
        l += w * Ft[j];
    }
    *lam = l;
    return mus * f - fabs(l) + noise;
}

/* Where the stick of pair k ends -- the interpolant of its multiplier lambda_t reaches mu_s F of its normal force's
 * (F: the pair's and its followers')
 * (beyond the multiplier's accuracy, UNSTICK_* of the largest nodal mu_s F or lambda_t of the step and of ``scale``,
 * the phase's largest multiplier: the interpolants' own error where both vanish, at a contact's onset and end), first seen at one of
 * UNSTICK_SAMPLES points past the step's start -- and *kind, FB_EVENT_UNSTICK_PLUS or _MINUS by the sign of lambda_t
 * there (at the step's start: of its largest nodal value); FB_NO_EVENT if it holds. */
double fb_find_unstick(const fb_phase *ph, int k, const double *F, const double *Ft, double scale, int *kind) {
    double mus = ph->c.mus[k], lam, big = scale, top = 0.0;
    for (int j = 0; j < FB_P; j++) {
        big = fmax(big, fmax(mus * F[j], fabs(Ft[j])));
        if (fabs(Ft[j]) > fabs(top)) top = Ft[j];
    }
    double noise = fmax(UNSTICK_RTOL * ph->rtol, UNSTICK_NOISE) * big, prev = stick_margin(ph->tb, mus, F, Ft, noise, 0.0, &lam);
    for (int i = 1; i <= UNSTICK_SAMPLES; i++) {
        double x = (double)i / UNSTICK_SAMPLES, cur = stick_margin(ph->tb, mus, F, Ft, noise, x, &lam);
        if (cur >= 0.0) {
            prev = cur;
            continue;
        }
        if (prev < 0.0) { /* already beyond at the previous sample: the step's start */
            *kind = top > 0.0 ? FB_EVENT_UNSTICK_PLUS : FB_EVENT_UNSTICK_MINUS;
            return (i - 1.0) / UNSTICK_SAMPLES;
        }
        double lo = (i - 1.0) / UNSTICK_SAMPLES, hi = x;
        for (int it = 0; it < 55 && hi - lo > 1e-15; it++) {
            double mid = 0.5 * (lo + hi);
            if (stick_margin(ph->tb, mus, F, Ft, noise, mid, &lam) >= 0.0)
                lo = mid;
            else
                hi = mid;
        }
        stick_margin(ph->tb, mus, F, Ft, noise, hi, &lam);
        *kind = lam > 0.0 ? FB_EVENT_UNSTICK_PLUS : FB_EVENT_UNSTICK_MINUS;
        return hi;
    }
    return FB_NO_EVENT;
}

/* Where the slip of pair d->pair stops (*kind FB_EVENT_STOP), FB_NO_EVENT if it goes on: the slip velocity at the
 * step's start, nodes and end clear of zero by twice its spread there, the slip goes on (no samples); else the
 * samples of fb_find_stop decide. */
static double slip_stop(const fb_dense *d, const fb_work *w, int *kind) {
    const fb_phase *ph = d->ph;
    int k = d->pair;
    *kind = FB_EVENT_STOP;
    double sg = ph->c.sdir[k] > 0.0 ? 1.0 : -1.0, vt, lo, hi;
    fb_tangent_at(ph, k, d->t0, d->eta0, d->v0, &vt);
    lo = hi = sg * vt; /* slip_state at the step's start (x = 0: the dense output's state is eta0, v0) */
    for (int j = 0; j <= FB_P; j++) {
        double f = sg * (j < FB_P ? w->node[j].vt[k] : w->end->vt[k]);
        lo = fmin(lo, f), hi = fmax(hi, f);
    }
    if (lo > STOP_CLEAR * (hi - lo)) return FB_NO_EVENT;
    return fb_find_stop(d, sg * vt);
}

/* a - PAINLEVE_SHARE W_nn, a = W_nn + sigma W_nt, of a held slipping pair at an evaluated node: a = jm . b (b holds
 * the slip's force direction; the modal basis spans the state, Psi Psi^T = M0^-1, so jm . b = J M^-1 (J + sigma
 * Jt)^T) and W_nn = a - sigma jm . bt.  Under the regularised law the tangential force is an unknown of its own (b
 * holds J's direction alone) and sigma = sigma(v_t) at the node: W_nn = jm . b, a = W_nn + sigma(v_t) jm . bt. */
static double slip_mass(const fb_phase *ph, const fb_node *nd, int k) {
    double a = 0.0, nt = 0.0;
    for (int i = 0; i < ph->b->N; i++) a += nd->jm[k][i] * nd->b[k][i], nt += nd->jm[k][i] * nd->bt[k][i];
    if (ph->c.regv[k] > 0.0) /* the regularised law: b is J's alone, its force sigma(v_t) F along Jt an unknown */
        return a + fb_slip_coefficient(&ph->c, k, nd->vt[k]) * nt - PAINLEVE_SHARE * a;
    return a - PAINLEVE_SHARE * (a - ph->c.slip[k] * nt);
}

/* a at the fraction x of the step (the node evaluated there). */
static double slip_mass_x(const fb_dense *d, double x) {
    double eta[FB_MAXN], v[FB_MAXN];
    fb_node nd;
    fb_dense_state(d, x, eta, v);
    fb_eval_node(d->ph, d->t0 + x * d->h, eta, v, FB_WANT_ACTIVE, &nd);
    return slip_mass(d->ph, &nd, d->pair);
}

/* Where a held (CCM) slipping pair's a = W_nn + sigma W_nt reaches PAINLEVE_SHARE W_nn (Painlevé, methods/painleve.py): the first
 * of the step's nodes and end below it, bisected against the sample before it (the step's start: above, its phase
 * began so); FB_NO_EVENT if a stays above it. */
static double find_painleve(const fb_dense *d, const fb_work *w) {
    const fb_tables *tb = d->tb;
    int k = d->pair;
    double lo = 0.0;
    for (int j = 0; j <= FB_P; j++) {
        double x = j < FB_P ? tb->c[j] : 1.0;
        if (slip_mass(d->ph, j < FB_P ? &w->node[j] : w->end, k) > 0.0) {
            lo = x;
            continue;
        }
        double hi = x;
        for (int it = 0; it < 55 && hi - lo > 1e-15; it++) {
            double mid = 0.5 * (lo + hi);
            if (slip_mass_x(d, mid) > 0.0)
                lo = mid;
            else
                hi = mid;
        }
        return hi;
    }
    return FB_NO_EVENT;
}

/* The earliest friction event of pair d->pair on an accepted step (its kind in *kind), FB_NO_EVENT if none. */
double fb_friction_event(const fb_dense *d, const fb_work *w, int events, int *kind) {
    const fb_phase *ph = d->ph;
    int k = d->pair;
    double xp = FB_NO_EVENT;
    int slips = ph->c.slip[k] != 0.0 || ph->c.regv[k] > 0.0; /* Coulomb's slip, or the regularised law's */
    if (slips && ph->c.mode[k] == FB_MODE_CONSTRAINT && (events & EV_PAINLEVE)) {
        xp = find_painleve(d, w);
        if (xp <= 0.0) {
            *kind = FB_EVENT_PAINLEVE;
            return xp;
        }
    }
    if (ph->c.sdir[k] != 0.0 && (events & EV_STOP)) { /* whatever mu_k: a pair with mu_k = 0 < mu_s sticks too */
        double xs = slip_stop(d, w, kind);
        if (xp < xs) *kind = FB_EVENT_PAINLEVE;
        return fmin(xs, xp);
    }
    if (ph->c.stick[k] && (events & EV_UNSTICK))
    {
        double F[FB_P]; /* the normal forces of the pair and its followers */
        for (int j = 0; j < FB_P; j++) F[j] = w->F[k][j];
        for (int l = 0; l < ph->c.npairs; l++)
            if (ph->c.follow[l] == k)
                for (int j = 0; j < FB_P; j++) F[j] += w->F[l][j];
        return fb_find_unstick(ph, k, F, w->Ft[k], w->lambda_scale, kind);
    }
    if (xp != FB_NO_EVENT) *kind = FB_EVENT_PAINLEVE; /* (the regularised law: neither a slip's stop nor a stick) */
    return xp;
}

/* Friction's dissipation rate -(sigma F + F_t) v_t of pair k at an evaluated node (normal force F, tangential
 * unknown Ft: a stick's multiplier or the regularised law's force); 0 for a frictionless pair. */
double fb_friction_rate(const fb_phase *ph, const fb_node *nd, int k, double F, double Ft) {
    if (fb_tangential_unknown(&ph->c, k)) return -Ft * nd->vt[k];
    if (ph->c.slip[k] != 0.0) return -fb_slip_coefficient(&ph->c, k, nd->vt[k]) * F * nd->vt[k];
    return 0.0;
}
