/* The Python glue of the model (glue.h): the right-hand side, the output columns, a point's kinematics, a pair's
 * gap, the equations of motion and the contact law (rhs.c, model.c). */
#include "glue.h"

/* rhs(model, t, y, contacts, dy, F) -> torque; F (npairs) the pairs' forces */
PyObject *py_rhs(PyObject *self, PyObject *args) {
    PyObject *om, *oy, *oc, *ody, *oF;
    double t;
    if (!PyArg_ParseTuple(args, "OdOOOO", &om, &t, &oy, &oc, &ody, &oF)) return NULL;
    buf_t b[5];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_contacts c;
    if (get_buf(om, &b[0], 0, "model") || get_buf(oy, &b[1], 0, "y") || get_buf(oc, &b[2], 0, "contacts") ||
        get_buf(ody, &b[3], 1, "dy") || get_buf(oF, &b[4], 1, "F") || model_from(&b[0], &m) ||
        contacts_from(&b[2], &m, &c))
        goto fail;
    if (LEN(b[1]) != (size_t)fb_state_size(&m) || LEN(b[3]) != LEN(b[1]) || LEN(b[4]) != (size_t)m.npairs) {
        PyErr_SetString(PyExc_ValueError, "rhs: y, dy must have the state size and F one entry per pair");
        goto fail;
    }
    double torque;
    fb_rhs(&m, t, PTR(b[1]), &c, PTR(b[3]), PTR(b[4]), &torque);
    release(b, 5);
    return PyFloat_FromDouble(torque);
fail:
    release(b, 5);
    return NULL;
}

/* contact_forces(model, t, y, contacts, F, Ft) -> status: the normal forces and the sticking pairs' tangential
 * multipliers with every pair's friction (rhs.c fb_contact_forces) */
PyObject *py_contact_forces(PyObject *self, PyObject *args) {
    PyObject *om, *oy, *oc, *oF, *oFt;
    double t;
    if (!PyArg_ParseTuple(args, "OdOOOO", &om, &t, &oy, &oc, &oF, &oFt)) return NULL;
    buf_t b[5];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_contacts c;
    if (get_buf(om, &b[0], 0, "model") || get_buf(oy, &b[1], 0, "y") || get_buf(oc, &b[2], 0, "contacts") ||
        get_buf(oF, &b[3], 1, "F") || get_buf(oFt, &b[4], 1, "Ft") || model_from(&b[0], &m) ||
        contacts_from(&b[2], &m, &c))
        goto fail;
    if (LEN(b[1]) != (size_t)fb_state_size(&m) || LEN(b[3]) != (size_t)m.npairs || LEN(b[4]) != (size_t)m.npairs) {
        PyErr_SetString(PyExc_ValueError, "contact_forces: y must have the state size, F and Ft one entry per pair");
        goto fail;
    }
    int status = fb_contact_forces(&m, t, PTR(b[1]), &c, PTR(b[3]), PTR(b[4]));
    release(b, 5);
    return PyLong_FromLong(status);
fail:
    release(b, 5);
    return NULL;
}

/* outputs(model, times, Y, contacts, cols, mv, pcols) */
PyObject *py_outputs(PyObject *self, PyObject *args) {
    PyObject *om, *ot, *oY, *oc, *ocols, *omv, *opc;
    if (!PyArg_ParseTuple(args, "OOOOOOO", &om, &ot, &oY, &oc, &ocols, &omv, &opc)) return NULL;
    buf_t b[7];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_contacts c;
    if (get_buf(om, &b[0], 0, "model") || get_buf(ot, &b[1], 0, "times") || get_buf(oY, &b[2], 0, "Y") ||
        get_buf(oc, &b[3], 0, "contacts") || get_buf(ocols, &b[4], 1, "cols") || get_buf(omv, &b[5], 1, "mv") ||
        get_buf(opc, &b[6], 1, "pcols") || model_from(&b[0], &m) || contacts_from(&b[3], &m, &c))
        goto fail;
    size_t count = LEN(b[1]);
    if (LEN(b[2]) != count * fb_state_size(&m) || LEN(b[4]) != count * FB_NCOLS ||
        LEN(b[5]) != count * (size_t)m.nmeasure || LEN(b[6]) != count * m.npairs * FB_PAIR_COLS) {
        PyErr_SetString(PyExc_ValueError, "outputs: array sizes do not match");
        goto fail;
    }
    Py_BEGIN_ALLOW_THREADS
    fb_outputs(&m, PTR(b[1]), PTR(b[2]), (int)count, &c, PTR(b[4]), PTR(b[5]), PTR(b[6]));
    Py_END_ALLOW_THREADS
    release(b, 7);
    Py_RETURN_NONE;
fail:
    release(b, 7);
    return NULL;
}

