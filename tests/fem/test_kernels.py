"""Element-level identities of the co-rotational beam element and its inertia.

* the tangent stiffness is the derivative of the internal force (finite differences);
* the inertia force is exactly Lagrange's d/dt dT/dz' - dT/dz of the kinetic energy
  the kernels evaluate (finite differences of T);
* a rigid motion of an element stores no strain energy and has no internal force;
* for a straight element the mass matrix is the classical consistent matrix
  (linear axial, Hermite-cubic transverse: e.g. Przemieniecki 1968, mu l/420 [156 ...]);
* the band LU solver agrees with a dense solve.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from flexbeam.fem import FemBeam
from flexbeam.fem.banded import band_solve
from flexbeam.fem.element import GAUSS_W, GAUSS_XI, corotational_element, inertia_element
from tests.fem.cases import general_beam, seed


def _deformed(beam: FemBeam, seed_value: int = 0):
    rng = np.random.default_rng(seed_value)
    z, zd = beam.straight(0.4, 1.3)
    z[1:] += 2e-3 * rng.standard_normal(z.size - 1)
    zd += 0.5 * rng.standard_normal(z.size)
    zdd = 10.0 * rng.standard_normal(z.size)
    return z, zd, zdd


@pytest.mark.parametrize("hub_radius", [0.0, 0.05])
def test_tangent_is_derivative_of_internal_force(hub_radius):
    case = seed(fem__elements=6, model__gravity=0.0, hub__radius=hub_radius)
    beam = FemBeam.from_case(case)
    beam.mu = 0.0  # internal forces only
    z, zd, zdd = _deformed(beam)
    _, ab, _ = beam.residual(0.0, z, zd, zdd, (0.0, 0.0, 1.0))
    K = beam.band_to_dense(ab)
    h = 1e-7
    Kfd = np.empty_like(K)
    for j in range(z.size):
        zp, zm = z.copy(), z.copy()
        zp[j] += h
        zm[j] -= h
        Kfd[:, j] = (beam.residual(0.0, zp, zd, zdd)[0] - beam.residual(0.0, zm, zd, zdd)[0]) / (2 * h)
    assert_allclose(K, Kfd, atol=1e-6 * np.abs(K).max())


def test_inertia_force_is_lagrange_of_kinetic_energy():
    """f_in = M(z) z'' + d(M z')/dz z' - dT/dz, with T from the energy kernel."""
    case = seed(fem__elements=5, model__gravity=0.0, hub__radius=0.03, hub__inertia=1e-3)
    beam = FemBeam.from_case(case)
    beam.EA = beam.EI = 0.0  # inertia only
    z, zd, zdd = _deformed(beam, 1)
    R, abM, _ = beam.residual(0.0, z, zd, zdd, (1.0, 0.0, 0.0))
    M = beam.band_to_dense(abM)

    def T(zz, vv):
        return beam.energies(zz, vv)[0]

    h = 1e-6
    # dT/dz' = M z' (check), d/dt of it along the motion, and dT/dz
    grad_v = np.array([(T(z, zd + h * e) - T(z, zd - h * e)) / (2 * h) for e in np.eye(z.size)])
    assert_allclose(grad_v, M @ zd, rtol=1e-7, atol=1e-9 * np.abs(M @ zd).max())
    dMv = (M_at(beam, z + h * zd) @ zd - M_at(beam, z - h * zd) @ zd) / (2 * h)
    grad_z = np.array([(T(z + h * e, zd) - T(z - h * e, zd)) / (2 * h) for e in np.eye(z.size)])
    lagrange = M @ zdd + dMv - grad_z
    assert_allclose(R, lagrange, atol=2e-6 * np.abs(R).max())


def M_at(beam: FemBeam, z: np.ndarray) -> np.ndarray:
    zero = np.zeros_like(z)
    _, ab, _ = beam.residual(0.0, z, zero, zero, (1.0, 0.0, 0.0))
    return beam.band_to_dense(ab)


def test_rigid_motion_is_strain_free():
    """Zero up to round-off: the stretch is a difference of lengths computed from coordinates of size |x|, so it
    errs by ~eps |x| / l0 (the rotations by eps |angle|), times the stiffness EA (EI / l0); measured 5.3e-10 N
    against that unit 2.4e-9 N, bound 10 units.  V = EA l0 stretch^2 / 2 is the square of it (< 1e-18)."""
    fe, Ke = np.empty(6), np.empty((6, 6))
    l0, EA, EI = 0.2, 1e6, 10.0
    for ang in (0.0, 0.7, -2.5, 3.1):
        c, s = math.cos(ang), math.sin(ang)
        xe = np.array([1.0, -2.0, ang + 4 * math.pi, 1.0 + l0 * c, -2.0 + l0 * s, ang - 2 * math.pi])
        V = corotational_element(xe, l0, EA, EI, fe, Ke, True)
        size, turn = np.max(np.abs(xe[[0, 1, 3, 4]])), np.max(np.abs(xe[[2, 5]]))
        unit = np.finfo(float).eps * (EA * size / l0 + EI * turn / l0**2)
        assert abs(V) < 1e-18
        assert_allclose(fe, 0.0, atol=10 * unit)


def test_straight_element_mass_is_classical_consistent_mass():
    mu, l0 = 2.0, 0.3
    xe = np.array([0.0, 0.0, 0.0, l0, 0.0, 0.0])
    fin, Me, fg, G = np.empty(6), np.empty((6, 6)), np.empty(6), np.empty((2, 6))
    inertia_element(xe, np.zeros(6), np.zeros(6), l0, mu, np.array([0.0, -9.81]), GAUSS_XI, GAUSS_W, fin, Me, fg, G)
    ell = l0
    bend = mu * ell / 420.0 * np.array([
        [156, 22 * ell, 54, -13 * ell],
        [22 * ell, 4 * ell * ell, 13 * ell, -3 * ell * ell],
        [54, 13 * ell, 156, -22 * ell],
        [-13 * ell, -3 * ell * ell, -22 * ell, 4 * ell * ell],
    ])  # fmt: skip
    axial = mu * ell / 6.0 * np.array([[2, 1], [1, 2]])
    iv, ia = [1, 2, 4, 5], [0, 3]
    assert_allclose(Me[np.ix_(iv, iv)], bend, rtol=1e-13, atol=1e-15)
    assert_allclose(Me[np.ix_(ia, ia)], axial, rtol=1e-13)
    assert_allclose(Me[np.ix_(ia, iv)], 0.0, atol=1e-15)
    # consistent gravity load: -mu g l [1/2, l/12, 1/2, -l/12] on (Y, psi)
    assert_allclose(fg[iv], -mu * 9.81 * ell * np.array([0.5, ell / 12, 0.5, -ell / 12]), rtol=1e-13)


def test_band_solver_matches_dense_solve():
    beam = FemBeam.from_case(general_beam(fem__elements=7))
    z, zd, zdd = _deformed(beam, 2)
    _, ab, _ = beam.residual(0.0, z, zd, zdd, (1e6, 1e3, 1.0))
    A = beam.band_to_dense(ab)
    b = np.arange(1.0, z.size + 1)
    x = b.copy()
    assert band_solve(ab.copy(), x)
    assert_allclose(x, np.linalg.solve(A, b), rtol=1e-10)
