/* Bookkeeping of a run: the energy it dissipates and the work its joint receives, at the nodes, over a step and on
 * the dense output; the mechanical energy of an evaluated state.
 *
 *   E_d = int sum_k (F_k - F_k,elastic)(-delta_k') + c_s s'^2 dt over the pairs under a law and the held ones (CCM's
 *   multiplier, no elastic part: the work of its Baumgarte stabilisation, delta' = -kappa delta while a drift
 *   decays), with friction's -F_t v_t (Gauss quadrature of the nodal rates); the work W of a constant applied
 *   torque is tau (phi1 - phi0), exact (phi the angle it works on, the joint's work_angle: the hub angle); for the
 *   coordinates g a joint gives as functions of time (theta(t) prescribed) W = int tau_g theta_g' dt, the joint's
 *   reaction tau_g = M_gg a_g + M_gr a_r - Q_g - J_g F, with its modal-acceleration part M_gr q'' theta_g'
 *   integrated by parts (its rapidly oscillating integrand is not quadrature material):
 *     W(t) = W0 + int [(M_gg a_g - Q_g - sum_k J_k,g F_k) theta_g' - M_gr q' a_g] dt + [M_gr q' theta_g']_t0^t.
 */
#include <string.h>

#include "integrator.h"
#include "phase.h"

/* Node j's rates of E_d and (prescribed theta) of W, with the nodal contact forces F[k][j], their elastic parts
 * Fk[k][j] and the tangential multipliers Ft[k][j] (stick) of the pairs; friction dissipates too (friction.c). */
void fb_node_rates(const fb_phase *ph, const fb_node *nd, const double F[][FB_P], const double Fk[][FB_P],
                   const double Ft[][FB_P], int j, double *ed, double *wd) {
    const fb_model *m = ph->m;
    int n = m->n, S = ph->c.npairs;
    *ed = 0.0;
    for (int k = 0; k < S; k++)
        if (ph->c.mode[k] == FB_MODE_FORCE) {
            *ed += (F[k][j] - Fk[k][j]) * (-nd->gap[k].rate);
            if (ph->c.friction) *ed += fb_friction_rate(ph, nd, k, F[k][j], Ft[k][j]);
        } else if (ph->c.mode[k] == FB_MODE_CONSTRAINT) { /* CCM: the held gap's stabilisation's work */
            *ed += F[k][j] * (-nd->gap[k].rate);
            if (ph->c.friction) *ed += fb_friction_rate(ph, nd, k, F[k][j], Ft[k][j]);
        }
    if (fb_compliant(m)) {
        double sd = nd->zd[ph->b->N - 1];
        *ed += m->obstacles[0].cs * sd * sd;
    }
    if (m->Cd) *ed += fb_damping_force(m, nd->zd + (m->nrigid - m->ngiven), NULL, 0); /* structural damping */
    *wd = 0.0;
    if (!m->ngiven) return;
    const fb_joint_ops *jt = fb_joint(m);
    int nr = m->nrigid, off = nr - m->ngiven;
    const double *q = nd->z + off, *qd = nd->zd + off;
    int N = ph->b->N, compliant = fb_compliant(m);
    /* the contact's Jacobian where the support has moved it (at its rest position the drive's work on the calibrated
     * sensor drifted by 4e-5 of the energy at -1 rad/s, 3e-3 at -4 rad/s, against the reference's 5e-9 and 4e-8) */
    double s = compliant ? nd->z[N - 1] : 0.0, sd = compliant ? nd->zd[N - 1] : 0.0;
    double Q[FB_MAXN], J[FB_MAXN], M[FB_MAXN * FB_MAXN];
    jt->forces(m, &nd->frame, q, qd, 0.0, 1, Q);
    jt->mass(m, q, M);
    double Mtt = M[0], mq = 0.0, JF = 0.0; /* the given coordinate 0 (theta): its row of M */
    for (int i = 0; i < n; i++) mq += M[nr + i] * qd[i];
    for (int k = 0; k < S; k++) {
        if (ph->c.mode[k] == FB_MODE_NONE) continue;
        if (fb_rough(&ph->c, k)) { /* friction's share */
            double Jt[FB_MAXN], vt;
            fb_pair_tangent(m, k, &nd->frame, q, qd, s, sd, 0, J, Jt, &vt);
            JF += Jt[0] * (fb_tangential_unknown(&ph->c, k) ? Ft[k][j] : fb_slip_coefficient(&ph->c, k, vt) * F[k][j]);
        } else {
            fb_pair_gap(m, k, &nd->frame, q, qd, s, sd, 0, J);
        }
        JF += J[0] * F[k][j];
    }
    *wd = (Mtt * nd->frame.thdd - Q[0] - JF) * nd->frame.thd - mq * nd->frame.thdd;
}

