/* The beam's part of the rigid-flexible coupling equations of docs/formulation.md, in physical coordinates: the model
 * buffer, a material point's kinematics in the floating frame, the gap of a contact pair and the contact laws.  The
 * frame's part -- its coordinates, its mass and forces, the drive, how the frame moves in the plane -- is the joint's
 * (joint.h; joint_revolute.c writes out the equations of a beam on a revolute joint).
 *
 * A material point at x, offset c below the centre line along the deformed section normal and c_t along its
 * tangent (section rotation a = Psi'(x) q), sits in the frame at
 *   rho = (r_h + x - 1/2 q^T H q + c sin a + c_t cos a + Phi_a p, Psi q - c cos a + c_t sin a),
 * Phi_a p the axial modes' stretch (model.axial_modes; the flexible coordinates are [q, p]).
 */
#include <string.h>

#include "flexbeam.h"

#define MAXZ 66 /* n <= 64 modes, theta, and a support coordinate */

/* Model buffer: [version, n (flexible coordinates), joint kind, njp, na (axial modes), npoints, nobstacles, npairs,
 * nmeasure, obstacle kinds (nobstacles),
 * Jc, m1, g, the joint's parameters (njp), Mc, Mqq, mtq, K, sf, G, d (the nb = n - na bending modes'), with na > 0:
 * Maa, Ka, mta, sa (na each), S (na x nb),
 * per point: base, offset, phi, dphi, H (nb), Phi_a (na); per obstacle: cx, cy, radius, nx, ny, ms, ks, cs, ux, uy,
 * ground;
 * per pair: point, obstacle, anywhere; hub_radius, nst, surface, first_order, then with nst > 0: x (nst), Psi, Psi', Psi'' (nst x n each),
 * H (nst x n x n), max |Psi| (n), max |Psi'| (n), with na > 0 Phi_a, Phi_a' (nst x na each), max |Phi_a| (na)]
 * (flexbeam.kernels.layout.pack_model writes it). */
