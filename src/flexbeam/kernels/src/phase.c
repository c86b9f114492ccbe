/* The phase driver: collocation steps, step-size control and event location over one phase of motion, with each
 * accepted step recorded as dense output; and the evaluation of that dense output at any time.
 *
 * Bookkeeping integrals: E_d = int (F - F_k)(-delta') + c_s s'^2 dt (Gauss quadrature of the nodal rates); the
 * joint work W of a free or torque-driven joint is tau (phi1 - phi0), exact for the constant torque (phi the hub
 * angle); with theta(t) prescribed W = int tau_joint theta' dt with the modal-acceleration part m_tq q'' theta'
 * integrated by parts (its rapidly oscillating integrand is not quadrature material):
 *   W(t) = W0 + int [(M_tt theta'' - Q_t - J_t F) theta' - m_tq q' theta''] dt + [m_tq q' theta']_t0^t.
 */
#include <stdlib.h>
#include <string.h>

#include "integrator.h"

/* A step's energy-balance residual may use this share of the energy error its state tolerance admits: the state's
 * error estimate is conservative, but its energy errors add up over the ~100 free-flight steps of a 0.1 s run
 * (measured on the seed case: drift 1.9e-6 at fast_rtol 1e-6 without this check, <= 6.4e-7 with it, at 0-8 %
 * more steps). */
#define BALANCE_SHARE 0.1
#define BALANCE_ROUNDOFF 1e-13 /* the residual's round-off, relative to its terms (a few hundred ulps) */
#define H_MIN_REL 1e-14 /* step-size underflow below this fraction of max(t, 1 s) */

enum { ADV_END = 0, ADV_EVENT = 1, ADV_FULL = 2, ADV_UNDERFLOW = 3, ADV_NONFINITE = 4 };
enum { EV_IMPACT = 1, EV_SEPARATION = 2, EV_RELEASE = 4 };

/* record row: [t0, h, Ed0, W0, eta0 (N), v0 (N), f (P x N), F (P), Ed rates (P), W rates (P)] */
int fb_record_size(int N) { return 4 + 2 * N + FB_P * N + 3 * FB_P; }

/* state buffer: [t, h, Ed, W, have_guess, eta (N), v (N), f (P x N), F (P)] */
int fb_state_buffer_size(int N) { return 5 + 2 * N + FB_P * N + FB_P; }

/* The node's rates of E_d and (prescribed theta) of W, for the nodal contact force F and its elastic part Fk. */
static void node_rates(const fb_phase *ph, const fb_node *nd, double F, double Fk, double *ed, double *wd) {
    const fb_model *m = ph->m;
    int n = m->n, compliant = fb_compliant(m);
    *ed = ph->mode == FB_MODE_FORCE ? (F - Fk) * (-nd->rate) : 0.0;
    if (compliant) {
        double sd = nd->zd[ph->b->N - 1];
        *ed += m->obstacles[0].cs * sd * sd;
    }
    *wd = 0.0;
    if (!m->prescribed) return;
    const double *q = nd->z, *qd = nd->zd;
    double Q[FB_MAXN], dr[2 * FB_MAXN], J[FB_MAXN];
    fb_forces(m, nd->th, nd->thd, q, qd, 0.0, 1, Q);
    double Mtt = m->Jc + fb_quad(m->Mc, q, n), mq = 0.0, Jt = 0.0;
    for (int i = 0; i < n; i++) mq += m->mtq[i] * qd[i];
    if (ph->mode != FB_MODE_NONE && m->nobstacles) {
        fb_kin k = {.want_acc = 0};
        fb_point_kinematics(m, &m->points[0], nd->th, nd->thd, q, qd, &k, dr);
        fb_gap_state(&m->obstacles[0], &k, dr, n + 1, 0.0, 0.0, J);
        Jt = J[0];
    }
    *wd = (Mtt * nd->thdd - Q[0] - Jt * F) * nd->thd - mq * nd->thdd;
}

static double boundary_work(const fb_phase *ph, double t, const double *v) {
    const fb_model *m = ph->m;
    if (!m->prescribed) return 0.0;
    double z[FB_MAXN], th, thd, thdd, acc = 0.0;
    fb_to_physical(ph->b, v, z);
    fb_drive_motion(m, t, &th, &thd, &thdd);
    for (int i = 0; i < m->n; i++) acc += m->mtq[i] * z[i];
    return acc * thd;
}

