"""Beam eigenfunctions (cantilever, pinned-free, hub + beam) and the modal integrals against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from flexbeam.model.beam import build_modal_beam
from flexbeam.model.modes import cantilever_modes, cantilever_roots, hub_beam_roots, mode_shapes, pinned_free_roots
from tests.conftest import seed

# beta_k L of a clamped-free beam, e.g. Blevins, Formulas for Natural Frequency and
# Mode Shape (1979), Table 8-1: 1.87510407, 4.69409113, 7.85475744, 10.99554073,
# 14.13716839; and (2k - 1) pi / 2 asymptotically.
PUBLISHED = [1.87510407, 4.69409113, 7.85475744, 10.99554073, 14.13716839]


def test_roots_match_published_table():
    """The table has eight decimals: within half a unit of the last (5e-9, which its rounding of 10.99554073 uses up
    to 4.9e-9) plus the root finder's ~1e-15."""
    assert_allclose(cantilever_roots(5), PUBLISHED, rtol=0, atol=5e-9 + 1e-12)


def test_high_roots_approach_asymptote():
    k = np.arange(20, 33)
    assert_allclose(cantilever_roots(32)[19:], (2 * k - 1) * np.pi / 2, rtol=1e-12)


def test_boundary_conditions_hold_for_high_modes():
    L = 0.7
    x0, xL = np.array([0.0]), np.array([L])
    n = 32
    assert_allclose(cantilever_modes(x0, L, n, 0), 0.0, atol=1e-9)
    assert_allclose(cantilever_modes(x0, L, n, 1), 0.0, atol=1e-6)  # scale beta ~ 140/m
    b = cantilever_roots(n) / L
    assert_allclose(cantilever_modes(xL, L, n, 2)[0] / b**2, 0.0, atol=1e-9)
    assert_allclose(cantilever_modes(xL, L, n, 3)[0] / b**3, 0.0, atol=1e-9)
    assert_allclose(np.abs(cantilever_modes(xL, L, n, 0)[0]), 2.0, rtol=1e-10)


@pytest.mark.parametrize("n", [1, 8, 32])
def test_modal_mass_and_stiffness_are_diagonal(n):
    beam = build_modal_beam(seed(model__modes=n, model__frame="hub"))
    mu, EI, L = beam.line_density, beam.bending_stiffness, beam.length
    assert_allclose(beam.Mff / (mu * L), np.eye(n), atol=1e-10)
    b = cantilever_roots(n) / L
    assert_allclose(beam.Kff / (EI * L * b[:, None] ** 2 * b[None, :] ** 2), np.eye(n), atol=1e-10)


def test_rigid_integrals_are_textbook():
    beam = build_modal_beam(seed(model__modes=0, hub__radius=0.1))
    mu, L, rh = beam.line_density, beam.length, 0.1
    assert_allclose(beam.J0, mu * ((rh + L) ** 3 - rh**3) / 3, rtol=1e-13)
    assert_allclose(beam.m1, mu * ((rh + L) ** 2 - rh**2) / 2, rtol=1e-13)


def test_geometric_stiffness_by_parts_matches_nested_definition():
    """D = int mu (r_h + x) H(x) dx computed the long way (nested quadrature)."""
    case = seed(model__modes=3, hub__radius=0.05)
    beam = build_modal_beam(case)
    xs, ws = np.polynomial.legendre.leggauss(80)
    L = beam.length
    x = 0.5 * L * (xs + 1)
    w = 0.5 * L * ws
    D = np.zeros((3, 3))
    G = np.zeros((3, 3))
    for xi, wi in zip(x, w):
        H = beam.point(xi).H
        D += wi * beam.line_density * (0.05 + xi) * H
        G += wi * beam.line_density * H
    assert_allclose(beam.D, D, rtol=1e-9, atol=1e-12 * np.abs(D).max())
    assert_allclose(beam.G, G, rtol=1e-9, atol=1e-12 * np.abs(G).max())


def test_zeroth_order_has_no_coupling_terms():
    beam = build_modal_beam(seed(model__modes=4, model__coupling="zeroth-order"))
    assert not beam.D.any() and not beam.G.any()
    assert not beam.point(0.5).H.any()


# ------------------------------------------------------------------------------------ the system frame's modes
# tan(bL) = tanh(bL), the flexible pinned-free roots: Blevins, Formulas for Natural Frequency and Mode Shape
# (1979), Table 8-1 (pinned-free): 3.92660231, 7.06858275, 10.21017612, 13.35176878, 16.49336143; (4k + 1) pi / 4
PINNED_FREE = [3.92660231, 7.06858275, 10.21017612, 13.35176878, 16.49336143]


def test_pinned_free_roots_match_published_table():
    assert_allclose(pinned_free_roots(5), PINNED_FREE, rtol=0, atol=5e-9 + 1e-12)  # eight decimals, as above
    k = np.arange(6, 33)
    assert_allclose(pinned_free_roots(32)[5:], (4 * k + 1) * np.pi / 4, rtol=1e-12)


