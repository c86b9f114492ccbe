/* The phase driver's interface (phase.c) and its bookkeeping (bookkeeping.c). */
#ifndef FLEXBEAM_PHASE_H
#define FLEXBEAM_PHASE_H

#include "integrator.h"

/* record row: [t0, h, Ed0, W0, eta0 (N), v0 (N), f (P x N), F (S x P), Ed rates (P), W rates (P), the tangential
 * multipliers (S x P), the summary], S pairs */
int fb_record_size(int N, int S);
/* state buffer: [t, h, Ed, W, have_guess, eta (N), v (N), f (P x N), F (S x P), the tangential multipliers (S x P),
 * the largest multiplier so far] */
int fb_state_buffer_size(int N, int S);
/* control buffer: [rtol, atol, hmax, omega_rigid, events (bits; FB_CTRL_RADAU: the phase collocates at Radau IIA's
 * nodes, a resting contact), contacts (fb_contacts_unpack)] */
#define FB_CTRL_HEAD 5
#define FB_CTRL_RADAU 128
/* what fb_advance returns: t_end reached, an event, the records full, a step-size underflow, a non-finite state, a
 * phase that cannot make progress, a pair anywhere's contact point jumping to and fro (jumps.c, JUMP_*) */
enum {
    ADV_END = 0, ADV_EVENT = 1, ADV_FULL = 2, ADV_UNDERFLOW = 3, ADV_NONFINITE = 4, ADV_STALLED = 5, ADV_JUMPING = 6
};
/* info, accumulated over the calls of one phase (zero at its start): [event kind, steps, rejected steps, node
 * evaluations, event pair, the phase's start time, rejections by cause (FB_REJECT_*), the step taken at the event
 * (before it was cut to end there; 0 without an event), then the jumps of a pair anywhere's point (jumps.c, JUMP_*):
 * their count in the current window, the window's start, the last jump's pair, its material coordinates before and
 * after] */
enum { FB_REJECT_ERROR, FB_REJECT_BALANCE, FB_REJECT_COLLOCATION, FB_REJECT_EVENT, FB_REJECT_CAUSES };
#define FB_INFO_T0 5
#define FB_INFO_REJECT 6
#define FB_INFO_STEP (FB_INFO_REJECT + FB_REJECT_CAUSES)
#define FB_INFO_JUMPS (FB_INFO_STEP + 1)
#define FB_INFO_SIZE (FB_INFO_JUMPS + 5)

/* the step just taken to t moved a pair anywhere's point by a jump: booked in info; ADV_JUMPING on a storm (jumps.c) */
int fb_jump_storm(const fb_phase *ph, const fb_work *w, double t, double *xprev, int *have_x, double *info);
int fb_advance(const fb_model *m, const fb_basis *b, const double *ctrl, size_t nctrl, double *state, double t_end,
               double *records, int capacity, int *nrec, double *info);
/* fb_advance with a phase's switches taken in place (switching.c): its rows' width, the rules (coef[0]) */
#define FB_SWITCH_HEAD 14
#define FB_SWITCH_ROW 5  /* the rule's row */
#define FB_SWITCH_JUMP 6 /* ... and what an onset's jump or a release gives the contact record (held_switch.c) */
enum { FB_SWITCH_FRICTION = 1, FB_SWITCH_HELD = 2, FB_SWITCH_REBOUND = 3 };
int fb_switch_width(int N);
/* A rule: at the event (kind, pair) at y (t = state[0]), 0 with ctrl switched for the next phase, row
 * (FB_SWITCH_ROW + FB_SWITCH_JUMP, zeroed by the caller) for the switch's record, y moved by a jump if any, and h the
 * next phase's first step; 1 (nothing changed) where Python decides.  coef: the rule's own (after coef[0]; a rule
 * may count down in it). */
typedef int (*fb_switch_rule)(const fb_model *m, double *ctrl, size_t nctrl, const double *state, const double *info,
                              double *y, int kind, int pair, double *coef, double *row, double *h);
int fb_friction_switch(const fb_model *m, double *ctrl, size_t nctrl, const double *state, const double *info,
                       double *y, int kind, int pair, double *coef, double *row, double *h);
int fb_held_switch(const fb_model *m, double *ctrl, size_t nctrl, const double *state, const double *info, double *y,
                   int kind, int pair, double *coef, double *row, double *h);
int fb_rebound_switch(const fb_model *m, double *ctrl, size_t nctrl, const double *state, const double *info,
                      double *y, int kind, int pair, double *coef, double *row, double *h);
int fb_advance_switching(const fb_model *m, const fb_basis *b, double *ctrl, size_t nctrl, double *state,
                         double t_end, double *records, int capacity, int *nrec, double *info, double *coef,
                         double *switches, int cap_switches, int *nswitch);
double fb_dense_layout(const fb_phase *ph, const double *rec, double t, double *eta, double *v, double *y);
int fb_dense_eval(const fb_model *m, const fb_basis *b, const double *records, int nrec, const double *times,
                  int count, double *Y);
void fb_column_max(const fb_model *m, const fb_basis *b, const double *records, int nrec, const fb_contacts *c,
                   double t0, double t1, const double *y0, const double *y1, int column, double sign,
                   const double *lo, const double *hi, const double *reach, double floor, int count, double xtol,
                   double *t_out, double *v_out);
void fb_tip_slack_at(const fb_model *m, const fb_basis *b, const double *records, int nrec, double t0, double t1,
                     const double *y0, const double *y1, double a, double z, double T, double parts[3]);
void fb_tip_slacks(const fb_model *m, const fb_basis *b, const double *records, int nrec, double t0, double t1,
                   const double *y0, const double *y1, const double *times, int count, double *out);
void fb_pair_force_many(const fb_model *m, const fb_basis *b, const double *records, int nrec, const fb_contacts *c,
                        double t0, double t1, const double *y0, const double *y1, int pair, const double *times,
                        int count, double *out);

void fb_start_guess(const fb_phase *ph, double t, const double *eta, const double *v, double *f, double F[][FB_P]);
void fb_node_rates(const fb_phase *ph, const fb_node *nd, const double F[][FB_P], const double Fk[][FB_P],
                   const double Ft[][FB_P], int j, double *ed, double *wd);
double fb_boundary_work(const fb_phase *ph, double t, const double *eta, const double *v);
double fb_hub_angle(const fb_phase *ph, const double *eta);
double fb_node_energy(const fb_phase *ph, const fb_node *nd, double *scale);
double fb_node_energy_parts(const fb_phase *ph, const fb_node *nd, double *scale, double *kinetic);
double fb_node_tip(const fb_phase *ph, const fb_node *nd);
/* Floats at the end of each record that summarise its step: [total energy T + V_e + V_g + U_c + E_d - W at the
 * step's end, kinetic energy there, the tip deflection at the FB_P nodes] (flexbeam.integrate.modal reads them). */
#define FB_RECORD_SUMMARY (2 + FB_P)
void fb_step_books(const fb_phase *ph, const fb_work *w, double t, double h, const double *eta, const double *v,
                   const fb_step *st, const double *f, double *red, double *rwd, double *dEd, double *dW);
void fb_damping_books(const fb_phase *ph, const fb_work *w, double h, const double *eta, const double *v,
                      const double *eta1, const double *v1, const double *f, double *red); /* damped.c */

#endif
