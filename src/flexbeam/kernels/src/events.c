/* Event search on a step's exact dense output: the gap closing (impact) or opening (separation), and the
 * collocated multiplier turning tensile (release, in release.c).
 *
 * A step is declared free of a gap event only on a guarantee: either the obstacle is out of reach (the gap
 * at the step start exceeds twice the largest distance P can travel, bounded mode by mode), or the gap,
 * sampled at m points of the exact dense output, stays clear of zero by twice the bound B on the modes
 * too fast for m samples, B = sum_k |j_k| (free amplitude_k + (max|f_k| + |f_k(0)| + V(f_k)) / w_k^2) over
 * w_k h / m > pi/4 (the forced response's bound by parts, forcing_bound.c).
 * Otherwise the sampling is refined (m x 4, twice), each finer level starting where the coarser one's samples
 * stop proving the step free from its start (both ends of an interval clear by B and the curvature term); when
 * every mode that can reach the obstacle is resolved, sign changes, excursions from zero and dips predicted by the
 * cubic Hermite interpolant through (gap, rate) are located by Brent's method (the samples end at the first sign
 * change); and when they are not, the step is too long to decide and is shortened to the first sample beyond.
 */
#include <string.h>

#include "integrator.h"
#include "surface.h"

#define SAMPLES 16      /* gap samples per step when the nodes do not decide (refined x4 up to twice) */
#define SURFACE_NOISE 1e-9 /* [m] a start on the surface counts as crossing only this far beyond it */
#define HERMITE_PTS 16  /* sub-intervals on which a Hermite-predicted dip is checked and searched */

void fb_dense_state(const fb_dense *d, double x, double *eta, double *v) {
    int N = d->ph->b->N;
    fb_weight W[FB_MAXN];
    for (int k = 0; k < N; k++) fb_mode_weights(d->tb, d->ph->b, k, d->h, x, &W[k]);
    fb_propagate(d->ph->b, W, 1, d->eta0, d->v0, d->f, eta, v);
}

static double gap_x(const fb_dense *d, double x, double *rate) {
    fb_gap g = fb_dense_gap(d, x);
    if (rate) *rate = g.rate;
    return g.delta;
}

static double gap_value(const fb_dense *d, double x) { return gap_x(d, x, NULL); }

static double brent(const fb_dense *d, double a, double b, double fa, double fb) {
    return fb_brent(d, a, b, fa, fb, gap_value);
}

/* The contact law's unclipped value K d^n (1 + chi' d') + C d' at the fraction x (d = -delta; -1 out of contact). */
static double law_raw_x(const fb_dense *d, double x) {
    double rate, delta = gap_x(d, x, &rate), pen = -delta;
    const double *p = d->ph->c.p[d->pair];
    if (pen <= 0.0) return -1.0;
    return p[0] * fb_pow(pen, p[1]) * (1.0 + p[2] * (-rate)) + p[3] * (-rate);
}

/* Where the law's force switches between pushing and clipped to zero inside the step (a kink of the forcing,
 * which the collocation polynomial cannot follow): the first sign change of the unclipped law value among the
 * given points, located by Brent's method; FB_NO_EVENT if none. */
double fb_find_kink(const fb_dense *d, const double *kx, const fb_gap *known, int count) {
    const double *p = d->ph->c.p[d->pair];
    double prev = 0.0;
    for (int i = 0; i < count; i++) {
        double pen = -known[i].delta, rate = -known[i].rate;
        double raw = pen > 0.0 ? p[0] * fb_pow(pen, p[1]) * (1.0 + p[2] * rate) + p[3] * rate : -1.0;
        if (i > 0 && pen > 0.0 && -known[i - 1].delta > 0.0 && (prev > 0.0) != (raw > 0.0))
            return fb_brent(d, kx[i - 1], kx[i], prev, raw, law_raw_x);
        prev = raw;
    }
    return FB_NO_EVENT;
}

