"""The FE reference's free beam (``joint.kind = "free"``, :mod:`flexbeam.fem.free`): every node free, no hub.

Checked against closed forms, not the modal model: the free-free frequencies (the roots of cos z cosh z = 1), the
rigid-body motion in free flight (momentum and the angular momentum about G constant, G on its parabola under
gravity, the energy kept), the starts of ``[initial]`` (G where the straight bar's end cap touches the floor) and the
mirror symmetry of a drop on either end cap.  Each bound is ~10x the value measured when it was written (in the
docstrings).  The FE-modal comparison is ``tests/validation/test_fem_free_beam.py``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import flexbeam as fb
from flexbeam.errors import ParameterError
from flexbeam.fem import FemBeam, simulate_fem
from flexbeam.fem.simulate import check_supported
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import initial_state
from tests.validation.test_free_beam_contact import steel_drop


def free_line(elements: int = 32, gravity: float = 0.0, **initial) -> fb.Case:
    """A free slender beam, L = 1 m, EI = 1 N m^2, mu = 10 kg/m, EA = 1e5 N (its first axial frequency, 314 rad/s,
    above the first four bending ones), the floor 10 m below: no contact."""
    return fb.load_case({
        "name": "free-line",
        "beam": {"length": 1.0, "density": 1000.0, "youngs_modulus": 1e7, "poisson_ratio": 0.3, "section": "general",
                 "area": 1e-2, "second_moment": 1e-7, "half_depth": 0.0},
        "joint": {"kind": "free"},
        "model": {"modes": 4, "gravity": gravity},
        "obstacle": {"kind": "half-plane", "centre": [0.0, -10.0], "normal": [0.0, 1.0]},
        "contact": {"law": "hertz", "position": 0.0, "stiffness": 1e6, "side": "centre"},
        "initial": {"kind": "state", **initial},
        "solver": {"t_end": 0.5},
        "fem": {"elements": elements},
    })  # fmt: skip


def cos_cosh_roots(k: int) -> np.ndarray:
    """The first k roots z > 0 of cos z cosh z = 1 (each within 0.3 of (j + 1/2) pi)."""
    f = lambda z: math.cos(z) * math.cosh(z) - 1.0  # noqa: E731
    return np.array(
        [brentq(f, (j + 0.5) * math.pi - 0.3, (j + 0.5) * math.pi + 0.3, xtol=1e-15) for j in range(1, k + 1)]
    )


def test_free_free_frequencies_are_the_roots_of_cos_cosh():
    """The linearised FE beam with no joint: three rigid-body modes (|w| < 1e-3 rad/s, round-off of the singular K;
    measured 1e-4), then w_k = (beta_k L)^2 sqrt(EI / (mu L^4)) with cos(beta L) cosh(beta L) = 1 (4.73004, 7.85320,
    10.99561, 14.13717): within 3e-4 relative at 32 elements (measured 3e-7 to 2.6e-5), converging as h^4 (halving
    the elements raises the error of the fourth by 12 to 20)."""
    fine = FemBeam.from_case(free_line(32)).frequencies()
    coarse = FemBeam.from_case(free_line(16)).frequencies()
    exact = cos_cosh_roots(4) ** 2 * math.sqrt(1.0 / 10.0)
    assert np.all(np.abs(fine[:3]) < 1e-3)
    np.testing.assert_allclose(fine[3:7], exact, rtol=3e-4)
    ratio = (coarse[6] / exact[3] - 1.0) / (fine[6] / exact[3] - 1.0)
    assert 12.0 < ratio < 20.0


@pytest.mark.parametrize("gravity", [0.0, 9.81])
def test_free_flight_keeps_momentum_and_energy(gravity):
    """A straight beam thrown spinning (G at (0.1, 2) m moving at (0.3, 1.5) m/s, 6 rad/s at 0.4 rad), 0.5 s at the
    automatic step (0.23 ms): G's velocity is v_0 - g t e_Y to 1e-12 m/s and G on its parabola to 1e-12 m (measured
    1.3e-13, 4e-14), the spin H_G / J_G starts at the rate and the angular momentum about G stays constant to 1e-5
    relative, the energy T + V_e + V_g to 1e-5 (measured 1e-6 and 1.1e-6: the time integration of the beam's axial
    vibration, which the centrifugal load starts; the same at rho_inf = 1).  The Buckens mean-axis angle starts at
    the angle and turns at the rate but for the centrifugal stretch (~mu w^2 L^2 / (8 EA) = 4.5e-4: its mean rate
    within 1e-3 relative)."""
    case = free_line(16, gravity, position=[0.1, 2.0], velocity=[0.3, 1.5], angle=0.4, rate=6.0)
    sol = simulate_fem(case)
    assert sol.status == "success" and not sol.contacts
    t, R = sol.motion.times, sol.motion.rigid
    np.testing.assert_allclose(R[:, 2], 0.3, rtol=0, atol=1e-12)
    np.testing.assert_allclose(R[:, 3], 1.5 - gravity * t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(R[:, 0], 0.1 + 0.3 * t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(R[:, 1], 2.0 + 1.5 * t - 0.5 * gravity * t * t, rtol=0, atol=1e-12)
    H = R[:, 6]
    assert H[0] / sol.motion.JG == pytest.approx(6.0, rel=1e-12)
    assert np.ptp(H) < 1e-5 * abs(H[0])
    E = sol["kinetic_energy"] + sol["elastic_energy"] + sol["gravitational_energy"]
    assert np.ptp(E) < 1e-5 * abs(E[0])
    assert sol["theta"][0] == pytest.approx(0.4, abs=1e-14)
    assert (sol["theta"][-1] - 0.4) / 0.5 == pytest.approx(6.0, rel=1e-3)


def test_the_impact_start_touches_the_floor_on_the_end_cap():
    """``initial.kind = "impact"``: the straight bar at 30 degrees with its end cap touching the floor, G at
    (L/2) sin theta + c above it to 1e-15 m, translating along the floor's normal at the impact velocity -- the same
    start as the modal model's (its provenance's impact_y_G) by the FE's own gap."""
    case = steel_drop(30.0, 8)
    beam = FemBeam.from_case(case)
    z, zd, info = beam.free_initial_state()
    L, c = case.beam.length, case.beam.radius
    rg = beam.rigid(z, zd)
    assert rg.position[1] == pytest.approx(0.5 * L * math.sin(math.radians(30.0)) + c, abs=1e-15)
    assert info["impact_y_G"] == pytest.approx(rg.position[1], abs=1e-16) and info["impact_x_G"] == 0.0
    _, modal = initial_state(BeamSystem.from_case(case), case)
    assert info["impact_y_G"] == pytest.approx(modal["impact_y_G"], abs=1e-15)
    np.testing.assert_allclose(rg.velocity, [0.0, -1.4], rtol=0, atol=1e-15)
    assert rg.momentum == pytest.approx(0.0, abs=1e-16)  # no spin (round-off of m L v0 ~ 0.1)
    assert beam.gap(z, zd)[:2] == pytest.approx((0.0, -1.4), abs=1e-15)


