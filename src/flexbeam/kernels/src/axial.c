/* The axial modes' part of the equations (model.axial_modes > 0; docs/formulation.md, "Axial deformation"),
 * shared by the joints.
 *
 * The flexible coordinates are [q, p]: nb bending modes q, then na axial modes p whose stretch Phi_a(x) p joins the
 * centre line's u_x (Kane, Ryan & Banerjee 1987).  To second order, with the frame turning at theta':
 *
 *   T  += 1/2 theta'^2 (2 m_ta p + p^T M_aa p) + theta' (p^T S q' - q^T S^T p') + 1/2 p'^T M_aa p'
 *   V_e += 1/2 p^T K_a p                     (V_g += g sin(theta) s_a p on a revolute joint: its joint adds it)
 *
 * so that M(q, p) gains, in the frame angle's row and column, 2 m_ta p + p^T M_aa p (theta-theta), S^T p (on q) and
 * -S q (on p), and M_aa on p; Lagrange's equations add
 *
 *   Q_theta += -2 theta' (m_ta + p^T M_aa) p'
 *   Q_q     += -2 theta' S^T p'
 *   Q_p      = -K_a p + theta'^2 (m_ta + M_aa p) + 2 theta' S q'.
 *
 * M_aa and K_a are diagonal (the rod's eigenfunctions).  The collocation's M0 M(q, p)^-1 is a rank-two update of M0
 * (joint.h, fb_update): Woodbury's identity with U = [e, u], C = [[ds, 1], [1, 0]].
 */
#include "flexbeam.h"

/* The frame angle's row of M from the axial modes over the flexible coordinates, u = (S^T p, -S q), and the change
 * of its theta-theta entry 2 m_ta p + p^T M_aa p (returned). */
double fb_axial_row(const fb_model *m, const double *q, double *u) {
    int nb = fb_nb(m), na = m->na;
    const double *p = q + nb;
    double dJ = 0.0;
    for (int j = 0; j < nb; j++) u[j] = 0.0;
    for (int k = 0; k < na; k++) {
        const double *Sk = m->S + (size_t)k * nb;
        double sq = 0.0;
        for (int j = 0; j < nb; j++) {
            sq += Sk[j] * q[j];
            u[j] += Sk[j] * p[k];
        }
        u[nb + k] = -sq;
        dJ += (2.0 * m->mta[k] + m->Maa[k] * p[k]) * p[k];
    }
    return dJ;
}

/* The axial modes' generalised forces: Qf (the flexible coordinates' part of Q) gains -2 theta' S^T p' on q, and
 * its p rows are set to theta'^2 (m_ta + M_aa p) + 2 theta' S q' (- K_a p if ``elastic``); returns the frame
 * angle's -2 theta' (m_ta + p^T M_aa) p'. */
double fb_axial_forces(const fb_model *m, double thd, const double *q, const double *qd, int elastic, double *Qf) {
    int nb = fb_nb(m), na = m->na;
    const double *p = q + nb, *pd = qd + nb;
    double qth = 0.0;
    for (int k = 0; k < na; k++) {
        const double *Sk = m->S + (size_t)k * nb;
        double sqd = 0.0;
        for (int j = 0; j < nb; j++) {
            sqd += Sk[j] * qd[j];
            Qf[j] -= 2.0 * thd * Sk[j] * pd[k];
        }
        double lever = m->mta[k] + m->Maa[k] * p[k];
        Qf[nb + k] = thd * thd * lever + 2.0 * thd * sqd - (elastic ? m->Ka[k] * p[k] : 0.0);
        qth -= 2.0 * thd * lever * pd[k];
    }
    return qth;
}

/* The axial modes' share of the kinetic and elastic energies (added to *T and *Ve). */
void fb_axial_energies(const fb_model *m, double thd, const double *q, const double *qd, double *T, double *Ve) {
    int nb = fb_nb(m), na = m->na;
    const double *p = q + nb, *pd = qd + nb;
    double dJ = 0.0, h = 0.0, tp = 0.0, vp = 0.0;
    for (int k = 0; k < na; k++) {
        const double *Sk = m->S + (size_t)k * nb;
        double sqd = 0.0, sq = 0.0;
        for (int j = 0; j < nb; j++) {
            sqd += Sk[j] * qd[j];
            sq += Sk[j] * q[j];
        }
        h += p[k] * sqd - sq * pd[k];
        dJ += (2.0 * m->mta[k] + m->Maa[k] * p[k]) * p[k];
        tp += m->Maa[k] * pd[k] * pd[k];
        vp += m->Ka[k] * p[k] * p[k];
    }
    *T += 0.5 * thd * thd * dJ + thd * h + 0.5 * tp;
    *Ve += 0.5 * vp;
}

