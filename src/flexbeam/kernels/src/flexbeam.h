/* flexbeam compiled kernels: shared types and declarations.
 *
 * The model (model.c) evaluates the rigid-flexible coupling equations of docs/formulation.md;
 * the integrator (propagation.c, collocation.c, events.c, stepcontrol.c, phase.c) propagates
 * the modal equations exactly and collocates the nonlinear remainder.  module.c and glue*.c are
 * the Python glue (glue.h).  Python packs every array once per system into two flat buffers (layout in
 * flexbeam/kernels/layout.py) which fb_model_unpack / fb_basis_unpack read back as pointers.
 */
#ifndef FLEXBEAM_KERNELS_H
#define FLEXBEAM_KERNELS_H

#include <math.h>
#include <stddef.h>

#include "detmath.h" /* sin, cos, exp, pow with the same bits on every machine */
#include "joint.h"   /* the joint seam: the frame's motion, its mass and forces, the drive */

#define FB_LAYOUT_VERSION 4
#define FB_PI 3.14159265358979323846
#if defined(_MSC_VER)
#define FB_THREAD_LOCAL __declspec(thread)
#else
#define FB_THREAD_LOCAL __thread
#endif
#define FB_MAX_POINTS 64
#define FB_MAX_OBSTACLES 8
#define FB_MAX_PAIRS 8
#define FB_MAX_JOINT_PARAMS 64 /* the joint's given coordinates (accelerations) at most */
#define FB_MAX_JOINT_BUFFER 1000000 /* the joint's parameters in the model buffer (a moving base's table rows) */
#define FB_P 4          /* Gauss-Legendre collocation nodes per step */
#define FB_NPTS (FB_P + 1) /* the nodes and the step end */

/* ContactMode (flexbeam.solution.ContactMode) */
enum { FB_MODE_NONE = 0, FB_MODE_FORCE = 1, FB_MODE_CONSTRAINT = 2 };
enum { FB_SPHERE = 0, FB_PLANE = 1 };

/* A material point of the beam: base = r_h + x, offset c below the centre line (along -n of the deformed
 * section) and offset_t along its tangent (a point on the rounded end cap; 0 elsewhere), Psi(x), Psi'(x), H(x). */
typedef struct {
    double base, offset, offset_t;
    const double *phi, *dphi, *H;
    const double *aphi; /* Phi_a(x), the axial shapes (m->na of them; NULL without axial modes) */
} fb_point;

/* An obstacle: sphere (centre, radius) or half-plane (point, outward unit normal), optionally on a
 * support of mass ms, stiffness ks, damping cs along the unit axis (ux, uy); ms = 0: rigidly held.  On a moving base
 * an obstacle is carried by the base (fixed in the base frame) unless ``ground``. */
typedef struct {
    int kind;
    int ground; /* fixed to the ground, not carried by a moving base: at C - r_O(t) in the base frame */
    double cx, cy, radius, nx, ny;
    double ms, ks, cs, ux, uy;
} fb_obstacle;

/* A contact pair: a material point of the beam (index into points) against an obstacle (index into obstacles).
 * Only obstacle 0 may stand on a compliant support. */
typedef struct {
    int point, obstacle;
    int anywhere; /* the contact point is the beam-surface point nearest the obstacle (nearest.c): 1 on the capsule
                   * (hemispherical end caps), 2 with flat end faces; 0 a fixed material point */
} fb_pair;

