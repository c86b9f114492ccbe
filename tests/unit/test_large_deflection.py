"""A modal run whose tip deflects beyond the small deflections the model assumes is warned of (results/summary.py
``warn_large_deflection``): a shaker at 0.5 m amplitude swung the 0.3 m beam of tests/validation/data/shaker-stop.toml
1.45 m off its line -- 131 kN of contact force, 110 m/s after the contact -- and the run said "success" (an
exploratory hunt)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import flexbeam as fb
from flexbeam.errors import FlexbeamWarning
from flexbeam.results.summary import LARGE_DEFLECTION, warn_large_deflection

SHAKER = Path(__file__).parents[1] / "validation" / "data" / "shaker-stop.toml"


def test_a_shaker_swinging_the_tip_beyond_a_tenth_of_the_length_is_warned_of():
    case = fb.load_case(SHAKER, {"solver.t_end": 0.06, "base.harmonics[0].amplitude": 0.5})
    sol = fb.simulate(case, "ccm")
    with pytest.warns(FlexbeamWarning, match=r"^tip_deflection: the tip's elastic deflection reaches .* beam\.length"):
        m = sol.metrics()
    assert max(abs(m["tip_deflection_min"]), abs(m["tip_deflection_max"])) > LARGE_DEFLECTION * case.beam.length
    # the preset's own drive (0.5 mm): a few mm at the tip, no warning (pytest's filterwarnings = error)
    sol = fb.simulate(fb.load_case(SHAKER, {"solver.t_end": 0.06}), "ccm")
    m = sol.metrics()
    assert max(abs(m["tip_deflection_min"]), abs(m["tip_deflection_max"])) < 0.1 * LARGE_DEFLECTION * 0.3


def test_the_threshold_and_what_is_not_checked():
    L = 0.7
    below = {"tip_deflection_min": -LARGE_DEFLECTION * L * 0.999, "tip_deflection_max": math.nan}
    warn_large_deflection(below, L)  # (no warning: filterwarnings = error)
    warn_large_deflection({"tip_deflection_min": math.nan, "tip_deflection_max": math.nan}, L)
    warn_large_deflection({"tip_deflection_min": -1.0, "tip_deflection_max": 1.0}, None)  # the FE's: no length
    with pytest.warns(FlexbeamWarning, match=r"reaches 0\.0701 m = 0\.1 beam\.length"):
        warn_large_deflection({"tip_deflection_min": -0.0701, "tip_deflection_max": 0.0}, L)
