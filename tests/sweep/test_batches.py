"""Sweeps in batches on the process's local cluster: the same answer as one task per case and as a serial loop,
resuming from a half-done store, a failing case inside a batch, the cluster started once and reused, BLAS on one
thread inside a worker.  (A case that kills its worker inside a batch: tests/test_cli_contracts.py.)

Every case is a short run on the compiled integrator (2 modes, 5 ms: a few milliseconds each), so the batches are
set with ``batch_size``; no test measures time.
"""

from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest
import xarray as xr

import flexbeam as fb
from flexbeam.errors import ParameterError
from flexbeam.sweep import cluster, plan
from flexbeam.sweep.dataset import METRICS

BASE = {"model.modes": 2, "solver.t_end": 0.005}
GRID = {"contact.restitution": [0.5, 0.6, 0.7, 0.8], "contact.stiffness": [1e9, 2e9, 4e9]}
TIMING = ["wall_time", "elapsed"]  # the only variables that differ between identical runs


def _sweep(grid=GRID, **kw) -> xr.Dataset:
    return fb.sweep("seed-experiment", grid=grid, overrides=BASE, **kw)


def _records(store) -> dict[str, dict]:
    return {p.stem: json.loads(p.read_text()) for p in (store / "cases").glob("*.json")}


@pytest.fixture(scope="module")
def one_per_case(tmp_path_factory):
    """The grid with one task per case (the path before batches)."""
    return _sweep(batch_size=1, out=tmp_path_factory.mktemp("one") / "store")


@pytest.mark.parametrize("batch_size", [None, 5, 12])
def test_batches_give_the_dataset_of_one_task_per_case(one_per_case, batch_size, tmp_path):
    ds = _sweep(batch_size=batch_size, out=tmp_path / "store")
    xr.testing.assert_identical(ds.drop_vars(TIMING), one_per_case.drop_vars(TIMING))


def test_batches_give_the_metrics_of_a_serial_loop(one_per_case):
    ds = _sweep(batch_size=5)
    case = fb.load_case("seed-experiment", BASE)
    for p in plan(case, grid=GRID).points:
        metrics = fb.simulate(fb.load_case(case, p.overrides)).metrics()
        point = ds.sel(p.overrides)
        assert str(point["case_key"].values) == p.key
        for name in METRICS:
            if name in TIMING:
                continue
            want = metrics.get(name, math.nan)
            got = float(point[name])
            assert got == want or (math.isnan(got) and math.isnan(want)), (p.overrides, name, got, want)


def test_a_half_done_store_computes_only_the_rest(one_per_case, tmp_path):
    store = tmp_path / "store"
    half = {"contact.restitution": GRID["contact.restitution"][:2], "contact.stiffness": GRID["contact.stiffness"]}
    first = _sweep(half, batch_size=4, out=store)
    assert first.attrs["computed"] == 6
    before = {p.name: p.read_bytes() for p in (store / "cases").glob("*.json")}
    calls: list[tuple[int, int]] = []
    ds = _sweep(batch_size=4, out=store, progress=lambda done, total: calls.append((done, total)))
    assert ds.attrs["reused"] == 6 and ds.attrs["computed"] == 6 and ds.attrs["missing"] == 0
    assert calls[0] == (0, 6) and calls[-1] == (6, 6)
    for name, content in before.items():  # the finished cases were not computed again
        assert (store / "cases" / name).read_bytes() == content
    assert len(_records(store)) == 12
    xr.testing.assert_equal(ds.drop_vars(TIMING), one_per_case.drop_vars(TIMING))  # attrs: computed, reused
    again = _sweep(batch_size=4, out=store)
    assert again.attrs["computed"] == 0 and again.attrs["reused"] == 12


def test_a_failing_case_in_a_batch_does_not_lose_the_others(tmp_path):
    # 'release' without gravity raises inside the simulation; 'impact' runs; one batch, failures between successes
    grid = {"contact.restitution": [0.6, 0.8], "initial.kind": ["release", "impact"]}
    store = tmp_path / "store"
    ds = fb.sweep("seed-experiment", grid=grid, overrides={**BASE, "model.gravity": 0.0}, batch_size=4, out=store)
    assert ds["status"].sel({"initial.kind": "release"}).values.tolist() == ["error", "error"]
    assert ds["status"].sel({"initial.kind": "impact"}).values.tolist() == ["success", "success"]
    assert all("gravity" in e for e in ds["error"].sel({"initial.kind": "release"}).values)
    assert np.all(ds["peak_force"].sel({"initial.kind": "impact"}) > 0)
    records = _records(store)
    assert len(records) == 4 and len({r["worker"] for r in records.values()}) == 1  # one batch, all stored
    assert ds.attrs["failed"] == 2 and ds.attrs["missing"] == 0


