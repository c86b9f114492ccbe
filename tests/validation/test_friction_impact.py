"""Frictional impacts (IMM with ``contact.friction``): Stronge's energetic restitution along the slip process.

* A rigid bar (no modes, no thickness, no gravity) of mass m and length L, translating at (v_x, -v0) with its axis at
  theta to rough ground, strikes it with its end x = 0, at r = -(L/2)(cos theta, sin theta) from G.  With the contact
  axes t = (-1, 0), n = (0, 1) and J_G = m L^2 / 12 the inverse mass is (r x t = r_y, r x n = r_x)

      W_tt = 1/m + r_y^2 / J_G,   W_tn = r_x r_y / J_G,   W_nn = 1/m + r_x^2 / J_G

  (Stronge 2000, Impact Mechanics, ch. 5).  Dropped straight (v_x = 0) the end starts without slip: it sticks
  throughout when |W_tn| <= mu_s W_tt, P_n = (1 + e) v0 / (W_nn - W_tn^2 / W_tt), P_t = -(W_tn / W_tt) P_n; else it
  slips throughout in the direction sign(W_tn), P_n = (1 + e) v0 / (W_nn - mu W_tn), P_t = -mu P_n.  G's velocity
  and the spin follow from the impulse: dv_G = (P_t t + P_n n) / m, d omega = (P_t r_y + P_n r_x) / J_G.
* Every other slip history (slip that stops, sticks or reverses) against an independent brute-force integration of
  the same impulse process in small steps of p, written here.
* Kane's paradox (a rigid link pinned at O striking rough ground at a shallow angle, where Newton's kinematic
  restitution with friction creates energy): the kinetic energy after the impact never exceeds that before, over a
  grid of angles, mu and e.
* A slip that first drives the contact point deeper (Painlevé's configuration at an impact) still ends with a
  finite impulse: with a positive definite W the slip stops before the normal velocity could diverge.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.errors import FlexbeamWarning

L, M_BAR = 0.5, 7800.0 * 1e-4 * 0.5


def rough_bar(angle_deg: float, mu: float, e: float, vx: float = 0.0, v0: float = 1.0, mu_s: float | None = None):
    """The rigid line bar of test_free_beam_contact.py, its end x = 0 on the ground at ``angle_deg``, moving at
    (vx, -v0) without spin, no gravity, Coulomb friction mu (static mu_s, default mu)."""
    th = math.radians(angle_deg)
    return fb.load_case({
        "name": "rough-bar",
        "beam": {"length": L, "density": 7800.0, "youngs_modulus": 200e9, "poisson_ratio": 0.3, "section": "general",
                 "area": 1e-4, "second_moment": 1e-9, "half_depth": 0.0},
        "joint": {"kind": "free"},
        "model": {"modes": 0, "gravity": 0.0},
        "obstacle": {"kind": "half-plane", "centre": [0.0, 0.0], "normal": [0.0, 1.0]},
        "contact": {"law": "hertz", "position": 0.0, "stiffness": 1e10, "side": "centre", "restitution": e,
                    "friction": mu, "friction_static": mu if mu_s is None else mu_s},
        "initial": {"kind": "state", "position": [0.5 * L * math.cos(th), 0.5 * L * math.sin(th)],
                    "velocity": [vx, -v0], "angle": th, "rate": 0.0},
        "solver": {"t_end": 1e-3},
    })  # fmt: skip


def inverse_mass(angle_deg: float) -> tuple[float, float, float, float, float]:
    """(W_tt, W_tn, W_nn, r_x, r_y) of the rigid bar (module docstring)."""
    th = math.radians(angle_deg)
    rx, ry = -0.5 * L * math.cos(th), -0.5 * L * math.sin(th)
    JG = M_BAR * L**2 / 12.0
    return 1.0 / M_BAR + ry * ry / JG, rx * ry / JG, 1.0 / M_BAR + rx * rx / JG, rx, ry


def after(sol) -> np.ndarray:
    """(v_Gx, v_Gy, omega) after the run."""
    y = sol.source.run.segments[-1].y1
    return np.array(y[3:6])


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("mu", [0.1, 2.0])
@pytest.mark.parametrize("angle", [20.0, 45.0, 70.0])
def test_rigid_bar_on_rough_ground_closed_form(angle, mu, e):
    """Stick or slip throughout (the module docstring's closed forms): the impulses, G's velocity and the spin to 1e-12
    relative; the normal velocity after is -e times that before (a constant slope: Stronge's e is Newton's)."""
    Wtt, Wtn, Wnn, rx, ry = inverse_mass(angle)
    sol = fb.simulate(rough_bar(angle, mu, e), "imm")
    assert sol.status == "success" and len(sol.contacts) == 1
    if abs(Wtn) <= mu * Wtt:  # stick
        Pn = (1.0 + e) / (Wnn - Wtn * Wtn / Wtt)
        Pt = -(Wtn / Wtt) * Pn
    else:  # slip in sign(W_tn)
        s = math.copysign(1.0, Wtn)
        Pn = (1.0 + e) / (Wnn - mu * s * Wtn)
        Pt = -mu * s * Pn
    ev = sol.contacts[0]
    assert ev.impulse == pytest.approx(Pn, rel=1e-12)
    assert ev.tangential_impulse == pytest.approx(Pt, rel=1e-12, abs=1e-15)
    JG = M_BAR * L**2 / 12.0
    expected = [-Pt / M_BAR, -1.0 + Pn / M_BAR, (Pt * ry + Pn * rx) / JG]
    np.testing.assert_allclose(after(sol), expected, rtol=1e-12, atol=1e-13)
    assert ev.velocity_after == pytest.approx(e * 1.0, rel=1e-12, abs=1e-13)


def brute_force(W, vt, vn, e, mu_s, mu_k, steps=200_000):
    """The impulse process integrated in small steps of the normal impulse (independent of flexbeam's piecewise-exact
    solution): slip opposes v_t with mu_k; at v_t = 0 stick if |W_tn| <= mu_s W_tt, else slip on; compression until
    v_n >= 0, restitution until the normal work returns e^2 of the compression's (or v_n falls back to 0)."""
    Wtt, Wtn, Wnn = W
    # the step: a fraction of the stick impulse scale |v_n| / (W_nn - W_tn^2 / W_tt) (its slope is the flattest a
    # slip that sticks can end in)
    dp = 5.0 * (1.0 + e) * -vn / (Wnn - Wtn * Wtn / Wtt) / steps
    p = Pt = wc = wr = 0.0
    compressing = True
    for _ in range(50 * steps):
        if abs(vt) < abs(Wtt * mu_k * dp) * 2 and abs(Wtn) <= mu_s * Wtt:
            dPt, vt = -Wtn / Wtt, 0.0
        else:
            s = math.copysign(1.0, vt) if vt != 0.0 else math.copysign(1.0, Wtn)
            dPt = -mu_k * s
        dvt, dvn = (Wtt * dPt + Wtn) * dp, (Wtn * dPt + Wnn) * dp
        work = (vn + 0.5 * dvn) * dp
        if compressing and vn + dvn >= 0.0:
            compressing = False
        if compressing:
            wc += work
        else:
            wr += work
            if wr >= e * e * -wc or vn + dvn < 0.0:
                p, Pt = p + dp, Pt + dPt * dp
                break
        p, Pt, vt, vn = p + dp, Pt + dPt * dp, vt + dvt, vn + dvn
    return p, Pt


@pytest.mark.parametrize(("angle", "vx", "mu"), [(30.0, -0.8, 0.3), (30.0, 0.5, 0.3), (60.0, -1.5, 0.6),
                                                 (45.0, 0.3, 0.8), (70.0, -0.2, 0.15)])  # fmt: skip
@pytest.mark.parametrize("e", [0.3, 0.8])
def test_slip_that_stops_sticks_or_reverses_against_brute_force(angle, vx, mu, e):
    """Bars arriving with a slip velocity (v_x != 0) in either direction: the normal and tangential impulses equal the
    brute-force integration of the process (200 000 steps: its first-order error ~ 1e-5 relative; to 2e-4), and the
    kinetic energy does not increase."""
    W = inverse_mass(angle)[:3]
    sol = fb.simulate(rough_bar(angle, mu, e, vx=vx), "imm")
    assert sol.status == "success"
    ev = sol.contacts[0]
    Pn, Pt = brute_force(W, -vx, -1.0, e, mu, mu)
    assert ev.impulse == pytest.approx(Pn, rel=2e-4)
    assert ev.tangential_impulse == pytest.approx(Pt, rel=2e-4, abs=2e-4 * Pn)
    assert ev.energy_after <= ev.energy_before * (1.0 + 1e-12)


def kane_link(angle_deg: float, mu: float, e: float) -> fb.Case:
    """A rigid link pinned at O (Kane & Levinson's double pendulum reduced to one link) swinging down onto rough
    horizontal ground, its tip striking it with the link at ``angle_deg`` below the horizontal."""
    th = math.radians(angle_deg)
    return fb.load_case({
        "name": "kane-link",
        "beam": {"length": 1.0, "density": 7800.0, "youngs_modulus": 200e9, "section": "general", "area": 1e-4,
                 "second_moment": 1e-9, "half_depth": 0.0},
        "model": {"modes": 0, "gravity": 0.0},
        "obstacle": {"kind": "half-plane", "centre": [0.0, -math.sin(th)], "normal": [0.0, 1.0]},
        "contact": {"law": "hertz", "position": 1.0, "stiffness": 1e10, "side": "centre", "restitution": e,
                    "friction": mu},
        "initial": {"kind": "impact", "impact_angle": -th, "impact_velocity": -1.0},
        "solver": {"t_end": 1e-4},
    })  # fmt: skip


@pytest.mark.parametrize("angle", [3.0, 8.0, 20.0, 45.0])
@pytest.mark.parametrize("mu", [0.2, 0.6, 1.5])
@pytest.mark.parametrize("e", [0.5, 1.0])
def test_kanes_paradox_never_gains_energy(angle, mu, e):
    """The link's kinetic energy after the impact is at most that before (to 1e-12 relative): Coulomb friction and
    Stronge's energetic restitution dissipate, whatever the slip does (Newton's restitution would gain energy here for
    shallow angles and large mu: Kane & Levinson 1985, Stronge 1991)."""
    sol = fb.simulate(kane_link(angle, mu, e), "imm")
    assert sol.status == "success" and sol.contacts
    ev = sol.contacts[0]
    assert ev.energy_after <= ev.energy_before * (1.0 + 1e-12)


def test_slip_driving_the_end_deeper_still_ends():
    """At 45 degrees W_nn / W_tn = 5/3: slipping with mu = 2 in the direction that drives the end into the ground
    (v_t > 0, the bar moving left), dv_n/dp < 0 at first -- the impact's form of Painlevé's configuration.  With a
    positive definite W the slip stops first (dv_t/dp = W_tn - mu W_tt < 0, since W_tn^2 < W_tt W_nn), then the end
    sticks or reverses and the normal velocity recovers: a finite impulse equal to the brute-force process, no
    warning, no gain of energy."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", FlexbeamWarning)
        sol = fb.simulate(rough_bar(45.0, 2.0, 0.5, vx=-1.0), "imm")
    assert sol.status == "success"
    ev = sol.contacts[0]
    Pn, Pt = brute_force(inverse_mass(45.0)[:3], 1.0, -1.0, 0.5, 2.0, 2.0)
    assert ev.impulse == pytest.approx(Pn, rel=2e-4)
    assert ev.energy_after <= ev.energy_before * (1.0 + 1e-12)


@pytest.mark.parametrize(
    ("overrides", "fragment"),
    [
        ({"contact.friction": -0.1}, "contact.friction"),
        ({"contact.friction": 0.5, "contact.friction_static": 0.3}, "contact.friction_static"),
    ],
)
def test_bad_friction_names_the_field(overrides, fragment):
    with pytest.raises(ValueError, match=fragment.replace(".", r"\.")):
        fb.load_case("seed-experiment", overrides)


def test_frictionless_takes_newtons_map():
    """friction = 0 (the default) takes the frictionless map: the rigid bar's impulse is Newton's (1 + e) v0 / W_nn to
    1e-12 with no tangential impulse (NaN, null in the JSON), where mu = 0.1 would stick or slip (the other tests);
    the seed case's records have none either.  (The fingerprints of tests/validation/fingerprints.py hold the
    frictionless runs to their bits.)"""
    Wtt, Wtn, Wnn, rx, ry = inverse_mass(30.0)
    sol = fb.simulate(rough_bar(30.0, 0.0, 0.5), "imm")
    assert sol.contacts[0].impulse == pytest.approx(1.5 / Wnn, rel=1e-12)
    assert math.isnan(sol.contacts[0].tangential_impulse)
    a = fb.simulate(fb.load_case("seed-experiment"), "imm")
    assert math.isnan(a.metrics()["events"][0]["tangential_impulse"])


def test_the_result_file_holds_the_tangential_impulses(tmp_path):
    """result.nc of a frictional run has contact_tangential_impulse, equal to the records'; a frictionless run's has
    none."""
    sol = fb.simulate(rough_bar(30.0, 0.3, 0.5), "imm")
    ds = sol.to_xarray()
    assert ds["contact_tangential_impulse"].values.tolist() == [c.tangential_impulse for c in sol.contacts]
    assert "contact_tangential_impulse" not in fb.simulate(rough_bar(30.0, 0.0, 0.5), "imm").to_xarray()
