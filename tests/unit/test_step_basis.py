"""The per-step modal basis of the exponential integrator: a rank-one modified eigenproblem.

With the mass matrix frozen at ds = q^T M_c q the modal equations are the pencil
(W^2, M_s = I + ds u u^T).  :func:`_step_basis` solves it through the secular equation; the
truth here is its defining property (W^2 X = M_s X diag(w~^2), X^T M_s X = I), scipy's
generalised symmetric eigensolver for the eigenvalues, and the interlacing of a rank-one
update (Golub 1973).
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
from numpy.testing import assert_allclose

import flexbeam as fb
from flexbeam.integrate.exponential import ModalIntegrator
from flexbeam.integrate.exponential_kernels import (
    FULL_FREEZE_MIN,
    _basis_buffers,
    _modal_model,
    _step_basis,
)
from flexbeam.model.system import BeamSystem


def _model(n):
    integ = ModalIntegrator(BeamSystem.from_case(fb.load_case("seed-experiment", {"model.modes": n})))
    return integ, _modal_model(integ.lin, integ.sysd)


def _basis(integ, mm, ds_inv00):
    """The basis at a state with ds (M_ref^-1)_00 = ``ds_inv00`` (M_c replaced by a multiple of I)."""
    omega = integ.lin[0]
    N = omega.size
    inv00 = integ.lin[5]
    eta = np.zeros(N)
    eta[1] = 1.0
    mm_s = (mm[0], np.eye(N) * (ds_inv00 / inv00))  # ds = eta^T M eta
    basis = _basis_buffers(N)
    _step_basis(eta, integ.lin, integ.sysd, mm_s, np.empty(N), basis)
    return basis, ds_inv00 / inv00


@pytest.mark.parametrize("n", [4, 12, 32])
@pytest.mark.parametrize("ds_inv00", [-0.8, -0.3, -0.06, 0.06, 0.5, 3.0])
def test_step_basis_diagonalises_the_frozen_pencil(n, ds_inv00):
    integ, mm = _model(n)
    basis, ds = _basis(integ, mm, ds_inv00)
    wt, X, XT, XiT, cu, w2u, shift, full = basis
    assert full[0] == 1.0
    omega, u = integ.lin[0], mm[0]
    N = omega.size
    W2 = np.diag(omega**2)
    Ms = np.eye(N) + ds * np.outer(u, u)
    lam = wt**2
    big = lam.max()
    # Eigenvectors from the secular equation lose orthogonality in proportion to the coupling
    # (Gu & Eisenstat 1994, SIAM J. Matrix Anal. Appl. 15): measured <= 2e-11 up to
    # |ds (M^-1)_00| = 3 at n = 32, 1e-15 at the weak end -- far below the integrator's rtol.
    tol = 1e-13 + 1e-11 * abs(ds_inv00)
    # eigenpairs: residual of W^2 x = lambda M_s x in units of the largest eigenvalue
    assert np.abs(W2 @ X - Ms @ X * lam).max() <= 10 * tol * big * np.abs(X).max()
    assert_allclose(X.T @ Ms @ X, np.eye(N), rtol=0, atol=tol)  # M_s-orthonormal
    assert_allclose(XiT.T @ X, np.eye(N), rtol=0, atol=tol)  # X^-1 = X^T M_s
    assert_allclose(XT, X.T, rtol=0, atol=0)
    ref = sla.eigh(W2, Ms, eigvals_only=True)
    assert_allclose(np.sort(lam), ref, rtol=1e-9, atol=1e-12 * big)
    # interlacing: ds > 0 (heavier theta) lowers each frequency towards the one below, ds < 0 raises it
    w2 = omega**2
    for k in range(1, N):
        if ds > 0:
            assert w2[k - 1] - 1e-9 * w2[k] <= lam[k] <= w2[k] * (1 + 1e-12)
        else:
            assert w2[k] * (1 - 1e-12) <= lam[k] <= (w2[k + 1] + 1e-9 * w2[k] if k + 1 < N else np.inf)
    assert lam[0] == 0.0  # the rigid mode stays rigid
    assert_allclose(cu, ds / (1 + ds * integ.lin[5]) * u, rtol=1e-14)


def test_weak_coupling_keeps_the_identity_basis_and_shifts_the_frequencies():
    """Below FULL_FREEZE_MIN only the diagonal of the frozen coupling enters the frequencies."""
    integ, mm = _model(12)
    ds_inv00 = -0.5 * FULL_FREEZE_MIN
    basis, ds = _basis(integ, mm, ds_inv00)
    wt, X, XT, XiT, cu, w2u, shift, full = basis
    assert full[0] == 0.0
    assert_allclose(X, np.eye(X.shape[0]), rtol=0, atol=0)
    omega, u = integ.lin[0], mm[0]
    c0 = ds / (1 + ds * integ.lin[5])
    assert_allclose(shift, c0 * u**2 * omega**2, rtol=1e-14)
    assert_allclose(wt**2, omega**2 - shift, rtol=1e-12)