static double hub_angle(const fb_phase *ph, const double *eta) {
    const fb_model *m = ph->m;
    double z[FB_MAXN], acc;
    fb_to_physical(ph->b, eta, z);
    acc = z[0];
    for (int i = 0; i < m->n; i++) acc += m->d[i] * z[i + 1];
    return acc;
}

/* T + V_e + V_g (+ the contact potential in a force phase, + the support's energy) at an evaluated node, and
 * *scale = T + V_e (+ the support's), the energy the step's state error is measured against. */
static double node_energy(const fb_phase *ph, const fb_node *nd, double *scale) {
    const fb_model *m = ph->m;
    const double *q = m->prescribed ? nd->z : nd->z + 1, *qd = m->prescribed ? nd->zd : nd->zd + 1;
    double T, Ve, Vg;
    fb_energies(m, nd->th, nd->thd, q, qd, &T, &Ve, &Vg);
    if (fb_compliant(m)) {
        const fb_obstacle *o = &m->obstacles[0];
        double s = nd->z[ph->b->N - 1], sd = nd->zd[ph->b->N - 1];
        T += 0.5 * o->ms * sd * sd;
        Ve += 0.5 * o->ks * s * s;
    }
    *scale = T + Ve;
    double E = T + Ve + Vg;
    if (ph->mode == FB_MODE_FORCE) E += fb_law_potential(ph->p, -nd->delta);
    return E;
}

/* The bookkeeping over a step [t, t + h] whose nodes and end are in w and st: the nodal rates of E_d and W (red,
 * rwd) and their increments, E_d by Gauss quadrature, W as documented at the top of this file. */
static void step_books(const fb_phase *ph, const fb_work *w, double t, double h, const double *eta, const double *v,
                       const fb_step *st, double *red, double *rwd, double *dEd, double *dW) {
    const fb_tables *tb = fb_gauss();
    const fb_model *m = ph->m;
    double ed = 0.0, wd = 0.0;
    for (int j = 0; j < FB_P; j++) {
        node_rates(ph, &w->node[j], w->F[j], w->Fk[j], &red[j], &rwd[j]);
        ed += tb->w[j] * red[j];
        wd += tb->w[j] * rwd[j];
    }
    *dEd = h * ed;
    if (m->prescribed)
        *dW = h * wd + boundary_work(ph, t + h, st->v1) - boundary_work(ph, t, v);
    else if (m->drive == FB_DRIVE_TORQUE)
        *dW = m->torque * (hub_angle(ph, st->eta1) - hub_angle(ph, eta));
    else
        *dW = 0.0;
}

/* The step's energy-balance residual r = E(t + h) - E(t) + dE_d - dW against BALANCE_SHARE of the energy error the
 * state tolerance admits: a state error e in the energy norm (|x|^2 = 2 (T + V_e) = 2 scale) moves the energy by
 * at most |x| |e| + |e|^2 / 2, and |e| <= tol = atol + rtol |x|; but never below the round-off of the residual's
 * terms (``size``: the sum of their magnitudes).  Returns |r| over that (> 1: reject). */
static double balance_error(const fb_phase *ph, double r, double scale, double size) {
    double x = sqrt(2.0 * scale), tol = ph->atol + ph->rtol * x;
    return fabs(r) / fmax(BALANCE_SHARE * (x * tol + 0.5 * tol * tol), BALANCE_ROUNDOFF * size);
}

/* Forcing guess for a phase's first step: the forcing at its start, constant. */
static void start_guess(const fb_phase *ph, double t, const double *eta, const double *v, double *f, double *F) {
    fb_node nd;
    int N = ph->b->N, contact = ph->mode != FB_MODE_NONE;
    fb_eval_node(ph, t, eta, v, contact, &nd);
    double F0 = 0.0;
    if (ph->mode == FB_MODE_FORCE) F0 = fb_law_force(ph->p, -nd.delta, -nd.rate, NULL, NULL, NULL);
    for (int j = 0; j < FB_P; j++) {
        F[j] = F0;
        for (int k = 0; k < N; k++) f[j * N + k] = nd.smooth[k] + (contact ? nd.b[k] * F0 : 0.0);
    }
}

