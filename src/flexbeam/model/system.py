"""The assembled beam system: equations of motion, contact kinematics and energies.

State vector (first-order form, with two bookkeeping integrals appended):

* joint free or torque-driven:  y = [theta, q_1..q_n, theta', q'_1..q'_n, E_d, W]
* theta(t) prescribed:          y = [q_1..q_n, q'_1..q'_n, E_d, W]
* compliant obstacle support:   [s, s'] inserted just before [E_d, W]

E_d is the energy dissipated by the contact force, int (F - F_k) d' dt (plus the
support's dashpot, int c_s s'^2 dt), and W the work of the joint torque,
int tau theta' dt; the total energy T + V_e + V_g + U_c + E_d - W (T and V_e include
the support's 1/2 m_s s'^2 and 1/2 k_s s^2) is then conserved exactly by the
equations, which the tests check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numba import njit

from ..contact.hertz import effective_modulus, sphere_on_cylinder_stiffness
from ..contact.laws import ContactLaw, law_force, make_law
from ..parameters.case import Case
from .beam import ModalBeam, PointData, build_modal_beam
from .drive import JointDrive
from .kernels import gap_state, generalized_forces, mass_matrix, point_kinematics

OBSTACLE_SPHERE, OBSTACLE_PLANE = 0, 1


@njit(cache=True)
def _state_split(y, n, prescribed, th_p, thd_p):
    if prescribed:
        return th_p, thd_p, y[0:n], y[n : 2 * n]
    return y[0], y[n + 1], y[1 : n + 1], y[n + 2 : 2 * n + 2]


CONTACT_NONE, CONTACT_FORCE, CONTACT_CONSTRAINT = 0, 1, 2


@njit(cache=True)
def support_slot(n, prescribed):
    """Index of a compliant support's s in the state (s' follows): right after the beam's part."""
    return 2 * n if prescribed else 2 * n + 2


@njit(cache=True)
def contact_gap(r, v, a0, dr, okind, ocentre, oradius, onormal, osup, s, sd, J):
    """:func:`gap_state` for an obstacle displaced by s along its support axis u.

    ``osup = [m_s, k_s, c_s, u_x, u_y]`` (m_s = 0: rigid obstacle, s = s' = 0).  The
    obstacle translates, so the gap uses P's position and velocity relative to it,
    r - s u and r' - s' u; the curvature term of a sphere's gamma then holds with the
    relative velocity, and d delta/d s = -n.u is returned as ``Js`` (the obstacle's
    acceleration at s'' = 0 is zero, so gamma needs no other change).
    Returns (delta, delta', gamma, nx, ny, Js).
    """
    if osup[0] <= 0.0:
        delta, vn, gamma, nx, ny = gap_state(r, v, a0, dr, okind, ocentre, oradius, onormal, J)
        return delta, vn, gamma, nx, ny, 0.0
    ux, uy = osup[3], osup[4]
    c = np.empty(2)
    c[0] = ocentre[0] + s * ux
    c[1] = ocentre[1] + s * uy
    vr = np.empty(2)
    vr[0] = v[0] - sd * ux
    vr[1] = v[1] - sd * uy
    delta, vn, gamma, nx, ny = gap_state(r, vr, a0, dr, okind, c, oradius, onormal, J)
    return delta, vn, gamma, nx, ny, -(nx * ux + ny * uy)