/* argmin of sign * gap on [lo, hi] by golden-section search (Kiefer 1953). */
static double golden_min(const fb_dense *d, double lo, double hi, double sign) {
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
    double a = lo, b = hi, x1 = b - gr * (b - a), x2 = a + gr * (b - a);
    double f1 = sign * gap_x(d, x1, NULL), f2 = sign * gap_x(d, x2, NULL);
    while (b - a > 1e-14) {
        if (f1 < f2) {
            b = x2; x2 = x1; f2 = f1;
            x1 = b - gr * (b - a);
            f1 = sign * gap_x(d, x1, NULL);
        } else {
            a = x1; x1 = x2; f1 = f2;
            x2 = a + gr * (b - a);
            f2 = sign * gap_x(d, x2, NULL);
        }
    }
    return 0.5 * (a + b);
}

/* A phase that starts on the event surface at rest (P left on the obstacle by a CCM release at lambda = 0, or by
 * a plastic jump) can cross inside an excursion far below round-off: the first point of a geometric grid from a
 * where the gap is beyond the surface by more than ``depth`` and still moving that way is reported
 * (Brent-refined if the gap is seen on the near side just before); FB_NO_EVENT if none. */
static double leaves_surface(const fb_dense *d, double a, double b, double ga, double depth, double sign) {
    double prev_x = a, prev_g = ga;
    for (int k = 48; k >= 0; k--) {
        double x = a + (b - a) * ldexp(1.0, -k), rx;
        double gx = gap_x(d, x, &rx);
        if (sign * gx > depth && sign * rx > 0.0) return -sign * prev_g > 0.0 ? brent(d, prev_x, x, prev_g, gx) : x;
        prev_x = x;
        prev_g = gx;
    }
    return FB_NO_EVENT;
}

static int crosses(double a, double b, double sign) {
    return sign < 0.0 ? (a > 0.0 && b <= 0.0) : (a < 0.0 && b >= 0.0);
}

/* Earliest event in the sampled (x, g, g' h): sign change, excursion from zero, or Hermite-predicted dip.  A
 * phase that starts on the surface (P left there by a plastic jump or a release; a held constraint may leave it
 * a little beyond) either lifts off -- a hump, whose return is the event -- or sinks in: the event is where it
 * is first SURFACE_NOISE further beyond than it started (a jump at e = 0 on a flexible beam can leave P pushed
 * off by one mode and pulled back in by the others a few ns later, a hump far below round-off). */
static double scan(const fb_dense *d, const double *jb, double gam, const double *x, const double *g,
                   const double *rate, int m, double sign) {
    int resting = 0;                                  /* within SURFACE_NOISE of the depth it started at */
    double depth = fmax(sign * g[0], 0.0) + SURFACE_NOISE;
    for (int i = 0; i < m; i++) {
        double a = g[i], b = g[i + 1], ra = rate[i], rb = rate[i + 1], hh = x[i + 1] - x[i];
        if (crosses(a, b, sign)) return b == 0.0 ? x[i + 1] : brent(d, x[i], x[i + 1], a, b);
        if (-sign * a <= 0.0 && -sign * b < 0.0) { /* starts on (or just behind) zero, ends beyond it */
            int start = i == 0 || resting;
            if (fb_on_surface_quiet(d, jb, gam, x[i], hh, a, b, sign, start ? fmax(depth, 1e-6 * fabs(b)) : INFINITY)) {
                resting |= start;                     /* what the hump and the sinking searches would find */
                continue;
            }
            if (start || -sign * ra > 0.0) {          /* a hump: it left, then returns */
                double xm = golden_min(d, x[i], x[i + 1], sign), gm = gap_x(d, xm, NULL);
                if (-sign * gm > 0.0) return brent(d, xm, x[i + 1], gm, b);
            }
            if (start) {
                double xl = leaves_surface(d, x[i], x[i + 1], a, fmax(depth, 1e-6 * fabs(b)), sign);
                if (xl <= 1.0) return xl;
                resting = 1;
            }
            continue;
        }
        resting = 0;
        int same = sign < 0.0 ? (a > 0.0 && b > 0.0) : (a < 0.0 && b < 0.0);
        if (!same) continue;
        int dip = 0;
        for (int k = 0; k <= HERMITE_PTS && !dip; k++) {
            double s = (double)k / HERMITE_PTS, s2 = s * s, s3 = s2 * s;
            double poly = (2 * s3 - 3 * s2 + 1) * a + (s3 - 2 * s2 + s) * hh * ra + (-2 * s3 + 3 * s2) * b +
                          (s3 - s2) * hh * rb;
            dip = sign < 0.0 ? poly < 0.0 : poly > 0.0;
        }
        if (!dip) continue;
        double px = x[i], pg = a;
        for (int k = 1; k <= HERMITE_PTS; k++) {
            double xx = x[i] + hh * k / HERMITE_PTS, gx = k == HERMITE_PTS ? b : gap_x(d, xx, NULL);
            if (crosses(pg, gx, sign)) return brent(d, px, xx, pg, gx);
            px = xx;
            pg = gx;
        }
    }
    return FB_NO_EVENT;
}