int fb_model_unpack(fb_model *m, const double *buf, size_t nbuf) {
    static FB_THREAD_LOCAL unsigned long long unpacked;
    m->uid = ++unpacked;
    const double *ints = buf;
    size_t nints = 9;
    if (nbuf < nints || (int)ints[0] != FB_LAYOUT_VERSION) return -1;
    int n = (int)ints[1], na = (int)ints[4], nb = n - na;
    m->n = n;
    m->na = na;
    m->joint = (int)ints[2];
    m->njp = (int)ints[3];
    m->npoints = (int)ints[5];
    m->nobstacles = (int)ints[6];
    m->npairs = (int)ints[7];
    m->nmeasure = (int)ints[8];
    if (n < 0 || n > 64 || na < 0 || na > n || m->npoints < 1 || m->npoints > FB_MAX_POINTS || m->nobstacles < 0 ||
        m->nobstacles > FB_MAX_OBSTACLES || m->npairs < 0 || m->npairs > FB_MAX_PAIRS || m->nmeasure < 0 ||
        m->nmeasure > m->npoints - 2 || m->joint < 0 || m->joint >= FB_JOINT_KINDS || m->njp < 0 ||
        m->njp > FB_MAX_JOINT_BUFFER ||
        nbuf < nints + (size_t)m->nobstacles)
        return -1;
    nints += (size_t)m->nobstacles;
    const double *f = buf + nints;
    size_t nf = nbuf - nints;
    size_t need = 3 + (size_t)m->njp + 4 * (size_t)nb * nb + 3 * (size_t)nb + (size_t)na * (4 + (size_t)nb) +
                  (size_t)m->npoints * (2 + 2 * nb + (size_t)nb * nb + (size_t)na) + 11 * (size_t)m->nobstacles +
                  3 * (size_t)m->npairs + 4;
    if (nf < need) return -2;
    const double *p = f;
    m->Jc = *p++;
    m->m1 = *p++;
    m->g = *p++;
    m->jp = p; p += m->njp;
    m->Mc = p; p += nb * nb;
    m->Mqq = p; p += nb * nb;
    m->mtq = p; p += nb;
    m->K = p; p += nb * nb;
    m->sf = p; p += nb;
    m->G = p; p += nb * nb;
    m->d = p; p += nb;
    m->Maa = p; p += na;
    m->Ka = p; p += na;
    m->mta = p; p += na;
    m->sa = p; p += na;
    m->S = p; p += na * nb;
    for (int i = 0; i < m->npoints; i++) {
        fb_point *P = &m->points[i];
        P->base = *p++;
        P->offset = *p++;
        P->offset_t = 0.0;
        P->phi = p; p += nb;
        P->dphi = p; p += nb;
        P->H = p; p += nb * nb;
        P->aphi = na ? p : NULL; p += na;
    }
    for (int i = 0; i < m->nobstacles; i++) {
        fb_obstacle *o = &m->obstacles[i];
        o->kind = (int)ints[9 + i];
        o->cx = *p++; o->cy = *p++; o->radius = *p++; o->nx = *p++; o->ny = *p++;
        o->ms = *p++; o->ks = *p++; o->cs = *p++; o->ux = *p++; o->uy = *p++;
        o->ground = *p++ != 0.0;
        if (i > 0 && o->ms > 0.0) return -3; /* only obstacle 0 may stand on a support */
    }
    for (int k = 0; k < m->npairs; k++) {
        m->pairs[k].point = (int)*p++;
        m->pairs[k].obstacle = (int)*p++;
        m->pairs[k].anywhere = (int)*p++;
        if (m->pairs[k].point < 0 || m->pairs[k].point >= m->npoints || m->pairs[k].obstacle < 0 ||
            m->pairs[k].obstacle >= m->nobstacles)
            return -3;
    }
    m->hub_radius = *p++;
    m->nst = (int)*p++;
    m->surface = *p++;
    m->first_order = (int)*p++;
    size_t M = (size_t)m->nst;
    size_t axial_st = M ? 2 * M * (size_t)na + (size_t)na : 0; /* Phi_a, Phi_a' (M x na), max |Phi_a| (na) */
    size_t full = need + M * (1 + 3 * (size_t)nb + (size_t)nb * nb) + (M ? 2 * (size_t)nb : 0) + axial_st;
    if (nf != full && nf != full + (size_t)n * n) return -2; /* + the damping matrix C (n x n) when damped */
    for (int k = 0; k < m->npairs; k++)
        if (m->pairs[k].anywhere && M < 2) return -3;
    m->st_x = p; p += M;
    m->st_phi = p; p += M * nb;
    m->st_dphi = p; p += M * nb;
    m->st_ddphi = p; p += M * nb;
    m->st_H = p; p += M * nb * nb;
    m->st_maxphi = p; p += M ? nb : 0;
    m->st_maxdphi = p; p += M ? nb : 0;
    m->st_aphi = m->st_daphi = m->st_maxaphi = NULL;
    if (M && na) {
        m->st_aphi = p; p += M * na;
        m->st_daphi = p; p += M * na;
        m->st_maxaphi = p;
        p += na;
    }
    m->Cd = nf == full + (size_t)n * n ? p : NULL;
    return fb_joint(m)->unpack(m) ? -4 : 0;
}

/* The frame and the modal coordinates of a reference-layout state [z, z', ...] (z: the state's nz coordinates). */
void fb_state_split(const fb_model *m, double t, const double *y, fb_frame *f, const double **q, const double **qd) {
    fb_joint(m)->split(m, t, y, y + fb_nz(m), f, q, qd);
}

/* out = A x for a symmetric A, by column sweeps: out_i accumulates A_ji x_j over j in order, from 0.0 (the row-by-row
 * dot product's order, bit for bit, whatever the vectorisation).  The outputs are taken in blocks of 8 (then 4, then
 * one) whose partial sums stay in registers over the whole sweep: the same sums in the same order, without storing
 * and reloading out at every column (issue 25: this is the kernel's hottest loop, the point kinematics' q^T H q,
 * the coupling's Mc q and G q). */
void fb_symv(const double *A, const double *x, int n, double *out) {
    int i0 = 0;
    for (; i0 + 8 <= n; i0 += 8) {
        double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0, a4 = 0.0, a5 = 0.0, a6 = 0.0, a7 = 0.0;
        for (int j = 0; j < n; j++) {
            const double xj = x[j], *Aj = A + (size_t)j * n + i0;
            a0 += Aj[0] * xj;
            a1 += Aj[1] * xj;
            a2 += Aj[2] * xj;
            a3 += Aj[3] * xj;
            a4 += Aj[4] * xj;
            a5 += Aj[5] * xj;
            a6 += Aj[6] * xj;
            a7 += Aj[7] * xj;
        }
        out[i0] = a0, out[i0 + 1] = a1, out[i0 + 2] = a2, out[i0 + 3] = a3;
        out[i0 + 4] = a4, out[i0 + 5] = a5, out[i0 + 6] = a6, out[i0 + 7] = a7;
    }
    for (; i0 + 4 <= n; i0 += 4) {
        double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
        for (int j = 0; j < n; j++) {
            const double xj = x[j], *Aj = A + (size_t)j * n + i0;
            a0 += Aj[0] * xj;
            a1 += Aj[1] * xj;
            a2 += Aj[2] * xj;
            a3 += Aj[3] * xj;
        }
        out[i0] = a0, out[i0 + 1] = a1, out[i0 + 2] = a2, out[i0 + 3] = a3;
    }
    for (; i0 < n; i0++) {
        double a = 0.0;
        for (int j = 0; j < n; j++) a += A[(size_t)j * n + i0] * x[j];
        out[i0] = a;
    }
}

