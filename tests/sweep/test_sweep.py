"""Sweeps on a real Dask cluster on loopback: resume, a killed worker, an interrupt, failures.

A scheduler and one single-threaded worker (under its nanny) run as subprocesses on
127.0.0.1 for the whole module; every case is a short 2-mode run on the reference integrator
(~0.06 s: slow enough that an interrupt sent after a few finished cases lands mid-sweep; the
compiled integrator finishes such a case in ~10 ms, the whole grid between two polls).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.errors import ParameterError
from flexbeam.sweep import Distribution, case_key, load, open_history, parse_grid, parse_samples, plan

BASE = {"model.modes": 2, "solver.t_end": 0.005, "solver.integrator": "reference"}
GRID = {"contact.restitution": [0.5, 0.6, 0.7, 0.8], "contact.stiffness": [1e9, 2e9, 4e9]}
GRID_ARGS = ["--grid", "contact.restitution=0.5,0.6,0.7,0.8", "--grid", "contact.stiffness=1e9,2e9,4e9"]
TIMING = ["wall_time", "elapsed"]  # the only variables that differ between identical runs


def _start(args: list[str], log: Path) -> subprocess.Popen:
    with log.open("w") as f:
        return subprocess.Popen(args, stdout=f, stderr=subprocess.STDOUT, start_new_session=True)


def _stop(proc: subprocess.Popen) -> None:
    """End a process group this module started (by its id), politely first."""
    if proc.poll() is not None:
        return
    for sig, wait in ((signal.SIGTERM, 10), (signal.SIGKILL, 10)):
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            return
        try:
            proc.wait(wait)
            return
        except subprocess.TimeoutExpired:
            continue


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """(address, client) of a loopback scheduler with one worker process of one thread."""
    from dask.distributed import Client

    d = tmp_path_factory.mktemp("dask")
    sched_file = d / "scheduler.json"
    dask = [sys.executable, "-m", "dask"]
    procs = [
        _start(
            [
                *dask,
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--no-dashboard",
                "--dashboard-address",
                "127.0.0.1:0",
                "--scheduler-file",
                str(sched_file),
            ],
            d / "scheduler.log",
        )
    ]
    try:
        deadline = time.monotonic() + 30
        while not sched_file.exists():
            assert time.monotonic() < deadline, (d / "scheduler.log").read_text()
            time.sleep(0.05)
        procs.append(
            _start(
                [
                    *dask,
                    "worker",
                    "--scheduler-file",
                    str(sched_file),
                    "--host",
                    "127.0.0.1",
                    "--nworkers",
                    "1",
                    "--nthreads",
                    "1",
                    "--no-dashboard",
                ],
                d / "worker.log",
            )
        )
        address = json.loads(sched_file.read_text())["address"]
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(1, timeout=30)
            yield address, client
    finally:
        for proc in reversed(procs):
            _stop(proc)


@pytest.fixture(scope="module")
def reference(cluster, tmp_path_factory):
    """The uninterrupted sweep."""
    out = tmp_path_factory.mktemp("reference") / "store"
    return fb.sweep("seed-experiment", grid=GRID, overrides=BASE, scheduler=cluster[0], out=out)


def _finished(store: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in (store / "cases").glob("*.json")}


def _wait_for(store: Path, count: int, proc: subprocess.Popen, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while len(list((store / "cases").glob("*.json"))) < count:
        assert proc.poll() is None, "the sweep ended early"
        assert time.monotonic() < deadline, "the sweep made no progress"
        time.sleep(0.02)


# The CLI with Ctrl-C restored: a process started from a background job inherits SIGINT ignored.
_CLI = (
    "import runpy, signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
    "sys.argv[0] = 'flexbeam'; runpy.run_module('flexbeam.cli', run_name='__main__')"
)


def _cli(*args: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", _CLI, *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )


def _sweep_args(store: Path, address: str) -> list[str]:
    """One case per task (``--batch-size 1``): a worker killed or a Ctrl-C falls between cases, whatever the
    machine's speed (batches sized to ~0.5 s of work could hold the whole grid)."""
    sets = [a for k, v in BASE.items() for a in ("--set", f"{k}={v}")]
    return ["sweep", "seed-experiment", *sets, *GRID_ARGS, "--scheduler", address, "--out", str(store),
            "--batch-size", "1"]  # fmt: skip


