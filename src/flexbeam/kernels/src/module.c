/* Python glue of the compiled kernels: every argument array is a C-contiguous float64 buffer (numpy arrays),
 * outputs are written into caller-allocated buffers.  The model and basis buffers are packed once per system
 * by flexbeam.kernels.layout and unpacked per call (a few pointer assignments). */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <string.h>

#include "detmath.h"
#include "linalg.h"
#include "phase.h"

typedef struct {
    Py_buffer view;
    int held;
} buf_t;

static int get_buf(PyObject *obj, buf_t *b, int writable, const char *name) {
    b->held = 0;
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, &b->view, flags) < 0) {
        PyErr_Format(PyExc_TypeError, "%s: expected a C-contiguous%s float64 array", name, writable ? " writable" : "");
        return -1;
    }
    b->held = 1;
    const char *fmt = b->view.format;
    if (b->view.itemsize != 8 || !fmt || !(fmt[0] == 'd' || ((fmt[0] == '<' || fmt[0] == '=') && fmt[1] == 'd'))) {
        PyErr_Format(PyExc_TypeError, "%s: expected float64", name);
        PyBuffer_Release(&b->view);
        b->held = 0;
        return -1;
    }
    return 0;
}

static void release(buf_t *bufs, int count) {
    for (int i = 0; i < count; i++)
        if (bufs[i].held) PyBuffer_Release(&bufs[i].view);
}

#define LEN(b) ((size_t)((b).view.len / 8))
#define PTR(b) ((double *)(b).view.buf)

static int model_from(buf_t *b, fb_model *m) {
    if (fb_model_unpack(m, PTR(*b), LEN(*b))) {
        PyErr_SetString(PyExc_ValueError, "model: buffer does not match the kernel layout");
        return -1;
    }
    return 0;
}

static int contacts_from(buf_t *b, const fb_model *m, fb_contacts *c) {
    if (fb_contacts_unpack(c, m, PTR(*b), LEN(*b))) {
        PyErr_SetString(PyExc_ValueError, "contacts: buffer does not match the model's pairs");
        return -1;
    }
    return 0;
}

static int basis_from(buf_t *b, fb_basis *bs) {
    if (fb_basis_unpack(bs, PTR(*b), LEN(*b))) {
        PyErr_SetString(PyExc_ValueError, "basis: buffer does not match the kernel layout");
        return -1;
    }
    return 0;
}