double fb_quad(const double *A, const double *x, int n) {
    double Ax[MAXZ], acc = 0.0;
    fb_symv(A, x, n, Ax);
    for (int i = 0; i < n; i++) acc += x[i] * Ax[i];
    return acc;
}

void fb_matvec(const double *A, const double *x, int n, double *out) {
    for (int i = 0; i < n; i++) {
        double row = 0.0;
        for (int j = 0; j < n; j++) row += A[i * n + j] * x[j];
        out[i] = row;
    }
}

double fb_dot(const double *a, const double *b, int n) {
    double acc = 0.0;
    for (int i = 0; i < n; i++) acc += a[i] * b[i];
    return acc;
}

/* Position r, velocity v and the acceleration a0 at z'' = 0 (velocity-product terms, for J' z') of a point,
 * and dr (2 x nfull, row-major): dr/dz with z = [rigid, q]: the point's motion in the frame, placed by the joint. */
void fb_point_kinematics(const fb_model *m, const fb_point *P, const fb_frame *f, const double *q, const double *qd,
                         fb_kin *out, double *dr) {
    int n = m->n, nb = fb_nb(m);
    double ang = fb_dot(P->dphi, q, nb), angd = fb_dot(P->dphi, qd, nb);
    double sa, ca, c = P->offset, ot = P->offset_t;
    fb_sincos(ang, &sa, &ca);
    double qHq = 0.0, rhod_x = 0.0, rhod_y = 0.0, qdHqd = 0.0, hq[MAXZ], hqd[MAXZ], drho[2 * MAXZ];
    fb_symv(P->H, q, nb, hq);
    if (out->want_acc) {
        fb_symv(P->H, qd, nb, hqd);
        for (int i = 0; i < nb; i++) qdHqd += qd[i] * hqd[i];
    }
    for (int i = 0; i < nb; i++) {
        qHq += q[i] * hq[i];
        double dx = -hq[i] + (c * ca - ot * sa) * P->dphi[i];
        double dy = P->phi[i] + (c * sa + ot * ca) * P->dphi[i];
        rhod_x += dx * qd[i];
        rhod_y += dy * qd[i];
        drho[i] = dx;
        drho[n + i] = dy;
    }
    double stretch = 0.0; /* the axial modes' Phi_a(x) p along the frame's e1 (linear: no velocity product) */
    for (int k = 0; k < m->na; k++) {
        stretch += P->aphi[k] * q[nb + k];
        rhod_x += P->aphi[k] * qd[nb + k];
        drho[nb + k] = P->aphi[k];
        drho[n + nb + k] = 0.0;
    }
    fb_body_kin bk;
    bk.rho[0] = P->base - 0.5 * qHq + c * sa + ot * ca;
    if (m->na) bk.rho[0] += stretch;
    bk.rho[1] = fb_dot(P->phi, q, nb) - c * ca + ot * sa;
    bk.rhod[0] = rhod_x;
    bk.rhod[1] = rhod_y;
    bk.acc[0] = -qdHqd - (c * sa + ot * ca) * angd * angd;
    bk.acc[1] = (c * ca - ot * sa) * angd * angd;
    fb_joint(m)->place(m, f, &bk, drho, out, dr);
}

/* Gap delta to obstacle o displaced by s along its support axis, its rate, gamma = delta'' at z'' = 0,
 * the normal and J = d delta / dz (nz entries: the full coordinates, from dr) and Js = d delta / ds.
 * Sphere: delta = |r - c| - r_s, delta'' = n.r'' + (|r'|^2 - (n.r')^2) / |r - c|; half-plane: delta = n.(r - c).
 * An obstacle fixed to the ground (o->ground, on a moving base) sits at C - r_O(t) in the base frame f: the point's
 * motion relative to it gains r_O, v_O and a_O (a time-explicit term of gamma; /work/research/moving_base.md, 4). */