def test_grid_result_has_a_dimension_per_field_and_a_variable_per_metric(reference):
    ds = reference
    assert ds["peak_force"].dims == ("contact.restitution", "contact.stiffness")
    assert ds["contact.stiffness"].values.tolist() == GRID["contact.stiffness"]
    assert set(ds["status"].values.ravel()) == {"success"}
    for name in (
        "peak_force",
        "contact_duration",
        "contacts",
        "post_impact_velocity",
        "second_peak_force",
        "wall_time",
    ):
        assert name in ds
    assert ds["peak_force"].attrs["units"] == "N"
    # the swept fields' units, as the case schema gives them (before: a long_name only)
    assert ds["contact.stiffness"].attrs == {"long_name": "contact.stiffness", "units": "N/m^n"}
    assert ds["contact.restitution"].attrs["units"] == "-"
    # a stiffer contact gives a higher, shorter pulse; more restitution a faster rebound
    assert np.all(np.diff(ds["peak_force"].values, axis=1) > 0)
    assert np.all(np.diff(ds["contact_duration"].values, axis=1) < 0)
    assert np.all(np.diff(ds["post_impact_velocity"].values, axis=0) > 0)
    single = fb.simulate(
        "seed-experiment",
        model__modes=2,
        solver__t_end=0.005,
        contact__restitution=0.6,
        contact__stiffness=2e9,
        solver__integrator="reference",
    ).metrics()
    point = ds.sel({"contact.restitution": 0.6, "contact.stiffness": 2e9})
    assert float(point["peak_force"]) == single["peak_force"]


def test_killed_worker_and_interrupt_lose_no_finished_case_and_resume_equals_uninterrupted(
    cluster, reference, tmp_path
):
    address, client = cluster
    store = tmp_path / "store"
    proc = _cli(*_sweep_args(store, address))
    try:
        _wait_for(store, 2, proc)
        before_kill = _finished(store)
        (pid,) = client.run(os.getpid).values()
        os.kill(pid, signal.SIGKILL)  # the worker process; its nanny starts a new one
        _wait_for(store, len(before_kill) + 2, proc)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        _stop(proc)
    assert proc.returncode == 130, err
    finished = _finished(store)
    total = reference["peak_force"].size
    assert len(before_kill) + 2 <= len(finished) < total, "interrupted mid-sweep"
    for name, content in before_kill.items():
        assert finished[name] == content
    for content in finished.values():
        assert json.loads(content)["status"] == "success"
    partial = load(store)
    assert int((partial["status"] == "missing").sum()) == total - len(finished)

    again = _cli(*_sweep_args(store, address), "--json")
    out, err = again.communicate(timeout=120)
    assert again.returncode == 0, err
    summary = json.loads(out)
    assert summary["reused"] == len(finished) and summary["computed"] == total - len(finished)
    assert summary["missing"] == 0 and summary["failures"] == []
    import xarray as xr

    with xr.open_dataset(store / "result.nc") as resumed:
        xr.testing.assert_equal(resumed.drop_vars(TIMING).load(), reference.drop_vars(TIMING))
    assert resumed.attrs["missing"] == 0