/* Values at the next step's nodes (1 + ratio c_i) of the interpolant through the nodal rows of f (and F). */
static void extrapolate(int N, double ratio, double *f, double *F) {
    const fb_tables *tb = fb_gauss();
    double L[FB_P][FB_P], g[FB_P * FB_MAXN], G[FB_P];
    for (int i = 0; i < FB_P; i++)
        for (int j = 0; j < FB_P; j++) L[i][j] = fb_lagrange(j, 1.0 + ratio * tb->c[i]);
    for (int i = 0; i < FB_P; i++) {
        G[i] = 0.0;
        for (int k = 0; k < N; k++) g[i * N + k] = 0.0;
        for (int j = 0; j < FB_P; j++) {
            G[i] += L[i][j] * F[j];
            for (int k = 0; k < N; k++) g[i * N + k] += L[i][j] * f[j * N + k];
        }
    }
    memcpy(f, g, sizeof(double) * FB_P * N);
    memcpy(F, G, sizeof(double) * FB_P);
}

/* Advance one phase from the state buffer toward t_end.  ctrl = [mode, p0, p1, p2, p3, rtol, atol, hmax,
 * omega_rigid, events (bits EV_*)]; records (capacity rows of fb_record_size(N)); info = [event kind, steps,
 * rejected, node evaluations].  Returns ADV_* and the number of records written in *nrec. */
