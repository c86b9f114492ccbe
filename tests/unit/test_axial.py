"""The axial modes (``model.axial_modes``; docs/formulation.md, "Axial deformation") against independent truths.

* the modal integrals' closed forms (M_aa, K_a, s_a, m_ta) against Gauss-Legendre quadrature of their definitions
  with the shapes written out here; S's parity for free-free modes (S_kj = 0 for k + j even, symmetry about L/2);
* the linearised model's axial frequencies against the rod's: (k - 1/2) pi c / L fixed-free (revolute joint) and
  k pi c / L free-free (free beam), c = sqrt(E / rho);
* the kinetic energy is the second-order expansion of the exact one (quadrature of mu |r'|^2 / 2 over the beam with
  rho = (b + Phi_a p - 1/2 q^T H q, Psi q) kept whole): the difference falls like eps^3;
* M(q, p) and Q are Lagrange's equations of the kernels' own T and V (the Hessian of T in z', finite differences
  for the rest), so that with the previous check the equations are those of the exact energy to second order;
* the contact Jacobian's axial columns against finite differences of the gap;
* a free beam's first impact under IMM: P = (1 + e) m v0 / (1 + (3 + 4 n) cos^2 th + 2 n_a sin^2 th)
  (an end's Phi_a,k(0)^2 = 2 per axial mode, free_beam.md section 6).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import flexbeam as fb
from flexbeam.integrate.modal import ModalBasis
from flexbeam.model.system import BeamSystem

DATA = "tests/validation/data/free-bar-drop.toml"


def revolute(**over):
    over = {"model.axial_modes": 3, "model.modes": 3, "hub.radius": 0.05, "hub.inertia": 0.02, "drive.kind": "torque",
            "drive.torque": 1.3, **over}  # fmt: skip
    return fb.load_case("seed-experiment", overrides=over)


def free(**over):
    over = {"model.axial_modes": 3, "model.modes": 3, "contact.anywhere": False, "contact.side": "centre", **over}
    return fb.load_case(DATA, overrides=over)


CASES = {"revolute": revolute, "revolute-hub-frame": lambda **o: revolute(**{"model.frame": "hub", **o}), "free": free}


def own_axial(x: np.ndarray, L: float, count: int, free_free: bool) -> np.ndarray:
    """sqrt(2) cos(k pi x / L) (free-free) or sqrt(2) sin((k - 1/2) pi x / L) (fixed-free), k = 1..count."""
    k = np.arange(1, count + 1)
    if free_free:
        return math.sqrt(2.0) * np.cos(np.outer(x, k * math.pi / L))
    return math.sqrt(2.0) * np.sin(np.outer(x, (k - 0.5) * math.pi / L))


@pytest.mark.parametrize("kind", ["revolute", "free"])
def test_axial_integrals_match_quadrature_of_their_definitions(kind):
    case = CASES[kind](**{"model.axial_modes": 6})
    b = BeamSystem.from_case(case).beam
    L, mu, EA = b.length, b.line_density, case.beam.axial_stiffness
    xg, wg = np.polynomial.legendre.leggauss(400)
    x, w = 0.5 * L * (xg + 1.0), 0.5 * L * wg
    Phi = own_axial(x, L, 6, kind == "free")
    base = x - 0.5 * L if kind == "free" else case.hub.radius + x
    ax = b.axial
    assert_allclose(ax.Maa, (w * mu) @ (Phi * Phi), rtol=1e-12)
    # atol: the quadrature's round-off of a vanishing integral of terms of size mu L
    assert_allclose(ax.sa, (w * mu) @ Phi, rtol=1e-12, atol=1e-13 * mu * L)
    # its terms are of size mu L (r_h + L) and cancel: round-off relative to that
    assert_allclose(ax.mta, (w * mu * base) @ Phi, rtol=0, atol=1e-13 * mu * L * (abs(base).max()))
    assert_allclose(ax.S, (Phi * (w * mu)[:, None]).T @ b.shapes(x, 0), rtol=1e-10, atol=1e-12 * mu * L)
    kap = np.arange(1, 7) * math.pi / L if kind == "free" else (np.arange(1, 7) - 0.5) * math.pi / L
    assert_allclose(ax.Ka, EA * L * kap**2, rtol=1e-14)
    if kind == "free":  # parity about L/2: an axial mode k and a bending mode j couple only for k + j odd
        k, j = np.meshgrid(np.arange(1, 7), np.arange(1, b.n + 1), indexing="ij")
        assert np.all(np.abs(ax.S[(k + j) % 2 == 0]) <= 1e-13 * mu * L)
        assert np.all(np.abs(ax.S[(k + j) % 2 == 1]) > 1e-3 * mu * L)


@pytest.mark.parametrize("kind", list(CASES))
def test_axial_frequencies_are_the_rods(kind):
    case = CASES[kind](**{"model.axial_modes": 8})
    system = BeamSystem.from_case(case)
    omega = ModalBasis.of(system).omega
    c = math.sqrt(case.beam.youngs_modulus / case.beam.density)
    k = np.arange(1, 9)
    expected = (k if kind == "free" else k - 0.5) * math.pi * c / case.beam.length
    # the axial coordinates are the state's last ones, and M0, K0 are block-diagonal there in every frame
    assert_allclose(np.sort(omega)[-8:], expected, rtol=1e-13)


def _state(system, rng, amplitude, rate):
    nz, L = system.nz, system.beam.length
    z = np.zeros(nz)
    zd = np.zeros(nz)
    nr = system.joint.nrigid - system.joint.ngiven
    z[:nr] = rng.normal(size=nr) * 0.3
    zd[:nr] = rng.normal(size=nr) * 0.5
    zd[nr - 1] = rate
    z[nr:] = amplitude * L * rng.normal(size=nz - nr)
    zd[nr:] = amplitude * L * 300.0 * rng.normal(size=nz - nr)
    return z, zd


def _y(system, z, zd):
    y = np.zeros(system.size)
    y[: system.nz], y[system.nz : 2 * system.nz] = z, zd
    return y


@pytest.mark.parametrize("kind", ["revolute", "free"])
def test_kinetic_energy_is_the_second_order_expansion_of_the_exact_one(kind):
    system = BeamSystem.from_case(CASES[kind](**{"model.gravity": 0.0}))
    b = system.beam
    L, mu, n, na = b.length, b.line_density, b.n, b.na
    xg, wg = np.polynomial.legendre.leggauss(200)
    x, w = 0.5 * L * (xg + 1), 0.5 * L * wg
    psi, phi_a = b.shapes(x, 0), own_axial(x, L, na, kind == "free")
    H = np.array([b.point(xi).H for xi in x])
    base = b.hub_radius + x
    rng = np.random.default_rng(5)
    q0, qd0, p0, pd0 = rng.normal(size=n), 50 * rng.normal(size=n), rng.normal(size=na), 5e3 * rng.normal(size=na)
    omega, vG = 7.0, np.array([0.3, -0.8])
    errors = []
    for eps in (1e-3, 5e-4, 2.5e-4):
        q, qd, p, pd = eps * q0, eps * qd0, eps * p0, eps * pd0
        uy, uyd = psi @ q, psi @ qd
        ux = phi_a @ p - 0.5 * np.einsum("i,kij,j->k", q, H, q)
        uxd = phi_a @ pd - np.einsum("i,kij,j->k", qd, H, q)
        vx, vy = uxd - omega * uy, omega * (base + ux) + uyd  # in the frame's axes (theta = 0)
        T_exact = 0.5 * np.sum(w * mu * (vx**2 + vy**2))
        if kind == "free":
            T_exact += 0.5 * mu * L * (vG @ vG) + mu * (vG @ [w @ vx, w @ vy])
            z = np.concatenate(([0.0, 0.0, 0.0], q, p))
            zd = np.concatenate((vG, [omega], qd, pd))
        else:
            dq = float(b.d @ q)
            T_exact += 0.5 * b.hub_inertia * (omega + float(b.d @ qd) / math.sqrt(1.0 - dq * dq)) ** 2
            z, zd = np.concatenate(([0.0], q, p)), np.concatenate(([omega], qd, pd))
        T_model = system.energies(0.0, _y(system, z, zd))["kinetic"]
        errors.append(abs(T_model - T_exact))
    order = np.log(errors[0] / errors[2]) / np.log(4.0)
    assert order > 2.8, errors


@pytest.mark.parametrize("kind", list(CASES))
def test_equations_are_lagranges_of_the_energies(kind):
    case = CASES[kind]()
    system = BeamSystem.from_case(case)
    rng = np.random.default_rng(11)
    z, zd = _state(system, rng, 1e-3, 20.0)
    nz = system.nz

    def T(z, zd):
        return system.energies(0.0, _y(system, z, zd))["kinetic"]

    def V(z):
        e = system.energies(0.0, _y(system, z, np.zeros(nz)))
        return e["elastic"] + e["gravitational"]

    eye = np.eye(nz)
    M = np.array([[T(z, eye[i] + eye[j]) - T(z, eye[i]) - T(z, eye[j]) for j in range(nz)] for i in range(nz)])
    assert_allclose(system.mass_matrix(0.0, _y(system, z, zd)), M, rtol=0, atol=1e-12 * np.abs(M).max())
    hz = 1e-6 * np.maximum(np.abs(z), system.beam.length * 1e-3)
    dT, dV, mixed = np.empty(nz), np.empty(nz), np.empty(nz)
    for i in range(nz):
        e = eye[i] * hz[i]
        dT[i] = (T(z + e, zd) - T(z - e, zd)) / (2 * hz[i])
        dV[i] = (V(z + e) - V(z - e)) / (2 * hz[i])
    for i in range(nz):  # (d/dz of dT/dz'_i) . z'

        def p_i(zz, i=i):
            return (T(zz, zd + eye[i]) - T(zz, zd - eye[i])) / 2.0

        mixed[i] = sum((p_i(z + eye[j] * hz[j]) - p_i(z - eye[j] * hz[j])) / (2 * hz[j]) * zd[j] for j in range(nz))
    Q = system.generalized_forces(0.0, _y(system, z, zd))
    Q0 = system.generalized_forces(0.0, _y(system, z, np.zeros(nz)))
    velocity = dT - mixed
    assert_allclose(Q - Q0, velocity, rtol=0, atol=1e-6 * np.abs(velocity).max())
    static = -dV
    if kind != "free":  # the drive's torque on the hub angle theta + d q
        static += case.drive.torque * np.concatenate(([1.0], system.beam.d, np.zeros(system.beam.na)))
    assert_allclose(Q0, static, rtol=0, atol=1e-6 * np.abs(static).max())


@pytest.mark.parametrize("kind", ["revolute", "free"])
def test_contact_jacobian_axial_columns_match_finite_differences(kind):
    system = BeamSystem.from_case(CASES[kind]())
    z, zd = _state(system, np.random.default_rng(3), 1e-4, 5.0)
    y = _y(system, z, zd)
    J = system.gap(0.0, y)[3]
    h = 1e-8
    for i in range(system.nz - system.beam.na, system.nz):
        dy = np.zeros_like(y)
        dy[i] = h
        fd = (system.gap(0.0, y + dy)[0] - system.gap(0.0, y - dy)[0]) / (2 * h)
        assert_allclose(J[i], fd, rtol=1e-6, atol=1e-9)
    assert np.abs(J[system.nz - system.beam.na :]).max() > 0.1  # the end's Phi_a,k(0) = sqrt(2) along the normal


@pytest.mark.parametrize("angle", [20.0, 50.0, 80.0])
@pytest.mark.parametrize("na", [0, 1, 5])
def test_free_beam_impulse_with_axial_modes(angle, na):
    th = math.radians(angle)
    e, v0, n = 0.5, 1.4, 2
    # a thin section (half_depth 1e-10 m), so that the end face's centre strikes before its corner does
    case = free(**{"model.modes": n, "model.axial_modes": na, "model.gravity": 0.0, "initial.impact_angle": th,
                   "contact.restitution": e, "solver.t_end": 1e-6, "beam.section": "general", "beam.area": 1.267e-4,
                   "beam.second_moment": 1.277e-9, "beam.half_depth": 1e-10, "beam.radius": None})  # fmt: skip
    sol = fb.simulate(case, method="imm")
    m = case.beam.mass
    P = (1 + e) * m * v0 / (1 + (3 + 4 * n) * math.cos(th) ** 2 + 2 * na * math.sin(th) ** 2)
    assert_allclose(sol.contacts[0].impulse, P, rtol=1e-12)
