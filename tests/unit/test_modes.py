"""Cantilever eigenfunctions and the modal integrals against closed forms."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from flexbeam.model.beam import build_modal_beam
from flexbeam.model.modes import cantilever_modes, cantilever_roots
from tests.conftest import seed

# beta_k L of a clamped-free beam, e.g. Blevins, Formulas for Natural Frequency and
# Mode Shape (1979), Table 8-1: 1.87510407, 4.69409113, 7.85475744, 10.99554073,
# 14.13716839; and (2k - 1) pi / 2 asymptotically.
PUBLISHED = [1.87510407, 4.69409113, 7.85475744, 10.99554073, 14.13716839]


def test_roots_match_published_table():
    assert_allclose(cantilever_roots(5), PUBLISHED, rtol=2e-9)


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
    beam = build_modal_beam(seed(model__modes=n))
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
