"""The finite-element beam on its hub: mesh, properties, obstacle and equations.

The mesh has ``case.fem.elements`` two-node co-rotational elements (see
:mod:`flexbeam.fem.element` for the element and the reasons for it), split so that a
node lies at the contact point x_P: n_1 = round(N x_P / L) uniform elements on
[0, x_P] and N - n_1 on [x_P, L] (at least one on each part of non-zero length).
With several contact pairs at different material points x_1 < ... < x_m the beam is
split at each of them alike (node k_i = round(N x_i / L), kept increasing).

Generalised coordinates z = [theta, X_1, Y_1, psi_1, ..., X_N, Y_N, psi_N] (global
node positions and absolute section rotations); node 0 is clamped to the hub at
r_h e1(theta) with rotation theta.  The equations of motion are

    R(z, z', z'', t) = f_in + f_int - f_g - J^T F + [J_h theta'' - tau, 0, ...] = 0,

with f_in the exact inertia force of the interpolated field, f_int the
co-rotational internal force, f_g the gravity force, F >= 0 the CCFM contact force at
P and J = d delta / dz its gap Jacobian (with several contact pairs, the sum
sum_k J_k^T F_k over the pairs, each at its own point against its own obstacle under
its own law: :class:`FemPair`; a pair anywhere acts at the point of the capsule surface
nearest its obstacle, with J = n^T G of the element holding it, G = dr/dz_e its
interpolation).  With theta(t) prescribed, theta is removed
from the unknowns and the first component of R is the joint torque needed.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from ..contact.laws import ContactLaw
from ..contact.setup import ContactSetup
from ..errors import ParameterError
from ..model.joints.drive import JointDrive
from ..parameters.case import Case
from .assembly import assemble, energies, node_states, normal_velocities
from .banded import BAND, band_to_dense, fix_first_dof
from .element import GAUSS_W, GAUSS_XI, point_on_element
from .gap import anywhere_gap, gap_at


def build_mesh(length: float, elements: int, x_contact: float | Sequence[float]) -> np.ndarray:
    """Node coordinates x_0 = 0 < ... < x_N = L with a node at ``x_contact``.

    Parameters
    ----------
    length
        Beam length L [m].
    elements
        Requested number of elements N; raised to 2 when x_P lies strictly inside
        (to m + 1 for m distinct contact points inside).
    x_contact
        Material coordinate of the contact point x_P [m], or those of several contact
        points (then node k_i = round(N x_i / L) lies at x_i, kept strictly increasing,
        with uniform elements between).
    """
    if elements < 1:
        raise ParameterError(f"fem.elements: must be >= 1 (got {elements})")
    tol = 1e-12 * length
    if not np.isscalar(x_contact):
        inside = sorted({float(x) for x in x_contact if tol < x < length - tol})
        if len(inside) > 1:
            return _split_mesh(length, elements, inside)
        x_contact = inside[0] if inside else 0.0
    if x_contact <= tol or x_contact >= length - tol:
        return np.linspace(0.0, length, elements + 1)
    n1 = int(round(elements * x_contact / length))
    n1 = min(max(n1, 1), max(elements - 1, 1))
    n2 = max(elements - n1, 1)
    left = np.linspace(0.0, x_contact, n1 + 1)
    right = np.linspace(x_contact, length, n2 + 1)
    return np.concatenate((left, right[1:]))


def _split_mesh(length: float, elements: int, points: list[float]) -> np.ndarray:
    """Uniform elements between 0, the sorted interior ``points`` and L, node k_i = round(N x_i / L)."""
    m = len(points)
    total = max(elements, m + 1)
    ks, prev = [], 0
    for i, x in enumerate(points):
        k = min(max(int(round(total * x / length)), prev + 1), total - (m - i))
        ks.append(k)
        prev = k
    bounds = [0.0, *points, length]
    counts = np.diff([0, *ks, total])
    parts = [np.linspace(bounds[i], bounds[i + 1], int(n) + 1)[:-1] for i, n in enumerate(counts)]
    return np.concatenate((*parts, [length]))


def locate(x_nodes: np.ndarray, x: float) -> tuple[int, float]:
    """Element index and local coordinate xi in [0, 1] of material point x."""
    e = int(np.searchsorted(x_nodes, x, side="right") - 1)
    e = min(max(e, 0), x_nodes.size - 2)
    xi = (x - x_nodes[e]) / (x_nodes[e + 1] - x_nodes[e])
    return e, float(min(max(xi, 0.0), 1.0))


def initial_angle(case: Case) -> float:
    """Hub angle theta(0) a prescribed drive starts from: the initial state's angle, the release
    angle when given, else the impact angle (the case's convention, as in the modal model)."""
    init = case.initial
    if init.kind == "state":
        return init.angle
    if init.kind == "release" and init.release_angle is not None:
        return init.release_angle
    return init.impact_angle


@dataclass(frozen=True)
class FemPair:
    """One contact pair of the FE model: the contact point at mesh node ``node`` (material coordinate
    ``position``, signed ``offset`` c below the centre line: r_P = X - c n(psi)) against one rigid obstacle
    (``kind`` 0 sphere / 1 half-plane, ``centre``, ``radius``, outward ``normal``) under the CCFM ``law``.

    With ``anywhere`` the contact point is instead the point of the beam's capsule surface (radius ``offset`` = c
    about the deformed centre line, hemispherical caps at x = 0 and L) nearest the obstacle, found at every
    evaluation (:func:`flexbeam.fem.gap.anywhere_gap`); ``node`` and ``position`` are then only the mesh node at the
    case's contact position (a start)."""

    node: int
    position: float
    offset: float
    kind: int
    centre: np.ndarray
    radius: float
    normal: np.ndarray
    law: ContactLaw
    label: str
    anywhere: bool = False


class ContactState:
    """Which contact pairs are in their contact phase, and their law parameters [K, n, chi/d'_0, C].

    ``laws[k]`` is pair k's parameter vector (None while it is free); ``active`` (int64, S) and ``params``
    (S x 4, zeros for free pairs) are the arrays the kernels read.
    """

    __slots__ = ("active", "laws", "params")

    def __init__(self, laws: tuple[np.ndarray | None, ...]) -> None:
        self.laws = tuple(laws)
        self.active = np.array([p is not None for p in self.laws], np.int64)
        self.params = np.zeros((len(self.laws), 4))
        for k, p in enumerate(self.laws):
            if p is not None:
                self.params[k] = p

    @property
    def any(self) -> bool:
        """Is some pair in contact?"""
        return any(p is not None for p in self.laws)

    def with_pair(self, pair: int, params: np.ndarray | None) -> ContactState:
        """A copy with pair ``pair`` in contact under ``params`` (None: free)."""
        laws = list(self.laws)
        laws[pair] = params
        return ContactState(tuple(laws))


@dataclass
class FemBeam:
    """Everything the time integrator needs about one case, for the FE model.

    Build it with :meth:`from_case`.
    """

    case: Case
    x_nodes: np.ndarray
    l0: np.ndarray
    pnode: int
    mu: float
    EA: float
    EI: float
    offset: float
    hub_radius: float
    hub_inertia: float
    gravity: float
    drive: JointDrive
    law: ContactLaw
    obstacle_kind: int
    obstacle_centre: np.ndarray
    obstacle_radius: float
    obstacle_normal: np.ndarray
    measuring: list[tuple[int, float]]
    pairs: tuple[FemPair, ...] = ()

    def __post_init__(self) -> None:
        if not self.pairs:  # one pair from the pair-0 fields
            self.pairs = (
                FemPair(
                    self.pnode, float(self.x_nodes[self.pnode]), self.offset, self.obstacle_kind,
                    self.obstacle_centre, self.obstacle_radius, self.obstacle_normal, self.law, "obstacle",
                ),
            )  # fmt: skip
        ps = self.pairs
        self._pair_args = (
            np.array([p.node for p in ps], np.int64),
            np.array([p.offset for p in ps], float),
            np.array([p.kind for p in ps], np.int64),
            np.array([p.centre for p in ps], float).reshape(len(ps), 2),
            np.array([p.radius for p in ps], float),
            np.array([p.normal for p in ps], float).reshape(len(ps), 2),
            np.array([int(p.anywhere) for p in ps], np.int64),
        )
        self.free_state = ContactState((None,) * len(ps))
        self._pout = np.zeros((len(ps), 5))

    # ------------------------------------------------------------------ set-up
    @classmethod
    def from_case(cls, case: Case) -> FemBeam:
        """Mesh, properties, drive, contact law and obstacle (read from the case, as the modal model does)."""
        b = case.beam
        contact = ContactSetup.from_case(case)
        if len(contact.pairs) == 1:
            x_nodes = build_mesh(b.length, case.fem.elements, case.contact.position)
        else:
            x_nodes = build_mesh(b.length, case.fem.elements, [p.position for p in contact.pairs])
        pnode = int(np.argmin(np.abs(x_nodes - case.contact.position)))
        measuring = [locate(x_nodes, x) for x in case.output.measuring_points]
        pairs = []
        for p in contact.pairs:
            ob = contact.obstacles[p.obstacle]
            offset = abs(b.surface_offset) if p.anywhere else p.offset  # anywhere: the capsule's radius c
            pairs.append(
                FemPair(
                    int(np.argmin(np.abs(x_nodes - p.position))), p.position, offset, int(ob.kind),
                    np.asarray(ob.centre, float), float(ob.radius), np.asarray(ob.normal, float), p.law, p.label,
                    p.anywhere,
                )
            )  # fmt: skip
        return cls(
            case=case,
            x_nodes=x_nodes,
            l0=np.diff(x_nodes),
            pnode=pnode,
            mu=b.line_density,
            EA=b.youngs_modulus * b.section_area,
            EI=b.bending_stiffness,
            offset=contact.offset,
            hub_radius=case.hub.radius,
            hub_inertia=case.hub.inertia,
            gravity=case.model.gravity,
            drive=JointDrive(case.drive, theta0=initial_angle(case)),
            law=contact.law,
            obstacle_kind=int(contact.obstacle.kind),
            obstacle_centre=np.asarray(contact.obstacle.centre, float),
            obstacle_radius=float(contact.obstacle.radius),
            obstacle_normal=np.asarray(contact.obstacle.normal, float),
            measuring=measuring,
            pairs=tuple(pairs),
        )

    # -------------------------------------------------------------- sizes
    @property
    def elements(self) -> int:
        return int(self.l0.size)

    @property
    def size(self) -> int:
        """Number of generalised coordinates, 1 + 3 N."""
        return 1 + 3 * self.elements

    @property
    def npairs(self) -> int:
        """Number of contact pairs S."""
        return len(self.pairs)

    @property
    def any_anywhere(self) -> bool:
        """Has some pair its contact point anywhere?"""
        return any(p.anywhere for p in self.pairs)

    def contact_state(self, lawp: ContactState | np.ndarray | None) -> ContactState:
        """``lawp`` as a :class:`ContactState`: None = all pairs free, an array = pair 0 in contact under it."""
        if isinstance(lawp, ContactState):
            return lawp
        if lawp is None:
            return self.free_state
        return self.free_state.with_pair(0, np.asarray(lawp, float))

    @property
    def prescribed(self) -> bool:
        return self.drive.prescribed

    def torque(self, t: float) -> float:
        """Applied joint torque tau(t) (0 when theta is prescribed)."""
        return 0.0 if self.prescribed else self.drive.torque(t)

    # ---------------------------------------------------------- equations
    def model_args(self) -> tuple:
        """Arguments of the kernels after the state: hub, mesh, material, gravity, quadrature."""
        return (
            self.hub_radius,
            self.hub_inertia,
            self.l0,
            self.mu,
            self.EA,
            self.EI,
            self.gravity,
            GAUSS_XI,
            GAUSS_W,
        )

    def contact_args(self) -> tuple:
        """Arguments of the kernels describing the pairs' points and obstacles (arrays over the pairs)."""
        return self._pair_args

    def residual(
        self,
        t: float,
        z: np.ndarray,
        zd: np.ndarray,
        zdd: np.ndarray,
        coefficients: tuple[float, float, float] = (1.0, 0.0, 1.0),
        want_matrix: bool = True,
        lawp: ContactState | np.ndarray | None = None,
        out: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> tuple[np.ndarray, np.ndarray, tuple[float, float, float, float]]:
        """Residual R and iteration matrix S = cM M + cC C + cK K (band storage).

        Returns (R, ab, (F, F_k, delta, delta')) (pair 0's).  ``lawp`` switches the contact
        forces on (see :meth:`contact_state`).
        """
        n = self.size
        if out is None:
            R = np.empty(n)
            ab = np.zeros((3 * BAND + 1, n))
        else:
            R, ab = out
        cM, cC, cK = coefficients
        cs = self.contact_state(lawp)
        info = assemble(
            z,
            zd,
            zdd,
            self.torque(t),
            *self.model_args(),
            cM,
            cC,
            cK,
            want_matrix,
            *self.contact_args(),
            cs.active,
            cs.params,
            self._pout,
            R,
            ab,
        )
        return R, ab, info

    @staticmethod
    def band_to_dense(ab: np.ndarray) -> np.ndarray:
        """Dense matrix from LAPACK general-band storage (kl = ku = BAND)."""
        return band_to_dense(ab)

    def matrices(self, z: np.ndarray, zd: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Dense mass matrix M and tangent stiffness K at (z, z') (for small meshes)."""
        zd = np.zeros_like(z) if zd is None else zd
        zdd = np.zeros_like(z)
        _, abM, _ = self.residual(0.0, z, zd, zdd, (1.0, 0.0, 0.0))
        _, abK, _ = self.residual(0.0, z, zd, zdd, (0.0, 0.0, 1.0))
        return self.band_to_dense(abM), self.band_to_dense(abK)

    # --------------------------------------------------------- kinematics
    def nodes(self, z: np.ndarray, zd: np.ndarray, zdd: np.ndarray | None = None):
        """Node arrays (X, V, A), each (N + 1) x 3: X, Y, psi per node."""
        nn = self.elements + 1
        X, V, A = np.empty((nn, 3)), np.empty((nn, 3)), np.empty((nn, 3))
        node_states(z, zd, np.zeros_like(z) if zdd is None else zdd, self.hub_radius, X, V, A)
        return X, V, A

    def gap(self, z: np.ndarray, zd: np.ndarray, zdd: np.ndarray | None = None, pair: int = 0):
        """(delta, delta', delta'', J_node) of the contact point of ``pair`` (0: P).

        J_node = d delta / d(X, Y, psi) of the contact node (3); for a pair anywhere d delta / dz_e of the
        element holding the nearest point (6, its two nodes' (X, Y, psi)).
        """
        X, V, A = self.nodes(z, zd, zdd)
        return self._gap_of(X, V, A, pair)

    def _gap_of(self, X, V, A, pair: int):
        pr = self.pairs[pair]
        if pr.anywhere:
            J = np.empty(6)
            d, vn, dd, _, _ = anywhere_gap(X, V, A, self.l0, pr.offset, pr.kind, pr.centre, pr.radius, pr.normal, J)
            return float(d), float(vn), float(dd), J
        J = np.empty(3)
        p = pr.node
        d, vn, dd = gap_at(X[p], V[p], A[p], pr.offset, pr.kind, pr.centre, pr.radius, pr.normal, J)
        return float(d), float(vn), float(dd), J

    def contact_point(self, z: np.ndarray, pair: int = 0) -> tuple[int, float, float]:
        """(element e, local xi, material coordinate x) of the contact point of ``pair`` (for a fixed pair its
        node, as the start of the element after it, or the end of the last one)."""
        pr = self.pairs[pair]
        if not pr.anywhere:
            e = min(pr.node, self.elements - 1)
            return e, float(pr.node - e), float(self.x_nodes[pr.node])
        X, V, A = self.nodes(z, np.zeros_like(z))
        _, _, _, e, xi = anywhere_gap(
            X, V, A, self.l0, pr.offset, pr.kind, pr.centre, pr.radius, pr.normal, np.empty(6)
        )
        return int(e), float(xi), float(self.x_nodes[e] + xi * self.l0[e])

    def rotation_jacobian(self, z: np.ndarray, pair: int = 0) -> float:
        """d delta / d theta of ``pair`` under a rigid rotation of the whole beam about the hub axis:
        sum over the nodes a of J_a . (-Y_a, X_a, 1) (J_a the gap's derivative by node a's (X, Y, psi))."""
        X, _, _ = self.nodes(z, np.zeros_like(z))
        _, _, _, Jn = self.gap(z, np.zeros_like(z), pair=pair)
        pr = self.pairs[pair]
        first = self.contact_point(z, pair)[0] if pr.anywhere else pr.node
        total = 0.0
        for a in range(Jn.size // 3):
            p = X[first + a]
            total += float(Jn[3 * a : 3 * a + 3] @ np.array([-p[1], p[0], 1.0]))
        return total

    def gaps(self, z: np.ndarray, zd: np.ndarray, zdd: np.ndarray | None = None) -> list[tuple]:
        """:meth:`gap` of every pair."""
        X, V, A = self.nodes(z, zd, zdd)
        return [self._gap_of(X, V, A, k) for k in range(self.npairs)]

    def gap_jacobian(self, z: np.ndarray, pair: int = 0) -> np.ndarray:
        """d delta / dz of ``pair`` (dense, length 1 + 3N)."""
        _, _, _, Jn = self.gap(z, np.zeros_like(z), pair=pair)
        J = np.zeros(self.size)
        pr = self.pairs[pair]
        first = self.contact_point(z, pair)[0] if pr.anywhere else pr.node
        for a in range(Jn.size // 3):
            p = first + a
            Ja = Jn[3 * a : 3 * a + 3]
            if p == 0:
                th = z[0]
                J[0] += Ja @ np.array([-self.hub_radius * math.sin(th), self.hub_radius * math.cos(th), 1.0])
            else:
                J[3 * p - 2 : 3 * p + 1] += Ja
        return J

    def point_state(self, z: np.ndarray, zd: np.ndarray, where: tuple[int, float]):
        """Position and velocity of a centre-line point (element, xi)."""
        X, V, _ = self.nodes(z, zd)
        e, xi = where
        xe = np.concatenate((X[e], X[e + 1]))
        ve = np.concatenate((V[e], V[e + 1]))
        return point_on_element(xe, ve, self.l0[e], xi)

    def measuring_velocities(self, z: np.ndarray, zd: np.ndarray) -> np.ndarray:
        """Velocities along e2(theta) of all measuring points [m/s]."""
        if not self.measuring:
            return np.empty(0)
        if not hasattr(self, "_meas"):
            self._meas = (
                np.array([m[0] for m in self.measuring], np.int64),
                np.array([m[1] for m in self.measuring], float),
            )
        return normal_velocities(z, zd, self.hub_radius, self.l0, *self._meas)

    def tip_deflection(self, z: np.ndarray) -> float:
        """Transverse tip displacement in the hub frame, e2(theta) . r_tip [m]."""
        th = z[0]
        return float(-math.sin(th) * z[-3] + math.cos(th) * z[-2])

    def effective_mass(self, z: np.ndarray, pair: int = 0) -> float:
        """1 / (J M^-1 J^T) at a pair's point with the FE mass matrix (theta fixed if prescribed) [kg]."""
        M, _ = self.matrices(z)
        J = self.gap_jacobian(z, pair)
        if self.prescribed:
            M, J = M[1:, 1:], J[1:]
        return float(1.0 / (J @ np.linalg.solve(M, J)))

    def energies(self, z: np.ndarray, zd: np.ndarray) -> tuple[float, float, float]:
        """(kinetic, elastic, gravitational) energy [J]; V_g = g int mu Y dx."""
        T, Ve, Vg = energies(
            z,
            zd,
            self.hub_radius,
            self.hub_inertia,
            self.l0,
            self.mu,
            self.EA,
            self.EI,
            self.gravity,
            GAUSS_XI,
            GAUSS_W,
        )
        return float(T), float(Ve), float(Vg)

    # ------------------------------------------------------ configurations
    def straight(self, theta: float, omega: float) -> tuple[np.ndarray, np.ndarray]:
        """Straight beam at hub angle theta in rigid rotation at rate omega: (z, z')."""
        x = self.hub_radius + self.x_nodes[1:]
        e1 = np.array([math.cos(theta), math.sin(theta)])
        e2 = np.array([-math.sin(theta), math.cos(theta)])
        z = np.empty(self.size)
        zd = np.empty(self.size)
        z[0], zd[0] = theta, omega
        nodes = np.empty((x.size, 3))
        rates = np.empty((x.size, 3))
        nodes[:, :2] = x[:, None] * e1
        nodes[:, 2] = theta
        rates[:, :2] = omega * x[:, None] * e2
        rates[:, 2] = omega
        z[1:] = nodes.ravel()
        zd[1:] = rates.ravel()
        return z, zd

    def static_equilibrium(
        self,
        theta: float,
        load: np.ndarray | None = None,
        z0: np.ndarray | None = None,
        steps: int = 1,
        tol: float = 1e-11,
        max_iter: int = 30,
    ) -> np.ndarray:
        """Static equilibrium with the hub held at ``theta`` (Newton, load stepping).

        Solves f_int(z) - f_g(z) - lambda ``load`` = 0 up to lambda = 1, ``load``
        being an external generalised force (length 1 + 3N), with load increments of
        1/``steps`` that are halved whenever Newton fails.  No contact.

        Raises
        ------
        SolverError
            When the load increment becomes too small.
        """
        from scipy.linalg import solve_banded

        from ..errors import SolverError

        z = self.straight(theta, 0.0)[0] if z0 is None else z0.copy()
        z[0] = theta
        zero = np.zeros_like(z)
        load = np.zeros_like(z) if load is None else np.asarray(load, float)
        scale = self.increment_scale()
        lam, dlam = 0.0, 1.0 / steps
        while lam < 1.0:
            target = min(1.0, lam + dlam)
            trial = z.copy()
            converged = False
            for _ in range(max_iter):
                R, ab, _ = self.residual(0.0, trial, zero, zero, (0.0, 0.0, 1.0))
                R = R - target * load
                R[0] = 0.0
                fix_first_dof(ab)
                dz = solve_banded((BAND, BAND), ab[BAND:], -R)
                if not np.all(np.isfinite(dz)):
                    break
                trial += dz
                if np.max(np.abs(dz) / scale) < tol:
                    converged = True
                    break
            if converged:
                z, lam = trial, target
                dlam = min(2.0 * dlam, 1.0 / steps)
            else:
                dlam *= 0.5
                if dlam < 1e-6 / steps:
                    raise SolverError(f"fem: static equilibrium did not converge (load factor {lam:.6g})")
        return z

    def increment_scale(self) -> np.ndarray:
        """Per-DOF scale of Newton increments: L for positions, 1 rad for rotations."""
        s = np.ones(self.size)
        L = float(self.x_nodes[-1])
        s[1::3] = L
        s[2::3] = L
        return s

    def frequencies(self, theta: float = 0.0, pinned: bool | None = None) -> np.ndarray:
        """Natural frequencies [rad/s] of small vibration about the straight beam at rest.

        ``pinned`` (default: the joint is free) keeps theta as a coordinate (the root
        rotates with the hub: pinned-free for J_h = r_h = 0); otherwise the root is
        clamped.  Zero-frequency (rigid-body) modes are included.
        """
        pinned = (not self.prescribed) if pinned is None else pinned
        z, _ = self.straight(theta, 0.0)
        M, K = self.matrices(z)
        if not pinned:
            M, K = M[1:, 1:], K[1:, 1:]
        w2 = eigh(K, M, eigvals_only=True)
        return np.sqrt(np.clip(w2, 0.0, None))
