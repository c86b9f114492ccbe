/* The Python glue of the compiled kernels: every argument array is a C-contiguous float64 buffer (numpy arrays),
 * outputs are written into caller-allocated buffers.  The model and basis buffers are packed once per system
 * by flexbeam.kernels.layout and unpacked per call (a few pointer assignments).
 *
 * module.c holds the method table and the module's init; the functions it lists are in glue_model.c (the model's
 * equations, kinematics and contact laws), glue_integrator.c (the phase driver, dense output and the integrator's
 * tables) and glue_math.c (the elementary functions of detmath_*.c and the linear algebra of linalg.c); glue.c
 * holds the buffer helpers.  Include this header first (it includes Python.h). */
#ifndef FLEXBEAM_GLUE_H
#define FLEXBEAM_GLUE_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <string.h>

#include "flexbeam.h"

/* hidden: shared between the glue's files, not exported from the extension (PyInit__core and the fb_ kernels are) */
#if defined(__GNUC__)
#define FB_GLUE __attribute__((visibility("hidden")))
#else
#define FB_GLUE
#endif

typedef struct {
    Py_buffer view;
    int held;
} buf_t;

/* b = the buffer of obj, a C-contiguous float64 array (writable if asked); else a TypeError naming it, -1 */
FB_GLUE int get_buf(PyObject *obj, buf_t *b, int writable, const char *name);
/* release the held buffers among bufs[0..count) */
FB_GLUE void release(buf_t *bufs, int count);

#define LEN(b) ((size_t)((b).view.len / 8))
#define PTR(b) ((double *)(b).view.buf)

/* the model, contacts (of the model's pairs) and basis buffers unpacked; else a ValueError, -1 */
FB_GLUE int model_from(buf_t *b, fb_model *m);
FB_GLUE int contacts_from(buf_t *b, const fb_model *m, fb_contacts *c);
FB_GLUE int basis_from(buf_t *b, fb_basis *bs);

/* glue_model.c */
FB_GLUE PyObject *py_rhs(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_contact_forces(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_outputs(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_kinematics(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_gap(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_tangent(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_nearest_path(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_equations(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_law_force(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_normal_jump(PyObject *self, PyObject *args);

/* glue_integrator.c */
FB_GLUE PyObject *py_advance(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_dense(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_column_max(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_tip_slack(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_tip_slacks(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_dense_bounds(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_pair_force(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_moments(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_weights(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_damped_weights(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_damped_dissipation(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_nodes(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_sizes(PyObject *self, PyObject *args);

/* glue_math.c */
FB_GLUE PyObject *py_unary(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_vunary(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_binary(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_vbinary(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_matmul(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_gram(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_solve(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_cholesky(PyObject *self, PyObject *args);
FB_GLUE PyObject *py_eigh(PyObject *self, PyObject *args);

#endif
