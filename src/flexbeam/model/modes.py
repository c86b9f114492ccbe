"""Euler-Bernoulli eigenfunctions of a beam on a rotating hub, in a numerically stable form.

Two families of shape functions serve the two body frames of :mod:`flexbeam.model.beam`
(``docs/formulation.md``):

* **clamped-free** (the hub frame): the cantilever modes, u(0) = u'(0) = 0;
* **hub + beam** (the system frame of a free or torque-driven joint): the flexible eigenmodes
  of the linear system of a hub of inertia J_h and radius r_h, free to turn about O, carrying
  the beam clamped to its rim.  The beam root then moves with the hub angle alpha,
  u(0) = r_h u'(0), u'(0) = alpha, and the hub's moment balance is the boundary condition

      J_h alpha'' = EI (u''(0) - r_h u'''(0)),   i.e.   -J_h w^2 u'(0) = EI (u''(0) - r_h u'''(0)).

  (from the variation of 1/2 J_h alpha'^2 + int 1/2 mu u'^2 - 1/2 EI u''^2 with
  du(0) = r_h d alpha, du'(0) = d alpha).  J_h = 0, r_h = 0 gives the pinned-free beam
  (tan bL = tanh bL); J_h -> inf the clamped-free one.  The modes are orthogonal to the rigid
  rotation (u = r_h + x, alpha = 1) and to each other in the kinetic-energy inner product
  <u, v> = int mu u v dx + J_h u'(0) v'(0).

Stable form.  The free end (u'' = u''' = 0 at x = L) leaves two constants; with xi = x/L,
z = beta L, E = e^-z,

    u(xi) = c e^(-z xi) + (a - c E) e^(-z (1 - xi)) + a cos z(1 - xi) + (2 c E - a) sin z(1 - xi),

in which every exponential has a non-positive argument, so the modes are accurate for any
index (the classical cosh/sinh form loses all digits for high modes; Goncalves et al.,
J. Sound Vib. 2007 use the same idea).  The two root conditions are a 2 x 2 linear system in
(a, c) whose determinant, scaled to O(1), is the characteristic function; its k-th positive
root lies between the k-th and (k+1)-th clamped-free roots (a rank-one relaxation of the
clamped constraint interlaces the spectra), where it is bracketed and refined.

Normalisation: int_0^L u^2 dx + (J_h / mu) u'(0)^2 = L (the classical int phi^2 dx = L for the
cantilever, |phi(L)| = 2), with the sign of the cantilever convention, sign u_k(L) = (-1)^(k+1).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from .. import numerics as nm


@functools.cache
def _root(k: int) -> float:
    """k-th root of cos z + 1/cosh z = 0 (i.e. cos z cosh z = -1) by Newton's method.

    Started at 1.875 (k = 1) or the asymptote (2k - 1) pi/2, where |f'| ~ 1 and the
    correction is below 1/cosh z: quadratic convergence to round-off in a few steps
    (scipy.optimize is not imported for this, to keep start-up short).
    """
    z = 1.875 if k == 1 else (2 * k - 1) * math.pi / 2
    for _ in range(50):
        ch = nm.cosh(z)
        f = nm.cos(z) + 1.0 / ch
        df = -nm.sin(z) - nm.tanh(z) / ch
        step = f / df
        z -= step
        if abs(step) <= 4e-16 * z:
            break
    return z


def cantilever_roots(n: int) -> np.ndarray:
    """First ``n`` roots beta_k L of cos(bL) cosh(bL) = -1 (1.8751, 4.6941, 7.8548, ...)."""
    return np.array([_root(k) for k in range(1, n + 1)], dtype=float)


def _root_rows(z: float, inertia: float, radius: float) -> tuple[float, float, float, float]:
    """The two root conditions as rows (r1a, r1c), (r2a, r2c) in the constants (a, c), scaled to O(1).

    ``inertia`` = J_h / (mu L^3) (``inf``: clamped), ``radius`` = r_h / L.  Row 1 is
    u(0) - r_h u'(0) = 0, row 2 is J_h w^2 u'(0) + EI (u''(0) - r_h u'''(0)) = 0 divided by EI/L^2
    (with w^2 = EI beta^4 / mu), each divided by its largest coefficient scale.
    """
    E = nm.exp(-z)
    c, s = nm.cos(z), nm.sin(z)
    # u(0), u'(0) L / z, u''(0) L^2 / z^2, u'''(0) L^3 / z^3 as (coefficient of a, coefficient of c)
    a0, c0 = E + c - s, 1.0 - E * E + 2.0 * E * s
    a1, c1 = E + s + c, -1.0 - E * E - 2.0 * E * c
    a2, c2 = E - c + s, 1.0 - E * E - 2.0 * E * s
    a3, c3 = E - s - c, -1.0 - E * E + 2.0 * E * c
    rz = radius * z
    r1a, r1c = (a0 - rz * a1) / (1.0 + rz), (c0 - rz * c1) / (1.0 + rz)
    if math.isinf(inertia):
        return r1a, r1c, a1, c1
    jz3 = inertia * (z * z * z)
    scale = 1.0 + jz3 + rz
    return r1a, r1c, (jz3 * a1 + a2 - rz * a3) / scale, (jz3 * c1 + c2 - rz * c3) / scale


def _characteristic(z: float, inertia: float, radius: float) -> float:
    r1a, r1c, r2a, r2c = _root_rows(z, inertia, radius)
    return r1a * r2c - r1c * r2a


def _illinois(f, a: float, b: float, fa: float, fb: float) -> float:
    """Root of f in the bracket [a, b] (fa fb < 0) by the Illinois variant of regula falsi
    (Dowell & Jarratt 1971): superlinear, always bracketed (scipy.optimize is not imported
    at start-up)."""
    side = 0
    for _ in range(200):
        m = (a * fb - b * fa) / (fb - fa)
        fm = f(m)
        if fm == 0.0 or abs(b - a) <= 4e-16 * abs(m):
            return m
        if (fm > 0.0) == (fb > 0.0):
            b, fb = m, fm
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a, fa = m, fm
            if side == 1:
                fb *= 0.5
            side = 1
    return 0.5 * (a + b)


def hub_beam_roots(n: int, inertia: float, radius: float) -> np.ndarray:
    """First ``n`` flexible roots beta_k L of the hub + beam system.

    Parameters
    ----------
    n
        Number of roots.
    inertia
        Hub inertia ratio J_h / (mu L^3) (``math.inf``: clamped-free).
    radius
        Hub radius ratio r_h / L.
    """
    if math.isinf(inertia):
        return cantilever_roots(n)
    clamped = cantilever_roots(n + 1)
    f = lambda z: _characteristic(z, inertia, radius)  # noqa: E731
    out = np.empty(n)
    for k in range(n):
        lo, hi = clamped[k] * (1.0 + 1e-13), clamped[k + 1] * (1.0 - 1e-13)
        grid = np.linspace(lo, hi, 9)
        vals = [f(z) for z in grid]
        root = clamped[k]  # a very heavy hub: the root sits within round-off above the clamped one
        for i in range(len(grid) - 1):
            if vals[i] == 0.0:
                root = grid[i]
                break
            if (vals[i] > 0.0) != (vals[i + 1] > 0.0):
                root = _illinois(f, grid[i], grid[i + 1], vals[i], vals[i + 1])
                break
        out[k] = root
    return out


def _stable_terms(z: float, xi: np.ndarray):
    """e^(-z xi), e^(-z (1 - xi)), cos z(1 - xi), sin z(1 - xi)."""
    arg = z * (1.0 - xi)
    return nm.exp(-z * xi), nm.exp(-arg), nm.cos(arg), nm.sin(arg)


def _combine(z, a, c, terms, derivative):
    e1, e2, co, si = terms
    E = nm.exp(-z)
    d, b = a - c * E, 2.0 * c * E - a
    if derivative == 0:
        return c * e1 + d * e2 + a * co + b * si
    if derivative == 1:
        return -c * e1 + d * e2 + a * si - b * co
    if derivative == 2:
        return c * e1 + d * e2 - a * co - b * si
    if derivative == 3:
        return -c * e1 + d * e2 - a * si + b * co
    raise ValueError("derivative: must be 0, 1, 2 or 3")


@dataclass(frozen=True)
class ModeShapes:
    """``n`` flexible eigenfunctions of a beam of ``length`` L on a hub (see the module docstring).

    Attributes
    ----------
    length
        Beam length L [m].
    roots
        beta_k L (n).
    a, c
        Constants of the stable form, normalised.
    inertia, radius
        J_h / (mu L^3) (``inf`` for clamped-free) and r_h / L.
    """

    length: float
    roots: np.ndarray
    a: np.ndarray
    c: np.ndarray
    inertia: float
    radius: float

    @property
    def n(self) -> int:
        return int(self.roots.size)

    @property
    def clamped(self) -> bool:
        return math.isinf(self.inertia)

    def __call__(self, x: np.ndarray, derivative: int = 0) -> np.ndarray:
        """Shapes (or their x-derivatives) at points ``x`` [m]: ``out[i, k] = psi_k^(derivative)(x_i)``."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.n == 0:
            return np.empty((x.size, 0))
        xi = (x / self.length)[:, None]
        z = self.roots[None, :]
        return nm.integer_power(z / self.length, derivative) * _combine(
            z, self.a[None, :], self.c[None, :], _stable_terms(z, xi), derivative
        )


@functools.cache
def mode_shapes(n: int, length: float, inertia: float = math.inf, radius: float = 0.0) -> ModeShapes:
    """The first ``n`` eigenfunctions for hub inertia ratio J_h/(mu L^3) and radius ratio r_h/L.

    ``inertia = inf`` (the default) gives the clamped-free cantilever modes.
    """
    roots = hub_beam_roots(n, inertia, radius)
    a = np.empty(n)
    c = np.empty(n)
    xs, ws = nm.leggauss(8 * n + 48)
    xi, wi = 0.5 * (xs + 1.0), 0.5 * ws
    for k, z in enumerate(roots):
        r1a, r1c, r2a, r2c = _root_rows(z, inertia, radius)
        ak, ck = (r1c, -r1a) if nm.hypot(r1a, r1c) >= nm.hypot(r2a, r2c) else (r2c, -r2a)
        terms = _stable_terms(z, xi)
        u = _combine(z, ak, ck, terms, 0)
        norm2 = nm.fsum(wi * u * u)  # int_0^1 u^2 dxi
        if not math.isinf(inertia):
            slope = _combine(z, ak, ck, _stable_terms(z, np.zeros(1)), 1)[0] * z  # du/dxi at 0
            norm2 += inertia * slope * slope  # (J_h / (mu L^3)) (du/dxi)^2 = (J_h / mu) u'(0)^2 / L
        tip = _combine(z, ak, ck, _stable_terms(z, np.ones(1)), 0)[0]
        sign = (1.0 if tip >= 0.0 else -1.0) * (1.0 if k % 2 == 0 else -1.0)
        scale = sign / math.sqrt(norm2)
        a[k], c[k] = ak * scale, ck * scale
    return ModeShapes(float(length), roots, a, c, float(inertia), float(radius))


def cantilever_modes(x: np.ndarray, length: float, n: int, derivative: int = 0) -> np.ndarray:
    """Clamped-free mode shapes (or their derivatives 0..3) at points ``x``, shape (m, n)."""
    return mode_shapes(n, float(length))(x, derivative)


def free_free_roots(n: int) -> np.ndarray:
    """First ``n`` flexible roots beta_k L of cos z cosh z = 1 (the free-free beam: 4.7300, 7.8532, 10.9956, ...).

    The O(1) characteristic function f(z) = cos z (1 + E^2) - 2 E with E = e^-z (cos z cosh z - 1 scaled by
    2 e^-z) has its k-th root within 0.3 of (k + 1/2) pi, where it is bracketed and refined (Illinois).
    """
    out = np.empty(n)

    def f(z: float) -> float:
        E = nm.exp(-z)
        return nm.cos(z) * (1.0 + E * E) - 2.0 * E

    for k in range(1, n + 1):
        lo, hi = (k + 0.5) * math.pi - 0.3, (k + 0.5) * math.pi + 0.3
        out[k - 1] = _illinois(f, lo, hi, f(lo), f(hi))
    return out


@dataclass(frozen=True)
class FreeFreeShapes:
    """``n`` free-free bending eigenfunctions of a uniform beam of ``length`` L (no hub, no joint), in the stable
    form with xi = x/L, z = beta L, E = e^-z (every exponential with a non-positive argument):

        Psi(xi) = s [cos z xi - sigma sin z xi + 1/2 (1 + sigma) e^(-z xi) + B e^(-z (1 - xi))],
        sigma = (1 + E^2 - 2 E cos z) / (1 - E^2 - 2 E sin z),   B = (cos z - sin z - E) / (1 - E^2 - 2 E sin z),

    the classical cosh z xi + cos z xi - sigma (sinh z xi + sin z xi) rewritten; s normalises int_0^L Psi^2 dx = L
    (so |Psi(0)| = |Psi(L)| = 2), with Psi(0) > 0.  They are orthogonal to each other and to the rigid translation
    and rotation: int Psi dx = int (x - L/2) Psi dx = 0 (the mean-axis conditions of the free beam's frame).

    Attributes
    ----------
    length
        Beam length L [m].
    roots
        beta_k L (n), roots of cos z cosh z = 1.
    sigma, B, scale
        Constants of the stable form, per mode.
    """

    length: float
    roots: np.ndarray
    sigma: np.ndarray
    B: np.ndarray
    scale: np.ndarray

    @property
    def n(self) -> int:
        return int(self.roots.size)

    @property
    def clamped(self) -> bool:
        return False

    def __call__(self, x: np.ndarray, derivative: int = 0) -> np.ndarray:
        """Shapes (or their x-derivatives 0..3) at points ``x`` [m]: ``out[i, k] = psi_k^(derivative)(x_i)``."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.n == 0:
            return np.empty((x.size, 0))
        xi = (x / self.length)[:, None]
        z = self.roots[None, :]
        u = _free_free(z, self.sigma[None, :], self.B[None, :], xi, derivative)
        return nm.integer_power(z / self.length, derivative) * self.scale[None, :] * u


def _free_free(z, sigma, B, xi, derivative: int):
    """The stable form's bracket (see :class:`FreeFreeShapes`) or its derivative by z xi."""
    co, si = nm.cos(z * xi), nm.sin(z * xi)
    e1, e2 = nm.exp(-z * xi), nm.exp(-z * (1.0 - xi))
    a = 0.5 * (1.0 + sigma)
    if derivative == 0:
        return co - sigma * si + a * e1 + B * e2
    if derivative == 1:
        return -si - sigma * co - a * e1 + B * e2
    if derivative == 2:
        return -co + sigma * si + a * e1 + B * e2
    if derivative == 3:
        return si + sigma * co - a * e1 + B * e2
    raise ValueError("derivative: must be 0, 1, 2 or 3")


@functools.cache
def free_free_shapes(n: int, length: float) -> FreeFreeShapes:
    """The first ``n`` free-free eigenfunctions of a beam of ``length`` L (:class:`FreeFreeShapes`)."""
    roots = free_free_roots(n)
    E = nm.exp(-roots)
    den = 1.0 - E * E - 2.0 * E * nm.sin(roots)
    sigma = (1.0 + E * E - 2.0 * E * nm.cos(roots)) / den
    B = (nm.cos(roots) - nm.sin(roots) - E) / den
    xs, ws = nm.leggauss(8 * n + 48)
    xi, wi = 0.5 * (xs + 1.0), 0.5 * ws
    scale = np.empty(n)
    for k in range(n):
        u = _free_free(roots[k], sigma[k], B[k], xi, 0)
        norm2 = nm.fsum(wi * u * u)  # int_0^1 u^2 dxi
        root = _free_free(roots[k], sigma[k], B[k], np.zeros(1), 0)[0]
        scale[k] = (1.0 if root >= 0.0 else -1.0) / math.sqrt(norm2)
    return FreeFreeShapes(float(length), roots, sigma, B, scale)


def pinned_free_roots(n: int) -> np.ndarray:
    """First ``n`` positive roots of tan z = tanh z (the flexible pinned-free modes: 3.9266, 7.0686, ...).

    Newton's method on sin z cosh z - cos z sinh z scaled by e^-z, from the asymptote (4k + 1) pi/4.
    """
    out = np.empty(n)
    for k in range(1, n + 1):
        z = (4 * k + 1) * math.pi / 4
        for _ in range(50):
            t = nm.exp(-2.0 * z)
            sz, cz = nm.sin(z), nm.cos(z)
            f = sz * (1.0 + t) - cz * (1.0 - t)  # 2 e^-z (sin cosh - cos sinh)
            df = cz * (1.0 + t) + sz * (1.0 - t) - 2.0 * t * (sz + cz)
            step = f / df
            z -= step
            if abs(step) <= 4e-16 * z:
                break
        out[k - 1] = z
    return out
