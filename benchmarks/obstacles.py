"""Several obstacles and contact anywhere: cost per step against the seed case, in one run.

Run: ``python benchmarks/obstacles.py`` (a Markdown table on stdout; ``--json`` for one JSON object;
``--quick`` for a smoke run: 4 modes, 5 ms, one repeat).

Rows, each timed after a 2 ms warm-up, ``--repeats`` times (median):

* ``seed-experiment`` -- the baseline: one fixed pair.
* ``seed + 7 far`` -- the seed case with seven more spheres 1 m below the joint, which the beam never nears:
  their pairs are screened by the events' far bound, so they should cost little per step (the claim of
  issue 11: the cost grows with the pairs that can touch, not with a search on every step).
* ``seed anywhere`` -- the seed case with ``contact.anywhere``: the contact point found on the deformed beam.
* ``two-stops`` (0.2 s), ``spinning-stop`` (0.5 s, contact anywhere), ``tip-wall`` (0.05 s) -- the presets.

Columns: ``wall`` is the Solution's own integration time (``metrics()["wall_time"]``), ``simulate`` the whole
call; ``steps`` the integrator's accepted steps, ``us/step`` wall over steps, and ``x seed`` that per-step cost
over the seed row's, measured in the same run.  ``contacts`` counts the contact records (all pairs).
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from seed import environment  # noqa: E402

import flexbeam as fb  # noqa: E402
from flexbeam.parameters.case import Case  # noqa: E402

COLUMNS = ("case", "method", "n", "t_end [s]", "runs", "wall [ms]", "simulate [ms]", "steps", "us/step", "x seed")


def _far_obstacles(case: Case) -> Case:
    data = case.model_dump()
    data["obstacles"] = [
        {"kind": "sphere", "radius": 0.01, "centre": [0.09 * k, -1.0], "contact": {"position": 0.09 * k}}
        for k in range(1, 8)
    ]
    return Case.model_validate(data)


def cases(modes: int | None, t_end: float | None) -> list[tuple[str, Case]]:
    """(label, case) of every row, with the modes and end time overridden when given."""

    def load(name: str, extra: dict | None = None) -> Case:
        over = dict(extra or {})
        if modes is not None:
            over["model.modes"] = modes
        if t_end is not None:
            over["solver.t_end"] = t_end
        return fb.load_case(name, over)

    seed = load("seed-experiment")
    return [
        ("seed-experiment", seed),
        ("seed + 7 far", _far_obstacles(seed)),
        ("seed anywhere", load("seed-experiment", {"contact.anywhere": True})),
        ("two-stops", load("two-stops")),
        ("spinning-stop", load("spinning-stop")),
        ("tip-wall", load("tip-wall")),
    ]


def row(label: str, case: Case, method: str, repeats: int) -> dict[str, Any]:
    warm = case.model_copy(update={"solver": case.solver.model_copy(update={"t_end": min(2e-3, case.solver.t_end)})})
    fb.simulate(warm, method)
    calls, walls, steps = [], [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        sol = fb.simulate(case, method)
        calls.append(time.perf_counter() - t0)
        m = sol.metrics()
        walls.append(float(m["wall_time"]))
        steps.append(int(m["steps"]))
    wall = statistics.median(walls)
    return {
        "case": label,
        "method": method,
        "n": case.model.modes,
        "t_end [s]": case.solver.t_end,
        "runs": repeats,
        "wall [ms]": 1e3 * wall,
        "simulate [ms]": 1e3 * statistics.median(calls),
        "steps": steps[-1],
        "us/step": 1e6 * wall / max(steps[-1], 1),
        "contacts": len(sol.contacts),
        "status": sol.status,
    }


def fmt(v: Any) -> str:
    if isinstance(v, float):
        return "nan" if not math.isfinite(v) else f"{v:.4g}"
    return str(v)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--methods", default="ccfm,ccm,imm", help="comma-separated impact methods")
    p.add_argument("--repeats", type=int, default=5, help="timed runs per row (median)")
    p.add_argument("--modes", type=int, default=None, help="override model.modes (default: each case's)")
    p.add_argument("--quick", action="store_true", help="smoke run: 4 modes, 5 ms, one repeat")
    p.add_argument("--json", action="store_true", help="one JSON object instead of the table")
    args = p.parse_args(argv)
    modes, t_end, repeats = (4, 5e-3, 1) if args.quick else (args.modes, None, args.repeats)
    rows = []
    for method in args.methods.split(","):
        base = None
        for label, case in cases(modes, t_end):
            r = row(label, case, method, repeats)
            base = r["us/step"] if base is None else base
            r["x seed"] = r["us/step"] / base
            rows.append(r)
    if args.json:
        print(json.dumps({"environment": environment(), "rows": rows}, indent=1))
        return 0
    env = environment()
    load = env["load_average"]
    print(f"machine: {env['machine']}, {env['cores']} cores, load {load:.2f}; flexbeam {env['flexbeam']}")
    print()
    print("| " + " | ".join(COLUMNS + ("contacts",)) + " |")
    print("|" + "---|" * (len(COLUMNS) + 1))
    for r in rows:
        print("| " + " | ".join(fmt(r[c]) for c in COLUMNS + ("contacts",)) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
