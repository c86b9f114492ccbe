"""Seed experiment, first contact: peak force and duration versus modes and FE elements.

Run: ``python benchmarks/mode_convergence.py`` (prints a Markdown table).
"""

from __future__ import annotations

import platform

import flexbeam as fb


def main() -> None:
    print(f"machine: {platform.machine()} {platform.processor() or ''}, python {platform.python_version()}\n")
    print("| model | peak force [N] | duration [ms] | second peak [N] |")
    print("|---|---|---|---|")
    for n in (2, 4, 6, 8, 12, 16, 24, 32):
        m = fb.simulate("seed-experiment", model__modes=n, solver__t_end=1e-3).metrics()
        print(
            f"| {n} modes | {m['peak_force']:.2f} | {m['contact_duration'] * 1e3:.5f} | {m['second_peak_force']:.1f} |"
        )
    for e in (8, 16, 32, 64):
        m = fb.simulate("seed-experiment", method="fem", fem__elements=e, solver__t_end=1e-3).metrics()
        print(
            f"| FEM {e} elements | {m['peak_force']:.2f} | {m['contact_duration'] * 1e3:.5f} | "
            f"{m['second_peak_force']:.1f} |"
        )


if __name__ == "__main__":
    main()