@njit(cache=True)
def rhs_kernel(
    y, n, prescribed, th_p, thd_p, thdd_p, tau, g,
    Jc, m1, Mc, Mff, mtf, Kff, sf, G,
    pbase, pphi, pdphi, pH, pc, okind, ocentre, oradius, onormal, osup,
    contact_mode, p,
):  # fmt: skip
    """Right-hand side dy/dt of the beam (and a compliant obstacle) in one of three contact modes.

    ``contact_mode``:

    * 0 -- no contact (unimpact equations M z'' = Q);
    * 1 -- CCFM: the law force F(d, d'), ``p = [K, n, chi/d'_0, C]``, enters as J^T F;
    * 2 -- CCM: the unilateral contact held closed by the multiplier lambda of
      [M J^T; J 0][z''; -lambda] = [Q; -gamma - 2 alpha delta' - beta^2 delta]
      (Baumgarte stabilisation, ``p = [alpha, beta, 0, 0]``), i.e.
      lambda = (-gamma - 2 alpha delta' - beta^2 delta - J M^-1 Q) / (J M^-1 J^T).

    With theta(t) prescribed only the modal rows are solved (theta'' is known and
    moves to the right-hand side) and the joint torque is the first row's residual.

    A compliant obstacle (``osup[0] = m_s > 0``, see :func:`contact_gap`) adds
    m_s s'' = -k_s s - c_s s' + Js F, the obstacle's row of the same system (its mass
    matrix block is m_s, uncoupled from the beam's but for the contact); in CCM the
    multiplier then sees the effective inverse mass J M^-1 J^T + Js^2/m_s.
    Returns (dy/dt, contact force [N], joint torque [N m]).
    """
    N = n + 1
    if not np.all(np.isfinite(y)):  # a trial stage that blew up: let the solver reject it
        return np.full(y.size, np.nan), np.nan, np.nan
    theta, omega, q, qd = _state_split(y, n, prescribed, th_p, thd_p)
    nb = support_slot(n, prescribed)  # the beam's part of the state ends here
    ms = osup[0]
    s_ob = y[nb] if ms > 0.0 else 0.0
    sd_ob = y[nb + 1] if ms > 0.0 else 0.0
    Fs = -osup[1] * s_ob - osup[2] * sd_ob if ms > 0.0 else 0.0  # support force on the obstacle
    Js = 0.0
    M = np.empty((N, N))
    Q = np.empty(N)
    mass_matrix(q, Jc, Mc, Mff, mtf, M)
    generalized_forces(theta, omega, q, qd, 0.0 if prescribed else tau, g, m1, Mc, Kff, sf, G, Q)
    F = 0.0
    diss = 0.0
    J = np.zeros(N)
    if not (np.all(np.isfinite(M)) and np.all(np.isfinite(Q))):
        return np.full(y.size, np.nan), np.nan, np.nan
    if contact_mode != 0:
        dr = np.empty((2, N))
        r, v, a0 = point_kinematics(theta, omega, q, qd, pbase, pphi, pdphi, pH, pc, dr)
        delta, vn, gamma, nx, ny, Js = contact_gap(
            r, v, a0, dr, okind, ocentre, oradius, onormal, osup, s_ob, sd_ob, J
        )
        if not (np.all(np.isfinite(J)) and math.isfinite(gamma)):
            return np.full(y.size, np.nan), np.nan, np.nan
        if contact_mode == 1:
            F, Fk = law_force(p, -delta, -vn)
            diss = (F - Fk) * (-vn)
        else:
            rhs_c = -gamma - 2.0 * p[0] * vn - p[1] * p[1] * delta
            inv_mass = 0.0
            if ms > 0.0:  # the obstacle's share of J M^-1 J^T and J M^-1 Q
                rhs_c -= Js * Fs / ms
                inv_mass = Js * Js / ms
            if prescribed:
                rhs_c -= J[0] * thdd_p
                if n > 0:
                    Qr = Q[1:] - M[1:, 0] * thdd_p
                    a = np.linalg.solve(M[1:, 1:], Qr)
                    b = np.linalg.solve(M[1:, 1:], J[1:])
                    rhs_c -= J[1:] @ a
                    inv_mass += J[1:] @ b
            else:
                a = np.linalg.solve(M, Q)
                b = np.linalg.solve(M, J)
                rhs_c -= J @ a
                inv_mass += J @ b
            if inv_mass > 0.0:
                F = rhs_c / inv_mass
        for i in range(N):
            Q[i] += J[i] * F
    dy = np.empty(y.size)
    if ms > 0.0:
        dy[nb] = sd_ob
        dy[nb + 1] = (Fs + Js * F) / ms
        diss += osup[2] * sd_ob * sd_ob
    if prescribed:
        qdd = np.empty(n)
        if n > 0:
            rhs = Q[1:] - M[1:, 0] * thdd_p
            qdd = np.linalg.solve(M[1:, 1:], rhs)
        torque = M[0, 0] * thdd_p - Q[0]
        for i in range(n):
            torque += M[0, i + 1] * qdd[i]
            dy[i] = qd[i]
            dy[n + i] = qdd[i]
        dy[y.size - 2] = diss
        dy[y.size - 1] = torque * omega
        return dy, F, torque
    zdd = np.linalg.solve(M, Q)
    dy[0] = omega
    for i in range(n):
        dy[i + 1] = qd[i]
    for i in range(N):
        dy[N + i] = zdd[i]
    dy[y.size - 2] = diss
    dy[y.size - 1] = tau * omega
    return dy, F, tau


@dataclass
class ContactGeometry:
    """Contact point P on the beam and the obstacle, as arrays for the kernels."""

    point: PointData
    kind: int
    centre: np.ndarray
    radius: float
    normal: np.ndarray
    #: [m_s, k_s, c_s, u_x, u_y] of a compliant support, zeros for a rigid obstacle
    support: np.ndarray = field(default_factory=lambda: np.zeros(5))

    @property
    def compliant(self) -> bool:
        return bool(self.support[0] > 0.0)