/* M's rows and columns of the axial coordinates and the frame angle's (index r of the full coordinates) changes:
 * the p block M_aa, no p-q or p-rigid coupling but the frame angle's -S q, and S^T p added to its q entries. */
void fb_axial_mass(const fb_model *m, const double *q, int r, double *M) {
    int n = m->n, nb = fb_nb(m), o = m->nrigid, N = o + n;
    double u[FB_JOINT_MAXZ];
    double dJ = fb_axial_row(m, q, u);
    for (int k = 0; k < m->na; k++) {
        int a = o + nb + k;
        for (int j = 0; j < N; j++) M[(size_t)a * N + j] = M[(size_t)j * N + a] = 0.0;
        M[(size_t)a * N + a] = m->Maa[k];
    }
    M[(size_t)r * N + r] += dJ;
    for (int j = 0; j < n; j++) {
        M[(size_t)r * N + o + j] += u[j];
        M[(size_t)(o + j) * N + r] += u[j];
    }
}

/* R = M0 M(q, p)^-1 (Q - K0 z) + K0 z over the state's coordinates (the frame angle free, at index ``row``; Q over
 * the full coordinates without the elastic force), M = M0 + U C U^T with U = [e, u], C = [[ds, 1], [1, 0]]:
 * M0 M^-1 x = x - U G^-1 [row0 . x, w . x], w = M0^-1 u = Psi Psi^T u, G = [[inv00, 1 + row0 . u],
 * [1 + row0 . u, u . w - ds]] (Woodbury).  Fills ``up`` for fb_axial_correct; returns 0. */
double fb_axial_remainder(const fb_model *m, const fb_basis *b, int row, const double *q, const double *Q, double ds,
                          fb_update *up, double *R) {
    int nb = fb_nb(m), o = m->nrigid - m->ngiven, nz = b->nz, N = b->N;
    double x[FB_JOINT_MAXZ], kq[FB_JOINT_MAXZ], pad[FB_JOINT_MAXZ], eta[FB_JOINT_MAXZ];
    for (int i = 0; i < N; i++) pad[i] = 0.0;
    for (int i = 0; i < nz; i++) up->u[i] = 0.0;
    fb_axial_row(m, q, up->u + o);
    fb_symv(m->K, q, nb, kq);
    for (int i = 0; i < nz; i++) x[i] = Q[i];
    for (int j = 0; j < nb; j++) x[o + j] -= kq[j];
    for (int k = 0; k < m->na; k++) x[o + nb + k] -= m->Ka[k] * q[nb + k];
    for (int i = 0; i < nz; i++) pad[i] = up->u[i];
    fb_project(b, pad, eta);
    fb_to_physical(b, eta, pad);
    double ru = 0.0, uw = 0.0, rx = 0.0, wx = 0.0;
    for (int i = 0; i < nz; i++) {
        up->w[i] = pad[i];
        ru += b->row0[i] * up->u[i];
        uw += up->u[i] * pad[i];
        rx += b->row0[i] * x[i];
        wx += pad[i] * x[i];
    }
    double g00 = b->inv00, g01 = 1.0 + ru, g11 = uw - ds, det = g00 * g11 - g01 * g01;
    up->G[0][0] = g11 / det;
    up->G[0][1] = up->G[1][0] = -g01 / det;
    up->G[1][1] = g00 / det;
    up->active = up->rank2 = 1;
    up->row = row;
    up->c = 0.0;
    double alpha = up->G[0][0] * rx + up->G[0][1] * wx, beta = up->G[1][0] * rx + up->G[1][1] * wx;
    for (int i = 0; i < nz; i++) R[i] = Q[i] - beta * up->u[i];
    R[row] -= alpha;
    return 0.0;
}

/* x <- M0 M^-1 x for the rank-two update of fb_axial_remainder. */
void fb_axial_correct(const fb_basis *b, const fb_update *up, double *x) {
    double rx = 0.0, wx = 0.0;
    for (int i = 0; i < b->nz; i++) {
        rx += b->row0[i] * x[i];
        wx += up->w[i] * x[i];
    }
    double alpha = up->G[0][0] * rx + up->G[0][1] * wx, beta = up->G[1][0] * rx + up->G[1][1] * wx;
    for (int i = 0; i < b->nz; i++) x[i] -= beta * up->u[i];
    x[up->row] -= alpha;
}
