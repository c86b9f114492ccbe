"""Coulomb friction under CCFM (issue 28): what a frictional run costs per step against the same frictionless run.

Runs each case with CCFM frictionless and with ``contact.friction`` in one process, ``--runs`` times each, and prints
a Markdown table: the steps, the events, the median integration time (the phase loop's wall time, without the
outputs) and its time per step, and the ratio of the frictional run's time per step to the frictionless one's (issue
28's target: at most 1.3); the same for the phase loop's thread CPU time, which a machine shared with other jobs
inflates less than the wall time.  A step costs the same with friction (the sliding bar: sustained slip); a friction
event (a stop, a stick's end) costs a restart of the collocation and the location of its time, which runs that switch
often between stick and slip pay per step (the compiled stepper takes most of them without returning to the phase
loop: ``kernels/src/friction_switch.c``).
The machine it ran on is printed below the table.

``--sweep CASE`` separates the two costs: it runs the case frictionless and at friction coefficients from 0.05 to 1
(their events per step differ) and fits the phase loop's CPU time of the frictional runs as a steps + b events, a
the cost of a frictional step without events, b the cost of an event (its location, the step retaken to it, the
next phase's start); a against the frictionless run's cost per step net of its own events at the same b is the
ratio per step that friction itself costs.

    python benchmarks/friction.py [--runs 5] [--quick] [--sweep tip-wall]
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import time

import numpy as np

import flexbeam as fb
import flexbeam.simulation as simulation

_CPU: list[float] = []  # the thread CPU time of each phase loop run since the last measure()
_run_phases = simulation.run_phases


def _timed_run_phases(*args, **kwargs):
    """simulation.run_phases, its thread CPU time appended to _CPU."""
    c0 = time.thread_time()
    try:
        return _run_phases(*args, **kwargs)
    finally:
        _CPU.append(time.thread_time() - c0)


simulation.run_phases = _timed_run_phases

#: a flexible steel bar (4 modes) sliding along its axis on two hemispherical stops, contact anywhere: sustained slip
#: with two events (the rigid bar of tests/validation/test_friction_ccfm.py, bar_on_stops)
SLIDING_BAR = {
    "name": "sliding-bar",
    "joint": {"kind": "free"},
    "model": {"modes": 4, "gravity": 9.81},
    "beam": {
        "length": 0.2,
        "density": 7870.0,
        "youngs_modulus": 200e9,
        "poisson_ratio": 0.29,
        "section": "circle",
        "radius": 0.00635,
    },
    "obstacle": {"kind": "sphere", "centre": [-0.06, 0.08365], "radius": 0.01},
    "obstacles": [{"kind": "sphere", "centre": [0.06, 0.08365], "radius": 0.01, "contact": {"position": 0.16}}],
    "contact": {
        "law": "lankarani_nikravesh",
        "position": 0.04,
        "stiffness": 1.16e10,
        "side": "below",
        "restitution": 0.5,
        "anywhere": True,
    },
    "initial": {"kind": "state", "position": [0.0, 0.1], "velocity": [0.1, 0.0], "angle": 0.0, "rate": 0.0},
    "solver": {"t_end": 0.03},
}

CASES = [
    ("sliding bar", SLIDING_BAR, {"contact.friction": 0.3}),
    ("free-bar-drop", "tests/validation/data/free-bar-drop.toml", {"contact.friction": 0.3}),
    ("two-stops", "two-stops", {"contact.friction": 0.5}),
    ("tip-wall", "tip-wall", {"contact.friction": 0.3}),
    ("seed-experiment", "seed-experiment", {"contact.friction": 0.3, "solver.t_end": 0.02}),
    ("seed-experiment (threlfall)", "seed-experiment",
     {"contact.friction": 0.3, "contact.friction_model": "threlfall", "solver.t_end": 0.02}),
]  # fmt: skip


def measure(source: str | dict, overrides: dict, runs: int) -> tuple[int, int, float, float]:
    """(steps, events, median integration wall time [s], its median thread CPU time [s]) of ``runs`` CCFM runs of the
    case."""
    walls, cpus, steps, events = [], [], 0, 0
    case = fb.load_case(source, overrides)
    for _ in range(runs):
        _CPU.clear()
        sol = fb.simulate(case, "ccfm")
        walls.append(sol.source.run.wall_time)
        cpus.append(_CPU[-1])
        steps, events = sol.source.run.steps, sol.source.run.events
    return steps, events, statistics.median(walls), statistics.median(cpus)


#: the friction coefficients of ``--sweep``
SWEEP_MU = (0.05, 0.1, 0.2, 0.3, 0.5, 0.8, 1.0)


def sweep(name: str, runs: int) -> None:
    """Print the phase loop's CPU time of case ``name`` (of CASES) frictionless and at SWEEP_MU, and the fit of the
    frictional runs' times as a steps + b events."""
    source, rough = next((src, ov) for case, src, ov in CASES if case == name)
    base = {k: v for k, v in rough.items() if not k.startswith("contact.friction")}
    print("| friction | steps | events | events per step | CPU [ms] | CPU per step [us] |")
    print("|---|---|---|---|---|---|")
    rows = []
    for mu in (0.0, *SWEEP_MU):
        steps, events, _, cpu = measure(source, {**base, "contact.friction": mu} if mu else base, runs)
        rows.append((steps, events, cpu))
        print(f"| {mu} | {steps} | {events} | {events / steps:.3f} | {1e3 * cpu:.2f} | {1e6 * cpu / steps:.2f} |")
    fit = np.array(rows[1:])
    (a, b), *_ = np.linalg.lstsq(fit[:, :2], fit[:, 2], rcond=None)
    steps0, events0, cpu0 = rows[0]
    a0 = (cpu0 - b * events0) / steps0
    print(
        f"\nfit over the frictional runs: a = {1e6 * a:.2f} us per step, b = {1e6 * b:.1f} us per event; the "
        f"frictionless run: {1e6 * a0:.2f} us per step net of its {events0} events at that b; a / a0 = {a / a0:.2f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--quick", action="store_true", help="one run of the first case")
    parser.add_argument(
        "--sweep",
        metavar="CASE",
        choices=[c[0] for c in CASES],
        help="a frictional step's and an event's cost apart, over friction coefficients",
    )
    args = parser.parse_args()
    if args.sweep:
        sweep(args.sweep, args.runs)
        return
    cases = CASES[:1] if args.quick else CASES
    runs = 1 if args.quick else args.runs
    print("| case | friction | steps | events | integration [ms] | per step [us] | ratio per step | CPU per step [us] |"
          " CPU ratio per step | events per step |")  # fmt: skip
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, source, rough in cases:
        smooth = {k: v for k, v in rough.items() if not k.startswith("contact.friction")}
        n0, e0, w0, c0 = measure(source, smooth, runs)
        n1, e1, w1, c1 = measure(source, rough, runs)
        ratio, cpu_ratio = (w1 / n1) / (w0 / n0), (c1 / n1) / (c0 / n0)
        mu = rough["contact.friction"]
        print(f"| {name} | 0 | {n0} | {e0} | {1e3 * w0:.1f} | {1e6 * w0 / n0:.1f} | | {1e6 * c0 / n0:.1f} | "
              f"| {e0 / n0:.3f} |")  # fmt: skip
        print(f"| {name} | {mu} | {n1} | {e1} | {1e3 * w1:.1f} | {1e6 * w1 / n1:.1f} | {ratio:.2f} "
              f"| {1e6 * c1 / n1:.1f} | {cpu_ratio:.2f} | {e1 / n1:.3f} |")  # fmt: skip
    machine = platform.processor() or platform.machine()
    print(f"\n{machine}, {os.cpu_count()} cores, Python {platform.python_version()}, median of {runs} run(s)")


if __name__ == "__main__":
    main()
