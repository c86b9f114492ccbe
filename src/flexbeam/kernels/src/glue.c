/* The buffer helpers of the Python glue (glue.h): the argument arrays as C-contiguous float64 buffers, and the
 * model, contacts and basis buffers unpacked, each with a Python exception on a mismatch. */
#include "glue.h"

int get_buf(PyObject *obj, buf_t *b, int writable, const char *name) {
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

void release(buf_t *bufs, int count) {
    for (int i = 0; i < count; i++)
        if (bufs[i].held) PyBuffer_Release(&bufs[i].view);
}

int model_from(buf_t *b, fb_model *m) {
    if (fb_model_unpack(m, PTR(*b), LEN(*b))) {
        PyErr_SetString(PyExc_ValueError, "model: buffer does not match the kernel layout");
        return -1;
    }
    return 0;
}

int contacts_from(buf_t *b, const fb_model *m, fb_contacts *c) {
    if (fb_contacts_unpack(c, m, PTR(*b), LEN(*b))) {
        PyErr_SetString(PyExc_ValueError, "contacts: buffer does not match the model's pairs");
        return -1;
    }
    return 0;
}

int basis_from(buf_t *b, fb_basis *bs) {
    if (fb_basis_unpack(bs, PTR(*b), LEN(*b))) {
        PyErr_SetString(PyExc_ValueError, "basis: buffer does not match the kernel layout");
        return -1;
    }
    return 0;
}
