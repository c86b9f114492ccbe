"""The assembled beam system: equations of motion, contact kinematics and energies (via the compiled kernels).

The beam hangs on its joint (:mod:`flexbeam.model.joints`), whose frame coordinates lead the full coordinates
[rigid, q]; the coordinates the joint gives as functions of time are not in the state.  State vector (first-order
form, with two bookkeeping integrals appended), for the revolute joint:

* joint free or torque-driven:  y = [theta, q_1..q_n, theta', q'_1..q'_n, E_d, W]
* theta(t) prescribed:          y = [q_1..q_n, q'_1..q'_n, E_d, W]
* compliant obstacle support:   [s, s'] inserted just before [E_d, W]
* axial modes (``model.axial_modes``): the n_a axial coordinates p follow the bending ones, q = [q_b, p]

theta is the angle of the body frame (``docs/formulation.md``): in the hub frame the hub angle itself, in the
system frame the angle of the frame carrying the rigid rotation, the hub angle being theta + d q.  E_d is the
energy dissipated by the contact force, int (F - F_k) d' dt (plus the support's dashpot, int c_s s'^2 dt), and
W the work of the joint torque on the hub angle; the total energy T + V_e + V_g + U_c + E_d - W (T and V_e
include the support's 1/2 m_s s'^2 and 1/2 k_s s^2) is then conserved by the equations, which the tests check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from .. import numerics as nm
from ..contact.setup import ContactSetup
from ..kernels import OUTPUT_COLUMNS, PAIR_COLUMNS, core, pack_contacts, pack_model
from ..parameters.case import Case
from .beam import ModalBeam, PointData, build_modal_beam
from .damping import damping_matrix
from .joints import Joint, joint_of
from .stations import station_table

#: columns of :meth:`BeamSystem.outputs` that exist only for a compliant obstacle support
SUPPORT_COLUMNS = ("support_displacement", "sensor_force")


@dataclass
class BeamSystem:
    """Everything the integrators need about one case.  Build it with :meth:`from_case`.

    Methods take the full state vector ``y`` (see the module docstring) and time ``t``.
    """

    case: Case
    beam: ModalBeam
    joint: Joint
    contact: ContactSetup
    point: PointData
    measuring: list[PointData] = field(default_factory=list)
    pair_points: list[PointData] = field(default_factory=list)

    @classmethod
    def from_case(cls, case: Case, contact: ContactSetup | None = None) -> BeamSystem:
        """Modal matrices of the case's frame, the contact points and the drive."""
        beam = build_modal_beam(case)
        contact = contact or ContactSetup.from_case(case)
        P = beam.point(contact.position, offset=contact.offset)
        joint = joint_of(case)
        measuring = [beam.point(x, 0.0) for x in case.output.measuring_points]
        others = [beam.point(p.position, offset=p.offset) for p in contact.pairs[1:]]
        return cls(case, beam, joint, contact, P, measuring, others)

    @cached_property
    def kernel(self) -> np.ndarray:
        """The packed model buffer of the compiled kernels (points: P, tip, measuring points, the other pairs'
        contact points)."""
        points = [self.point, self.beam.point(self.beam.length), *self.measuring, *self.pair_points]
        # anywhere: 0 a fixed material point, 1 the capsule's nearest point, 2 with flat end faces (nearest.c)
        caps = 2 if self.case.beam.end_caps == "flat" else 1
        pairs = [(self.pair_point(k), p.obstacle, caps * int(p.anywhere)) for k, p in enumerate(self.contact.pairs)]
        stations = None
        if any(p.anywhere for p in self.contact.pairs):
            stations = station_table(self.beam, self.case.beam.surface_offset)
        return pack_model(
            self.beam, self.joint.code, self.joint.parameters(), self.g, points, list(self.contact.obstacles), pairs,
            len(self.measuring), stations, self.damping,
        )  # fmt: skip

    @cached_property
    def damping(self) -> np.ndarray | None:
        """The beam's structural damping C of the flexible coordinates (:mod:`flexbeam.model.damping`), None if
        undamped."""
        return damping_matrix(self.case, self.beam)

    @property
    def pairs(self) -> int:
        """Number of contact pairs."""
        return len(self.contact.pairs)

    def pair_point(self, pair: int) -> int:
        """Index (for :meth:`point_state`) of a pair's contact point."""
        return 0 if pair == 0 else 2 + len(self.measuring) + pair - 1

    @cached_property
    def free_contacts(self) -> np.ndarray:
        """The contacts buffer with every pair free."""
        return self.contacts()

    def contacts(self, modes=None, parameters=None, alpha: float = 0.0, beta: float = 0.0) -> np.ndarray:
        """The kernels' contacts buffer: per pair its :class:`~flexbeam.integrate.phases.ContactMode` (default:
        free) and law parameters [K, n, chi/d'_0, C] (rows), and the constraints' Baumgarte alpha and beta."""
        S = self.pairs
        modes = [0] * S if modes is None else [int(m) for m in modes]
        parameters = np.zeros((S, 4)) if parameters is None else parameters
        return pack_contacts(modes, parameters, alpha, beta)

    @cached_property
    def n(self) -> int:
        """The flexible coordinates [q, p]: the bending modes, then the axial ones (``model.axial_modes``)."""
        return self.beam.nq

    @property
    def law(self):
        return self.contact.law

    @property
    def prescribed(self) -> bool:
        """Does the joint give a coordinate as a function of time (theta(t) prescribed)?"""
        return self.joint.prescribed

    @cached_property
    def nfull(self) -> int:
        """Number of full coordinates [rigid, q] (the equations' rows)."""
        return self.joint.nrigid + self.n

    @cached_property
    def ngiven(self) -> int:
        """Number of the joint's coordinates given as functions of time (leading the full coordinates)."""
        return self.joint.ngiven

    @cached_property
    def compliant(self) -> bool:
        """Is the obstacle on a compliant support (two more states s, s')?"""
        return self.contact.obstacle.compliant

    @cached_property
    def nz(self) -> int:
        """Number of the state's generalised coordinates of the beam: the full ones without the given ones (n + 1,
        [theta, q], or n with theta prescribed)."""
        return self.nfull - self.ngiven

    @cached_property
    def size(self) -> int:
        """Length of the state vector."""
        return 2 * self.nz + (2 if self.compliant else 0) + 2

    @property
    def support_index(self) -> int:
        """Index of s in the state vector (compliant support; s' follows)."""
        return 2 * self.nz

    @property
    def g(self) -> float:
        return self.case.model.gravity

    # ---------------------------------------------------------- state access
    def split(self, t: float, y: np.ndarray) -> tuple[float, float, np.ndarray, np.ndarray]:
        """(theta, theta', q, q') of state y at time t (theta the frame angle)."""
        return self.joint.frame(t, y, self.n)

    def hub_angle(self, t: float, y: np.ndarray) -> tuple[float, float]:
        """Hub angle phi = theta + d q and its rate [rad, rad/s]."""
        return self.joint.hub_angle(self.beam, *self.split(t, y))

    def support_state(self, y: np.ndarray) -> tuple[float, float]:
        """(s, s') of a compliant obstacle support; (0, 0) for a rigid obstacle."""
        if not self.compliant:
            return 0.0, 0.0
        k = self.support_index
        return float(y[k]), float(y[k + 1])

    def velocities(self, t: float, y: np.ndarray) -> np.ndarray:
        """Generalised velocities over the full coordinates, z' = [theta', q'] (and s' of a compliant support)."""
        if not self.ngiven and not self.compliant:  # all of them in the state (the joint's own copy, without its call)
            nz = self.nz
            return np.array(y[nz : 2 * nz], float)
        zd = self.joint.full_velocities(t, y, self.n)
        return np.append(zd, self.support_state(y)[1]) if self.compliant else zd

    def with_velocities(self, t: float, y: np.ndarray, zd: np.ndarray) -> np.ndarray:
        """Copy of y with the generalised velocities ``zd`` (full coordinates [, s']) put in (those the joint gives
        are left out)."""
        if not self.ngiven:  # (the joint's copy, without its call)
            y, nz = y.copy(), self.nz
            y[nz : 2 * nz] = zd[:nz]
        else:
            y = self.joint.with_velocities(y, zd, self.n)
        if self.compliant:
            y[self.support_index + 1] = zd[self.nfull]
        return y

    # ----------------------------------------------------------- equations
    def rhs(self, t: float, y: np.ndarray, contacts: np.ndarray | None = None):
        """(dy/dt, the pairs' contact forces, joint torque) with the ``contacts`` buffer (:meth:`contacts`; default:
        every pair free): a pair under its law contributes J^T F(d, d'), a held pair its multiplier of the
        unilateral constraint with Baumgarte stabilisation."""
        dy, F = np.empty(self.size), np.empty(self.pairs)
        torque = core.rhs(
            self.kernel,
            float(t),
            np.ascontiguousarray(y, float),
            self.free_contacts if contacts is None else contacts,
            dy,
            F,
        )
        return dy, F, torque

    def rhs_function(self, contacts: np.ndarray | None = None):
        """A fast ``fun(t, y)`` for scipy's solvers (arrays bound once)."""
        kernel, size, rhs = self.kernel, self.size, core.rhs
        contacts = self.free_contacts if contacts is None else contacts
        F = np.empty(self.pairs)

        def fun(t: float, y: np.ndarray) -> np.ndarray:
            dy = np.empty(size)
            rhs(kernel, t, y if y.flags.c_contiguous and y.dtype == float else np.ascontiguousarray(y, float),
                contacts, dy, F)  # fmt: skip
            return dy

        return fun

    def contact_forces(self, t: float, y: np.ndarray, contacts: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """(F, lambda_t) at (t, y) under the phase ``contacts``, as :meth:`rhs` solves them: the normal forces and
        the sticking holders' tangential multipliers, of their rows J_t z'' = -gamma_t - 2 alpha v_t
        (``kernels/src/rhs.c`` fb_contact_forces); None if singular."""
        F, Ft = np.empty(self.pairs), np.empty(self.pairs)
        bad = core.contact_forces(self.kernel, float(t), np.ascontiguousarray(y, float), contacts, F, Ft)
        return None if bad else (F, Ft)

    def joint_torque(self, t: float, y: np.ndarray, contacts: np.ndarray | None = None) -> float:
        """Joint torque: applied tau (free/torque) or the reaction needed for theta(t)."""
        return float(self.rhs(t, y, contacts)[2])

    def _equations(self, t: float, y: np.ndarray):
        N = self.nfull
        M, Q, E = np.empty((N, N)), np.empty(N), np.empty(3)
        core.equations(self.kernel, float(t), np.ascontiguousarray(y, float), M, Q, E)
        return M, Q, E

    def mass_matrix(self, t: float, y: np.ndarray) -> np.ndarray:
        """Generalised mass matrix M(q) over the full coordinates, bordered by m_s for a compliant support."""
        return self._bordered(self._equations(t, y)[0])

    def mass_and_kinetic(self, t: float, y: np.ndarray) -> tuple[np.ndarray, float]:
        """(:meth:`mass_matrix`, the kinetic energy of :meth:`energies`) from one evaluation of the equations."""
        M, _, E = self._equations(t, y)
        return self._bordered(M), self._kinetic(E[0], y)

    def _bordered(self, M: np.ndarray) -> np.ndarray:
        if self.compliant:
            N = M.shape[0]
            Mb = np.zeros((N + 1, N + 1))
            Mb[:N, :N] = M
            Mb[N, N] = self.contact.obstacle.support[0]
            return Mb
        return M

    def generalized_forces(self, t: float, y: np.ndarray) -> np.ndarray:
        """Q(z, z', t) without contact (includes the applied torque if not prescribed)."""
        return self._equations(t, y)[1]

    # ---------------------------------------------------------- kinematics
    def point_state(self, t: float, y: np.ndarray, index: int = 0):
        """(r, v, a0, dr/dz) of point ``index`` (0: P, 1: tip, 2..: measuring points, then the other pairs'
        contact points); a0 = acceleration at z''=0."""
        out = np.empty(6 + 2 * self.nfull)
        core.kinematics(self.kernel, int(index), float(t), np.ascontiguousarray(y, float), out)
        return out[0:2], out[2:4], out[4:6], out[6:].reshape(2, self.nfull)

    def gap(self, t: float, y: np.ndarray, pair: int = 0) -> tuple[float, float, float, np.ndarray]:
        """(delta, delta', gamma, J) of contact pair ``pair``: gap, its rate, J' z' and the Jacobian d delta/dz.

        For a compliant support z includes s and J ends with d delta/d s (zero for a pair on another obstacle).
        """
        J = np.empty(self.nfull + (1 if self.compliant else 0))
        delta, rate, gamma = core.gap(self.kernel, int(pair), float(t), np.ascontiguousarray(y, float), J)[:3]
        return delta, rate, gamma, J

    def normal_jump(
        self, t: float, y: np.ndarray, pair: int, restitution: float
    ) -> tuple[np.ndarray, np.ndarray] | None:
        """One frictionless pair's impulse-momentum map, compiled (``kernels/src/impulse_map.c``, the same bits as
        :func:`flexbeam.methods.impulse.impulse_jump`'s): (y+, [P, v-, v+, T-, T+]); None where that map must take
        it (prescribed theta, a compliant support, an obstacle fixed to the ground on a moving base, M singular)."""
        y_plus, out = np.empty(self.size), np.empty(5)
        status = core.normal_jump(self.kernel, int(pair), float(t), np.ascontiguousarray(y, float),
                                  float(restitution), y_plus, out)  # fmt: skip
        return None if status else (y_plus, out)

    def tangent(self, t: float, y: np.ndarray, pair: int = 0) -> tuple[float, float, float, np.ndarray, np.ndarray]:
        """(delta, delta', slip velocity, J, J_t) of contact pair ``pair``: the gap, its rate, the contact point's
        velocity along the tangent t = (-n_y, n_x), and the normal and tangential Jacobians d delta/dz, d(t . r)/dz
        (Coulomb friction)."""
        size = self.nfull + (1 if self.compliant else 0)
        J, Jt = np.empty(size), np.empty(size)
        delta, rate, vt, _, _, _ = core.tangent(self.kernel, int(pair), float(t), np.ascontiguousarray(y, float), J, Jt)
        return delta, rate, vt, J, Jt

    def slip_acceleration(self, t: float, y: np.ndarray, pair: int = 0) -> float:
        """gamma_t [m/s^2]: the rate of a pair's slip velocity at z'' = 0 (v_t' = J_t z'' + gamma_t), for a pair
        anywhere the contact point's, moving along the beam (``kernels/src/anywhere_gamma.c``)."""
        size = self.nfull + (1 if self.compliant else 0)
        J, Jt = np.empty(size), np.empty(size)
        return core.tangent(self.kernel, int(pair), float(t), np.ascontiguousarray(y, float), J, Jt, 1)[5]

    def contact_coordinate(self, t: float, y: np.ndarray, pair: int = 0) -> float:
        """The material coordinate x [m] of a pair's contact point: its fixed point's, or for a pair anywhere the
        nearest point's now (``kernels/src/nearest.c``)."""
        J = np.empty(self.nfull + (1 if self.compliant else 0))
        return core.gap(self.kernel, int(pair), float(t), np.ascontiguousarray(y, float), J)[5]

    def sensor_force(self, y: np.ndarray) -> float:
        """Force read by a sensor under a compliant support, -(k_s s + c_s s') [N] (0 if rigid)."""
        s, sd = self.support_state(y)
        sup = self.contact.obstacle.support
        return -(sup[1] * s + sup[2] * sd)

    def effective_mass(self, t: float, y: np.ndarray, pair: int = 0) -> float:
        """Effective mass at a pair's contact point along its normal, 1/(J M^-1 J^T) [kg]."""
        W = self.delassus(t, y, [pair])
        return math.inf if W[0, 0] <= 0.0 else float(1.0 / W[0, 0])

    def delassus(self, t: float, y: np.ndarray, pairs) -> np.ndarray:
        """The Delassus matrix W = J M^-1 J^T of the given pairs (rows of J: their gap Jacobians) [1/kg]."""
        J = np.array([self.gap(t, y, k)[3] for k in pairs])
        M = self.mass_matrix(t, y)
        if self.ngiven:
            g = self.ngiven
            J, M = J[:, g:], M[g:, g:]
            if J.shape[1] == 0:
                return np.zeros((len(pairs), len(pairs)))
        return nm.matmul(J, nm.solve(M, np.ascontiguousarray(J.T)))

    # ------------------------------------------------------------- energies
    def energies(self, t: float, y: np.ndarray) -> dict[str, float]:
        """Kinetic, elastic, gravitational energy [J] and the two bookkeeping integrals.

        Kinetic and elastic energy include the support's 1/2 m_s s'^2 and 1/2 k_s s^2.
        """
        T, Ve, Vg = self._equations(t, y)[2]
        s, sd = self.support_state(y)
        sup = self.contact.obstacle.support
        return {
            "kinetic": self._kinetic(T, y),
            "elastic": float(Ve + 0.5 * sup[1] * s * s),
            "gravitational": float(Vg),
            "dissipated": float(y[-2]),
            "drive_work": float(y[-1]),
        }

    def kinetic(self, t: float, y: np.ndarray) -> float:
        """The kinetic energy of :meth:`energies` alone [J]."""
        return self._kinetic(self._equations(t, y)[2][0], y)

    def _kinetic(self, T: float, y: np.ndarray) -> float:
        """The beam's kinetic energy T plus the support's 1/2 m_s s'^2."""
        sd = self.support_state(y)[1]
        return float(T + 0.5 * self.contact.obstacle.support[0] * sd * sd)

    def outputs(
        self, times: np.ndarray, states: np.ndarray, contacts: np.ndarray | None = None
    ) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray]:
        """Output columns (:data:`~flexbeam.kernels.OUTPUT_COLUMNS`), measuring-point normal velocities and the
        pairs' columns (samples x pairs x :data:`~flexbeam.kernels.PAIR_COLUMNS`).

        ``theta``/``theta_rate`` are the hub angle and rate; ``tip_deflection`` is the tip's distance from the
        hub's radial line; the measuring points' velocities are normal to that line; ``gap``, ``normal_velocity``
        and ``contact_force`` are the first pair's.
        """
        times = np.ascontiguousarray(times, float)
        m = times.size
        cols = np.empty((m, len(OUTPUT_COLUMNS)))
        mv = np.empty((m, len(self.measuring)))
        pc = np.empty((m, self.pairs, len(PAIR_COLUMNS)))
        core.outputs(
            self.kernel,
            times,
            np.ascontiguousarray(states, float).reshape(m, self.size),
            self.free_contacts if contacts is None else contacts,
            cols,
            mv,
            pc,
        )
        return {name: cols[:, i] for i, name in enumerate(OUTPUT_COLUMNS)}, mv, pc

    # ----------------------------------------------------------- initial state
    def state(self, theta: float, omega: float, q=None, qd=None) -> np.ndarray:
        """State vector from (theta, theta', q, q') with zero bookkeeping integrals."""
        n = self.n
        q = np.zeros(n) if q is None else np.asarray(q, float)
        qd = np.zeros(n) if qd is None else np.asarray(qd, float)
        tail = [0.0, 0.0, 0.0, 0.0] if self.compliant else [0.0, 0.0]  # [s, s',] E_d, W
        return self.joint.state(n, np.array([theta]), np.array([omega]), q, qd, tail)
