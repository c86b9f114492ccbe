"""The benchmark script runs (smoke test) and the CLI starts without the heavy libraries."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_seed_benchmark_quick_prints_the_table():
    r = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "seed.py"), "--quick"],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr
    out = r.stdout
    header = next(line for line in out.splitlines() if line.startswith("| method |"))
    columns = [c.strip() for c in header.strip("|").split("|")]
    assert columns == [
        "method",
        "n",
        "integrator",
        "ran",
        "runs",
        "wall [ms]",
        "simulate [ms]",
        "metrics [ms]",
        "steps",
        "free max",
        "contact med/max",
        "peak [N]",
        "d ref(n)",
        "d conv",
        "scipy [ms]",
        "scipy/x",
    ]
    rows = [line for line in out.splitlines() if line.startswith(("| ccfm |", "| ccm |"))]
    assert len(rows) == 4  # two methods x two integrators at 2 modes
    assert not any("error" in row for row in rows), out
    for part in (
        "converged peak (ccfm)",
        "scipy solve_ivp DOP853",
        "flexbeam run seed-experiment --json",
        "kane-spinup",
    ):
        assert part in out


def test_import_cli_does_not_import_heavy_libraries():
    code = (
        "import json, sys, flexbeam.cli; print(json.dumps(sorted({m.split('.')[0] for m in sys.modules} & "
        "{'xarray', 'matplotlib', 'dask', 'distributed', 'pandas', 'netCDF4', 'rich', 'scipy', 'numba'})))"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout) == []


def test_obstacles_benchmark_quick_prints_a_row_per_case_and_method():
    r = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "obstacles.py"), "--quick", "--json"],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr
    rows = json.loads(r.stdout)["rows"]
    assert len(rows) == 6 * 3
    assert {row["case"] for row in rows} >= {"seed-experiment", "two-stops", "spinning-stop", "tip-wall"}
    for row in rows:
        assert row["status"] == "success" and row["steps"] > 0 and row["us/step"] > 0.0
    assert all(row["x seed"] == 1.0 for row in rows if row["case"] == "seed-experiment")


def test_long_run_benchmark_quick_streams_two_lengths():
    r = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "long_run.py"), "--quick", "--json"],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr
    rows = json.loads(r.stdout)["rows"]
    assert [row["t_end [s]"] for row in rows] == [0.5, 1.0]
    for row in rows:
        assert row["status"] == "success" and row["steps"] > 0 and row["peak RSS [MB]"] > 0
        assert row["samples"] > row["t_end [s]"] / 1e-3  # the 1 ms grid and every phase's ends
        assert row["file [MB]"] > 0.0 and row["estimate [MB]"] < 1000


def test_sweep_benchmark_quick_prints_a_row_per_set_up():
    r = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "sweep.py"), "--quick", "--json"],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    rows = {row["set-up"]: row for row in data["rows"]}
    assert len(rows) == 5 and data["cases"] == 8
    assert rows["one task per case, a cluster per sweep (before)"]["x before"] == 1.0
    for row in rows.values():
        assert row["runs"] == 1 and row["cases/s"] > 0 and row["CPU/case [ms]"] > 0


def test_free_beam_benchmark_quick_prints_a_row_per_case_and_method():
    r = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "free_beam.py"), "--quick", "--json"],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=ROOT,
    )
    assert r.returncode == 0, r.stderr
    rows = json.loads(r.stdout)["rows"]
    assert len(rows) == 4 * 2
    assert {row["case"] for row in rows} == {"seed-experiment", "seed anywhere", "free-bar-drop", "free-bar-drop fixed"}
    for row in rows:
        assert row["status"] == "success" and row["steps"] > 0 and row["us/step"] > 0.0 and row["n"] == 4
    assert all(row["x seed"] == 1.0 for row in rows if row["case"] == "seed-experiment")


def test_method_cost_benchmark_compares_two_builds():
    """A smoke run of benchmarks/method_cost.py with this interpreter as its own baseline: a row per build and
    method, CCFM's ratio 1."""
    r = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "method_cost.py"), "--modes", "2", "--t-end", "0.002",
         "--warmup", "0", "--repeats", "1", "--rounds", "1", "--baseline", sys.executable, "--json"],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=ROOT,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    results = json.loads(r.stdout)["results"]
    assert sorted(results) == ["after", "before"]
    for build in results.values():
        assert sorted(build) == ["ccfm", "ccm", "imm"]
        assert all(row["simulate"] >= row["kernel"] > 0.0 for row in build.values())