def test_hub_without_inertia_gives_the_pinned_free_beam():
    """J_h = 0, r_h = 0: the hub + beam roots are the pinned-free ones, and the shapes are the closed form
    u = sin(bx) / sin(bL) + sinh(bx) / sinh(bL) (u(0) = u''(0) = 0, free end) up to normalisation."""
    n, L = 8, 0.7
    assert_allclose(hub_beam_roots(n, 0.0, 0.0), pinned_free_roots(n), rtol=1e-12)
    shapes = mode_shapes(n, L, 0.0, 0.0)
    x = np.linspace(0.0, L, 201)
    got = shapes(x, 0)
    for k, z in enumerate(pinned_free_roots(5)):
        b = z / L
        ref = np.sin(b * x) / np.sin(z) + np.sinh(b * x) / np.sinh(z)
        scale = ref @ got[:, k] / (ref @ ref)
        assert_allclose(got[:, k], scale * ref, rtol=0, atol=1e-10 * np.abs(got[:, k]).max())


def test_heavy_hub_gives_the_clamped_free_beam():
    """J_h -> inf: the roots and shapes tend to the cantilever's (the k-th root lies between the k-th and
    (k+1)-th clamped roots for any J_h, approaching the k-th as 1 / J_h)."""
    n, L = 6, 0.7
    clamped = cantilever_roots(n + 1)
    prev = None
    for j in (1e-2, 1.0, 1e2, 1e4):
        roots = hub_beam_roots(n, j, 0.0)
        assert np.all(roots > clamped[:n]) and np.all(roots < clamped[1:])
        if prev is not None:
            assert np.all(roots < prev)  # more hub inertia, lower frequencies
        prev = roots
    assert_allclose(prev, clamped[:n], rtol=1e-4)
    x = np.linspace(0.0, L, 101)
    assert_allclose(mode_shapes(n, L, 1e6, 0.0)(x, 0), cantilever_modes(x, L, n, 0), atol=1e-4)


@pytest.mark.parametrize(("j", "rho"), [(0.0, 0.0), (0.05, 0.0), (0.3, 0.1), (0.0, 0.2), (10.0, 0.5)])
def test_hub_beam_modes_satisfy_the_boundary_conditions_and_orthogonality(j, rho):
    """u(0) = r_h u'(0); J_h w^2 u'(0) + EI (u''(0) - r_h u'''(0)) = 0; u''(L) = u'''(L) = 0; and orthonormal and
    orthogonal to the rigid rotation (r_h + x, hub angle 1) in int mu u v dx + J_h u'(0) v'(0) (mu = EI = 1)."""
    n, L = 10, 0.7
    mu, EI = 1.0, 1.0
    Jh, rh = j * mu * L**3, rho * L
    shapes = mode_shapes(n, L, j, rho)
    b = shapes.roots / L
    w2 = EI * b**4 / mu
    d = [shapes(np.array([0.0]), k)[0] for k in range(4)]
    scale = [np.abs(shapes(np.linspace(0, L, 50), k)).max(axis=0) for k in range(4)]
    assert_allclose(d[0] - rh * d[1], 0.0, atol=1e-10 * scale[0].max())
    assert_allclose(Jh * w2 * d[1] + EI * (d[2] - rh * d[3]), 0.0, atol=1e-9 * (EI * scale[3]).max())
    tip = [shapes(np.array([L]), k)[0] for k in (2, 3)]
    assert_allclose(tip[0] / scale[2], 0.0, atol=1e-10)
    assert_allclose(tip[1] / scale[3], 0.0, atol=1e-10)
    xg, wg = np.polynomial.legendre.leggauss(400)
    x, w = 0.5 * L * (xg + 1), 0.5 * L * wg
    P = shapes(x, 0)
    M = (P * (w * mu)[:, None]).T @ P + Jh * np.outer(d[1], d[1])
    assert_allclose(M / (mu * L), np.eye(n), atol=1e-12)
    rigid = (w * mu * (rh + x)) @ P + Jh * d[1]
    assert_allclose(rigid / (mu * L**2), 0.0, atol=1e-12)
    K = (shapes(x, 2) * (w * EI)[:, None]).T @ shapes(x, 2)
    assert_allclose(K / (mu * L * w2[:, None]), np.eye(n), atol=1e-9)


def test_system_frame_integrals_match_quadrature():
    """The system frame's exact integrals (used so that the linear mass and stiffness are diagonal) agree with
    their quadrature: m_tf + J_h d = 0, M_ff + J_h d^T d = mu L I, K_ff = EI L diag(beta^4)."""
    case = seed(model__modes=8, model__frame="system", hub__inertia=0.02, hub__radius=0.04)
    beam = build_modal_beam(case)
    mu, EI, L, rh, Jh = beam.line_density, beam.bending_stiffness, beam.length, beam.hub_radius, beam.hub_inertia
    xg, wg = np.polynomial.legendre.leggauss(300)
    x, w = 0.5 * L * (xg + 1), 0.5 * L * wg
    P, P2 = beam.shapes(x, 0), beam.shapes(x, 2)
    assert_allclose((P * (w * mu)[:, None]).T @ P, beam.Mff, atol=1e-10 * mu * L)
    assert_allclose((w * mu * (rh + x)) @ P, beam.mtf, atol=1e-10 * mu * L**2)
    kd = np.diag(beam.Kff)[:, None]
    assert_allclose((P2 * (w * EI)[:, None]).T @ P2 / kd, beam.Kff / kd, atol=1e-9)
    assert_allclose(beam.mtq, 0.0, atol=0)
    assert_allclose(beam.Mqq, mu * L * np.eye(beam.n), atol=1e-14 * mu * L)
    assert_allclose(beam.d, beam.shapes(np.zeros(1), 1)[0])
    assert math.isclose(beam.Jc, Jh + mu * ((rh + L) ** 3 - rh**3) / 3, rel_tol=1e-13)