def test_a_cases_run_time_warning_is_said_once_naming_the_case_and_kept_in_the_result(cluster, tmp_path):
    """The FE reference at fem.time_step = 1e-4 and 2e-4 s resolves the seed's 0.61 ms contact in 6.1 and 3.1 steps
    and warns of it (tests/fem/test_contact.py): the warning arises on the worker, in another process.  Before, the
    worker printed it raw (two lines, per case, into the worker's own output: an external cluster's log) and the
    sweep's user saw nothing of it.  Now: one line per case naming its key, the result's ``warning`` and the summary's
    ``warned``."""
    store = tmp_path / "s"
    sets = ["--set", "solver.t_end=1e-3", "--set", "fem.elements=8"]
    proc = _cli("sweep", "seed-experiment", "-m", "fem", *sets, "--grid", "fem.time_step=1e-4,2e-4",
                "--scheduler", cluster[0], "--out", str(store), "--json")  # fmt: skip
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 0, err
    assert json.loads(out)["warned"] == 2
    import xarray as xr

    with xr.open_dataset(store / "result.nc") as ds:
        warned = dict(zip(ds["case_key"].values, ds["warning"].values))
    said = [line for line in err.splitlines() if line.startswith("warning: case ")]
    assert len(said) == 2 and "FlexbeamWarning" not in err
    for key, text in warned.items():
        assert text.startswith("fem.time_step: ") and "fewer than 20" in text
        assert f"warning: case {key}: {text}" in said


def test_the_client_says_the_first_cases_warnings_and_counts_the_rest():
    from flexbeam.errors import FlexbeamWarning
    from flexbeam.sweep.case_warnings import SAID, Teller, recorded

    record: dict = {}
    with recorded(record):
        import warnings

        for text in ("a\nb", "a\nb", "c"):  # distinct ones, on one line each
            warnings.warn(text, FlexbeamWarning, stacklevel=1)
        warnings.warn("d", RuntimeWarning, stacklevel=1)
    assert record["warnings"] == ["a b", "c", "RuntimeWarning: d"]
    teller = Teller()
    with pytest.warns(FlexbeamWarning) as said:
        for i in range(SAID + 3):
            teller.say(f"k{i}", {"warnings": ["x"]} if i != 1 else {})
        teller.close()
    texts = [str(w.message) for w in said]
    assert texts[:SAID] == [f"case k{i}: x" for i in range(SAID + 1) if i != 1]
    assert texts[SAID:] == ["2 more cases warned: the result's variable 'warning' holds every case's warnings"]


def test_warnings_are_taken_aside_only_on_a_one_thread_worker_in_another_process(cluster):
    """``warnings.catch_warnings`` changes the whole process's filters: never in the client's process (an in-process
    cluster's worker threads would take the client's own warnings, or restore each other's filters) nor outside a
    Dask worker; on the loopback cluster's single-threaded worker process, yes."""
    from flexbeam.sweep.case_warnings import exclusive

    assert not exclusive(None) and not exclusive(os.getpid()) and not exclusive(os.getpid() + 1)
    assert cluster[1].submit(exclusive, os.getpid(), pure=False).result(timeout=30)


def test_repeated_samples_are_counted_so_the_summary_adds_up(cluster, tmp_path):
    """Two samples of choice(hertz, flores) drawn alike are one case, computed once: the summary read "2 cases: 1
    computed, 0 reused, 0 failed, 0 missing" (an exploratory hunt); ``repeated`` counts the row that repeats."""
    from flexbeam.sweep import summary

    samples = {"contact.law": "choice(hertz,flores)"}
    keys = [p.key for p in plan(fb.load_case("seed-experiment", BASE), samples=samples, n=2, seed=0).points]
    assert keys[0] == keys[1]  # (seed 0 draws the same law twice: else nothing is tested here)
    ds = fb.sweep("seed-experiment", samples=samples, n=2, seed=0, overrides=BASE, scheduler=cluster[0])
    info = summary(ds)
    assert (info["cases"], info["computed"], info["repeated"]) == (2, 1, 1)


