/* Coulomb's switches of a CCFM phase taken in place (issue 28; the loop that takes them: switching.c): at each stop
 * or end of a stick that methods/coulomb.py and methods/stick_start.py would decide alone -- a phase of pairs under
 * their laws, at most one of them sticking -- the pair's new friction row written into the control buffer, the phase
 * started again from the event with the step the controller took there.  The rules, from those modules:
 *
 *   stop of pair k (its slip velocity reached zero): k sticks, row [0, 1, mu_s, 0, 0]; the stick holds if
 *     mu_s F_k - |lambda_t| + band max(|lambda_t|, mu_s F_k) >= 0 with (F, lambda_t) the multipliers of the phase
 *     with that row (rhs.c fb_contact_forces), band = max(UNSTICK_RTOL rtol, UNSTICK_NOISE); else k slips on
 *     against lambda_t at once (the unstick below, sign(lambda_t) its event);
 *   end of pair k's stick (UNSTICK_PLUS / _MINUS): k slips in direction s = -1 / +1, row
 *     [-mu_k s, 0, mu_s, 2 |v_t|, s], v_t its residual slip velocity at the event.
 *
 * Anything else returns the event to Python as fb_advance does: another slipping pair within REST_SPEED of a stop
 * (it stops too), a stop beside a sticking pair or a stick's end beside two (the holders and followers of
 * coulomb.grouped), a held pair (CCM's rows), Threlfall's law, a part of the phase that made no step (the phase
 * loop counts those), an event at t_end (the loop ends there), non-finite multipliers.  The switch's row (switching.c)
 * carries the pair's new friction row. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "phase.h"

/* pair k's friction row [sigma, stick, mu_s, v_rest, s] in the contacts buffer (pack_contacts: 10 floats a pair) */
static double *friction_row(double *contacts, int k) { return contacts + 3 + 10 * k + 5; }

/* the slip velocity v_t of pair k at (t, y) (as core.tangent) */
static double slip_velocity(const fb_model *m, double t, const double *y, int k, double *J) {
    fb_frame fr;
    const double *q, *qd;
    double vt;
    int nb = 2 * fb_nz(m), compliant = fb_compliant(m);
    fb_state_split(m, t, y, &fr, &q, &qd);
    fb_pair_tangent(m, k, &fr, q, qd, compliant ? y[nb] : 0.0, compliant ? y[nb + 1] : 0.0, 0, J,
                    J + fb_nfull(m) + 1, &vt);
    return vt;
}

/* The friction row of `pair` after its event `kind` at (t, y) (the rules above), in row; 0, or 1 where Python
 * decides.  contacts: the phase's contacts buffer (nbuf floats), unchanged; coef: [band, REST_SPEED, mu_k (S),
 * mu_s (S)]. */
static int decide(const fb_model *m, const double *contacts, size_t nbuf, double t, const double *y, int kind,
                  int pair, const double *coef, double *row) {
    if (kind < FB_EVENT_STOP || kind > FB_EVENT_UNSTICK_MINUS) return 1;
    int S = m->npairs, others = 0;
    fb_contacts c;
    if (fb_contacts_unpack(&c, m, contacts, nbuf) || nbuf != 3 + 10 * (size_t)S) return 1;
    for (int k = 0; k < S; k++) {
        if (c.mode[k] == FB_MODE_CONSTRAINT || c.follow[k] >= 0 || c.regv[k] > 0.0) return 1;
        others += k != pair && c.stick[k];
    }
    double band = coef[0], rest = coef[1], muk = coef[2 + pair], mus = coef[2 + S + pair];
    double *J = malloc(sizeof(double) * 2 * (size_t)(fb_nfull(m) + 1));
    if (!J) return 1;
    int python = 0;
    if (kind == FB_EVENT_STOP) {
        python = others > 0 || c.stick[pair] || c.sdir[pair] == 0.0;
        for (int k = 0; k < S && !python; k++) /* coulomb.stop: another slip this slow stops with it */
            python = k != pair && c.sdir[k] != 0.0 && !c.stick[k] && fabs(slip_velocity(m, t, y, k, J)) <= rest;
        if (!python) { /* the stick; does it hold there? (stick_start.holding, breaking) */
            double buf[3 + 10 * FB_MAX_PAIRS], F[FB_MAX_PAIRS], Ft[FB_MAX_PAIRS];
            memcpy(buf, contacts, sizeof(double) * nbuf);
            double stick[5] = {0.0, 1.0, mus, 0.0, 0.0};
            memcpy(friction_row(buf, pair), stick, sizeof stick);
            memcpy(row, stick, sizeof stick);
            fb_contacts cs;
            if (fb_contacts_unpack(&cs, m, buf, nbuf)) {
                python = 1;
            } else if (fb_contact_forces(m, t, y, &cs, F, Ft) == 0) { /* (singular: no multipliers, it holds) */
                double Fs = F[pair] + 0.0, lt = fabs(Ft[pair]), held = mus * Fs;
                if (!isfinite(Fs) || !isfinite(lt)) {
                    python = 1;
                } else if (held - lt + band * fmax(lt, fmax(held, lt)) < 0.0) {
                    kind = Ft[pair] > 0.0 ? FB_EVENT_UNSTICK_PLUS : FB_EVENT_UNSTICK_MINUS;
                }
            }
        }
    } else if (kind == FB_EVENT_UNSTICK_PLUS || kind == FB_EVENT_UNSTICK_MINUS) {
        python = others > 1 || !c.stick[pair];
    } else {
        python = 1;
    }
    if (!python && kind != FB_EVENT_STOP) { /* coulomb.unstick: slip against the multiplier that held it */
        double s = kind == FB_EVENT_UNSTICK_PLUS ? -1.0 : 1.0;
        row[0] = -muk * s, row[1] = 0.0, row[2] = mus, row[3] = 2.0 * fabs(slip_velocity(m, t, y, pair, J));
        row[4] = s;
    }
    free(J);
    return python;
}

int fb_friction_switch(const fb_model *m, double *ctrl, size_t nctrl, const double *state, const double *info,
                       double *y, int kind, int pair, double *coef, double *row, double *h) {
    if (decide(m, ctrl + FB_CTRL_HEAD, nctrl - FB_CTRL_HEAD, state[0], y, kind, pair, coef, row)) return 1;
    memcpy(friction_row(ctrl + FB_CTRL_HEAD, pair), row, sizeof(double) * 5);
    *h = info[FB_INFO_STEP]; /* (the step the controller took: a stick's residual slip decays over it, modal.py) */
    return 0;
}
