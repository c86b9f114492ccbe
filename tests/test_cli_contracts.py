"""Output contracts of the CLI: strict ``--json`` equal to the API's metrics, and exit codes.

Exit codes (see the cli module docstring): 0 for a complete run, 1 when a run ends before
``solver.t_end`` or a sweep leaves cases missing, 2 for bad input (tests/test_cli_errors.py).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from typing import Any

import pytest

from tests.conftest import seed

SHORT = {"model.modes": 2, "solver.t_end": 0.002}
COMPLIANT = {"obstacle.support.stiffness": 3e7, "obstacle.support.mass": 0.02, "obstacle.support.damping": 50.0}
#: the README's "--json prints ..." keys with their documented types
FLOAT_KEYS = [
    "peak_force",
    "peak_time",
    "contact_duration",
    "post_impact_velocity",
    "impulse",
    "energy_drift",
    "wall_time",
]
INT_KEYS = ["contacts", "contact_records", "micro_impacts", "chatter_episodes", "steps"]
LIST_KEYS = ["force_peaks", "force_peak_times"]
STR_KEYS = ["method", "status", "message"]
#: a timing, the only metric that differs between two runs of the same case
TIMING = {"wall_time"}
#: the same case run twice is deterministic; 1e-12 leaves room for nothing but the last bits
REL = 1e-12


def flexbeam(*args: str, env: dict[str, str] | None = None, timeout: float = 600) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "flexbeam.cli", *args], capture_output=True, text=True, timeout=timeout, env=env
    )


def sets(overrides: dict[str, Any]) -> list[str]:
    return [a for k, v in overrides.items() for a in ("--set", f"{k}={v!r}")]


def strict_json(text: str) -> Any:
    """Parse JSON, refusing the NaN / Infinity / -Infinity that Python's json module would accept."""

    def refuse(name: str) -> Any:
        raise ValueError(f"not strict JSON: {name}")

    return json.loads(text, parse_constant=refuse)


def assert_metrics_equal(got: Any, expected: Any, exclude: set[str] = frozenset(), key: str = "") -> None:
    """``got`` (parsed JSON) equals ``expected`` (Solution.metrics()): NaN as null, floats to REL, lists and the
    per-pair records item by item."""
    if isinstance(expected, dict):
        assert isinstance(got, dict) and set(got) == set(expected), key
        for k, want in expected.items():
            if k not in exclude:
                assert_metrics_equal(got[k], want, key=f"{key}.{k}" if key else k)
    elif isinstance(expected, list):
        assert isinstance(got, list) and len(got) == len(expected), key
        for h, w in zip(got, expected):
            assert_metrics_equal(h, w, key=key)
    elif isinstance(expected, float) and math.isnan(expected):
        assert got is None, (key, got)
    elif isinstance(expected, float):
        assert isinstance(got, float) and math.isclose(got, expected, rel_tol=REL, abs_tol=0.0), (key, got, expected)
    else:
        assert got == expected and type(got) is type(expected), (key, got, expected)


def assert_documented_types(data: dict[str, Any]) -> None:
    for key in FLOAT_KEYS:
        assert data[key] is None or type(data[key]) is float, (key, data[key])
    for key in INT_KEYS:
        assert type(data[key]) is int, (key, data[key])  # not bool, not float
    for key in LIST_KEYS:
        assert isinstance(data[key], list) and all(type(v) is float for v in data[key]), (key, data[key])
    assert len(data["force_peaks"]) == len(data["force_peak_times"])
    for key in STR_KEYS:
        assert isinstance(data[key], str), (key, data[key])
    # pairs: one record per contact pair, the first pair's metrics repeated in the first one
    assert isinstance(data["pairs"], list) and data["pairs"] and data["pairs"][0]["pair"] == 0
    for record in data["pairs"]:
        assert type(record["pair"]) is int and isinstance(record["obstacle"], str)
        assert all(type(record[key]) is int for key in ("contacts", "contact_records", "micro_impacts")), record
        for key in ("peak_force", "contact_duration", "impulse", "impact_velocity"):
            assert record[key] is None or type(record[key]) is float, (key, record)
    for key in ("peak_force", "contact_duration", "impulse"):
        assert data["pairs"][0][key] == data[key]
    # events: one record per contact record (the full check against the schema: tests/test_json_schema.py)
    assert isinstance(data["events"], list) and len(data["events"]) == data["contact_records"]
    for record in data["events"]:
        assert type(record["index"]) is int and type(record["pair"]) is int and type(record["onset"]) is float
        assert record["kind"] in ("contact", "micro-impact"), record
    # every other metric is a number or null too (the contract may grow, by adding keys)
    for key, value in data.items():
        if key not in (*INT_KEYS, *LIST_KEYS, *STR_KEYS, "pairs", "events"):
            assert value is None or type(value) in (float, int), (key, value)


@pytest.mark.parametrize(
    ("method", "overrides"),
    [
        ("ccfm", SHORT),  # one peak: second_peak_force is NaN -> null
        ("imm", SHORT),  # impulsive: no force history, peak_force etc. NaN -> null
        ("ccfm", {**SHORT, **COMPLIANT}),  # adds the sensor_* metrics
    ],
    ids=["ccfm", "imm", "ccfm-compliant"],
)
def test_json_is_strict_and_equals_the_api_metrics(method, overrides):
    r = flexbeam("run", "seed-experiment", "--method", method, "--json", *sets(overrides))
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    data = strict_json(r.stdout)
    assert_documented_types(data)
    import flexbeam as fb

    expected = fb.simulate(seed(**{k.replace(".", "__"): v for k, v in overrides.items()}), method).metrics()
    assert any(isinstance(v, float) and math.isnan(v) for v in expected.values())  # null is exercised
    assert_metrics_equal(data, expected, exclude=TIMING)
    assert data["status"] == "success" and data["method"] == method