int fb_advance(const fb_model *m, const fb_basis *b, const double *ctrl, double *state, double t_end,
               double *records, int capacity, int *nrec, double *info) {
    fb_phase ph = {m, b, (int)ctrl[0], {ctrl[1], ctrl[2], ctrl[3], ctrl[4]}, ctrl[5], ctrl[6], ctrl[8], 0};
    for (int i = 1; i < b->nz && !m->prescribed; i++)
        if (b->row0[i] != 0.0) ph.row0_q = 1;
    double hmax = ctrl[7];
    int events = (int)ctrl[9], N = b->N, R = fb_record_size(N);
    double t = state[0], h = state[1], Ed = state[2], W = state[3];
    double *eta = state + 5, *v = eta + N, *f = v + N, *F = f + FB_P * N;
    fb_work *w = malloc(sizeof(fb_work));
    if (!w) return ADV_NONFINITE;
    w->h = -1.0;
    w->lambda_scale = 0.0;
    if (state[4] == 0.0) start_guess(&ph, t, eta, v, f, F);
    state[4] = 1.0;
    *nrec = 0;
    int code = ADV_END;
    double trial[FB_P * FB_MAXN];
    fb_step st;
    const fb_tables *tb = fb_gauss();
    int contact = ph.mode != FB_MODE_NONE, have_gap0 = 0;
    fb_gap gap0;
    int retry = 0; /* the step was just cut: it may not stretch back to t_end */
    int have_E0 = 0;    /* E0: the energy at t (T + V_e + V_g + U_c), scale0 its T + V_e */
    double E0 = 0.0, scale0 = 0.0;
    while (t < t_end) {
        if (*nrec >= capacity) {
            code = ADV_FULL;
            break;
        }
        if (h > hmax) h = hmax;
        int last = 0;
        if (t + (retry ? 1.0 : 1.01) * h >= t_end) {
            h = t_end - t;
            last = 1;
        }
        if (h < H_MIN_REL * fmax(fabs(t), 1.0)) {
            code = ADV_UNDERFLOW;
            break;
        }
        memcpy(trial, f, sizeof(double) * FB_P * N);
        memcpy(w->F, F, sizeof(double) * FB_P);
        int bad = fb_collocate(&ph, w, t, h, eta, v, trial, &st);
        info[3] += FB_P * w->iterations;
        if (bad || !st.converged) {
            if (bad && h < 1e-12) {
                code = ADV_NONFINITE;
                break;
            }
            h *= 0.25;
            info[2] += 1;
            retry = 1;
            continue;
        }
        if (st.err > 1.0) {
            h = fb_next_step(h, st.err, 0);
            info[2] += 1;
            retry = 1;
            continue;
        }
        double E1, scale1, dEd, dW, red[FB_P], rwd[FB_P];
        step_books(&ph, w, t, h, eta, v, &st, red, rwd, &dEd, &dW);
        E1 = node_energy(&ph, &w->end, &scale1);
        if (!have_E0) {
            fb_node n0;
            fb_eval_node_acc(&ph, t, eta, v, 1, 0, &n0);
            E0 = node_energy(&ph, &n0, &scale0);
            have_E0 = 1;
        }
        double balance = balance_error(&ph, E1 - E0 + dEd - dW, fmax(scale0, scale1),
                                       fabs(E1) + fabs(E0) + fabs(dEd) + fabs(dW));
        if (balance > 1.0) {
            h = fb_next_step(h, balance, 0);
            info[2] += 1;
            retry = 1;
            continue;
        }
        /* events on the accepted step's dense output */
        double x = FB_NO_EVENT, beyond = 1.0;
        int kind = 0;
        fb_gap known[FB_P + 2];
        double kx[FB_P + 2];
        if (events & (EV_IMPACT | EV_SEPARATION)) {
            if (!have_gap0) gap0 = fb_gap_at(&ph, t, eta, v);
            double ek[(FB_P + 2) * FB_MAXN];
            kx[0] = 0.0, known[0] = gap0;
            memcpy(ek, eta, sizeof(double) * N);
            for (int j = 0; j < FB_P; j++) {
                double *e = ek + (size_t)(j + 1) * N, u[FB_MAXN];
                fb_propagate(b, &w->W[0][j], FB_NPTS, eta, v, trial, e, u);
                if (!contact) { /* free flight: the nodes were evaluated without the gap (the first fully: jm) */
                    if (j == 0)
                        fb_eval_node(&ph, t + tb->c[j] * h, e, u, 1, &w->node[j]);
                    else
                        w->node[j].gap = fb_gap_at(&ph, t + tb->c[j] * h, e, u);
                }
                kx[j + 1] = tb->c[j], known[j + 1] = w->node[j].gap;
            }
            kx[FB_P + 1] = 1.0, known[FB_P + 1] = w->end.gap;
            memcpy(ek + (size_t)(FB_P + 1) * N, st.eta1, sizeof(double) * N);
            fb_dense dd = {&ph, t, h, eta, v, trial};
            x = fb_find_gap_event(&dd, (events & EV_IMPACT) ? -1 : 1, kx, known, ek, w->node[0].jm, &beyond);
            kind = (events & EV_IMPACT) ? FB_EVENT_IMPACT : FB_EVENT_SEPARATION;
        }
        if (x == FB_NO_EVENT && (events & EV_RELEASE)) {
            x = fb_find_release(w->F);
            kind = FB_EVENT_RELEASE;
        }
        if (x == FB_UNDECIDED) { /* shorten the step, to just past the first sample seen beyond the surface */
            h *= beyond < 1.0 ? fmax(beyond, 0.0625) : 0.25;
            info[2] += 1;
            retry = 1;
            continue;
        }
        int event = x <= 1.0;
        if (ph.mode == FB_MODE_FORCE && (!event || x > 1e-6)) { /* a kink of the law's force before any event: */
            fb_dense dd = {&ph, t, h, eta, v, trial};         /* end the step there (the collocation polynomial */
            double xk = fb_find_kink(&dd, kx, known, FB_P + 2); /* cannot follow it, nor see it from its end) */
            if (xk > 1e-6 && xk < 1.0 - 1e-6 && (!event || xk < x)) {
                x = xk;
                event = 0;
            }
        }
        if (x < 1.0 && x > 0.0) { /* retake the step to end at the event (or kink) */
            double hx = x * h;
            memcpy(trial, f, sizeof(double) * FB_P * N);
            memcpy(w->F, F, sizeof(double) * FB_P);
            fb_collocate(&ph, w, t, hx, eta, v, trial, &st);
            info[3] += FB_P * w->iterations;
            h = hx;
            last = 0;
        } else if (event && x <= 0.0) {
            code = ADV_EVENT;
            info[0] = kind;
            break;
        }
        /* record the step and move to its end */
        double *rec = records + (size_t)(*nrec) * R, *rf = rec + 4 + 2 * N;
        rec[0] = t;
        rec[1] = h;
        rec[2] = Ed;
        rec[3] = W;
        memcpy(rec + 4, eta, sizeof(double) * N);
        memcpy(rec + 4 + N, v, sizeof(double) * N);
        memcpy(rf, trial, sizeof(double) * FB_P * N);
        if (x < 1.0 && x > 0.0) step_books(&ph, w, t, h, eta, v, &st, red, rwd, &dEd, &dW);
        double *rF = rf + FB_P * N;
        memcpy(rF, w->F, sizeof(double) * FB_P);
        memcpy(rF + FB_P, red, sizeof(double) * FB_P);
        memcpy(rF + 2 * FB_P, rwd, sizeof(double) * FB_P);
        for (int j = 0; j < FB_P; j++) w->lambda_scale = fmax(w->lambda_scale, fabs(w->F[j]));
        (*nrec)++;
        info[1] += 1;
        W += dW;
        Ed += dEd;
        memcpy(eta, st.eta1, sizeof(double) * N);
        memcpy(v, st.v1, sizeof(double) * N);
        memcpy(f, trial, sizeof(double) * FB_P * N);
        memcpy(F, w->F, sizeof(double) * FB_P);
        t = last ? t_end : t + h;
        gap0 = w->end.gap, have_gap0 = (events & (EV_IMPACT | EV_SEPARATION)) != 0;
        if (x < 1.0 && x > 0.0) { /* retaken to an event or kink: its end is evaluated afresh */
            have_E0 = 0;
        } else {
            E0 = E1, scale0 = scale1;
        }
        if (event) {
            code = ADV_EVENT;
            info[0] = kind;
            break;
        }
        retry = 0;
        double hn = fb_next_step(h, st.err, 1);
        extrapolate(N, hn / h, f, F);
        h = hn;
    }
    state[0] = t;
    state[1] = h;
    state[2] = Ed;
    state[3] = W;
    free(w);
    return code;
}

