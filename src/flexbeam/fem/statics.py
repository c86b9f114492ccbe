"""The FE beam at rest: static equilibrium under gravity and a load (Newton with load stepping), and the natural
frequencies of small vibration about the straight beam (the generalised eigenproblem K phi = w^2 M phi)."""

from __future__ import annotations

import numpy as np
from scipy.linalg import eigh, solve_banded

from ..errors import SolverError
from .banded import BAND, fix_first_dof


class StaticsAndVibration:
    """Equilibria and vibration of :class:`~flexbeam.fem.beam.FemBeam` (a mixin: it uses the beam's
    :meth:`~flexbeam.fem.beam.FemBeam.residual`, ``matrices``, ``straight`` and ``increment_scale``)."""

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
        z = self.straight(theta, 0.0)[0] if z0 is None else z0.copy()
        z[0] = theta
        load = np.zeros_like(z) if load is None else np.asarray(load, float)
        lam, dlam = 0.0, 1.0 / steps
        while lam < 1.0:
            target = min(1.0, lam + dlam)
            trial = self._static_newton(z, target * load, tol, max_iter)
            if trial is not None:
                z, lam = trial, target
                dlam = min(2.0 * dlam, 1.0 / steps)
            else:
                dlam *= 0.5
                if dlam < 1e-6 / steps:
                    raise SolverError(f"fem: static equilibrium did not converge (load factor {lam:.6g})")
        return z

    def _static_newton(self, z: np.ndarray, load: np.ndarray, tol: float, max_iter: int) -> np.ndarray | None:
        """Newton from ``z`` (the hub held) on f_int - f_g - ``load`` = 0: the solution, or None if it fails."""
        zero = np.zeros_like(z)
        scale = self.increment_scale()
        trial = z.copy()
        for _ in range(max_iter):
            R, ab, _ = self.residual(0.0, trial, zero, zero, (0.0, 0.0, 1.0))
            R = R - load
            R[0] = 0.0
            fix_first_dof(ab)
            dz = solve_banded((BAND, BAND), ab[BAND:], -R)
            if not np.all(np.isfinite(dz)):
                return None
            trial += dz
            if np.max(np.abs(dz) / scale) < tol:
                return trial
        return None

    def frequencies(self, theta: float = 0.0, pinned: bool | None = None) -> np.ndarray:
        """Natural frequencies [rad/s] of small vibration about the straight beam at rest.

        ``pinned`` (default: the joint is free) keeps theta as a coordinate (the root
        rotates with the hub: pinned-free for J_h = r_h = 0); otherwise the root is
        clamped.  Zero-frequency (rigid-body) modes are included.  A free beam (no joint) is free-free, at
        ``theta``, its three rigid-body modes the first three.
        """
        if self.free:
            z, _ = self.free_straight(np.zeros(2), theta, np.zeros(2), 0.0)
            M, K = self.matrices(z)
            w2 = eigh(K, M, eigvals_only=True)
            return np.sqrt(np.clip(w2, 0.0, None))
        pinned = (not self.prescribed) if pinned is None else pinned
        z, _ = self.straight(theta, 0.0)
        M, K = self.matrices(z)
        if not pinned:
            M, K = M[1:, 1:], K[1:, 1:]
        w2 = eigh(K, M, eigvals_only=True)
        return np.sqrt(np.clip(w2, 0.0, None))
