/* The phase driver: collocation steps, step-size control and event location over one phase of motion, with each
 * accepted step recorded as dense output (evaluated by bookkeeping.c's fb_dense_eval).
 *
 * Events are searched pair by pair on each accepted step's exact dense output: a free pair's gap closing
 * (impact), a pair under its law opening (separation), a held pair's multiplier turning tensile (release); the
 * earliest ends the phase, the step retaken to end there.  A kink of a law's force (its clipping at zero) ends a
 * step too.  Each step must also keep the energy balance (bookkeeping.c) within a share of its tolerance.
 */
#include <stdlib.h>
#include <string.h>

#include "phase.h"

#define H_MIN_REL 1e-14 /* step-size underflow below this fraction of max(t, 1 s) */
/* A law's kink less than this fraction of max(t, 1 s) past a step's start is at its start: retaken to it, the step
 * would be a few underflow limits long, and the next step, grown by at most 5x from it, would fall below the limit
 * (a kink located just short of the raw law's zero is seen again at the next step's start, 1e-15 s on) */
#define KINK_MIN_REL 1e-12
/* Bounded effort: a phase that cannot make progress -- its step size collapsing, or its steps rejected again and
 * again, as when the forcing and the energy it is checked against disagree -- ends (ADV_STALLED) once its step
 * attempts, accepted and rejected, reach EFFORT_BASE + EFFORT_RATE r (t - t0): t0 the phase's start, r its
 * characteristic rate max(omega_rigid, 1 / hmax) (the lowest flexible frequency; in contact the step bound the
 * contact's duration sets).  Measured over the test suite (fast and slow) and the presets: at most 1564 attempts in
 * a phase and 343 per unit of r (t - t0), except a rigid rod resting under gravity (IMM's resting or CCM's
 * constrained phase, 7 of 8 steps rejected by the energy balance: up to 3.3e3 per unit, 3.5e5 attempts in one
 * phase, until the balance's budget counted the rigid modes' load: ~500 steps a second at rest now); the bound is
 * >= 12 times every phase's use.  The faults of issue 23 that break the energy balance stopped
 * after 1e4-2e5 attempts. */
#define EFFORT_BASE 1e4
#define EFFORT_RATE 4e4

enum { EV_IMPACT = 1, EV_SEPARATION = 2, EV_RELEASE = 4 };

int fb_record_size(int N, int S) { return 4 + 2 * N + FB_P * N + 2 * S * FB_P + 2 * FB_P + 1 + FB_RECORD_SUMMARY; }

/* The node set a record (of R floats) was taken with: its flag before the summary, 1 Radau's, 0 Gauss's. */
const fb_tables *fb_record_tables(const double *rec, int R) {
    return rec[R - FB_RECORD_SUMMARY - 1] != 0.0 ? fb_radau() : fb_gauss();
}

int fb_state_buffer_size(int N, int S) { return 5 + 2 * N + FB_P * N + 2 * S * FB_P + 1; }

static void reject(double *info, int cause) {
    info[2] += 1;
    info[FB_INFO_REJECT + cause] += 1;
}

/* The earliest event of the accepted step [t, t + h] over the pairs, as a fraction of the step (FB_NO_EVENT if
 * none; FB_UNDECIDED, with *beyond, if some pair's search cannot decide), its kind and pair; and the earliest kink
 * of a law's force before it (*kink, FB_NO_EVENT if none).  later: not the phase's first step (fb_find_release). */