@dataclass
class BeamSystem:
    """Everything the integrator needs about one case.

    Build it with :meth:`from_case`.  Methods take the full state vector ``y``
    (see the module docstring) and time ``t``.
    """

    case: Case
    beam: ModalBeam
    drive: JointDrive
    contact: ContactGeometry
    law: ContactLaw
    measuring: list[PointData] = field(default_factory=list)

    # ------------------------------------------------------------------ set-up
    @classmethod
    def from_case(cls, case: Case) -> BeamSystem:
        """Assemble modal matrices, contact geometry, contact law and drive."""
        beam = build_modal_beam(case)
        c = case.beam.surface_offset
        P = beam.point(case.contact.position, offset=c)
        drive = JointDrive(case.drive, theta0=_initial_angle_guess(case))
        geometry = _place_obstacle(case, P)
        K = case.contact.stiffness
        if K is None:
            E_star = effective_modulus(
                case.beam.youngs_modulus,
                case.beam.poisson_ratio,
                case.obstacle.youngs_modulus,
                case.obstacle.poisson_ratio,
            )
            radius = case.beam.radius if case.beam.section == "circle" else 0.0
            K = sphere_on_cylinder_stiffness(case.obstacle.radius, radius or 0.0, E_star)
            exponent = 1.5
        else:
            exponent = case.contact.exponent
        law = make_law(case.contact.law, K, exponent, case.contact.restitution)
        measuring = [beam.point(x, 0.0) for x in case.output.measuring_points]
        return cls(case, beam, drive, geometry, law, measuring)

    @property
    def n(self) -> int:
        return self.beam.n

    @cached_property
    def tip(self) -> PointData | None:
        """Modal data of the beam tip (None without flexible modes)."""
        return self.beam.point(self.beam.length) if self.beam.n else None

    @property
    def prescribed(self) -> bool:
        return self.drive.prescribed

    @property
    def compliant(self) -> bool:
        """Is the obstacle on a compliant support (two more states s, s')?"""
        return self.contact.compliant

    @property
    def size(self) -> int:
        """Length of the state vector."""
        return (2 * self.n + 2 if self.prescribed else 2 * self.n + 4) + (2 if self.compliant else 0)

    @property
    def support_index(self) -> int:
        """Index of s in the state vector (compliant support; s' follows)."""
        return support_slot(self.n, self.prescribed)

    @property
    def g(self) -> float:
        return self.case.model.gravity

    # ---------------------------------------------------------- state access
    def split(self, t: float, y: np.ndarray) -> tuple[float, float, np.ndarray, np.ndarray]:
        """(theta, theta', q, q') of state y at time t."""
        n = self.n
        if self.prescribed:
            th, thd, _ = self.drive.motion(t)
            return th, thd, y[:n], y[n : 2 * n]
        return float(y[0]), float(y[n + 1]), y[1 : n + 1], y[n + 2 : 2 * n + 2]

    def support_state(self, y: np.ndarray) -> tuple[float, float]:
        """(s, s') of a compliant obstacle support; (0, 0) for a rigid obstacle."""
        if not self.compliant:
            return 0.0, 0.0
        k = self.support_index
        return float(y[k]), float(y[k + 1])

    def velocities(self, t: float, y: np.ndarray) -> np.ndarray:
        """Generalised velocities z' = [theta', q'] (and s' of a compliant support)."""
        _, thd, _, qd = self.split(t, y)
        extra = [self.support_state(y)[1]] if self.compliant else []
        return np.concatenate(([thd], qd, extra))

    def with_velocities(self, t: float, y: np.ndarray, zd: np.ndarray) -> np.ndarray:
        """Copy of y with generalised velocities replaced (theta' only if free)."""
        y = y.copy()
        n = self.n
        if self.prescribed:
            y[n : 2 * n] = zd[1 : n + 1]
        else:
            y[n + 1 : 2 * n + 2] = zd[: n + 1]
        if self.compliant:
            y[self.support_index + 1] = zd[n + 1]
        return y

    # ----------------------------------------------------------- equations
    def _args(self, t: float, y: np.ndarray):
        b, P, o = self.beam, self.contact.point, self.contact
        if self.prescribed:
            th, thd, thdd = self.drive.motion(t)
        else:
            th = thd = thdd = 0.0
        return (
            y, b.n, self.prescribed, th, thd, thdd, self.drive.torque(t), self.g,
            b.hub_inertia + b.J0, b.m1, b.Mff - b.D, b.Mff, b.mtf, b.Kff, b.sf, b.G,
            P.base, P.phi, P.dphi, P.H, P.offset, o.kind, o.centre, o.radius, o.normal, o.support,
        )  # fmt: skip

    def rhs(self, t: float, y: np.ndarray, mode: int = CONTACT_NONE, p: np.ndarray | None = None):
        """(dy/dt, contact force, joint torque) in contact ``mode`` with parameters ``p``."""
        return rhs_kernel(*self._args(t, y), mode, _NO_LAW if p is None else p)

    def rhs_function(self, mode: int = CONTACT_NONE, p: np.ndarray | None = None):
        """A fast ``fun(t, y)`` for scipy's solvers (constant arrays bound once).

        ``mode``/``p`` as in :func:`rhs_kernel`: no contact, CCFM law parameters, or
        CCM Baumgarte parameters.
        """
        b, P, o = self.beam, self.contact.point, self.contact
        const = (
            b.hub_inertia + b.J0, b.m1, np.ascontiguousarray(b.Mff - b.D), b.Mff, b.mtf, b.Kff,
            b.sf, b.G, P.base, P.phi, P.dphi, P.H, P.offset, o.kind, o.centre, o.radius, o.normal,
            o.support,
        )  # fmt: skip
        n, prescribed, g, drive = b.n, self.prescribed, self.g, self.drive
        p = _NO_LAW if p is None else p

        if prescribed:

            def fun(t: float, y: np.ndarray) -> np.ndarray:
                th, thd, thdd = drive.motion(t)
                return rhs_kernel(y, n, True, th, thd, thdd, 0.0, g, *const, mode, p)[0]

        else:
            tau_const = drive.spec.kind != "torque"

            def fun(t: float, y: np.ndarray) -> np.ndarray:
                tau = 0.0 if tau_const else drive.torque(t)
                return rhs_kernel(y, n, False, 0.0, 0.0, 0.0, tau, g, *const, mode, p)[0]

        return fun

    def joint_torque(self, t: float, y: np.ndarray, mode: int = CONTACT_NONE,
                     p: np.ndarray | None = None) -> float:
        """Joint torque: applied tau (free/torque) or the reaction needed for theta(t)."""
        return float(self.rhs(t, y, mode, p)[2])

    def mass_matrix(self, t: float, y: np.ndarray) -> np.ndarray:
        """Generalised mass matrix M(q), (n+1) x (n+1), bordered by m_s for a compliant support."""
        _, _, q, _ = self.split(t, y)
        b = self.beam
        N = b.n + 1 + (1 if self.compliant else 0)
        M = np.zeros((N, N))
        Mb = np.empty((b.n + 1, b.n + 1))
        mass_matrix(np.ascontiguousarray(q), b.hub_inertia + b.J0, b.Mff - b.D, b.Mff, b.mtf, Mb)
        M[: b.n + 1, : b.n + 1] = Mb
        if self.compliant:
            M[-1, -1] = self.contact.support[0]
        return M

    def generalized_forces(self, t: float, y: np.ndarray) -> np.ndarray:
        """Q(z, z', t) without contact (includes the applied torque if not prescribed)."""
        th, thd, q, qd = self.split(t, y)
        b = self.beam
        Q = np.empty(b.n + 1)
        tau = 0.0 if self.prescribed else self.drive.torque(t)
        generalized_forces(
            th, thd, np.ascontiguousarray(q), np.ascontiguousarray(qd), tau, self.g,
            b.m1, b.Mff - b.D, b.Kff, b.sf, b.G, Q,
        )  # fmt: skip
        return Q

    # ---------------------------------------------------------- kinematics
    def point_state(self, t: float, y: np.ndarray, point: PointData):
        """(r, v, a0, dr/dz) of a material point; a0 = acceleration at z'' = 0."""
        th, thd, q, qd = self.split(t, y)
        dr = np.empty((2, self.n + 1))
        r, v, a0 = point_kinematics(
            th, thd, np.ascontiguousarray(q), np.ascontiguousarray(qd),
            point.base, point.phi, point.dphi, point.H, point.offset, dr,
        )  # fmt: skip
        return r, v, a0, dr

    def gap(self, t: float, y: np.ndarray) -> tuple[float, float, float, np.ndarray]:
        """(delta, delta', gamma, J): gap, its rate, J' z' and the Jacobian d delta/dz.

        For a compliant support z includes s and J ends with d delta/d s.
        """
        r, v, a0, dr = self.point_state(t, y, self.contact.point)
        J = np.empty(self.n + 1)
        o = self.contact
        s, sd = self.support_state(y)
        delta, vn, gamma, _, _, Js = contact_gap(r, v, a0, dr, o.kind, o.centre, o.radius, o.normal,
                                                 o.support, s, sd, J)
        if self.compliant:
            J = np.append(J, Js)
        return delta, vn, gamma, J

    def sensor_force(self, y: np.ndarray) -> float:
        """Force read by a sensor under a compliant support, -(k_s s + c_s s') [N] (0 if rigid)."""
        s, sd = self.support_state(y)
        return -(self.contact.support[1] * s + self.contact.support[2] * sd)

    def normal_velocity(self, t: float, y: np.ndarray, point: PointData) -> float:
        """Velocity of a beam point along the floating-frame normal e2 [m/s]."""
        th = self.split(t, y)[0]
        _, v, _, _ = self.point_state(t, y, point)
        return float(-math.sin(th) * v[0] + math.cos(th) * v[1])

    def effective_mass(self, t: float, y: np.ndarray) -> float:
        """Effective mass at P along the contact normal, 1/(J M^-1 J^T) [kg]."""
        J = self.gap(t, y)[3]
        M = self.mass_matrix(t, y)
        if self.prescribed:
            J, M = J[1:], M[1:, 1:]
            if J.size == 0:
                return math.inf
        return float(1.0 / (J @ np.linalg.solve(M, J)))

    # ------------------------------------------------------------- energies
    def energies(self, t: float, y: np.ndarray) -> dict[str, float]:
        """Kinetic, elastic, gravitational energy [J] and the two bookkeeping integrals.

        Kinetic and elastic energy include the support's 1/2 m_s s'^2 and 1/2 k_s s^2.
        """
        from .kernels import energies

        th, thd, q, qd = self.split(t, y)
        b = self.beam
        T, Ve, Vg = energies(
            th, thd, np.ascontiguousarray(q), np.ascontiguousarray(qd), b.hub_inertia + b.J0,
            b.Mff - b.D, b.Mff, b.mtf, b.Kff, b.m1, b.sf, b.G, self.g,
        )  # fmt: skip
        s, sd = self.support_state(y)
        T += 0.5 * self.contact.support[0] * sd * sd
        Ve += 0.5 * self.contact.support[1] * s * s
        return {"kinetic": T, "elastic": Ve, "gravitational": Vg,
                "dissipated": float(y[-2]), "drive_work": float(y[-1])}

    # ----------------------------------------------------------- initial state
    def state(self, theta: float, omega: float, q=None, qd=None) -> np.ndarray:
        """State vector from (theta, theta', q, q') with zero bookkeeping integrals."""
        n = self.n
        q = np.zeros(n) if q is None else np.asarray(q, float)
        qd = np.zeros(n) if qd is None else np.asarray(qd, float)
        tail = [0.0, 0.0, 0.0, 0.0] if self.compliant else [0.0, 0.0]  # [s, s',] E_d, W
        if self.prescribed:
            return np.concatenate((q, qd, tail))
        return np.concatenate(([theta], q, [omega], qd, tail))


