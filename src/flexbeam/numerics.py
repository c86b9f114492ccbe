"""Arithmetic that gives the same bits on every machine: the elementary functions, sums and small dense linear
algebra that feed a simulation.

Why.  numpy's ``@``, ``dot`` and ``linalg`` call whichever BLAS/LAPACK kernel OpenBLAS (or MKL) picks for the CPU,
numpy's ``exp``/``sin``/``cos`` run SIMD loops chosen by CPU, and glibc's libm picks an FMA variant of ``exp``,
``sin``, ``cos`` and ``pow`` at run time: the same case gives results that differ in the last bits from one
machine to the next.  An event-driven impact simulation amplifies such a bit -- a step accepted on one machine is
rejected on the other, an impact at 1e-6 m/s exists on one and not the other -- into a different contact count.
Everything that determines a run of the modal model therefore goes through this module or the compiled kernels:

* elementary functions: ``kernels/src/detmath*.c`` (only +, -, *, / and sqrt, which IEEE 754 rounds correctly);
* sums: :func:`math.fsum` (correctly rounded) or the fixed order of ``kernels/src/linalg.c``;
* linear algebra: ``kernels/src/linalg.c`` (fixed summation order, no contraction);
* numpy only for what IEEE 754 makes exact: elementwise +, -, *, /, sqrt, abs, comparisons, copies.

The results of the modal model are then a function of the case alone (``docs/methods.md``, "The same answer on
every machine"); the tests run the presets under several BLAS kernels and SIMD levels and compare the bits.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .kernels import _core

_SIN, _COS, _EXP, _EXPM1, _LOG, _LOG1P, _GAMMA = range(7)
_POW, _ATAN2 = 0, 1


def _unary(code: int, x):
    if type(x) is float:  # (the common case, without np.ndim's ~0.5 us)
        return _core.unary(code, x)
    if np.ndim(x) == 0:
        return _core.unary(code, float(x))
    a = np.ascontiguousarray(x, dtype=float)
    out = np.empty_like(a)
    _core.vunary(code, a.reshape(-1), out.reshape(-1))
    return out


def _binary(code: int, a, b):
    if type(a) is float and type(b) is float:  # (the common case, without np.ndim's ~0.5 us)
        return _core.binary(code, a, b)
    if np.ndim(a) == 0 and np.ndim(b) == 0:
        return _core.binary(code, float(a), float(b))
    A, B = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
    A, B = np.ascontiguousarray(A), np.ascontiguousarray(B)
    out = np.empty(A.shape)
    _core.vbinary(code, A.reshape(-1), B.reshape(-1), out.reshape(-1))
    return out


def sin(x):
    """sin x (float or array)."""
    return _unary(_SIN, x)


def cos(x):
    """cos x (float or array)."""
    return _unary(_COS, x)


def exp(x):
    """e^x (float or array)."""
    return _unary(_EXP, x)


def expm1(x):
    """e^x - 1, accurate near 0 (float or array)."""
    return _unary(_EXPM1, x)


def log(x):
    """Natural logarithm (float or array; x > 0)."""
    return _unary(_LOG, x)


def log1p(x):
    """log(1 + x), accurate near 0 (float or array)."""
    return _unary(_LOG1P, x)


def gamma(x):
    """Gamma(x) for x > 0 (float or array)."""
    return _unary(_GAMMA, x)


def pow(x, y):  # noqa: A001 - the name of the function it replaces
    """x^y (floats or arrays, broadcast)."""
    return _binary(_POW, x, y)


def atan2(y, x):
    """The angle of (x, y) in (-pi, pi] (floats or arrays, broadcast)."""
    return _binary(_ATAN2, y, x)


def cosh(x):
    """cosh x = (e^x + e^-x) / 2."""
    e = exp(x)
    return 0.5 * (e + 1.0 / e)


def tanh(x):
    """tanh x = (1 - e^-2|x|) / (1 + e^-2|x|) with the sign of x."""
    if np.ndim(x) == 0:
        t = exp(-2.0 * abs(float(x)))
        return math.copysign((1.0 - t) / (1.0 + t), float(x))
    x = np.asarray(x, dtype=float)
    t = exp(-2.0 * np.abs(x))
    return np.copysign((1.0 - t) / (1.0 + t), x)


def asin(s: float) -> float:
    """arcsin s for |s| <= 1: the angle of (sqrt(1 - s^2), s)."""
    return atan2(s, math.sqrt(max(0.0, (1.0 - s) * (1.0 + s))))


def hypot(a: float, b: float) -> float:
    """sqrt(a^2 + b^2), scaled against overflow."""
    a, b = abs(float(a)), abs(float(b))
    big, small = (a, b) if a >= b else (b, a)
    if big == 0.0 or not math.isfinite(big):
        return big
    r = small / big
    return big * math.sqrt(1.0 + r * r)


def integer_power(x, k: int):
    """x^k for a small integer k >= 0 by repeated multiplication (exact for k <= 2, deterministic always)."""
    out = np.ones_like(np.asarray(x, dtype=float)) if np.ndim(x) else 1.0
    for _ in range(k):
        out = out * x
    return out


# ----------------------------------------------------------------------------------------------- sums, products
def fsum(x) -> float:
    """The correctly rounded sum of the entries of ``x`` (:func:`math.fsum`)."""
    return math.fsum(np.asarray(x, dtype=float).reshape(-1).tolist())


def dot(a, b) -> float:
    """sum_i a_i b_i, the products summed by :func:`math.fsum` (correctly rounded: independent of order)."""
    a = np.asarray(a, dtype=float).reshape(-1)
    b = np.asarray(b, dtype=float).reshape(-1)
    if a.size != b.size:
        raise ValueError(f"dot: sizes {a.size} and {b.size} differ")
    return math.fsum((a * b).tolist())


def matmul(A, B) -> np.ndarray:
    """A @ B for 1-D or 2-D arrays (numpy's conventions), each entry summed in increasing index order."""
    A = np.asarray(A, dtype=float)
    B = np.asarray(B, dtype=float)
    a2 = A if A.ndim == 2 else A.reshape(1, -1)
    b2 = B if B.ndim == 2 else B.reshape(-1, 1)
    m, k = a2.shape
    k2, n = b2.shape
    if k != k2:
        raise ValueError(f"matmul: shapes {A.shape} and {B.shape} do not match")
    C = np.empty((m, n))
    _core.matmul(np.ascontiguousarray(a2), np.ascontiguousarray(b2), C, m, k, n)
    if A.ndim == 1 and B.ndim == 1:
        return C[0, 0]
    if A.ndim == 1:
        return C[0]
    if B.ndim == 1:
        return C[:, 0]
    return C


def gram(A, w, B=None) -> np.ndarray:
    """A^T diag(w) B (B = A by default): a quadrature of products of columns, summed over the rows in order."""
    A = np.ascontiguousarray(A, dtype=float)
    B = A if B is None else np.ascontiguousarray(B, dtype=float)
    w = np.ascontiguousarray(w, dtype=float)
    m, ka = A.shape
    mb, kb = B.shape
    if mb != m or w.size != m:
        raise ValueError("gram: A, w and B must have the same number of rows")
    C = np.empty((ka, kb))
    _core.gram(A, w, B, C, m, ka, kb)
    return C


def solve(A, B) -> np.ndarray:
    """A^-1 B (B a vector or a matrix) by LU with partial pivoting; :class:`numpy.linalg.LinAlgError` if A is
    singular."""
    A = np.array(A, dtype=float, order="C")
    B = np.asarray(B, dtype=float)
    n = A.shape[0]
    if A.shape != (n, n) or B.shape[0] != n:
        raise ValueError(f"solve: shapes {A.shape} and {B.shape} do not match")
    X = np.array(B.reshape(n, -1), dtype=float, order="C")
    if _core.solve(A, X, n, X.shape[1]):
        raise np.linalg.LinAlgError("singular matrix")
    return X.reshape(B.shape)


def inv(A) -> np.ndarray:
    """A^-1."""
    n = np.shape(A)[0]
    return solve(A, np.eye(n))


def cholesky(A) -> np.ndarray:
    """The lower factor L of A = L L^T; :class:`numpy.linalg.LinAlgError` if A is not positive definite."""
    L = np.array(A, dtype=float, order="C")
    if _core.cholesky(L, L.shape[0]):
        raise np.linalg.LinAlgError("matrix is not positive definite")
    return L


def eigh(A) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (ascending) and eigenvectors (columns) of a symmetric matrix, by the cyclic Jacobi method;
    each eigenvector's largest component is positive."""
    S = np.array(A, dtype=float, order="C")
    n = S.shape[0]
    w, V = np.empty(n), np.empty((n, n))
    if _core.eigh(S, n, w, V) < 0:
        raise np.linalg.LinAlgError("eigh: the Jacobi sweeps did not converge")
    return w, V


def lstsq_symmetric(W, b, rcond: float = 1e-12) -> np.ndarray:
    """The least-norm least-squares solution of W x = b for a symmetric W (the Moore-Penrose inverse from the
    eigen-decomposition, eigenvalues below ``rcond`` times the largest magnitude dropped) -- what
    ``numpy.linalg.lstsq`` gives for a symmetric matrix."""
    w, V = eigh(W)
    top = float(np.max(np.abs(w), initial=0.0))
    keep = np.abs(w) > rcond * top
    c = matmul(np.ascontiguousarray(V.T), np.asarray(b, dtype=float))
    c = np.where(keep, c / np.where(keep, w, 1.0), 0.0)
    return matmul(V, c)


# ----------------------------------------------------------------------------------------------- quadrature
@functools.cache
def leggauss(m: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes (ascending) and weights on [-1, 1] with ``m`` points.

    Newton's method on the three-term recurrence of the Legendre polynomials from Tricomi's initial guesses
    x_i ~ cos(pi (i - 1/4) / (m + 1/2)) (Abramowitz & Stegun 22.16.6; Press et al., Numerical Recipes, Sec. 4.6),
    all nodes at once; weights 2 / ((1 - x^2) P_m'(x)^2); symmetrised.  Only elementwise arithmetic: the same bits
    everywhere (numpy's ``leggauss`` starts from LAPACK eigenvalues).
    """
    if m < 1:
        raise ValueError("leggauss: m must be >= 1")
    i = np.arange(1, m + 1, dtype=float)
    x = cos(math.pi * (i - 0.25) / (m + 0.5))
    dp = np.ones(m)
    for _ in range(100):
        p0, p1 = np.ones(m), x.copy()
        for k in range(1, m):
            p0, p1 = p1, ((2 * k + 1) * x * p1 - k * p0) / (k + 1)
        dp = m * (x * p1 - p0) / (x * x - 1.0) if m > 1 else np.ones(m)
        dx = p1 / dp
        x = x - dx
        if float(np.max(np.abs(dx))) <= 1e-15:
            break
    p0, p1 = np.ones(m), x.copy()
    for k in range(1, m):
        p0, p1 = p1, ((2 * k + 1) * x * p1 - k * p0) / (k + 1)
    dp = m * (x * p1 - p0) / (x * x - 1.0) if m > 1 else np.ones(m)
    w = 2.0 / ((1.0 - x * x) * dp * dp)
    x, w = x[::-1].copy(), w[::-1].copy()
    x = 0.5 * (x - x[::-1])
    w = 0.5 * (w + w[::-1])
    return x, w


__all__ = [
    "asin", "atan2", "cholesky", "cos", "cosh", "dot", "eigh", "exp", "expm1", "fsum", "gamma", "gram", "hypot",
    "integer_power", "inv", "leggauss", "log", "log1p", "lstsq_symmetric", "matmul", "pow", "sin", "solve", "tanh",
]  # fmt: skip
