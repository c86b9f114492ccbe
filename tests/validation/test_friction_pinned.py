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

import numpy as np
import pytest

import flexbeam as fb
from tests.validation.test_resting_contact import static_force


def _run(method: str, mu: float):
    case = fb.load_case("seed-experiment", {"model.modes": 0, "contact.friction": mu, "solver.t_end": 0.5,
                                            "output.interval": 1e-3})  # fmt: skip
    return case, fb.simulate(case, method)


#: the resting force of a rigid beam on a law's contact against the held one, relative: measured <= 1.5e-7 over the last
#: 0.1 s of 1 s on three presets (the law's contact still rings about its rest), 33 times that
RESTING_RTOL = 5e-6


@pytest.mark.parametrize("method", ["ccm", "imm"])
def test_a_rigid_beam_held_on_its_stop_sticks_with_the_static_force_and_no_friction_force(method):
    """The seed beam made rigid, mu = 0.3: it lands (CCM) or comes to rest (IMM, by 0.3 s), then rests held at P to
    t_end = 0.5 s.  At t_end: the normal force is F_s within 1e-9 of it (measured 1.2e-12 and 1.1e-12: the held beam's
    steps bounded by HELD_STEPS / kappa, base.py) and the frictionless run's within 1e-9 of F_s (measured 1.4e-12,
    1.9e-12), the friction state stick, the tangential force 0 (no multiplier: indeterminate), and the energy
    balance closes within 1e-10 (measured <= 5e-13)."""
    case, sol = _run(method, 0.3)
    assert sol.status == "success", sol.message
    ds = sol.to_xarray()
    F_s = static_force(case)
    assert ds["contact_force"].values[-1] == pytest.approx(F_s, rel=1e-9)
    assert ds["pair_friction_state"].values[-1, 0] == 2
    assert ds["pair_tangential_force"].values[-1, 0] == 0.0
    assert sol.metrics()["energy_drift_max"] <= 1e-10
    _, smooth = _run(method, 0.0)
    assert smooth.to_xarray()["contact_force"].values[-1] == pytest.approx(F_s, rel=1e-9)
    assert ds["contact_force"].values[-1] == pytest.approx(smooth.to_xarray()["contact_force"].values[-1], rel=1e-9)


@pytest.mark.parametrize("src", ["seed-experiment", "two-stops", "tip-wall"])
def test_a_rigid_beam_coming_to_rest_on_a_law_runs_on_and_rests_at_the_held_force(src):
    """Not friction, its neighbour: the rigid beam under CCFM without friction settles on its stop's law.  At rest
    the energy balance's residual is the round-off of the contact's work (its force times an ulp of the gap,
    1.3e-17 J on the seed case), while the budget counted only T + V_e, ~0 at rest without elastic energy: every
    step was rejected and the run stopped (a step-size underflow or no progress at 0.27-0.39 s).  The budget counts
    the rigid modes' load now (``fb_balance_error``, kernels/src/stepcontrol.c): the run reaches t_end = 1 s; over
    its last 0.1 s the force's median is CCM's held one within RESTING_RTOL (measured 1.5e-7, 1.5e-7 and 4.4e-8 on
    the three presets), and the energy balance closes within 4e-6 (measured <= 4.7e-7).  The held beam's gap keeps
    still: |delta'| at t_end below 1e-12 m/s (measured <= 1e-15; 6.9e-8 on tip-wall with unbounded held steps,
    which grew to 0.78 s: the collocation does not damp the drift on steps longer than a few 1 / kappa)."""
    case = fb.load_case(src, {"model.modes": 0, "solver.t_end": 1.0, "output.interval": 1e-3})
    sol, held = fb.simulate(case, "ccfm"), fb.simulate(case, "ccm")
    assert sol.status == "success", sol.message
    assert held.status == "success", held.message
    F, F_held = (np.median(s.to_xarray()["contact_force"].values[-100:]) for s in (sol, held))
    assert F == pytest.approx(F_held, rel=RESTING_RTOL)
    end = held.source.run.segments[-1]
    assert abs(held.source.system.gap(end.t1, end.y1, 0)[1]) < 1e-12
    assert sol.metrics()["energy_drift_max"] <= 4e-6
