"""The revolute joint at a fixed point O: the floating frame turns by theta about O (docs/formulation.md).

Coordinates ``[theta, q]``.  The drive (:class:`~flexbeam.model.joints.drive.JointDrive`, ``[drive]``) leaves theta
free, applies a constant torque on the hub angle phi = theta + d q, or prescribes theta(t) -- then theta is given:
the state holds q alone and the joint torque is an output.  The frame ``model.frame`` goes with the drive
(``docs/formulation.md``, *The frame must match the joint*): the system frame with the hub + beam eigenmodes for a
free or torque-driven joint, the hub frame with clamped-free modes for a prescribed angle.  The compiled side of the
joint is ``kernels/src/joint_revolute.c``.

Initial states (``[initial]``): ``impact`` (frame at the impact angle, beam straight, theta' giving P the impact
velocity), ``state`` (theta, theta' as given, beam straight) and ``release`` (at rest in static equilibrium under
gravity with the hub held at the release angle, solved for by shooting when not given).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from ... import numerics as nm
from ...errors import ParameterError
from ...parameters.case import Case
from .base import Joint
from .drive import JointDrive

if TYPE_CHECKING:
    from ..beam import ModalBeam
    from ..system import BeamSystem

DRIVES = {"free": 0, "torque": 1, "prescribed": 2}
PROFILES = {"constant-rate": 0, "kane-spinup": 1}


def initial_modal(case: Case, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(q, q') over the n flexible coordinates [q, p] of ``initial.modal_displacement`` and ``initial.modal_velocity``
    (the bending modes) and ``initial.axial_displacement``, ``initial.axial_velocity`` (the axial ones, after the
    ``model.modes`` bending modes), the modes they leave out at 0."""
    q, qd = np.zeros(n), np.zeros(n)
    init, nb = case.initial, case.model.modes
    q[: len(init.modal_displacement)] = init.modal_displacement
    qd[: len(init.modal_velocity)] = init.modal_velocity
    q[nb : nb + len(init.axial_displacement)] = init.axial_displacement
    qd[nb : nb + len(init.axial_velocity)] = init.axial_velocity
    return q, qd


def flexible_blocks(beam: ModalBeam) -> tuple[np.ndarray, np.ndarray]:
    """The linearised mass and stiffness of the flexible coordinates [q, p] at rest: blockdiag(M_qq, M_aa) and
    blockdiag(K_ff, K_a) (no axial-bending coupling at first order)."""
    n, nq = beam.n, beam.nq
    M, K = np.zeros((nq, nq)), np.zeros((nq, nq))
    M[:n, :n], K[:n, :n] = beam.Mqq, beam.Kff
    if beam.axial is not None:
        M[n:, n:], K[n:, n:] = np.diag(beam.axial.Maa), np.diag(beam.axial.Ka)
    return M, K


def initial_angle_guess(case: Case) -> float:
    """The hub angle a prescribed drive starts from: the initial state's angle."""
    init = case.initial
    if init.kind == "state":
        return init.angle
    if init.kind == "release" and init.release_angle is not None:
        return init.release_angle
    return init.impact_angle


def table_parameters(base) -> list[float]:
    """The kernels' part of a base table (``base_motion.c``): [rows, max |T_x''|, max |T_y''|, per row t, x, y and
    the spline's second derivatives x'', y''] ([0, 0, 0] without a table).  T'' is linear between the rows, so its
    largest magnitude is at one."""
    if base.spline is None:
        return [0.0, 0.0, 0.0]
    rows = np.asarray(base.table, float)
    second = base.spline(rows[:, 0], 2)
    peak = np.max(np.abs(second), axis=0)
    return [float(len(rows)), float(peak[0]), float(peak[1]), *np.column_stack((rows, second)).ravel().tolist()]


