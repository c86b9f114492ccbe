"""The free beam (``joint.kind = "free"``): its free-free modes and modal integrals, its free flight (momentum,
angular momentum and energy conserved; G on the parabola under gravity) and what it refuses.

Independent truths: the roots of cos z cosh z = 1 (published to 5 decimals; mpmath to 30 digits), the mean-axis
conditions int mu Psi = int mu (x - L/2) Psi = 0, the continuum frequencies of a spinning free-free beam (a
Chebyshev collocation solution of EI w'''' - (N w')' - mu Omega^2 w = mu omega^2 w with N = mu Omega^2 x (L - x) / 2,
free ends; /work/research/free_beam.md section 2), and the conservation laws of a body in free flight.
"""

from __future__ import annotations

import math
import re

import mpmath
import numpy as np
import pytest
from numpy.testing import assert_allclose

import flexbeam as fb
from flexbeam.errors import ParameterError
from flexbeam.integrate.modal import ModalBasis
from flexbeam.model.beam import build_modal_beam
from flexbeam.model.modes import free_free_roots, free_free_shapes
from flexbeam.model.stations import station_table
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import initial_state

#: beta_k L of the free-free beam, roots of cos z cosh z = 1 (Blevins 1979, Table 8-1, to the digits of issue 26)
PUBLISHED = [4.73004, 7.85320, 10.99561, 14.13717]

#: the steel bar of the bar-drop set-up (/work/research/presets.md: assumed values), 20 cm long, 12.7 mm across
BAR = {"length": 0.2, "density": 7870.0, "youngs_modulus": 200e9, "poisson_ratio": 0.29, "section": "circle",
       "radius": 0.00635}  # fmt: skip


def free_case(**overrides) -> fb.Case:
    """A free steel bar far above a half-plane (no contact within the tests' times), overrides as dotted keys with
    '__' for '.'."""
    data = {
        "name": "free-bar",
        "beam": dict(BAR),
        "joint": {"kind": "free"},
        "model": {"modes": 6, "gravity": 0.0},
        "obstacle": {"kind": "half-plane", "centre": [0.0, -100.0], "normal": [0.0, 1.0]},
        "contact": {"law": "hertz", "position": 0.0, "stiffness": 1e10, "exponent": 1.5, "side": "below"},
        "initial": {"kind": "state"},
    }
    return fb.load_case(data, {k.replace("__", "."): v for k, v in overrides.items()})


# ----------------------------------------------------------------------------------------------- modes
def test_roots_match_the_published_values():
    """To the 5 decimals given (half a unit of the last, 5e-6) and to mpmath's roots of cos z cosh z = 1 at 30
    digits to 1e-14."""
    roots = free_free_roots(12)
    assert_allclose(roots[:4], PUBLISHED, rtol=0, atol=5e-6)
    mpmath.mp.dps = 30
    exact = [float(mpmath.findroot(lambda z: mpmath.cos(z) * mpmath.cosh(z) - 1, (k + 0.5) * mpmath.pi))
             for k in range(1, 13)]  # fmt: skip
    assert_allclose(roots, exact, rtol=1e-14)


def test_frequencies_of_the_free_beam_model():
    """The linearised model's (M0, K0) modes: three zero frequencies (translation, rotation), then
    omega_k = (beta_k L)^2 sqrt(EI / (mu L^4)) with the published beta_k L."""
    case = free_case(model__modes=4)
    system = BeamSystem.from_case(case)
    omega = ModalBasis.of(system).omega
    assert_allclose(omega[:3], 0.0, atol=0.0)
    b = case.beam
    scale = math.sqrt(b.bending_stiffness / (b.line_density * b.length**4))
    assert_allclose(omega[3:], np.square(PUBLISHED) * scale, rtol=2.2e-6)  # the 5 decimals' rounding, squared


