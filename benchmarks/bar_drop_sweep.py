"""Issue 26's restitution sweep: a free bar dropped at 90 inclinations, and the restitution-against-angle figure.

Run: ``python benchmarks/bar_drop_sweep.py [--angles 90] [--runs 3] [--figure out.png] [--json]``.

The case is ``tests/validation/data/free-bar-drop.toml`` as it stands (8 free-free modes, CCFM, elastic Hertz on the
hemispherical end cap, 1.4 m/s, its own t_end 0.01 s; the assumed bar, no ``bar-drop`` preset yet: see
docs/free-beam.md), the inclination ``initial.impact_angle`` on a grid from 1 to 89 degrees.  Each run is, from a
cold start of the sweep machinery, what a user's command does: ``flexbeam.sweep`` on the default local Dask cluster
(one single-threaded worker per core, started by the sweep), into a fresh store, then the figure of the apparent
restitution (Newton's, Poisson's, Stronge's) and the contacts of the first episode against the angle, written as a
PNG.  The median wall time of the runs is reported with the machine (issue 26's target: at most 30 s on 2 cores).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

import flexbeam as fb

sys.path.insert(0, str(Path(__file__).resolve().parent))
from seed import environment  # noqa: E402  (the machine and library versions, as every benchmark reports them)

BAR_DROP = Path(__file__).resolve().parents[1] / "tests" / "validation" / "data" / "free-bar-drop.toml"


def figure(result, path: Path) -> None:
    """The apparent restitution and the first episode's contacts against the inclination, as a PNG at ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    degrees = np.degrees(result["initial.impact_angle"].values)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True, height_ratios=(2, 1), layout="constrained")
    for name, style, label in (("restitution_newton", "o-", "Newton"), ("restitution_poisson", "x", "Poisson"),
                               ("restitution_energetic", "+", "Stronge")):  # fmt: skip
        top.plot(degrees, result[name].values, style, ms=4, label=label)
    top.set(ylabel="apparent restitution", title="free-bar-drop: 8 modes, elastic Hertz, CCFM")
    top.legend(fontsize="small")
    bottom.plot(degrees, result["episode_contacts"].values, "o-", ms=3)
    bottom.set(xlabel="inclination [deg]", ylabel="contacts in\nthe first episode")
    fig.savefig(path, dpi=100)
    plt.close(fig)


def one_run(angles: np.ndarray, png: Path) -> dict[str, Any]:
    """Wall times [s] of one sweep (its local cluster started and closed by it) and of its figure."""
    grid = {"initial.impact_angle": [float(a) for a in angles]}
    with tempfile.TemporaryDirectory() as store:
        t0 = time.perf_counter()
        result = fb.sweep(str(BAR_DROP), grid=grid, out=store)
        t1 = time.perf_counter()
        figure(result, png)
        t2 = time.perf_counter()
    _close()
    e = result["restitution_newton"].values
    return {
        "sweep": t1 - t0,
        "figure": t2 - t1,
        "total": t2 - t0,
        "cases": int(angles.size),
        "failed": int(np.sum(~np.isfinite(e))),
        "e_min": float(np.nanmin(e)),
        "e_max": float(np.nanmax(e)),
    }


def _close() -> None:
    """Close the process's local cluster, so that every run pays its start-up as a user's command does."""
    from flexbeam.sweep import close_local_cluster

    close_local_cluster()


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--angles", type=int, default=90)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--figure", type=Path, default=Path(tempfile.gettempdir()) / "bar_drop_restitution.png")
    p.add_argument("--json", action="store_true")
    args = p.parse_args(argv)
    env = environment()
    angles = np.radians(np.linspace(1.0, 89.0, args.angles))
    runs = [one_run(angles, args.figure) for _ in range(args.runs)]
    med = {k: statistics.median(r[k] for r in runs) for k in ("sweep", "figure", "total")}
    out = {"environment": env, "runs": runs, "median": med, "figure": str(args.figure)}
    if args.json:
        print(json.dumps(out, indent=1))
        return 0
    print(f"machine: {env['machine']}, {env['cores']} cores, python {env['python']}, load {env['load_average']:.2f}")
    print(f"{args.angles} angles, {args.runs} runs; figure {args.figure}\n")
    print("| run | sweep [s] | figure [s] | total [s] | failed | e_N range |")
    print("|---|---|---|---|---|---|")
    for i, r in enumerate(runs):
        print(f"| {i + 1} | {r['sweep']:.2f} | {r['figure']:.2f} | {r['total']:.2f} | {r['failed']} | "
              f"{r['e_min']:.3f}-{r['e_max']:.3f} |")  # fmt: skip
    print(f"| median | {med['sweep']:.2f} | {med['figure']:.2f} | {med['total']:.2f} | | |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
