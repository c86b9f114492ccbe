"""The FE beam with no joint (``joint.kind = "free"``): every node free, no hub; its rigid-body motion and start.

The free FE beam is the mesh of :mod:`flexbeam.fem.mesh` with all N + 1 nodes free, z = [X_0, Y_0, psi_0, ...,
X_N, Y_N, psi_N] (:mod:`flexbeam.fem.assembly` with ``free``): no hub, no theta, no drive, gravity on every element.
No floating frame and no mean-axis condition: the rigid-body motion is read off the field of the interpolated
elements (:func:`rigid_sums`, 4-point Gauss quadrature per element, exact for these polynomial integrands: r and
its rates are cubic in xi):

* m = int mu dx, G at r_G = int mu r dx / m, its velocity v_G = int mu r' dx / m (the mass-weighted nodal velocities
  of the consistent mass: the total momentum over m) and acceleration a_G = int mu r'' dx / m;
* the angular momentum about G, H_G = int mu (r - r_G) x r' dx, and its rate int mu (r - r_G) x r'' dx (the torque of
  the external forces about G: gravity has none);
* the spin Omega = H_G / J_G, J_G = mu L^3 / 12 the straight bar's rotary inertia about G -- the modal model's
  p_theta / J_G (docs/free-beam.md): conserved in free flight, whatever the vibration, and theta' for a rigid bar.
  The chord's or an end section's angle rate would oscillate with the bending vibration that an impact excites;
* the angle theta of Buckens' mean axis: the direction of S = int mu (x - L/2) r dx, theta = atan2(S_y, S_x), and
  theta' = (S x S') / |S|^2 (S' = int mu (x - L/2) r' dx) -- the frame in which int mu (x - L/2) u_y dx = 0, the
  modal model's linear mean-axis condition, so that the FE's theta and the modal frame's angle are alike (the FE's
  ``theta`` and ``theta_rate`` outputs, its tip deflection e2(theta) . (r(L) - r_G) and the measuring points'
  velocities along e2(theta)).

Initial states (``[initial]``, as the modal model's free beam reads them, evaluated with the FE's own kinematics):
``state`` -- the straight beam with G at ``position`` moving at ``velocity`` and turning at ``rate`` about G at
``angle`` (no ``modal_displacement``/``modal_velocity``: the FE has no modes); ``impact`` -- the straight beam at
``impact_angle`` translating at ``impact_velocity`` along pair 0's contact normal, placed so that its gap is zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from .element import GAUSS_W, GAUSS_XI, gather, point_kinematics
from .jit import fem_jit

#: the sums of :func:`rigid_sums`: m, int mu r (2), int mu r' (2), int mu r'' (2), int mu r x r', int mu r x r'',
#: int mu b r (2), int mu b r' (2)  (b = x - L/2)
RIGID_SUMS = 13


@fem_jit
def rigid_sums(X, V, A, l0, mu, gxi, gw, out):
    """The mass-weighted integrals of the field over the beam (see :data:`RIGID_SUMS`), written to ``out``."""
    for k in range(RIGID_SUMS):
        out[k] = 0.0
    L = 0.0
    for e in range(l0.size):
        L += l0[e]
    xe = np.empty(6)
    ve = np.empty(6)
    ae = np.empty(6)
    G = np.empty((2, 6))
    x0 = 0.0
    for e in range(l0.size):
        gather(X, V, A, e, xe, ve, ae)
        for q in range(gxi.size):
            w = gw[q] * mu * l0[e]
            r, v, a = point_kinematics(xe, ve, ae, l0[e], gxi[q], G)
            b = x0 + gxi[q] * l0[e] - 0.5 * L
            out[0] += w
            out[1] += w * r[0]
            out[2] += w * r[1]
            out[3] += w * v[0]
            out[4] += w * v[1]
            out[5] += w * a[0]
            out[6] += w * a[1]
            out[7] += w * (r[0] * v[1] - r[1] * v[0])
            out[8] += w * (r[0] * a[1] - r[1] * a[0])
            out[9] += w * b * r[0]
            out[10] += w * b * r[1]
            out[11] += w * b * v[0]
            out[12] += w * b * v[1]
        x0 += l0[e]


@dataclass(frozen=True)
class Rigid:
    """The rigid-body motion of the FE field at one state (see the module docstring; SI units)."""

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    #: angular momentum about G and its rate
    momentum: float
    torque: float
    #: Buckens' mean-axis angle (in (-pi, pi]) and its rate
    angle: float
    angle_rate: float


class FreeBody:
    """The free FE beam's rigid-body motion and start (a mixin of :class:`~flexbeam.fem.beam.FemBeam`: it reads
    ``l0``, ``x_nodes``, ``mu``, ``case``, ``pairs`` and the beam's :meth:`nodes`, :meth:`gap` and
    :meth:`contact_point`)."""

    @property
    def rigid_inertia(self) -> float:
        """J_G = mu L^3 / 12, the straight beam's rotary inertia about G [kg m^2]."""
        L = float(self.x_nodes[-1])
        return self.mu * L**3 / 12.0

    def rigid(self, z: np.ndarray, zd: np.ndarray, zdd: np.ndarray | None = None) -> Rigid:
        """The rigid-body motion at (z, z', z'') (a free beam)."""
        X, V, A = self.nodes(z, zd, zdd)
        s = np.empty(RIGID_SUMS)
        rigid_sums(X, V, A, self.l0, self.mu, GAUSS_XI, GAUSS_W, s)
        m = s[0]
        rG, vG, aG = s[1:3] / m, s[3:5] / m, s[5:7] / m
        H = s[7] - (rG[0] * s[4] - rG[1] * s[3])
        dH = s[8] - (rG[0] * s[6] - rG[1] * s[5])
        S, Sd = s[9:11], s[11:13]
        angle = math.atan2(S[1], S[0])
        rate = (S[0] * Sd[1] - S[1] * Sd[0]) / (S[0] ** 2 + S[1] ** 2)
        return Rigid(rG, vG, aG, float(H), float(dH), angle, float(rate))

    def free_straight(
        self, position: np.ndarray, angle: float, velocity: np.ndarray, rate: float
    ) -> tuple[np.ndarray, np.ndarray]:
        """The straight free beam with G at ``position`` moving at ``velocity``, at ``angle`` turning at ``rate``
        about G: (z, z')."""
        b = self.x_nodes - 0.5 * float(self.x_nodes[-1])
        e1 = np.array([math.cos(angle), math.sin(angle)])
        e2 = np.array([-math.sin(angle), math.cos(angle)])
        nodes = np.empty((b.size, 3))
        rates = np.empty((b.size, 3))
        nodes[:, :2] = np.asarray(position, float) + b[:, None] * e1
        nodes[:, 2] = angle
        rates[:, :2] = np.asarray(velocity, float) + rate * b[:, None] * e2
        rates[:, 2] = rate
        return nodes.ravel(), rates.ravel()

    def rigid_jacobian(self, z: np.ndarray, pair: int = 0) -> np.ndarray:
        """(d delta/dx_G, d delta/dy_G, d delta/dtheta) of ``pair``: its gap's rates under a rigid translation of
        the whole beam and a rigid rotation about G (the contact normal n and the lever arm (rho_P x n)_z)."""
        X, _, _ = self.nodes(z, np.zeros_like(z))
        rG = self.rigid(z, np.zeros_like(z)).position
        _, _, _, Jn = self.gap(z, np.zeros_like(z), pair=pair)
        pr = self.pairs[pair]
        first = self.contact_point(z, pair)[0] if pr.anywhere else pr.node
        out = np.zeros(3)
        for a in range(Jn.size // 3):
            p = X[first + a]
            Ja = Jn[3 * a : 3 * a + 3]
            out[:2] += Ja[:2]
            out[2] += float(Ja @ np.array([-(p[1] - rG[1]), p[0] - rG[0], 1.0]))
        return out

    def rigid_effective_mass(self, z: np.ndarray, pair: int = 0) -> float:
        """1 / (|n|^2 / m + a^2 / J_G): the straight rigid bar's effective mass at ``pair``'s point [kg]."""
        n = self.rigid_jacobian(z, pair)
        m = self.mu * float(self.x_nodes[-1])
        return 1.0 / ((n[0] ** 2 + n[1] ** 2) / m + n[2] ** 2 / self.rigid_inertia)

    def free_initial_state(self) -> tuple[np.ndarray, np.ndarray, dict[str, float]]:
        """(z, z', info) of ``case.initial`` for a free beam (the module docstring)."""
        init = self.case.initial
        if init.kind == "state":
            z, zd = self.free_straight(init.position, init.angle, init.velocity, init.rate)
            return z, zd, {}
        if init.kind != "impact":
            raise ParameterError(
                f"initial.kind: '{init.kind}' needs a joint; a free beam starts with 'state' or 'impact'"
            )
        position = np.zeros(2)
        L = float(self.x_nodes[-1])
        for _ in range(3):  # translate along the normal until pair 0 touches (exact at once for a half-plane)
            z, zd = self.free_straight(position, init.impact_angle, np.zeros(2), 0.0)
            delta = self.gap(z, zd, pair=0)[0]
            position = position - delta * self.rigid_jacobian(z, 0)[:2]
            if abs(delta) <= 1e-15 * max(1.0, L):
                break
        z, _ = self.free_straight(position, init.impact_angle, np.zeros(2), 0.0)
        normal = self.rigid_jacobian(z, 0)[:2]
        z, zd = self.free_straight(position, init.impact_angle, init.impact_velocity * normal, 0.0)
        return z, zd, {"impact_x_G": float(position[0]), "impact_y_G": float(position[1])}


__all__ = ["RIGID_SUMS", "FreeBody", "Rigid", "rigid_sums"]