static double find_events(const fb_phase *ph, fb_work *w, int events, double t, double h, const double *eta,
                          const double *v, const double *f, const fb_step *st, const fb_gap *gap0, int later,
                          int *kind, int *pair, double *beyond, double *kink) {
    const fb_tables *tb = ph->tb;
    int N = ph->b->N, S = ph->c.npairs, need_jm = 0;
    double x = FB_NO_EVENT, ek[(FB_P + 2) * FB_MAXN];
    *beyond = 1.0;
    *kink = FB_NO_EVENT;
    for (int k = 0; k < S; k++) need_jm |= ph->c.mode[k] == FB_MODE_NONE && (events & EV_IMPACT);
    memcpy(ek, eta, sizeof(double) * N);
    double un[FB_P][FB_MAXN];
    int far[FB_MAX_PAIRS] = {0};
    for (int j = 0; j < FB_P; j++) { /* the nodes' states; the sweeps evaluated the gaps of the pairs in contact */
        double *e = ek + (size_t)(j + 1) * N;
        fb_propagate(ph->b, &w->W[0][j], FB_NPTS, eta, v, f, e, un[j]);
        if (j == 0 && need_jm) {
            fb_eval_node(ph, t + tb->c[j] * h, e, un[j], FB_WANT_JM, &w->node[j]);
            for (int k = 0; k < S; k++) { /* a free pair out of reach needs no samples (fb_find_gap_event) */
                fb_dense dd = {ph, t, h, eta, v, f, k, ph->tb};
                far[k] = ph->c.mode[k] == FB_MODE_NONE && fb_gap_far(&dd, w->node[0].jb[k], gap0[k].delta);
            }
        }
    }
    for (int j = need_jm ? 1 : 0; j < FB_P; j++)
        for (int k = 0; k < S; k++)
            if (ph->c.mode[k] == FB_MODE_NONE && !far[k])
                w->node[j].gap[k] = fb_gap_at(ph, k, t + tb->c[j] * h, ek + (size_t)(j + 1) * N, un[j]);
    memcpy(ek + (size_t)(FB_P + 1) * N, st->eta1, sizeof(double) * N);
    double kx[FB_P + 2];
    kx[0] = 0.0, kx[FB_P + 1] = 1.0;
    for (int j = 0; j < FB_P; j++) kx[j + 1] = tb->c[j];
    int undecided = 0;
    for (int k = 0; k < S; k++) {
        int mode = ph->c.mode[k];
        double xk = FB_NO_EVENT, bk = 1.0;
        fb_gap known[FB_P + 2];
        known[0] = gap0[k], known[FB_P + 1] = w->end->gap[k];
        for (int j = 0; j < FB_P; j++) known[j + 1] = w->node[j].gap[k];
        fb_dense dd = {ph, t, h, eta, v, f, k, ph->tb};
        const double *jm = ph->m->pairs[k].anywhere ? NULL : w->node[0].jm[k];
        if (mode == FB_MODE_NONE && (events & EV_IMPACT)) {
            xk = fb_find_gap_event(&dd, -1, kx, known, ek, jm, w->node[0].jb[k], &bk);
            if (xk <= 1.0 && xk != FB_UNDECIDED && xk < x) x = xk, *kind = FB_EVENT_IMPACT, *pair = k;
        } else if (mode == FB_MODE_FORCE && (events & EV_SEPARATION)) {
            xk = fb_find_gap_event(&dd, 1, kx, known, ek, jm, w->node[0].jb[k], &bk);
            if (xk <= 1.0 && xk != FB_UNDECIDED && xk < x) x = xk, *kind = FB_EVENT_SEPARATION, *pair = k;
        } else if (mode == FB_MODE_CONSTRAINT && (events & EV_RELEASE)) {
            xk = fb_find_release(ph->tb, w->F[k], later);
            if (xk <= 1.0 && xk < x) x = xk, *kind = FB_EVENT_RELEASE, *pair = k;
        }
        int fk = 0; /* Coulomb friction's events (friction.c) */
        double xf = mode != FB_MODE_NONE && ph->c.friction ? fb_friction_event(&dd, w, events, &fk) : FB_NO_EVENT;
        if (xf <= 1.0 && xf < x && xk != FB_UNDECIDED) x = xf, *kind = fk, *pair = k;
        if (xk == FB_UNDECIDED) {
            undecided = 1;
            *beyond = fmin(*beyond, bk);
        }
    }
    if (undecided) return FB_UNDECIDED;
    for (int k = 0; k < S; k++) { /* a kink of a law's force before any event */
        if (ph->c.mode[k] != FB_MODE_FORCE || (x <= 1.0 && x <= 1e-6)) continue;
        fb_gap known[FB_P + 2];
        known[0] = gap0[k], known[FB_P + 1] = w->end->gap[k];
        for (int j = 0; j < FB_P; j++) known[j + 1] = w->node[j].gap[k];
        fb_dense dd = {ph, t, h, eta, v, f, k, ph->tb};
        double xk = fb_find_kink(&dd, kx, known, FB_P + 2);
        if (xk > 1e-6 && xk * h > KINK_MIN_REL * fmax(fabs(t), 1.0) && xk < 1.0 - 1e-6 && xk < x && xk < *kink)
            *kink = xk;
    }
    return x;
}