typedef struct fb_model_s {
    int n;      /* flexible coordinates [q, p]: n - na bending modes q, then na axial modes p */
    int na;     /* axial modes (0: an inextensible beam) */
    int joint;  /* the joint's kind, FB_JOINT_* (joint.h); its code in joint_<kind>.c */
    int nrigid; /* the floating frame's coordinates, leading the full coordinates [rigid, q] (1: theta) */
    int ngiven; /* of them, those the joint gives as functions of time (not in the state: 1 for theta(t) prescribed) */
    int njp;    /* the joint's parameters jp (joint_<kind>.c reads them) */
    const double *jp; /* into the model buffer */
    double Jc, m1, g;
    const double *Mc, *Mqq, *mtq, *K, *sf, *G, *d; /* the bending modes': nb x nb, nb x nb, nb, nb x nb, nb, nb x nb, nb */
    const double *Maa, *Ka, *mta, *sa, *S;         /* the axial modes' (na > 0): na, na, na, na, na x nb (axial.c) */
    int npoints, nobstacles, npairs, nmeasure; /* nmeasure: measuring points, points[2 .. 2 + nmeasure) */
    fb_point points[FB_MAX_POINTS];       /* points[0]: the first pair's contact point P, points[1]: the tip */
    fb_obstacle obstacles[FB_MAX_OBSTACLES];
    fb_pair pairs[FB_MAX_PAIRS];
    /* stations along the beam for contact anywhere (nst = 0 if no pair needs them): x, Psi, Psi', Psi'' (nst x nb),
     * H (nst x nb x nb), and per mode the largest |Psi_k|, |Psi'_k| over the beam (bounds of the event search); with
     * axial modes Phi_a, Phi_a' (nst x na) and the largest |Phi_a,k| (NULL without) */
    double hub_radius; /* r_h: a point's material x is its base - r_h */
    int nst;
    double surface;  /* c: the beam's surface from its centre line (the capsule's radius) */
    int first_order; /* the coupling deformation u_x = -1/2 q^T H q is kept */
    const double *st_x, *st_phi, *st_dphi, *st_ddphi, *st_H, *st_maxphi, *st_maxdphi;
    const double *st_aphi, *st_daphi, *st_maxaphi;
    const double *Cd; /* the structural damping of the flexible coordinates, n x n (NULL: undamped) */
    unsigned long long uid; /* this unpacking's number in its thread (fb_model_unpack; from 1): keys the contact
                             * search's kept references (nearest_scan.c) to the buffers unpacked */
} fb_model;

/* How the contacts act during a phase, pair by pair: FB_MODE_NONE (free), FB_MODE_FORCE (the law
 * p = [K, n, chi/d'_0, C]: F = max(0, K d^n (1 + chi' d') + C d')) or FB_MODE_CONSTRAINT (held closed by a
 * multiplier; Baumgarte's alpha, beta in the reference integrator, the decay rate alpha in the collocation). */
typedef struct {
    int npairs;
    int mode[FB_MAX_PAIRS];
    double p[FB_MAX_PAIRS][4];
    double alpha, beta;
    /* Coulomb friction of a FORCE pair (friction.c): slip[k] = sigma_k, the tangential force sigma_k F_k along the
     * tangent t = (-n_y, n_x) of a slipping pair (sigma = -mu_k sdir[k]; 0: none); sdir[k] = sign(v_t) of a slipping
     * pair (0: none), watched for its stop whatever mu_k (a pair with mu_k = 0 < mu_s sticks where it stops);
     * stick[k]: the pair is held tangentially by a multiplier lambda_t (|lambda_t| <= mus[k] (F_k + the forces of
     * its followers), mus the static coefficient); follow[k] >= 0: the pair sticks along with pair follow[k], its tangential row dependent on that
     * pair's (two points of a rigid bar on two stops), which holds for both (-1: none).  regv[k] > 0: the pair's
     * friction is Threlfall's regularised law sigma(v_t) = -regmu[k] (1 - exp(-3 |v_t| / regv[k])) sign(v_t). */
    int friction; /* some pair slips, sticks or is under the regularised law */
    double slip[FB_MAX_PAIRS], mus[FB_MAX_PAIRS], regmu[FB_MAX_PAIRS], regv[FB_MAX_PAIRS];
    double vrest[FB_MAX_PAIRS]; /* a slip that starts from a stick: the stick's residual slip speed it may run back */
    double sdir[FB_MAX_PAIRS]; /* the slip's direction sign(v_t) (+-1; 0: not slipping) */
    int stick[FB_MAX_PAIRS], follow[FB_MAX_PAIRS];
} fb_contacts;

/* Does pair k carry Coulomb friction in these contacts (it slips, sticks, or is under the regularised law)? */
static inline int fb_rough(const fb_contacts *c, int k) {
    return c->friction && (c->sdir[k] != 0.0 || c->stick[k] || c->regv[k] > 0.0);
}

/* Does pair k carry a tangential unknown at the collocation nodes (nodal.c): a sticking pair's multiplier, or the
 * regularised law's tangential force, solved with the normal forces by Newton's method? */
static inline int fb_tangential_unknown(const fb_contacts *c, int k) {
    return c->friction && c->mode[k] != FB_MODE_NONE && (c->stick[k] || c->regv[k] > 0.0);
}

