"""Each contact pair's own friction law (``[[obstacles]].contact.friction_model``, ``.friction_velocity``; omitted:
the ``[contact]`` section's).

The rigid bar of ``test_friction_ccfm.py`` lies on an incline with tan(alpha) = 0.1 on two stops with mu_k = 0.2,
mu_s = 0.3: the first pair under Coulomb's law with stick, the second under Threlfall's regularised law (no stick,
no force at v_t = 0).  With both regularised the bar creeps (``test_threlfalls_regularised_law_creeps_at_its_closed_
form_speed``); with the Coulomb pair's stick holding it, it cannot: its static equilibrium along the incline puts the
whole weight's component m g sin(alpha) on the sticking pair (within mu_s N = 0.15 m g cos(alpha) of it, so the stick
holds), and the regularised pair, not slipping, carries none.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
from scipy.integrate import simpson

import flexbeam as fb
from flexbeam.model.system import BeamSystem

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_ccfm import STEEL, G, bar_on_stops, creep  # noqa: E402


def mixed_case(t_end: float = 1.2) -> fb.Case:
    data = bar_on_stops(0.2, 0.0, t_end, alpha=math.atan(0.1), mu_s=0.3).model_dump()
    data["obstacles"][0]["contact"].update(friction_model="threlfall", friction_velocity=1e-3)
    return fb.load_case(data)


def test_each_pair_takes_its_own_law_and_the_section_the_rest():
    """The pairs' laws: the first the [contact] section's (Coulomb, v_0 default), the second its own."""
    pairs = BeamSystem.from_case(mixed_case()).contact.pairs
    assert [(p.friction_model, p.friction_velocity) for p in pairs] == [("coulomb", 1e-3), ("threlfall", 1e-3)]
    data = mixed_case().model_dump()
    data["contact"]["friction_model"] = "threlfall"
    data["obstacles"][0]["contact"].update(friction_model=None, friction_velocity=None)
    pairs = BeamSystem.from_case(fb.load_case(data)).contact.pairs
    assert [p.friction_model for p in pairs] == ["threlfall", "threlfall"]


def test_a_sticking_coulomb_pair_holds_the_bar_the_regularised_one_carries_nothing():
    """After settling (t > 0.2 s): the Coulomb pair sticks and the Threlfall pair is in its law throughout
    (pair_friction_state 2 and 1); the contact points creep less than 1e-9 m over 1 s (as the stick test of
    test_friction_ccfm.py; measured 7e-15 m); the sticking pair's tangential force averages -m g sin(alpha) within
    4e-4 relative (measured 3.7e-5: the forces ring about their static values, x10) and the regularised pair's
    averages below 1e-6 of it (measured 4e-12: Threlfall's force at the stick's residual slip, ~1e-12 m/s)."""
    case = mixed_case()
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    ds = sol.to_xarray()
    t = ds["time"].values
    late = t >= 0.2
    state, ft = ds["pair_friction_state"].values[late], ds["pair_tangential_force"].values[late]
    assert np.all(state[:, 0] == 2) and np.all(state[:, 1] == 1)
    m = STEEL["density"] * math.pi * STEEL["radius"] ** 2 * STEEL["length"]
    weight = m * G * math.sin(math.atan(0.1))
    span = t[late][-1] - t[late][0]
    assert abs(simpson(ft[:, 0], x=t[late]) / span + weight) <= 4e-4 * weight
    assert abs(simpson(ft[:, 1], x=t[late]) / span) <= 1e-6 * weight
    assert max(abs(c) for c in creep(sol, BeamSystem.from_case(case), 0.2, 1.2)) < 1e-9
