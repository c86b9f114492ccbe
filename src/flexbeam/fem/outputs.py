"""What the FE beam reports at a state besides its contacts: energies, the tip deflection, the velocities of the
measuring points and of any centre-line point (their kernels in Numba, on the element of
:mod:`flexbeam.fem.element`)."""

from __future__ import annotations

import math

import numpy as np

from .assembly import node_states
from .damping import damping_power
from .element import GAUSS_W, GAUSS_XI, corotational_element, inertia_element, point_on_element
from .jit import fem_jit


@fem_jit
def state_energies(z, zd, rh, Jh, free, l0, mu, EA, EI, field, gxi, gw):
    """(kinetic, elastic, gravitational) energy [J] of the mesh and hub (a ``free`` beam has none)."""
    nel = l0.size
    nn = nel + 1
    X = np.empty((nn, 3))
    V = np.empty((nn, 3))
    A = np.empty((nn, 3))
    node_states(z, zd, np.zeros(z.size), rh, free, X, V, A)
    xe = np.empty(6)
    ve = np.empty(6)
    fe = np.empty(6)
    Ke = np.empty((6, 6))
    fin = np.empty(6)
    Me = np.empty((6, 6))
    fg = np.empty(6)
    G = np.empty((2, 6))
    T = 0.0 if free else 0.5 * Jh * zd[0] * zd[0]
    Ve = 0.0
    Vg = 0.0
    for e in range(nel):
        for k in range(3):
            xe[k] = X[e, k]
            xe[3 + k] = X[e + 1, k]
            ve[k] = V[e, k]
            ve[3 + k] = V[e + 1, k]
        Ve += corotational_element(xe, l0[e], EA, EI, fe, Ke, False)
        Te, Vge = inertia_element(xe, ve, ve, l0[e], mu, field, gxi, gw, fin, Me, fg, G)
        T += Te
        Vg += Vge
    return T, Ve, Vg


@fem_jit
def normal_velocities(z, zd, rh, free, theta, l0, elems, xis):
    """Velocities along e2(theta) of centre-line points (element, xi) [m/s]."""
    nn = l0.size + 1
    X = np.empty((nn, 3))
    V = np.empty((nn, 3))
    A = np.empty((nn, 3))
    node_states(z, zd, zd, rh, free, X, V, A)
    out = np.empty(elems.size)
    xe = np.empty(6)
    ve = np.empty(6)
    st, ct = math.sin(theta), math.cos(theta)
    for p in range(elems.size):
        e = elems[p]
        for k in range(3):
            xe[k] = X[e, k]
            xe[3 + k] = X[e + 1, k]
            ve[k] = V[e, k]
            ve[3 + k] = V[e + 1, k]
        _, v = point_on_element(xe, ve, l0[e], xis[p])
        out[p] = -st * v[0] + ct * v[1]
    return out


@fem_jit
def momentum(z, zd, rh, free, l0, mu, gxi, gw):
    """The beam's linear momentum int mu r' dx [kg m/s] (the rate of its first moment; a hub's centre is at O), by
    the elements' Gauss points."""
    nn = l0.size + 1
    X = np.empty((nn, 3))
    V = np.empty((nn, 3))
    A = np.empty((nn, 3))
    node_states(z, zd, zd, rh, free, X, V, A)
    xe = np.empty(6)
    ve = np.empty(6)
    out = np.zeros(2)
    for e in range(l0.size):
        for k in range(3):
            xe[k] = X[e, k]
            xe[3 + k] = X[e + 1, k]
            ve[k] = V[e, k]
            ve[3 + k] = V[e + 1, k]
        for q in range(gxi.size):
            _, v = point_on_element(xe, ve, l0[e], gxi[q])
            out[0] += gw[q] * mu * l0[e] * v[0]
            out[1] += gw[q] * mu * l0[e] * v[1]
    return out


class BeamOutputs:
    """The output quantities of :class:`~flexbeam.fem.beam.FemBeam` (a mixin: it reads the beam's mesh ``l0``,
    properties, ``measuring`` points and :meth:`~flexbeam.fem.beam.FemBeam.nodes`)."""

    def point_state(self, z: np.ndarray, zd: np.ndarray, where: tuple[int, float]):
        """Position and velocity of a centre-line point (element, xi)."""
        X, V, _ = self.nodes(z, zd)
        e, xi = where
        xe = np.concatenate((X[e], X[e + 1]))
        ve = np.concatenate((V[e], V[e + 1]))
        return point_on_element(xe, ve, self.l0[e], xi)

    def measuring_velocities(self, z: np.ndarray, zd: np.ndarray, theta: float | None = None) -> np.ndarray:
        """Velocities along e2(theta) of all measuring points [m/s] (``theta``: default the hub angle; a free
        beam's mean-axis angle, :meth:`~flexbeam.fem.free.FreeBody.rigid`)."""
        if not self.measuring:
            return np.empty(0)
        if not hasattr(self, "_meas"):
            self._meas = (
                np.array([m[0] for m in self.measuring], np.int64),
                np.array([m[1] for m in self.measuring], float),
            )
        if theta is None:
            theta = self.rigid(z, zd).angle if self.free else float(z[0])
        return normal_velocities(z, zd, self.hub_radius, self.free, theta, self.l0, *self._meas)

    def base_power(self, t: float, z: np.ndarray, zd: np.ndarray) -> float:
        """The rate of the base's work on the beam, -a_O(t) . int mu r' dx [W] (0 without base motion): in the base
        frame the field's share -a_O does work on the beam's momentum (docs/formulation.md, *A moving base*)."""
        if not self.case.base.moving:
            return 0.0
        a = self.case.base.motion(t)[2]
        P = momentum(z, zd, self.hub_radius, self.free, self.l0, self.mu, GAUSS_XI, GAUSS_W)
        return -float(a[0] * P[0] + a[1] * P[1])

    def tip_deflection(self, z: np.ndarray, rigid=None) -> float:
        """Transverse tip displacement in the hub frame, e2(theta) . r_tip [m]; a free beam's in its mean-axis
        frame, e2(theta) . (r_tip - r_G) (``rigid``: its :meth:`~flexbeam.fem.free.FreeBody.rigid`, if known)."""
        if self.free:
            rigid = self.rigid(z, np.zeros_like(z)) if rigid is None else rigid
            th = rigid.angle
            return float(-math.sin(th) * (z[-3] - rigid.position[0]) + math.cos(th) * (z[-2] - rigid.position[1]))
        th = z[0]
        return float(-math.sin(th) * z[-3] + math.cos(th) * z[-2])

    def damping_power(self, z: np.ndarray, zd: np.ndarray) -> float:
        """The power [W] the beam's structural damping dissipates (:func:`flexbeam.fem.damping.damping_power`)."""
        if not (self.damping[0] > 0.0 or self.damping[1] > 0.0):
            return 0.0
        X, V, _ = self.nodes(z, zd)
        thd = 0.0 if self.free else float(zd[0])
        return float(damping_power(X, V, thd, self.free, self.l0, self.EA, self.EI, self.damping, self.mu,
                                   GAUSS_XI, GAUSS_W))  # fmt: skip

    def energies(self, z: np.ndarray, zd: np.ndarray) -> tuple[float, float, float]:
        """(kinetic, elastic, gravitational) energy [J]; V_g = g int mu Y dx."""
        T, Ve, Vg = state_energies(z, zd, *self.model_args())
        return float(T), float(Ve), float(Vg)
