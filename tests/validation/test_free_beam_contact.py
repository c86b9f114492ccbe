"""A free bar striking the ground (``joint.kind = "free"``): the impulse-momentum map against the rigid bar's
closed forms, the contact force method on the bar's end caps (either end, its rigid limit, the energy balance).

The rigid bar (no modes) of mass m and length L, translating down at v0 with its axis at the angle theta to the
frictionless ground, strikes it with its end x = 0 (the frame angle theta: that end is the lower one).  With
M = diag(m, m, m L^2 / 12) and J_n = [0, 1, -(L/2) cos theta] the Delassus number is W = (1 + 3 cos^2 theta) / m, so
Newton's law gives (Stronge 2000, Impact Mechanics, sec. 4.2; /work/research/free_beam.md section 6)

    P = (1 + e) m v0 / (1 + 3 cos^2 theta),   omega+ = -6 P cos theta / (m L),   v_G+ = -v0 + P / m  (v_Gx+ = 0).

With n free-free modes the end's Jacobian gains A(theta)(0, Psi_k(0)) with Psi_k(0)^2 = 4 (free_beam.md section
6), so W = (1 + (3 + 4 n) cos^2 theta) / m.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import flexbeam as fb
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import initial_state

#: the steel bar (/work/research/presets.md: steel assumed, 20 cm, 12.7 mm across)
STEEL = {"length": 0.2, "density": 7870.0, "youngs_modulus": 200e9, "poisson_ratio": 0.29, "section": "circle",
         "radius": 0.00635}  # fmt: skip


def line_bar(angle_deg: float, e: float, modes: int = 0, v0: float = 1.0) -> fb.Case:
    """A bar of no thickness (half_depth 0: its body is its centre line) whose end x = 0 touches the ground y = 0 at
    ``angle_deg``, translating down at ``v0``, no gravity."""
    return fb.load_case({
        "name": "line-bar",
        "beam": {"length": 0.5, "density": 7800.0, "youngs_modulus": 200e9, "poisson_ratio": 0.3, "section": "general",
                 "area": 1e-4, "second_moment": 1e-9, "half_depth": 0.0},
        "joint": {"kind": "free"},
        "model": {"modes": modes, "gravity": 0.0},
        "obstacle": {"kind": "half-plane", "centre": [0.0, 0.0], "normal": [0.0, 1.0]},
        "contact": {"law": "hertz", "position": 0.0, "stiffness": 1e10, "side": "centre", "restitution": e},
        "initial": {"kind": "impact", "impact_angle": math.radians(angle_deg), "impact_velocity": -v0},
        "solver": {"t_end": 1e-3},
    })  # fmt: skip


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("angle", [10.0, 30.0, 45.0, 60.0, 80.0])
def test_rigid_bar_impulse_momentum_closed_form(angle, e):
    """IMM, no modes: the impulse, the spin and G's velocity after the impact to round-off (1e-14 relative), one
    impact, and the bar leaves (no second contact without gravity)."""
    case = line_bar(angle, e)
    sol = fb.simulate(case, "imm")
    assert sol.status == "success" and len(sol.contacts) == 1
    m, L, v0, th = case.beam.mass, case.beam.length, 1.0, math.radians(angle)
    P = (1.0 + e) * m * v0 / (1.0 + 3.0 * math.cos(th) ** 2)
    assert sol.contacts[0].impulse == pytest.approx(P, rel=1e-14)
    y = sol.source.run.segments[-1].y1  # [x_G, y_G, theta, x_G', y_G', theta', E_d, W]
    assert y[3] == pytest.approx(0.0, abs=1e-15)
    assert y[4] == pytest.approx(-v0 + P / m, rel=1e-14, abs=1e-15)
    assert y[5] == pytest.approx(-6.0 * P * math.cos(th) / (m * L), rel=1e-14)
    assert abs(sol.contacts[0].velocity_after) == pytest.approx(e * v0, abs=1e-14)


@pytest.mark.parametrize("modes", [1, 4, 12])
@pytest.mark.parametrize("angle", [20.0, 70.0])
def test_delassus_number_with_free_free_modes(angle, modes):
    """W = (1 + (3 + 4 n) cos^2 theta) / m at the straight bar's end (Psi_k(0) = 2), to 1e-12: the modes' part of
    the contact kinematics and of the mass matrix."""
    case = line_bar(angle, 1.0, modes)
    system = BeamSystem.from_case(case)
    y0, _ = initial_state(system, case)
    W = system.delassus(0.0, y0, [0])[0, 0]
    th = math.radians(angle)
    assert W == pytest.approx((1.0 + (3.0 + 4.0 * modes) * math.cos(th) ** 2) / case.beam.mass, rel=1e-12)


def steel_drop(angle_deg: float, modes: int, t_end: float = 0.004) -> fb.Case:
    """The steel bar with hemispherical end caps (``contact.anywhere``: the capsule's point nearest the ground) at
    ``angle_deg`` touching the ground y = 0, translating down at 1.4 m/s (a 0.1 m drop), no gravity, an elastic
    Hertz contact of the stiffness of /work/research/presets.md (1.16e10 N/m^1.5: a 6.35 mm steel cap on steel)."""
    return fb.load_case({
        "name": "steel-drop",
        "beam": dict(STEEL),
        "joint": {"kind": "free"},
        "model": {"modes": modes, "gravity": 0.0},
        "obstacle": {"kind": "half-plane", "centre": [0.0, 0.0], "normal": [0.0, 1.0]},
        "contact": {"law": "hertz", "position": 0.0, "stiffness": 1.16e10, "exponent": 1.5, "side": "centre",
                    "anywhere": True},
        "initial": {"kind": "impact", "impact_angle": math.radians(angle_deg), "impact_velocity": -1.4},
        "solver": {"t_end": t_end},
    })  # fmt: skip


def _first_contact_x(sol) -> float:
    seg = next(s for s in sol.source.segments if s.t1 > s.t0 and s.phase.name != "free")
    t = np.array([0.5 * (seg.t0 + seg.t1)])
    return float(sol.source.evaluate_pairs(seg, t)[2][0, 0, 3])


@pytest.mark.parametrize("angle", [30.0, 60.0])
def test_rigid_bar_on_its_cap_approaches_the_elastic_closed_form(angle):
    """CCFM, no modes, the elastic Hertz law: the cap's contact normal passes through the cap's centre, the bar's
    end, so the closed form with e = 1 holds but for the bar's turn during the ~0.1 ms contact: G's velocity within
    1e-3 v0 and the spin within 1e-3 relative (measured 2e-4 v0 and 8e-5 at 30 and 60 degrees); the start places G
    at (L/2) sin theta + c; the energy is conserved to 1e-6 relative."""
    case = steel_drop(angle, 0)
    system = BeamSystem.from_case(case)
    y0, _ = initial_state(system, case)
    L, c = case.beam.length, case.beam.radius
    th = math.radians(angle)
    assert y0[1] == pytest.approx(0.5 * L * math.sin(th) + c, rel=1e-14)
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success" and len(sol.contacts) == 1
    m, v0 = case.beam.mass, 1.4
    P = 2.0 * m * v0 / (1.0 + 3.0 * math.cos(th) ** 2)
    y = sol.source.run.segments[-1].y1
    assert y[4] == pytest.approx(-v0 + P / m, abs=1e-3 * v0)
    assert y[5] == pytest.approx(-6.0 * P * math.cos(th) / (m * L), rel=1e-3)
    assert abs(sol.metrics()["energy_drift"]) < 1e-6
    assert _first_contact_x(sol) == 0.0  # the lower end's cap


@pytest.mark.parametrize("modes", [0, 6])
def test_either_end_strikes_and_the_motion_mirrors(modes):
    """At -30 degrees the end x = L is the lower one: the contact is on its cap and the motion mirrors that at +30
    degrees (theta and omega change sign, G's velocity does not): to round-off without modes, to 1e-9 m/s with six
    (the odd and even free-free modes mirror with opposite signs of q)."""
    a, b = (fb.simulate(steel_drop(s * 30.0, modes), "ccfm") for s in (1.0, -1.0))
    assert len(a.contacts) == len(b.contacts) >= 1
    assert _first_contact_x(a) == 0.0
    assert _first_contact_x(b) == pytest.approx(0.2, abs=1e-12)
    ya, yb = a.source.run.segments[-1].y1, b.source.run.segments[-1].y1
    nz = 3 + modes
    tol = 1e-12 if modes == 0 else 1e-9
    assert_allclose(yb[nz : nz + 2] * [-1.0, 1.0], ya[nz : nz + 2], rtol=0, atol=tol)
    assert yb[nz + 2] == pytest.approx(-ya[nz + 2], abs=tol * 100)
    for ca, cb in zip(a.contacts, b.contacts, strict=True):
        assert cb.peak_force == pytest.approx(ca.peak_force, rel=1e-6)


def test_flexible_bar_drop_balances_energy_and_bounces_several_times():
    """Eight modes at 30 degrees: the bar's bending vibration brings the end back to the ground (micro-impacts: more
    than one contact in the first 0.6 ms, as Stoianovici & Hurmuzlu 1996 observed), the energy balance of the
    elastic contact holds to 1e-5 relative, and momentum: the impulses' sum equals m times the change of v_Gy (no
    gravity, frictionless) to 1e-6 relative."""
    case = steel_drop(30.0, 8, t_end=0.003)
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success" and len(sol.contacts) >= 2
    assert abs(sol.metrics()["energy_drift"]) < 1e-5
    y0, y1 = sol.source.run.segments[0].y0, sol.source.run.segments[-1].y1
    nz = 3 + 8
    impulses = sum(c.impulse for c in sol.contacts)
    assert case.beam.mass * (y1[nz + 1] - y0[nz + 1]) == pytest.approx(impulses, rel=1e-6)
    assert y1[nz] == pytest.approx(0.0, abs=1e-15)  # frictionless: no horizontal force
