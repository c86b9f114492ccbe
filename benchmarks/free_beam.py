"""A free beam (``joint.kind = "free"``): cost per step of the bar drop against the seed case at the same modes.

Run: ``python benchmarks/free_beam.py`` (a Markdown table on stdout; ``--json`` for one JSON object; ``--quick``
for a smoke run: 4 modes, one repeat).

Rows, each timed after a 2 ms warm-up, ``--repeats`` times (median), every case at ``--modes`` modes (default 8,
the bar drop's):

* ``seed-experiment`` -- the baseline: the beam on its revolute joint, one fixed contact point, 0.1 s.
* ``seed anywhere`` -- the seed case with ``contact.anywhere`` (the nearest surface point found at every gap).
* ``free-bar-drop`` -- ``tests/validation/data/free-bar-drop.toml``: the free steel bar dropped at 30 degrees on
  its hemispherical end cap (contact anywhere), 0.01 s (its collision episode ends by 0.5 ms; the rest is flight).
* ``free-bar-drop fixed`` -- the same with the contact at the fixed point x = 0 on the lower surface (the end's
  lower corner, no search): what the free joint costs without contact anywhere.

Columns as in ``benchmarks/obstacles.py``: ``wall`` the Solution's integration time, ``simulate`` the whole call,
``steps``, ``us/step`` wall over steps and ``x seed`` that per-step cost over the seed row's in the same run and
method; ``metrics [ms]`` the ``metrics()`` call after it (for the free bar: with its collision episodes and their
restitution on the dense output).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from obstacles import fmt  # noqa: E402
from seed import environment  # noqa: E402

import flexbeam as fb  # noqa: E402
from flexbeam.parameters.case import Case  # noqa: E402

BAR_DROP = Path(__file__).resolve().parents[1] / "tests" / "validation" / "data" / "free-bar-drop.toml"
COLUMNS = ("case", "method", "n", "t_end [s]", "runs", "wall [ms]", "simulate [ms]", "metrics [ms]", "steps",
           "us/step", "x seed", "contacts")  # fmt: skip


def cases(modes: int) -> list[tuple[str, Case]]:
    """(label, case) of every row at ``modes`` modes."""
    n = {"model.modes": modes}
    return [
        ("seed-experiment", fb.load_case("seed-experiment", n)),
        ("seed anywhere", fb.load_case("seed-experiment", {**n, "contact.anywhere": True})),
        ("free-bar-drop", fb.load_case(BAR_DROP, n)),
        ("free-bar-drop fixed", fb.load_case(BAR_DROP, {**n, "contact.anywhere": False, "contact.side": "below"})),
    ]


def row(label: str, case: Case, method: str, repeats: int) -> dict[str, Any]:
    warm = case.model_copy(update={"solver": case.solver.model_copy(update={"t_end": min(2e-3, case.solver.t_end)})})
    fb.simulate(warm, method)
    calls, walls, metrics, steps = [], [], [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        sol = fb.simulate(case, method)
        t1 = time.perf_counter()
        m = sol.metrics()
        metrics.append(time.perf_counter() - t1)
        calls.append(t1 - t0)
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
        "metrics [ms]": 1e3 * statistics.median(metrics),
        "steps": steps[-1],
        "us/step": 1e6 * wall / max(steps[-1], 1),
        "contacts": len(sol.contacts),
        "status": sol.status,
    }


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--methods", default="ccfm,imm", help="comma-separated impact methods (CCM: not for a free beam)")
    p.add_argument("--repeats", type=int, default=7, help="timed runs per row (median)")
    p.add_argument("--modes", type=int, default=8, help="model.modes of every row")
    p.add_argument("--quick", action="store_true", help="smoke run: 4 modes, one repeat")
    p.add_argument("--json", action="store_true", help="one JSON object instead of the table")
    args = p.parse_args(argv)
    modes, repeats = (4, 1) if args.quick else (args.modes, args.repeats)
    rows = []
    for method in args.methods.split(","):
        base = None
        for label, case in cases(modes):
            r = row(label, case, method, repeats)
            base = r["us/step"] if base is None else base
            r["x seed"] = r["us/step"] / base
            rows.append(r)
    env = environment()
    if args.json:
        print(json.dumps({"environment": env, "rows": rows}, indent=1))
        return 0
    load = env["load_average"]
    print(f"machine: {env['machine']}, {env['cores']} cores, load {load:.2f}; flexbeam {env['flexbeam']}")
    print()
    print("| " + " | ".join(COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS))
    for r in rows:
        print("| " + " | ".join(fmt(r[c]) for c in COLUMNS) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