static double max_forcing(const fb_dense *d, int k) {
    int N = d->ph->b->N;
    double fm = 0.0;
    for (int j = 0; j < FB_P; j++) fm = fmax(fm, fabs(d->f[j * N + k]));
    return fm;
}

/* Is the obstacle out of reach within the step?  Each mode's velocity stays below its free amplitude
 * sqrt(v^2 + w^2 eta^2) plus h L max_j |f_jk|, L a bound on the nodes' Lebesgue function (fb_tables; a damped
 * mode's too: its energy (v^2 + w^2 eta^2) / 2 only decreases, and its impulse response's velocity stays below 1),
 * so the gap's rate stays below R = sum_k |j_k| (that bound) (+ |J_theta| max|theta'| for a prescribed theta: the
 * joint's rate_bound; |J_theta| <= |r_P|; + max|v_O| for an obstacle fixed to the ground on a moving base, which
 * comes at P with the base's speed); far if gap0 > 2 R h (a factor 2 for the variation of J over the step). */
static int far(const fb_dense *d, const double *jm, double gap0) {
    if (gap0 <= 0.0) return 0;
    const fb_basis *b = d->ph->b;
    double R = 0.0;
    for (int k = 0; k < b->N; k++) {
        double om = b->omega[k];
        double amp = sqrt(d->v0[k] * d->v0[k] + om * om * d->eta0[k] * d->eta0[k]);
        R += fabs(jm[k]) * (amp + d->h * d->tb->lebesgue * max_forcing(d, k));
    }
    const fb_model *m = d->ph->m;
    double given = fb_joint(m)->rate_bound(m, d->t0, d->t0 + d->h);
    if (given != 0.0) R += fb_pair_reach(d) * given;
    if (m->obstacles[m->pairs[d->pair].obstacle].ground) R += fb_base_speed_bound(m, d->t0, d->t0 + d->h);
    return gap0 > 2.0 * R * d->h;
}

/* far() for the phase driver: it may skip a free pair's samples inside the step when this holds. */
int fb_gap_far(const fb_dense *d, const double *jb, double gap0) { return far(d, jb, gap0); }