double fb_boundary_work(const fb_phase *ph, double t, const double *eta, const double *v) {
    const fb_model *m = ph->m;
    if (!m->ngiven) return 0.0;
    double z[FB_MAXN], zd[FB_MAXN], M[FB_MAXN * FB_MAXN], acc = 0.0;
    fb_frame fr;
    const double *q, *qd;
    fb_to_physical(ph->b, v, zd);
    if (m->na) /* the axial modes' theta row depends on (q, p): -q^T S^T, S^T p */
        fb_to_physical(ph->b, eta, z);
    else
        memset(z, 0, sizeof z); /* the frame's rate needs no position: given coordinates come from time */
    fb_joint(m)->split(m, t, z, zd, &fr, &q, &qd);
    fb_joint(m)->mass(m, q, M);
    for (int i = 0; i < m->n; i++) acc += M[m->nrigid + i] * zd[i];
    return acc * fr.thd;
}

double fb_hub_angle(const fb_phase *ph, const double *eta) {
    double z[FB_MAXN];
    fb_to_physical(ph->b, eta, z);
    return fb_joint(ph->m)->work_angle(ph->m, z);
}

/* T + V_e + V_g (+ the pairs' contact potentials under a law, + the support's energy) at an evaluated node, and
 * *scale = T + V_e (+ the support's), the energy the step's state error is measured against. */
double fb_node_energy(const fb_phase *ph, const fb_node *nd, double *scale) {
    double T;
    return fb_node_energy_parts(ph, nd, scale, &T);
}

/* The tip's deflection from the hub's radial line at an evaluated node (the output column tip_deflection). */
double fb_node_tip(const fb_phase *ph, const fb_node *nd) {
    const fb_model *m = ph->m;
    int off = m->nrigid - m->ngiven;
    return fb_tip_deflection(m, &nd->frame, nd->z + off, nd->zd + off);
}

/* fb_node_energy, and the kinetic energy T (+ the support's) in *kinetic. */
double fb_node_energy_parts(const fb_phase *ph, const fb_node *nd, double *scale, double *kinetic) {
    const fb_model *m = ph->m;
    const double *q = nd->z + (m->nrigid - m->ngiven), *qd = nd->zd + (m->nrigid - m->ngiven);
    double T, Ve, Vg;
    fb_joint(m)->energies(m, &nd->frame, q, qd, &T, &Ve, &Vg);
    if (fb_compliant(m)) {
        const fb_obstacle *o = &m->obstacles[0];
        double s = nd->z[ph->b->N - 1], sd = nd->zd[ph->b->N - 1];
        T += 0.5 * o->ms * sd * sd;
        Ve += 0.5 * o->ks * s * s;
    }
    *scale = T + Ve;
    *kinetic = T;
    double E = T + Ve + Vg;
    for (int k = 0; k < ph->c.npairs; k++)
        if (ph->c.mode[k] == FB_MODE_FORCE) E += fb_law_potential(ph->c.p[k], -nd->gap[k].delta);
    return E;
}

/* Forcing guess for a phase's first step: the forcing at its start, constant (each law's force at the start, F's
 * first S rows; the tangential unknowns, its next S rows: the regularised law's force there, a stick's zero). */
