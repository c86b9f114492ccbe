"""Modal integrals of a uniform beam on a hub (Gauss-Legendre quadrature).

With transverse deflection u_y = Phi(x) q and the coupling deformation
u_x = -1/2 q^T H(x) q, H(x) = int_0^x Phi'^T Phi' dxi (PHYSICS.md), the constant
matrices of the rigid-flexible coupling equations are

    J0   = int mu (r_h + x)^2 dx             m1   = int mu (r_h + x) dx
    M_ff = int mu Phi^T Phi dx               K_ff = int EI Phi''^T Phi'' dx
    m_tf = int mu (r_h + x) Phi dx           s_f  = int mu Phi dx
    D    = int mu (r_h + x) H(x) dx = int Phi'^T Phi' [int_x^L mu (r_h + xi) dxi] dx
    G    = int mu H(x) dx        = int Phi'^T Phi' mu (L - x) dx

(the last forms follow by integrating by parts, so no nested quadrature is needed).
The zeroth-order model sets D = G = H = 0.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from ..parameters.case import Case
from .modes import cantilever_modes


@dataclass(frozen=True)
class PointData:
    """Modal data of one material point x of the beam.

    ``base = r_h + x``; ``phi``, ``dphi`` are Phi(x), Phi'(x); ``H`` is H(x);
    ``offset`` is the distance c from the centre line to the point, measured against
    the floating-frame normal e2 (c > 0: below the centre line).
    """

    x: float
    base: float
    phi: np.ndarray
    dphi: np.ndarray
    H: np.ndarray
    offset: float


@dataclass(frozen=True)
class ModalBeam:
    """Constant modal matrices of the rigid-flexible coupling beam model.

    All arrays are float64; with ``n = 0`` they are empty and the model is a rigid rod.
    """

    n: int
    coupling: str
    length: float
    line_density: float
    bending_stiffness: float
    hub_radius: float
    hub_inertia: float
    J0: float
    m1: float
    Mff: np.ndarray
    Kff: np.ndarray
    mtf: np.ndarray
    sf: np.ndarray
    D: np.ndarray
    G: np.ndarray

    @property
    def first_order(self) -> bool:
        """True when the coupling deformation u_x is kept."""
        return self.coupling == "first-order"

    def point(self, x: float, offset: float = 0.0) -> PointData:
        """Modal data of the material point ``x`` (``offset`` below the centre line)."""
        phi = cantilever_modes(np.array([x]), self.length, self.n, 0)[0]
        dphi = cantilever_modes(np.array([x]), self.length, self.n, 1)[0]
        H = np.zeros((self.n, self.n))
        if self.first_order and self.n and x > 0.0:
            xg, wg = _gauss(0.0, x, _auto_points(self.n, 0))
            d1 = cantilever_modes(xg, self.length, self.n, 1)
            H = (d1 * wg[:, None]).T @ d1
        return PointData(float(x), self.hub_radius + x, phi, dphi, H, float(offset))


def _auto_points(n: int, requested: int) -> int:
    return requested if requested > 0 else 8 * n + 48


@functools.cache
def _leggauss(m: int) -> tuple[np.ndarray, np.ndarray]:
    return np.polynomial.legendre.leggauss(m)


def _gauss(a: float, b: float, m: int) -> tuple[np.ndarray, np.ndarray]:
    xi, wi = _leggauss(m)
    return 0.5 * (b - a) * xi + 0.5 * (b + a), 0.5 * (b - a) * wi


def build_modal_beam(case: Case) -> ModalBeam:
    """Compute the modal integrals of ``case`` by Gauss-Legendre quadrature.

    The default number of Gauss points, 8 n + 48, integrates products of the n-th
    mode's second derivatives to machine precision (checked in the unit tests
    against K_ff = EI beta_k^4 L delta_kl and M_ff = mu L I).
    """
    beam, hub, model = case.beam, case.hub, case.model
    n, L = model.modes, beam.length
    mu, EI, rh = beam.line_density, beam.bending_stiffness, hub.radius
    x, w = _gauss(0.0, L, _auto_points(n, model.quadrature_points))
    phi = cantilever_modes(x, L, n, 0)
    d1 = cantilever_modes(x, L, n, 1)
    d2 = cantilever_modes(x, L, n, 2)
    r = rh + x
    J0 = float(np.sum(w * mu * r**2))
    m1 = float(np.sum(w * mu * r))
    Mff = (phi * (w * mu)[:, None]).T @ phi
    Kff = (d2 * (w * EI)[:, None]).T @ d2
    mtf = (w * mu * r) @ phi
    sf = (w * mu) @ phi
    if model.coupling == "first-order" and n:
        outer = mu * (rh * (L - x) + 0.5 * (L**2 - x**2))  # int_x^L mu (r_h + xi) dxi
        D = (d1 * (w * outer)[:, None]).T @ d1
        G = (d1 * (w * mu * (L - x))[:, None]).T @ d1
    else:
        D = np.zeros((n, n))
        G = np.zeros((n, n))
    sym = lambda a: 0.5 * (a + a.T)  # noqa: E731 - remove round-off asymmetry
    return ModalBeam(
        n=n,
        coupling=model.coupling,
        length=L,
        line_density=mu,
        bending_stiffness=EI,
        hub_radius=rh,
        hub_inertia=hub.inertia,
        J0=J0,
        m1=m1,
        Mff=sym(Mff),
        Kff=sym(Kff),
        mtf=mtf,
        sf=sf,
        D=sym(D),
        G=sym(G),
    )
