"""Rigid-beam limits (n = 0) against closed-form mechanics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import flexbeam as fb
from flexbeam.contact.laws import Hertz
from flexbeam.model.system import BeamSystem
from tests.conftest import rigid_rod_mass_inertia, seed


@pytest.mark.parametrize("theta0", [0.2, 0.7, 1.2])
def test_pinned_rod_reaches_horizontal_with_textbook_rate(theta0):
    """Energy: 1/2 (m L^2/3) w^2 = m g (L/2) sin(theta0)  ->  w^2 = 3 g sin(theta0) / L."""
    case = seed(model__modes=0, initial__kind="release", initial__release_angle=theta0,
                contact__law="hertz", solver__t_end=0.8)
    sol = fb.simulate(case)
    ev = sol.contacts[0]
    i = int(np.searchsorted(sol.time, ev.onset))
    w = abs(sol["theta_rate"][i])
    L, g = case.beam.length, case.model.gravity
    assert_allclose(w**2, 3 * g * math.sin(theta0) / L, rtol=1e-8)
    # P's normal velocity is that of the material point x_P
    assert_allclose(ev.velocity_before, -w * case.contact.position, rtol=1e-6)


def _hertz_closed_form(m, v, K):
    """Rigid body on a Hertz spring, Johnson (1985) Sec. 11.4 (written out independently)."""
    dmax = (5 * m * v**2 / (4 * K)) ** 0.4
    return dmax, K * dmax**1.5, 2.9432 * dmax / v


@pytest.mark.parametrize("v0", [-0.4, -1.0])
def test_rigid_rod_hertz_impact_matches_closed_form(v0):
    case = seed(model__modes=0, model__gravity=0.0, contact__law="hertz", initial__impact_velocity=v0,
                solver__t_end=2e-3)
    sol = fb.simulate(case)
    _, J_O = rigid_rod_mass_inertia(case)
    m_eff = J_O / case.contact.position**2
    K = BeamSystem.from_case(case).law.stiffness
    _, F_max, t_c = _hertz_closed_form(m_eff, abs(v0), K)
    m = sol.metrics()
    assert_allclose(m["peak_force"], F_max, rtol=0.01)
    assert_allclose(m["contact_duration"], t_c, rtol=0.01)
    assert_allclose(m["post_impact_velocity"], -v0, rtol=1e-6)  # elastic: e = 1


def test_hertz_stiffness_of_a_sphere_on_a_cylinder():
    """K = 4/3 E* sqrt(R_e) with R_e = sqrt(R' R''), Johnson (1985) eq. 4.29 approximation."""
    case = seed()
    K = BeamSystem.from_case(case).law.stiffness
    E = case.beam.youngs_modulus
    E_star = E / (2 * (1 - 0.3**2))
    Rs, Rc = case.obstacle.radius, case.beam.radius
    R1, R2 = Rs, 1 / (1 / Rs + 1 / Rc)
    assert_allclose(K, 4 / 3 * E_star * math.sqrt(math.sqrt(R1 * R2)), rtol=1e-12)
    assert isinstance(BeamSystem.from_case(seed(contact__law="hertz")).law, Hertz)
