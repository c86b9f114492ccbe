"""Axial modes of an extensible beam (``model.axial_modes``; docs/formulation.md, *Axial deformation*).

The variables of Kane, Ryan & Banerjee (1987): the stretch s(x) = Phi_a(x) p is the growth in arc length of the
centre line from the root to x, and the transverse displacement u_y = Psi(x) q as before; to second order

    u_x = Phi_a(x) p - 1/2 q^T H(x) q,    axial strain s' = Phi_a' p,    V_a = 1/2 p^T K_a p,

with no elastic coupling between p and q.  The shapes are the rod's own eigenfunctions:

* a revolute joint (either frame): fixed-free, Phi_k = sqrt(2) sin(kappa_k x), kappa_k = (k - 1/2) pi / L -- the
  root is pinned on the hub's rim and cannot move along the beam;
* a free beam: free-free, Phi_k = sqrt(2) cos(kappa_k x), kappa_k = k pi / L (k >= 1), orthogonal to the axial
  translation (s_a = 0), so that the frame stays at the centre of mass.

Their integrals in closed form (int mu Phi_k^2 = mu L, int EA Phi_k'^2 = EA L kappa_k^2), with the base b(x) =
r_h + x (revolute) or x - L/2 (free):

    M_aa = mu L I,   K_a = EA L diag(kappa^2),
    s_a  = int mu Phi_a        = sqrt(2) mu / kappa_k                         (fixed-free; 0 free-free)
    m_ta = int mu b Phi_a      = sqrt(2) mu [r_h / kappa_k + (-1)^(k+1) / kappa_k^2]   (fixed-free)
                               = sqrt(2) mu ((-1)^k - 1) / kappa_k^2                    (free-free)
    S    = int mu Phi_a^T Psi  (n_a x n, Gauss-Legendre quadrature)

which enter the kinetic energy through the frame's rotation alone (centrifugal forcing and stiffening, a
gyroscopic axial-bending coupling theta' (p^T S q' - q^T S^T p')) and the potential through gravity (s_a p).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .. import numerics as nm

if TYPE_CHECKING:
    from ..parameters.case import Case

SQRT2 = math.sqrt(2.0)


@dataclass(frozen=True)
class AxialShapes:
    """The first ``count`` axial eigenfunctions of a rod of ``length`` L: fixed-free (``free = False``) or
    free-free (``free = True``), normalised to int Phi_k^2 dx = L."""

    length: float
    count: int
    free: bool

    @property
    def wavenumbers(self) -> np.ndarray:
        """kappa_k [1/m]: (k - 1/2) pi / L (fixed-free) or k pi / L (free-free), k = 1 .. count."""
        k = np.arange(1, self.count + 1, dtype=float)
        return (k if self.free else k - 0.5) * (math.pi / self.length)

    def __call__(self, x: np.ndarray, derivative: int = 0) -> np.ndarray:
        """Shapes (or their x-derivatives 0..2) at points ``x`` [m]: ``out[i, k] = Phi_k^(derivative)(x_i)``."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.count == 0:
            return np.empty((x.size, 0))
        kap = self.wavenumbers[None, :]
        arg = x[:, None] * kap
        s, c = nm.sin(arg), nm.cos(arg)
        # d/dx of sin -> cos -> -sin; of cos -> -sin -> -cos
        table = [(c, -s, -c), (s, c, -s)] if self.free else [(s, c, -s), (c, -s, -c)]
        if derivative not in (0, 1, 2):
            raise ValueError("derivative: must be 0, 1 or 2")
        return SQRT2 * nm.integer_power(kap, derivative) * table[0][derivative]


@dataclass(frozen=True)
class AxialModes:
    """The axial modes of a beam and their modal integrals (see the module docstring); vectors over the axial modes,
    ``S`` n_a x n (axial rows, bending columns)."""

    shapes: AxialShapes
    #: the diagonal of M_aa = int mu Phi_a^T Phi_a [kg]
    Maa: np.ndarray
    #: the diagonal of K_a = int EA Phi_a'^T Phi_a' [N/m]
    Ka: np.ndarray
    #: int mu b Phi_a [kg m]
    mta: np.ndarray
    #: int mu Phi_a [kg]
    sa: np.ndarray
    #: int mu Phi_a^T Psi [kg]
    S: np.ndarray

    @property
    def count(self) -> int:
        return self.shapes.count

    @property
    def frequencies(self) -> np.ndarray:
        """The axial natural frequencies omega_k = sqrt(K_a,k / M_aa,k) = kappa_k c [rad/s]."""
        return np.sqrt(self.Ka / self.Maa)


def axial_modes(
    count: int, length: float, line_density: float, axial_stiffness: float, hub_radius: float, free: bool,
    bending, quadrature: int,
) -> AxialModes:  # fmt: skip
    """The :class:`AxialModes` of a beam: ``count`` modes, fixed-free on a hub of radius ``hub_radius`` or free-free
    (``free``, base x - L/2), ``bending`` the bending shapes (callable x -> Psi) for S, by ``quadrature`` Gauss points
    (at least 8 (n + n_a) + 48)."""
    L, mu, EA = length, line_density, axial_stiffness
    shapes = AxialShapes(float(L), int(count), bool(free))
    kap = shapes.wavenumbers
    sign = np.where(np.arange(1, count + 1) % 2 == 1, 1.0, -1.0)  # (-1)^(k+1)
    Maa = np.full(count, mu * L)
    Ka = EA * L * (kap * kap)
    if free:
        sa = np.zeros(count)
        mta = SQRT2 * mu * (-sign - 1.0) / (kap * kap)  # (-1)^k - 1
    else:
        sa = SQRT2 * mu / kap
        mta = SQRT2 * mu * (hub_radius / kap + sign / (kap * kap))
    nb = bending.n
    if nb and count:
        xi, wi = nm.leggauss(max(quadrature, 8 * (nb + count) + 48))
        x, w = 0.5 * L * (xi + 1.0), 0.5 * L * wi
        S = nm.gram(shapes(x, 0), w * mu, bending(x, 0))
    else:
        S = np.zeros((count, nb))
    return AxialModes(shapes, Maa, Ka, mta, sa, S)


def case_axial(case: Case, bending) -> AxialModes | None:
    """The axial modes of ``case`` (``model.axial_modes``; None without them) with its bending shapes ``bending``:
    free-free on a free beam (``joint.kind = "free"``), fixed-free on a revolute joint."""
    count = case.model.axial_modes
    if not count:
        return None
    beam, free = case.beam, case.joint.kind == "free"
    return axial_modes(count, beam.length, beam.line_density, beam.axial_stiffness, 0.0 if free else case.hub.radius,
                       free, bending, case.model.quadrature_points)  # fmt: skip


__all__ = ["AxialModes", "AxialShapes", "axial_modes", "case_axial"]
