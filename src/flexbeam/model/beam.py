"""Modal integrals of a uniform beam on a hub, in the hub frame or the system frame.

Formulation (``docs/formulation.md``).  The floating frame turns by theta about O; the beam
point of material coordinate x sits at rho(x) = (r_h + x + u_x, u_y) in it, with the transverse
deflection u_y = Psi(x) q and the coupling (foreshortening) deformation

    u_x(x) = -1/2 q^T H(x) q,     H(x) = r_h d^T d + int_0^x Psi'^T Psi' dxi,     d = Psi'(0),

(the beam does not stretch: its root lies on the hub's rim and its arc is inextensible; the
r_h d^T d term is the rim's own shortening, r_h (1 - cos alpha) for a root slope alpha = d q).
The hub angle is phi = theta + d q; the hub's kinetic energy 1/2 J_h phi'^2.

* ``frame = "hub"``: Psi are the clamped-free modes, d = 0, theta is the hub angle.
* ``frame = "system"``: Psi are the flexible eigenmodes of the hub + beam system
  (:func:`flexbeam.model.modes.mode_shapes` with the case's J_h and r_h), orthogonal to the
  rigid rotation in the kinetic-energy inner product, so that the linear mass matrix is
  diag(J_h + J0, mu L I): theta carries the system's rigid rotation and no coordinate is light.

The constant matrices, by Gauss-Legendre quadrature (no nested quadrature: the double integrals
are integrated by parts):

    J0   = int mu (r_h + x)^2 dx              m1  = int mu (r_h + x) dx
    M_ff = int mu Psi^T Psi dx                K_ff = int EI Psi''^T Psi'' dx
    m_tf = int mu (r_h + x) Psi dx            s_f = int mu Psi dx
    D    = int mu (r_h + x) H(x) dx = r_h m1 d^T d + int Psi'^T Psi' [int_x^L mu (r_h + xi) dxi] dx
    G    = int mu H(x) dx          = r_h mu L d^T d + int Psi'^T Psi' mu (L - x) dx

and the mass-matrix blocks seen by the equations (the hub's 1/2 J_h (theta' + d q')^2 included):
J_c = J_h + J0, m_tq = m_tf + J_h d, M_qq = M_ff + J_h d^T d, M_c = M_ff - D.  The zeroth-order
model sets D = G = H = 0.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .. import numerics as nm
from ..parameters.case import Case
from .axial import AxialModes, case_axial
from .modes import FreeFreeShapes, ModeShapes, free_free_shapes, mode_shapes


@dataclass(frozen=True)
class PointData:
    """Modal data of one material point x of the beam.

    ``base = r_h + x``; ``phi``, ``dphi`` are Psi(x), Psi'(x); ``H`` is H(x);
    ``offset`` is the distance c from the centre line to the point, measured against
    the floating-frame normal e2 (c > 0: below the centre line).
    """

    x: float
    base: float
    phi: np.ndarray
    dphi: np.ndarray
    H: np.ndarray
    offset: float
    #: Phi_a(x), the axial shapes (model.axial_modes; empty without them)
    aphi: np.ndarray = field(default_factory=lambda: np.zeros(0))


@dataclass(frozen=True)
class ModalBeam:
    """Constant modal matrices of the rigid-flexible coupling beam model (see the module docstring).

    All arrays are float64; with ``n = 0`` they are empty and the model is a rigid rod.
    """

    n: int
    coupling: str
    frame: str
    length: float
    line_density: float
    bending_stiffness: float
    hub_radius: float
    hub_inertia: float
    shapes: ModeShapes | FreeFreeShapes
    J0: float
    m1: float
    Mff: np.ndarray
    Kff: np.ndarray
    mtf: np.ndarray
    sf: np.ndarray
    D: np.ndarray
    G: np.ndarray
    #: hub slope d = Psi'(0) [1/m] (zero in the hub frame): hub angle = theta + d q
    d: np.ndarray
    #: H(0), where the foreshortening's H(x) starts: r_h d^T d when None (a beam on a hub); -H_bar for a free beam,
    #: whose u_x is measured from its mean (frame ``"mean-axis"``)
    H_root: np.ndarray | None = None
    #: the axial modes (``model.axial_modes``), whose coordinates p follow q: None for an inextensible beam
    axial: AxialModes | None = None
    #: points already built by :meth:`point` (x, offset) -> PointData
    _points: dict = field(default_factory=dict, compare=False, repr=False)
    #: station tables already built by :func:`flexbeam.model.stations.station_table`, by surface offset
    _tables: dict = field(default_factory=dict, compare=False, repr=False)

    @property
    def first_order(self) -> bool:
        """True when the coupling deformation u_x is kept."""
        return self.coupling == "first-order"

    @property
    def na(self) -> int:
        """The axial modes' count n_a (0: inextensible)."""
        return 0 if self.axial is None else self.axial.count

    @property
    def nq(self) -> int:
        """The flexible coordinates [q, p]: n bending modes, then n_a axial ones."""
        return self.n + self.na

    @property
    def Jc(self) -> float:
        """J_h + J0: the rigid rotary inertia about O [kg m^2]."""
        return self.hub_inertia + self.J0

    @property
    def Mc(self) -> np.ndarray:
        """M_ff - D: the q-dependent part of the theta-theta mass entry, J_c + q^T M_c q."""
        return self.Mff - self.D

    @property
    def mtq(self) -> np.ndarray:
        """theta-q mass coupling m_tf + J_h d (zero in the system frame)."""
        return self.mtf + self.hub_inertia * self.d

    @property
    def Mqq(self) -> np.ndarray:
        """q-q mass block M_ff + J_h d^T d (mu L I in either frame)."""
        return self.Mff + self.hub_inertia * np.outer(self.d, self.d)

    def point(self, x: float, offset: float = 0.0) -> PointData:
        """Modal data of the material point ``x`` (``offset`` below the centre line)."""
        key = (float(x), float(offset))
        if key not in self._points:
            self._points[key] = self._point(*key)
        return self._points[key]

    def _point(self, x: float, offset: float) -> PointData:
        phi = self.shapes(np.array([x]), 0)[0]
        dphi = self.shapes(np.array([x]), 1)[0]
        H = np.zeros((self.n, self.n))
        if self.first_order and self.n:
            H = self.hub_radius * np.outer(self.d, self.d) if self.H_root is None else self.H_root.copy()
            if x > 0.0:
                xg, wg = _gauss(0.0, x, _auto_points(self.n, 0))
                d1 = self.shapes(xg, 1)
                H = H + nm.gram(d1, wg)
            H = 0.5 * (H + H.T)  # exactly symmetric: the kernels read it by columns
        aphi = np.zeros(0) if self.axial is None else self.axial.shapes(np.array([x]), 0)[0]
        return PointData(float(x), self.hub_radius + x, phi, dphi, H, float(offset), aphi)