/* kinematics(model, point, t, y, out) : out = [r (2), v (2), a0 (2), dr (2 x (n+1))] */
PyObject *py_kinematics(PyObject *self, PyObject *args) {
    PyObject *om, *oy, *oo;
    int ip;
    double t;
    if (!PyArg_ParseTuple(args, "OidOO", &om, &ip, &t, &oy, &oo)) return NULL;
    buf_t b[3];
    memset(b, 0, sizeof b);
    fb_model m;
    if (get_buf(om, &b[0], 0, "model") || get_buf(oy, &b[1], 0, "y") || get_buf(oo, &b[2], 1, "out") ||
        model_from(&b[0], &m))
        goto fail;
    if (ip < 0 || ip >= m.npoints || LEN(b[1]) != (size_t)fb_state_size(&m) ||
        LEN(b[2]) != (size_t)(6 + 2 * fb_nfull(&m))) {
        PyErr_SetString(PyExc_ValueError, "kinematics: bad point index or array sizes");
        goto fail;
    }
    double *out = PTR(b[2]);
    fb_frame fr;
    const double *q, *qd;
    fb_state_split(&m, t, PTR(b[1]), &fr, &q, &qd);
    fb_kin k = {.want_acc = 1};
    fb_point_kinematics(&m, &m.points[ip], &fr, q, qd, &k, out + 6);
    out[0] = k.r[0]; out[1] = k.r[1]; out[2] = k.v[0]; out[3] = k.v[1]; out[4] = k.a0[0]; out[5] = k.a0[1];
    release(b, 3);
    Py_RETURN_NONE;
fail:
    release(b, 3);
    return NULL;
}

/* gap(model, pair, t, y, J) -> (delta, rate, gamma, nx, ny, x); J (nfull [+ 1 with a support]) = d delta / dz, x the
 * contact point's material coordinate (it moves for a pair anywhere) */
PyObject *py_gap(PyObject *self, PyObject *args) {
    PyObject *om, *oy, *oJ;
    int pair;
    double t;
    if (!PyArg_ParseTuple(args, "OidOO", &om, &pair, &t, &oy, &oJ)) return NULL;
    buf_t b[3];
    memset(b, 0, sizeof b);
    fb_model m;
    if (get_buf(om, &b[0], 0, "model") || get_buf(oy, &b[1], 0, "y") || get_buf(oJ, &b[2], 1, "J") ||
        model_from(&b[0], &m))
        goto fail;
    int compliant = fb_compliant(&m), N = fb_nfull(&m);
    if (pair < 0 || pair >= m.npairs || LEN(b[1]) != (size_t)fb_state_size(&m) ||
        LEN(b[2]) != (size_t)(N + compliant)) {
        PyErr_SetString(PyExc_ValueError, "gap: no such pair, or array sizes do not match");
        goto fail;
    }
    double *J = PTR(b[2]);
    fb_frame fr;
    const double *q, *qd, *y = PTR(b[1]);
    fb_state_split(&m, t, y, &fr, &q, &qd);
    int nb = 2 * fb_nz(&m);
    double s = compliant ? y[nb] : 0.0, sd = compliant ? y[nb + 1] : 0.0;
    fb_gap g = fb_pair_gap(&m, pair, &fr, q, qd, s, sd, 1, J);
    if (compliant) J[N] = g.Js;
    release(b, 3);
    return Py_BuildValue("dddddd", g.delta, g.rate, g.gamma, g.nx, g.ny, g.x);
fail:
    release(b, 3);
    return NULL;
}

/* tangent(model, pair, t, y, J, Jt[, acc]) -> (delta, rate, slip velocity, nx, ny, slip rate); J and Jt (nfull [+ 1
 * with a support]): the normal and tangential Jacobians of the pair's contact point (fb_pair_tangent); with acc the
 * slip velocity's rate at z'' = 0 (gamma_t; else 0) */
