"""Cost of the impact methods on a preset (the seed case by default): thread CPU time of ``simulate()`` per method
(issue 25).

Run: ``python benchmarks/method_cost.py`` (Markdown table on stdout; ``--json`` for one JSON object).

What is measured: ``fb.simulate(case, method)`` of ``--case`` (default ``seed-experiment``; ``--modes``, default
the preset's, ``--t-end``) for each of
``--methods`` (default CCFM, CCM, IMM), after ``--warmup`` runs of each, then ``--repeats`` rounds that run the
methods in turn (so that a change of the machine's load falls on all of them alike).  ``simulate`` is the median
thread CPU time (``time.thread_time``) of the whole call -- the load of other processes disturbs it much less than
the wall time --, ``kernel`` the median thread CPU time spent in the compiled step loop (``core.advance``) within
it, ``x ccfm`` the ratio of ``simulate`` to CCFM's of the same process.

``--baseline PYTHON`` compares two builds: ``--rounds`` pairs of fresh processes, this interpreter's and
``PYTHON``'s (e.g. the main checkout's venv, which imports its own flexbeam), alternated, each running the
measurement above; the table gives the medians over the processes of each build.  The load average at the start
and the end is printed: timings on a loaded machine are noisy.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import flexbeam as fb
from flexbeam.kernels import _core

METHODS = ("ccfm", "ccm", "imm")


def measure(
    methods, modes: int | None, t_end: float, warmup: int, repeats: int, preset: str = "seed-experiment"
) -> dict[str, dict[str, float]]:
    """{method: {"simulate": ms, "kernel": ms}}: medians of thread CPU time over ``repeats`` rounds."""
    overrides = {"solver.t_end": t_end} if modes is None else {"model.modes": modes, "solver.t_end": t_end}
    case = fb.load_case(preset, overrides)
    for _ in range(warmup):
        for m in methods:
            fb.simulate(case, m)
    advance, spent = _core.advance, [0.0]

    def timed_advance(*args):
        t0 = time.thread_time()
        try:
            return advance(*args)
        finally:
            spent[0] += time.thread_time() - t0

    times: dict[str, list[tuple[float, float]]] = {m: [] for m in methods}
    _core.advance = timed_advance  # the integrator looks it up on the module at each call
    try:
        for _ in range(repeats):
            for m in methods:
                spent[0] = 0.0
                t0 = time.thread_time()
                fb.simulate(case, m)
                times[m].append((time.thread_time() - t0, spent[0]))
    finally:
        _core.advance = advance
    return {
        m: {
            "simulate": 1e3 * statistics.median(s for s, _ in v),
            "kernel": 1e3 * statistics.median(k for _, k in v),
        }
        for m, v in times.items()
    }


def compare(args) -> dict[str, dict[str, dict[str, float]]]:
    """Alternate fresh worker processes of this build and of ``args.baseline``; medians per build and method."""
    builds = {"after": sys.executable, "before": args.baseline}
    runs: dict[str, list[dict]] = {b: [] for b in builds}
    worker = [__file__, "--worker", "--case", args.case, "--t-end", str(args.t_end), "--warmup", str(args.warmup),
              "--repeats", str(args.repeats), "--methods", *args.methods]  # fmt: skip
    if args.modes is not None:
        worker += ["--modes", str(args.modes)]
    # the baseline imports its own flexbeam: a PYTHONPATH that points this build's source at it is left out
    envs = {"after": None, "before": {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}}
    for r in range(args.rounds):
        for b in sorted(builds, reverse=bool(r % 2)):
            out = subprocess.run([builds[b], *worker], capture_output=True, text=True, check=True, cwd=os.getcwd(),
                                 env=envs[b])  # fmt: skip
            runs[b].append(json.loads(out.stdout))
    return {
        b: {m: {k: statistics.median(run[m][k] for run in v) for k in ("simulate", "kernel")} for m in args.methods}
        for b, v in runs.items()
    }


def table(results: dict[str, dict[str, dict[str, float]]], methods) -> str:
    lines = ["| build | method | simulate [ms] | kernel [ms] | x ccfm |", "|---|---|---|---|---|"]
    for b, res in results.items():
        base = res.get("ccfm", {}).get("simulate")
        for m in methods:
            ratio = f"{res[m]['simulate'] / base:.2f}" if base else "-"
            lines.append(f"| {b} | {m} | {res[m]['simulate']:.2f} | {res[m]['kernel']:.2f} | {ratio} |")
    return "\n".join(lines)


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--methods", nargs="+", default=list(METHODS), choices=METHODS)
    p.add_argument("--case", default="seed-experiment", help="the preset")
    p.add_argument("--modes", type=int, default=None, help="bending modes (default: the preset's)")
    p.add_argument("--t-end", type=float, default=0.1, help="simulated time [s]")
    p.add_argument("--warmup", type=int, default=3, help="untimed runs of each method first")
    p.add_argument("--repeats", type=int, default=15, help="timed rounds (median)")
    p.add_argument("--baseline", help="another build's Python interpreter to compare with (alternated processes)")
    p.add_argument("--rounds", type=int, default=5, help="process pairs with --baseline")
    p.add_argument("--json", action="store_true")
    p.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.worker:
        print(json.dumps(measure(args.methods, args.modes, args.t_end, args.warmup, args.repeats, args.case)))
        return
    load0 = os.getloadavg()[0]
    if args.baseline:
        results = compare(args)
    else:
        results = {"this": measure(args.methods, args.modes, args.t_end, args.warmup, args.repeats, args.case)}
    load1 = os.getloadavg()[0]
    if args.json:
        print(json.dumps({"results": results, "load_average": [load0, load1]}))
        return
    modes = "the preset's" if args.modes is None else args.modes
    print(f"{args.case}, n = {modes}, t_end = {args.t_end} s; {os.cpu_count()} cores, "
          f"load average {load0:.2f} -> {load1:.2f}\n")  # fmt: skip
    print(table(results, args.methods))


if __name__ == "__main__":
    main()
