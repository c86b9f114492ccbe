"""CCFM's resting contact (issue 25, item 3): steps per simulated second while the seed beam rests on the sphere.

Runs ``seed-experiment`` to 3 s with CCFM twice in one process: with the step bound t_c / CONTACT_STEPS lifted once a
contact has lasted RESTING_DURATIONS t_c (``flexbeam.methods.base``, the default: the resting contact then collocates
at Radau IIA's nodes, ``kernels/src/propagation.c``) and with it kept for the whole contact (RESTING_DURATIONS = inf,
the behaviour before, Gauss's nodes throughout), and prints a Markdown table: the resting phase's steps, its
steps per simulated second overall and from t = 2 s, the wall time and the contact force at t_end.

    python benchmarks/resting.py [--t-end 3.0]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

import flexbeam as fb
import flexbeam.methods.base as base


def measure(resting: float, t_end: float) -> dict:
    base.RESTING_DURATIONS = resting
    case = fb.load_case("seed-experiment", {"solver.t_end": t_end, "solver.memory_limit": 2e10})
    w0 = time.perf_counter()
    sol = fb.simulate(case, "ccfm")
    wall = time.perf_counter() - w0
    run = sol.source.run
    seg = run.segments[-1]
    t = seg.dense.records[:, 0]
    late = 2.0 if seg.t1 >= 2.5 else 0.5 * (seg.t0 + seg.t1)
    cols, _, _ = sol.source.system.outputs(np.array([seg.t1]), seg.y1[None, :], seg.phase.buffer)
    return {
        "bound lifted after": "never" if math.isinf(resting) else f"{resting:g} t_c",
        "rest from [s]": f"{seg.t0:.3f}",
        "rest steps": len(t),
        "steps/s": f"{len(t) / (seg.t1 - seg.t0):.0f}",
        f"steps/s from {late:g} s": f"{np.count_nonzero(t >= late) / (seg.t1 - late):.0f}",
        "run steps": run.steps,
        "wall [s]": f"{wall:.2f}",
        "F(t_end) [N]": f"{cols['contact_force'][0]:.6f}",
    }


WINDOW_POINTS = 20001
WINDOW_EDGES = (1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 15.0, 20.0, 30.0, 50.0, 100.0)


def windows(t_end: float) -> None:
    """Print the resting contact's steps per second and ringing in the windows WINDOW_EDGES up to ``t_end``."""
    case = fb.load_case("seed-experiment", {"solver.t_end": t_end, "solver.memory_limit": 2e10})
    sol = fb.simulate(case, "ccfm")
    seg = sol.source.run.segments[-1]
    t = seg.dense.records[:, 0]
    print(f"resting contact from {seg.t0:.3f} s, {len(t)} steps")
    print("| window [s] | steps/s | F mean [N] | F std (ringing) [N] |")
    print("|---|---|---|---|")
    for a, b in zip(WINDOW_EDGES[:-1], WINDOW_EDGES[1:]):
        if b > t_end or a < seg.t0:
            continue
        force = sol.source.force_many(np.linspace(a, b, WINDOW_POINTS), 0)
        steps = np.count_nonzero((t >= a) & (t < b)) / (b - a)
        print(f"| {a:g}-{b:g} | {steps:.0f} | {force.mean():.4f} | {force.std():.3g} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=3.0)
    ap.add_argument("--windows", action="store_true", help="steps/s and ringing by window, default bound only")
    args = ap.parse_args()
    if args.windows:
        windows(args.t_end)
        return
    default = base.RESTING_DURATIONS
    rows = [measure(math.inf, args.t_end), measure(default, args.t_end)]
    base.RESTING_DURATIONS = default
    keys = list(rows[0])
    print("| " + " | ".join(keys) + " |")
    print("|" + "---|" * len(keys))
    for r in rows:
        print("| " + " | ".join(str(r[k]) for k in keys) + " |")


if __name__ == "__main__":
    main()