/* The tangential force per unit normal force of pair k slipping at v_t, and its derivative in v_t (friction.c). */
double fb_slip_coefficient(const fb_contacts *c, int k, double vt);
double fb_slip_slope(const fb_contacts *c, int k, double vt);


/* Contacts buffer (flexbeam.kernels.layout.pack_contacts): [npairs, alpha, beta, (mode, p0, p1, p2, p3) per pair],
 * with friction [npairs, alpha, beta, (mode, p0, p1, p2, p3, sigma, stick, mu_s, v_rest, sign(v_t)) per pair]. */
int fb_contacts_unpack(fb_contacts *c, const fb_model *m, const double *buf, size_t nbuf);

/* The bending modes' count (the flexible coordinates without the axial ones). */
static inline int fb_nb(const fb_model *m) { return m->n - m->na; }
/* Number of full coordinates [rigid, q] (the equations' rows) and of the state's coordinates (without the given
 * ones): [theta, q] or q. */
static inline int fb_nfull(const fb_model *m) { return m->nrigid + m->n; }
static inline int fb_nz(const fb_model *m) { return m->nrigid - m->ngiven + m->n; }
/* Is obstacle 0 on a compliant support (two more states s, s')? */
static inline int fb_compliant(const fb_model *m) { return m->nobstacles > 0 && m->obstacles[0].ms > 0.0; }
/* Length of the reference-layout state [z, z', (s, s'), E_d, W]. */
static inline int fb_state_size(const fb_model *m) { return 2 * fb_nz(m) + (fb_compliant(m) ? 2 : 0) + 2; }

int fb_model_unpack(fb_model *m, const double *buf, size_t nbuf);

/* ------------------------------------------------------------------ model.c */
typedef struct fb_kin_s {
    double r[2], v[2], a0[2];
    double rel[2]; /* r - R, the point's position from the frame's origin (A(theta) rho), formed before R is added:
                    * what is measured in the beam's frame keeps its digits however far R is from the origin */
    int want_acc; /* in: compute a0 (its q'^T H q' costs an n x n product; the gap and its rate do not need it) */
} fb_kin;

typedef struct {
    double delta, rate, gamma, nx, ny, Js;
    double tgamma; /* the slip velocity's rate at z'' = 0 (fb_pair_tangent with want_acc; else 0) */
    double speed; /* |r' - s' u|: P's speed relative to the obstacle */
    double x;     /* the contact point's material coordinate (fb_pair_gap) */
} fb_gap;

/* The slip velocity t . (v - the obstacle's velocity) of a point with kinematics k and gap state g (its normal), the
 * tangent t = (-n_y, n_x), obstacle o moving at sd along its support axis (fixed to the ground: plus v_O). */
static inline double fb_slip_velocity(const fb_obstacle *o, const fb_frame *f, const fb_kin *k, const fb_gap *g,
                                      double sd, double *vx, double *vy) {
    *vx = k->v[0] - sd * o->ux, *vy = k->v[1] - sd * o->uy;
    if (o->ground) *vx += f->vO[0], *vy += f->vO[1];
    return -g->ny * *vx + g->nx * *vy;
}

/* The frame and the modal coordinates of a reference-layout state y = [z, z', ...] at time t. */
void fb_state_split(const fb_model *m, double t, const double *y, fb_frame *f, const double **q, const double **qd);
/* A moving base (base_motion.c) */
int fb_base_unpack(const fb_model *m);
int fb_base_moving(const fb_model *m);
void fb_base_motion(const fb_model *m, double t, double *r, double *v, double *a, double *j);
double fb_base_speed_bound(const fb_model *m, double t0, double t1);
double fb_base_next_knot(const fb_model *m, double t, double tol);
double fb_base_power(const fb_model *m, double t, const fb_frame *f, const double *q, const double *qd, double sud);
double fb_base_work_rate(const fb_model *m, double t, const fb_frame *f, const double *q, double su);
double fb_base_boundary(const fb_model *m, double t, const fb_frame *f, const double *q, double su);
/* The inertial force -m_s a_O . u on a support's mass carried by a moving base (0 otherwise). */
double fb_support_base_force(const fb_model *m, const fb_frame *f);
double fb_quad(const double *A, const double *x, int n);
void fb_symv(const double *A, const double *x, int n, double *out);
void fb_matvec(const double *A, const double *x, int n, double *out);
double fb_dot(const double *a, const double *b, int n);
void fb_point_kinematics(const fb_model *m, const fb_point *P, const fb_frame *f, const double *q, const double *qd,
                         fb_kin *out, double *dr);
