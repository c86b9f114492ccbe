/* The joint seam: what the kernels know about the joint that carries the beam's floating frame.
 *
 * The beam's full coordinates are [rigid, q]: the frame's m->nrigid coordinates, then the n modal coordinates.  A
 * joint says how the frame moves (its angle and rates from the state, or from time for the coordinates it gives:
 * the first m->ngiven of them are functions of time and not in the state), the frame's part of the mass matrix and
 * of the generalised forces, the energies, how a point's motion in the frame is placed in the plane, and what the
 * drive does (its torque, the work it does).
 *
 * Two kinds: FB_JOINT_REVOLUTE, a revolute joint at a fixed point O (joint_revolute.c: free, torque-driven or
 * with theta(t) prescribed), and FB_JOINT_FREE, a free-flying beam whose frame sits at its centre of mass
 * (joint_free.c).  joint.c dispatches on m->joint: it is the only place in the kernels that knows the
 * kinds.  Adding a kind: its FB_JOINT_* code here, its joint_<kind>.c with the functions of fb_joint_ops, one line
 * in joint.c's table, and the Python side (flexbeam/model/joints/, docs/architecture.md, "Adding a joint kind").
 */
#ifndef FLEXBEAM_JOINT_H
#define FLEXBEAM_JOINT_H

enum { FB_JOINT_REVOLUTE = 0, FB_JOINT_FREE = 1, FB_JOINT_KINDS = 2 };

/* The floating frame's motion: its angle theta and its rates; its origin R and the origin's velocity R' in the
 * plane (zero for a frame turning about the fixed point O; the centre of mass G of a free beam). */
typedef struct {
    double th, thd, thdd;
    double R[2], Rd[2];
    double field[2]; /* the uniform field on the beam in the plane's axes: (0, -g), less a_O(t) on a moving base */
    /* a moving base's r_O(t), v_O(t), a_O(t) (zero otherwise): an obstacle fixed to the ground sits at C - r_O in the
     * base frame (fb_gap_state) */
    double rO[2], vO[2], aO[2];
} fb_frame;

/* A point's motion relative to the floating frame, in its axes: position rho, velocity rho' and the velocity-product
 * part of its acceleration (at q'' = 0); its derivatives by the modal coordinates drho (2 x n, row-major). */
typedef struct {
    double rho[2], rhod[2], acc[2];
} fb_body_kin;

struct fb_model_s;
struct fb_kin_s;
struct fb_basis_s;

#define FB_JOINT_MAXZ 66 /* the state's coordinates: at most 64 flexible ones, the frame's, a support coordinate */

/* How M(q) differs from the linearised M0 over the state's coordinates, for the collocation's M0 M(q)^-1 x
 * (joint.h, remainder and correct).  Rank one, M = M0 + ds e e^T (e the frame's angle): M0 M^-1 x = x - c e (row0 . x)
 * by Sherman-Morrison.  With axial modes the frame angle's row and column change too, M = M0 + ds e e^T + e u^T +
 * u e^T (u: S^T p on q, -S q on p), a rank-two update by Woodbury's identity (axial.c, rank2). */
typedef struct {
    int active; /* M differs from M0 (correct() changes a direction) */
    int rank2;  /* the axial modes' rank-two update (else rank one with c) */
    int row;    /* the frame angle's index e in the state's coordinates */
    double c;
    double u[FB_JOINT_MAXZ], w[FB_JOINT_MAXZ]; /* u and M0^-1 u over the state's coordinates */
    double G[2][2];                            /* the inverse of Woodbury's 2 x 2 capacitance matrix */
} fb_update;

