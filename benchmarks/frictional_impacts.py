"""Friction at simultaneous impacts (issue 28): what :func:`flexbeam.methods.frictional_lcp.solve_frictional_impact`
costs for s = 1..8 pairs, against the enumeration of all 4^s mode patterns in the same run.

The Delassus matrices W = J M^-1 J^T and approach velocities are those of a flexible steel bar (20 cm, 12.7 mm
across, free, ``--modes`` modes) landing flat at v = (v_x, -1 m/s) on s stops evenly spaced beneath it (the
flexbeam case built below, its system's rows at the start), sliding (v_x = 0.5 m/s) or nearly sticking (0.01 m/s),
with mu_s = mu_k = ``--mu``.  With 3 + modes < 2 s coordinates W is singular: no uniqueness certificate, and the
solver enumerates (the "search" column says which ran).  Prints a Markdown table of medians and whether the two
solvers' impulses agree (max abs difference over max abs impulse), and the machine and load below it.

    python benchmarks/frictional_impacts.py [--modes 16] [--mu 0.1] [--runs 5] [--max-pairs 8]
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import time

import numpy as np

import flexbeam as fb
from flexbeam.methods import frictional_lcp
from flexbeam.methods.frictional_search import certified_unique
from flexbeam.validation import bars
from flexbeam.validation.bars import start_delassus


def bar_on_stops(s: int, modes: int, mu: float, vx: float) -> fb.Case:
    """The steel bar horizontal with G at (0, 0.1 m), s stops (r = 1 cm) touching its lower surface beneath
    x = (0.05 .. 0.95) L, moving at (vx, -1 m/s), gravity on, friction mu (:mod:`flexbeam.validation.bars`)."""
    return bars.bar_on_stops(bars.evenly_beneath(s), (vx, -1.0), modes=modes, mu=mu, name="rough-bar-on-stops")


def timed(W, v, mu, runs: int, enumerate_all: bool) -> tuple[float, np.ndarray]:
    """(median seconds, impulses) of ``runs`` solutions, by the enumeration when ``enumerate_all``."""
    s = v.size // 2
    saved = frictional_lcp.ENUMERATED_PAIRS
    frictional_lcp.ENUMERATED_PAIRS = s if enumerate_all else saved
    times = []
    try:
        for _ in range(runs):
            t0 = time.perf_counter()
            P = frictional_lcp.solve_frictional_impact(W, v, np.full(s, 0.5), np.full(s, mu), np.full(s, mu))
            times.append(time.perf_counter() - t0)
    finally:
        frictional_lcp.ENUMERATED_PAIRS = saved
    return statistics.median(times), P


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--modes", type=int, default=16)
    parser.add_argument("--mu", type=float, default=0.1)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--max-pairs", type=int, default=8)
    args = parser.parse_args()
    print("| pairs | v_x [m/s] | search | solver [ms] | enumeration [ms] | speed-up | difference |")
    print("|---|---|---|---|---|---|---|")
    for s in range(1, args.max_pairs + 1):
        for vx in (0.5, 0.01):
            W, v = start_delassus(bar_on_stops(s, args.modes, args.mu, vx))
            mu = np.full(s, args.mu)
            search = s > frictional_lcp.ENUMERATED_PAIRS and certified_unique(W, mu, mu)
            t1, P1 = timed(W, v, args.mu, args.runs, False)
            t0, P0 = timed(W, v, args.mu, args.runs if s < 7 else 1, True)
            diff = float(np.max(np.abs(P1 - P0)) / np.max(np.abs(P0)))
            print(f"| {s} | {vx} | {'yes' if search else 'no'} | {1e3 * t1:.2f} | {1e3 * t0:.1f} | "
                  f"{t0 / t1:.0f}x | {diff:.1e} |")  # fmt: skip
    machine = platform.processor() or platform.machine()
    load = os.getloadavg()[0]
    print(
        f"\n{machine}, {os.cpu_count()} cores, load {load:.1f}, Python {platform.python_version()}, "
        f"{args.modes} modes, "
        f"mu = {args.mu}, median of {args.runs} run(s) (the enumeration: 1 run from 7 pairs)"
    )


if __name__ == "__main__":
    main()
