/* The largest value of one output on a phase's dense output within given brackets, each located by Brent's
 * method for a minimum without derivatives (golden-section steps safeguarding successive parabolic interpolation;
 * R. P. Brent, Algorithms for Minimization without Derivatives, 1973, ch. 5), applied to -sign * output.
 *
 * It serves the contact records' peak forces and the tip's extremes (flexbeam.results): one call per phase, every
 * evaluation a single point of the step's exact dense output (fb_dense_eval) and of the outputs (fb_outputs), so
 * a peak costs some 50-70 evaluations of a microsecond or two, not a Python round trip each. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "detmath.h"
#include "joint.h"
#include "phase.h"
#include "tip_bound.h"

typedef struct {
    const fb_model *m;
    const fb_basis *b;
    const double *records;
    int nrec, R;
    const fb_contacts *c;
    double t0, t1;
    const double *y0, *y1;
    int column; /* >= 0: an output column (FB_NCOLS); < 0: the contact force of pair -1 - column */
    double sign;
    const fb_phase *ph; /* a phase without contacts, for the tip's dense states (fb_dense_layout) */
    const fb_tip_model *tip; /* the tip's linear part and bound (tip_bound.c; the tip column only) */
    int via_outputs;         /* a contact force through fb_outputs even when its law gives it (fb_pair_force_many) */
} probe_t;

