"""Coulomb friction in the FE reference (``--method fem``): Brown & McPhee's regularised law at each pair.

* The law against its published form (Brown & McPhee 2016, J. Comput. Nonlinear Dynam. 11(5) 054502): odd in the
  slip velocity, mu_s (to tanh(4)) at the transition velocity v_s, mu_k in sliding, its derivative.
* The rigid limit: a short, very stiff bar (no gravity) striking rough ground with its end at an angle, under an
  elastic Hertz contact (Stronge's energetic e = 1).  The FE bar's impulses tend to the rigid bar's closed forms of
  tests/validation/test_friction_impact.py (slip throughout, or stick) as the contact's duration t_c goes to zero:
  what is left of the impact's finite duration (the bar turns during it) is O(t_c) and t_c ~ K^(-2/5) (Hertz), so
  that the errors at K and 10 K stand in the ratio 10^(-2/5) and their Richardson extrapolation to t_c = 0 vanishes.
  Measured (16 elements, E = 2e15 Pa so that the bar's vibration is out of the picture, v_s = 1e-4 m/s): the errors
  2e-3 - 6e-5 at K = 4.4e10, ratios 0.39 - 0.41, the extrapolation within 3e-5 of the closed forms.
* The energy balance of a frictional run closes (the friction's dissipation -F_t v_t >= 0 booked), and the records
  carry the tangential impulse along t = (-n_y, n_x), as IMM's.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.fem.beam import FemBeam
from flexbeam.fem.contact_law import friction_law

L, R, RHO = 0.1, 0.01, 7800.0
AREA = math.pi * R * R
MASS = RHO * AREA * L


def rough_stiff_bar(angle_deg: float, mu: float, stiffness: float, youngs: float = 2e15, cap: bool = False) -> fb.Case:
    """A free bar (0.1 m, 10 mm radius, no gravity) falling at 1 m/s without spin onto rough ground with its end x = 0,
    its axis at ``angle_deg``; Hertz contact of stiffness K (elastic); Coulomb mu_s = mu_k = ``mu``.  The contact point
    is the end of the centre line, or with ``cap`` the lowest point of the end's hemispherical cap (contact anywhere:
    a point of the capsule's surface, which turns with the end section)."""
    th = math.radians(angle_deg)
    section = (
        {"section": "circle", "radius": R}
        if cap
        else {"section": "general", "area": AREA, "second_moment": math.pi * R**4 / 4, "half_depth": 0.0}
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a stubby bar: the slender-beam warning (its bending is not what is tested)
        return fb.load_case({
            "name": "rough-stiff-bar",
            "beam": {"length": L, "density": RHO, "youngs_modulus": youngs, "poisson_ratio": 0.3, **section},
            "joint": {"kind": "free"},
            "model": {"modes": 0, "gravity": 0.0},
            "obstacle": {"kind": "half-plane", "centre": [0.0, 0.0], "normal": [0.0, 1.0]},
            "contact": {"law": "hertz", "position": 0.0, "stiffness": stiffness, "side": "centre", "anywhere": cap,
                        "friction": mu, "friction_static": mu},
            "initial": {"kind": "state",
                        "position": [0.5 * L * math.cos(th), 0.5 * L * math.sin(th) + (R + 1e-9 if cap else 0.0)],
                        "velocity": [0.0, -1.0], "angle": th, "rate": 0.0},
            "solver": {"t_end": 2e-3},
            "fem": {"elements": 16, "friction_velocity": 1e-4},
        })  # fmt: skip


def rigid_impulses(angle_deg: float, mu: float, cap: bool = False, v0: float = 1.0, e: float = 1.0):
    """(P_n, P_t) of the rigid bar, stick or slip throughout (test_friction_impact.py's closed forms, Stronge 2000
    ch. 5): W the 2 x 2 inverse mass of the contact point in the axes t = (-1, 0), n = (0, 1); with ``cap`` the point
    lies R below the centre line's end."""
    th = math.radians(angle_deg)
    rx, ry = -0.5 * L * math.cos(th), -0.5 * L * math.sin(th) - (R if cap else 0.0)
    JG = MASS * L * L / 12.0
    Wtt, Wtn, Wnn = 1.0 / MASS + ry * ry / JG, rx * ry / JG, 1.0 / MASS + rx * rx / JG
    if abs(Wtn) <= mu * Wtt:  # stick
        Pn = (1.0 + e) * v0 / (Wnn - Wtn * Wtn / Wtt)
        return Pn, -(Wtn / Wtt) * Pn
    s = math.copysign(1.0, Wtn)  # slip throughout
    Pn = (1.0 + e) * v0 / (Wnn - mu * s * Wtn)
    return Pn, -mu * s * Pn


def test_the_regularised_law_is_brown_and_mcphees():
    """phi odd; phi(v_s) = mu_k tanh(4) + (mu_s - mu_k) (the Stribeck peak at v_s); phi -> mu_k when sliding fast;
    phi' against central differences (1e-7 relative: the step 1e-6 v_s, the derivative's third-order error)."""
    mu_k, mu_s, vs = 0.3, 0.5, 1e-3
    assert friction_law(mu_k, mu_s, vs, -2e-4)[0] == -friction_law(mu_k, mu_s, vs, 2e-4)[0]
    assert friction_law(mu_k, mu_s, vs, vs)[0] == pytest.approx(mu_k * math.tanh(4.0) + (mu_s - mu_k), rel=1e-15)
    assert friction_law(mu_k, mu_s, vs, 1e3 * vs)[0] == pytest.approx(mu_k, rel=1e-5)
    for v in (-3e-3, -1e-4, 0.0, 5e-4, 2e-3):
        h = 1e-6 * vs
        fd = (friction_law(mu_k, mu_s, vs, v + h)[0] - friction_law(mu_k, mu_s, vs, v - h)[0]) / (2 * h)
        assert friction_law(mu_k, mu_s, vs, v)[1] == pytest.approx(fd, rel=1e-7)


@pytest.mark.parametrize(
    ("angle", "mu", "cap"),
    [(20.0, 2.0, False), (45.0, 0.1, False), (70.0, 2.0, False), (70.0, 0.1, False), (20.0, 2.0, True),
     (45.0, 0.1, True), (70.0, 2.0, True)],
)  # fmt: skip
def test_the_fe_bar_tends_to_the_rigid_closed_form(angle, mu, cap):
    """Stick (20 and 70 deg, mu = 2) and slip throughout (mu = 0.1), at the centre line's end or on the end's cap
    (contact anywhere; sticking there holds the surface point, which turns with the section): the normal and
    tangential impulses at K and 10 K (module docstring): each error shrinks as t_c ~ K^(-2/5) (ratio 0.398 +- 15 %;
    measured within 2 %) and their extrapolation to t_c = 0 is within 3e-4 of the closed form (10x the largest
    measured, 2.8e-5)."""
    Pn, Pt = rigid_impulses(angle, mu, cap)
    errors = []
    for K in (4.4e9, 4.4e10):
        sol = fb.simulate(rough_stiff_bar(angle, mu, K, cap=cap), "fem")
        assert sol.status == "success" and len(sol.contacts) == 1
        ev = sol.contacts[0]
        errors.append(np.array([ev.impulse / Pn - 1.0, ev.tangential_impulse / Pt - 1.0]))
    r = 10.0**-0.4
    assert np.all(np.abs(errors[1] / errors[0] - r) <= 0.15 * r), errors
    extrapolated = (errors[1] - r * errors[0]) / (1.0 - r)
    assert np.all(np.abs(extrapolated) <= 3e-4), extrapolated


def test_a_frictional_fe_run_balances_its_energy_and_keeps_its_outputs():
    """The sliding impact (45 deg, mu = 0.1) on a bar of steel's stiffness: the energy balance closes to 2e-4 of the
    kinetic energy (10x the 1.9e-5 measured; friction's work booked as dissipation, which grows monotonically), the
    friction force and slip velocity are in the Dataset, and the record's tangential impulse is their integral."""
    sol = fb.simulate(rough_stiff_bar(45.0, 0.1, 4.4e9, youngs=2e11), "fem")
    T0 = 0.5 * MASS
    E = sol.arrays["total_energy"]
    assert np.max(np.abs(E - E[0])) <= 2e-4 * T0
    assert np.all(np.diff(sol.arrays["dissipated_energy"]) >= -1e-12 * T0)
    assert sol.arrays["dissipated_energy"][-1] > 1e-3 * T0  # the slip did dissipate
    ds = sol.to_xarray()
    Ft, vt = ds["pair_tangential_force"].values[:, 0], ds["pair_slip_velocity"].values[:, 0]
    state = ds["pair_friction_state"].values[:, 0]
    assert np.all(Ft * vt <= 0.0)  # friction opposes the slip at every sample
    # it slips throughout (mu = 0.1), from rest along t at the onset (within the law's band there, state 2)
    ev = sol.contacts[0]
    late = (sol.time > ev.onset + 0.1 * (ev.end - ev.onset)) & (sol.time < ev.end)
    assert np.all(state[late] == 1.0) and np.all(state[sol.arrays["contact_force"] == 0.0] == 0.0)
    assert sol.contacts[0].tangential_impulse == pytest.approx(np.trapezoid(Ft, sol.time), rel=1e-9)


def test_threlfalls_law_for_a_case_that_names_it():
    """``contact.friction_model = "threlfall"``: the FE uses the case's law, mu_k (1 - exp(-3 v / v_0)) sign(v) (as
    CCFM does), with its v_0, not the Brown & McPhee stand-in for exact Coulomb friction."""
    mu_k, v0 = 0.4, 2e-3
    for v in (-5e-3, -1e-4, 1e-4, 3e-3):
        phi, dphi = friction_law(mu_k, mu_k, v0, v, 1.0)
        assert phi == pytest.approx(mu_k * math.copysign(1.0 - math.exp(-3.0 * abs(v) / v0), v), rel=1e-15)
        assert dphi == pytest.approx(3.0 * mu_k / v0 * math.exp(-3.0 * abs(v) / v0), rel=1e-15)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the stubby bar's slender-beam warning
        case = fb.load_case(rough_stiff_bar(45.0, 0.4, 4.4e9).model_dump(),
                            {"contact.friction_model": "threlfall", "contact.friction_velocity": v0})  # fmt: skip
    beam = FemBeam.from_case(case)
    assert beam.free_state.friction[0].tolist() == [0.4, 0.4, v0, 1.0]