/* rhs(model, t, y, contacts, dy, F) -> torque; F (npairs) the pairs' forces */
static PyObject *py_rhs(PyObject *self, PyObject *args) {
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

/* outputs(model, times, Y, contacts, cols, mv, pcols) */
static PyObject *py_outputs(PyObject *self, PyObject *args) {
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
static PyObject *py_kinematics(PyObject *self, PyObject *args) {
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

/* gap(model, pair, t, y, J) -> (delta, rate, gamma, nx, ny); J (nfull [+ 1 with a support]) = d delta / dz */
static PyObject *py_gap(PyObject *self, PyObject *args) {
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
    return Py_BuildValue("ddddd", g.delta, g.rate, g.gamma, g.nx, g.ny);
fail:
    release(b, 3);
    return NULL;
}

/* equations(model, t, y, M, Q, E): M (nfull x nfull), Q (nfull, with the applied torque), E = [T, Ve, Vg] */
static PyObject *py_equations(PyObject *self, PyObject *args) {
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
static PyObject *py_law_force(PyObject *self, PyObject *args) {
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

/* advance(model, basis, ctrl, state, t_end, records, info) -> (code, nrec) */
static PyObject *py_advance(PyObject *self, PyObject *args) {
    PyObject *om, *ob, *oc, *os, *orec, *oi;
    double t_end;
    if (!PyArg_ParseTuple(args, "OOOOdOO", &om, &ob, &oc, &os, &t_end, &orec, &oi)) return NULL;
    buf_t b[6];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_basis bs;
    if (get_buf(om, &b[0], 0, "model") || get_buf(ob, &b[1], 0, "basis") || get_buf(oc, &b[2], 0, "ctrl") ||
        get_buf(os, &b[3], 1, "state") || get_buf(orec, &b[4], 1, "records") || get_buf(oi, &b[5], 1, "info") ||
        model_from(&b[0], &m) || basis_from(&b[1], &bs))
        goto fail;
    int R = fb_record_size(bs.N, m.npairs);
    if (LEN(b[3]) != (size_t)fb_state_buffer_size(bs.N, m.npairs) || LEN(b[4]) % R || LEN(b[5]) < FB_INFO_SIZE ||
        bs.N > FB_MAXN) {
        PyErr_SetString(PyExc_ValueError, "advance: array sizes do not match");
        goto fail;
    }
    int nrec = 0, code;
    Py_BEGIN_ALLOW_THREADS
    code = fb_advance(&m, &bs, PTR(b[2]), LEN(b[2]), PTR(b[3]), t_end, PTR(b[4]), (int)(LEN(b[4]) / R), &nrec,
                      PTR(b[5]));
    Py_END_ALLOW_THREADS
    release(b, 6);
    if (code < 0) {
        PyErr_SetString(PyExc_ValueError, "advance: ctrl does not match the model's pairs");
        return NULL;
    }
    return Py_BuildValue("ii", code, nrec);
fail:
    release(b, 6);
    return NULL;
}

/* dense(model, basis, records, nrec, times, Y) */
static PyObject *py_dense(PyObject *self, PyObject *args) {
    PyObject *om, *ob, *orec, *ot, *oY;
    int nrec;
    if (!PyArg_ParseTuple(args, "OOOiOO", &om, &ob, &orec, &nrec, &ot, &oY)) return NULL;
    buf_t b[5];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_basis bs;
    if (get_buf(om, &b[0], 0, "model") || get_buf(ob, &b[1], 0, "basis") || get_buf(orec, &b[2], 0, "records") ||
        get_buf(ot, &b[3], 0, "times") || get_buf(oY, &b[4], 1, "Y") || model_from(&b[0], &m) ||
        basis_from(&b[1], &bs))
        goto fail;
    size_t count = LEN(b[3]);
    if (nrec < 1 || LEN(b[2]) < (size_t)nrec * fb_record_size(bs.N, m.npairs) ||
        LEN(b[4]) != count * fb_state_size(&m)) {
        PyErr_SetString(PyExc_ValueError, "dense: array sizes do not match");
        goto fail;
    }
    Py_BEGIN_ALLOW_THREADS
    fb_dense_eval(&m, &bs, PTR(b[2]), nrec, PTR(b[3]), (int)count, PTR(b[4]));
    Py_END_ALLOW_THREADS
    release(b, 5);
    Py_RETURN_NONE;
fail:
    release(b, 5);
    return NULL;
}

/* moments(theta) -> (Cm_0..Cm_3, Sm_0..Sm_3) of propagation.c (for the tests) */
static PyObject *py_moments(PyObject *self, PyObject *args) {
    double th, Cm[FB_P], Sm[FB_P];
    if (!PyArg_ParseTuple(args, "d", &th)) return NULL;
    fb_moments(th, Cm, Sm);
    return Py_BuildValue("(dddd)(dddd)", Cm[0], Cm[1], Cm[2], Cm[3], Sm[0], Sm[1], Sm[2], Sm[3]);
}

/* weights(w, h, s) -> (C, SW, WS, RE (4), RV (4)) of one mode at the fraction s of a step h (for the tests) */
static PyObject *py_weights(PyObject *self, PyObject *args) {
    double w, h, s;
    if (!PyArg_ParseTuple(args, "ddd", &w, &h, &s)) return NULL;
    fb_weight W;
    fb_weights(w, h, s, &W);
    return Py_BuildValue("ddd(dddd)(dddd)", W.C, W.SW, W.WS, W.RE[0], W.RE[1], W.RE[2], W.RE[3], W.RV[0], W.RV[1],
                         W.RV[2], W.RV[3]);
}

/* nodes() -> the Gauss nodes of the collocation on (0, 1) */
static PyObject *py_nodes(PyObject *self, PyObject *args) {
    const fb_tables *t = fb_gauss();
    return Py_BuildValue("dddd", t->c[0], t->c[1], t->c[2], t->c[3]);
}

static PyObject *py_sizes(PyObject *self, PyObject *args) {
    int N, S;
    if (!PyArg_ParseTuple(args, "ii", &N, &S)) return NULL;
    return Py_BuildValue("iiiii", fb_record_size(N, S), fb_state_buffer_size(N, S), FB_P, FB_NCOLS, FB_PAIR_COLS);
}

/* ------------------------------------------------------------------ numerics (detmath.c, linalg.c) */
typedef double (*unary_fn)(double);
static const unary_fn UNARY[] = {fb_sin, fb_cos, fb_exp, fb_expm1, fb_log, fb_log1p, fb_tgamma};
#define N_UNARY ((int)(sizeof UNARY / sizeof UNARY[0]))

/* unary(code, x) -> f(x) for a float x (code: sin, cos, exp, expm1, log, log1p, tgamma) */
static PyObject *py_unary(PyObject *self, PyObject *args) {
    int code;
    double x;
    if (!PyArg_ParseTuple(args, "id", &code, &x)) return NULL;
    if (code < 0 || code >= N_UNARY) {
        PyErr_SetString(PyExc_ValueError, "unary: unknown function code");
        return NULL;
    }
    return PyFloat_FromDouble(UNARY[code](x));
}

/* vunary(code, x, out): out[i] = f(x[i]) */
static PyObject *py_vunary(PyObject *self, PyObject *args) {
    int code;
    PyObject *ox, *oo;
    if (!PyArg_ParseTuple(args, "iOO", &code, &ox, &oo)) return NULL;
    if (code < 0 || code >= N_UNARY) {
        PyErr_SetString(PyExc_ValueError, "vunary: unknown function code");
        return NULL;
    }
    buf_t b[2];
    memset(b, 0, sizeof b);
    if (get_buf(ox, &b[0], 0, "x") || get_buf(oo, &b[1], 1, "out")) goto fail;
    if (LEN(b[0]) != LEN(b[1])) {
        PyErr_SetString(PyExc_ValueError, "vunary: x and out must have the same size");
        goto fail;
    }
    {
        const double *x = PTR(b[0]);
        double *o = PTR(b[1]);
        size_t n = LEN(b[0]);
        unary_fn f = UNARY[code];
        for (size_t i = 0; i < n; i++) o[i] = f(x[i]);
    }
    release(b, 2);
    Py_RETURN_NONE;
fail:
    release(b, 2);
    return NULL;
}

/* binary(code, a, b) -> pow(a, b) (code 0) or atan2(a, b) (code 1) */
static PyObject *py_binary(PyObject *self, PyObject *args) {
    int code;
    double a, c;
    if (!PyArg_ParseTuple(args, "idd", &code, &a, &c)) return NULL;
    return PyFloat_FromDouble(code == 0 ? fb_pow(a, c) : fb_atan2(a, c));
}

/* vbinary(code, a, b, out): out[i] = pow(a[i], b[i]) or atan2(a[i], b[i]); a or b may have size 1 */
static PyObject *py_vbinary(PyObject *self, PyObject *args) {
    int code;
    PyObject *oa, *ob, *oo;
    if (!PyArg_ParseTuple(args, "iOOO", &code, &oa, &ob, &oo)) return NULL;
    buf_t b[3];
    memset(b, 0, sizeof b);
    if (get_buf(oa, &b[0], 0, "a") || get_buf(ob, &b[1], 0, "b") || get_buf(oo, &b[2], 1, "out")) goto fail;
    {
        size_t n = LEN(b[2]), na = LEN(b[0]), nb = LEN(b[1]);
        if ((na != n && na != 1) || (nb != n && nb != 1)) {
            PyErr_SetString(PyExc_ValueError, "vbinary: a and b must have the size of out, or size 1");
            goto fail;
        }
        const double *a = PTR(b[0]), *c = PTR(b[1]);
        double *o = PTR(b[2]);
        for (size_t i = 0; i < n; i++) {
            double x = a[na == 1 ? 0 : i], y = c[nb == 1 ? 0 : i];
            o[i] = code == 0 ? fb_pow(x, y) : fb_atan2(x, y);
        }
    }
    release(b, 3);
    Py_RETURN_NONE;
fail:
    release(b, 3);
    return NULL;
}

/* matmul(A, B, C, m, k, n): C = A B */
static PyObject *py_matmul(PyObject *self, PyObject *args) {
    PyObject *oa, *ob, *oc;
    int m, k, n;
    if (!PyArg_ParseTuple(args, "OOOiii", &oa, &ob, &oc, &m, &k, &n)) return NULL;
    buf_t b[3];
    memset(b, 0, sizeof b);
    if (get_buf(oa, &b[0], 0, "A") || get_buf(ob, &b[1], 0, "B") || get_buf(oc, &b[2], 1, "C")) goto fail;
    if (m < 0 || k < 0 || n < 0 || LEN(b[0]) != (size_t)m * k || LEN(b[1]) != (size_t)k * n ||
        LEN(b[2]) != (size_t)m * n) {
        PyErr_SetString(PyExc_ValueError, "matmul: sizes do not match");
        goto fail;
    }
    Py_BEGIN_ALLOW_THREADS
    fb_la_matmul(PTR(b[0]), PTR(b[1]), PTR(b[2]), m, k, n);
    Py_END_ALLOW_THREADS
    release(b, 3);
    Py_RETURN_NONE;
fail:
    release(b, 3);
    return NULL;
}

/* gram(A, w, B, C, m, ka, kb): C = A^T diag(w) B */
static PyObject *py_gram(PyObject *self, PyObject *args) {
    PyObject *oa, *ow, *ob, *oc;
    int m, ka, kb;
    if (!PyArg_ParseTuple(args, "OOOOiii", &oa, &ow, &ob, &oc, &m, &ka, &kb)) return NULL;
    buf_t b[4];
    memset(b, 0, sizeof b);
    if (get_buf(oa, &b[0], 0, "A") || get_buf(ow, &b[1], 0, "w") || get_buf(ob, &b[2], 0, "B") ||
        get_buf(oc, &b[3], 1, "C"))
        goto fail;
    if (m < 0 || ka < 0 || kb < 0 || LEN(b[0]) != (size_t)m * ka || LEN(b[1]) != (size_t)m ||
        LEN(b[2]) != (size_t)m * kb || LEN(b[3]) != (size_t)ka * kb) {
        PyErr_SetString(PyExc_ValueError, "gram: sizes do not match");
        goto fail;
    }
    Py_BEGIN_ALLOW_THREADS
    fb_la_gram(PTR(b[0]), PTR(b[1]), PTR(b[2]), PTR(b[3]), m, ka, kb);
    Py_END_ALLOW_THREADS
    release(b, 4);
    Py_RETURN_NONE;
fail:
    release(b, 4);
    return NULL;
}

/* solve(A, B, n, nrhs) -> status; A (n x n) and B (n x nrhs) overwritten, the solution in B */
static PyObject *py_solve(PyObject *self, PyObject *args) {
    PyObject *oa, *ob;
    int n, nrhs, status = 0;
    if (!PyArg_ParseTuple(args, "OOii", &oa, &ob, &n, &nrhs)) return NULL;
    buf_t b[2];
    memset(b, 0, sizeof b);
    if (get_buf(oa, &b[0], 1, "A") || get_buf(ob, &b[1], 1, "B")) goto fail;
    if (n < 0 || nrhs < 0 || LEN(b[0]) != (size_t)n * n || LEN(b[1]) != (size_t)n * nrhs) {
        PyErr_SetString(PyExc_ValueError, "solve: sizes do not match");
        goto fail;
    }
    status = fb_la_solve(PTR(b[0]), PTR(b[1]), n, nrhs);
    release(b, 2);
    return PyLong_FromLong(status);
fail:
    release(b, 2);
    return NULL;
}

/* cholesky(A, n) -> status; the lower factor in A */
static PyObject *py_cholesky(PyObject *self, PyObject *args) {
    PyObject *oa;
    int n, status = 0;
    if (!PyArg_ParseTuple(args, "Oi", &oa, &n)) return NULL;
    buf_t b[1];
    memset(b, 0, sizeof b);
    if (get_buf(oa, &b[0], 1, "A")) goto fail;
    if (n < 0 || LEN(b[0]) != (size_t)n * n) {
        PyErr_SetString(PyExc_ValueError, "cholesky: sizes do not match");
        goto fail;
    }
    status = fb_la_cholesky(PTR(b[0]), n);
    release(b, 1);
    return PyLong_FromLong(status);
fail:
    release(b, 1);
    return NULL;
}

/* eigh(A, n, w, V) -> sweeps (-1: not converged); A overwritten */
static PyObject *py_eigh(PyObject *self, PyObject *args) {
    PyObject *oa, *ow, *ov;
    int n, status = 0;
    if (!PyArg_ParseTuple(args, "OiOO", &oa, &n, &ow, &ov)) return NULL;
    buf_t b[3];
    memset(b, 0, sizeof b);
    if (get_buf(oa, &b[0], 1, "A") || get_buf(ow, &b[1], 1, "w") || get_buf(ov, &b[2], 1, "V")) goto fail;
    if (n < 0 || LEN(b[0]) != (size_t)n * n || LEN(b[1]) != (size_t)n || LEN(b[2]) != (size_t)n * n) {
        PyErr_SetString(PyExc_ValueError, "eigh: sizes do not match");
        goto fail;
    }
    status = fb_la_eigh(PTR(b[0]), n, PTR(b[1]), PTR(b[2]));
    release(b, 3);
    return PyLong_FromLong(status);
fail:
    release(b, 3);
    return NULL;
}

static PyMethodDef methods[] = {
    {"rhs", py_rhs, METH_VARARGS, "rhs(model, t, y, contacts, dy, F) -> torque"},
    {"outputs", py_outputs, METH_VARARGS, "outputs(model, times, Y, contacts, cols, mv, pcols)"},
    {"kinematics", py_kinematics, METH_VARARGS, "kinematics(model, point, t, y, out)"},
    {"gap", py_gap, METH_VARARGS, "gap(model, pair, t, y, J) -> (delta, rate, gamma, nx, ny)"},
    {"equations", py_equations, METH_VARARGS, "equations(model, t, y, M, Q, E)"},
    {"law_force", py_law_force, METH_VARARGS, "law_force(p, d, dd) -> (F, Fk, dF/dd, dF/ddd)"},
    {"advance", py_advance, METH_VARARGS, "advance(model, basis, ctrl, state, t_end, records, info) -> (code, nrec)"},
    {"dense", py_dense, METH_VARARGS, "dense(model, basis, records, nrec, times, Y)"},
    {"moments", py_moments, METH_VARARGS, "moments(theta) -> (Cm, Sm)"},
    {"weights", py_weights, METH_VARARGS, "weights(w, h, s) -> (C, SW, WS, RE, RV)"},
    {"nodes", py_nodes, METH_NOARGS, "nodes() -> the collocation's Gauss nodes on (0, 1)"},
    {"sizes", py_sizes, METH_VARARGS,
     "sizes(N, npairs) -> (record size, state buffer size, nodes, output columns, columns per pair)"},
    {"unary", py_unary, METH_VARARGS, "unary(code, x) -> f(x): detmath.c's sin, cos, exp, expm1, log, log1p, tgamma"},
    {"vunary", py_vunary, METH_VARARGS, "vunary(code, x, out): out = f(x) elementwise"},
    {"binary", py_binary, METH_VARARGS, "binary(code, a, b) -> pow(a, b) (0) or atan2(a, b) (1)"},
    {"vbinary", py_vbinary, METH_VARARGS, "vbinary(code, a, b, out): elementwise pow or atan2"},
    {"matmul", py_matmul, METH_VARARGS, "matmul(A, B, C, m, k, n): C = A B in a fixed order"},
    {"gram", py_gram, METH_VARARGS, "gram(A, w, B, C, m, ka, kb): C = A^T diag(w) B in a fixed order"},
    {"solve", py_solve, METH_VARARGS, "solve(A, B, n, nrhs) -> status: B = A^-1 B (LU, partial pivoting)"},
    {"cholesky", py_cholesky, METH_VARARGS, "cholesky(A, n) -> status: the lower factor in A"},
    {"eigh", py_eigh, METH_VARARGS, "eigh(A, n, w, V) -> sweeps: symmetric eigenproblem by cyclic Jacobi"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef moduledef = {PyModuleDef_HEAD_INIT, "_core", "flexbeam compiled kernels", -1, methods};

PyMODINIT_FUNC PyInit__core(void) { return PyModule_Create(&moduledef); }