/* The next step's size and whether it is the phase's last: h is bounded by hmax and stretched to t_end when
 * within 1% of it (not after a cut), and ends at the next knot of a base table inside it (fb_base_next_knot);
 * returns ADV_FULL, ADV_UNDERFLOW or ADV_STALLED when the phase must stop here (the records are full, the step is
 * below round-off, the step budget EFFORT_* is spent), else -1. */
static int plan_step(const fb_model *m, double t, double t_end, double hmax, double rate, int retry, int nrec,
                     int capacity, const double *info, double *h, int *last) {
    if (nrec >= capacity) return ADV_FULL;
    if (*h > hmax) *h = hmax;
    *last = 0;
    if (t + (retry ? 1.0 : 1.01) * *h >= t_end) {
        *h = t_end - t;
        *last = 1;
    }
    double knot = fb_base_next_knot(m, t, 1e-9 * *h);
    if (knot < t + *h) {
        *h = knot - t;
        *last = 0;
    }
    if (*h < H_MIN_REL * fmax(fabs(t), 1.0)) return ADV_UNDERFLOW;
    if (info[1] + info[2] >= EFFORT_BASE + EFFORT_RATE * rate * (t - info[FB_INFO_T0])) return ADV_STALLED;
    return -1;
}

/* One step's record (layout: fb_record_size): [t, h, E_d, W, eta, v, the nodal forcing f, the pairs' nodal forces
 * F, the dissipation and drive-work rates at the nodes, the pairs' nodal tangential multipliers (stick), the node
 * set (1: Radau's, 0: Gauss's; fb_record_tables), the summary FB_RECORD_SUMMARY]; books = [E_d, W at the
 * step's start, their increments over it, the energy and the kinetic energy at its end].  A constrained pair's
 * multipliers raise the phase's multiplier scale. */
static void write_record(const fb_phase *ph, fb_work *w, double *rec, double t, double h, const double *books,
                         const double *eta, const double *v, const double *trial, const double *red,
                         const double *rwd) {
    int N = ph->b->N, S = ph->m->npairs;
    double Ed = books[0], W = books[1], dEd = books[2], dW = books[3], E1 = books[4], T1 = books[5];
    double *rf = rec + 4 + 2 * N, *rF = rf + FB_P * N;
    rec[0] = t;
    rec[1] = h;
    rec[2] = Ed;
    rec[3] = W;
    memcpy(rec + 4, eta, sizeof(double) * N);
    memcpy(rec + 4 + N, v, sizeof(double) * N);
    memcpy(rf, trial, sizeof(double) * FB_P * N);
    memcpy(rF, w->F, sizeof(double) * S * FB_P);
    memcpy(rF + S * FB_P, red, sizeof(double) * FB_P);
    memcpy(rF + S * FB_P + FB_P, rwd, sizeof(double) * FB_P);
    memcpy(rF + S * FB_P + 2 * FB_P, w->Ft, sizeof(double) * S * FB_P);
    rF[2 * S * FB_P + 2 * FB_P] = ph->tb == fb_radau(); /* the node set */
    double *sum = rF + 2 * S * FB_P + 2 * FB_P + 1; /* the summary: energy balance and tip at the end, tip at nodes */
    sum[0] = E1 + (Ed + dEd) - (W + dW);
    sum[1] = T1;
    for (int j = 0; j < FB_P; j++) sum[2 + j] = fb_node_tip(ph, &w->node[j]);
    for (int k = 0; k < S; k++) {
        if (ph->c.mode[k] == FB_MODE_CONSTRAINT)
            for (int j = 0; j < FB_P; j++) w->lambda_scale = fmax(w->lambda_scale, fabs(w->F[k][j]));
        if (ph->c.friction && ph->c.stick[k]) /* a sticking pair's (CCFM holds no other) */
            for (int j = 0; j < FB_P; j++) w->lambda_scale = fmax(w->lambda_scale, fabs(w->Ft[k][j]));
    }
}

