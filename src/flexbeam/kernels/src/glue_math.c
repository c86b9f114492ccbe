/* The Python glue of the numerics (glue.h): the elementary functions of detmath_*.c and the fixed-order linear
 * algebra of linalg.c. */
#include "glue.h"
#include "linalg.h"

typedef double (*unary_fn)(double);
static const unary_fn UNARY[] = {fb_sin, fb_cos, fb_exp, fb_expm1, fb_log, fb_log1p, fb_tgamma};
#define N_UNARY ((int)(sizeof UNARY / sizeof UNARY[0]))

/* unary(code, x) -> f(x) for a float x (code: sin, cos, exp, expm1, log, log1p, tgamma) */
PyObject *py_unary(PyObject *self, PyObject *args) {
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
PyObject *py_vunary(PyObject *self, PyObject *args) {
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
PyObject *py_binary(PyObject *self, PyObject *args) {
    int code;
    double a, c;
    if (!PyArg_ParseTuple(args, "idd", &code, &a, &c)) return NULL;
    return PyFloat_FromDouble(code == 0 ? fb_pow(a, c) : fb_atan2(a, c));
}

/* vbinary(code, a, b, out): out[i] = pow(a[i], b[i]) or atan2(a[i], b[i]); a or b may have size 1 */
PyObject *py_vbinary(PyObject *self, PyObject *args) {
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
PyObject *py_matmul(PyObject *self, PyObject *args) {
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
PyObject *py_gram(PyObject *self, PyObject *args) {
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
PyObject *py_solve(PyObject *self, PyObject *args) {
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
PyObject *py_cholesky(PyObject *self, PyObject *args) {
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
PyObject *py_eigh(PyObject *self, PyObject *args) {
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
