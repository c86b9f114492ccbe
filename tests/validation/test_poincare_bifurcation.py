"""Poincaré sections and bifurcation diagrams of a beam on a moving base.

* A non-impacting steady state is one point of the Poincaré map: the base-excited cantilever started on its steady
  state (test_moving_base.py) shows, at every period, the relative tip deflection (T(beta L) - 1) Y sin(2 pi phase)
  of the Euler-Bernoulli closed form.
* ``flexbeam bifurcation``: the store and the diagram of a shaker case with a stop (the assumed case
  tests/validation/data/shaker-stop.toml), the sweep up and down, resuming from the store, and bad input.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import flexbeam as fb
from flexbeam.bifurcation import bifurcation
from flexbeam.model.system import BeamSystem
from flexbeam.results.poincare import section_times

from .test_moving_base import CANTILEVER, transmissibility

SHAKER = Path(__file__).resolve().parent / "data" / "shaker-stop.toml"


@pytest.mark.parametrize(("z", "phase"), [(3.0, 0.25), (6.0, 0.6)])
def test_a_steady_non_impacting_response_is_one_point(z, phase):
    """20 periods of the cantilever shaken at beta L = z from its steady state (24 modes): all 20 sections equal
    (T - 1) Y sin(2 pi phase) to 2e-4 Y (the modal truncation bound of test_moving_base.py)."""
    Y = 1e-3
    case = fb.load_case(CANTILEVER, {"model.modes": 24, "model.gravity": 0.0})
    beam = BeamSystem.from_case(case).beam
    mu, EI, L = case.beam.line_density, case.beam.youngs_modulus * case.beam.second_moment, case.beam.length
    w = z * z / L**2 * math.sqrt(EI / mu)
    amp = np.linalg.solve(np.asarray(beam.Kff) - w * w * np.asarray(beam.Mff), np.asarray(beam.sf) * Y * w * w)
    case = fb.load_case(case.model_dump(), {
        "base.frequency": w / (2.0 * math.pi), "base.harmonics": [{"axis": "y", "amplitude": Y}],
        "initial.modal_velocity": [float(v) for v in w * amp], "solver.t_end": 20 * 2.0 * math.pi / w,
    })  # fmt: skip
    sec = fb.simulate(case, "ccfm").poincare(phase)
    assert sec["period"].tolist() == list(range(20)) or sec["period"].tolist() == list(range(21))
    expected = (transmissibility(z) - 1.0) * Y * math.sin(2.0 * math.pi * phase)
    assert np.max(np.abs(sec["tip_deflection"] - expected)) < 2e-4 * Y


def test_section_times_are_the_phase_of_every_period():
    k, t = section_times(0.0, 1.0, 4.0, 0.25)
    assert k.tolist() == [0, 1, 2, 3] and np.allclose(t, (k + 0.25) / 4.0, rtol=0, atol=1e-15)
    k, t = section_times(0.3, 1.0, 4.0, 0.0)
    assert k.tolist() == [2, 3, 4]


@pytest.mark.parametrize("discard", [-1, 1.5, True])
def test_a_poincare_section_discards_a_whole_number_of_periods(discard):
    """discard = -1 gave the sections from period 0 on, as 0 does; 1.5 compared as a number."""
    sol = fb.simulate(fb.load_case(SHAKER, {"solver.t_end": 0.2}), "ccfm")
    with pytest.raises(ValueError, match="discard"):
        sol.poincare(discard=discard)


def test_a_poincare_section_needs_a_shaken_base():
    sol = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 0.01}), "ccfm")
    with pytest.raises(ValueError, match="base.frequency"):
        sol.poincare()


def test_bifurcation_store_resumes_and_sweeps_both_ways(tmp_path):
    """Three frequencies, 8 periods of which 4 discarded: both branches succeed, the Dataset holds 5 sections per point
    (k = 4 .. 8, the last at the run's end: the file kept 4 before, though the store and the amplitude had the
    fifth) and the up branch at the lowest frequency starts from the case's own start (the down branch arrives there
    by continuation: their sections differ); a second call finds every point in the store and returns the same
    values."""
    case = fb.load_case(SHAKER)
    ds = bifurcation(case, 12.0, 20.0, 3, periods=8, discard=4, out=tmp_path, workers=1)
    assert ds["tip"].shape == (2, 3, 5)
    assert (ds["status"].values == "success").all()
    assert np.isfinite(ds["tip"].values).all()
    up, down = ds["tip"].sel(branch="up").values, ds["tip"].sel(branch="down").values
    assert not np.array_equal(up[0], down[0])
    stored = json.loads((tmp_path / "branch-up.json").read_text())
    assert [p["frequency"] for p in stored["points"]] == [12.0, 16.0, 20.0]
    assert [len(p["tip"]) for p in stored["points"]] == [5, 5, 5]
    again = bifurcation(case, 12.0, 20.0, 3, periods=8, discard=4, out=tmp_path, workers=1)
    xr.testing.assert_identical(ds, again)
    assert (tmp_path / "bifurcation.nc").exists()


def test_a_store_made_with_other_settings_is_computed_afresh(tmp_path):
    """A diagram over 6 periods, then the same command with --periods 8 into the same store: its points are those of
    a fresh store, not the 6-period points relabelled (before: 4 sections of the old run NaN-padded to 6 in a file
    that said periods = 8, nothing recomputed)."""
    case = fb.load_case(SHAKER)
    bifurcation(case, 14.0, 16.0, 2, periods=6, discard=3, out=tmp_path / "store", workers=1)
    again = bifurcation(case, 14.0, 16.0, 2, periods=8, discard=3, out=tmp_path / "store", workers=1)
    fresh = bifurcation(case, 14.0, 16.0, 2, periods=8, discard=3, out=tmp_path / "fresh", workers=1)
    assert again["tip"].shape == (2, 2, 6) and np.isfinite(again["tip"].values).all()
    xr.testing.assert_identical(again, fresh)


def test_the_amplitude_is_the_largest_tip_deflection_after_the_transient():
    """The up branch's first point is the case's own run at 14 Hz: its ``amplitude`` equals the largest |tip
    deflection| of that run after the discarded periods, sampled every 2 us on the dense output (the located maximum
    is at least every sample, and above the largest sample by less than 1e-3 of it: the sampling's own error, a
    peak's curvature times (2 us)^2 / 8, is ~1e-5 of it for the 6 modes' fastest, 2.6 kHz).  Before, it was the
    largest of the 4 Poincaré samples: 4.05e-4 m against 1.23e-3 m."""
    case = fb.load_case(SHAKER)
    ds = bifurcation(case, 14.0, 16.0, 2, periods=6, discard=3, workers=1)
    amplitude = float(ds["amplitude"].sel(branch="up", frequency=14.0))
    run = fb.load_case(SHAKER, {"base.frequency": 14.0, "solver.t_end": 6 / 14.0})
    sol = fb.simulate(run, "ccfm")
    t_discard, sampled = 3 / 14.0, 0.0
    for seg in sol.source.segments:
        if seg.t1 > t_discard:
            t = np.arange(max(seg.t0, t_discard), seg.t1, 2e-6)
            sampled = max(sampled, float(np.max(np.abs(sol.source.evaluate(seg, t)[0]["tip_deflection"]))))
    assert sampled <= amplitude * (1.0 + 1e-12) and amplitude <= sampled * (1.0 + 1e-3), (amplitude, sampled)
    assert amplitude > 2.0 * float(np.nanmax(np.abs(ds["tip"].sel(branch="up", frequency=14.0))))


def flexbeam_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "flexbeam.cli", *args], capture_output=True, text=True, timeout=600)


def test_the_bifurcation_command_writes_the_diagram(tmp_path):
    r = flexbeam_cli("bifurcation", str(SHAKER), "--param", "base.frequency=12:20:2", "--periods", "6",
                     "--discard", "3", "-o", str(tmp_path), "--workers", "1", "--json")  # fmt: skip
    assert r.returncode == 0, r.stderr
    info = json.loads(r.stdout)
    assert info["points"] == 4 and info["success"] == 4
    assert (tmp_path / "bifurcation.png").stat().st_size > 10_000


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (("--param", "base.frequency=12:20:2", "--periods", "5", "--discard", "5"), "--discard"),
        (("--param", "base.frequency=0:20:2", "--periods", "5", "--discard", "1"), "--param"),
        (("--param", "contact.stiffness=1:2:3", "--periods", "5", "--discard", "1"), "--param"),
        # an up branch that went down, a count that dropped hi, twice the same frequency (they ran before)
        (("--param", "base.frequency=16:14:2", "--periods", "5", "--discard", "1"), "--param"),
        (("--param", "base.frequency=14:16:1", "--periods", "5", "--discard", "1"), "--param"),
        (("--param", "base.frequency=14:14:2", "--periods", "5", "--discard", "1"), "--param"),
    ],
)
def test_bad_bifurcation_input_is_one_line(tmp_path, args, field):
    r = flexbeam_cli("bifurcation", str(SHAKER), *args, "-o", str(tmp_path))
    assert r.returncode == 2 and r.stdout == ""
    assert len(r.stderr.strip().splitlines()) == 1 and r.stderr.startswith(f"error: {field}"), r.stderr
