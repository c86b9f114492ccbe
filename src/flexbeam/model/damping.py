"""The beam's structural damping: two physically defined laws, diagonal in the modes of a clamped beam.

* **Kelvin-Voigt material damping** (``beam.kelvin_voigt`` = c [s]): the stress sigma = E (epsilon + c epsilon'),
  so EI -> EI (1 + c d/dt) in bending (and EA -> EA (1 + c d/dt) in the axial modes); the generalised force on the
  flexible coordinates is -c K q', K = blockdiag(K_ff, K_a), and mode i's damping ratio is zeta_i = c omega_i / 2
  (the stiffness-proportional part of Rayleigh damping: R. W. Clough, J. Penzien, *Dynamics of Structures*, 2nd ed.,
  McGraw-Hill 1993).
* **Viscous damping per unit length** (``beam.viscous_damping`` = eta [N s/m^2]): a force -eta w' per unit length on
  the deformation velocity relative to the beam's frame (Wagg & Bishop, J. Sound Vib. 256 (2002) 803, "viscous
  damping eta per unit length"), acting between the beam and its frame (internal: it dissipates, it does not brake
  the frame); the generalised force is -(eta / mu) M q', M = blockdiag(M_ff, M_aa) = int mu [Psi, Phi_a]^T [Psi,
  Phi_a] dx, and zeta_i = eta / (2 mu omega_i) (mass-proportional damping).

Both act on the flexible coordinates only, C = c K + (eta / mu) M, dissipating q'^T C q' >= 0.  In the hub frame
of a clamped beam (a prescribed hub angle, a moving base) C is diagonal in the modal basis, 2 zeta_i omega_i =
c omega_i^2 + eta / mu; in the system frame with a hub inertia, or in the hub frame of a free hub angle, the viscous
part is not, and its off-diagonal part is left to the collocated remainder (``kernels/src/damped.c``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .. import numerics as nm

if TYPE_CHECKING:
    from ..parameters import Case
    from .beam import ModalBeam


def damping_matrix(case: Case, beam: ModalBeam) -> np.ndarray | None:
    """C = c K + (eta / mu) M over the flexible coordinates [q, p] (n + n_a square), or None for an undamped beam
    (both coefficients 0: the kernels' buffers and results are then exactly the undamped ones)."""
    c, eta = case.beam.kelvin_voigt, case.beam.viscous_damping
    if c == 0.0 and eta == 0.0:
        return None
    n, nq = beam.n, beam.nq
    K, M = np.zeros((nq, nq)), np.zeros((nq, nq))
    K[:n, :n], M[:n, :n] = beam.Kff, beam.Mff
    if beam.axial is not None:
        K[n:, n:], M[n:, n:] = np.diag(beam.axial.Ka), np.diag(beam.axial.Maa)
    return c * K + (eta / beam.line_density) * M


def modal_damping(C: np.ndarray | None, Psi: np.ndarray, omega: np.ndarray, offset: int) -> np.ndarray | None:
    """Each mode's damping coefficient d_k = 2 zeta_k omega_k = (Psi^T C_z Psi)_kk, C_z the damping C of the flexible
    coordinates placed at ``offset`` in the integrator's coordinates (the rigid ones before, a support's after);
    0 for a mode of zero frequency (a rigid mode, which C does not damp).  None when C is None."""
    if C is None:
        return None
    N, nq = omega.size, C.shape[0]
    Cz = np.zeros((N, N))
    Cz[offset : offset + nq, offset : offset + nq] = C
    CP = nm.matmul(Cz, np.ascontiguousarray(Psi))
    d = np.array([nm.dot(np.ascontiguousarray(Psi[:, k]), np.ascontiguousarray(CP[:, k])) for k in range(N)])
    return np.where(omega > 0.0, np.maximum(d, 0.0), 0.0)
