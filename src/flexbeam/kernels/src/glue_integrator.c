/* The Python glue of the integrator (glue.h): a phase (phase.c), its dense output (bookkeeping.c) and an output's
 * largest value on it (extremes.c); the propagation's moments, weights and Gauss nodes (propagation.c, for the
 * tests) and the sizes of the phase's buffers. */
#include "glue.h"
#include "phase.h"

/* the length a switching rule's coef must have (switching.c): [FB_SWITCH_FRICTION, band, REST_SPEED, mu_k (S), mu_s
 * (S)], [FB_SWITCH_HELD, 7 numbers] or [FB_SWITCH_REBOUND, 9 numbers, e (S)] (held_switch.c); 0 for anything else */
static size_t coef_size(const double *coef, size_t n, int S) {
    if (n < 1) return 1;
    if (coef[0] == FB_SWITCH_FRICTION) return 3 + 2 * (size_t)S;
    if (coef[0] == FB_SWITCH_HELD) return 8;
    if (coef[0] == FB_SWITCH_REBOUND) return 10 + (size_t)S;
    return 0;
}

/* advance(model, basis, ctrl, state, t_end, records, info[, coef, switches]) -> (code, nrec, nswitch): a phase's step
 * loop (fb_advance); with coef and switches, the switches of coef[0]'s rule taken in place (switching.c: CCFM's
 * friction switches, CCM's onsets and releases on one pair; ctrl updated, each switch a row of `switches`,
 * switch_width(N) floats) */
PyObject *py_advance(PyObject *self, PyObject *args) {
    PyObject *om, *ob, *oc, *os, *orec, *oi, *ocoef = NULL, *osw = NULL;
    double t_end;
    if (!PyArg_ParseTuple(args, "OOOOdOO|OO", &om, &ob, &oc, &os, &t_end, &orec, &oi, &ocoef, &osw)) return NULL;
    buf_t b[8];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_basis bs;
    int switching = ocoef != NULL && osw != NULL;
    if (get_buf(om, &b[0], 0, "model") || get_buf(ob, &b[1], 0, "basis") || get_buf(oc, &b[2], 1, "ctrl") ||
        get_buf(os, &b[3], 1, "state") || get_buf(orec, &b[4], 1, "records") || get_buf(oi, &b[5], 1, "info") ||
        (switching && (get_buf(ocoef, &b[6], 1, "coef") || get_buf(osw, &b[7], 1, "switches"))) ||
        model_from(&b[0], &m) || basis_from(&b[1], &bs))
        goto fail;
    int R = fb_record_size(bs.N, m.npairs), width = fb_switch_width(bs.N);
    if (LEN(b[3]) != (size_t)fb_state_buffer_size(bs.N, m.npairs) || LEN(b[4]) % R || LEN(b[5]) < FB_INFO_SIZE ||
        bs.N > FB_MAXN ||
        (switching && (LEN(b[6]) != coef_size(PTR(b[6]), LEN(b[6]), m.npairs) || LEN(b[7]) % width))) {
        PyErr_SetString(PyExc_ValueError, "advance: array sizes do not match");
        goto fail;
    }
    int nrec = 0, nsw = 0, code, capacity = (int)(LEN(b[4]) / R);
    Py_BEGIN_ALLOW_THREADS
    if (switching)
        code = fb_advance_switching(&m, &bs, PTR(b[2]), LEN(b[2]), PTR(b[3]), t_end, PTR(b[4]), capacity, &nrec,
                                    PTR(b[5]), PTR(b[6]), PTR(b[7]), (int)(LEN(b[7]) / width), &nsw);
    else
        code = fb_advance(&m, &bs, PTR(b[2]), LEN(b[2]), PTR(b[3]), t_end, PTR(b[4]), capacity, &nrec, PTR(b[5]));
    Py_END_ALLOW_THREADS
    release(b, 8);
    if (code < 0) {
        PyErr_SetString(PyExc_ValueError, "advance: ctrl does not match the model's pairs");
        return NULL;
    }
    return Py_BuildValue("iii", code, nrec, nsw);
fail:
    release(b, 8);
    return NULL;
}