fb_gap fb_gap_state(const fb_obstacle *o, const fb_frame *f, const fb_kin *k, const double *dr, int nz, double s,
                    double sd, double *J) {
    fb_gap out;
    double cx = o->cx + s * o->ux, cy = o->cy + s * o->uy;
    double vx = k->v[0] - sd * o->ux, vy = k->v[1] - sd * o->uy, ax = k->a0[0], ay = k->a0[1];
    if (o->ground && f) {
        cx -= f->rO[0], cy -= f->rO[1];
        vx += f->vO[0], vy += f->vO[1];
        ax += f->aO[0], ay += f->aO[1];
    }
    if (o->kind == FB_SPHERE) {
        double dx = k->r[0] - cx, dy = k->r[1] - cy;
        double dist = sqrt(dx * dx + dy * dy);
        out.nx = dx / dist;
        out.ny = dy / dist;
        out.delta = dist - o->radius;
        out.rate = out.nx * vx + out.ny * vy;
        out.gamma = out.nx * ax + out.ny * ay + (vx * vx + vy * vy - out.rate * out.rate) / dist;
    } else {
        out.nx = o->nx;
        out.ny = o->ny;
        out.delta = o->nx * (k->r[0] - cx) + o->ny * (k->r[1] - cy);
        out.rate = o->nx * vx + o->ny * vy;
        out.gamma = o->nx * ax + o->ny * ay;
    }
    out.Js = o->ms > 0.0 ? -(out.nx * o->ux + out.ny * o->uy) : 0.0;
    out.tgamma = 0.0;
    out.speed = sqrt(vx * vx + vy * vy);
    if (J && dr)
        for (int i = 0; i < nz; i++) J[i] = out.nx * dr[i] + out.ny * dr[nz + i];
    return out;
}

/* The gap state of contact pair ``pair`` with the frame f and (q, q'), the support at (s, s') (used only if the
 * pair's obstacle is the compliant obstacle 0), and J = d delta / d[rigid, q] (nfull entries; NULL: not wanted). */
/* The kinematics of pair pr's contact point (the surface point nearest the obstacle now for an anywhere pair, as a
 * material point: envelope theorem, its offsets from the centre line in ``offsets`` if not NULL) into k and dr;
 * returns its material coordinate. */
static double pair_point(const fb_model *m, const fb_pair *pr, const fb_obstacle *o, const fb_frame *f,
                         const double *q, const double *qd, double s, fb_kin *k, double *dr, double *offsets) {
    if (pr->anywhere) {
        fb_surface_point sp;
        fb_nearest_point(m, o, f, q, s, pr->anywhere == 2, &sp);
        fb_point_kinematics(m, &sp.P, f, q, qd, k, dr);
        if (offsets) offsets[0] = sp.P.offset, offsets[1] = sp.P.offset_t;
        return sp.x;
    }
    const fb_point *P = &m->points[pr->point];
    fb_point_kinematics(m, P, f, q, qd, k, dr);
    return P->base - m->hub_radius;
}

fb_gap fb_pair_gap(const fb_model *m, int pair, const fb_frame *f, const double *q, const double *qd, double s,
                   double sd, int want_acc, double *J) {
    const fb_pair *pr = &m->pairs[pair];
    const fb_obstacle *o = &m->obstacles[pr->obstacle];
    double dr[2 * MAXZ];
    fb_kin k = {.want_acc = want_acc};
    if (o->ms <= 0.0) s = sd = 0.0;
    double x = pair_point(m, pr, o, f, q, qd, s, &k, J ? dr : NULL, NULL);
    fb_gap g = fb_gap_state(o, f, &k, J ? dr : NULL, fb_nfull(m), s, sd, J);
    g.x = x;
    if (pr->anywhere && want_acc)
        g.gamma = fb_anywhere_gamma(m, o, f, q, qd, s, sd, pr->anywhere == 2, x, g.gamma, NULL, NULL);
    return g;
}

/* fb_pair_gap with J, and along the contact's tangent t = (-n_y, n_x) (the normal turned by +90 degrees) the
 * Jacobian Jt = t . dr/dz (nfull entries) and the slip velocity *vt = t . (v - the obstacle's velocity): Coulomb
 * friction's kinematics (flexbeam.methods.friction).  With want_acc, tgamma = v_t' at z'' = 0: the material point's,
 * and for an anywhere pair plus the contact point's motion along the beam (anywhere_gamma.c). */