def test_modes_are_orthogonal_to_the_rigid_modes_and_each_other():
    """int Psi_k dx = int (x - L/2) Psi_k dx = 0 to 1e-13 L (relative to int |Psi_k| ~ L), int Psi_j Psi_k = L delta,
    int Psi_j'' Psi_k'' = beta^4 L delta, by Gauss-Legendre quadrature of 200 points for 12 modes."""
    L, n = 0.2, 12
    shapes = free_free_shapes(n, L)
    xg, wg = np.polynomial.legendre.leggauss(200)
    x, w = 0.5 * L * (xg + 1.0), 0.5 * L * wg
    P, P2 = shapes(x, 0), shapes(x, 2)
    assert_allclose(w @ P, 0.0, atol=1e-13 * L)
    assert_allclose((w * (x - 0.5 * L)) @ P, 0.0, atol=1e-13 * L * L)
    assert_allclose(P.T @ (w[:, None] * P), L * np.eye(n), atol=1e-12 * L)
    beta = shapes.roots / L
    assert_allclose(P2.T @ (w[:, None] * P2), L * np.diag(beta**4), rtol=0, atol=1e-11 * L * beta[-1] ** 4)


def test_free_end_conditions_hold():
    """Psi'' = Psi''' = 0 at both ends (scaled by beta^2, beta^3), |Psi| = 2 there, Psi(0) > 0."""
    L, n = 0.2, 24
    shapes = free_free_shapes(n, L)
    beta = shapes.roots / L
    ends = np.array([0.0, L])
    assert_allclose(shapes(ends, 2) / beta**2, 0.0, atol=1e-11)
    assert_allclose(shapes(ends, 3) / beta**3, 0.0, atol=1e-11)
    assert_allclose(shapes(ends, 0)[0], 2.0, rtol=1e-12)
    assert_allclose(shapes(ends, 0)[1], 2.0 * (-1.0) ** np.arange(n), rtol=1e-12)


def test_modal_integrals_of_the_free_beam():
    """The model's integrals against their definitions: J_G = mu L^3 / 12, the quadrature's s_f and m_tf vanish
    (the exact zeros the model uses), D and H_bar by nested quadrature of their definitions D = int mu (x - L/2) H,
    H(x) = int_0^x Psi'^T Psi' - H_bar, and G = int mu H = 0 with that H; D / (mu L) and H_bar L against the values of
    /work/research/free_beam.md section 4 (an independent sympy/numpy script)."""
    case = free_case(model__modes=4)
    beam = build_modal_beam(case)
    mu, L = beam.line_density, beam.length
    assert beam.frame == "mean-axis" and beam.hub_radius == -0.5 * L
    assert_allclose(beam.Jc, mu * L**3 / 12.0, rtol=1e-14)
    assert beam.m1 == 0.0 and not beam.sf.any() and not beam.mtq.any() and not beam.G.any() and not beam.d.any()
    # nested quadrature of the definitions
    xg, wg = np.polynomial.legendre.leggauss(80)
    x, w = 0.5 * L * (xg + 1.0), 0.5 * L * wg
    H0 = np.array([_inner(beam, 0.0, xi) for xi in x])  # int_0^x Psi'^T Psi'
    Hbar = np.einsum("i,ijk->jk", w, H0) / L
    H = H0 - Hbar
    D = np.einsum("i,ijk->jk", w * mu * (x - 0.5 * L), H)
    assert_allclose(np.einsum("i,ijk->jk", w * mu, H), 0.0, atol=1e-12 * mu * L)
    assert_allclose(beam.D, D, rtol=0, atol=1e-12 * mu * L)
    assert_allclose(beam.point(0.0).H, -Hbar, rtol=0, atol=1e-11 / L)
    assert_allclose(beam.point(L).H, _inner(beam, 0.0, L) - Hbar, rtol=0, atol=1e-11 / L)
    research_D = [[3.049764, 0, -0.587446, 0], [0, 6.397395, 0, -1.861120], [-0.587446, 0, 11.324607, 0],
                  [0, -1.861120, 0, 17.905002]]  # fmt: skip
    assert_allclose(beam.D / (mu * L), research_D, rtol=0, atol=1e-6)
    research_Hbar = [[24.740411, 22.226509, 17.688756, 18.518624], [22.226509, 54.462296, 42.239038, 28.794407],
                     [17.688756, 42.239038, 93.433356, 65.856931],
                     [18.518624, 28.794407, 65.856931, 142.341572]]  # fmt: skip
    assert_allclose(-beam.point(0.0).H * L, research_Hbar, rtol=0, atol=1e-6)
    # the station table of contact anywhere starts at the same H(0) and ends at H(L)
    st = station_table(beam, 0.0)
    assert_allclose(st.H[0], beam.point(0.0).H, rtol=0, atol=1e-12 / L)
    assert_allclose(st.H[-1], beam.point(L).H, rtol=0, atol=1e-10 / L)


