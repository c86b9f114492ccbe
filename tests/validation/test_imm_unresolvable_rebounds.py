"""IMM ends a Zeno sequence whose rebound flights its gap cannot resolve
(:meth:`flexbeam.methods.imm.IMM.unresolvable`).

A pair pressed back onto its obstacle at a large acceleration a (a flexible bar's vibrating end: ~1.5e4 m/s^2) and
rebounding at w rises only w^2 / (2 a) -- 5e-17 m at w = 1.2e-6 m/s, above the default ``solver.rest_velocity``
(1e-6 m/s).  Such a landing lies below the gap's round-off (~16 eps of its scale, ``kernels/src/surface.c``): the
event search could not locate it and the run ended in a step-size underflow.  A rebound whose flight would rise less
than RISE_ULPS = 64 eps (abs(r_P) + abs(c) + R) now comes to rest like one slower than ``solver.rest_velocity``.
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.methods.imm import EPS, RISE_ULPS

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_simultaneous import steel_bar_on_stops  # noqa: E402

E, G = 0.5, 1e4  # restitution; gravity at the schema's upper bound, so that the floor is above rest_velocity
BAR = {"length": 0.2, "radius": 0.00635, "y_G": 0.1, "arm": 0.3, "stop": 0.01}  # steel_bar_on_stops' geometry


def floor_speed() -> float:
    """The rebound speed below which the rigid bar's flight on its stops rises less than the floor: sqrt(2 g h),
    h = RISE_ULPS eps (abs(r_P) + abs(c) + R) with P at the bar's lower surface above the stop's centre c."""
    x = -BAR["arm"] * BAR["length"]
    r_p = math.hypot(x, BAR["y_G"] - BAR["radius"])
    c = math.hypot(x, BAR["y_G"] - BAR["radius"] - BAR["stop"])
    return math.sqrt(2.0 * G * RISE_ULPS * EPS * (r_p + c + BAR["stop"]))


def test_a_rigid_bar_rests_where_its_rebounds_fall_below_what_the_gap_resolves():
    """A rigid bar (no modes) dropped flat on two stops at v0 under g = 1e4 m/s^2, e = 0.5 (IMM). Its flights are
    ballistic: the k-th impact at t_k = sum_{j=1..k} 2 e^j v0 / g approaches at e^k v0. v0 puts the floor speed w_f
    (:func:`floor_speed`, 8.0e-6 m/s here, above solver.rest_velocity = 1e-6) halfway, in ratio, between the rebounds
    e^10 v0 and e^11 v0 (a factor sqrt 2 from each: the index cannot change with round-off, whose relative error of
    the speeds is 1.3e-3 there): impacts 0..9 rebound, impact 10 -- whose rebound e^11 v0 would rise 1/2 of the floor
    -- comes to rest at t_10, ~2.3e-9 s before the sequence's accumulation point (the former build bounced on to
    impact 12, its rebound below 1e-6 m/s). Checked: the rest's onset at the closed-form t_10 within 5e-11 s (10x the
    5.0e-12 s measured: each landing is located on a flight of ~1e-9 s), its approach speed e^10 v0 within g x 5e-11 s
    (the speed a landing misplaced by that much has; measured 1.5e-8 m/s), every earlier record a rebound; the bar
    then stays on its stops (gap within 1e-12 m) with each stop bearing m g / 2 (1e-9 relative)."""
    w_f = floor_speed()
    v0 = w_f / math.sqrt(2.0) * 2.0**11
    case = fb.load_case(
        steel_bar_on_stops(modes=0, mu=0.0, e=E, vx=0.0, v0=v0).model_dump(),
        {"solver.t_end": 1e-4, "model.gravity": G},
    )
    sol = fb.simulate(case, "imm")
    assert sol.status == "success", sol.message
    records = [r for r in sol.contacts if r.pair == 0]
    k_rest = next(k for k in range(40) if (E ** (k + 1) * v0) ** 2 < w_f**2)
    assert k_rest == 10  # the design above
    assert len(records) == k_rest + 1
    for rec in records[:-1]:
        assert rec.velocity_after == pytest.approx(-E * rec.velocity_before, rel=1e-12)
    rest = records[-1]
    t_rest = sum(2.0 * E**j * v0 / G for j in range(1, k_rest + 1))
    assert abs(rest.onset - t_rest) < 5e-11
    assert abs(-rest.velocity_before - E**k_rest * v0) < G * 5e-11
    assert math.isnan(rest.end)
    mass = 7870.0 * math.pi * BAR["radius"] ** 2 * BAR["length"]
    assert np.max(np.abs(sol.arrays["pair_gap"][-1])) < 1e-12
    assert sol.arrays["pair_contact_force"][-1] == pytest.approx([mass * G / 2.0] * 2, rel=1e-9)


@pytest.mark.parametrize("modes", [4, 6])
def test_a_flexible_bar_dropped_flat_on_two_stops_runs_to_its_end(modes):
    """The flexible steel bar (4 and 6 modes) dropped flat on two stops at 1 m/s, sliding at 0.5 m/s, e = 0.5, with the
    default solver.rest_velocity: one end rests while the other's rebounds accumulate, pressed back at ~1.5e4 m/s^2 by
    the bar's vibration. With 4 modes the former build ended in a step-size underflow at 8.7e-5 s (its flights down to
    5e-17 m); now the run reaches t_end, both ends come to rest, and the energy balance closes within test_energy.py's
    bound at the default tolerance, 1e-5 (measured 2.6e-9 and 1.6e-8)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = fb.simulate(steel_bar_on_stops(modes=modes, mu=0.0, e=E, vx=0.5), "imm")
    assert sol.status == "success", sol.message
    assert {r.pair for r in sol.contacts if not r.end == r.onset} == {0, 1}  # both ends rested (not only bounced)
    assert sol.energy_drift()[1] < 1e-5