/* Bounds on the gap between samples spaced by the fraction dx: *fast (modes with w dx h > pi/4, by their
 * amplitude: free amplitude + the forced response's (max|f| + |f(0)| + V(f)) / w^2, V the forcing's total
 * variation over the step; by parts, forcing_bound.c) and the return value, the deviation of the other modes from
 * the linear interpolant, (dx h)^2 / 8 max|g''| with |g''| <= sum_k |j_k| (w_k^2 A_k + max|f_k|) + 2 max|gamma|
 * (gamma: the gap's velocity-product acceleration, the curvature of P's path relative to the obstacle, at the
 * samples), A_k = free amplitude + min(that forced bound, h^2 max|f_k|) (|eta_forced| <= t^2 / 2 max|f|); max|f_k|
 * and V are the forcing polynomial's own.  A damped mode (d = 2 zeta w, damped.c) keeps these bounds -- its free
 * amplitude only decays, its step response's free part stays within 1 (its energy decays: forcing_bound.c) -- and
 * adds d (w A_k + h max|f_k|) to |eta''|. */
double fb_dense_bounds(const fb_dense *d, const double *jm, double gamma, double dx, double *fast) {
    const fb_basis *b = d->ph->b;
    double B = 0.0, G2 = 2.0 * gamma, T = dx * d->h;
    for (int k = 0; k < b->N; k++) {
        if (jm[k] == 0.0) continue; /* adds nothing */
        fb_forcing fc;
        fb_forcing_bound(d->tb, d->f, b->N, k, &fc);
        double om = b->omega[k], fm = fc.max;
        double amp = om > 0.0 ? sqrt(d->eta0[k] * d->eta0[k] + (d->v0[k] / om) * (d->v0[k] / om)) : 0.0;
        if (om * T > 0.25 * FB_PI) {
            B += fabs(jm[k]) * (amp + fb_forced_amplitude(&fc, om));
        } else {
            double forced = om > 0.0 ? fmin(fb_forced_amplitude(&fc, om), d->h * d->h * fm) : 0.0;
            G2 += fabs(jm[k]) * (om * om * (amp + forced) + fm);
            if (b->damp && b->damp[k] > 0.0) /* eta'' also holds -d v, |v| <= w amp + h max|f| (energy decays) */
                G2 += fabs(jm[k]) * b->damp[k] * (om * amp + d->h * fm);
        }
    }
    *fast = B;
    return 0.125 * T * T * G2;
}

/* The largest sample spacing (fraction of the step) at which P cannot pass through a sphere of radius R between
 * two samples: P may move at most max(R / 4, gap / 2) between them (the reference integrator's rule), at the
 * largest sampled speed with a margin of 2.  No limit for a half-plane. */
static double safe_spacing(const fb_dense *d, const fb_gap *g, int count) {
    const fb_obstacle *o = &d->ph->m->obstacles[d->ph->m->pairs[d->pair].obstacle];
    if (o->kind != FB_SPHERE) return 1.0;
    double speed = 0.0, gap = INFINITY;
    for (int i = 0; i < count; i++) {
        speed = fmax(speed, g[i].speed);
        gap = fmin(gap, fabs(g[i].delta));
    }
    if (speed <= 0.0) return 1.0;
    return fmax(0.25 * (o->radius > 0.0 ? o->radius : 1e-3), 0.5 * gap) / (2.0 * speed * d->h);
}

/* The linearised contribution sum_k j_k eta_k of the modes too fast for samples spaced by T (w_k T > pi/4). */
static double fast_part(const fb_dense *d, const double *jm, const double *eta, double T) {
    const fb_basis *b = d->ph->b;
    double acc = 0.0;
    if (!jm) return 0.0; /* a moving contact point: nothing subtracted, the bound covers all of it */
    for (int k = 0; k < b->N; k++)
        if (b->omega[k] * T > 0.25 * FB_PI) acc += jm[k] * eta[k];
    return acc;
}

/* What a level of samples must show for its search to end there (fb_find_gap_event): the gap clear of zero by
 * more than the fast modes' bound B and the curvature term at every sample (-sign (g_i - fast_i) - B - curve > 0),
 * or B = 0 (the scan).  With B != 0 a single sample that fails the first test, with the curvature term at its
 * least (curve0: no velocity-product acceleration, the bound rounds monotonically in it), settles that the level
 * cannot end the search: its further samples are not needed, but at the last level for the first sample beyond
 * the surface (where the step is cut).  With B = 0 the scan ends at the first sign change at the latest: the
 * samples after it are not needed either. */