/* A joint kind's functions (joint_<kind>.c); joint.c picks the table of m->joint. */
typedef struct {
    /* the joint's parameters jp checked, m->nrigid and m->ngiven set; nonzero if they are inconsistent */
    int (*unpack)(struct fb_model_s *m);
    /* the frame's motion and the modal coordinates at time t from the state's coordinates z and rates zd (nz each) */
    void (*split)(const struct fb_model_s *m, double t, const double *z, const double *zd, fb_frame *f,
                  const double **q, const double **qd);
    /* the applied generalised force of the drive on the frame's coordinates (0 where they are given) */
    double (*torque)(const struct fb_model_s *m, double t);
    /* the full mass matrix M(q) (nfull x nfull, row-major) */
    void (*mass)(const struct fb_model_s *m, const double *q, double *M);
    /* the full generalised forces Q (with the elastic -K q if ``elastic``) for the drive's ``tau``; returns the
     * change of the frame's rotary inertia q^T Mc q (the rank-one part of M(q) - M0) */
    double (*forces)(const struct fb_model_s *m, const fb_frame *f, const double *q, const double *qd, double tau,
                     int elastic, double *Q);
    /* kinetic, elastic and gravitational energy */
    void (*energies)(const struct fb_model_s *m, const fb_frame *f, const double *q, const double *qd, double *T,
                     double *Ve, double *Vg);
    /* a point's motion in the plane from its motion in the frame: r, v, a0, and dr/d[rigid, q] (2 x nfull; its
     * modal columns from drho) */
    void (*place)(const struct fb_model_s *m, const fb_frame *f, const fb_body_kin *bk, const double *drho,
                  struct fb_kin_s *out, double *dr);
    /* a point (direction = 0) or a direction (1) of the plane in the frame's axes */
    void (*to_body)(const struct fb_model_s *m, const fb_frame *f, const double *p, int direction, double *out);
    /* the angle an applied torque works on, from the state's coordinates z (bookkeeping of the work) */
    double (*work_angle)(const struct fb_model_s *m, const double *z);
    /* the hub angle and its rate (outputs) */
    void (*hub)(const struct fb_model_s *m, const fb_frame *f, const double *q, const double *qd, double *phi,
                double *phid);
    /* the rate of the drive's work at a state, for a joint reaction ``torque`` on the given coordinates or the
     * applied torque */
    double (*power)(const struct fb_model_s *m, const fb_frame *f, const double *q, const double *qd, double torque);
    /* a bound on the given coordinates' contribution to a point's speed over [t0, t1], per unit lever arm */
    double (*rate_bound)(const struct fb_model_s *m, double t0, double t1);
    /* the accelerations of the given coordinates (ngiven of them) */
    void (*given_acc)(const struct fb_model_s *m, const fb_frame *f, double *acc);
    /* bounds on |d r / d rigid| over the beam for a reach |r| <= reach (contact anywhere): nrigid entries */
    void (*rigid_bound)(const struct fb_model_s *m, double reach, double *env);
    /* does the Sherman-Morrison update of the collocation need K0 z (M0^-1 couples the frame to q: hub frame)? */
    int (*row0_coupled)(const struct fb_model_s *m, const struct fb_basis_s *b);
    /* the linearised model's remainder R = M0 M(q)^-1 Q over the state's coordinates (collocation.c; the elastic
     * force is not in Q, K0 z is in the linear part) from Q over the full coordinates and ds (forces); returns the
     * coefficient c of M(q) = M0 + ds e e^T by which correct() turns a contact direction x into M0 M^-1 x (the
     * update up: rank one, or rank two with axial modes) */
    double (*remainder)(const struct fb_model_s *m, const struct fb_basis_s *b, int row0_q, const fb_frame *f,
                        const double *q, const double *Q, double ds, fb_update *up, double *R);
    void (*correct)(const struct fb_model_s *m, const struct fb_basis_s *b, const fb_update *up, double *x);
} fb_joint_ops;

/* The table of m's joint kind (joint.c). */
const fb_joint_ops *fb_joint(const struct fb_model_s *m);

extern const fb_joint_ops fb_joint_revolute;
extern const fb_joint_ops fb_joint_free;

#endif