PyObject *py_tangent(PyObject *self, PyObject *args) {
    PyObject *om, *oy, *oJ, *oJt;
    int pair, acc = 0;
    double t;
    if (!PyArg_ParseTuple(args, "OidOOO|i", &om, &pair, &t, &oy, &oJ, &oJt, &acc)) return NULL;
    buf_t b[4];
    memset(b, 0, sizeof b);
    fb_model m;
    if (get_buf(om, &b[0], 0, "model") || get_buf(oy, &b[1], 0, "y") || get_buf(oJ, &b[2], 1, "J") ||
        get_buf(oJt, &b[3], 1, "Jt") || model_from(&b[0], &m))
        goto fail;
    int compliant = fb_compliant(&m), N = fb_nfull(&m);
    if (pair < 0 || pair >= m.npairs || LEN(b[1]) != (size_t)fb_state_size(&m) ||
        LEN(b[2]) != (size_t)(N + compliant) || LEN(b[3]) != (size_t)(N + compliant)) {
        PyErr_SetString(PyExc_ValueError, "tangent: no such pair, or array sizes do not match");
        goto fail;
    }
    double *J = PTR(b[2]), *Jt = PTR(b[3]), vt;
    fb_frame fr;
    const double *q, *qd, *y = PTR(b[1]);
    fb_state_split(&m, t, y, &fr, &q, &qd);
    int nb = 2 * fb_nz(&m);
    double s = compliant ? y[nb] : 0.0, sd = compliant ? y[nb + 1] : 0.0;
    fb_gap g = fb_pair_tangent(&m, pair, &fr, q, qd, s, sd, acc != 0, J, Jt, &vt);
    if (compliant) {
        const fb_obstacle *o = &m.obstacles[m.pairs[pair].obstacle];
        J[N] = g.Js;
        Jt[N] = o->ms > 0.0 ? -(-g.ny * o->ux + g.nx * o->uy) : 0.0;
    }
    release(b, 4);
    return Py_BuildValue("dddddd", g.delta, g.rate, vt, g.nx, g.ny, g.tgamma);
fail:
    release(b, 4);
    return NULL;
}

/* nearest_path(model, pair, t, Y, warm, out) -> full scans: for each row y of Y (states, one model unpacking for all)
 * the pair's gap and contact point, out rows [delta, x, nx, ny]; with warm = 0 every search scans all the stations
 * (nearest_scan.c's warm scan off: the reference the warm one must reproduce); returns how many full scans of a
 * half-plane's stations the searches made */
PyObject *py_nearest_path(PyObject *self, PyObject *args) {
    PyObject *om, *oY, *oout;
    int pair, warm;
    double t;
    if (!PyArg_ParseTuple(args, "OidOiO", &om, &pair, &t, &oY, &warm, &oout)) return NULL;
    buf_t b[3];
    memset(b, 0, sizeof b);
    fb_model m;
    if (get_buf(om, &b[0], 0, "model") || get_buf(oY, &b[1], 0, "Y") || get_buf(oout, &b[2], 1, "out") ||
        model_from(&b[0], &m))
        goto fail;
    size_t S = (size_t)fb_state_size(&m), rows = LEN(b[1]) / (S ? S : 1);
    if (pair < 0 || pair >= m.npairs || LEN(b[1]) != rows * S || LEN(b[2]) != 4 * rows) {
        PyErr_SetString(PyExc_ValueError, "nearest_path: no such pair, or array sizes do not match");
        goto fail;
    }
    int compliant = fb_compliant(&m), nb = 2 * fb_nz(&m);
    fb_nearest_warm(warm);
    long full = fb_nearest_full_scans();
    for (size_t i = 0; i < rows; i++) {
        fb_frame fr;
        const double *q, *qd, *y = PTR(b[1]) + i * S;
        fb_state_split(&m, t, y, &fr, &q, &qd);
        fb_gap g = fb_pair_gap(&m, pair, &fr, q, qd, compliant ? y[nb] : 0.0, compliant ? y[nb + 1] : 0.0, 0, NULL);
        double *o = PTR(b[2]) + 4 * i;
        o[0] = g.delta, o[1] = g.x, o[2] = g.nx, o[3] = g.ny;
    }
    fb_nearest_warm(1);
    full = fb_nearest_full_scans() - full;
    release(b, 3);
    return PyLong_FromLong(full);
fail:
    release(b, 3);
    return NULL;
}

