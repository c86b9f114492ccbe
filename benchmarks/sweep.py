"""Sweep throughput: seed cases per second on the machine's cores, batched against one task per case.

Run: ``python benchmarks/sweep.py [--cases 200] [--runs 5] [--json]`` (prints a Markdown table).

Each case is the seed experiment as its preset has it (12 modes, CCFM, its own t_end 0.1 s; about 5 ms of
``simulate`` and 14 ms of ``metrics()`` here), the contact restitution varied over the cases.  Every sweep writes
a fresh store (nothing is reused) and the workers have run a case before any timing.  The rows, measured in turn
within each run so that a change of the machine's load touches them alike:

* **serial, in process**: ``simulate(...).metrics()`` for every case, one after the other (one core; twice its
  rate is what the cores could give with no overhead at all);
* **one task per case, a cluster per sweep**: the path before batches -- each ``sweep()`` started its local
  cluster (one single-threaded worker process per core) and submitted a task per case (``batch_size=1``); the
  cluster's start-up is in the time;
* **one task per case, reused cluster**: ``batch_size=1`` on the process's local cluster;
* **batches, reused cluster**: the default (batches sized as the sweep goes, the local cluster started by the first
  sweep of the process and reused);
* **batches, first sweep of a process**: the default after :func:`flexbeam.sweep.close_local_cluster`, the
  cluster's start-up in the time.

"cases/s" is the median over the runs, "CPU/case" the processor time of the whole process tree (client,
scheduler, workers, and the workers a sweep started and ended) per case, which the machine's load changes far less
than the wall time.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

import flexbeam as fb
from flexbeam.sweep import close_local_cluster, local_client


def grid(n: int) -> dict[str, list[float]]:
    return {"contact.restitution": [float(v) for v in np.linspace(0.5, 0.9, n)]}


def cpu_seconds() -> float:
    """Processor time of this process, its live descendants and its reaped children."""
    import psutil

    me = psutil.Process()
    t = me.cpu_times()
    total = t.user + t.system + t.children_user + t.children_system
    for child in me.children(recursive=True):
        try:
            c = child.cpu_times()
        except psutil.Error:
            continue
        total += c.user + c.system
    return total


def _warm() -> None:
    fb.simulate("seed-experiment", solver__t_end=1e-3).metrics()


def serial(n: int, overrides: dict[str, Any], root: Path) -> None:
    for e in grid(n)["contact.restitution"]:
        fb.simulate(fb.load_case("seed-experiment", {**overrides, "contact.restitution": e})).metrics()


def per_case_new_cluster(n: int, overrides: dict[str, Any], root: Path) -> None:
    from dask.distributed import Client, LocalCluster

    from flexbeam.sweep.cluster import cpu_count, workers_skip_main

    with (
        workers_skip_main(),
        LocalCluster(
            n_workers=cpu_count(),
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        ) as cluster,
        Client(cluster) as client,
    ):
        _check(fb.sweep("seed-experiment", grid=grid(n), overrides=overrides, scheduler=client, out=root, batch_size=1))


def per_case_reused(n: int, overrides: dict[str, Any], root: Path) -> None:
    _check(fb.sweep("seed-experiment", grid=grid(n), overrides=overrides, out=root, batch_size=1))


def batched_reused(n: int, overrides: dict[str, Any], root: Path) -> None:
    _check(fb.sweep("seed-experiment", grid=grid(n), overrides=overrides, out=root))


def batched_first(n: int, overrides: dict[str, Any], root: Path) -> None:
    close_local_cluster()
    _check(fb.sweep("seed-experiment", grid=grid(n), overrides=overrides, out=root))


def _check(ds: Any) -> None:
    assert ds.attrs["computed"] == ds.attrs["cases"] and ds.attrs["failed"] == 0, dict(ds.attrs)


ROWS: list[tuple[str, Callable[[int, dict[str, Any], Path], None]]] = [
    ("serial, in process (1 core)", serial),
    ("one task per case, a cluster per sweep (before)", per_case_new_cluster),
    ("one task per case, reused cluster", per_case_reused),
    ("batches, reused cluster (now)", batched_reused),
    ("batches, first sweep of a process", batched_first),
]


def environment() -> dict[str, Any]:
    import dask

    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), cpu)
    except OSError:
        pass
    from flexbeam.sweep.cluster import cpu_count

    return {
        "machine": f"{platform.machine()} {cpu}".strip(),
        "cores": cpu_count(),
        "python": platform.python_version(),
        "flexbeam": fb.__version__,
        "numpy": np.__version__,
        "dask": dask.__version__,
        "load_average": os.getloadavg()[0] if hasattr(os, "getloadavg") else math.nan,
    }


def measure(n: int, runs: int, overrides: dict[str, Any]) -> list[dict[str, Any]]:
    _warm()
    local_client().run(_warm)
    times: dict[str, list[float]] = {name: [] for name, _ in ROWS}
    cpus: dict[str, list[float]] = {name: [] for name, _ in ROWS}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(runs):
            for name, fn in ROWS:
                root = Path(tmp) / f"{len(times[name])}-{r}-{fn.__name__}"
                c0, t0 = cpu_seconds(), time.perf_counter()
                fn(n, overrides, root)
                times[name].append(time.perf_counter() - t0)
                cpus[name].append(cpu_seconds() - c0)
            local_client().run(_warm)  # the first-sweep row left a new cluster: warm it like the first
    rows = []
    for name, _ in ROWS:
        t = statistics.median(times[name])
        rows.append(
            {
                "set-up": name,
                "runs": len(times[name]),
                "cases/s": n / t,
                "min-max cases/s": (n / max(times[name]), n / min(times[name])),
                "sweep [s]": t,
                "CPU/case [ms]": 1e3 * statistics.median(cpus[name]) / n,
            }
        )
    base = next(row for row in rows if row["set-up"].endswith("(before)"))["cases/s"]
    for row in rows:
        row["x before"] = row["cases/s"] / base
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", type=int, default=200)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--quick", action="store_true", help="smoke test: 8 short cases, one run")
    parser.add_argument("--json", action="store_true", help="print the environment and rows as JSON")
    args = parser.parse_args()
    overrides: dict[str, Any] = {}
    if args.quick:
        args.cases, args.runs, overrides = 8, 1, {"model.modes": 2, "solver.t_end": 0.005}
    env = environment()
    rows = measure(args.cases, args.runs, overrides)
    env["load_average_after"] = os.getloadavg()[0] if hasattr(os, "getloadavg") else math.nan
    if args.json:
        print(json.dumps({"environment": env, "cases": args.cases, "rows": rows}, indent=1))
        return
    print(
        f"machine: {env['machine']}, {env['cores']} cores, python {env['python']}, numpy {env['numpy']}, "
        f"dask {env['dask']}, load average {env['load_average']:.2f} before, {env['load_average_after']:.2f} after"
    )
    what = "seed cases (12 modes, CCFM, t_end 0.1 s)" if not overrides else f"short cases {overrides}"
    print(f"{args.cases} {what} per sweep, median of {args.runs} runs\n")
    print("| set-up | runs | cases/s | min-max | x before | sweep [s] | CPU/case [ms] |")
    print("|---|---|---|---|---|---|---|")
    for row in rows:
        lo, hi = row["min-max cases/s"]
        print(
            f"| {row['set-up']} | {row['runs']} | {row['cases/s']:.1f} | {lo:.1f}-{hi:.1f} | {row['x before']:.2f} "
            f"| {row['sweep [s]']:.2f} | {row['CPU/case [ms]']:.1f} |"
        )


if __name__ == "__main__":  # the local cluster's worker processes re-import this file
    main()
