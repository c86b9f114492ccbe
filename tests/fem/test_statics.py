"""Static cantilever under a tip load: linear theory and the large-deflection elastica.

Reference for the large deflection: K. E. Bisshopp, D. C. Drucker, "Large deflection
of cantilever beams", *Quart. Appl. Math.* 3 (1945) 272-275, who give for
P L^2/(EI) = 1 the vertical tip deflection 0.30172 L and the horizontal tip
displacement 0.05643 L.  The test recomputes these independently (shooting on the
elastica ODE with :func:`scipy.integrate.solve_ivp`, cross-checked against the
elliptic-integral solution) and compares the finite-element solution with them.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import ellipe, ellipeinc, ellipk, ellipkinc

from flexbeam.fem import FemBeam
from tests.fem.cases import general_beam


def elastica_shooting(alpha: float) -> tuple[float, float, float]:
    """(horizontal, vertical tip displacement, tip rotation) / L for alpha = P L^2/EI.

    Inextensible elastica with s in [0, 1]: theta' = kappa, kappa' = alpha cos(theta)
    (EI theta' = -P (x_L - x), differentiated), x' = cos(theta), y' = sin(theta),
    theta(0) = 0, kappa(1) = 0; kappa(0) found by :func:`scipy.optimize.brentq`.
    """

    def rhs(s, y):
        th, k = y[0], y[1]
        return [k, alpha * np.cos(th), np.cos(th), np.sin(th)]

    def end(k0):
        return solve_ivp(rhs, (0.0, 1.0), [0.0, k0, 0.0, 0.0], rtol=1e-12, atol=1e-14).y[:, -1]

    k0 = brentq(lambda k: end(k)[1], -1.0001 * alpha, 0.0, xtol=1e-14)
    th, _, x, y = end(k0)
    return 1.0 - x, -y, -th


def elastica_elliptic(alpha: float) -> tuple[float, float, float]:
    """The same from the elliptic-integral solution (Bisshopp & Drucker 1945).

    alpha = [K(p) - F(p, phi1)]^2 with p^2 = (1 + sin phi0)/2, sin phi1 = 1/(sqrt2 p),
    x_L/L = sqrt(2 sin phi0 / alpha), delta_v/L = 1 - 2 [E(p) - E(p, phi1)]/sqrt(alpha),
    phi0 being the tip rotation.
    """

    def parts(phi0):
        m = (1.0 + np.sin(phi0)) / 2.0
        phi1 = np.arcsin(1.0 / np.sqrt(2.0 * m))
        return m, phi1

    def f(phi0):
        m, phi1 = parts(phi0)
        return (ellipk(m) - ellipkinc(phi1, m)) ** 2 - alpha

    phi0 = brentq(f, 1e-9, np.pi / 2 - 1e-9, xtol=1e-15)
    m, phi1 = parts(phi0)
    dv = 1.0 - 2.0 / np.sqrt(alpha) * (ellipe(m) - ellipeinc(phi1, m))
    return 1.0 - np.sqrt(2.0 * np.sin(phi0) / alpha), dv, phi0


def tip_load_solution(elements: int, P: float, steps: int = 1):
    # EA / EI = 1e7 m^-2: axial strain P/EA <= 1e-6, negligible against the inextensible elastica
    case = general_beam(fem__elements=elements, drive__kind="prescribed", beam__area=1.0)
    beam = FemBeam.from_case(case)
    load = np.zeros(beam.size)
    load[-2] = -P
    z = beam.static_equilibrium(0.0, load, steps=steps)
    L, EI = case.beam.length, case.beam.bending_stiffness
    return beam, z, L, EI


def test_references_agree_with_published_values():
    shoot = elastica_shooting(1.0)
    ell = elastica_elliptic(1.0)
    assert_allclose(shoot, ell, rtol=1e-9)
    assert_allclose(shoot[:2], [0.05643, 0.30172], atol=1e-5)  # Bisshopp & Drucker (1945)


def test_small_tip_load_gives_linear_deflection():
    """delta = P L^3 / (3 EI); cubic Hermite elements are nodally exact in linear theory."""
    P = 1e-6
    beam, z, L, EI = tip_load_solution(4, P)
    assert_allclose(-z[-2], P * L**3 / (3 * EI), rtol=1e-6)
    assert_allclose(-z[-1], P * L**2 / (2 * EI), rtol=1e-6)


@pytest.mark.parametrize("elements, rtol", [(16, 1e-3), (64, 1e-4)])
def test_large_deflection_matches_elastica(elements, rtol):
    """P L^2/EI = 1: tip displacements within rtol of the elastica."""
    dh, dv, rot = elastica_shooting(1.0)
    beam, z, L, EI = tip_load_solution(elements, P=1.0, steps=4)
    assert_allclose(-z[-2] / L, dv, rtol=rtol)
    assert_allclose((L - z[-3]) / L, dh, rtol=rtol)
    assert_allclose(-z[-1], rot, rtol=rtol)


def test_very_large_deflection_matches_elastica():
    """P L^2/EI = 10 (tip rotation ~ 82 degrees), adaptive load stepping."""
    dh, dv, rot = elastica_shooting(10.0)
    beam, z, L, EI = tip_load_solution(128, P=10.0, steps=20)
    assert_allclose([-z[-2] / L, (L - z[-3]) / L, -z[-1]], [dv, dh, rot], rtol=1e-4)