def _auto_points(n: int, requested: int) -> int:
    return requested if requested > 0 else 8 * n + 48


def _gauss(a: float, b: float, m: int) -> tuple[np.ndarray, np.ndarray]:
    xi, wi = nm.leggauss(m)
    return 0.5 * (b - a) * xi + 0.5 * (b + a), 0.5 * (b - a) * wi


def case_shapes(case: Case) -> ModeShapes | FreeFreeShapes:
    """Shape functions of ``case``'s frame: clamped-free (hub frame), hub + beam eigenmodes (system) or free-free
    (a free beam's mean-axis frame)."""
    beam, hub = case.beam, case.hub
    L = beam.length
    if case.frame == "mean-axis":
        return free_free_shapes(case.model.modes, L)
    if case.frame == "hub":
        return mode_shapes(case.model.modes, L)
    inertia = hub.inertia / (beam.line_density * (L * L * L))
    return mode_shapes(case.model.modes, L, inertia, hub.radius / L)


def build_modal_beam(case: Case) -> ModalBeam:
    """The modal beam of ``case`` (memoised on the fields it depends on: sweeps over contact or initial
    parameters reuse it)."""
    key = (case.beam.model_dump_json(), case.hub.model_dump_json(), case.model.model_dump_json(), case.frame)
    beam = _BEAMS.get(key)
    if beam is None:
        if len(_BEAMS) >= 32:
            _BEAMS.pop(next(iter(_BEAMS)))
        beam = _BEAMS[key] = _build_modal_beam(case)
    return beam


_BEAMS: dict[tuple, ModalBeam] = {}


def _build_modal_beam(case: Case) -> ModalBeam:
    """Compute the modal integrals of ``case`` by Gauss-Legendre quadrature.

    The default number of Gauss points, 8 n + 48, integrates products of the n-th
    mode's second derivatives to machine precision (checked in the unit tests
    against K_ff = EI beta_k^4 L delta_kl and M_ff = mu L I).
    """
    if case.frame == "mean-axis":
        return _build_free_beam(case)
    beam, hub, model = case.beam, case.hub, case.model
    n, L = model.modes, beam.length
    mu, EI, rh = beam.line_density, beam.bending_stiffness, hub.radius
    shapes = case_shapes(case)
    x, w = _gauss(0.0, L, _auto_points(n, model.quadrature_points))
    phi = shapes(x, 0)
    d1 = shapes(x, 1)
    d2 = shapes(x, 2)
    d = shapes(np.zeros(1), 1)[0] if case.frame == "system" else np.zeros(n)
    r = rh + x
    J0 = nm.fsum(w * mu * (r * r))
    m1 = nm.fsum(w * mu * r)
    Mff = nm.gram(phi, w * mu)
    Kff = nm.gram(d2, w * EI)
    mtf = nm.matmul(w * mu * r, phi)
    sf = nm.matmul(w * mu, phi)
    if model.coupling == "first-order" and n:
        outer = mu * (rh * (L - x) + 0.5 * (L * L - x * x))  # int_x^L mu (r_h + xi) dxi
        dd = np.outer(d, d)
        D = rh * m1 * dd + nm.gram(d1, w * outer)
        G = rh * mu * L * dd + nm.gram(d1, w * mu * (L - x))
    else:
        D = np.zeros((n, n))
        G = np.zeros((n, n))
    Mff, Kff, mtf = _orthogonality(shapes, mu, EI, hub.inertia, d, Mff, Kff, mtf)
    sym = lambda a: 0.5 * (a + a.T)  # noqa: E731 - remove round-off asymmetry
    return ModalBeam(
        n=n,
        coupling=model.coupling,
        frame=case.frame,
        length=L,
        line_density=mu,
        bending_stiffness=EI,
        hub_radius=rh,
        hub_inertia=hub.inertia,
        shapes=shapes,
        J0=J0,
        m1=m1,
        Mff=sym(Mff),
        Kff=sym(Kff),
        mtf=mtf,
        sf=sf,
        D=sym(D),
        G=sym(G),
        d=d,
        axial=case_axial(case, shapes),
    )