typedef struct {
    double sign, B, curve0;
    int leaving, need_beyond;
} hopeless_test;

static int hopeless_at(const hopeless_test *ht, const fb_gap *g, const double *fast, int i, int s, int *fail,
                       int *beyond) {
    if (ht->B == 0.0) return i > s && crosses(g[i - 1].delta, g[i].delta, ht->sign);
    if (!*fail && (-ht->sign * (g[i].delta - fast[i]) - ht->B) - ht->curve0 <= 0.0) *fail = 1;
    if (i > 0 && !*beyond && -ht->sign * g[i].delta <= 0.0) *beyond = 1;
    return *fail && (*beyond || !ht->need_beyond);
}

/* The gap at the points i / m, i = s..m, of the step by exact hops between consecutive points (from the start:
 * the points before s only hopped over, not evaluated; point 0 is the caller's), and the fast modes' part of it at
 * each (``fast``, for samples spaced by h / m).  Returns the last point sampled: m, or fewer when ``ht`` says the
 * rest cannot change the search's outcome. */
static int sample_hops(const fb_dense *d, const double *A, const double *jm, int m, int s, double *x, fb_gap *g,
                       double *fast, const hopeless_test *ht) {
    const fb_basis *b = d->ph->b;
    int N = b->N, fail = !ht->leaving, beyond = 0;
    fb_hops H;
    fb_hops_fill(b, d->h / m, &H);
    double eta[FB_MAXN], v[FB_MAXN];
    memcpy(eta, d->eta0, sizeof(double) * N);
    memcpy(v, d->v0, sizeof(double) * N);
    for (int i = 1; i <= s; i++) fb_hop_advance(b, &H, A, (double)(i - 1) / m, 1.0 / m, eta, v);
    x[s] = (double)s / m;
    if (s > 0) g[s] = fb_gap_at(d->ph, d->pair, d->t0 + x[s] * d->h, eta, v);
    fast[s] = fast_part(d, jm, eta, d->h / m);
    if (hopeless_at(ht, g, fast, s, s, &fail, &beyond)) return s;
    for (int i = s + 1; i <= m; i++) {
        fb_hop_advance(b, &H, A, (double)(i - 1) / m, 1.0 / m, eta, v);
        x[i] = (double)i / m;
        g[i] = fb_gap_at(d->ph, d->pair, d->t0 + x[i] * d->h, eta, v);
        fast[i] = fast_part(d, jm, eta, d->h / m);
        if (hopeless_at(ht, g, fast, i, s, &fail, &beyond)) return i;
    }
    return m;
}

/* The end of the free stretch the points s..last prove: the last of the points from s on that are all clear of
 * zero by B + curve (so is every interval between them), or ``xa`` if there is no interval among them. */
static double proven_to(const double *x, const fb_gap *g, const double *fast, int s, int last, double sign,
                        double margin, double xa) {
    int p = s - 1;
    while (p < last && -sign * (g[p + 1].delta - fast[p + 1]) - margin > 0.0) p++;
    return p > s ? x[p] : xa;
}

/* First crossing of the gap in ``direction`` (-1: closing, +1: opening) inside the step, as a fraction of it:
 * FB_NO_EVENT when the step is provably free of it, FB_UNDECIDED when it is too long to decide.
 * ``known``: the gap at the start, the FB_P nodes and the end (the points kx, modal states ``eta_known``, FB_P + 2
 * rows) that the step's evaluation has already; ``jb``: a bound on |jm| over the step (the pair's point may move),
 * ``jm``: the modal gap Jacobian near the start (at the first
 * node).  The gap splits into the part of the modes resolved by the samples, bounded between samples by its
 * curvature, and that of the faster modes, bounded by their amplitude B; the step is free if the resolved part
 * stays clear of zero by B.  A level's samples prove free each interval whose ends are both clear by that much:
 * the stretch [0, xa] they prove from the start is not sampled again by the finer levels, which start at xa.
 * When undecided, ``*beyond`` is the first sampled fraction found beyond the surface (1 if none): an event lies
 * before it, so the caller may shorten the step to there. */
