"""Rigid-beam limits (n = 0) against closed-form mechanics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

import flexbeam as fb
from flexbeam.contact.hertz import sphere_on_cylinder_stiffness
from flexbeam.contact.laws import Hertz
from flexbeam.model.system import BeamSystem
from tests.conftest import rigid_rod_mass_inertia, seed


@pytest.mark.parametrize("theta0", [0.2, 0.7, 1.2])
def test_pinned_rod_reaches_horizontal_with_textbook_rate(theta0):
    """Energy: 1/2 (m L^2/3) w^2 = m g (L/2) sin(theta0)  ->  w^2 = 3 g sin(theta0) / L."""
    case = seed(
        model__modes=0, initial__kind="release", initial__release_angle=theta0, contact__law="hertz", solver__t_end=0.8
    )
    sol = fb.simulate(case)
    ev = sol.contacts[0]
    i = int(np.searchsorted(sol.time, ev.onset))
    w = abs(sol["theta_rate"][i])
    L, g = case.beam.length, case.model.gravity
    assert_allclose(w**2, 3 * g * math.sin(theta0) / L, rtol=1e-8)
    # P's normal velocity is that of the material point x_P
    assert_allclose(ev.velocity_before, -w * case.contact.position, rtol=1e-6)


def _rod_about_O(case) -> tuple[float, float]:
    """(m_1, J_O) of a uniform rod of mass m on a hub of radius r_h and inertia J_h, from the textbook integrals:
    first moment m_1 = m (r_h + L/2), J_O = J_h + m (r_h^2 + r_h L + L^2/3)."""
    m, _ = rigid_rod_mass_inertia(case)
    L, rh = case.beam.length, case.hub.radius
    return m * (rh + L / 2), case.hub.inertia + m * (rh * rh + rh * L + L * L / 3)


@pytest.mark.parametrize("hub", [(0.0, 0.0), (0.05, 0.01)])
def test_rigid_pendulum_angular_acceleration_at_horizontal(hub):
    """Released at rest horizontal (theta = 0: the gravity torque is largest), theta'' = -g m_1 / J_O exactly,
    through the compiled forces (``fb_forces``) that both integrators use.  Round-off only: rtol 1e-12."""
    case = seed(model__modes=0, hub__radius=hub[0], hub__inertia=hub[1])
    system = BeamSystem.from_case(case)
    m1, J = _rod_about_O(case)
    yd, _, _ = system.rhs(0.0, system.state(0.0, 0.0))
    assert_allclose(yd[1], -case.model.gravity * m1 / J, rtol=1e-12)


def test_rigid_pendulum_period_at_small_amplitude():
    """The rod swinging about its hanging position (theta = -pi/2) with amplitude a = 0.1 rad under the default
    integrator: period T = 4 K(sin^2(a/2)) / w0, w0^2 = g m_1 / J_O (the pendulum's exact period; the small-angle
    2 pi / w0 is a^2/16 = 6e-4 shorter).  Periods from the upward zero crossings of theta' (linear between 1e-4 s
    samples: theta' is linear to second order there).  Measured 1.4e-10; bound 1e-8."""
    a = 0.1
    case = seed(
        model__modes=0,
        initial__kind="state",
        initial__angle=-math.pi / 2 + a,
        initial__rate=0.0,
        solver__t_end=3.0,
        solver__sample_step=1e-4,
    )
    sol = fb.simulate(case)
    assert sol.status == "success" and not sol.contacts
    m1, J = _rod_about_O(case)
    period = 4 * ellipk(math.sin(a / 2) ** 2) / math.sqrt(case.model.gravity * m1 / J)
    t, r = sol.time, sol["theta_rate"]
    i = np.nonzero((r[:-1] < 0.0) & (r[1:] >= 0.0))[0]
    crossings = t[i] - r[i] * (t[i + 1] - t[i]) / (r[i + 1] - r[i])
    assert crossings.size == 2
    assert_allclose(np.diff(crossings), period, rtol=1e-8)


def _hertz_closed_form(m, v, K):
    """Rigid body on a Hertz spring, Johnson (1985) Sec. 11.4, with his numbers: delta_max = (5 m v^2 / (4 K))^(2/5),
    F_max = K delta_max^(3/2), t_c = 2.9432 delta_max / v (Hunter 1957: 2.94)."""
    dmax = (5 * m * v**2 / (4 * K)) ** 0.4
    return dmax, K * dmax**1.5, 2.9432 * dmax / v


