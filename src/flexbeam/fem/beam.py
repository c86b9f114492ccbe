"""The finite-element beam on its hub: properties, coordinates and equations of motion.

Generalised coordinates z = [theta, X_1, Y_1, psi_1, ..., X_N, Y_N, psi_N] (global
node positions and absolute section rotations, on the mesh of :mod:`flexbeam.fem.mesh`);
node 0 is clamped to the hub at r_h e1(theta) with rotation theta.  A free beam (``joint.kind = "free"``,
:mod:`flexbeam.fem.free`) has no hub and no theta: z = [X_0, Y_0, psi_0, ..., X_N, Y_N, psi_N].  The equations of
motion are

    R(z, z', z'', t) = f_in + f_int - f_g - J^T F + [J_h theta'' - tau, 0, ...] = 0,

with f_in the exact inertia force of the interpolated field, f_int the
co-rotational internal force, f_g the gravity force, F >= 0 the CCFM contact force at
P and J = d delta / dz its gap Jacobian (with several contact pairs, the sum
sum_k J_k^T F_k over the pairs, each at its own point against its own obstacle under
its own law: :class:`~flexbeam.fem.pairs.FemPair`; a pair anywhere acts at the point of the capsule surface
nearest its obstacle, with J = n^T G of the element holding it, G = dr/dz_e its
interpolation).  With theta(t) prescribed, theta is removed
from the unknowns and the first component of R is the joint torque needed.

:class:`FemBeam` holds the case's data and evaluates R and its iteration matrix (:mod:`flexbeam.fem.assembly`);
its contact geometry (:mod:`flexbeam.fem.contact_geometry`), outputs (:mod:`flexbeam.fem.outputs`), statics and
frequencies (:mod:`flexbeam.fem.statics`) come from one module each.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from dataclasses import field as dataclass_field

import numpy as np

from ..contact.laws import ContactLaw
from ..contact.setup import ContactSetup
from ..errors import ModelError
from ..model.joints import joint_of
from ..model.joints.drive import JointDrive
from ..parameters.case import Case
from .assembly import POUT_COLUMNS, assemble, node_states
from .banded import BAND, band_to_dense
from .contact_geometry import PairGeometry
from .element import GAUSS_W, GAUSS_XI
from .free import FreeBody
from .mesh import build_mesh, locate
from .outputs import BeamOutputs
from .pairs import ContactState, FemPair, friction_params, pair_arrays, pairs_from_setup
from .statics import StaticsAndVibration

#: the joint kinds the FE reference models: a revolute joint at O (free, torque-driven or with its angle prescribed)
#: and no joint at all (a free-flying beam: every node free, no hub)
JOINT_KINDS = ("revolute", "free")


def joint_drive(case: Case) -> JointDrive:
    """The drive of the case's joint, as the modal model takes it (:func:`flexbeam.model.joints.joint_of`): the
    profile of ``[drive]`` and the hub angle theta(0) that a prescribed drive starts from.

    Parameters
    ----------
    case
        The validated case.

    Returns
    -------
    JointDrive
        The joint's own drive (the FE's hub angle theta is the revolute joint's angle); for a free beam the
        drive of ``[drive]``, which is ``free`` (no torque, nothing prescribed).

    Raises
    ------
    ModelError
        For a joint kind the FE reference does not model (naming it): the FE beam is clamped to a hub turning about
        the fixed point O, or free.
    """
    joint = joint_of(case)
    grounded = [i for i, ob in enumerate([case.obstacle, *case.obstacles]) if ob.fixed_to == "ground"]
    if case.base.moving and grounded:
        name = "obstacle" if grounded[0] == 0 else f"obstacles[{grounded[0] - 1}]"
        raise ModelError(
            f"{name}.fixed_to: the FE reference carries its obstacles with a moving base; run an obstacle fixed to "
            "the ground with a modal method"
        )
    if joint.kind not in JOINT_KINDS:
        raise ModelError(
            f"joint.kind: the FE reference models a {' or '.join(map(repr, JOINT_KINDS))} joint, not {joint.kind!r}"
        )
    if joint.kind == "free":
        return JointDrive(case.drive)
    return joint.drive


@dataclass
class FemBeam(PairGeometry, BeamOutputs, StaticsAndVibration, FreeBody):
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
    free: bool = False
    friction_velocity: float = 1e-4  #: v_s of the regularised friction (fem.friction_velocity)
    #: the beam's structural damping [c, eta / mu] (``beam.kelvin_voigt``, ``beam.viscous_damping``:
    #: :mod:`flexbeam.fem.damping`)
    damping: np.ndarray = dataclass_field(default_factory=lambda: np.zeros(2))

    def __post_init__(self) -> None:
        """The pairs from the pair-0 fields when none are given, and the kernels' arrays of them."""
        if not self.pairs:  # one pair from the pair-0 fields
            self.pairs = (
                FemPair(
                    self.pnode, float(self.x_nodes[self.pnode]), self.offset, self.obstacle_kind,
                    self.obstacle_centre, self.obstacle_radius, self.obstacle_normal, self.law, "obstacle",
                ),
            )  # fmt: skip
        self._pair_args = pair_arrays(self.pairs)
        self.free_state = ContactState((None,) * len(self.pairs), friction_params(self.pairs, self.friction_velocity))
        self._pout = np.zeros((len(self.pairs), POUT_COLUMNS))

    # ------------------------------------------------------------------ set-up
    @classmethod
    def from_case(cls, case: Case) -> FemBeam:
        """Mesh, properties, drive, contact law and obstacle (read from the case, as the modal model does).

        Raises
        ------
        ModelError
            For a joint kind the FE reference does not model (:func:`joint_drive`).
        """
        b = case.beam
        contact = ContactSetup.from_case(case)
        if case.beam.end_caps == "flat" and any(p.anywhere for p in contact.pairs):
            raise ModelError(
                "beam.end_caps: the FE reference finds contact anywhere on the capsule (hemispherical end caps); "
                "use end_caps = 'hemisphere' or a modal method"
            )
        if case.joint.kind == "free" and b.viscous_damping > 0.0:
            raise ModelError(
                "beam.viscous_damping: the FE reference damps the deformation relative to the hub's frame, which a "
                "free beam has not; run it with a modal method or with beam.kelvin_voigt"
            )
        if len(contact.pairs) == 1:
            x_nodes = build_mesh(b.length, case.fem.elements, case.contact.position)
        else:
            x_nodes = build_mesh(b.length, case.fem.elements, [p.position for p in contact.pairs])
        pnode = int(np.argmin(np.abs(x_nodes - case.contact.position)))
        measuring = [locate(x_nodes, x) for x in case.output.measuring_points]
        pairs = pairs_from_setup(contact, x_nodes, b.surface_offset)
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
            drive=joint_drive(case),
            law=contact.law,
            obstacle_kind=int(contact.obstacle.kind),
            obstacle_centre=np.asarray(contact.obstacle.centre, float),
            obstacle_radius=float(contact.obstacle.radius),
            obstacle_normal=np.asarray(contact.obstacle.normal, float),
            measuring=measuring,
            pairs=pairs,
            free=case.joint.kind == "free",
            friction_velocity=case.fem.friction_velocity,
            damping=np.array([b.kelvin_voigt, b.viscous_damping / b.line_density]),
        )

    # -------------------------------------------------------------- sizes
    @property
    def elements(self) -> int:
        """Number of elements N."""
        return int(self.l0.size)

    @property
    def size(self) -> int:
        """Number of generalised coordinates, 1 + 3 N (a free beam: 3 (N + 1))."""
        return 3 * (self.elements + 1) if self.free else 1 + 3 * self.elements

    @property
    def npairs(self) -> int:
        """Number of contact pairs S."""
        return len(self.pairs)

    @property
    def frictional(self) -> bool:
        """Has some pair Coulomb friction?"""
        return any(p.friction_static > 0.0 for p in self.pairs)

    @property
    def pair_outputs(self) -> np.ndarray:
        """What the last :meth:`residual` wrote per pair (S x :data:`flexbeam.fem.assembly.POUT_COLUMNS`)."""
        return self._pout

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
        """Is the hub angle theta(t) prescribed (then not an unknown)?"""
        return self.drive.prescribed

    def torque(self, t: float) -> float:
        """Applied joint torque tau(t) (0 when theta is prescribed)."""
        return 0.0 if self.prescribed else self.drive.torque(t)

    # ---------------------------------------------------------- equations
    def model_args(self, t: float | None = None) -> tuple:
        """Arguments of the kernels after the state: hub (none if ``free``), mesh, material, the uniform field the
        beam feels at ``t`` (:meth:`field`; None: gravity alone, for the energies), quadrature."""
        return (
            self.hub_radius,
            self.hub_inertia,
            self.free,
            self.l0,
            self.mu,
            self.EA,
            self.EI,
            self.field(t),
            GAUSS_XI,
            GAUSS_W,
        )

    def field(self, t: float | None = None) -> np.ndarray:
        """The uniform field (g_x, g_y) on the beam at ``t``: gravity (0, -g), less the base's acceleration a_O(t) on a
        moving base, whose frame (origin at O, axes parallel to the plane's) the FE reference then works in, as the
        modal model does (docs/formulation.md, *A moving base*).  ``t`` None: gravity alone."""
        if t is None or not self.case.base.moving:
            return np.array([0.0, -self.gravity])
        a = self.case.base.motion(t)[2]
        return np.array([-a[0], -self.gravity - a[1]])

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
            *self.model_args(t),
            self.damping,
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
        node_states(z, zd, np.zeros_like(z) if zdd is None else zdd, self.hub_radius, self.free, X, V, A)
        return X, V, A

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

    def increment_scale(self) -> np.ndarray:
        """Per-DOF scale of Newton increments: L for positions, 1 rad for rotations."""
        s = np.ones(self.size)
        L = float(self.x_nodes[-1])
        first = 0 if self.free else 1
        s[first::3] = L
        s[first + 1 :: 3] = L
        return s
