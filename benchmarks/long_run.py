"""Long runs streamed to disk: peak memory and wall time of ``seed-experiment`` for 10, 100 and 1000 s.

Run: ``python benchmarks/long_run.py`` (a Markdown table on stdout; ``--json`` for one JSON object;
``--lengths 10,100`` for other run lengths [s]; ``--interval`` for the output interval [s], 1 ms by default;
``--quick`` for a smoke run: 0.5 and 1 s).

Each length runs in a fresh interpreter (``flexbeam run seed-experiment --stream --out DIR --set solver.t_end=T
--set output.interval=1e-3``, in-process through :func:`flexbeam.simulation.simulate` with ``stream``), which
reports its own peak resident memory (``getrusage``: everything the process held, the interpreter, numpy, xarray,
netCDF4 and HDF5 included) and, sampled as the run goes (``/proc/self/statm`` at every segment it hands on), the
resident memory at 10 % and at the end of the run, so that its growth shows.  The beam falls on its stop and ends
resting there after 0.71 s: from then on one contact record lasts to the end of the run (~520 steps per simulated
second once it rests, on Radau IIA's nodes), which an in-memory run would hold as dense output (``memory`` column: the
estimate :func:`flexbeam.memory.estimate` gives the run held in memory, an upper bound that counts the bounded
~14 000 steps per second, which a default ``solver.memory_limit`` refuses beyond a few hundred seconds).

Columns: ``t_end``; ``samples`` written; ``steps`` of the integrator; ``wall`` the whole run (integration, samples,
file), ``integration`` the integrator's share (``metrics()["wall_time"]``); ``peak RSS`` the process's peak,
``RSS 10 %`` and ``RSS end`` while the run goes on; ``estimate`` the streamed run's memory estimate (what the stream
keeps, without the interpreter and its libraries); ``file`` the size of ``result.nc``; ``in memory`` the estimate of
the same run held in memory.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

COLUMNS = (
    "t_end [s]", "samples", "steps", "wall [s]", "integration [s]", "peak RSS [MB]", "RSS 10 % [MB]",
    "RSS end [MB]", "estimate [MB]", "file [MB]", "in memory [GB]",
)  # fmt: skip


def child(t_end: float, interval: float, method: str) -> dict[str, Any]:
    """One streamed run in this process: its numbers (see the module docstring)."""
    import flexbeam as fb
    from flexbeam import memory
    from flexbeam.results import stream
    from flexbeam.simulation import simulate

    case = fb.load_case("seed-experiment", {"solver.t_end": t_end, "output.interval": interval})
    page = os.sysconf("SC_PAGE_SIZE")
    marks: list[tuple[float, float]] = []
    handed = stream.RunStream.__call__

    def call(self, seg):  # the resident memory as the run goes on
        handed(self, seg)
        with open("/proc/self/statm") as f:
            marks.append((seg.t1, int(f.read().split()[1]) * page / 1e6))

    stream.RunStream.__call__ = call
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "result.nc"
        t0 = time.perf_counter()
        sol = simulate(case, method, stream=path)
        metrics = sol.metrics()
        wall = time.perf_counter() - t0
        size = path.stat().st_size
        import netCDF4

        with netCDF4.Dataset(path) as nc:
            samples = len(nc.dimensions["time"])
    rss = {}
    for share in (0.1, 1.0):
        rss[share] = next((m for t, m in marks if t >= share * t_end - 1e-9), marks[-1][1] if marks else float("nan"))
    return {
        "t_end [s]": t_end,
        "samples": samples,
        "steps": metrics["steps"],
        "wall [s]": round(wall, 1),
        "integration [s]": round(metrics["wall_time"], 1),
        "peak RSS [MB]": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e3),
        "RSS 10 % [MB]": round(rss[0.1]),
        "RSS end [MB]": round(rss[1.0]),
        "estimate [MB]": round(memory.estimate(case, method, stream=True).total / 1e6),
        "file [MB]": round(size / 1e6, 2),
        "in memory [GB]": round(memory.estimate(case, method, outputs=True).total / 1e9, 3),
        "status": metrics["status"],
        "contact_records": metrics["contact_records"],
        "energy_drift_max": metrics["energy_drift_max"],
    }


def run(lengths: list[float], interval: float, method: str) -> list[dict[str, Any]]:
    rows = []
    for t_end in lengths:
        cmd = [sys.executable, __file__, "--child", repr(t_end), "--interval", repr(interval), "--method", method]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            rows.append({"t_end [s]": t_end, "error": r.stderr.strip().splitlines()[-1:]})
            continue
        rows.append(json.loads(r.stdout.strip().splitlines()[-1]))
    return rows


def markdown(rows: list[dict[str, Any]]) -> str:
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for row in rows:
        if "error" in row:
            lines.append(f"| {row['t_end [s]']:g} | error: {row['error']} |")
            continue
        lines.append(
            "| " + " | ".join(f"{row[c]:g}" if isinstance(row[c], float) else str(row[c]) for c in COLUMNS) + " |"
        )
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lengths", default="10,100,1000", help="run lengths [s], comma-separated")
    parser.add_argument("--interval", type=float, default=1e-3, help="output interval [s]")
    parser.add_argument("--method", default="ccfm")
    parser.add_argument("--quick", action="store_true", help="smoke run: 0.5 and 1 s")
    parser.add_argument("--json", action="store_true", help="one JSON object")
    parser.add_argument("--child", type=float, default=None, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        print(json.dumps(child(args.child, args.interval, args.method)))
        return
    lengths = [0.5, 1.0] if args.quick else [float(x) for x in args.lengths.split(",") if x.strip()]
    from seed import environment

    rows = run(lengths, args.interval, args.method)
    if args.json:
        print(json.dumps({"environment": environment(), "interval": args.interval, "rows": rows}, indent=2))
        return
    env = environment()
    print(
        f"seed-experiment streamed ({args.method}, output.interval = {args.interval:g} s); {env['machine']}, "
        f"{env['cores']} cores, load average {env['load_average']:.2f}\n"
    )
    print(markdown(rows), end="")


if __name__ == "__main__":
    main()