/* Collocate a step of size h from (t, eta, v), the iteration starting from the last nodal values (f, F); the
 * nodal forcing in trial, the pairs' nodal forces in w->F.  Returns fb_collocate's status. */
static int collocate_from(const fb_phase *ph, fb_work *w, double t, double h, const double *eta, const double *v,
                          const double *f, double F[][FB_P], double *trial, fb_step *st, double *info) {
    int N = ph->b->N, S = ph->m->npairs;
    memcpy(trial, f, sizeof(double) * FB_P * N);
    memcpy(w->F, F, sizeof(double) * S * FB_P);
    memcpy(w->Ft, F + S, sizeof(double) * S * FB_P); /* the tangential multipliers' guess follows F (fb_advance) */
    int bad = fb_collocate(ph, w, t, h, eta, v, trial, st);
    info[3] += FB_P * w->iterations;
    return bad;
}

/* A step attempt of size *h: 0 when the collocation converged and the error estimate accepts it; 1 when it is
 * rejected (*h cut, the cause booked in info); ADV_NONFINITE when the state is not finite even at 1e-12 s. */
static int collocate_step(const fb_phase *ph, fb_work *w, double t, double *h, const double *eta, const double *v,
                          const double *f, double F[][FB_P], double *trial, fb_step *st, double *info) {
    int bad = collocate_from(ph, w, t, *h, eta, v, f, F, trial, st, info);
    if (bad || !st->converged) {
        if (bad && *h < 1e-12) return ADV_NONFINITE;
        *h *= 0.25;
        reject(info, FB_REJECT_COLLOCATION);
        return 1;
    }
    if (st->err > 1.0) {
        *h = fb_next_step(*h, st->err, 0);
        reject(info, FB_REJECT_ERROR);
        return 1;
    }
    return 0;
}

/* T + V_e + V_g (+ U_c) at (t, eta, v), and its scale T + V_e in *scale (fb_node_energy). */
static double energy_at(const fb_phase *ph, double t, const double *eta, const double *v, double *scale) {
    fb_node n0;
    fb_eval_node(ph, t, eta, v, FB_WANT_GAP, &n0);
    return fb_node_energy(ph, &n0, scale);
}

/* The phase ends at an event at t: its kind and pair in info; returns ADV_EVENT.  The step *h handed on is the next
 * phase's first guess: the step just taken (cut to the event), unless that is below the underflow limit -- the event
 * ~1e-15 s into its step, as the second of two separations that nearly coincide -- which would end the next phase
 * before its first attempt (plan_step); then the step the controller accepted before the cut, ``taken`` (plan_step
 * bounds it again by the next phase's hmax and t_end).  ``taken`` is also left in info[FB_INFO_STEP]: a friction
 * switch resumes from it (integrate/modal.py). */
static int event_code(double *info, int kind, int pair, double t, double *h, double taken) {
    if (*h < H_MIN_REL * fmax(fabs(t), 1.0)) *h = taken;
    info[FB_INFO_STEP] = taken;
    info[0] = kind;
    info[4] = pair;
    return ADV_EVENT;
}

/* The events on an accepted step's dense output: the fraction of the step at which the first event (*kind,
 * *pair; *event set) or a law's kink (the collocation polynomial cannot follow it; *event cleared) falls, > 1 when
 * none does; FB_UNDECIDED when the step must be shortened first, to just past the first sample seen beyond the
 * surface (*h cut, the cause booked).  gap0: the pairs' gaps at the step's start, evaluated unless have_gap0. */
