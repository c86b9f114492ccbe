"""Clamped-free (cantilever) Euler-Bernoulli eigenfunctions in a stable form.

The classical form

    phi(x) = cosh(bx) - cos(bx) - sigma (sinh(bx) - sin(bx)),
    sigma = (cosh(bL) + cos(bL)) / (sinh(bL) + sin(bL)),

loses all digits for high modes (cosh - sigma sinh cancels).  Writing
cosh(a) - sigma sinh(a) = 1/2 e^{-a} (1 + sigma) + 1/2 e^{a} (1 - sigma) and

    1/2 e^{bL} (1 - sigma) = (sin bL - cos bL - e^{-bL}) / (1 - e^{-2bL} + 2 e^{-bL} sin bL)

keeps every exponential argument <= 0, so the modes are accurate for any index
(see e.g. Gonçalves et al., J. Sound Vib. 2007 for the same idea).  The normalisation
is the classical one, int_0^L phi^2 dx = L, |phi(L)| = 2.

The roots b_k L of cos(bL) cosh(bL) = -1 are found by :func:`scipy.optimize.brentq`
on the bounded form cos(z) + 1/cosh(z) = 0 near (2k - 1) pi / 2.
"""

from __future__ import annotations

import functools
import math

import numpy as np


@functools.cache
def _root(k: int) -> float:
    """k-th root of cos z + 1/cosh z = 0 (i.e. cos z cosh z = -1) by Newton's method.

    Started at 1.875 (k = 1) or the asymptote (2k - 1) pi/2, where |f'| ~ 1 and the
    correction is below 1/cosh z: quadratic convergence to round-off in a few steps
    (scipy.optimize is not imported for this, to keep start-up short).
    """
    z = 1.875 if k == 1 else (2 * k - 1) * math.pi / 2
    for _ in range(50):
        f = math.cos(z) + 1.0 / math.cosh(z)
        df = -math.sin(z) - math.tanh(z) / math.cosh(z)
        step = f / df
        z -= step
        if abs(step) <= 4e-16 * z:
            break
    return z


def cantilever_roots(n: int) -> np.ndarray:
    """First ``n`` roots beta_k L of cos(bL) cosh(bL) = -1 (1.8751, 4.6941, 7.8548, ...)."""
    return np.array([_root(k) for k in range(1, n + 1)], dtype=float)


def cantilever_modes(x: np.ndarray, length: float, n: int, derivative: int = 0) -> np.ndarray:
    """Clamped-free mode shapes (or their derivatives) at points ``x``.

    Parameters
    ----------
    x
        Material coordinates in [0, L] [m], shape (m,).
    length
        Beam length L [m].
    n
        Number of modes.
    derivative
        0, 1, 2 or 3: which derivative d^k phi / dx^k to return.

    Returns
    -------
    ndarray, shape (m, n)
        ``out[i, k] = phi_k^(derivative)(x_i)``.
    """
    x = np.atleast_1d(np.asarray(x, dtype=float))
    out = np.empty((x.size, n))
    if n == 0:
        return out
    bl = cantilever_roots(n)
    for k, z in enumerate(bl):
        b = z / length
        em = math.exp(-z)
        den = 1.0 - em * em + 2.0 * em * math.sin(z)
        sigma = (1.0 + em * em + 2.0 * em * math.cos(z)) / den
        a_plus = (math.sin(z) - math.cos(z) - em) / den  # = 1/2 e^{bL}(1 - sigma)
        bx = b * x
        e_minus = 0.5 * (1.0 + sigma) * np.exp(-bx)  # 1/2 (1 + sigma) e^{-bx}
        e_plus = a_plus * np.exp(bx - z)  # 1/2 (1 - sigma) e^{bx}
        c, s = np.cos(bx), np.sin(bx)
        if derivative == 0:
            val = e_minus + e_plus - c + sigma * s
        elif derivative == 1:
            val = b * (-e_minus + e_plus + s + sigma * c)
        elif derivative == 2:
            val = b**2 * (e_minus + e_plus + c - sigma * s)
        elif derivative == 3:
            val = b**3 * (-e_minus + e_plus - s - sigma * c)
        else:
            raise ValueError("derivative: must be 0, 1, 2 or 3")
        out[:, k] = val
    return out