@pytest.mark.parametrize("angle", [30.0, -30.0])
def test_either_end_cap_strikes_and_the_drop_mirrors(angle):
    """At +30 degrees the end x = 0 is the lower one, at -30 degrees x = L: the first contact is on that end's cap
    (pair_contact_position 0 or L) and the motions mirror: G's vertical velocity after the episode the same, the spin
    opposite, to 1e-9 (measured 1e-13); the contact point anywhere finds both hemispherical caps."""
    sols = {s: simulate_fem(fb.load_case(steel_drop(s * 30.0, 8, 1e-3), {"fem.elements": 16})) for s in (1, -1)}
    s = 1 if angle > 0 else -1
    sol = sols[s]
    k = int(np.searchsorted(sol.time, sol.contacts[0].onset, side="right"))
    assert sol["pair_contact_position"][k, 0] == pytest.approx(0.0 if s > 0 else 0.2, abs=1e-12)
    a, b = (sols[1].episodes()[0], sols[-1].episodes()[0])
    assert b.velocity_after[1] == pytest.approx(a.velocity_after[1], abs=1e-9)
    assert b.velocity_after[0] == pytest.approx(-a.velocity_after[0], abs=1e-9)
    assert b.spin_after == pytest.approx(-a.spin_after, rel=1e-9)


def test_the_fe_free_beam_starts_straight():
    """The FE has no modes: a free beam's modal start is refused naming the field; a release start needs a joint."""
    base = free_line(4)
    with pytest.raises(ParameterError, match="initial.modal_displacement"):
        check_supported(fb.load_case(base, {"initial.modal_displacement": [1e-3]}))
    check_supported(fb.load_case(base, {"initial.modal_velocity": [0.0]}))
    with pytest.raises(ParameterError, match="initial.kind"):
        FemBeam.from_case(fb.load_case(steel_drop(30.0, 8), {"initial.kind": "release"})).free_initial_state()


def test_the_fe_free_beams_metrics_have_the_episodes():
    """``metrics()`` of an FE free-beam run has the collision episodes' keys, as the modal model's: G's velocity and
    spin before and after (here 30 degrees, no gravity, 16 elements), the episode's impulse m dv_G (1e-6 relative;
    measured 1e-8, the trapezoidal impulse of the samples against the integrator's momentum) and the three apparent
    coefficients, which agree within 1 % (measured 0.13 %: the bar's turn during the episode)."""
    case = fb.load_case(steel_drop(30.0, 8, 2e-3), {"fem.elements": 16})
    fem, modal = simulate_fem(case), fb.simulate(case, "ccfm")
    mf, mm = fem.metrics(), modal.metrics()
    assert set(mf) == set(mm)
    assert set(mf["episodes"][0]) == set(mm["episodes"][0])
    assert mf["collision_episodes"] == 1 and mf["episode_contacts"] >= 2
    ep = fem.episodes()[0]
    assert ep.velocity_before == pytest.approx((0.0, -1.4), abs=1e-15) and ep.spin_before == pytest.approx(0, abs=1e-12)
    dv = ep.velocity_after[1] - ep.velocity_before[1]
    assert case.beam.mass * dv == pytest.approx(ep.impulse, rel=1e-6)
    assert ep.onset < ep.compression_end < ep.end
    eN = mf["restitution_newton"]
    assert 0.0 < eN < 1.0
    assert mf["restitution_poisson"] == pytest.approx(eN, rel=1e-2)
    assert mf["restitution_energetic"] == pytest.approx(eN, rel=1e-2)
