/* The jumps of a pair anywhere's contact point (phase.c's fb_advance ends a phase on a storm of them). */
#include <math.h>

#include "phase.h"

/* A pair anywhere holds one point per surface.  Where the beam touches the surface at two places at once -- a bar
 * lying flat on a half-plane, at its ends -- that point jumps from one to the other whenever their depths cross, and
 * the force's point of application with it: a force phase resolves each jump with ever smaller steps (a rigid free
 * bar under Threlfall's regularised friction settled flat and went on at steps of ~1e-9 s without end; its depths
 * cross at the 1e-16 rad level of its angle).  A jump: the point moves by more than JUMP_REACH of the beam's length
 * over one accepted step (a point that follows the surface moves continuously, at the rate -delta_xq q' / delta_xx,
 * by far less over a step that resolves the motion).  JUMP_EVENTS jumps within JUMP_SPAN end the phase (ADV_JUMPING),
 * as a storm of friction switches ends the run (flexbeam.integrate.loop.STORM_EVENTS).  Measured: the flat bar's
 * jumps came 1e-8 s apart (rigid; 100 in 9.9e-7 s) and 2.5e-9 s (4 axial modes); over 270 random runs of the free
 * bar and the spinning stop (every method, law and friction model, near-flat drops among them) no run that succeeded
 * had a single jump, and those that failed had at most 6 but for a storm of friction switches (170, 100 in 6.9e-6 s,
 * now ended by either guard). */
#define JUMP_REACH 0.5
#define JUMP_EVENTS 100
#define JUMP_SPAN 1e-5

/* Book the jumps of the pairs anywhere in contact over the step ending at t (their points at its end: w->end; before
 * it: xprev, when *have_x) in info's window (FB_INFO_JUMPS); ADV_JUMPING when the window holds JUMP_EVENTS of them,
 * else ADV_END. */
int fb_jump_storm(const fb_phase *ph, const fb_work *w, double t, double *xprev, int *have_x, double *info) {
    const fb_model *m = ph->m;
    if (m->nst < 2) return ADV_END; /* (no pair anywhere) */
    double reach = JUMP_REACH * (m->st_x[m->nst - 1] - m->st_x[0]), *jump = info + FB_INFO_JUMPS;
    int storm = ADV_END;
    for (int k = 0; k < m->npairs; k++) {
        if (!m->pairs[k].anywhere || ph->c.mode[k] == FB_MODE_NONE) continue;
        double x = w->end->gap[k].x;
        if (*have_x && fabs(x - xprev[k]) > reach) {
            if (jump[0] == 0.0 || t - jump[1] >= JUMP_SPAN) jump[0] = 0.0, jump[1] = t; /* a new window */
            jump[0] += 1.0, jump[2] = k, jump[3] = xprev[k], jump[4] = x;
            if (jump[0] >= JUMP_EVENTS) storm = ADV_JUMPING;
        }
        xprev[k] = x;
    }
    *have_x = 1;
    return storm;
}