/* The first step that ends at or after t (the dense output's own choice), by bisection on the step ends. */
static int step_of(const probe_t *p, double t) {
    int lo = 0, hi = p->nrec - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        const double *rec = p->records + (size_t)mid * p->R;
        if (rec[0] + rec[1] < t)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* A phase without contacts for the dense states (fb_dense_layout), into ph. */
static const fb_phase *free_phase(const fb_model *m, const fb_basis *b, fb_phase *ph) {
    fb_contacts none;
    memset(&none, 0, sizeof none);
    none.npairs = m->npairs;
    fb_phase_init(ph, m, b, &none, 0.0, 0.0, 0.0);
    return ph;
}

/* sign * output at t; the phase's ends give its exact start and end states (as the Python segments do).  The tip,
 * and a contact force given by its law, are computed alone, from the positions and rates (fb_dense_layout), with
 * fb_outputs' arithmetic for them; any other output through fb_dense_eval and fb_outputs. */
static double probe_value(const probe_t *p, double t) {
    double y[2 * FB_MAXN + 4], cols[FB_NCOLS], mv[FB_MAX_POINTS], pc[FB_MAX_PAIRS * FB_PAIR_COLS];
    const fb_model *m = p->m;
    int size = fb_state_size(m), pair = -1 - p->column;
    int alone = p->column == FB_COL_TIP || (pair >= 0 && p->c->mode[pair] == FB_MODE_FORCE && !p->via_outputs);
    if (t <= p->t0)
        memcpy(y, p->y0, sizeof(double) * size);
    else if (t >= p->t1)
        memcpy(y, p->y1, sizeof(double) * size);
    else if (alone) { /* the positions and rates alone: no energy bookkeeping */
        double eta[FB_MAXN], v[FB_MAXN];
        fb_dense_layout(p->ph, p->records + (size_t)step_of(p, t) * p->R, t, eta, v, y);
    } else
        fb_dense_eval(m, p->b, p->records + (size_t)step_of(p, t) * p->R, 1, &t, 1, y);
    if (alone) {
        fb_frame fr;
        const double *q, *qd;
        fb_state_split(m, t, y, &fr, &q, &qd);
        if (p->column == FB_COL_TIP) return p->sign * fb_tip_deflection(m, &fr, q, qd);
        int nb = 2 * fb_nz(m), compliant = fb_compliant(m);
        double s = compliant ? y[nb] : 0.0, sd = compliant ? y[nb + 1] : 0.0;
        fb_gap g = fb_pair_gap(m, pair, &fr, q, qd, s, sd, 0, NULL);
        return p->sign * fb_law_force(p->c->p[pair], -g.delta, -g.rate, NULL, NULL, NULL);
    }
    fb_outputs(m, &t, y, 1, p->c, cols, mv, pc);
    double v = p->column >= 0 ? cols[p->column] : pc[pair * FB_PAIR_COLS + 2];
    return p->sign * v;
}

/* Brent's minimisation of f = -probe_value on [a, b] to an absolute tolerance xtol; returns the abscissa of the
 * smallest f evaluated and its value in *best (as a maximum of probe_value). */
static double brent_max(const probe_t *p, double a, double b, double xtol, double *best) {
    const double golden = 0.3819660112501051; /* (3 - sqrt(5)) / 2 */
    double x = a + golden * (b - a), w = x, v = x;
    double fx = -probe_value(p, x), fw = fx, fv = fx;
    double d = 0.0, e = 0.0;
    for (int iter = 0; iter < 200; iter++) {
        double mid = 0.5 * (a + b), tol1 = 0.5 * xtol + 1e-16 * fabs(x), tol2 = 2.0 * tol1;
        if (fabs(x - mid) <= tol2 - 0.5 * (b - a)) break;
        int parabolic = 0;
        if (fabs(e) > tol1) { /* try a parabola through x, w, v */
            double r = (x - w) * (fx - fv), q = (x - v) * (fx - fw), pp = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if (q > 0.0) pp = -pp;
            q = fabs(q);
            double etemp = e;
            e = d;
            if (fabs(pp) < fabs(0.5 * q * etemp) && pp > q * (a - x) && pp < q * (b - x)) {
                d = pp / q;
                double u = x + d;
                if (u - a < tol2 || b - u < tol2) d = mid >= x ? tol1 : -tol1;
                parabolic = 1;
            }
        }
        if (!parabolic) { /* a golden-section step into the larger part */
            e = (x >= mid ? a : b) - x;
            d = golden * e;
        }
        double u = fabs(d) >= tol1 ? x + d : x + (d > 0.0 ? tol1 : -tol1);
        double fu = -probe_value(p, u);
        if (fu <= fx) {
            if (u >= x)
                a = x;
            else
                b = x;
            v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
        } else {
            if (u < x)
                a = u;
            else
                b = u;
            if (fu <= fw || w == x) {
                v = w, fv = fw, w = u, fw = fu;
            } else if (fu <= fv || v == x || v == w) {
                v = u, fv = fu;
            }
        }
    }
    *best = -fx;
    return x;
}

/* The fastest rate the output can oscillate at between the nodes of the step starting at record r, in a
 * measurable amount: for the tip, the fastest mode whose free vibration there (amplitude |g_k| sqrt(eta_k^2 +
 * (v_k / omega_k)^2) at the step's start, g_k the tip's deflection per unit eta_k) and that of every faster mode
 * add up to more than 1e-9 of the sum over all modes; for any other output, the fastest mode. */
static double fastest_rate(const probe_t *p, int r) {
    const fb_basis *b = p->b;
    int N = b->N;
    double wmax = 0.0;
    for (int k = 0; k < N; k++) wmax = fmax(wmax, b->omega[k]);
    if (p->column != FB_COL_TIP) return wmax;
    const double *rec = p->records + (size_t)r * p->R, *eta = rec + 4, *v = eta + N;
    double amp[FB_MAXN], total = 0.0;
    for (int k = 0; k < N; k++) {
        double w = b->omega[k], a = w > 0.0 ? sqrt(eta[k] * eta[k] + (v[k] / w) * (v[k] / w)) : 0.0;
        amp[k] = fabs(p->tip->g[k]) * a;
        total += amp[k];
    }
    int used[FB_MAXN] = {0};
    double unresolved = 0.0; /* drop the fastest modes while what they add up to is negligible */
    for (int it = 0; it < N; it++) {
        int top = -1;
        for (int k = 0; k < N; k++)
            if (!used[k] && (top < 0 || b->omega[k] > b->omega[top])) top = k;
        if (unresolved + amp[top] > 1e-9 * total) return b->omega[top];
        unresolved += amp[top];
        used[top] = 1;
    }
    return 0.0;
}

/* The grid a bracket [a, z] is searched on before Brent's method: 33 points, and at least 8 per half-period of
 * the fastest measurable oscillation there (fastest_rate; the exactly propagated steps are not limited by the
 * modes' frequencies, so the output may oscillate between the step's nodes), at most 4097. */
static int grid_points(const probe_t *p, double a, double z) {
    double w = fmax(fastest_rate(p, step_of(p, a)), fastest_rate(p, step_of(p, z)));
    double need = 1.0 + ceil(8.0 * w * (z - a) / 3.141592653589793);
    return need < 33.0 ? 33 : need > 4097.0 ? 4097 : (int)need;
}

/* |theta| of the frame at the phase's ends: the scale of the tip's rounding (tip_bound.c). */
static void frame_scale(const probe_t *p, double *th) {
    *th = 0.0;
    for (int s = 0; s < 2; s++) {
        fb_frame fr;
        const double *q, *qd;
        fb_state_split(p->m, s ? p->t1 : p->t0, s ? p->y1 : p->y0, &fr, &q, &qd);
        *th = fmax(*th, fabs(fr.th));
    }
}

/* The tip's bounds over the steps [a, z] touches (tip_bound.c). */
static void tip_bracket(const probe_t *p, double a, double z, fb_tip_bracket *br) {
    double th;
    frame_scale(p, &th);
    fb_tip_reach(p->tip, p->b, p->records, p->R, step_of(p, a), step_of(p, z), th, br);
}

#define OPEN_MAX 8192 /* sub-intervals a pruned search may keep open at one level */

typedef struct { /* the open sub-intervals of a pruned search: left end, sign * deflection at both ends */
    double t[OPEN_MAX], vl[OPEN_MAX], vr[OPEN_MAX];
    int count;
} open_set;

typedef struct { /* what the tip's pruned search keeps: the open sub-intervals, the deflection's linear part */
    open_set open;
    fb_tip_model tip;
} tip_search;

/* The tip's largest sample in [a, z] by branch and bound: 5 samples, then each sub-interval that may hold a value of
 * at least ``top`` or the best sample yet (its larger end plus fb_tip_slack) split in four, until the spacing is that of
 * the grid of G points.  Returns 1 with the best sample (*t_best, *v_best) and the final spacing (*dt) when some
 * sub-interval is still open, 0 when none is (the bracket cannot reach ``top``; *v_best a value the deflection
 * takes), -1 when too many are open (then search the plain grid). */
static int pruned_grid_max(const probe_t *p, open_set *o, double a, double z, int G, double top, double *t_best,
                           double *v_best, double *dt) {
    double h = (z - a) / 4.0, v_prev = probe_value(p, a);
    fb_tip_bracket br;
    tip_bracket(p, a, z, &br);
    *t_best = a, *v_best = v_prev;
    for (int i = 0; i < 4; i++) {
        double t = i == 3 ? z : a + (i + 1) * h, v = probe_value(p, t);
        o->t[i] = a + i * h, o->vl[i] = v_prev, o->vr[i] = v;
        if (v > *v_best) *t_best = t, *v_best = v;
        v_prev = v;
    }
    o->count = 4;
    for (;;) {
        double slack = fb_tip_slack(p->tip, &br, h), ref = fmax(top, *v_best);
        int kept = 0;
        for (int i = 0; i < o->count; i++)
            if (fmax(o->vl[i], o->vr[i]) + slack >= ref) {
                o->t[kept] = o->t[i], o->vl[kept] = o->vl[i], o->vr[kept] = o->vr[i];
                kept++;
            }
        o->count = kept;
        *dt = h;
        if (!kept) return 0;
        if (h * (G - 1) <= (z - a) * (1.0 + 1e-12)) return 1;
        if (4 * kept > OPEN_MAX) return -1;
        h *= 0.25;
        for (int i = kept - 1; i >= 0; i--) { /* in place, from the last: sub-interval 4 i + j */
            double t0 = o->t[i], vl = o->vl[i], vr = o->vr[i], v[5] = {vl, 0.0, 0.0, 0.0, vr};
            for (int j = 1; j < 4; j++) {
                v[j] = probe_value(p, t0 + j * h);
                if (v[j] > *v_best) *t_best = t0 + j * h, *v_best = v[j];
            }
            for (int j = 0; j < 4; j++) o->t[4 * i + j] = t0 + j * h, o->vl[4 * i + j] = v[j], o->vr[4 * i + j] = v[j + 1];
        }
        o->count = 4 * kept;
    }
}

/* The largest sample of sign * output on the grid of G points over [a, z], at *t_best, and the spacing *dt. */
static double grid_max(const probe_t *p, double a, double z, int G, double *t_best, double *dt) {
    double v_best = -INFINITY;
    *dt = (z - a) / (G - 1), *t_best = a;
    for (int i = 0; i < G; i++) {
        double t = i == G - 1 ? z : a + i * *dt, v = probe_value(p, t);
        if (v > v_best) *t_best = t, v_best = v;
    }
    return v_best;
}

/* For each bracket [lo[k], hi[k]] (clipped to [t0, t1]) the abscissa and the value of the largest sign * output:
 * the largest value on a grid that resolves the fastest mode (grid_points), then Brent's method between that grid
 * point's neighbours, where the output is unimodal.  A bracket whose bound reach[k] on its maximum is below the
 * best value found so far (or ``floor``) is skipped (t_out NaN, v_out -inf): give the brackets in decreasing
 * order of their bounds. */
void fb_column_max(const fb_model *m, const fb_basis *b, const double *records, int nrec, const fb_contacts *c,
                   double t0, double t1, const double *y0, const double *y1, int column, double sign,
                   const double *lo, const double *hi, const double *reach, double floor, int count, double xtol,
                   double *t_out, double *v_out) {
    probe_t p = {m, b, records, nrec, fb_record_size(b->N, m->npairs), c, t0, t1, y0, y1, column, sign, NULL, NULL};
    fb_phase ph;
    p.ph = free_phase(m, b, &ph);
    tip_search *ts = column == FB_COL_TIP ? malloc(sizeof *ts) : NULL; /* the tip: a pruned search */
    open_set *o = ts ? &ts->open : NULL;
    if (ts) fb_tip_model_init(m, b, &ts->tip), p.tip = &ts->tip;
    double top = floor;
    for (int k = 0; k < count; k++) {
        if (reach[k] < top) {
            t_out[k] = NAN;
            v_out[k] = -INFINITY;
            continue;
        }
        double a = fmax(lo[k], t0), z = fmin(hi[k], t1);
        int G = grid_points(&p, a, z), open = -1;
        double dt, t_best, v_best;
        if (o) open = pruned_grid_max(&p, o, a, z, G, top, &t_best, &v_best, &dt);
        if (open < 0) v_best = grid_max(&p, a, z, G, &t_best, &dt);
        if (open != 0 && z - a > xtol) {
            double best, t = brent_max(&p, fmax(a, t_best - dt), fmin(z, t_best + dt), xtol, &best);
            if (best > v_best) t_best = t, v_best = best;
        }
        t_out[k] = t_best;
        v_out[k] = v_best;
        if (v_best > top) top = v_best;
    }
    free(ts);
}

/* A probe of the tip's deflection on a phase [t0, t1], with the tip's model alone (not a pruned search's open set),
 * which the caller frees. */
static fb_tip_model *tip_probe(const fb_model *m, const fb_basis *b, const double *records, int nrec, double t0,
                               double t1, const double *y0, const double *y1, probe_t *p) {
    *p = (probe_t){m, b, records, nrec, fb_record_size(b->N, m->npairs), NULL, t0, t1, y0, y1, FB_COL_TIP, 1.0, NULL,
                   NULL};
    fb_tip_model *tm = malloc(sizeof *tm);
    fb_tip_model_init(m, b, tm);
    p->tip = tm;
    return tm;
}

/* The tip's pruned search's bound for samples T apart in [a, z] of a phase (fb_tip_slack_parts: the linear part's,
 * the rest's and the rounding's shares), for the tests that check it against brute force. */
void fb_tip_slack_at(const fb_model *m, const fb_basis *b, const double *records, int nrec, double t0, double t1,
                     const double *y0, const double *y1, double a, double z, double T, double parts[3]) {
    probe_t p;
    fb_tip_model *tm = tip_probe(m, b, records, nrec, t0, t1, y0, y1, &p);
    fb_tip_bracket br;
    tip_bracket(&p, a, z, &br);
    fb_tip_slack_parts(p.tip, &br, T, parts);
    free(tm);
}

/* For the count - 1 intervals between consecutive ``times`` of a phase, how far the tip's deflection can exceed the
 * larger of its values at the interval's ends (fb_tip_slack with T the interval): the intervals the extremes must
 * search, whatever the samples' spacing against the modes' periods. */
void fb_tip_slacks(const fb_model *m, const fb_basis *b, const double *records, int nrec, double t0, double t1,
                   const double *y0, const double *y1, const double *times, int count, double *out) {
    probe_t p;
    fb_tip_model *tm = tip_probe(m, b, records, nrec, t0, t1, y0, y1, &p);
    int N = b->N, r = 0, cur = -1, joint = -1; /* cur: the step bounded in A..E[1] (its predecessor's in [0]) */
    double th, A[2][FB_MAXN], V[2][FB_MAXN], E[2][FB_MAXN], a[FB_MAXN], v[FB_MAXN], e[FB_MAXN];
    fb_tip_bracket own, both; /* the current step's bracket, and its own with its predecessor's */
    frame_scale(&p, &th);
    for (int i = 0; i + 1 < count; i++) { /* times ascending: the steps are walked once, each bounded once */
        double ta = times[i], tz = times[i + 1];
        while (r < nrec - 1 && records[(size_t)r * p.R] + records[(size_t)r * p.R + 1] < ta) r++;
        int r0 = r, r1 = r0;
        while (r1 < nrec - 1 && records[(size_t)r1 * p.R] + records[(size_t)r1 * p.R + 1] < tz) r1++;
        const fb_tip_bracket *br = &own;
        if (r1 > r0 + 1 || r0 < cur) { /* not within one step or two consecutive ones (never on the tip's grid) */
            fb_tip_reach(p.tip, b, records, p.R, r0, r1, th, &both);
            br = &both, joint = -1;
        } else {
            while (cur < r1) {
                memcpy(A[0], A[1], sizeof A[1]), memcpy(V[0], V[1], sizeof V[1]), memcpy(E[0], E[1], sizeof E[1]);
                fb_tip_step_bounds(p.tip, b, records + (size_t)++cur * p.R, p.R, A[1], V[1], E[1]);
                fb_tip_combine(p.tip, A[1], V[1], E[1], th, &own);
            }
            if (r0 < r1) { /* across the step's start: both steps' bounds */
                if (joint != cur) {
                    for (int k = 0; k < N; k++)
                        a[k] = fmax(A[0][k], A[1][k]), v[k] = fmax(V[0][k], V[1][k]), e[k] = fmax(E[0][k], E[1][k]);
                    fb_tip_combine(p.tip, a, v, e, th, &both);
                    joint = cur;
                }
                br = &both;
            }
        }
        out[i] = tz > ta ? fb_tip_slack(p.tip, br, tz - ta) : 0.0;
    }
    free(tm);
}

/* The contact force (or multiplier) of ``pair`` at ``count`` times of a phase [t0, t1] (exact states y0, y1 at its
 * ends), as fb_outputs gives it on the dense output's states (flexbeam.results.arrays.RunSource.pair_force): a
 * force given by its law -- unless a coordinate is given by time or a pair is held, where fb_outputs takes the
 * forces from fb_rhs -- from the positions and rates alone (probe_value), any other through fb_outputs. */
void fb_pair_force_many(const fb_model *m, const fb_basis *b, const double *records, int nrec, const fb_contacts *c,
                        double t0, double t1, const double *y0, const double *y1, int pair, const double *times,
                        int count, double *out) {
    probe_t p = {m, b, records, nrec, fb_record_size(b->N, m->npairs), c, t0, t1, y0, y1, -1 - pair, 1.0, NULL,
                 NULL};
    fb_phase ph;
    p.ph = free_phase(m, b, &ph);
    int held = 0;
    for (int k = 0; k < m->npairs; k++) held |= c->mode[k] == FB_MODE_CONSTRAINT;
    p.via_outputs = m->ngiven || held;
    for (int i = 0; i < count; i++) out[i] = probe_value(&p, times[i]);
}