double fb_find_gap_event(const fb_dense *d, int direction, const double *kx, const fb_gap *known,
                         const double *eta_known, const double *jm, const double *jb, double *beyond) {
    double sign = direction < 0 ? -1.0 : 1.0;
    double gap0 = known[0].delta, rate0 = known[0].rate;
    if (direction < 0 && far(d, jb, gap0)) return FB_NO_EVENT;
    int leaving = sign < 0.0 ? (gap0 > 0.0 || rate0 > 0.0) : (gap0 < 0.0 || rate0 < 0.0);
    static const int levels[3] = {SAMPLES, 4 * SAMPLES, 16 * SAMPLES};
    int N = d->ph->b->N;
    double x[16 * SAMPLES + 1], gv[16 * SAMPLES + 1], r[16 * SAMPLES + 1], fast[16 * SAMPLES + 1];
    double A[FB_P * FB_MAXN];
    fb_gap g[16 * SAMPLES + 1];
    int m = FB_P + 1, level = 0, have_A = 0;
    double dx = 0.0, xa = 0.0; /* [0, xa]: proven free by a coarser level */
    for (int i = 0; i <= m; i++) {
        x[i] = kx[i];
        g[i] = known[i];
        if (i) dx = fmax(dx, x[i] - x[i - 1]);
    }
    for (int i = 0; i <= m; i++) fast[i] = fast_part(d, jm, eta_known + (size_t)i * N, dx * d->h);
    int s = 0, last = m, hopeless = 0; /* the level's points s..last sampled; it cannot end the search */
    for (;;) {
        double gam = 0.0;
        for (int i = s; i <= last; i++) gam = fmax(gam, fabs(g[i].gamma));
        double B, curve = fb_dense_bounds(d, jb, gam, dx, &B), safe = safe_spacing(d, g + s, last - s + 1);
        if (!hopeless) {
            double worst = INFINITY;
            for (int i = s; i <= last; i++) {
                gv[i] = g[i].delta;
                r[i] = g[i].rate * d->h;
                worst = fmin(worst, -sign * (gv[i] - fast[i]));
            }
            if (dx <= safe) {
                if (leaving && worst - B - curve > 0.0) return FB_NO_EVENT;
                if (B == 0.0) return scan(d, jb, gam, x + s, gv + s, r + s, last - s, sign);
            }
            while (level < 3 && 1.0 / levels[level] > fmin(dx, safe) * (1.0 - 1e-12) && levels[level] <= m) level++;
        }
        if (dx <= safe) xa = proven_to(x, g, fast, s, last, sign, B + curve, xa);
        if (level == 3) {
            *beyond = 1.0;
            for (int i = s + 1; i <= last; i++)
                if (-sign * g[i].delta <= 0.0) {
                    *beyond = x[i];
                    break;
                }
            return FB_UNDECIDED;
        }
        if (!have_A) fb_monomial(d->tb, d->f, N, A), have_A = 1;
        m = levels[level++];
        dx = 1.0 / m;
        s = (int)fmin(floor(xa * m), m - 1);
        x[0] = 0.0;
        g[0] = known[0];
        hopeless_test ht = {sign, 0.0, 0.0, leaving, level == 3};
        ht.curve0 = fb_dense_bounds(d, jb, 0.0, dx, &ht.B);
        last = sample_hops(d, A, jm, m, s, x, g, fast, &ht);
        hopeless = last < m && ht.B != 0.0;
    }
}
