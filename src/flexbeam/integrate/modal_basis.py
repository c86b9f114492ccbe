"""The linearisation's modes of a system: the basis in which the compiled integrator propagates each mode exactly
(:class:`ModalBasis`, ``flexbeam.integrate.modal``), and which sets the reference integrator's stiffness."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import numerics as nm
from ..kernels import pack_basis
from ..model.damping import modal_damping
from ..model.system import BeamSystem

OMEGA_RIGID_DEFAULT = 1e3  # [rad/s] weighs a rigid angle error when the beam has no flexible mode


@dataclass(frozen=True)
class ModalBasis:
    """The linearisation's modes: z_ext = Psi eta with z_ext = [z, s] (s: a compliant support's coordinate).

    ``omega`` (N) and ``Psi`` (N x N) with Psi^T M0 Psi = I, Psi^T K0 Psi = diag(omega^2); ``toM`` = Psi^T M0
    (eta from z); ``row0`` = e0^T M0^-1 and ``inv00`` = (M0^-1)_00 for the Sherman-Morrison update of a free
    joint's mass matrix; ``diagonal``: Psi is diagonal.
    """

    omega: np.ndarray
    Psi: np.ndarray
    toM: np.ndarray
    row0: np.ndarray
    inv00: float
    nz: int
    diagonal: bool
    #: each mode's damping coefficient d = 2 zeta omega of the beam's structural damping (None: undamped)
    damp: np.ndarray | None = None

    @classmethod
    def of(cls, system: BeamSystem) -> ModalBasis:
        nz = system.nz
        M0, K0, varying = system.joint.linear_model(system.beam)
        offdiag = lambda A: A - np.diag(np.diag(A))  # noqa: E731
        diagonal = not offdiag(M0).any() and not offdiag(K0).any()
        if diagonal:
            Psi = np.diag(1.0 / np.sqrt(np.diag(M0))) if nz else np.zeros((0, 0))
            w2 = np.diag(K0) / np.diag(M0) if nz else np.zeros(0)
        else:  # (K0, M0) through the Cholesky factor M0 = L L^T (no scipy at start-up)
            Linv = nm.inv(nm.cholesky(M0))
            w2, Y = nm.eigh(nm.matmul(nm.matmul(Linv, K0), np.ascontiguousarray(Linv.T)))
            Psi = nm.matmul(np.ascontiguousarray(Linv.T), Y)
            w2 = np.where(w2 < 1e-10 * max(float(np.max(w2, initial=0.0)), 1.0), 0.0, w2)
        omega = np.sqrt(np.maximum(w2, 0.0))
        if nz:
            M0inv = nm.inv(M0)
            row0 = M0inv[varying] if varying is not None else np.zeros(nz)
            inv00 = float(M0inv[varying, varying]) if varying is not None else 0.0
        else:
            row0, inv00 = np.zeros(0), 0.0
        toM = nm.matmul(np.ascontiguousarray(Psi.T), M0)
        if system.compliant:  # the support's sqrt(m_s) s, frequency sqrt(k_s / m_s)
            ms, ks = float(system.contact.obstacle.support[0]), float(system.contact.obstacle.support[1])  # obstacle 0
            omega = np.append(omega, math.sqrt(ks / ms))
            Psi = _border(Psi, 1.0 / math.sqrt(ms))
            toM = _border(toM, math.sqrt(ms))
        damp = modal_damping(system.damping, Psi, omega, system.joint.nrigid - system.joint.ngiven)
        return cls(omega, np.ascontiguousarray(Psi), np.ascontiguousarray(toM), row0, inv00, nz, diagonal, damp)

    @property
    def N(self) -> int:
        return self.omega.size

    def packed(self) -> np.ndarray:
        return pack_basis(
            self.omega, self.Psi, self.toM, self.row0, self.inv00, self.nz, self.diagonal, self.damp
        )  # fmt: skip

    @property
    def omega_rigid(self) -> float:
        """Lowest flexible frequency: it weighs a rigid-mode angle error in the energy norm."""
        positive = self.omega[self.omega > 0.0]
        return float(positive.min()) if positive.size else OMEGA_RIGID_DEFAULT


def _border(A: np.ndarray, value: float) -> np.ndarray:
    N = A.shape[0]
    out = np.zeros((N + 1, N + 1))
    out[:N, :N] = A
    out[N, N] = value
    return out