def test_a_failing_case_is_recorded_and_the_others_finish(cluster, tmp_path):
    # 'release' without gravity raises inside the simulation; 'impact' runs
    grid = {"initial.kind": ["impact", "release"], "contact.restitution": [0.6, 0.8]}
    kw = dict(
        grid=grid, overrides={**BASE, "model.gravity": 0.0}, scheduler=cluster[0], out=tmp_path / "s", histories=True
    )
    ds = fb.sweep("seed-experiment", **kw)
    impact, release = ds.sel({"initial.kind": "impact"}), ds.sel({"initial.kind": "release"})
    assert set(impact["status"].values) == {"success"} and np.all(impact["peak_force"] > 0)
    assert set(release["status"].values) == {"error"}
    assert all("gravity" in e for e in release["error"].values)
    assert np.all(np.isnan(release["peak_force"]))
    assert ds.attrs["failed"] == 2 and ds.attrs["missing"] == 0
    key = str(impact["case_key"].values[0])
    hist = open_history(tmp_path / "s", key)
    assert float(hist["contact_force"].max()) == pytest.approx(float(impact["peak_force"][0]), rel=1e-3)
    # a recorded failure is a finished case: the re-run computes nothing
    again = fb.sweep("seed-experiment", **kw)
    assert again.attrs["computed"] == 0 and again.attrs["reused"] == 4


def test_samples_have_a_case_dimension_and_more_samples_reuse_the_first(cluster, tmp_path):
    samples = {"contact.restitution": "uniform(0.5, 0.9)", "contact.stiffness": "loguniform(1e9, 5e9)"}
    kw = dict(
        samples=samples,
        seed=7,
        overrides={"model.modes": 0, "solver.t_end": 0.003},
        scheduler=cluster[0],
        out=tmp_path / "s",
    )
    first = fb.sweep("seed-experiment", n=3, **kw)
    assert first["peak_force"].dims == ("case",) and first.sizes["case"] == 3
    assert first["contact.stiffness"].attrs["units"] == "N/m^n" and "units" not in first["case"].attrs
    e = first["contact.restitution"].values
    assert np.all((e >= 0.5) & (e <= 0.9))
    more = fb.sweep("seed-experiment", n=5, **kw)
    assert more.attrs["reused"] == 3 and more.attrs["computed"] == 2
    np.testing.assert_array_equal(more["peak_force"].values[:3], first["peak_force"].values)


def test_local_cluster_by_default(tmp_path):
    ds = fb.sweep(
        "seed-experiment",
        grid={"contact.restitution": [0.6, 0.8]},
        overrides={"model.modes": 0, "solver.t_end": 0.003},
        workers=1,
        out=tmp_path / "s",
    )
    assert set(ds["status"].values) == {"success"}
    assert (tmp_path / "s" / "result.nc").exists()


# ------------------------------------------------------------------ no cluster needed
def test_case_key_is_the_hash_of_the_parameters_and_method():
    a = fb.load_case("seed-experiment")
    assert case_key(a, "ccfm") == case_key(fb.load_case(a, {"name": "renamed"}), "ccfm")
    assert case_key(a, "ccfm") != case_key(a, "ccm")
    assert case_key(a, "ccfm") != case_key(fb.load_case(a, {"contact.restitution": 0.7}), "ccfm")
    # 1 and 1.0 are the same validated value
    assert case_key(fb.load_case(a, {"model.gravity": 9}), "ccfm") == case_key(
        fb.load_case(a, {"model.gravity": 9.0}), "ccfm"
    )


def test_samples_are_reproducible_and_invalid_samples_are_cases():
    case = fb.load_case("seed-experiment")
    p1 = plan(case, samples={"contact.restitution": "normal(0.9, 0.2)"}, n=50, seed=3)
    p2 = plan(case, samples={"contact.restitution": "normal(0.9, 0.2)"}, n=50, seed=3)
    assert [p.key for p in p1.points] == [p.key for p in p2.points]
    invalid = [p for p in p1.points if p.data is None]
    assert invalid and all("contact.restitution" in p.error for p in invalid)
    assert all(p.overrides["contact.restitution"] > 1 or p.overrides["contact.restitution"] < 0 for p in invalid)


