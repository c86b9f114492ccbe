/* The compiled kernels' Python module, flexbeam.kernels._core: its method table and init.  The functions are
 * in glue_model.c, glue_integrator.c and glue_math.c (declared in glue.h, which describes the glue). */
#include "glue.h"

static PyMethodDef methods[] = {
    {"rhs", py_rhs, METH_VARARGS, "rhs(model, t, y, contacts, dy, F) -> torque"},
    {"contact_forces", py_contact_forces, METH_VARARGS,
     "contact_forces(model, t, y, contacts, F, Ft) -> status: normal forces, sticking pairs' tangential multipliers"},
    {"outputs", py_outputs, METH_VARARGS, "outputs(model, times, Y, contacts, cols, mv, pcols)"},
    {"kinematics", py_kinematics, METH_VARARGS, "kinematics(model, point, t, y, out)"},
    {"gap", py_gap, METH_VARARGS, "gap(model, pair, t, y, J) -> (delta, rate, gamma, nx, ny, x)"},
    {"tangent", py_tangent, METH_VARARGS, "tangent(model, pair, t, y, J, Jt) -> (delta, rate, slip velocity, nx, ny)"},
    {"nearest_path", py_nearest_path, METH_VARARGS,
     "nearest_path(model, pair, t, Y, warm, out) -> full scans: rows [delta, x, nx, ny], the pair's gap and point"},
    {"equations", py_equations, METH_VARARGS, "equations(model, t, y, M, Q, E)"},
    {"law_force", py_law_force, METH_VARARGS, "law_force(p, d, dd) -> (F, Fk, dF/dd, dF/ddd)"},
    {"normal_jump", py_normal_jump, METH_VARARGS,
     "normal_jump(model, pair, t, y, e, y_plus, out) -> status: one frictionless pair's impulse map (impulse_map.c)"},
    {"advance", py_advance, METH_VARARGS,
     "advance(model, basis, ctrl, state, t_end, records, info[, coef, switches]) -> (code, nrec, nswitch)"},
    {"dense", py_dense, METH_VARARGS, "dense(model, basis, records, nrec, times, Y)"},
    {"column_max", py_column_max, METH_VARARGS,
     "column_max(model, basis, records, nrec, contacts, t0, t1, y0, y1, column, sign, lo, hi, reach, floor, xtol, "
     "t_out, v_out)"},
    {"pair_force", py_pair_force, METH_VARARGS,
     "pair_force(model, basis, records, nrec, contacts, t0, t1, y0, y1, pair, times, out): a pair's contact force"},
    {"tip_slack", py_tip_slack, METH_VARARGS,
     "tip_slack(model, basis, records, nrec, t0, t1, y0, y1, a, z, T) -> (linear, rest, rounding): the tip's bound"},
    {"tip_slacks", py_tip_slacks, METH_VARARGS,
     "tip_slacks(model, basis, records, nrec, t0, t1, y0, y1, times, out): the tip's bound between the times"},
    {"dense_bounds", py_dense_bounds, METH_VARARGS,
     "dense_bounds(omega, damp, h, eta0, v0, f, jm, gamma, dx) -> (curve, fast): the event search's bounds"},
    {"moments", py_moments, METH_VARARGS, "moments(theta) -> (Cm, Sm)"},
    {"weights", py_weights, METH_VARARGS, "weights(w, h, s[, radau]) -> (C, SW, WS, RE, RV)"},
    {"damped_weights", py_damped_weights, METH_VARARGS, "damped_weights(w, d, h, s) -> (EE, EV, VE, VV, RE, RV)"},
    {"damped_dissipation", py_damped_dissipation, METH_VARARGS,
     "damped_dissipation(w, d, h, a, eta0, v0, eta1, v1) -> d int v^2 dt"},
    {"nodes", py_nodes, METH_VARARGS, "nodes([radau]) -> the collocation's Gauss (or Radau IIA) nodes on (0, 1]"},
    {"sizes", py_sizes, METH_VARARGS,
     "sizes(N, npairs) -> (record size, state buffer size, nodes, output columns, columns per pair)"},
    {"unary", py_unary, METH_VARARGS, "unary(code, x) -> f(x): detmath's sin, cos, exp, expm1, log, log1p, tgamma"},
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
