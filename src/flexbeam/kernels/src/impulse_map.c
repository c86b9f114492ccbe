/* The impulse-momentum map of one frictionless pair (flexbeam.methods.impulse, its module docstring: Khulief &
 * Shabana 1987): the jump IMM takes at each impact and CCM at each onset (e = 0), compiled for the measured cost of
 * the Python map (~25 us of small calls a jump, 24 jumps in CCM's 0.1 s of the seed case).
 *
 * With the pair's Jacobian J (delta' = J z'), the generalised mass M(q) and v- = J z'^-:
 *
 *     W = J M^-1 J^T,   P = -(1 + e) v- / W  (0 unless the pair approaches),   z'^+ = z'^- + M^-1 J^T P,
 *
 * the impulse's work W_c = P (v- + v+) / 2 booked on the dissipated-energy integral and the change of T it does not
 * explain (none here) on the work integral.  The same operations in the same order as the Python map
 * (impulse._normal_jump, _apply and solve_impact_lcp with numerics' matmul and solve, linalg.c), so the same bits:
 * tests/unit/test_impulse_map.py compares the two.  Only for a state that holds all its coordinates (no prescribed
 * theta), no compliant support and an obstacle not fixed to the ground on a moving base (a moving obstacle's
 * velocity enters v- there), and a finite result: returns 1 for any other, and the Python map takes it (an overflow
 * raises its floating-point error, which ends the run). */
#include <string.h>

#include "flexbeam.h"
#include "linalg.h"

#define JUMP_MAXZ 66 /* n <= 64 modes, theta and a support coordinate (rhs.h's MAXZ) */

/* the beam's kinetic energy at (t, y) (the joint's energies, as numerics' equations gives them) */
static double kinetic(const fb_model *m, double t, const double *y) {
    fb_frame fr;
    const double *q, *qd;
    double T, Ve, Vg;
    fb_state_split(m, t, y, &fr, &q, &qd);
    fb_joint(m)->energies(m, &fr, q, qd, &T, &Ve, &Vg);
    return T + 0.0; /* + 1/2 m_s s'^2 of a support, none here (system._kinetic adds it) */
}

int fb_normal_jump(const fb_model *m, int pair, double t, const double *y, double e, double *y_plus, double *out) {
    int N = fb_nfull(m), nz = fb_nz(m), S = fb_state_size(m);
    if (m->ngiven || fb_compliant(m) || N > JUMP_MAXZ || m->obstacles[m->pairs[pair].obstacle].ground) return 1;
    double J[JUMP_MAXZ], M[JUMP_MAXZ * JUMP_MAXZ], X[JUMP_MAXZ], dz[JUMP_MAXZ], W, vm, vp;
    fb_frame fr;
    const double *q, *qd;
    fb_state_split(m, t, y, &fr, &q, &qd);
    fb_pair_gap(m, pair, &fr, q, qd, 0.0, 0.0, 1, J);
    const double *zd = y + nz; /* the velocities: the state's second block (nothing given) */
    fb_la_matmul(J, zd, &vm, 1, N, 1);
    vm = vm + 0.0; /* the obstacle's drift: none */
    fb_joint(m)->mass(m, q, M);
    double T_minus = kinetic(m, t, y);
    memcpy(X, J, sizeof(double) * (size_t)N);
    if (fb_la_solve(M, X, N, 1)) return -1; /* X = M^-1 J^T */
    fb_la_matmul(J, X, &W, 1, N, 1);
    double target = -(1.0 + e) * vm, P = target > 0.0 && W > 0.0 ? target / W : 0.0;
    fb_la_matmul(X, &P, dz, N, 1, 1);
    memcpy(y_plus, y, sizeof(double) * (size_t)S);
    for (int i = 0; i < N; i++) y_plus[nz + i] = zd[i] + dz[i];
    fb_la_matmul(J, y_plus + nz, &vp, 1, N, 1);
    vp = vp + 0.0;
    double T_plus = kinetic(m, t, y_plus), work = 0.5 * (P * (vm + vp));
    y_plus[S - 2] += -work;
    y_plus[S - 1] += (T_plus - T_minus) - work;
    /* an overflow: the Python map's floating-point error ends the run, as before (the state would be non-finite) */
    if (!isfinite(T_minus) || !isfinite(y_plus[S - 2]) || !isfinite(y_plus[S - 1])) return 1;
    for (int i = 0; i < N; i++)
        if (!isfinite(y_plus[nz + i])) return 1;
    out[0] = P, out[1] = vm, out[2] = vp, out[3] = T_minus, out[4] = T_plus;
    return 0;
}
