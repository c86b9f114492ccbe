"""A free beam's collision episodes (docs/free-beam.md, *Collision episodes*): G's velocity and spin before and
after, and the apparent restitution of Newton, Poisson and Stronge (W. J. Stronge, Impact Mechanics, 2000,
sec. 2.3-2.4 and 4.2), against the rigid bar's closed forms.

The rigid bar (no modes) of mass m and length L, translating down at v0 at the inclination theta, strikes the
frictionless ground with one end: P = (1 + e) m v0 / (1 + 3 cos^2 theta), |omega+| = 6 P cos theta / (m L),
v_G+ = -v0 + P / m.  At one frictionless contact the normal velocity of the striking point is linear in the normal
impulse, v = v- + W p, so Newton's, Poisson's and Stronge's coefficients coincide (Stronge 2000, sec. 4.2); IMM
imposes Newton's law, so all three equal its e to round-off.  A contact law restitutes its own effective e_eff on a
rigid body of constant effective mass, which depends on e and the law alone (tests/validation/test_contact_laws.py:
Lankarani-Nikravesh 0.9132 at e = 0.9, +1.5 %, and 0.7252 at e = 0.5, +45 %; Carvalho-Martins exact); the bar turns
a little during the ~0.2 ms contact, which the closed form leaves out (measured: 3e-4 at most).
"""

from __future__ import annotations

import math

import pytest

import flexbeam as fb
from tests.validation.test_free_beam_contact import line_bar, steel_drop

COEFFICIENTS = ("restitution_newton", "restitution_poisson", "restitution_energetic")


def closed_form(case: fb.Case, angle: float, e: float, v0: float = 1.0) -> tuple[float, float, float]:
    """(P, v_Gy+, omega+) of the rigid bar."""
    m, L, th = case.beam.mass, case.beam.length, math.radians(angle)
    P = (1.0 + e) * m * v0 / (1.0 + 3.0 * math.cos(th) ** 2)
    return P, -v0 + P / m, -6.0 * P * math.cos(th) / (m * L)


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("angle", [10.0, 45.0, 80.0])
def test_imm_rigid_bar_episode_has_the_closed_form_and_e_in_all_three_definitions(angle, e):
    """IMM, no modes: one episode of one impact; G's velocity and the spin before and after to round-off, and
    Newton = Poisson = Stronge = e to 1e-14."""
    case = line_bar(angle, e)
    sol = fb.simulate(case, "imm")
    (ep,) = sol.episodes()
    P, vy, w = closed_form(case, angle, e)
    assert ep.records == (0,) and ep.contacts == 1 and ep.micro_impacts == 0
    assert ep.velocity_before == pytest.approx((0.0, -1.0), abs=1e-15) and ep.spin_before == 0.0
    assert ep.velocity_after[0] == pytest.approx(0.0, abs=1e-15)
    assert ep.velocity_after[1] == pytest.approx(vy, rel=1e-14, abs=1e-15)
    assert ep.spin_after == pytest.approx(w, rel=1e-14)
    assert ep.impulse == pytest.approx(P, rel=1e-14)
    assert ep.compression_impulse == pytest.approx(P / (1.0 + e), rel=1e-14)
    for key in COEFFICIENTS:
        assert getattr(ep, key) == pytest.approx(e, abs=1e-14), key
    m = sol.metrics()
    assert m["collision_episodes"] == 1 and m["episodes"][0]["restitution_newton"] == ep.restitution_newton


@pytest.mark.parametrize(
    ("law", "e", "e_eff"),
    [("lankarani_nikravesh", 0.9, 0.9132), ("lankarani_nikravesh", 0.5, 0.7252), ("carvalho_martins", 0.5, 0.5)],
)
@pytest.mark.parametrize("angle", [10.0, 60.0, 80.0])
def test_ccfm_rigid_bar_restitutes_the_laws_effective_e(angle, law, e, e_eff):
    """CCFM, no modes: Newton's coefficient is the law's e_eff on one mass (within 5e-4, the bar's turn and the
    table's 4 digits), Poisson's and Stronge's equal it to 3e-4; G and the spin follow the closed form with e_eff
    (2e-4 v0 and 5e-4 relative)."""
    case = fb.load_case(line_bar(angle, e), {"contact.law": law})
    (ep,) = fb.simulate(case, "ccfm").episodes()
    eN = ep.restitution_newton
    assert eN == pytest.approx(e_eff, abs=5e-4)
    assert ep.restitution_poisson == pytest.approx(eN, abs=3e-4)
    assert ep.restitution_energetic == pytest.approx(eN, abs=3e-4)
    _, vy, w = closed_form(case, angle, eN)
    assert ep.velocity_after[1] == pytest.approx(vy, abs=2e-4)
    assert ep.spin_after == pytest.approx(w, rel=5e-4)
    assert ep.onset < ep.compression_end < ep.end


