"""The command-line contract: JSON keys, outputs, case round trip, one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import flexbeam as fb

CONTRACT = ["peak_force", "peak_time", "contact_duration", "force_peaks", "contacts",
            "post_impact_velocity", "energy_drift", "wall_time", "steps"]


def flexbeam(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "flexbeam.cli", *args], capture_output=True, text=True,
                          timeout=600)


def test_run_json_has_the_contract_keys(tmp_path):
    r = flexbeam("run", "seed-experiment", "--json", "--set", "model.modes=2", "--set", "solver.t_end=0.002",
                 "--out", str(tmp_path / "out"))
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    for key in CONTRACT:
        assert key in data
    assert data["contacts"] >= 1 and data["peak_force"] > 0
    assert data["post_impact_velocity"] > 0  # away from the obstacle after the first contact
    for name in ("result.nc", "summary.json", "contact_force.png", "normal_velocity.png"):
        assert (tmp_path / "out" / name).stat().st_size > 0
    import xarray as xr

    with xr.open_dataset(tmp_path / "out" / "result.nc") as ds:
        assert ds["contact_force"].attrs["units"] == "N"
        assert float(ds["contact_force"].max()) == pytest.approx(data["peak_force"], rel=1e-3)


def test_cases_show_round_trips_through_run(tmp_path):
    r = flexbeam("cases", "show", "seed-experiment")
    assert r.returncode == 0
    path = tmp_path / "seed.toml"
    path.write_text(r.stdout)
    assert fb.load_case(path) == fb.load_case("seed-experiment")
    listing = flexbeam("cases")
    assert "seed-experiment" in listing.stdout


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["--set", "beam.lenght=1"], "beam.lenght"),
        (["--set", "beam.length=-1"], "beam.length"),
        (["--set", "contact.position=2"], "contact.position"),
        (["--set", "model.modes=-3"], "model.modes"),
        (["--set", "contact.restitution=2"], "contact.restitution"),
        (["--set", "beam.youngs_modulus=abc"], "beam.youngs_modulus"),
        (["--set", "beam.youngs_modulus=nan"], "beam.youngs_modulus"),
        (["--method", "xyz"], "method"),
    ],
)
def test_bad_input_is_one_line_exit_2(args, field):
    r = flexbeam("run", "seed-experiment", "--json", *args)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and field in lines[0]
    assert "Traceback" not in r.stderr


def test_frequencies_json_lists_both_models():
    r = flexbeam("frequencies", "seed-experiment", "--spin", "0", "--modes", "3", "--json")
    data = json.loads(r.stdout)
    assert len(data["first-order"]) == 3 and len(data["zeroth-order"]) == 3