fb_gap fb_pair_tangent(const fb_model *m, int pair, const fb_frame *f, const double *q, const double *qd, double s,
                       double sd, int want_acc, double *J, double *Jt, double *vt) {
    const fb_pair *pr = &m->pairs[pair];
    const fb_obstacle *o = &m->obstacles[pr->obstacle];
    double dr[2 * MAXZ];
    fb_kin k = {.want_acc = want_acc};
    if (o->ms <= 0.0) s = sd = 0.0;
    int N = fb_nfull(m);
    double offsets[2];
    double x = pair_point(m, pr, o, f, q, qd, s, &k, dr, offsets);
    fb_gap g = fb_gap_state(o, f, &k, dr, N, s, sd, J);
    g.x = x;
    double tx = -g.ny, ty = g.nx, vx, vy; /* relative to the obstacle (fixed to the ground: fb_gap_state) */
    for (int i = 0; i < N; i++) Jt[i] = tx * dr[i] + ty * dr[N + i];
    *vt = fb_slip_velocity(o, f, &k, &g, sd, &vx, &vy);
    if (want_acc) { /* v_t' at z'' = 0: t . a0 (+ a_O), and on a sphere t' . v, t' = (-n_y', n_x'),
                     * n' = (v - v_n n) / |r - c| */
        double ax = k.a0[0], ay = k.a0[1];
        if (o->ground) ax += f->aO[0], ay += f->aO[1];
        g.tgamma = tx * ax + ty * ay;
        if (o->kind == FB_SPHERE) {
            double dist = g.delta + o->radius, nxd = (vx - g.rate * g.nx) / dist, nyd = (vy - g.rate * g.ny) / dist;
            g.tgamma += -nyd * vx + nxd * vy;
        }
    }
    if (pr->anywhere && want_acc)
        g.gamma = fb_anywhere_gamma(m, o, f, q, qd, s, sd, pr->anywhere == 2, x, g.gamma, offsets, &g.tgamma);
    return g;
}

/* Contact law F = max(0, K d^n (1 + chi' d') + C d') with p = [K, n, chi / d'_0, C]; d = -delta >= 0.
 * Returns F, its elastic part K d^n in *fk and the partial derivatives dF/dd, dF/dd'. */
double fb_law_force(const double *p, double d, double dd, double *fk, double *dF_dd, double *dF_ddd) {
    if (dF_dd) *dF_dd = 0.0;
    if (dF_ddd) *dF_ddd = 0.0;
    if (d <= 0.0) {
        if (fk) *fk = 0.0;
        return 0.0;
    }
    double kdn = p[0] * fb_pow(d, p[1]);
    if (fk) *fk = kdn;
    double F = kdn * (1.0 + p[2] * dd) + p[3] * dd;
    if (F <= 0.0) return 0.0;
    if (dF_dd) *dF_dd = p[1] * kdn / d * (1.0 + p[2] * dd);
    if (dF_ddd) *dF_ddd = kdn * p[2] + p[3];
    return F;
}

double fb_law_potential(const double *p, double d) {
    if (d <= 0.0) return 0.0;
    return p[0] * fb_pow(d, p[1] + 1.0) / (p[1] + 1.0);
}

/* Solve A x = b in place (b <- x) by Gaussian elimination with partial pivoting; A (n x n) is destroyed. */
int fb_solve(double *A, double *b, int n) {
    for (int k = 0; k < n; k++) {
        int piv = k;
        double best = fabs(A[k * n + k]);
        for (int i = k + 1; i < n; i++)
            if (fabs(A[i * n + k]) > best) {
                best = fabs(A[i * n + k]);
                piv = i;
            }
        if (!(best > 0.0)) return -1;
        if (piv != k) {
            for (int j = 0; j < n; j++) {
                double t = A[k * n + j];
                A[k * n + j] = A[piv * n + j];
                A[piv * n + j] = t;
            }
            double t = b[k];
            b[k] = b[piv];
            b[piv] = t;
        }
        double inv = 1.0 / A[k * n + k];
        for (int i = k + 1; i < n; i++) {
            double f = A[i * n + k] * inv;
            if (f == 0.0) continue;
            for (int j = k + 1; j < n; j++) A[i * n + j] -= f * A[k * n + j];
            b[i] -= f * b[k];
        }
    }
    for (int k = n - 1; k >= 0; k--) {
        double acc = b[k];
        for (int j = k + 1; j < n; j++) acc -= A[k * n + j] * b[j];
        b[k] = acc / A[k * n + k];
    }
    return 0;
}