fb_gap fb_gap_state(const fb_obstacle *o, const fb_frame *f, const fb_kin *k, const double *dr, int nz, double s,
                    double sd, double *J);
double fb_ground_rate(const fb_model *m, const fb_frame *f, const int *mode, const double *F, const fb_gap *g);
fb_gap fb_pair_gap(const fb_model *m, int pair, const fb_frame *f, const double *q, const double *qd, double s,
                   double sd, int want_acc, double *J);
fb_gap fb_pair_tangent(const fb_model *m, int pair, const fb_frame *f, const double *q, const double *qd, double s,
                       double sd, int want_acc, double *J, double *Jt, double *vt);
/* impulse_map.c: one frictionless pair's impulse-momentum map (e its restitution): y_plus, out = [P, v-, v+, T-, T+];
 * 1 where the Python map must take it (given coordinates, a compliant support, an obstacle on the ground), -1 singular */
int fb_normal_jump(const fb_model *m, int pair, double t, const double *y, double e, double *y_plus, double *out);

/* ------------------------------------------------------------------ axial.c (the axial modes, na > 0) */
double fb_axial_row(const fb_model *m, const double *q, double *u);
double fb_axial_forces(const fb_model *m, double thd, const double *q, const double *qd, int elastic, double *Qf);
void fb_axial_energies(const fb_model *m, double thd, const double *q, const double *qd, double *T, double *Ve);
void fb_axial_mass(const fb_model *m, const double *q, int r, double *M);
double fb_axial_remainder(const fb_model *m, const struct fb_basis_s *b, int row, const double *q, const double *Q,
                          double ds, fb_update *up, double *R);
void fb_axial_correct(const struct fb_basis_s *b, const fb_update *up, double *x);

/* ------------------------------------------------------------------ nearest.c (contact anywhere) */
/* A point of the beam's surface built on the fly: its fb_point and the arrays it points to. */
typedef struct {
    fb_point P;
    double x; /* its material coordinate */
    double phi[64], dphi[64], H[64 * 64], aphi[64];
} fb_surface_point;

void fb_nearest_point(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, double s,
                      int flat, fb_surface_point *out);
void fb_centre_point(const fb_model *m, double x, fb_surface_point *out);
double fb_nearest_rate(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, const double *qd,
                       double s, double sd, double x, int end, double *doff);
double fb_anywhere_gamma(const fb_model *m, const fb_obstacle *o, const fb_frame *f, const double *q, const double *qd,
                         double s, double sd, int flat, double x, double gamma, const double *offsets, double *tgamma);
void fb_anywhere_bound(const fb_model *m, const double *q, double *env);
void fb_nearest_warm(int on); /* nearest_scan.c: the plane's warm scan on (default) or off (every scan full) */
long fb_nearest_full_scans(void); /* nearest_scan.c: the plane's full scans so far in the calling thread */
double fb_law_force(const double *p, double d, double dd, double *fk, double *dF_dd, double *dF_ddd);
double fb_law_potential(const double *p, double d);
int fb_solve(double *A, double *b, int n);
int fb_rhs(const fb_model *m, double t, const double *y, const fb_contacts *c, double *dy, double *F,
           double *torque);
int fb_contact_forces(const fb_model *m, double t, const double *y, const fb_contacts *c, double *F, double *Ft);
/* The output column tip_deflection: the tip's distance from the hub's radial line, measured from the frame's origin
 * (fb_tip_deflection_at: with the hub angle's sine and cosine already known). */
double fb_tip_deflection(const fb_model *m, const fb_frame *f, const double *q, const double *qd);
double fb_tip_deflection_at(const fb_model *m, const fb_frame *f, const double *q, const double *qd, double sphi,
                            double cphi);
void fb_outputs(const fb_model *m, const double *T, const double *Y, int count, const fb_contacts *c, double *cols,
                double *mv, double *pcols);

#define FB_NCOLS 15 /* columns of fb_outputs, in the order of flexbeam.kernels.OUTPUT_COLUMNS */
#define FB_COL_TIP 12 /* the column tip_deflection */
#define FB_PAIR_COLS 4 /* per pair: gap, its rate, the contact force, the contact point's x (kernels.PAIR_COLUMNS) */

