"""The compiled equations of motion (``kernels/src/model.c``) against their kinematics, in both frames:
energy rate = drive power, second-order accuracy of T, finite-difference Jacobians, measuring-point velocities."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from flexbeam.model.system import BeamSystem
from tests.conftest import seed

FRAMES = ["system", "hub"]


def _random_state(system, rng, scale=1e-4):
    """A state with modal amplitudes of a realistic spectrum (q_k ~ scale / k^2)."""
    n = system.n
    k2 = np.arange(1, n + 1) ** 2
    return system.state(
        rng.uniform(-1, 1), rng.uniform(-20, 20), rng.normal(size=n) * scale / k2, rng.normal(size=n) * scale * 300 / k2
    )


@pytest.mark.parametrize("frame", FRAMES)
@pytest.mark.parametrize("coupling", ["first-order", "zeroth-order"])
def test_energy_rate_equals_drive_power(frame, coupling):
    """d/dt (T + V_e + V_g) = tau phi' along the free equations, phi = theta + d q the hub angle (Lagrange
    consistency: a torque on the hub works on the hub angle, in the system frame through d = Psi'(0))."""
    case = seed(
        model__modes=4,
        model__coupling=coupling,
        model__frame=frame,
        hub__radius=0.05,
        hub__inertia=0.01,
        drive__kind="torque",
        drive__torque=3.0,
    )
    system = BeamSystem.from_case(case)
    rng = np.random.default_rng(1)
    for _ in range(5):
        y = _random_state(system, rng)
        yd = system.rhs(0.0, y)[0]
        energy = lambda s: sum(system.energies(0.0, s)[k] for k in ("kinetic", "elastic", "gravitational"))  # noqa: E731
        h = 1e-7
        rate = (energy(y + h * yd) - energy(y - h * yd)) / (2 * h)
        phi_rate = system.hub_angle(0.0, y)[1]
        assert_allclose(rate, 3.0 * phi_rate, rtol=1e-6, atol=1e-9)
        assert_allclose(yd[-1], 3.0 * phi_rate, rtol=1e-14)  # the booked drive power


@pytest.mark.parametrize("frame", FRAMES)
def test_kinetic_energy_is_the_second_order_expansion_of_the_exact_one(frame):
    """T_model - T_exact = O(eps^3) for deformation amplitude eps.  Exact: quadrature of mu |v|^2 / 2 over the beam
    with rho = (r_h + x - q^T H(x) q / 2, Psi(x) q) kept whole, plus the hub's 1/2 J_h phi'^2 with the exact
    hub angle phi = theta + asin(d q) (the root's slope in the frame)."""
    case = seed(model__modes=3, model__frame=frame, hub__radius=0.05, hub__inertia=0.02)
    system = BeamSystem.from_case(case)
    b = system.beam
    L, mu, rh, Jh = b.length, b.line_density, b.hub_radius, b.hub_inertia
    xg, wg = np.polynomial.legendre.leggauss(200)
    x, w = 0.5 * L * (xg + 1), 0.5 * L * wg
    phi = b.shapes(x, 0)
    H = np.array([b.point(xi).H for xi in x])
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
        dq = float(b.d @ q)
        hub_rate = omega + float(b.d @ qd) / math.sqrt(1.0 - dq * dq)
        T_exact = 0.5 * np.sum(w * mu * (vx**2 + vy**2)) + 0.5 * Jh * hub_rate**2
        T_model = system.energies(0.0, system.state(0.0, omega, q, qd))["kinetic"]
        errors.append(abs(T_model - T_exact))
    order = np.log(errors[0] / errors[2]) / np.log(4.0)
    assert order > 2.8


@pytest.mark.parametrize("frame", FRAMES)
def test_contact_jacobian_and_velocity_terms_match_finite_differences(frame):
    system = BeamSystem.from_case(seed(model__modes=4, model__frame=frame, hub__radius=0.03))
    rng = np.random.default_rng(3)
    y = _random_state(system, rng)
    delta, vn, gamma, J = system.gap(0.0, y)
    N = system.n + 1
    h = 1e-7
    for i in range(N):
        dy = np.zeros_like(y)
        dy[i] = h
        fd = (system.gap(0.0, y + dy)[0] - system.gap(0.0, y - dy)[0]) / (2 * h)
        assert_allclose(J[i], fd, rtol=1e-6, atol=1e-9)
    yd = system.rhs(0.0, y)[0]
    acc_fd = (system.gap(0.0, y + h * yd)[1] - system.gap(0.0, y - h * yd)[1]) / (2 * h)
    zdd = yd[N : 2 * N]
    assert_allclose(J @ zdd + gamma, acc_fd, rtol=1e-5)


@pytest.mark.parametrize("frame", FRAMES)
def test_mass_matrix_is_symmetric_positive_definite(frame):
    system = BeamSystem.from_case(seed(model__modes=6, model__frame=frame))
    y = _random_state(system, np.random.default_rng(4))
    M = system.mass_matrix(0.0, y)
    assert_allclose(M, M.T)
    assert np.all(np.linalg.eigvalsh(M) > 0)


def test_system_frame_has_no_light_coordinate():
    """The point of the system frame: at J_h = 0 the hub frame's root-slope angle has the Schur complement
    J0 - m_tf M_ff^-1 m_tf^T -> 0 as n grows (issue 4: 5e-6 kg m^2 at n = 12 against J0 = 0.21), while the
    system frame's linear mass matrix is diag(J0, mu L I): no coordinate is lighter than the beam itself."""
    for frame, small in (("hub", True), ("system", False)):
        system = BeamSystem.from_case(seed(model__modes=12, model__frame=frame))
        M = system.mass_matrix(0.0, system.state(0.0, 0.0))
        schur = M[0, 0] - M[0, 1:] @ np.linalg.solve(M[1:, 1:], M[1:, 0])
        J0 = system.beam.J0
        assert (schur < 1e-3 * J0) == small
        if frame == "system":
            assert_allclose(M, np.diag(np.diag(M)), atol=0)
            assert_allclose(schur, J0, rtol=1e-14)


@pytest.mark.parametrize("frame", FRAMES)
def test_measuring_point_velocity_is_the_rate_of_its_position(frame):
    """The output's measuring-point velocity = (d/dt of the point's global position) . (the hub's normal),
    central differences along the state's own rates."""
    case = seed(model__modes=5, model__frame=frame, hub__inertia=0.01, output__measuring_points=[0.1, 0.585, 0.7])
    system = BeamSystem.from_case(case)
    rng = np.random.default_rng(7)
    for _ in range(3):
        y = _random_state(system, rng, scale=1e-3)
        yd = system.rhs(0.0, y)[0]
        phi = system.hub_angle(0.0, y)[0]
        normal = np.array([-np.sin(phi), np.cos(phi)])
        _, mv, _ = system.outputs(np.zeros(1), y[None, :])
        h = 1e-7
        for j in range(3):
            ends = [system.point_state(0.0, y + s * yd, 2 + j)[0] for s in (h, -h)]
            v = (ends[0] - ends[1]) / (2 * h)
            assert_allclose(mv[0, j], v @ normal, rtol=1e-7, atol=1e-10)