class RevoluteJoint(Joint):
    """A revolute joint at O with its drive."""

    kind = "revolute"
    code = 0
    coordinates = ("theta",)

    def __init__(self, case: Case) -> None:
        super().__init__(case)
        self.drive = JointDrive(case.drive, theta0=initial_angle_guess(case))

    @property
    def ngiven(self) -> int:
        return 1 if self.drive.prescribed else 0

    def parameters(self) -> list[float]:
        """[drive, profile, torque, spin rate, spin-up time, theta0] (``joint_revolute.c``), then with a moving base
        [count, a_x, a_y, per harmonic: axis (0 x, 1 y), amplitude, 2 pi k f, phase] and the table
        (:func:`table_parameters`; ``base_motion.c``)."""
        d = self.drive.spec
        out = [float(DRIVES[d.kind]), float(PROFILES[d.profile]), d.torque if d.kind == "torque" else 0.0,
               d.spin_rate, d.spin_up_time, self.drive.theta0]  # fmt: skip
        base = self.case.base
        if base.moving:
            moving = [h for h in base.harmonics if h.amplitude != 0.0]
            out += [float(len(moving)), float(base.acceleration[0]), float(base.acceleration[1])]
            for h in moving:
                assert base.frequency is not None  # the Base section requires it with harmonics
                out += [1.0 if h.axis == "y" else 0.0, h.amplitude, 2.0 * math.pi * h.order * base.frequency, h.phase]
            out += table_parameters(base)
        return out

    def frame(self, t: float, y: np.ndarray, n: int) -> tuple[float, float, np.ndarray, np.ndarray]:
        if self.drive.prescribed:
            th, thd, _ = self.drive.motion(t)
            return th, thd, y[:n], y[n : 2 * n]
        return float(y[0]), float(y[n + 1]), y[1 : n + 1], y[n + 2 : 2 * n + 2]

    def given(self, t: float) -> np.ndarray:
        if not self.drive.prescribed:
            return np.zeros((3, 0))
        return np.array(self.drive.motion(t), float).reshape(3, 1)

    def state(self, n: int, rigid, rates, q, qd, tail) -> np.ndarray:
        if self.drive.prescribed:
            return np.concatenate((q, qd, tail))
        return np.concatenate(([rigid[0]], q, [rates[0]], qd, tail))

    def hub_angle(self, beam: ModalBeam, theta: float, rate: float, q: np.ndarray, qd: np.ndarray):
        if not beam.n:
            return theta, rate
        return theta + nm.dot(beam.d, q), rate + nm.dot(beam.d, qd)

    def linear_model(self, beam: ModalBeam) -> tuple[np.ndarray, np.ndarray, int | None]:
        n, nq = beam.n, beam.nq
        Mf, Kf = flexible_blocks(beam)
        if self.drive.prescribed:
            return Mf, Kf, None
        M0 = np.zeros((nq + 1, nq + 1))
        M0[0, 0] = beam.Jc
        M0[0, 1 : n + 1] = M0[1 : n + 1, 0] = beam.mtq
        M0[1:, 1:] = Mf
        K0 = np.zeros((nq + 1, nq + 1))
        K0[1:, 1:] = Kf
        return M0, K0, 0

    # ------------------------------------------------------------------------------------------ initial states
    def initial_state(self, system: BeamSystem, case: Case, first_impact: Callable[[np.ndarray], float]):
        init = case.initial
        if self.drive.prescribed:  # theta(0), theta'(0) from the profile; the beam as ``state`` sets it
            th, thd, _ = self.drive.motion(0.0)
            if init.kind == "state":
                return system.state(th, thd, *initial_modal(case, system.n)), {}
            return system.state(th, thd), {}
        if init.kind == "state":
            q, qd = initial_modal(case, system.n)
            return system.state(init.angle, init.rate, q, qd), {}
        if init.kind == "impact":
            y = system.state(init.impact_angle, 0.0)
            J_theta = system.gap(0.0, y)[3][0]
            try:
                rate = init.impact_rate(J_theta)
            except ParameterError as exc:
                if not system.contact.pairs[0].anywhere:
                    raise
                x = system.contact_coordinate(0.0, y, 0)  # (P is the nearest point, not contact.position)
                raise ParameterError(
                    f"{exc}; with contact.anywhere P is the straight beam's nearest point to the obstacle, here x = "
                    f"{x:.3g} m (a surface along the beam is nearest everywhere): start with initial.kind = 'state' "
                    "or 'release', or without contact.anywhere"
                ) from None
            y = system.state(init.impact_angle, rate)
            return y, {"impact_rate": float(y[system.n + 1])}
        angle = init.release_angle
        info: dict[str, float] = {}
        if angle is None:
            angle = self.solve_release_angle(system, case, first_impact)
        info["release_angle"] = float(angle)
        return self.release_state(system, angle), info

    @staticmethod
    def release_state(system: BeamSystem, angle: float) -> np.ndarray:
        """At rest in static equilibrium under gravity with the hub held at the hub angle ``angle``.

        The potential V = 1/2 q^T K q + g [sin(theta)(m1 - 1/2 q^T G q) + cos(theta) s_f q] is stationary under the
        constraint theta + d q = angle (d = 0 in the hub frame):
        [K - g sin(theta) (G - d^T s_f)] q = -g cos(theta) [s_f - (m1 - 1/2 q^T G q) d^T], theta = angle - d q,
        solved by fixed-point iteration on theta and q^T G q (d q is of the order of the static slope); the axial
        modes (no elastic coupling to q) at K_a p = -g sin(theta) s_a.
        """
        b, g = system.beam, system.g
        q = np.zeros(b.n)
        theta = angle
        if b.n:
            for _ in range(50):
                s, c = nm.sin(theta), nm.cos(theta)
                A = b.Kff - g * s * b.G + g * s * np.outer(b.d, b.sf)
                rhs = -g * c * b.sf + g * c * (b.m1 - 0.5 * nm.dot(q, nm.matmul(b.G, q))) * b.d
                q_new = nm.solve(A, rhs)
                theta_new = angle - nm.dot(b.d, q_new)
                done = abs(theta_new - theta) <= 1e-15 * max(1.0, abs(angle)) and np.allclose(
                    q_new, q, rtol=1e-14, atol=0.0
                )
                q, theta = q_new, theta_new
                if done:
                    break
        if b.axial is not None:  # K_a p = -g sin(theta) s_a: the rod's own weight along it
            q = np.concatenate((q, -g * nm.sin(theta) * b.axial.sa / b.axial.Ka))
        return system.state(theta, 0.0, q)

    def solve_release_angle(self, system: BeamSystem, case: Case, first_impact: Callable[[np.ndarray], float]):
        """Release angle from rest that gives P the impact velocity at first contact: brentq on the free flight
        (``first_impact``) around the rigid estimate g m1 (sin th_r - sin th_i) = 1/2 J_c rate^2."""
        init = case.initial
        th_i = init.impact_angle
        y = system.state(th_i, 0.0)
        rate = init.impact_rate(system.gap(0.0, y)[3][0])
        b = system.beam
        if system.g <= 0.0 or b.m1 <= 0.0:
            raise ParameterError("initial.kind: 'release' needs gravity (model.gravity > 0)")
        s = nm.sin(th_i) + 0.5 * b.Jc * (rate * rate) / (system.g * b.m1)
        if s >= 1.0:
            raise ParameterError(
                f"initial.impact_velocity: {init.impact_velocity:g} m/s cannot be reached by release "
                "from rest under gravity"
            )
        guess = nm.asin(s)
        target = init.impact_velocity

        def miss(angle: float) -> float:
            v = first_impact(self.release_state(system, angle))
            if math.isnan(v):
                raise ParameterError(
                    f"initial.release_angle: released at {angle:.6g} rad the beam does not reach the obstacle"
                )
            return v - target

        from scipy.optimize import brentq

        lo, hi = th_i + 0.8 * (guess - th_i), min(th_i + 1.25 * (guess - th_i), 0.5 * math.pi)
        try:
            return float(brentq(miss, lo, hi, xtol=1e-12, rtol=1e-10))
        except ValueError:
            raise ParameterError(
                "initial.release_angle: no release angle near the rigid estimate "
                f"{guess:.6g} rad gives the impact velocity; give initial.release_angle"
            ) from None