/* ------------------------------------------------------------------ modal basis (propagation.c) */
/* The linearisation about the undeformed beam at rest, M0 z'' + K0 z = R, in modal coordinates
 * z = Psi eta (Psi^T M0 Psi = I, Psi^T K0 Psi = diag(omega^2)); a compliant support adds the mode
 * sqrt(m_s) s of frequency sqrt(k_s / m_s) as the last one. */
typedef struct fb_basis_s {
    int N;            /* modal coordinates (beam + support) */
    int nz;           /* beam coordinates */
    int diagonal;     /* Psi is diagonal (system frame, prescribed theta) */
    double inv00;     /* (M0^-1)_00 (free joint) */
    const double *omega, *Psi, *toM, *row0, *K0;  /* N, N x N, N x N, nz, nz x nz */
    const double *damp; /* N: each mode's damping coefficient d = 2 zeta w (NULL: undamped) */
} fb_basis;

int fb_basis_unpack(fb_basis *b, const double *buf, size_t nbuf);
void fb_to_physical(const fb_basis *b, const double *eta, double *z);
void fb_project(const fb_basis *b, const double *x, double *out); /* out = Psi^T x */
void fb_project_abs(const fb_basis *b, const double *x, double *out); /* out = |Psi|^T x */

/* A collocation's node set on [0, 1] for FB_P nodes -- Gauss-Legendre (fb_gauss, every phase but a resting
 * contact's) or Radau IIA (fb_radau, a resting contact's: propagation.c) -- its nodes c, weights w, the Vandermonde
 * inverse (monomial coefficients from nodal values), the projection on the top Legendre polynomial (the
 * multiplier's error), the Lagrange basis polynomials' values at the step end, and a bound on their Lebesgue
 * function (the largest factor from nodal values to the interpolant's on [0, 1]: events.c). */
typedef struct {
    double c[FB_P], w[FB_P], Vinv[FB_P][FB_P], top[FB_P], lend[FB_P];
    double lebesgue; /* > max over [0, 1] of sum_j |l_j(s)|: 3 for Gauss's (2.856), 3.5 for Radau's (3.447) */
} fb_tables;

const fb_tables *fb_gauss(void);
const fb_tables *fb_radau(void);

/* Propagation weights of one mode for the fraction s of a step h: free response and the response to
 * each nodal forcing value (see propagation.c). */
typedef struct {
    double C, SW, WS;          /* cos(w T), sin(w T) / w, w sin(w T), T = s h (damped.c: eta from eta0, v0; -v from eta0) */
    double CV;                 /* v from v0: cos(w T) undamped */
    double RE[FB_P], RV[FB_P]; /* position and velocity response to nodal forcing values */
} fb_weight;

void fb_weights(const fb_tables *tb, double w, double h, double s, fb_weight *out);
void fb_weight_nodes(const fb_tables *tb, double T, double s, const double *Sm, const double *Cm, fb_weight *out);
void fb_moments(double th, double *Cm, double *Sm);

/* A hop of length T: free response and the responses to the monomials u^m of u in [0, 1]. */
typedef struct {
    double C, SW, WS, CV, pe[FB_P], pv[FB_P];
} fb_hop;

void fb_hop_weights(double w, double T, fb_hop *out);
/* The damped modes (damped.c): d = 2 zeta w, the basis's damp */
void fb_weights_damped(const fb_tables *tb, double w, double d, double h, double s, fb_weight *out);
void fb_hop_weights_damped(double w, double d, double T, fb_hop *out);
void fb_mode_weights(const fb_tables *tb, const fb_basis *b, int k, double h, double s, fb_weight *out);
void fb_mode_hop(const fb_basis *b, int k, double T, fb_hop *out);
double fb_damping_force(const fb_model *m, const double *qd, double *Q, int off);
void fb_damping_return(const fb_basis *b, const double *v, double *R);
double fb_mode_dissipation(double w, double d, double h, const double *a, double e0, double v0, double e1, double v1);
void fb_monomial(const fb_tables *tb, const double *f, int N, double *A);
void fb_propagate(const fb_basis *b, const fb_weight *W, int stride, const double *eta0, const double *v0,
                  const double *f, double *eta, double *v);
double fb_lagrange_integral(const fb_tables *tb, int j, double s);
double fb_lagrange(const fb_tables *tb, int j, double s);

#endif