def _inner(beam, a: float, b: float) -> np.ndarray:
    xg, wg = np.polynomial.legendre.leggauss(80)
    x, w = 0.5 * (b - a) * (xg + 1.0) + a, 0.5 * (b - a) * wg
    d1 = beam.shapes(x, 1)
    return d1.T @ (w[:, None] * d1)


@pytest.mark.parametrize(
    ("spin", "published"),
    [(0.0, [500.5639, 3803.5371, 14617.630]), (10.0, [705.3081, 4342.3383, 15648.440]),
     (30.0, [2332.1394, 8599.4308, 23789.452])],
)  # fmt: skip
def test_spin_stiffening_against_the_continuum(spin, published):
    """A free beam spinning at Omega: mu L q'' + [K_ff + Omega^2 (D - mu L I)] q = 0 (the model's linearisation
    about a steady spin, p_theta fixed); with 16 modes its omega^2 against the continuum's (Chebyshev collocation,
    mu = EI = L = 1: S = 1, I = 1e-4, E = 1e4; free_beam.md section 6, 8 digits given) to 1e-7 relative."""
    case = free_case(**{"model__modes": 16, "beam__section": "general", "beam__radius": None, "beam__area": 1.0,
                        "beam__second_moment": 1e-4, "beam__half_depth": 0.0, "beam__length": 1.0,
                        "beam__density": 1.0, "beam__youngs_modulus": 1e4})  # fmt: skip
    beam = build_modal_beam(case)
    K = beam.Kff + spin**2 * (beam.D - beam.Mff)
    w2 = np.linalg.eigvalsh(K / beam.line_density)
    assert_allclose(w2[:3], published, rtol=1e-7)


# ------------------------------------------------------------------------------------------ free flight
def _invariants(system: BeamSystem, y: np.ndarray) -> tuple[np.ndarray, float, float, np.ndarray]:
    """(linear momentum m R_G', the angular momentum about G of the model p_theta = theta' (J_G + q^T M_c q), the
    energy T + V_e + V_g, R_G)."""
    R, Rd = system.joint.origin(0.0, y, system.n)
    _, thd, _, _ = system.split(0.0, y)
    M = system.mass_matrix(0.0, y)
    e = system.energies(0.0, y)
    return system.case.beam.mass * Rd, float(M[2, 2] * thd), e["kinetic"] + e["elastic"] + e["gravitational"], R


def spinning(**overrides) -> fb.Case:
    """Spinning at 20 rad/s with its first three modes vibrating, G drifting at (0.3, -0.2) m/s, for 1 s, at the
    exponential integrator's rtol = 1e-10, atol = 1e-13."""
    values = {
        "initial__angle": 0.3, "initial__rate": 20.0, "initial__position": [0.01, 0.02],
        "initial__velocity": [0.3, -0.2], "initial__modal_displacement": [2e-5, -1e-5, 5e-6],
        "initial__modal_velocity": [0.01, 0.0, -0.02], "solver__t_end": 1.0, "solver__fast_rtol": 1e-10,
        "solver__fast_atol": 1e-13,
    }  # fmt: skip
    values.update(overrides)
    return free_case(**values)


