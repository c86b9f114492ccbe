"""What the outputs cost after the integration: ``simulate``, ``contacts`` and ``metrics`` of the seed case.

Run: ``python benchmarks/outputs.py`` (a Markdown table on stdout; ``--json`` for one JSON object;
``--lengths 0.1 2 10`` the simulated lengths [s]; ``--repeats`` runs per length, fewer once a row has
spent ``--budget`` seconds).

For each length of ``seed-experiment`` (CCFM, its preset's model, ``solver.memory_limit`` raised so that
long runs are allowed), every run is timed in the same process, in this order, on a fresh Solution:

* ``integration``: the Solution's own ``stats["wall_time"]``, the phases' integration alone -- the
  baseline every other column is a ratio to;
* ``simulate``: the whole ``simulate()`` call (set-up, start checks, integration, the contact log);
* ``contacts``: the first ``Solution.contacts`` (each record's peak force and impulse on the dense
  output);
* ``metrics``: the first ``Solution.metrics()`` after that (energy balance, tip extremes, force peaks,
  counts).

Each is also timed in the thread's CPU time (``time.thread_time``; the integration's by wrapping
``run_phases``), which other jobs on a shared machine disturb least.  The medians are reported with their ratios to
the median integration of the same row, with the
machine and its load average (issue 25's targets: simulate + metrics <= 1.2x the integration at
0.1 s; contacts of 10 s <= 50 ms; metrics of 10 s <= 0.1 s).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import flexbeam as fb
import flexbeam.simulation as fb_simulation
from flexbeam.simulation import simulate

sys.path.insert(0, str(Path(__file__).resolve().parent))
from seed import environment  # noqa: E402  (the machine and library versions, as every benchmark reports them)

CASE = "seed-experiment"


def one_run(t_end: float) -> dict[str, float]:
    """Times [s] of one run of the seed case over ``t_end``: wall clock, and the thread's CPU time (``cpu_*``,
    which other jobs on the machine disturb least)."""
    case = fb.load_case(CASE, {"solver.t_end": t_end, "solver.memory_limit": 2e10})
    marks = [(time.perf_counter(), time.thread_time())]
    sol = simulate(case, "ccfm")
    marks.append((time.perf_counter(), time.thread_time()))
    contacts = sol.contacts
    marks.append((time.perf_counter(), time.thread_time()))
    sol.metrics()
    marks.append((time.perf_counter(), time.thread_time()))
    out = {"integration": float(sol.stats["wall_time"]), "n_contacts": len(contacts), "steps": int(sol.stats["steps"])}
    for i, name in enumerate(("simulate", "contacts", "metrics")):
        out[name] = marks[i + 1][0] - marks[i][0]
        out[f"cpu_{name}"] = marks[i + 1][1] - marks[i][1]
    out["cpu_integration"] = _INTEGRATION_CPU.pop()
    return out


_INTEGRATION_CPU: list[float] = []


def _timed_run_phases(*args: Any, **kwargs: Any) -> Any:
    """``run_phases`` (the integration that ``stats["wall_time"]`` times) with its thread CPU time recorded."""
    c0 = time.thread_time()
    out = _RUN_PHASES(*args, **kwargs)
    _INTEGRATION_CPU.append(time.thread_time() - c0)
    return out


_RUN_PHASES = fb_simulation.run_phases
fb_simulation.run_phases = _timed_run_phases


def row(t_end: float, repeats: int, budget: float) -> dict[str, Any]:
    """Medians over up to ``repeats`` runs (after one warm-up run at 2 ms)."""
    one_run(min(t_end, 0.002))
    runs, start = [], time.perf_counter()
    for _ in range(repeats):
        runs.append(one_run(t_end))
        if time.perf_counter() - start > budget:
            break
    med = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
    base = med["integration"]
    cpu = med["cpu_integration"]
    med.update(
        t_end=t_end,
        runs=len(runs),
        simulate_ratio=med["simulate"] / base,
        after_ratio=(med["simulate"] + med["contacts"] + med["metrics"]) / base,
        cpu_after_ratio=(med["cpu_simulate"] + med["cpu_contacts"] + med["cpu_metrics"]) / cpu,
    )
    return med


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lengths", type=float, nargs="+", default=[0.1, 2.0, 10.0], help="simulated lengths [s]")
    ap.add_argument("--repeats", type=int, default=11, help="runs per length (at most)")
    ap.add_argument("--budget", type=float, default=20.0, help="seconds per length before fewer repeats")
    ap.add_argument("--json", action="store_true", help="one JSON object instead of Markdown")
    args = ap.parse_args()
    env = environment()
    rows = [row(t, args.repeats, args.budget) for t in args.lengths]
    if args.json:
        print(json.dumps({"environment": env, "rows": rows}, indent=1))
        return
    print(f"machine: {env['machine']}, {env['cores']} cores, load {env['load_average']:.2f}; python {env['python']}, "
          f"flexbeam {env['flexbeam']}, numpy {env['numpy']}\n")  # fmt: skip
    print("| t_end [s] | runs | contacts | steps | integration [ms] | simulate [ms] (x) | contacts [ms] | "
          "metrics [ms] | all after / integration | "
          "thread CPU: integration, simulate, contacts, metrics [ms] (x) |")  # fmt: skip
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        cpu = ", ".join(f"{1e3 * r[f'cpu_{k}']:.2f}" for k in ("integration", "simulate", "contacts", "metrics"))
        print(
            f"| {r['t_end']:g} | {r['runs']} | {r['n_contacts']:.0f} | {r['steps']:.0f} | "
            f"{1e3 * r['integration']:.1f} | {1e3 * r['simulate']:.1f} ({r['simulate_ratio']:.2f}) | "
            f"{1e3 * r['contacts']:.1f} | {1e3 * r['metrics']:.1f} | {r['after_ratio']:.2f} | "
            f"{cpu} ({r['cpu_after_ratio']:.2f}) |"
        )


if __name__ == "__main__":
    main()