/* dense(model, basis, records, nrec, times, Y) */
PyObject *py_dense(PyObject *self, PyObject *args) {
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

/* column_max(model, basis, records, nrec, contacts, t0, t1, y0, y1, column, sign, lo, hi, reach, floor, xtol,
 * t_out, v_out): per bracket [lo, hi] the largest sign * output (column >= 0; the contact force of pair
 * -1 - column) on a phase's dense output, by Brent's method (extremes.c); brackets whose bound reach is below the
 * best value yet are skipped */
PyObject *py_column_max(PyObject *self, PyObject *args) {
    PyObject *om, *ob, *orec, *oc, *oy0, *oy1, *olo, *ohi, *ore, *oto, *ovo;
    int nrec, column;
    double t0, t1, sign, floor, xtol;
    if (!PyArg_ParseTuple(args, "OOOiOddOOidOOOddOO", &om, &ob, &orec, &nrec, &oc, &t0, &t1, &oy0, &oy1, &column,
                          &sign, &olo, &ohi, &ore, &floor, &xtol, &oto, &ovo))
        return NULL;
    buf_t b[11];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_basis bs;
    fb_contacts c;
    if (get_buf(om, &b[0], 0, "model") || get_buf(ob, &b[1], 0, "basis") || get_buf(orec, &b[2], 0, "records") ||
        get_buf(oc, &b[3], 0, "contacts") || get_buf(oy0, &b[4], 0, "y0") || get_buf(oy1, &b[5], 0, "y1") ||
        get_buf(olo, &b[6], 0, "lo") || get_buf(ohi, &b[7], 0, "hi") || get_buf(oto, &b[8], 1, "t_out") ||
        get_buf(ovo, &b[9], 1, "v_out") || get_buf(ore, &b[10], 0, "reach") || model_from(&b[0], &m) ||
        basis_from(&b[1], &bs) ||
        contacts_from(&b[3], &m, &c))
        goto fail;
    size_t count = LEN(b[6]), size = (size_t)fb_state_size(&m);
    if (nrec < 1 || LEN(b[2]) < (size_t)nrec * fb_record_size(bs.N, m.npairs) || LEN(b[4]) != size ||
        LEN(b[5]) != size || LEN(b[7]) != count || LEN(b[8]) != count || LEN(b[9]) != count || LEN(b[10]) != count ||
        column >= FB_NCOLS || column < -m.npairs) {
        PyErr_SetString(PyExc_ValueError, "column_max: bad column or array sizes");
        goto fail;
    }
    Py_BEGIN_ALLOW_THREADS
    fb_column_max(&m, &bs, PTR(b[2]), nrec, &c, t0, t1, PTR(b[4]), PTR(b[5]), column, sign, PTR(b[6]), PTR(b[7]),
                  PTR(b[10]), floor, (int)count, xtol, PTR(b[8]), PTR(b[9]));
    Py_END_ALLOW_THREADS
    release(b, 11);
    Py_RETURN_NONE;
fail:
    release(b, 11);
    return NULL;
}

/* moments(theta) -> (Cm_0..Cm_3, Sm_0..Sm_3) of propagation.c (for the tests) */
PyObject *py_moments(PyObject *self, PyObject *args) {
    double th, Cm[FB_P], Sm[FB_P];
    if (!PyArg_ParseTuple(args, "d", &th)) return NULL;
    fb_moments(th, Cm, Sm);
    return Py_BuildValue("(dddd)(dddd)", Cm[0], Cm[1], Cm[2], Cm[3], Sm[0], Sm[1], Sm[2], Sm[3]);
}

/* weights(w, h, s[, radau]) -> (C, SW, WS, RE (4), RV (4)) of one mode at the fraction s of a step h, its forcing
 * given at Gauss's nodes (radau: Radau IIA's; for the tests) */
PyObject *py_weights(PyObject *self, PyObject *args) {
    double w, h, s;
    int radau = 0;
    if (!PyArg_ParseTuple(args, "ddd|p", &w, &h, &s, &radau)) return NULL;
    fb_weight W;
    fb_weights(radau ? fb_radau() : fb_gauss(), w, h, s, &W);
    return Py_BuildValue("ddd(dddd)(dddd)", W.C, W.SW, W.WS, W.RE[0], W.RE[1], W.RE[2], W.RE[3], W.RV[0], W.RV[1],
                         W.RV[2], W.RV[3]);
}

/* damped_weights(w, d, h, s) -> (EE, EV, VE, VV, RE (4), RV (4)) of a damped mode (damped.c; for the tests):
 * eta = EE eta0 + EV v0 + RE . f, v = VE eta0 + VV v0 + RV . f for the nodal forcing f */
PyObject *py_damped_weights(PyObject *self, PyObject *args) {
    double w, d, h, s;
    if (!PyArg_ParseTuple(args, "dddd", &w, &d, &h, &s)) return NULL;
    fb_weight W;
    fb_weights_damped(fb_gauss(), w, d, h, s, &W);
    return Py_BuildValue("dddd(dddd)(dddd)", W.C, W.SW, -W.WS, W.CV, W.RE[0], W.RE[1], W.RE[2], W.RE[3], W.RV[0],
                         W.RV[1], W.RV[2], W.RV[3]);
}

/* damped_dissipation(w, d, h, a (4), eta0, v0, eta1, v1) -> d int_0^h v^2 dt of a damped mode whose forcing has
 * the monomial coefficients a in t / h (damped.c; for the tests) */
PyObject *py_damped_dissipation(PyObject *self, PyObject *args) {
    double w, d, h, a[4], e0, v0, e1, v1;
    if (!PyArg_ParseTuple(args, "ddd(dddd)dddd", &w, &d, &h, &a[0], &a[1], &a[2], &a[3], &e0, &v0, &e1, &v1))
        return NULL;
    return PyFloat_FromDouble(fb_mode_dissipation(w, d, h, a, e0, v0, e1, v1));
}

/* The buffers of a query on one phase's dense output -- model, basis, records (nrec), its end states y0, y1 -- into
 * b[0 .. 4], m and bs unpacked, the sizes checked; nonzero with a Python error set otherwise. */
static int phase_buffers(PyObject *om, PyObject *ob, PyObject *orec, int nrec, PyObject *oy0, PyObject *oy1,
                         buf_t *b, fb_model *m, fb_basis *bs, const char *name) {
    if (get_buf(om, &b[0], 0, "model") || get_buf(ob, &b[1], 0, "basis") || get_buf(orec, &b[2], 0, "records") ||
        get_buf(oy0, &b[3], 0, "y0") || get_buf(oy1, &b[4], 0, "y1") || model_from(&b[0], m) || basis_from(&b[1], bs))
        return -1;
    size_t size = (size_t)fb_state_size(m);
    if (nrec < 1 || LEN(b[2]) < (size_t)nrec * fb_record_size(bs->N, m->npairs) || LEN(b[3]) != size ||
        LEN(b[4]) != size) {
        PyErr_Format(PyExc_ValueError, "%s: array sizes do not match the model", name);
        return -1;
    }
    return 0;
}

/* pair_force(model, basis, records, nrec, contacts, t0, t1, y0, y1, pair, times, out): the contact force of
 * ``pair`` at ``times`` of a phase, as outputs gives it on the dense output's states (extremes.c) */
PyObject *py_pair_force(PyObject *self, PyObject *args) {
    PyObject *om, *ob, *orec, *oc, *oy0, *oy1, *ot, *oo;
    int nrec, pair;
    double t0, t1;
    if (!PyArg_ParseTuple(args, "OOOiOddOOiOO", &om, &ob, &orec, &nrec, &oc, &t0, &t1, &oy0, &oy1, &pair, &ot, &oo))
        return NULL;
    buf_t b[8];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_basis bs;
    fb_contacts c;
    if (phase_buffers(om, ob, orec, nrec, oy0, oy1, b, &m, &bs, "pair_force") || get_buf(oc, &b[5], 0, "contacts") ||
        get_buf(ot, &b[6], 0, "times") || get_buf(oo, &b[7], 1, "out") || contacts_from(&b[5], &m, &c))
        goto fail;
    if (LEN(b[7]) != LEN(b[6]) || pair < 0 || pair >= m.npairs) {
        PyErr_SetString(PyExc_ValueError, "pair_force: bad pair, or out not the size of times");
        goto fail;
    }
    Py_BEGIN_ALLOW_THREADS
    fb_pair_force_many(&m, &bs, PTR(b[2]), nrec, &c, t0, t1, PTR(b[3]), PTR(b[4]), pair, PTR(b[6]), (int)LEN(b[6]),
                       PTR(b[7]));
    Py_END_ALLOW_THREADS
    release(b, 8);
    Py_RETURN_NONE;
fail:
    release(b, 8);
    return NULL;
}

/* tip_slack(model, basis, records, nrec, t0, t1, y0, y1, a, z, T) -> (linear, rest, rounding): how far the tip's
 * deflection can exceed the larger of two samples T apart in [a, z] of a phase (extremes.c, tip_bound.c) */
PyObject *py_tip_slack(PyObject *self, PyObject *args) {
    PyObject *om, *ob, *orec, *oy0, *oy1;
    int nrec;
    double t0, t1, a, z, T, parts[3];
    if (!PyArg_ParseTuple(args, "OOOiddOOddd", &om, &ob, &orec, &nrec, &t0, &t1, &oy0, &oy1, &a, &z, &T)) return NULL;
    buf_t b[5];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_basis bs;
    if (phase_buffers(om, ob, orec, nrec, oy0, oy1, b, &m, &bs, "tip_slack")) goto fail;
    if (!(a <= z) || !(T > 0.0)) {
        PyErr_SetString(PyExc_ValueError, "tip_slack: a <= z and T > 0 needed");
        goto fail;
    }
    fb_tip_slack_at(&m, &bs, PTR(b[2]), nrec, t0, t1, PTR(b[3]), PTR(b[4]), a, z, T, parts);
    release(b, 5);
    return Py_BuildValue("(ddd)", parts[0], parts[1], parts[2]);
fail:
    release(b, 5);
    return NULL;
}

/* tip_slacks(model, basis, records, nrec, t0, t1, y0, y1, times, out): out[i] how far the tip's deflection can exceed
 * the larger of its values at times[i] and times[i + 1] (extremes.c; out has len(times) - 1 entries) */
PyObject *py_tip_slacks(PyObject *self, PyObject *args) {
    PyObject *om, *ob, *orec, *oy0, *oy1, *ot, *oo;
    int nrec;
    double t0, t1;
    if (!PyArg_ParseTuple(args, "OOOiddOOOO", &om, &ob, &orec, &nrec, &t0, &t1, &oy0, &oy1, &ot, &oo)) return NULL;
    buf_t b[7];
    memset(b, 0, sizeof b);
    fb_model m;
    fb_basis bs;
    if (phase_buffers(om, ob, orec, nrec, oy0, oy1, b, &m, &bs, "tip_slacks") || get_buf(ot, &b[5], 0, "times") ||
        get_buf(oo, &b[6], 1, "out"))
        goto fail;
    if (LEN(b[5]) < 2 || LEN(b[6]) != LEN(b[5]) - 1) {
        PyErr_SetString(PyExc_ValueError, "tip_slacks: two times or more, and out one shorter than times");
        goto fail;
    }
    Py_BEGIN_ALLOW_THREADS
    fb_tip_slacks(&m, &bs, PTR(b[2]), nrec, t0, t1, PTR(b[3]), PTR(b[4]), PTR(b[5]), (int)LEN(b[5]), PTR(b[6]));
    Py_END_ALLOW_THREADS
    release(b, 7);
    Py_RETURN_NONE;
fail:
    release(b, 7);
    return NULL;
}

/* dense_bounds(omega, damp, h, eta0, v0, f, jm, gamma, dx) -> (curve, fast): fb_dense_bounds (events.c) for modes
 * of frequencies omega and damping coefficients damp over a step of length h from (eta0, v0) with the nodal forcing
 * f (FB_P x N, node-major) */
PyObject *py_dense_bounds(PyObject *self, PyObject *args) {
    PyObject *o[6];
    double h, gamma, dx, fast;
    if (!PyArg_ParseTuple(args, "OOdOOOOdd", &o[0], &o[1], &h, &o[2], &o[3], &o[4], &o[5], &gamma, &dx)) return NULL;
    static const char *names[6] = {"omega", "damp", "eta0", "v0", "f", "jm"};
    buf_t b[6];
    memset(b, 0, sizeof b);
    for (int i = 0; i < 6; i++)
        if (get_buf(o[i], &b[i], 0, names[i])) goto fail;
    size_t N = LEN(b[0]);
    if (N < 1 || N > FB_MAXN || LEN(b[1]) != N || LEN(b[2]) != N || LEN(b[3]) != N || LEN(b[4]) != FB_P * N ||
        LEN(b[5]) != N || !(h > 0.0) || !(dx > 0.0)) {
        PyErr_SetString(PyExc_ValueError, "dense_bounds: N = len(omega) in [1, 66], f of FB_P x N, h > 0, dx > 0");
        goto fail;
    }
    fb_basis bs;
    memset(&bs, 0, sizeof bs);
    bs.N = (int)N, bs.omega = PTR(b[0]), bs.damp = PTR(b[1]);
    fb_phase ph;
    memset(&ph, 0, sizeof ph);
    ph.b = &bs;
    ph.tb = fb_gauss();
    fb_dense d = {&ph, 0.0, h, PTR(b[2]), PTR(b[3]), PTR(b[4]), 0, ph.tb};
    double curve = fb_dense_bounds(&d, PTR(b[5]), gamma, dx, &fast);
    release(b, 6);
    return Py_BuildValue("(dd)", curve, fast);
fail:
    release(b, 6);
    return NULL;
}

/* nodes([radau]) -> the collocation's Gauss nodes on (0, 1) (radau: its Radau IIA nodes on (0, 1]) */
PyObject *py_nodes(PyObject *self, PyObject *args) {
    int radau = 0;
    if (!PyArg_ParseTuple(args, "|p", &radau)) return NULL;
    const fb_tables *t = radau ? fb_radau() : fb_gauss();
    return Py_BuildValue("dddd", t->c[0], t->c[1], t->c[2], t->c[3]);
}

PyObject *py_sizes(PyObject *self, PyObject *args) {
    int N, S;
    if (!PyArg_ParseTuple(args, "ii", &N, &S)) return NULL;
    return Py_BuildValue("iiiii", fb_record_size(N, S), fb_state_buffer_size(N, S), FB_P, FB_NCOLS, FB_PAIR_COLS);
}