#: a grid of 160 000 cases (refused before any is planned)
WIDE = {"contact.restitution": [0.5 + 1e-3 * i for i in range(400)], "contact.stiffness": [1e9 + i for i in range(400)]}


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda: parse_grid(["contact.restitution"]), "--grid"),
        (lambda: parse_grid(["model.modes=linspace(1,2)"]), "model.modes"),
        (lambda: parse_samples(["contact.restitution=nromal(1,2)"]), "best matches: normal"),
        (lambda: Distribution.parse("loguniform(0, 1)"), "0 < a < b"),
        (
            lambda: plan(fb.load_case("seed-experiment"), grid={"contact.restitutio": [1]}),
            "contact.restitutio: unknown field, did you mean restitution",
        ),
        (lambda: plan(fb.load_case("seed-experiment"), grid={"contact.restitution": [2.0]}), "contact.restitution"),
        (lambda: plan(fb.load_case("seed-experiment"), samples={"contact.restitution": "uniform(0,1)"}), "n:"),
        (lambda: plan(fb.load_case("seed-experiment")), "grid"),
        # a scalar or a string for a grid's values: a TypeError, or a sweep over the string's letters, before
        (lambda: plan(fb.load_case("seed-experiment"), grid={"contact.restitution": 0.5}), "give a list of values"),
        (lambda: plan(fb.load_case("seed-experiment"), grid={"contact.law": "hertz"}), "give a list of values"),
        (lambda: fb.sweep("seed-experiment", grid={"contact.restitution": [0.5]}, method="cfm"), "ccfm"),
        # a plan of 1e9 cases was built before anything ran: 21 GB, killed by the operating system (1e5 at most)
        (lambda: parse_grid(["contact.restitution=linspace(0.5,0.9,1e9)"]), "allowed 1 <= n <= 100000"),
        (
            lambda: plan(fb.load_case("seed-experiment"), samples={"contact.restitution": "uniform(0,1)"}, n=10**9),
            "n: 1000000000 samples; allowed 1 <= n <= 100000",
        ),
        (
            lambda: plan(fb.load_case("seed-experiment"), grid=WIDE),
            "--grid: 400 x 400 = 160000 cases; at most 100000",
        ),
        # 4 and 4.0 are one case: two rows with the same case_key before
        (lambda: plan(fb.load_case("seed-experiment"), grid={"model.modes": [4, 4.0]}), "repeated values"),
        # a continuous distribution on an integer field: every case "invalid", and the sweep exited 0
        (
            lambda: plan(fb.load_case("seed-experiment"), samples={"model.modes": "uniform(2,8)"}, n=2),
            "--sample: every one of the 2 cases is invalid; the first: ParameterError: model.modes",
        ),
    ],
)
def test_bad_input_names_the_field(call, field):
    with pytest.raises(ParameterError, match=field.replace("(", r"\(")):
        call()


def test_grid_values_parse_as_toml_and_ranges():
    grid = parse_grid(["contact.law=hertz,flores", "model.modes=1,2", "contact.stiffness=geomspace(1e9,4e9,3)"])
    assert grid["contact.law"] == ["hertz", "flores"] and grid["model.modes"] == [1, 2]
    # a list field's values: an array's commas do not separate (before: split into '[0.585' and '0.03]', "repeated")
    lists = parse_grid(["obstacles[0].centre=[0.585, 0.03],[0.585,0.04]", 'contact.law="hertz", "flores"'])
    assert lists == {"obstacles[0].centre": [[0.585, 0.03], [0.585, 0.04]], "contact.law": ["hertz", "flores"]}
    np.testing.assert_allclose(grid["contact.stiffness"], [1e9, 2e9, 4e9])
