"""Equations of motion against their kinematics: energy rate, expansion order, Jacobians."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from flexbeam.model.modes import cantilever_modes
from flexbeam.model.system import BeamSystem
from tests.conftest import seed


def _random_state(system, rng, scale=1e-4):
    """A state with modal amplitudes of a realistic spectrum (q_k ~ scale / k^2)."""
    n = system.n
    k2 = np.arange(1, n + 1) ** 2
    return system.state(rng.uniform(-1, 1), rng.uniform(-20, 20), rng.normal(size=n) * scale / k2,
                        rng.normal(size=n) * scale * 300 / k2)


@pytest.mark.parametrize("coupling", ["first-order", "zeroth-order"])
def test_energy_rate_equals_drive_power(coupling):
    """d/dt (T + V_e + V_g) = tau theta' along the free equations (Lagrange consistency)."""
    case = seed(model__modes=4, model__coupling=coupling, hub__radius=0.05, hub__inertia=0.01,
                drive__kind="torque", drive__torque=3.0)
    system = BeamSystem.from_case(case)
    rng = np.random.default_rng(1)
    for _ in range(5):
        y = _random_state(system, rng)
        yd = system.rhs(0.0, y)[0]
        energy = lambda s: sum(system.energies(0.0, s)[k] for k in ("kinetic", "elastic", "gravitational"))
        h = 1e-7
        rate = (energy(y + h * yd) - energy(y - h * yd)) / (2 * h)
        assert_allclose(rate, 3.0 * y[system.n + 1], rtol=1e-6, atol=1e-9)


def test_kinetic_energy_is_the_second_order_expansion_of_the_exact_one():
    """T_model - T_exact = O(eps^3) for deformation amplitude eps (exact = quadrature of |v|^2/2)."""
    case = seed(model__modes=3, hub__radius=0.05)
    system = BeamSystem.from_case(case)
    b = system.beam
    L, mu, rh = b.length, b.line_density, b.hub_radius
    xg, wg = np.polynomial.legendre.leggauss(200)
    x, w = 0.5 * L * (xg + 1), 0.5 * L * wg
    phi = cantilever_modes(x, L, 3, 0)
    H = np.array([system.beam.point(xi).H for xi in x])
    rng = np.random.default_rng(2)
    q0, qd0, omega = rng.normal(size=3), rng.normal(size=3) * 50, 7.0
    errors = []
    for eps in (1e-2, 5e-3, 2.5e-3):
        q, qd = eps * q0, eps * qd0
        uy, uyd = phi @ q, phi @ qd
        ux = -0.5 * np.einsum("i,kij,j->k", q, H, q)
        uxd = -np.einsum("i,kij,j->k", qd, H, q)
        vx = uxd - omega * uy
        vy = omega * (rh + x + ux) + uyd
        T_exact = 0.5 * np.sum(w * mu * (vx**2 + vy**2)) + 0.5 * 0.0 * omega**2
        T_model = system.energies(0.0, system.state(0.0, omega, q, qd))["kinetic"]
        errors.append(abs(T_model - T_exact))
    order = np.log(errors[0] / errors[2]) / np.log(4.0)
    assert order > 2.8


def test_contact_jacobian_and_velocity_terms_match_finite_differences():
    system = BeamSystem.from_case(seed(model__modes=4))
    rng = np.random.default_rng(3)
    y = _random_state(system, rng)
    delta, vn, gamma, J = system.gap(0.0, y)
    N = system.n + 1
    h = 1e-7
    z_index = [0] + list(range(1, N))
    for i in z_index:
        dy = np.zeros_like(y)
        dy[i] = h
        fd = (system.gap(0.0, y + dy)[0] - system.gap(0.0, y - dy)[0]) / (2 * h)
        assert_allclose(J[i], fd, rtol=1e-6, atol=1e-9)
    yd = system.rhs(0.0, y)[0]
    acc_fd = (system.gap(0.0, y + h * yd)[1] - system.gap(0.0, y - h * yd)[1]) / (2 * h)
    zdd = yd[N : 2 * N]
    assert_allclose(J @ zdd + gamma, acc_fd, rtol=1e-5)


def test_mass_matrix_is_symmetric_positive_definite():
    system = BeamSystem.from_case(seed(model__modes=6))
    y = _random_state(system, np.random.default_rng(4))
    M = system.mass_matrix(0.0, y)
    assert_allclose(M, M.T)
    assert np.all(np.linalg.eigvalsh(M) > 0)


def test_measuring_point_velocity_is_the_rate_of_its_position():
    """transverse_velocity = (d/dt of the point's global position) . (beam normal), central differences."""
    from flexbeam.model.kernels import point_kinematics, transverse_velocity

    system = BeamSystem.from_case(seed(model__modes=5))
    beam = system.beam
    rng = np.random.default_rng(7)
    dr = np.empty((2, beam.n + 1))
    for x in (0.1, 0.585, beam.length):
        pt = beam.point(x)
        for _ in range(3):
            theta, omega = rng.uniform(-1, 1), rng.uniform(-30, 30)
            q = rng.normal(size=beam.n) * 1e-3 / np.arange(1, beam.n + 1) ** 2
            qd = rng.normal(size=beam.n) * 0.3 / np.arange(1, beam.n + 1)
            h = 1e-7
            ends = [point_kinematics(theta + s * omega, omega, q + s * qd, qd, pt.base, pt.phi, pt.dphi, pt.H, 0.0,
                                     dr)[0] for s in (h, -h)]
            v = (ends[0] - ends[1]) / (2 * h)
            normal = np.array([-np.sin(theta), np.cos(theta)])
            got = transverse_velocity(omega, q, qd, pt.base, pt.phi, pt.H)
            assert_allclose(got, v @ normal, rtol=1e-7, atol=1e-10)
