"""A free FE beam's rigid-body motion for its collision episodes (:mod:`flexbeam.results.episodes`).

The episodes and the apparent restitution (:mod:`flexbeam.results.restitution`) read the beam's rigid-body motion
(v_G, Omega) before, during and after a collision.  The FE run records at every accepted state G's velocity and
acceleration and the angular momentum about G and its rate (:meth:`flexbeam.fem.free.FreeBody.rigid`: the momentum
of the interpolated field over m, H_G / J_G), and, where the contact state changes, each pair's contact normal n and
lever arm a = (rho_P x n)_z about G (:meth:`~flexbeam.fem.free.FreeBody.rigid_jacobian`).  Between two samples the
motion is the cubic Hermite interpolant of v_G and H_G through their values and rates at both ends (the rates are
the equations of motion's: the contact force over m less g, its torque about G); the contact force on an integrator
step is the FE's own dense force (:mod:`flexbeam.fem.dense_force`: the law on the quintic Hermite of the gap).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

import numpy as np

from ..results.restitution import Motion, Piece, free_free_period
from .contact_law import law_force
from .dense_force import _quintic

if TYPE_CHECKING:
    from .beam import FemBeam
    from .run_record import Record


class FemMotion(Motion):
    """(v_G, Omega) of a free FE beam's run on its samples (the module docstring).

    ``times`` and ``rigid``: the samples and their rows [x_G, y_G, v_Gx, v_Gy, a_Gx, a_Gy, H_G, H_G'] (SI units).
    """

    def __init__(
        self,
        times: np.ndarray,
        rigid: np.ndarray,
        strikes: list[tuple[float, np.ndarray]],
        dense: list[tuple],
        positions: np.ndarray,
        inertia: float,
        gravity: float,
        length: float,
        period: float,
    ) -> None:
        self.times, self.rigid, self.strikes, self.dense = times, rigid, strikes, dense
        self.positions, self.JG, self.g = positions, inertia, gravity
        self.length, self.period = length, period
        self.t_final = float(times[-1]) if times.size else 0.0
        self.normal, self.lever, self.t0 = np.array([0.0, 1.0]), 0.0, 0.0

    @classmethod
    def of_run(cls, beam: FemBeam, times: np.ndarray, sampler, rec: Record, arrays: dict[str, np.ndarray]) -> FemMotion:
        """The motion of a run's samples (``sampler``: :class:`flexbeam.fem.simulate._Sampler`), contact log and
        output ``arrays``."""
        L = float(beam.x_nodes[-1])
        if "pair_contact_position" in arrays:
            positions = np.asarray(arrays["pair_contact_position"], float)
        else:
            positions = np.tile([p.position for p in beam.pairs], (times.size, 1))
        return cls(
            np.asarray(times, float),
            np.asarray(sampler.rigid_rows, float).reshape(times.size, 8),
            list(sampler.strikes),
            list(rec.dense),
            positions,
            beam.rigid_inertia,
            beam.gravity,
            L,
            free_free_period(L, beam.EI, beam.mu),
        )

    # ------------------------------------------------------------------ the samples and between them
    def _index(self, t: float, after: bool) -> int | None:
        """The sample at time t (the last of equal times if ``after``, else the first), None between samples."""
        lo = int(np.searchsorted(self.times, t, side="left"))
        hi = int(np.searchsorted(self.times, t, side="right"))
        if hi > lo:
            return hi - 1 if after else lo
        return None

    def motion(self, times: np.ndarray) -> np.ndarray:
        """(v_Gx, v_Gy, Omega) at ``times`` (rows), cubic Hermite between the samples."""
        T, Y = self.times, self.rigid
        times = np.asarray(times, float)
        i = np.clip(np.searchsorted(T, times, side="right") - 1, 0, max(T.size - 2, 0))
        j = np.minimum(i + 1, T.size - 1)
        h = T[j] - T[i]
        s = np.where(h > 0.0, (times - T[i]) / np.where(h > 0.0, h, 1.0), 0.0)
        s2, s3 = s * s, s * s * s
        h00, h10, h01, h11 = 2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2
        out = np.empty((times.size, 3))
        for col, (val, rate) in enumerate(((2, 4), (3, 5), (6, 7))):
            y = h00 * Y[i, val] + h10 * h * Y[i, rate] + h01 * Y[j, val] + h11 * h * Y[j, rate]
            out[:, col] = y
        out[:, 2] /= self.JG
        return out

    def state(self, t: float, after: bool) -> np.ndarray:
        k = self._index(t, after)
        if k is None:
            return self.motion(np.array([t]))[0]
        v = self.rigid[k]
        return np.array([v[2], v[3], v[6] / self.JG])

    def strike(self, t0: float, pair: int) -> None:
        """The normal and lever arm of ``pair`` recorded at the contact-state change nearest t0."""
        k = int(np.argmin([abs(t - t0) for t, _ in self.strikes]))
        na = self.strikes[k][1][pair]
        self.normal, self.lever, self.t0 = np.array(na[:2], float), float(na[2]), t0

    def velocity(self, times: np.ndarray, rigid: np.ndarray) -> np.ndarray:
        """v(t) of the frozen striking point from (v_Gx, v_Gy, Omega) rows, gravity's share taken out."""
        vy = rigid[:, 1] + self.g * (np.asarray(times, float) - self.t0)
        return self.normal[0] * rigid[:, 0] + self.normal[1] * vy + self.lever * rigid[:, 2]

    def at(self, t: float, after: bool) -> float:
        return float(self.velocity(np.array([t]), self.state(t, after)[None, :])[0])

    def pieces(self, t0: float, t1: float, pair: int) -> Iterator[tuple[Piece, float, float]]:
        """One piece per contact step of ``pair`` over [t0, t1]."""
        for d in self.dense:
            if d[5] == pair and d[1] > d[0] and d[1] >= t0 and d[0] <= t1:
                yield _StepPiece(self, d), max(t0, d[0]), min(t1, d[1])

    def contact_position(self, t: float, pair: int) -> float:
        k = self._index(t, after=True)
        if k is None:
            k = max(int(np.searchsorted(self.times, t)) - 1, 0)
        return float(self.positions[k, pair])


class _StepPiece(Piece):
    """One FE contact step: the law on the quintic Hermite of its gap."""

    def __init__(self, motion: FemMotion, step: tuple) -> None:
        self.motion, self.step = motion, step

    def breaks(self) -> np.ndarray:
        return np.array(self.step[:2], float)

    def force(self, times: np.ndarray) -> np.ndarray:
        a, b, g0, g1, lawp, _ = self.step
        out = np.empty(len(times))
        for k, t in enumerate(times):
            d, dd = _quintic((t - a) / (b - a), b - a, g0, g1)
            out[k] = law_force(lawp, -d, -dd)[0]
        return out

    def speed(self, times: np.ndarray) -> np.ndarray:
        return self.motion.velocity(times, self.motion.motion(times))


__all__ = ["FemMotion"]