def _build_free_beam(case: Case) -> ModalBeam:
    """The modal integrals of a free beam (``joint.kind = "free"``): the frame at the centre of mass G, the
    free-free modes, the foreshortening measured from its mean (``docs/formulation.md``, *A free-flying beam*).

    With the base b(x) = x - L/2 (the hub radius r_h = -L/2 in the point tables) and Gauss-Legendre quadrature:

        J_G = int mu (x - L/2)^2 dx (= mu L^3 / 12),   D = int mu (x - L/2) H dx = 1/2 int mu x (L - x) Psi'^T Psi' dx,
        H(x) = int_0^x Psi'^T Psi' dxi - H_bar,   H_bar = (1/L) int (L - x) Psi'^T Psi' dx,

    and the values the modes' orthogonality fixes exactly: m_1 = int mu (x - L/2) = 0, M_ff = mu L I,
    K_ff = EI L diag(beta^4), s_f = int mu Psi = 0, m_tf = int mu (x - L/2) Psi = 0 (the mean-axis conditions; the
    unit tests check the quadrature against them), G = int mu H = 0, and no hub (d = 0, J_h = 0).  The zeroth-order
    model sets D = H = 0.
    """
    beam, model = case.beam, case.model
    n, L = model.modes, beam.length
    mu, EI = beam.line_density, beam.bending_stiffness
    shapes = free_free_shapes(n, L)
    x, w = _gauss(0.0, L, _auto_points(n, model.quadrature_points))
    b = x - 0.5 * L
    J0 = nm.fsum(w * mu * (b * b))
    if model.coupling == "first-order" and n:
        d1 = shapes(x, 1)
        D = nm.gram(d1, w * (0.5 * mu * x * (L - x)))
        H_root = -nm.gram(d1, w * ((L - x) / L))
    else:
        D = np.zeros((n, n))
        H_root = np.zeros((n, n))
    sym = lambda a: 0.5 * (a + a.T)  # noqa: E731 - remove round-off asymmetry
    return ModalBeam(
        n=n,
        coupling=model.coupling,
        frame="mean-axis",
        length=L,
        line_density=mu,
        bending_stiffness=EI,
        hub_radius=-0.5 * L,
        hub_inertia=0.0,
        shapes=shapes,
        J0=J0,
        m1=0.0,
        Mff=mu * L * np.eye(n),
        Kff=EI * L * np.diag(nm.integer_power(shapes.roots / L, 4)),
        mtf=np.zeros(n),
        sf=np.zeros(n),
        D=sym(D),
        G=np.zeros((n, n)),
        d=np.zeros(n),
        H_root=sym(H_root),
        axial=case_axial(case, shapes),
    )


def _orthogonality(
    shapes: ModeShapes,
    mu: float,
    EI: float,
    Jh: float,
    d: np.ndarray,
    Mff: np.ndarray,
    Kff: np.ndarray,
    mtf: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The exact values of the integrals that the eigenfunctions' orthogonality fixes.

    The shapes are exact eigenfunctions, normalised to int mu Psi^T Psi dx + J_h d^T d = mu L I with
    int EI Psi''^T Psi'' dx = EI L diag(beta^4) (Blevins 1979; for the hub + beam system by the boundary terms
    of docs/formulation.md), and in the system frame orthogonal to the rigid rotation, m_tf + J_h d = 0.  The
    quadrature reproduces these to ~1e-11 (the unit tests check it); the exact values are used so that the
    linearised mass and stiffness matrices are exactly diagonal in the modal coordinates.
    """
    n, L = shapes.n, shapes.length
    if n == 0:
        return Mff, Kff, mtf
    beta = shapes.roots / L
    Kff = EI * L * np.diag(nm.integer_power(beta, 4))
    Mff = mu * L * np.eye(n) - Jh * np.outer(d, d)
    if not shapes.clamped:
        mtf = -Jh * d
    return Mff, Kff, mtf


def hub_angle_rate(beam: ModalBeam, theta: float, omega: float, q: np.ndarray, qd: np.ndarray) -> tuple[float, float]:
    """Hub angle phi = theta + d q and rate phi' = theta' + d q' [rad, rad/s]."""
    if not beam.n:
        return theta, omega
    return theta + nm.dot(beam.d, q), omega + nm.dot(beam.d, qd)


__all__ = ["ModalBeam", "PointData", "build_modal_beam", "case_shapes", "hub_angle_rate"]