@pytest.mark.parametrize("method", ["ccfm", "imm"])
def test_flexible_bar_episode_holds_several_contacts_and_conserves_momentum(method):
    """Eight free-free modes at 30 degrees, no gravity, elastic Hertz (CCFM) or e = 1 (IMM): the bar's vibration
    brings the struck end back several times within one episode (Stoianovici & Hurmuzlu 1996), the episode's normal
    impulse is m times the change of G's velocity (1e-9 relative; frictionless: v_Gx stays 0), and the rigid
    motion keeps less than its energy: 0 < e < 1 in all three definitions, which agree to 1 % (the bar turns during
    the episode)."""
    case = fb.load_case(steel_drop(30.0, 8), {"contact.restitution": 1.0})
    sol = fb.simulate(case, method)
    eps = sol.episodes()
    ep = eps[0]
    assert len(ep.records) >= 2 and ep.contacts >= 2
    assert sum(len(e.records) for e in eps) == len(sol.contacts)
    m = case.beam.mass
    assert m * (ep.velocity_after[1] - ep.velocity_before[1]) == pytest.approx(ep.impulse, rel=1e-9)
    assert ep.impulse == pytest.approx(sum(sol.contacts[i].impulse for i in ep.records), rel=1e-9)
    assert ep.velocity_after[0] == pytest.approx(0.0, abs=1e-12)
    eN = ep.restitution_newton
    assert 0.0 < eN < 1.0
    assert ep.restitution_poisson == pytest.approx(eN, rel=1e-2)
    assert ep.restitution_energetic == pytest.approx(eN, rel=1e-2)


def test_gravity_is_taken_out_of_the_coefficients_but_not_out_of_g():
    """The bar drop of tests/validation/data under gravity: G's reported velocity includes gravity's -g dt over the
    episode; the impulse equals m (dv_Gy + g dt) to 1e-6."""
    from pathlib import Path

    case = fb.load_case(Path(__file__).parent / "data" / "free-bar-drop.toml")
    (ep, *_) = fb.simulate(case, "ccfm").episodes()
    g, m = case.model.gravity, case.beam.mass
    assert g > 0.0
    dv = ep.velocity_after[1] - ep.velocity_before[1]
    assert m * (dv + g * (ep.end - ep.onset)) == pytest.approx(ep.impulse, rel=1e-6)


def test_a_shorter_gap_splits_the_episode():
    """The gap is an option of :meth:`Solution.episodes`: below the free flights between the records, each record is
    an episode; the default (one first free-free period, ~0.7 ms for the 20 cm steel bar) groups them."""
    sol = fb.simulate(steel_drop(30.0, 8), "ccfm")
    assert len(sol.episodes()) == 1 < len(sol.contacts)
    assert len(sol.episodes(gap=1e-9)) == len(sol.contacts)


@pytest.mark.parametrize("stream", [False, True])
def test_an_episode_the_run_ends_in_has_no_end_and_no_coefficients(tmp_path, stream):
    """The run ends during the contact (the rigid bar's Hertz contact lasts ~0.2 ms; the run 0.05 ms): the episode is
    not over, so it has no end and no apparent coefficients (NaN, JSON null) -- they read the run's last state as
    'after' before (a rod still pressed on the plane: e_N = -0.04, success).  Held in memory and streamed alike; the
    same bar run to its end keeps all three."""
    case = fb.load_case(line_bar(45.0, 0.9), {"contact.law": "lankarani_nikravesh", "solver.t_end": 5e-5})
    sol = fb.simulate(case, "ccfm", **({"stream": tmp_path / "run.nc"} if stream else {}))
    assert sol.status == "success" and not math.isfinite(sol.contacts[0].end)
    (ep,) = sol.episodes()
    assert math.isnan(ep.end) and ep.onset == 0.0
    assert all(math.isnan(getattr(ep, key)) for key in COEFFICIENTS)
    m = sol.metrics()
    assert all(math.isnan(m[key]) for key in COEFFICIENTS)
    full = fb.simulate(fb.load_case(case, {"solver.t_end": 1e-3}), "ccfm").episodes()[0]
    assert all(0.85 < getattr(full, key) < 1.0 for key in COEFFICIENTS) and full.end < 1e-3


def test_the_last_episode_of_a_run_that_stopped_early_has_no_coefficients():
    """IMM on the rod's end (Saint-Venant's rod, the preset rod-end) stops at solver.max_contacts with the rod still
    driven into the plane; its episode read e_N = -0.82 from G's velocity at the stop.  Now: no end, no
    coefficients."""
    sol = fb.simulate(fb.load_case("rod-end", {"solver.max_contacts": 50}), "imm")
    assert sol.status == "max-contacts"
    ep = sol.episodes()[-1]
    assert math.isnan(ep.end) and all(math.isnan(getattr(ep, key)) for key in COEFFICIENTS)
    assert ep.velocity_after[1] < 0.0  # (G still moving into the plane at the stop: the collision was not over)