_NO_LAW = np.zeros(4)


def _initial_angle_guess(case: Case) -> float:
    init = case.initial
    if init.kind == "state":
        return init.angle
    if init.kind == "release" and init.release_angle is not None:
        return init.release_angle
    return init.impact_angle


def _place_obstacle(case: Case, P: PointData) -> ContactGeometry:
    """Obstacle arrays; when no centre is given it touches P at the impact configuration."""
    ob = case.obstacle
    th = case.initial.impact_angle
    e1 = np.array([math.cos(th), math.sin(th)])
    e2 = np.array([-math.sin(th), math.cos(th)])
    r_P = P.base * e1 - P.offset * e2  # beam straight
    if ob.kind == "sphere":
        centre = np.array(ob.centre, float) if ob.centre is not None else r_P - ob.radius * e2
        geometry = ContactGeometry(P, OBSTACLE_SPHERE, centre, float(ob.radius), np.zeros(2))
        outward = r_P - centre
        norm = math.hypot(*outward)
        outward = outward / norm if norm > 0.0 else e2
    else:
        centre = np.array(ob.centre, float) if ob.centre is not None else r_P
        normal = np.array(ob.normal, float) if ob.normal is not None else e2
        geometry = ContactGeometry(P, OBSTACLE_PLANE, centre, 0.0, normal)
        outward = normal
    sup = ob.support
    if sup.compliant:
        u = np.array(sup.direction, float) if sup.direction is not None else outward
        geometry.support = np.array([sup.mass, sup.stiffness, sup.damping, u[0], u[1]], float)
    return geometry