void fb_start_guess(const fb_phase *ph, double t, const double *eta, const double *v, double *f,
                        double F[][FB_P]) {
    fb_node nd;
    int N = ph->b->N, S = ph->c.npairs;
    fb_eval_node(ph, t, eta, v, ph->contact ? FB_WANT_ACTIVE : FB_WANT_NONE, &nd);
    double F0[FB_MAX_PAIRS], Ft0[FB_MAX_PAIRS];
    for (int k = 0; k < S; k++) {
        F0[k] = Ft0[k] = 0.0;
        if (ph->c.mode[k] == FB_MODE_FORCE)
            F0[k] = fb_law_force(ph->c.p[k], -nd.gap[k].delta, -nd.gap[k].rate, NULL, NULL, NULL);
        Ft0[k] = fb_regularised_force(ph, &nd, k, F0[k]);
        for (int j = 0; j < FB_P; j++) F[k][j] = F0[k], F[S + k][j] = Ft0[k];
    }
    for (int j = 0; j < FB_P; j++)
        for (int i = 0; i < N; i++) {
            double x = nd.smooth[i];
            for (int k = 0; k < S; k++) {
                if (ph->c.mode[k] != FB_MODE_NONE) x += nd.b[k][i] * F0[k];
                if (Ft0[k] != 0.0) x += nd.bt[k][i] * Ft0[k];
            }
            f[j * N + i] = x;
        }
}

/* The boundary term -a_O(t) . A s of a moving base's work (base_motion.c) at the modal state eta at t. */
static double base_boundary_at(const fb_phase *ph, double t, const double *eta) {
    double z[FB_MAXN];
    fb_frame fr;
    const double *q, *qd;
    fb_to_physical(ph->b, eta, z);
    fb_joint(ph->m)->split(ph->m, t, z, z, &fr, &q, &qd); /* the frame's rates are not needed: z for z' */
    return fb_base_boundary(ph->m, t, &fr, q, fb_compliant(ph->m) ? z[ph->b->N - 1] : 0.0);
}

/* The bookkeeping over a step [t, t + h] whose nodes and end are in w and st: the nodal rates of E_d and W (red,
 * rwd) and their increments, E_d by Gauss quadrature, W as documented at the top of this file; on a moving base W
 * also holds the base's work, its integrand j_O . A s in the nodal rates and its boundary term -a_O . A s, and the
 * work of the obstacles fixed to the ground, -sum_k F_k n_k . v_O (fb_ground_rate), in the nodal rates.  f: the
 * step's nodal forcing (the damped modes' dissipation, fb_damping_books). */
void fb_step_books(const fb_phase *ph, const fb_work *w, double t, double h, const double *eta, const double *v,
                   const fb_step *st, const double *f, double *red, double *rwd, double *dEd, double *dW) {
    const fb_tables *tb = ph->tb;
    const fb_model *m = ph->m;
    int moving = fb_base_moving(m), off = m->nrigid - m->ngiven;
    double ed = 0.0, wd = 0.0, wb = 0.0;
    for (int j = 0; j < FB_P; j++) {
        fb_node_rates(ph, &w->node[j], w->F, w->Fk, w->Ft, j, &red[j], &rwd[j]);
        if (moving) {
            const fb_node *nd = &w->node[j];
            double Fj[FB_MAX_PAIRS];
            for (int k = 0; k < ph->c.npairs; k++) Fj[k] = w->F[k][j];
            double su = fb_compliant(m) ? nd->z[ph->b->N - 1] : 0.0;
            double r = fb_base_work_rate(m, t + tb->c[j] * h, &nd->frame, nd->z + off, su) +
                       fb_ground_rate(m, &nd->frame, ph->c.mode, Fj, nd->gap);
            rwd[j] += r;
            wb += tb->w[j] * r;
        }
        ed += tb->w[j] * red[j];
        wd += tb->w[j] * rwd[j];
    }
    if (ph->b->damp) { /* the fast or strongly damped modes' exact dissipation (damped.c) */
        fb_damping_books(ph, w, h, eta, v, st->eta1, st->v1, f, red);
        ed = 0.0;
        for (int j = 0; j < FB_P; j++) ed += tb->w[j] * red[j];
    }
    *dEd = h * ed;
    double tau = fb_joint(m)->torque(m, t);
    if (m->ngiven)
        *dW = h * wd + fb_boundary_work(ph, t + h, st->eta1, st->v1) - fb_boundary_work(ph, t, eta, v);
    else if (tau != 0.0)
        *dW = tau * (fb_hub_angle(ph, st->eta1) - fb_hub_angle(ph, eta));
    else
        *dW = 0.0;
    if (moving)
        *dW += (m->ngiven ? 0.0 : h * wb) + base_boundary_at(ph, t + h, st->eta1) - base_boundary_at(ph, t, eta);
}