/* Reference-layout states [z, z', (s, s'), E_d, W] at sorted times from a phase's records (each time inside
 * [t0, t0 + h] of some record); W for a free/torque joint from the hub angle, as in fb_advance. */
int fb_dense_eval(const fb_model *m, const fb_basis *b, const double *records, int nrec, const double *times,
                  int count, double *Y) {
    int N = b->N, nz = b->nz, R = fb_record_size(N), size = fb_state_size(m), r = 0;
    fb_phase ph = {m, b, 0, {0, 0, 0, 0}, 0, 0, 0, 0};
    for (int i = 0; i < count; i++) {
        double t = times[i];
        while (r + 1 < nrec && t > records[(size_t)r * R] + records[(size_t)r * R + 1]) r++;
        const double *rec = records + (size_t)r * R;
        double x = (t - rec[0]) / rec[1];
        if (x < 0.0) x = 0.0;
        if (x > 1.0) x = 1.0;
        const double *eta0 = rec + 4, *v0 = eta0 + N, *f = v0 + N, *red = f + FB_P * N + FB_P, *rwd = red + FB_P;
        double eta[FB_MAXN], v[FB_MAXN], z[FB_MAXN], zd[FB_MAXN];
        fb_dense dd = {&ph, rec[0], rec[1], eta0, v0, f};
        fb_dense_state(&dd, x, eta, v);
        fb_to_physical(b, eta, z);
        fb_to_physical(b, v, zd);
        double *y = Y + (size_t)i * size;
        for (int k = 0; k < nz; k++) {
            y[k] = z[k];
            y[nz + k] = zd[k];
        }
        if (N > nz) {
            y[2 * nz] = z[N - 1];
            y[2 * nz + 1] = zd[N - 1];
        }
        double Ed = rec[2], W = rec[3];
        for (int j = 0; j < FB_P; j++) {
            double li = fb_lagrange_integral(j, x);
            Ed += rec[1] * li * red[j];
            W += rec[1] * li * rwd[j];
        }
        if (m->prescribed) {
            W += boundary_work(&ph, t, v) - boundary_work(&ph, rec[0], v0);
        } else if (m->drive == FB_DRIVE_TORQUE) {
            W = rec[3] + m->torque * (hub_angle(&ph, eta) - hub_angle(&ph, eta0));
        }
        y[size - 2] = Ed;
        y[size - 1] = W;
    }
    return 0;
}
