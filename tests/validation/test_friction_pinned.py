"""Coulomb friction at a contact its constraint pins (issue 28): a rigid beam pinned at O and held at P.

The rigid beam (``model.modes = 0``) turning about its joint O has one coordinate, theta.  Held on its stop at P (CCM's
contact after its e = 0 onset, IMM's resting contact), the normal constraint J theta' = 0 fixes it, and with it the
slip velocity v_t = J_t theta' (J_t = c J: the two rows of W = [J_t; J] M^-1 [J_t; J]^T are dependent, det W = 0).
So the pair cannot slip, and its friction force is indeterminate: the one equation of moments about O holds for any
(lambda_n, lambda_t) with J lambda_n + J_t lambda_t = the load, and any of them within the cone is a solution.
flexbeam takes lambda_t = 0 (:func:`flexbeam.methods.coulomb.pinned`): the pair sticks (friction state 2), its
tangential force is 0 and its normal force the frictionless one.  At rest level on the stop that is the static force
of the moments about O, F_s = m g L / (2 x_P) (:func:`tests.validation.test_resting_contact.static_force`).

Before, the stick took a tangential multiplier of its own, whose row made the collocation's linear system singular:
a step-size underflow at the first stop (0.19 ms after CCM's onset; IMM's resting phase at 0.23-0.26 s).
"""

from __future__ import annotations

import pytest

import flexbeam as fb
from tests.validation.test_resting_contact import static_force


def _run(method: str, mu: float):
    case = fb.load_case("seed-experiment", {"model.modes": 0, "contact.friction": mu, "solver.t_end": 0.5,
                                            "output.interval": 1e-3})  # fmt: skip
    return case, fb.simulate(case, method)


@pytest.mark.parametrize("method", ["ccm", "imm"])
def test_a_rigid_beam_held_on_its_stop_sticks_with_the_static_force_and_no_friction_force(method):
    """The seed beam made rigid, mu = 0.3: it lands (CCM) or comes to rest (IMM, by 0.3 s), then rests held at P to
    t_end = 0.5 s.  At t_end: the normal force is F_s within 1e-9 of it (measured 5e-13: the Baumgarte-held level
    beam) and the frictionless run's within 1e-9 of F_s (measured 6e-13), the friction state stick, the tangential
    force 0 (no multiplier: indeterminate), and the energy balance closes within 1e-10 (measured 1.4e-14)."""
    case, sol = _run(method, 0.3)
    assert sol.status == "success", sol.message
    ds = sol.to_xarray()
    F_s = static_force(case)
    assert ds["contact_force"].values[-1] == pytest.approx(F_s, rel=1e-9)
    assert ds["pair_friction_state"].values[-1, 0] == 2
    assert ds["pair_tangential_force"].values[-1, 0] == 0.0
    assert sol.metrics()["energy_drift_max"] <= 1e-10
    _, smooth = _run(method, 0.0)
    assert ds["contact_force"].values[-1] == pytest.approx(smooth.to_xarray()["contact_force"].values[-1], rel=1e-9)


def test_a_rigid_beam_coming_to_rest_on_a_law_says_why_it_stops_and_what_holds_it():
    """Not friction, its neighbour: the same rigid beam under CCFM without friction settles on its stop's law, where
    the energy balance's budget vanishes (the energy error of a state error in T + V_e, both ~0 at rest without
    elastic energy) while its residual carries the contact's and gravity's work at round-off: every step is rejected
    and the run stops (measured: a step-size underflow at 0.39 s).  A known limit, not fixed: the message says so and
    names what holds the beam at rest (CCM, IMM; with friction the stick does), and CCM runs the same case to t_end.
    (Whether it stops is a matter of round-off against a vanishing budget, so only its message is asserted.)"""
    case = fb.load_case("seed-experiment", {"model.modes": 0, "solver.t_end": 0.5})
    sol = fb.simulate(case, "ccfm")
    if sol.status != "success":
        assert "by the energy balance" in sol.message and "model.modes = 0" in sol.message
        assert "CCM or IMM" in sol.message
    assert fb.simulate(case, "ccm").status == "success"