/* The modal state (eta, v) at t in the step of record rec and its reference-layout positions and rates y[0 .. 2 nz]
 * (and s, s' of a compliant support); returns t's fraction of the step, clipped to [0, 1]. */
double fb_dense_layout(const fb_phase *ph, const double *rec, double t, double *eta, double *v, double *y) {
    const fb_basis *b = ph->b;
    int N = b->N, nz = b->nz;
    double x = (t - rec[0]) / rec[1];
    if (x < 0.0) x = 0.0;
    if (x > 1.0) x = 1.0;
    const double *eta0 = rec + 4, *v0 = eta0 + N, *f = v0 + N;
    double z[FB_MAXN], zd[FB_MAXN];
    fb_dense dd = {ph, rec[0], rec[1], eta0, v0, f, 0, fb_record_tables(rec, fb_record_size(N, ph->m->npairs))};
    fb_dense_state(&dd, x, eta, v);
    fb_to_physical(b, eta, z);
    fb_to_physical(b, v, zd);
    for (int k = 0; k < nz; k++) {
        y[k] = z[k];
        y[nz + k] = zd[k];
    }
    if (N > nz) {
        y[2 * nz] = z[N - 1];
        y[2 * nz + 1] = zd[N - 1];
    }
    return x;
}

/* Reference-layout states [z, z', (s, s'), E_d, W] at sorted times from a phase's records (each time inside
 * [t0, t0 + h] of some record); W for a free/torque joint from the hub angle, as in fb_advance. */
int fb_dense_eval(const fb_model *m, const fb_basis *b, const double *records, int nrec, const double *times,
                  int count, double *Y) {
    int N = b->N, S = m->npairs, R = fb_record_size(N, S), size = fb_state_size(m), r = 0;
    fb_phase ph;
    fb_contacts none;
    memset(&none, 0, sizeof none);
    none.npairs = S;
    fb_phase_init(&ph, m, b, &none, 0.0, 0.0, 0.0);
    for (int i = 0; i < count; i++) {
        double t = times[i];
        while (r + 1 < nrec && t > records[(size_t)r * R] + records[(size_t)r * R + 1]) r++;
        const double *rec = records + (size_t)r * R;
        const double *eta0 = rec + 4, *v0 = eta0 + N, *red = v0 + N + FB_P * N + S * FB_P, *rwd = red + FB_P;
        const fb_tables *tb = fb_record_tables(rec, R);
        double eta[FB_MAXN], v[FB_MAXN], *y = Y + (size_t)i * size;
        double x = fb_dense_layout(&ph, rec, t, eta, v, y);
        double Ed = rec[2], W = rec[3];
        for (int j = 0; j < FB_P; j++) {
            double li = fb_lagrange_integral(tb, j, x);
            Ed += rec[1] * li * red[j];
            W += rec[1] * li * rwd[j];
        }
        double tau = fb_joint(m)->torque(m, t);
        if (m->ngiven) {
            W += fb_boundary_work(&ph, t, eta, v) - fb_boundary_work(&ph, rec[0], eta0, v0);
        } else if (tau != 0.0) {
            W = (fb_base_moving(m) ? W : rec[3]) + tau * (fb_hub_angle(&ph, eta) - fb_hub_angle(&ph, eta0));
        }
        if (fb_base_moving(m)) W += base_boundary_at(&ph, t, eta) - base_boundary_at(&ph, rec[0], eta0);
        y[size - 2] = Ed;
        y[size - 1] = W;
    }
    return 0;
}