def test_a_case_stopped_by_the_zeno_guard_is_counted_as_incomplete(tmp_path):
    """A case that solver.max_contacts stops (status 'max-contacts', its metrics up to there) is no failure, but it
    did not reach solver.t_end: the summary counts it as ``incomplete`` (0 failed, 0 missing and nothing else said
    before, so a sweep read it as complete), beside the failures."""
    from flexbeam.sweep.dataset import summary

    over = {**BASE, "solver.t_end": 0.1}  # (2 modes: contacts at 0, 0.030 and 0.078 s; the third stops it)
    ds = fb.sweep("seed-experiment", grid={"solver.max_contacts": [3, 1000]}, overrides=over, out=tmp_path / "s")
    assert ds["status"].values.tolist() == ["max-contacts", "success"]
    info = summary(ds)
    assert ds.attrs["incomplete"] == 1 and info["incomplete"] == 1 and info["failed"] == 0 and info["failures"] == []


def test_a_history_is_stored_as_the_run_s_result_file(tmp_path):
    """A case's history (``histories=True``, cases/KEY.nc) holds what ``result.nc`` of the same run holds: its outputs
    rounded to the integrator's precision and every sampled variable deflated in chunks (they were stored unrounded
    and uncompressed: 10.3 MB a seed case against 2.7 MB for result.nc)."""
    from flexbeam.results.export import QUANTIZATION_INFO

    over = {**BASE, "solver.t_end": 0.01}
    ds = fb.sweep("seed-experiment", grid={"contact.restitution": [0.6, 0.8]}, overrides=over, out=tmp_path / "s",
                  histories=True)  # fmt: skip
    for e in (0.6, 0.8):
        key = str(ds["case_key"].sel({"contact.restitution": e}).values)
        stored = fb.load_case("seed-experiment", {**over, "contact.restitution": e})
        alone = fb.simulate(stored).to_netcdf(tmp_path / f"alone{e}.nc")
        with xr.open_dataset(tmp_path / "s" / "cases" / f"{key}.nc") as hist, xr.open_dataset(alone) as want:
            assert QUANTIZATION_INFO in hist.variables
            xr.testing.assert_equal(hist.load(), want.load())
            assert hist["contact_force"].encoding.get("zlib") and hist["time"].encoding.get("zlib")


def test_the_local_cluster_is_started_once_and_reused(tmp_path):
    small = {"contact.restitution": [0.6, 0.7, 0.8]}
    _sweep(small, out=tmp_path / "a", batch_size=1)
    client = cluster._Local.client
    assert client is not None and client.status == "running"
    pids = set(client.run(os.getpid).values())
    _sweep(small, out=tmp_path / "b", batch_size=1)
    assert cluster._Local.client is client and cluster.local_client() is client
    assert set(client.run(os.getpid).values()) == pids  # the same worker processes
    for out in ("a", "b"):
        assert {int(r["worker"].rpartition(":")[2]) for r in _records(tmp_path / out).values()} <= pids
    # one single-threaded worker per core
    assert sorted(client.nthreads().values()) == [1] * cluster.cpu_count()


def _blas_threads_in_a_batch() -> tuple[list[int], int]:
    """On a worker: the BLAS threads a case of a batch runs with, and those after the batch (BLAS set to 2)."""
    from threadpoolctl import threadpool_info, threadpool_limits

    def blas() -> int:
        return max(i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas")

    seen: list[int] = []
    original = cluster.run_case

    def probe(data, method, histories=False, aside=False):
        seen.append(blas())
        return {"status": "success", "metrics": {}}, None

    cluster.run_case = probe
    try:
        with threadpool_limits(limits=2, user_api="blas"):
            cluster.run_batch([("a", {}, {}), ("b", {}, {})], "ccfm")
            after = blas()
    finally:
        cluster.run_case = original
    return seen, after


def test_blas_runs_on_one_thread_inside_a_worker():
    client = cluster.local_client()
    seen, after = client.submit(_blas_threads_in_a_batch, pure=False).result()
    assert seen == [1, 1]
    assert after == 2  # restored after the batch (a worker may be a thread of the caller's process)


def test_the_cli_run_holds_blas_to_one_thread(monkeypatch):
    from threadpoolctl import threadpool_info

    import flexbeam.simulation
    from flexbeam.cli import runs

    seen = []
    monkeypatch.setattr(
        flexbeam.simulation,
        "simulate",
        lambda *a, **k: seen.append([i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]),
    )
    runs.simulate(fb.load_case("seed-experiment"), "ccfm")
    assert seen and all(n == 1 for n in seen[0])


def test_batch_sizes():
    size = cluster.batch_size
    assert size(200, 2, None) == 1  # until a case's time is known
    assert size(200, 2, 0.025) == 20  # about BATCH_SECONDS of work
    assert size(10, 2, 0.025) == 3  # an equal share of the rest among the batches in flight
    assert size(200, 2, 2.0) == 1  # a long case alone
    assert size(10_000, 2, 1e-6) == cluster.MAX_BATCH
    assert size(200, 2, None, fixed=7) == 7 and size(5, 2, 0.025, fixed=7) == 5


@pytest.mark.parametrize("bad", [0, -1, 1.5, True])
def test_bad_batch_size_names_the_option(bad):
    with pytest.raises(ParameterError, match="batch_size"):
        _sweep({"contact.restitution": [0.6]}, batch_size=bad)
