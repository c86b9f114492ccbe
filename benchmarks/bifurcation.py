"""Issue 27's bifurcation diagram: a shaker case swept over drive frequencies, up and down, with continuation.

Run: ``python benchmarks/bifurcation.py [--frequencies 100] [--periods 150] [--discard 100] [--lo 8] [--hi 30]``.

The case is ``tests/validation/data/shaker-stop.toml`` (an assumed steel cantilever on a vertically shaken base with
a stop under its tip, 6 modes, CCFM; no ``shaker-stop`` preset yet: Wagg & Bishop's numbers could not be read).  One
run of ``flexbeam.bifurcation.bifurcation`` on the default local cluster (two single-threaded workers, one branch
each), into a fresh store, then its figure; the wall time and the machine are printed (issue 27's target: 100
frequencies x 150 periods within 60 s on 2 cores), with the steps and contacts per point.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import flexbeam as fb
from flexbeam.bifurcation import bifurcation
from flexbeam.views.bifurcation import plot_bifurcation

sys.path.insert(0, str(Path(__file__).resolve().parent))
from seed import environment  # noqa: E402  (the machine and library versions, as every benchmark reports them)

SHAKER = Path(__file__).resolve().parents[1] / "tests" / "validation" / "data" / "shaker-stop.toml"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--frequencies", type=int, default=100)
    p.add_argument("--periods", type=int, default=150)
    p.add_argument("--discard", type=int, default=100)
    p.add_argument("--lo", type=float, default=8.0)
    p.add_argument("--hi", type=float, default=30.0)
    p.add_argument("--figure", type=Path, default=Path(tempfile.gettempdir()) / "bifurcation.png")
    p.add_argument("--json", action="store_true")
    args = p.parse_args(argv)
    env = environment()
    case = fb.load_case(SHAKER)
    with tempfile.TemporaryDirectory() as store:
        t0 = time.perf_counter()
        ds = bifurcation(case, args.lo, args.hi, args.frequencies, args.periods, args.discard, out=store)
        t1 = time.perf_counter()
        plot_bifurcation(ds, args.figure)
        t2 = time.perf_counter()
    status = ds["status"].values.ravel()
    impacts = np.sum(np.isfinite(ds["impact_velocity"].values), axis=-1)
    out = {
        "environment": env,
        "frequencies": args.frequencies,
        "periods": args.periods,
        "discard": args.discard,
        "points": int(status.size),
        "succeeded": int(np.sum(status == "success")),
        "diagram_s": t1 - t0,
        "figure_s": t2 - t1,
        "impacts_per_point_after_transient": float(np.mean(impacts)),
        "figure": str(args.figure),
    }
    if args.json:
        print(json.dumps(out, indent=1))
        return 0
    print(f"machine: {env['machine']}, {env['cores']} cores, python {env['python']}, load {env['load_average']:.2f}")
    print(f"{args.frequencies} frequencies x 2 branches, {args.periods} periods ({args.discard} discarded)")
    impacts = out["impacts_per_point_after_transient"]
    print(f"diagram {out['diagram_s']:.1f} s, figure {out['figure_s']:.2f} s; {out['succeeded']}/{out['points']} "
          f"points succeeded; {impacts:.0f} impacts per point after the transient")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
