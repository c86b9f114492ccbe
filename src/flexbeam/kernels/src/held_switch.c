/* CCM's and IMM's contacts on one frictionless pair taken in place (issue 25; the loop that takes them: switching.c).
 * The rules, from methods/base.py, methods/ccm.py and methods/imm.py (ImpactMethod.contact_transition, impacting,
 * approaching, held_set; CCM.on_impact, IMM.on_impact), where they decide alone:
 *
 *   release of pair k, the only pair in contact, held (CCM's constraint, IMM's resting contact): k free (its contact
 *     record ends there), the free phase's step bound, the next step the controller's;
 *   impact of pair k, every pair free: k's located gap closes at delta' < -grazing speed (a grazing touch goes to
 *     Python), no other pair's gap within gap tolerance + max(-delta', 0) simultaneity (several at once go to
 *     Python), a contact left under solver.max_contacts; then
 *     FB_SWITCH_HELD (CCM): the e = 0 jump (impulse_map.c, the Python map's bits); k held if its multiplier at the
 *       jumped state is >= 0 (fb_rhs with k held, as held_set), with the held phase's step bound and a first step of
 *       at most FIRST_STEP, else k leaves at once (the record's end) and the flight goes on;
 *     FB_SWITCH_REBOUND (IMM): k's restitution e > 0, its rebound speed w = -e delta' not below solver.rest_velocity
 *       and w^2 not below the rise limit (IMM.unresolvable's first test: a lower rebound goes to Python); the jump
 *       with e, the record ends there, the flight goes on.
 *
 * Nothing else: a phase with law forces or friction rows, a prescribed angle or a compliant support (their jumps are
 * the Python map's), non-zero law parameters in the buffer; and the methods offer the rules only where no pair has
 * Coulomb friction (a frictional pair's onset is Stronge's impulse).  The switch's row is [held (onsets), 0, 0, 0,
 * 0], its record values [P, v-, v+, T-, T+, 0] (an onset's jump, impulse_map.c's out) or [0, 0, 0, 0, 0, delta'] (a
 * release: the gap's rate at the event, as core.gap gives it); the phase loop builds the contact records and phases
 * from them with the method's own code (flexbeam.methods.switches.PairSwitches.kernel_switched).  coef: [grazing
 * speed, gap tolerance, simultaneity, contacts left (counted down here), the free and the held phase's step bounds,
 * FIRST_STEP], and for FB_SWITCH_REBOUND [rest velocity, rise limit, e of each pair] after them. */
#include <string.h>

#include "phase.h"

enum { GRAZING, GAP_TOL, SIMULTANEITY, LEFT, FREE_STEP, HELD_STEP, FIRST_STEP, REST, RISE, RESTITUTION };
#define ROW 5         /* a pair's row in a contacts buffer without friction: [mode, K, n, chi, C] (pack_contacts) */
#define HELD_MAXZ 67  /* the Jacobian's length at most: n <= 64 modes, theta, a support coordinate */

/* the mode of every pair is `mode` but pair k's, which is `mk`, and every law parameter is zero */
static int modes_are(const double *buf, int S, int k, double mk, double mode) {
    for (int l = 0; l < S; l++) {
        const double *r = buf + 3 + ROW * l;
        if (r[0] != (l == k ? mk : mode) || r[1] != 0.0 || r[2] != 0.0 || r[3] != 0.0 || r[4] != 0.0) return 0;
    }
    return 1;
}

/* pair k's gap at (t, y) (as core.gap: the state's own coordinates) */
static fb_gap gap_at(const fb_model *m, int k, double t, const double *y, double *J) {
    fb_frame fr;
    const double *q, *qd;
    fb_state_split(m, t, y, &fr, &q, &qd);
    return fb_pair_gap(m, k, &fr, q, qd, 0.0, 0.0, 1, J);
}

/* Does pair k's contact start alone (the impact rules above), a contact left?  0 with k's gap rate in *rate */
static int alone(const fb_model *m, const double *state, const double *y, int k, const double *coef, double *rate) {
    double J[HELD_MAXZ], t = state[0];
    int S = m->npairs;
    if (coef[LEFT] < 1.0 || fb_nfull(m) >= HELD_MAXZ) return 1;
    *rate = gap_at(m, k, t, y, J).rate;
    if (!(*rate < -coef[GRAZING])) return 1; /* (grazing: its acceleration decides; NaN) */
    for (int l = 0; l < S; l++) {
        if (l == k) continue;
        fb_gap g = gap_at(m, l, t, y, J);
        double closing = 0.0 > -g.rate ? 0.0 : -g.rate; /* (Python's max(-delta', 0.0)) */
        if (g.delta <= coef[GAP_TOL] + closing * coef[SIMULTANEITY]) return 1;
    }
    return 0;
}

