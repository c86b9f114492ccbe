"""Flat end faces (``beam.end_caps = "flat"``): a bar dropped at an angle strikes with the lower corner of its end
face instead of its hemispherical cap, against the rigid bar's impulse-momentum closed form with the corner's lever.

The rigid bar (no modes) of mass m, length L and radius c, translating down at v0 with its axis at theta to the
frictionless ground, strikes with the corner of its end x = 0 on the ground's side, at r = -(L/2) e - c nu from G
(e = (cos theta, sin theta) along the axis, nu = (-sin theta, cos theta) across).  Its lever about G for the normal
(0, 1) is r_x = -(L/2) cos theta + c sin theta, so with the moment of inertia J_G = m L^2 / 12 of the
Euler-Bernoulli bar (no rotary inertia of the sections) the Delassus number is W = 1/m + r_x^2 / J_G and Newton's law
gives (Stronge 2000, Impact Mechanics, sec. 4.2)

    P = (1 + e) v0 / W,   omega+ = r_x P / J_G,   v_G+ = -v0 + P / m,   v_Gx+ = 0.

A hemispherical cap's normal passes through the end's centre, r_x = -(L/2) cos theta: W = (1 + 3 cos^2 theta) / m
(test_free_beam_contact.py).  The start of ``initial.kind = "impact"`` places G so that the corner touches:
y_G = (L/2) sin theta + c cos theta.
"""

from __future__ import annotations

import math

import pytest

import flexbeam as fb
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import initial_state

from .test_free_beam_contact import steel_drop


def flat_drop(angle_deg: float, modes: int, e: float = 1.0, t_end: float = 0.004) -> fb.Case:
    """The steel bar of test_free_beam_contact.py with flat end faces, no gravity, a Hertz law of restitution e."""
    case = steel_drop(angle_deg, modes, t_end)
    beam = case.beam.model_copy(update={"end_caps": "flat"})
    contact = case.contact.model_copy(update={"restitution": e})
    return fb.load_case(case.model_copy(update={"beam": beam, "contact": contact}).model_dump())


def corner_closed_form(case: fb.Case, angle_deg: float, e: float) -> tuple[float, float, float]:
    """(P, omega+, v_Gy+) of the rigid bar struck at its lower end's corner (module docstring)."""
    m, L, c, v0 = case.beam.mass, case.beam.length, case.beam.radius, 1.4
    th = math.radians(angle_deg)
    JG = m * L**2 / 12.0
    rx = -0.5 * L * math.cos(th) + c * math.sin(th)
    P = (1.0 + e) * v0 / (1.0 / m + rx**2 / JG)
    return P, rx * P / JG, -v0 + P / m


@pytest.mark.parametrize("angle", [15.0, 45.0, 75.0])
def test_the_start_puts_the_corner_on_the_ground(angle):
    case = flat_drop(angle, 0)
    y0, _ = initial_state(BeamSystem.from_case(case), case)
    L, c, th = case.beam.length, case.beam.radius, math.radians(angle)
    assert y0[1] == pytest.approx(0.5 * L * math.sin(th) + c * math.cos(th), rel=1e-14)


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("angle", [15.0, 45.0, 75.0])
def test_rigid_bar_struck_at_its_corner_imm_closed_form(angle, e):
    """IMM, no modes: the impulse, the spin and G's velocity after the impact to 1e-12 relative (the model's J_G is
    m L^2 / 12 to round-off), one impact."""
    case = flat_drop(angle, 0, e)
    sol = fb.simulate(case, "imm")
    assert sol.status == "success" and len(sol.contacts) == 1
    P, omega, vy = corner_closed_form(case, angle, e)
    assert sol.contacts[0].impulse == pytest.approx(P, rel=1e-12)
    y = sol.source.run.segments[-1].y1  # [x_G, y_G, theta, x_G', y_G', theta', E_d, W]
    assert y[3] == pytest.approx(0.0, abs=1e-15)
    assert y[4] == pytest.approx(vy, rel=1e-12, abs=1e-15)
    assert y[5] == pytest.approx(omega, rel=1e-12)


@pytest.mark.parametrize("angle", [30.0, 60.0])
def test_rigid_bar_on_its_corner_ccfm_approaches_the_closed_form(angle):
    """CCFM, no modes, the elastic Hertz law: the closed form with e = 1 takes the bar as not turning during the impact;
    over the contact's duration t_c it turns by |omega+| t_c (~2e-3 rad here), which moves the corner's lever and so
    the impulse by about that fraction.  G's velocity within 2 |omega+| t_c v0 and the spin within 2 |omega+| t_c
    relative (measured 0.21 and 0.06 of |omega+| t_c: a 10x margin), and the energy conserved to 1e-6 (measured
    1.9e-7)."""
    case = flat_drop(angle, 0)
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success" and len(sol.contacts) == 1
    P, omega, vy = corner_closed_form(case, angle, 1.0)
    turn = abs(omega) * (sol.contacts[0].end - sol.contacts[0].onset)
    y = sol.source.run.segments[-1].y1
    assert y[4] == pytest.approx(vy, abs=2.0 * turn * 1.4)
    assert y[5] == pytest.approx(omega, rel=2.0 * turn)
    assert abs(sol.metrics()["energy_drift"]) < 1e-6


def test_flat_ends_strike_differently_from_caps_and_the_default_is_the_cap():
    """The default end is the hemispherical cap (the fingerprints keep today's runs); the flat end's corner has the
    shorter lever |r_x| = (L/2) cos theta - c sin theta, hence a larger impulse than the cap's, in the closed forms'
    ratio to 1e-12 (IMM, e = 1)."""
    cap = steel_drop(45.0, 0)
    assert cap.beam.end_caps == "hemisphere"
    elastic = cap.contact.model_copy(update={"restitution": 1.0})
    capped = fb.load_case(cap.model_copy(update={"contact": elastic}).model_dump())
    a, b = fb.simulate(capped, "imm"), fb.simulate(flat_drop(45.0, 0), "imm")
    m, th = cap.beam.mass, math.radians(45.0)
    P_cap = 2.0 * m * 1.4 / (1.0 + 3.0 * math.cos(th) ** 2)
    P_flat, _, _ = corner_closed_form(cap, 45.0, 1.0)
    assert a.contacts[0].impulse == pytest.approx(P_cap, rel=1e-12)
    assert b.contacts[0].impulse / a.contacts[0].impulse == pytest.approx(P_flat / P_cap, rel=1e-12)
    assert P_flat > P_cap * (1.0 + 1e-3)


def test_the_fe_reference_refuses_flat_ends_found_anywhere():
    """The FE's contact anywhere is on the capsule: flat end faces are refused in one line naming beam.end_caps."""
    from flexbeam.errors import ModelError

    case = fb.load_case("seed-experiment", {"contact.anywhere": True, "beam.end_caps": "flat"})
    with pytest.raises(ModelError, match=r"^beam\.end_caps:"):
        fb.simulate(case, "fem")