static double step_events(const fb_phase *ph, fb_work *w, int events, double t, double *h, const double *eta,
                          const double *v, const double *trial, fb_step *st, fb_gap *gap0, int have_gap0, int *event,
                          int *kind, int *pair, double *info) {
    if (!have_gap0)
        for (int k = 0; k < ph->m->npairs; k++) gap0[k] = fb_gap_at(ph, k, t, eta, v);
    double beyond, kink;
    int later = info[1] > 0.0; /* not the phase's first step */
    double x = find_events(ph, w, events, t, *h, eta, v, trial, st, gap0, later, kind, pair, &beyond, &kink);
    if (x == FB_UNDECIDED) {
        *h *= beyond < 1.0 ? fmax(beyond, 0.0625) : 0.25;
        reject(info, FB_REJECT_EVENT);
        return x;
    }
    *event = x <= 1.0;
    if (kink < x) {
        x = kink;
        *event = 0;
    }
    return x;
}

/* Move the phase's state to the recorded step's end: its modal state, its nodal values (the next step's first
 * guess) and its gaps. */
static void move_to_end(int N, int S, const fb_work *w, const fb_step *st, const double *trial, double *eta,
                        double *v, double *f, double F[][FB_P], fb_gap *gap0) {
    memcpy(eta, st->eta1, sizeof(double) * N);
    memcpy(v, st->v1, sizeof(double) * N);
    memcpy(f, trial, sizeof(double) * FB_P * N);
    memcpy(F, w->F, sizeof(double) * S * FB_P);
    memcpy(F + S, w->Ft, sizeof(double) * S * FB_P);
    memcpy(gap0, w->end->gap, sizeof(fb_gap) * S);
}

/* The work space of one call of fb_advance; at the phase's start (state[4] == 0) the first forcing guess, the start
 * time and a zero multiplier scale, else the scale the last call left.  NULL if out of memory. */
static fb_work *begin_call(const fb_phase *ph, double *state, double t, const double *eta, const double *v, double *f,
                           double F[][FB_P], double *lambda_scale, double *info) {
    fb_work *w = malloc(sizeof(fb_work));
    if (!w) return NULL;
    w->h = -1.0;
    w->tb = NULL;
    w->stick_h = 0.0;
    w->end = &w->ends[0], w->start = &w->ends[1], w->start_ok = 0;
    if (state[4] == 0.0) { /* the phase starts */
        fb_start_guess(ph, t, eta, v, f, F);
        info[FB_INFO_T0] = t;
        *lambda_scale = 0.0;
    }
    w->lambda_scale = *lambda_scale;
    state[4] = 1.0;
    return w;
}

/* Advance one phase from the state buffer toward t_end.  ctrl: see phase.h; records (capacity rows of
 * fb_record_size); info (FB_INFO_SIZE, see phase.h) accumulates over the calls of a phase.  Returns ADV_* and the
 * number of records written in *nrec. */