def test_run_that_stops_at_max_contacts_exits_1_and_still_prints_its_metrics():
    # modes = 2: the second contact comes at t ~ 31 ms, past solver.max_contacts = 1
    r = flexbeam("run", "seed-experiment", "--json", *sets({**SHORT, "solver.t_end": 0.035, "solver.max_contacts": 1}))
    assert r.returncode == 1, r.stderr
    data = strict_json(r.stdout)
    # solver.max_contacts limits contact records; the one record is the run's largest, so a contact
    assert data["status"] == "max-contacts" and data["contacts"] == data["contact_records"] == 1
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and "max-contacts" in lines[0] and "solver.max_contacts" in lines[0]
    assert "Traceback" not in r.stderr


def test_complete_run_exits_0_without_json_too():
    r = flexbeam("run", "seed-experiment", *sets(SHORT))
    assert r.returncode == 0, r.stderr
    assert "peak_force" in r.stdout


@pytest.mark.parametrize("args", [["--help"], ["run", "--help"], ["sweep", "--help"], ["cases"]])
def test_help_and_listing_exit_0(args):
    r = flexbeam(*args)
    assert r.returncode == 0, r.stderr
    assert r.stdout and r.stderr == ""


KILLER = '''
"""Dask worker preload: the worker dies (as on a crash or OOM kill) on the case with restitution 0.6."""
import importlib
import os

# flexbeam.sweep.run_case (public) is what every case runs; a task names it by its home module
# and name, so the replacement goes there.  The attribute flexbeam.sweep may be the function
# fb.sweep, hence import_module.  dask imports a preload and then reloads it: wrap the original once.
_run_case = importlib.import_module("flexbeam.sweep").run_case
_run_case = getattr(_run_case, "__wrapped__", _run_case)
home = importlib.import_module(_run_case.__module__)


def run_case(data, *args, **kwargs):
    if data["contact"]["restitution"] == 0.6:
        os._exit(1)
    return _run_case(data, *args, **kwargs)


run_case.__wrapped__ = _run_case
run_case.__module__, run_case.__qualname__ = _run_case.__module__, _run_case.__qualname__
setattr(home, _run_case.__name__, run_case)
'''


def test_sweep_with_missing_cases_exits_1(tmp_path):
    preload = tmp_path / "killer.py"
    preload.write_text(KILLER)
    env = {
        **os.environ,
        "DASK_DISTRIBUTED__WORKER__PRELOAD": json.dumps([str(preload)]),
        "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0",
    }  # lost at the first death, no retry
    store = tmp_path / "store"
    # one case only, the one that is lost (a complete sweep exiting 0 is in tests/sweep/test_sweep.py)
    r = flexbeam(
        "sweep",
        "seed-experiment",
        *sets(SHORT),
        "--grid",
        "contact.restitution=0.6",
        "--workers",
        "1",
        "--out",
        str(store),
        "--json",
        env=env,
        timeout=300,
    )
    assert r.returncode == 1, r.stderr
    info = strict_json(r.stdout)
    assert info["missing"] == 1 and info["cases"] == 1 and info["failed"] == 0
    import xarray as xr

    with xr.open_dataset(store / "result.nc") as ds:
        assert str(ds["status"].sel({"contact.restitution": 0.6}).values) == "missing"


def test_a_case_that_kills_its_worker_inside_a_batch_loses_no_other_case(tmp_path):
    # the batch of three dies with its worker on 0.6 (no retry); its cases run again one at a time: 0.5 and 0.7
    # are stored, 0.6 (which kills the worker again) is missing
    preload = tmp_path / "killer.py"
    preload.write_text(KILLER)
    env = {
        **os.environ,
        "DASK_DISTRIBUTED__WORKER__PRELOAD": json.dumps([str(preload)]),
        "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0",
    }
    store = tmp_path / "store"
    r = flexbeam(
        "sweep",
        "seed-experiment",
        *sets(SHORT),
        "--grid",
        "contact.restitution=0.5,0.6,0.7",
        "--batch-size",
        "3",
        "--workers",
        "1",
        "--out",
        str(store),
        "--json",
        env=env,
        timeout=300,
    )
    assert r.returncode == 1, r.stderr
    info = strict_json(r.stdout)
    assert info["missing"] == 1 and info["cases"] == 3 and info["failed"] == 0 and info["computed"] == 2
    import xarray as xr

    with xr.open_dataset(store / "result.nc") as ds:
        assert ds["status"].values.tolist() == ["success", "missing", "success"]
    assert len(list((store / "cases").glob("*.json"))) == 2


def test_a_sweep_says_a_cases_slenderness_warning_once(tmp_path):
    """The planning validates every case on the client, which says a thick beam's SlenderBeamWarning as one line;
    the worker validated the case again and printed the same warning raw (file, line and source) -- twice in all
    (found by exploratory testing)."""
    r = flexbeam("sweep", "seed-experiment", *sets(SHORT), "--grid", "beam.radius=0.1", "--workers", "1",
                 "--out", str(tmp_path / "store"), timeout=300)  # fmt: skip
    assert r.returncode == 0, r.stderr
    said = [line for line in r.stderr.splitlines() if "r/L = " in line]
    assert len(said) == 1 and said[0].startswith("warning: beam.radius: r/L = "), r.stderr
    assert "SlenderBeamWarning" not in r.stderr
