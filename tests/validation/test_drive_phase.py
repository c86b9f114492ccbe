"""The drive phase of each contact record on a shaken base (``events[].drive_phase``, ``contact_drive_phase``).

A base moving as y_O = Y sin(2 pi f t) carries a stiff clamped cantilever over a plane fixed to the ground, a depth h
below the tip's centre line: the tip follows the base (its deflection is quasi-static and tiny), so the first contact
starts where y_O(t) + w_tip(t) = -h.  The onset t* of that crossing is found here on an independent run with the
plane out of reach (the tip's free path, Brent's method), and the record's phase must be frac(f t*): in the drive's
own convention, sin(2 pi phase) = y_O(t*) / Y.  Without a periodic drive the phase is null (NaN).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import flexbeam as fb
from flexbeam.cli import main

SHAKER = "tests/validation/data/shaker-stop.toml"
Y, F, H = 2e-3, 12.0, 1e-3  # base amplitude [m], drive frequency [Hz], depth of the plane under the tip [m]


def shaken_over_plane(depth: float) -> dict:
    """The shaker's cantilever, 10x stiffer (first mode ~180 Hz against the 12 Hz drive), over a ground plane."""
    return {
        "beam.youngs_modulus": 2e12, "base.frequency": F, "base.harmonics": [{"axis": "y", "amplitude": Y}],
        "obstacle.kind": "half-plane", "obstacle.centre": [0.0, -depth], "obstacle.normal": [0.0, 1.0],
        "obstacle.fixed_to": "ground", "contact.side": "centre", "contact.law": "hertz", "contact.stiffness": 1e9,
        "solver.t_end": 0.06,
    }  # fmt: skip


def test_the_drive_phase_is_that_of_the_base_motion_at_the_onset():
    """The onset's phase against the free path's crossing of the plane: y_O(t) + w_tip(t) = -H, f t* = 0.583...
    (the base's descent; a phase of 7/12 for a rigid beam).  Tolerance 1e-8 of a period: the onsets agree to 1e-9 s
    (test_ground_obstacles) and f = 12 Hz; the JSON events and result.nc carry the same phase."""
    free = fb.simulate(fb.load_case(SHAKER, shaken_over_plane(10.0)), "ccfm")
    assert free.status == "success" and not free.contacts
    system, seg = free.source.system, free.source.segments[-1]

    def tip_y(t: float) -> float:  # the tip in the base frame plus the base: its height above the ground
        return float(system.point_state(t, seg.states(np.array([t]))[0], 1)[0][1]) + Y * math.sin(2 * math.pi * F * t)

    onset = brentq(lambda t: tip_y(t) + H, 1.0 / (2 * F), 0.06, xtol=1e-15)
    sol = fb.simulate(fb.load_case(SHAKER, shaken_over_plane(H)), "ccfm")
    first = sol.metrics()["events"][0]
    assert first["onset"] == pytest.approx(onset, abs=1e-9)
    assert first["drive_phase"] == pytest.approx(F * onset - math.floor(F * onset), abs=1e-8)
    # a rigid beam meets the plane where y_O = -H on the way down: phase 7/12.  The tip's deflection moves the onset
    # by at most twice its quasi-static value under the base's peak acceleration, w = mu a L^4 / (8 EI), over the
    # base's speed there: the phase by 2 w / (2 pi Y cos 30 deg) = 0.0125 (a wrong convention moves it by >= 1/6)
    beam = fb.load_case(SHAKER, shaken_over_plane(H)).beam
    w = beam.line_density * Y * (2 * math.pi * F) ** 2 * beam.length**4 / (8 * beam.youngs_modulus * beam.second_moment)
    rigid = (math.pi + math.asin(H / Y)) / (2 * math.pi)
    assert first["drive_phase"] == pytest.approx(rigid, abs=2 * w / (2 * math.pi * Y * math.cos(math.pi / 6)))
    phases = [ev["drive_phase"] for ev in sol.metrics()["events"]]
    assert sol.to_xarray()["contact_drive_phase"].values.tolist() == phases


def test_without_a_periodic_drive_the_phase_is_null(capsys):
    """A run on a fixed joint: every event's drive_phase is NaN (null in --json) and result.nc has no
    contact_drive_phase."""
    sol = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 0.01}), "ccfm")
    events = sol.metrics()["events"]
    assert events and all(math.isnan(ev["drive_phase"]) for ev in events)
    assert "contact_drive_phase" not in sol.to_xarray()
    main(["run", "seed-experiment", "--set", "solver.t_end=0.01", "--json"])
    assert all(ev["drive_phase"] is None for ev in json.loads(capsys.readouterr().out)["events"])
