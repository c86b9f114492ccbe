"""Sweep throughput: cases per second on 1 and 2 local Dask workers (median of runs).

Run: ``python benchmarks/sweep.py [--cases 16] [--runs 3]`` (prints a Markdown table).

Each case is the seed experiment with 4 modes over 20 ms (contact restitution varied,
about a quarter of a second each).  The baseline is the same cases run one after the other
in this process.  Every sweep writes a fresh store, so nothing is reused; the workers
are warmed up (compiled kernels loaded) before timing, and the cluster start-up is
reported apart.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

import flexbeam as fb

BASE = {"model.modes": 4, "solver.t_end": 0.02}


def grid(n: int) -> dict[str, list[float]]:
    return {"contact.restitution": [float(v) for v in np.linspace(0.5, 0.9, n)]}


def _warm() -> None:
    fb.simulate("seed-experiment", model__modes=4, solver__t_end=1e-3)


def serial(n: int, runs: int) -> list[float]:
    _warm()
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        for e in grid(n)["contact.restitution"]:
            fb.simulate(fb.load_case("seed-experiment", {**BASE, "contact.restitution": e})).metrics()
        times.append(time.perf_counter() - t0)
    return times


def on_cluster(workers: int, n: int, runs: int, root: Path) -> tuple[float, list[float]]:
    from dask.distributed import Client, LocalCluster

    t0 = time.perf_counter()
    with (
        LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        ) as cluster,
        Client(cluster) as client,
    ):
        client.run(_warm)
        startup = time.perf_counter() - t0
        times = []
        for r in range(runs):
            t0 = time.perf_counter()
            ds = fb.sweep(
                "seed-experiment", grid=grid(n), overrides=BASE, scheduler=client, out=root / f"w{workers}-run{r}"
            )
            times.append(time.perf_counter() - t0)
            assert ds.attrs["computed"] == n and ds.attrs["failed"] == 0
    return startup, times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", type=int, default=16)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    import dask

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    print(
        f"machine: {platform.machine()} {platform.processor() or ''}, {cores} cores, "
        f"python {platform.python_version()}, dask {dask.__version__}, load {os.getloadavg()[0]:.2f}"
    )
    print(f"{args.cases} cases per sweep (seed experiment, 4 modes, 20 ms), median of {args.runs} runs\n")
    base = statistics.median(serial(args.cases, args.runs))
    rows = [("serial, in process", args.cases / base, base, float("nan"))]
    with tempfile.TemporaryDirectory() as tmp:
        for w in (1, 2):
            startup, times = on_cluster(w, args.cases, args.runs, Path(tmp))
            t = statistics.median(times)
            rows.append((f"{w} local worker{'s' if w > 1 else ''}", args.cases / t, t, startup))
    print("| set-up | cases/s | ratio to serial | sweep wall time [s] | cluster start-up [s] |")
    print("|---|---|---|---|---|")
    for name, rate, t, startup in rows:
        start = "-" if startup != startup else f"{startup:.2f}"
        print(f"| {name} | {rate:.2f} | {rate / rows[0][1]:.2f} | {t:.2f} | {start} |")


if __name__ == "__main__":  # the local cluster's worker processes re-import this file
    main()