int fb_advance(const fb_model *m, const fb_basis *b, const double *ctrl, size_t nctrl, double *state, double t_end,
               double *records, int capacity, int *nrec, double *info) {
    fb_contacts c;
    if (nctrl < FB_CTRL_HEAD || fb_contacts_unpack(&c, m, ctrl + FB_CTRL_HEAD, nctrl - FB_CTRL_HEAD)) return -1;
    fb_phase ph;
    fb_phase_init(&ph, m, b, &c, ctrl[0], ctrl[1], ctrl[3]);
    double hmax = ctrl[2], rate = fmax(ctrl[3], 1.0 / hmax); /* rate: the phase's characteristic rate [1/s] */
    int events = (int)ctrl[4], N = b->N, S = m->npairs, R = fb_record_size(N, S);
    if (events & FB_CTRL_RADAU) ph.tb = fb_radau();
    double t = state[0], h = state[1], Ed = state[2], W = state[3];
    double *eta = state + 5, *v = eta + N, *f = v + N;
    double(*F)[FB_P] = (double(*)[FB_P])(f + FB_P * N); /* S rows F, then S rows of tangential multipliers */
    double *lambda_scale = f + FB_P * N + 2 * S * FB_P; /* kept in the state: a resumed phase goes on with its scale */
    fb_work *w = begin_call(&ph, state, t, eta, v, f, F, lambda_scale, info);
    if (!w) return ADV_NONFINITE;
    *nrec = 0;
    int code = ADV_END, have_gap0 = 0, retry = 0; /* retry: the step was just cut, it may not stretch to t_end */
    int have_E0 = 0;                              /* E0: the energy at t (T + V_e + V_g + U_c), scale0 its T + V_e */
    double trial[FB_P * FB_MAXN], E0 = 0.0, scale0 = 0.0;
    fb_gap gap0[FB_MAX_PAIRS];
    fb_step st;
    double xprev[FB_MAX_PAIRS]; /* the pairs anywhere's points at the last step's end (fb_jump_storm) */
    int have_x = 0;
    while (t < t_end) {
        int last = 0, stop = plan_step(m, t, t_end, hmax, rate, retry, *nrec, capacity, info, &h, &last);
        if (stop >= 0) {
            code = stop;
            break;
        }
        if (!retry) w->stick_h = h; /* a stick's residual decays over the step first tried, its retries' too */
        int tried = collocate_step(&ph, w, t, &h, eta, v, f, F, trial, &st, info);
        if (tried == ADV_NONFINITE) {
            code = ADV_NONFINITE;
            break;
        }
        if (tried) {
            retry = 1;
            continue;
        }
        double E1, scale1, T1, dEd, dW, red[FB_P], rwd[FB_P], h_taken = h; /* h_taken: the step accepted */
        fb_step_books(&ph, w, t, h, eta, v, &st, trial, red, rwd, &dEd, &dW);
        E1 = fb_node_energy_parts(&ph, w->end, &scale1, &T1);
        if (!have_E0) E0 = energy_at(&ph, t, eta, v, &scale0), have_E0 = 1;
        double balance =
            fb_balance_error(&ph, E1 - E0 + dEd - dW, fmax(scale0, scale1), fb_rigid_load(&ph, w->end),
                             fabs(E1) + fabs(E0) + fabs(dEd) + fabs(dW));
        if (balance > 1.0) {
            h = fb_next_step(h, balance, 0);
            reject(info, FB_REJECT_BALANCE);
            retry = 1;
            continue;
        }
        int kind = 0, pair = 0, event = 0;
        double x = step_events(&ph, w, events, t, &h, eta, v, trial, &st, gap0, have_gap0, &event, &kind, &pair, info);
        if (x == FB_UNDECIDED) {
            retry = 1;
            continue;
        }
        if (x < 1.0 && x > 0.0) { /* retake the step to end at the event (or kink) */
            h *= x;
            last = 0;
            collocate_from(&ph, w, t, h, eta, v, f, F, trial, &st, info);
            fb_step_books(&ph, w, t, h, eta, v, &st, trial, red, rwd, &dEd, &dW);
            double scale_x;
            E1 = fb_node_energy_parts(&ph, w->end, &scale_x, &T1);
        } else if (event && x <= 0.0) {
            code = event_code(info, kind, pair, t, &h, h_taken);
            break;
        }
        /* record the step and move to its end */
        double books[6] = {Ed, W, dEd, dW, E1, T1};
        write_record(&ph, w, records + (size_t)(*nrec) * R, t, h, books, eta, v, trial, red, rwd);
        (*nrec)++;
        info[1] += 1;
        W += dW, Ed += dEd;
        move_to_end(N, S, w, &st, trial, eta, v, f, F, gap0);
        t = last ? t_end : t + h;
        if (ph.contact && (code = fb_jump_storm(&ph, w, t, xprev, &have_x, info)) != ADV_END) break;
        have_gap0 = 1;
        if (x < 1.0 && x > 0.0) { /* retaken to an event or kink: its end is evaluated afresh */
            have_E0 = 0;
        } else {
            E0 = E1, scale0 = scale1;
        }
        if (event) {
            code = event_code(info, kind, pair, t, &h, h_taken);
            break;
        }
        fb_next_start(&ph, w);
        retry = 0;
        double hn = fb_next_step(h, st.err, 1);
        fb_extrapolate(ph.tb, N, S, hn / h, f, F);
        if (ph.c.friction) fb_extrapolate(ph.tb, 0, S, hn / h, f, F + S); /* the tangential multipliers */
        h = hn;
    }
    state[0] = t, state[1] = h, state[2] = Ed, state[3] = W;
    *lambda_scale = w->lambda_scale;
    free(w);
    return code;
}