@pytest.mark.parametrize("v0", [-0.4, -1.0])
def test_rigid_rod_hertz_impact_matches_closed_form(v0):
    """The closed form is for a point mass on a line; P moves on an arc of radius x_P and slides over the sphere,
    corrections of relative order delta_max / x_P at most (1e-4 and 2.1e-4 here; the duration measured 3.9e-6 and
    8.2e-6 off the exact constant at fast_rtol 1e-6 and 1e-10 alike, the peak 1e-7).  The constant 2.9432 is
    2 sqrt(pi) Gamma(7/5) / Gamma(9/10) = 2.943275 to four decimals: up to 1e-4 / 2.9432 = 3.4e-5 more on the
    duration (2.55e-5 of it here).  The integrator adds ~1e-7 (fast_rtol 1e-6)."""
    case = seed(
        model__modes=0, model__gravity=0.0, contact__law="hertz", initial__impact_velocity=v0, solver__t_end=2e-3
    )
    sol = fb.simulate(case)
    _, J_O = rigid_rod_mass_inertia(case)
    m_eff = J_O / case.contact.position**2
    K = BeamSystem.from_case(case).law.stiffness
    d_max, F_max, t_c = _hertz_closed_form(m_eff, abs(v0), K)
    geometry = d_max / case.contact.position
    m = sol.metrics()
    assert_allclose(m["peak_force"], F_max, rtol=geometry + 1e-6)
    assert_allclose(m["contact_duration"], t_c, rtol=geometry + 1e-4 / 2.9432 + 1e-6)
    assert_allclose(m["post_impact_velocity"], -v0, rtol=1e-6)  # elastic: e = 1; measured 7.2e-8


def _elliptical_hertz_stiffness(R1: float, R2: float, E_star: float) -> float:
    """K = P / delta^(3/2) of the exact (elliptical) Hertz contact of two bodies with principal relative radii
    R1 >= R2, written out from Johnson (1985) Sec. 3.5 and 4.2 (independently of flexbeam.contact.hertz).

    Gap A x^2 + B y^2 with A = 1/(2 R1) <= B = 1/(2 R2); the pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2) on the
    ellipse of semi-axes a >= b, e^2 = 1 - b^2/a^2, gives A = (p0/E*) (b/(e^2 a^2)) [K(e) - E(e)],
    B = (p0/E*) (b/(e^2 a^2)) [(a^2/b^2) E(e) - K(e)], delta = (p0/E*) b K(e), P = 2/3 pi a b p0.
    B/A fixes e; A and P fix a; then delta.
    """
    A, B, P = 1.0 / (2.0 * R1), 1.0 / (2.0 * R2), 1.0

    def excess(m):
        return (ellipe(m) / (1.0 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - B / A

    m = brentq(excess, 1e-9, 1.0 - 1e-12, xtol=1e-15, rtol=1e-15)
    a = (3.0 * P * (ellipk(m) - ellipe(m)) / (2.0 * math.pi * m * A * E_star)) ** (1.0 / 3.0)
    b = a * math.sqrt(1.0 - m)
    p0 = 3.0 * P / (2.0 * math.pi * a * b)
    delta = p0 * b * ellipk(m) / E_star
    return P / delta**1.5


def test_hertz_stiffness_of_a_sphere_on_a_flat_is_johnsons():
    """A sphere on a flat (an infinitely wide cylinder): K = 4/3 E* sqrt(R), Johnson (1985) Sec. 4.2, exact."""
    assert_allclose(sphere_on_cylinder_stiffness(0.01, math.inf, 3.8e10), 4 / 3 * 3.8e10 * math.sqrt(0.01), rtol=1e-14)


def test_hertz_stiffness_of_a_sphere_on_a_cylinder_against_the_elliptical_contact():
    """The seed case: a 10 mm aluminium sphere across the beam's 14.5 mm cylinder, R' = 10 mm along the beam and
    R'' = (1/R_s + 1/R_c)^-1 = 5.92 mm across it (the sphere's and the cylinder's curvatures add there).
    flexbeam uses the circular equivalent R_e = sqrt(R' R'') (Johnson eq. 4.29), which underestimates the exact
    elliptical contact's stiffness by (ln rho)^2 / 48 to leading order in ln rho, rho = R'/R'' (the expansion of
    the exact solution about rho = 1: 0.570 % at the seed's rho = 1.69, where the exact difference is 0.569 %);
    the bound is twice that leading term."""
    case = seed()
    K = BeamSystem.from_case(case).law.stiffness
    b, o = case.beam, case.obstacle
    E_star = 1 / ((1 - b.poisson_ratio**2) / b.youngs_modulus + (1 - o.poisson_ratio**2) / o.youngs_modulus)
    R1, R2 = o.radius, 1 / (1 / o.radius + 1 / b.radius)
    exact = _elliptical_hertz_stiffness(R1, R2, E_star)
    leading = math.log(R1 / R2) ** 2 / 48
    assert exact * (1 - 2 * leading) < K < exact
    assert isinstance(BeamSystem.from_case(seed(contact__law="hertz")).law, Hertz)
