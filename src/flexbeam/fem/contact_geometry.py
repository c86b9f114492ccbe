"""Where the FE beam's contact points are and how their gaps depend on the coordinates.

Each contact pair (:class:`~flexbeam.fem.pairs.FemPair`) has its point at a mesh node, r_P = X - c n(psi), or,
with ``contact.anywhere``, at the point of the deformed beam's capsule surface nearest its obstacle.  The gap
delta and its rates come from the FE's own kernels (:mod:`flexbeam.fem.gap`); the gap Jacobian J = d delta / dz
is n^T dr_P/d(X, Y, psi) of the contact node, or n^T G of the element holding the nearest point (G = dr/dz_e its
interpolation), mapped onto z (node 0 follows the hub angle theta).
"""

from __future__ import annotations

import math

import numpy as np

from .gap import anywhere_gap, gap_at


class PairGeometry:
    """The contact-point geometry of :class:`~flexbeam.fem.beam.FemBeam` (a mixin: it reads the beam's ``pairs``,
    ``l0``, ``x_nodes``, ``hub_radius``, ``elements``, ``size`` and :meth:`~flexbeam.fem.beam.FemBeam.nodes`)."""

    def gap(self, z: np.ndarray, zd: np.ndarray, zdd: np.ndarray | None = None, pair: int = 0):
        """(delta, delta', delta'', J_node) of the contact point of ``pair`` (0: P).

        J_node = d delta / d(X, Y, psi) of the contact node (3); for a pair anywhere d delta / dz_e of the
        element holding the nearest point (6, its two nodes' (X, Y, psi)).
        """
        X, V, A = self.nodes(z, zd, zdd)
        return self._gap_of(X, V, A, pair)

    def _gap_of(self, X, V, A, pair: int):
        """:meth:`gap` of ``pair`` from the node arrays (X, V, A) of :meth:`~flexbeam.fem.beam.FemBeam.nodes`."""
        pr = self.pairs[pair]
        if pr.anywhere:
            J = np.empty(6)
            d, vn, dd, _, _ = anywhere_gap(X, V, A, self.l0, pr.offset, pr.kind, pr.centre, pr.radius, pr.normal, J)
            return float(d), float(vn), float(dd), J
        J = np.empty(3)
        p = pr.node
        d, vn, dd = gap_at(X[p], V[p], A[p], pr.offset, pr.kind, pr.centre, pr.radius, pr.normal, J)
        return float(d), float(vn), float(dd), J

    def gaps(self, z: np.ndarray, zd: np.ndarray, zdd: np.ndarray | None = None) -> list[tuple]:
        """:meth:`gap` of every pair."""
        X, V, A = self.nodes(z, zd, zdd)
        return [self._gap_of(X, V, A, k) for k in range(self.npairs)]

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

    def gap_jacobian(self, z: np.ndarray, pair: int = 0) -> np.ndarray:
        """d delta / dz of ``pair`` (dense, length 1 + 3N; a free beam's 3 (N + 1))."""
        _, _, _, Jn = self.gap(z, np.zeros_like(z), pair=pair)
        J = np.zeros(self.size)
        pr = self.pairs[pair]
        first = self.contact_point(z, pair)[0] if pr.anywhere else pr.node
        for a in range(Jn.size // 3):
            p = first + a
            Ja = Jn[3 * a : 3 * a + 3]
            if self.free:
                J[3 * p : 3 * p + 3] += Ja
            elif p == 0:
                th = z[0]
                J[0] += Ja @ np.array([-self.hub_radius * math.sin(th), self.hub_radius * math.cos(th), 1.0])
            else:
                J[3 * p - 2 : 3 * p + 1] += Ja
        return J

    def effective_mass(self, z: np.ndarray, pair: int = 0) -> float:
        """1 / (J M^-1 J^T) at a pair's point with the FE mass matrix (theta fixed if prescribed) [kg]."""
        M, _ = self.matrices(z)
        J = self.gap_jacobian(z, pair)
        if self.prescribed:
            M, J = M[1:, 1:], J[1:]
        return float(1.0 / (J @ np.linalg.solve(M, J)))
