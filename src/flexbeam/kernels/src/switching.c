/* A phase's switches taken inside the compiled stepper's call: fb_advance, and at each event that the phase loop
 * (flexbeam.integrate.loop.run_phases with the method's transition) would decide alone by a rule written here too,
 * the control buffer switched and the phase started again from the event, as
 * flexbeam.integrate.modal.ModalStepper.advance starts a phase: a fresh collocation guess, the modal state passed
 * through the stepper's state vector (y = Psi eta, eta = toM y; a diagonal basis: the beam's coordinates and a
 * compliant support's), the phase's effort budget from the event.  Two sets of rules (coef[0]):
 *
 *   FB_SWITCH_FRICTION: CCFM's Coulomb switches, a slip's stop and a stick's end (friction_switch.c, issue 28);
 *   FB_SWITCH_HELD: CCM's contacts on one frictionless pair, its e = 0 onset and its release (held_switch.c);
 *   FB_SWITCH_REBOUND: IMM's, its rebound and its resting contact's release (held_switch.c).
 *
 * Anything the rules do not cover returns the event to Python as fb_advance does, and so do a part of the phase that
 * made no step (the phase loop counts those), an event at t_end (the loop ends there) and a basis that is not
 * diagonal.  Each switch taken is a row of `switches` (fb_switch_width(N) doubles): [records written before it, t,
 * the event, the pair, the rule's row (FB_SWITCH_ROW), the finished part's steps and node evaluations, the step taken
 * at the event, Ed, W, eta (N), v (N), the rule's record values (FB_SWITCH_JUMP), y (2 N + 2)] -- eta, v the state at
 * the event, before any jump, y the stepper's state vector after it; the stepper cuts the phase's records there. */
#include <stdlib.h>
#include <string.h>

#include "phase.h"

int fb_switch_width(int N) { return FB_SWITCH_HEAD + 4 * N + FB_SWITCH_JUMP + 2; }

int fb_advance_switching(const fb_model *m, const fb_basis *b, double *ctrl, size_t nctrl, double *state,
                         double t_end, double *records, int capacity, int *nrec, double *info, double *coef,
                         double *switches, int cap_switches, int *nswitch) {
    int N = b->N, S = m->npairs, R = fb_record_size(N, S), width = fb_switch_width(N), code;
    int nz = fb_nz(m), compliant = fb_compliant(m); /* the state vector [z (nz), z' (nz), (s, s'), Ed, W] */
    size_t ny = (size_t)fb_state_size(m);
    int kind0 = (int)coef[0];
    fb_switch_rule rule = kind0 == FB_SWITCH_HELD      ? fb_held_switch
                          : kind0 == FB_SWITCH_REBOUND ? fb_rebound_switch
                                                       : fb_friction_switch;
    *nrec = 0, *nswitch = 0;
    double *y = malloc(sizeof(double) * ny);
    if (!y) return ADV_NONFINITE;
    for (;;) {
        int n = 0;
        code = fb_advance(m, b, ctrl, nctrl, state, t_end, records + (size_t)(*nrec) * R, capacity - *nrec, &n, info);
        *nrec += n;
        int kind = (int)info[0], pair = (int)info[4];
        if (code != ADV_EVENT || *nswitch >= cap_switches || info[1] == 0.0 || state[0] >= t_end || !b->diagonal ||
            N != nz + compliant || ny != (size_t)(2 * N + 2)) /* (the row's room for y: fb_switch_width) */
            break;
        double t = state[0], *eta = state + 5, *v = eta + N, row[FB_SWITCH_ROW + FB_SWITCH_JUMP] = {0.0}, h;
        for (int i = 0; i < N; i++) { /* the stepper's state vector (ModalStepper.from_modal) */
            double psi = b->Psi[(size_t)i * N + i];
            int iz = i < nz ? i : 2 * nz, iv = i < nz ? nz + i : 2 * nz + 1; /* the support's s, s' after z' */
            y[iz] = psi * eta[i], y[iv] = psi * v[i];
        }
        y[ny - 2] = state[2], y[ny - 1] = state[3];
        /* the rule switches ctrl, may move y (a jump) and gives the next phase's first step; 1: Python decides */
        if (rule(m, ctrl, nctrl, state, info, y, kind, pair, coef + 1, row, &h)) break;
        double *e = switches + (size_t)(*nswitch) * width;
        e[0] = *nrec, e[1] = t, e[2] = kind, e[3] = pair;
        memcpy(e + 4, row, sizeof(double) * FB_SWITCH_ROW);
        e[9] = info[1], e[10] = info[3], e[11] = info[FB_INFO_STEP], e[12] = state[2], e[13] = state[3];
        memcpy(e + FB_SWITCH_HEAD, eta, sizeof(double) * 2 * N);
        memcpy(e + FB_SWITCH_HEAD + 2 * N, row + FB_SWITCH_ROW, sizeof(double) * FB_SWITCH_JUMP);
        memcpy(e + FB_SWITCH_HEAD + 2 * N + FB_SWITCH_JUMP, y, sizeof(double) * ny); /* ny = 2 N + 2 here */
        (*nswitch)++;
        memset(state, 0, sizeof(double) * (size_t)fb_state_buffer_size(N, S));
        state[0] = t, state[1] = h, state[2] = y[ny - 2], state[3] = y[ny - 1];
        for (int i = 0; i < N; i++) { /* (ModalStepper._put_modal) */
            double tom = b->toM[(size_t)i * N + i];
            int iz = i < nz ? i : 2 * nz, iv = i < nz ? nz + i : 2 * nz + 1;
            state[5 + i] = tom * y[iz], state[5 + N + i] = tom * y[iv];
        }
        memset(info, 0, sizeof(double) * FB_INFO_SIZE);
        info[FB_INFO_T0] = t;
    }
    free(y);
    return code;
}