/* equations(model, t, y, M, Q, E): M (nfull x nfull), Q (nfull, with the applied torque), E = [T, Ve, Vg] */
PyObject *py_equations(PyObject *self, PyObject *args) {
    PyObject *om, *oy, *oM, *oQ, *oE;
    double t;
    if (!PyArg_ParseTuple(args, "OdOOOO", &om, &t, &oy, &oM, &oQ, &oE)) return NULL;
    buf_t b[5];
    memset(b, 0, sizeof b);
    fb_model m;
    if (get_buf(om, &b[0], 0, "model") || get_buf(oy, &b[1], 0, "y") || get_buf(oM, &b[2], 1, "M") ||
        get_buf(oQ, &b[3], 1, "Q") || get_buf(oE, &b[4], 1, "E") || model_from(&b[0], &m))
        goto fail;
    size_t N = (size_t)fb_nfull(&m);
    if (LEN(b[1]) != (size_t)fb_state_size(&m) || LEN(b[2]) != N * N || LEN(b[3]) != N || LEN(b[4]) != 3) {
        PyErr_SetString(PyExc_ValueError, "equations: array sizes do not match");
        goto fail;
    }
    double *E = PTR(b[4]);
    fb_frame fr;
    const double *q, *qd;
    const fb_joint_ops *jt = fb_joint(&m);
    fb_state_split(&m, t, PTR(b[1]), &fr, &q, &qd);
    jt->mass(&m, q, PTR(b[2]));
    jt->forces(&m, &fr, q, qd, jt->torque(&m, t), 1, PTR(b[3]));
    jt->energies(&m, &fr, q, qd, &E[0], &E[1], &E[2]);
    release(b, 5);
    Py_RETURN_NONE;
fail:
    release(b, 5);
    return NULL;
}

/* law_force(p, d, dd) -> (F, Fk, dF/dd, dF/ddd) */
PyObject *py_law_force(PyObject *self, PyObject *args) {
    PyObject *op;
    double d, dd;
    if (!PyArg_ParseTuple(args, "Odd", &op, &d, &dd)) return NULL;
    buf_t b[1];
    memset(b, 0, sizeof b);
    if (get_buf(op, &b[0], 0, "p")) return NULL;
    if (LEN(b[0]) < 4) {
        release(b, 1);
        PyErr_SetString(PyExc_ValueError, "law_force: p must have four entries");
        return NULL;
    }
    double fk, gd, gr, F = fb_law_force(PTR(b[0]), d, dd, &fk, &gd, &gr);
    release(b, 1);
    return Py_BuildValue("dddd", F, fk, gd, gr);
}

/* normal_jump(model, pair, t, y, e, y_plus, out) -> status: one frictionless pair's impulse map (impulse_map.c
 * fb_normal_jump), out = [P, v-, v+, T-, T+]; 1: a state the Python map takes, -1: M singular */
PyObject *py_normal_jump(PyObject *self, PyObject *args) {
    PyObject *om, *oy, *oyp, *oout;
    int pair;
    double t, e;
    if (!PyArg_ParseTuple(args, "OidOdOO", &om, &pair, &t, &oy, &e, &oyp, &oout)) return NULL;
    buf_t b[4];
    memset(b, 0, sizeof b);
    fb_model m;
    if (get_buf(om, &b[0], 0, "model") || get_buf(oy, &b[1], 0, "y") || get_buf(oyp, &b[2], 1, "y_plus") ||
        get_buf(oout, &b[3], 1, "out") || model_from(&b[0], &m))
        goto fail;
    if (pair < 0 || pair >= m.npairs || LEN(b[1]) != (size_t)fb_state_size(&m) || LEN(b[2]) != LEN(b[1]) ||
        LEN(b[3]) != 5) {
        PyErr_SetString(PyExc_ValueError, "normal_jump: no such pair, or array sizes do not match");
        goto fail;
    }
    int status = fb_normal_jump(&m, pair, t, PTR(b[1]), e, PTR(b[2]), PTR(b[3]));
    release(b, 4);
    return PyLong_FromLong(status);
fail:
    release(b, 4);
    return NULL;
}