def test_free_flight_conserves_momentum_angular_momentum_and_energy():
    """No gravity, spinning at 20 rad/s and vibrating, 1 s (~1400 periods of the first mode): the linear momentum is
    constant to round-off (the translation rows are decoupled: 1e-15 relative), G moves on its straight line to
    1e-13 m, and p_theta (the model's angular momentum about G: it differs from the field's int mu (r - R_G) x r' by
    oscillating terms of third order in q) and the energy are constant to 1e-8 relative at the integrator's
    tolerance rtol = 1e-10 (measured: ~1e-13; at the default rtol = 1e-6, ~5e-4)."""
    case = spinning()
    system = BeamSystem.from_case(case)
    y0, _ = initial_state(system, case)
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success" and not sol.contacts
    y1 = sol.source.run.segments[-1].y1
    p0, a0, E0, R0 = _invariants(system, y0)
    p1, a1, E1, R1 = _invariants(system, y1)
    assert_allclose(p1, p0, rtol=0, atol=1e-15 * np.abs(p0).max())
    assert_allclose(R1, R0 + p0 / case.beam.mass * 1.0, rtol=0, atol=1e-13)
    assert abs(a1 - a0) <= 1e-8 * abs(a0)
    assert abs(E1 - E0) <= 1e-8 * abs(E0)
    assert np.abs(y1[3:6]).max() > 1e-6  # still vibrating


def test_under_gravity_the_centre_of_mass_follows_the_parabola():
    """g = 9.81, thrown at (1, 2) m/s while spinning and vibrating: R_G(t) = R0 + V0 t - g t^2 / 2 e_Y at every output
    sample over 0.5 s to 1e-12 m (its rows are m R'' = -m g e_Y exactly; the modes and spin do not enter them)."""
    case = spinning(model__gravity=9.81, initial__velocity=[1.0, 2.0], solver__t_end=0.5, solver__fast_rtol=1e-8,
                    solver__fast_atol=1e-11)  # fmt: skip
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success" and not sol.contacts
    (seg,) = sol.source.segments  # one free phase
    t = np.linspace(0.0, 0.5, 51)
    Y = seg.states(t)
    x = 0.01 + 1.0 * t
    y = 0.02 + 2.0 * t - 0.5 * 9.81 * t * t
    assert_allclose(Y[:, 0], x, rtol=0, atol=1e-12)
    assert_allclose(Y[:, 1], y, rtol=0, atol=1e-12)


# ------------------------------------------------------------------------------------------------ refusals
@pytest.mark.parametrize(
    ("overrides", "field"),
    [({"drive.kind": "torque", "drive.torque": 1.0}, "drive.kind"),
     ({"drive.kind": "prescribed"}, "drive.kind"),
     ({"hub.radius": 0.01}, "hub.radius"),
     ({"hub.inertia": 0.01}, "hub.inertia"),
     ({"model.frame": "system"}, "model.frame"),
     ({"model.modes": 63}, "model.modes"),
     ({"initial.kind": "release"}, "initial.kind"),
     ({"initial.modal_displacement": [0.0] * 7}, "initial.modal_displacement")],
)  # fmt: skip
def test_what_a_free_beam_does_not_have_is_refused(overrides, field):
    with pytest.raises(ParameterError, match="^" + re.escape(field) + ":"):
        free_case(**{k.replace(".", "__"): v for k, v in overrides.items()})


def test_every_method_models_a_free_beam():
    """CCM (tests/validation/test_free_beam_ccm.py) and the FE reference (tests/fem/test_free.py) run a free beam: no
    method is refused for the joint kind."""
    from flexbeam.model.joints import JOINTS

    assert JOINTS["free"].unsupported_methods == ()


def test_a_revolute_joint_refuses_a_centre_of_mass_start():
    with pytest.raises(ParameterError, match=r"^initial\.position:"):
        fb.load_case("seed-experiment", {"initial.position": [0.0, 1.0]})


def test_a_free_beam_starting_inside_an_obstacle_is_refused():
    """G 5 mm above a floor: the horizontal bar of radius 6.35 mm reaches 1.35 mm into it."""
    case = free_case(obstacle__centre=[0.0, 0.0], initial__position=[0.0, 0.005])
    with pytest.raises(ParameterError, match=r"^obstacle\.centre: the beam starts 0\.00135 m inside"):
        initial_state(BeamSystem.from_case(case), case)