/* IMM's rebound of pair k (FB_SWITCH_REBOUND above) */
static int rebound(const fb_model *m, const double *state, double *y, int k, double *coef, double *row, double *h) {
    double rate, e = coef[RESTITUTION + k], yp[2 * HELD_MAXZ + 4], out[5];
    if (alone(m, state, y, k, coef, &rate)) return 1;
    double w = e * -rate; /* (Python's e * speed, speed = -delta') */
    if (e == 0.0 || w < coef[REST] || w * w < coef[RISE] || fb_normal_jump(m, k, state[0], y, e, yp, out)) return 1;
    memcpy(y, yp, sizeof(double) * (size_t)fb_state_size(m));
    *h = state[1];
    row[0] = 0.0;
    memcpy(row + FB_SWITCH_ROW, out, sizeof out);
    coef[LEFT] -= 1.0;
    return 0;
}

static int onset(const fb_model *m, double *ctrl, size_t nctrl, const double *state, double *y, int k, double *coef,
                 double *row, double *h) {
    double *buf = ctrl + FB_CTRL_HEAD, t = state[0], rate;
    size_t ny = (size_t)fb_state_size(m), nbuf = nctrl - FB_CTRL_HEAD;
    if (alone(m, state, y, k, coef, &rate)) return 1;
    double yp[2 * HELD_MAXZ + 4], dy[2 * HELD_MAXZ + 4], out[5], F[FB_MAX_PAIRS], torque, hb[3 + ROW * FB_MAX_PAIRS];
    if (fb_normal_jump(m, k, t, y, 0.0, yp, out)) return 1;
    memcpy(hb, buf, sizeof(double) * nbuf);
    hb[3 + ROW * k] = FB_MODE_CONSTRAINT;
    fb_contacts c;
    if (fb_contacts_unpack(&c, m, hb, nbuf) || fb_rhs(m, t, yp, &c, dy, F, &torque)) return 1;
    int held = F[k] >= 0.0;
    memcpy(y, yp, sizeof(double) * ny);
    if (held) {
        buf[3 + ROW * k] = FB_MODE_CONSTRAINT;
        ctrl[2] = coef[HELD_STEP];
        *h = coef[FIRST_STEP] < state[1] ? coef[FIRST_STEP] : state[1]; /* (Python's min(h, FIRST_STEP)) */
    } else {
        *h = state[1];
    }
    row[0] = held;
    memcpy(row + FB_SWITCH_ROW, out, sizeof out);
    coef[LEFT] -= 1.0;
    return 0;
}

/* CCM's rules (FB_SWITCH_HELD) and IMM's (FB_SWITCH_REBOUND): the same release, the impact each its own */
static int pair_switch(const fb_model *m, double *ctrl, size_t nctrl, const double *state, double *y, int kind,
                       int pair, double *coef, double *row, double *h, int rebounds) {
    int S = m->npairs;
    double *buf = ctrl + FB_CTRL_HEAD;
    if (nctrl - FB_CTRL_HEAD != 3 + ROW * (size_t)S || m->ngiven || fb_compliant(m)) return 1;
    if (kind == FB_EVENT_RELEASE && modes_are(buf, S, pair, FB_MODE_CONSTRAINT, FB_MODE_NONE)) {
        double J[HELD_MAXZ];
        if (fb_nfull(m) >= HELD_MAXZ) return 1;
        buf[3 + ROW * pair] = FB_MODE_NONE;
        ctrl[2] = coef[FREE_STEP];
        *h = state[1];
        row[FB_SWITCH_ROW + 5] = gap_at(m, pair, state[0], y, J).rate;
        return 0;
    }
    if (kind == FB_EVENT_IMPACT && modes_are(buf, S, pair, FB_MODE_NONE, FB_MODE_NONE))
        return rebounds ? rebound(m, state, y, pair, coef, row, h) : onset(m, ctrl, nctrl, state, y, pair, coef, row, h);
    return 1;
}

int fb_held_switch(const fb_model *m, double *ctrl, size_t nctrl, const double *state, const double *info, double *y,
                   int kind, int pair, double *coef, double *row, double *h) {
    (void)info;
    return pair_switch(m, ctrl, nctrl, state, y, kind, pair, coef, row, h, 0);
}

int fb_rebound_switch(const fb_model *m, double *ctrl, size_t nctrl, const double *state, const double *info,
                      double *y, int kind, int pair, double *coef, double *row, double *h) {
    (void)info;
    return pair_switch(m, ctrl, nctrl, state, y, kind, pair, coef, row, h, 1);
}
