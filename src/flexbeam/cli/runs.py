"""Loading a case and running it from the command line: the case with its ``--set`` overrides, the progress bar
of a run, and exit code 1 for a run that ended before ``solver.t_end``."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from ..progress import StderrProgress
from .messages import one_line


def load(case: str, sets: list[str] | None):
    """The case ``case`` (a built-in name or a TOML file) with the ``KEY=VALUE`` overrides ``sets``."""
    from ..parameters.io import load_case, parse_overrides

    return load_case(case, parse_overrides(sets or []))


def run_progress(t_end: float, label: str) -> StderrProgress:
    """A run's progress bar: the simulated time, shown for runs longer than ~1 s on a terminal."""
    return StderrProgress(label, "s", total=t_end)


def simulate(case, method: str, outputs: bool = False, stream: Path | None = None, stop=None):
    """Run a case (``outputs``: its output samples will be written or drawn, so the memory estimate counts them;
    ``stream``: the result file it writes as it goes; ``stop``: what may end it early, keeping what was computed)."""
    from ..simulation import simulate
    from ..threads import single_threaded_blas

    progress = run_progress(case.solver.t_end, f"{case.name} [{method}]")
    try:
        with single_threaded_blas():  # small linear algebra: a BLAS thread pool only adds threads
            return simulate(case, method, progress=progress, outputs=outputs, stream=stream, stop=stop)
    finally:
        progress.close()


def exit_unless_complete(solutions: list[Any], signum: int = 0) -> None:
    """Exit with code 1 unless every run reached ``solver.t_end`` (status "success").

    A run that stops early -- a numerical failure ("failed") or the Zeno guard
    ``solver.max_contacts`` ("max-contacts") -- still prints its metrics (computed over
    what was integrated), but a script must not take them for a complete run: one line
    per such run on stderr and exit code 1.  A run that the signal ``signum`` ended, keeping
    what it computed (status "interrupted", ``--keep-interrupted``), exits as an interrupted
    command does: 128 + signum (130 Ctrl-C, 143 SIGTERM).
    """
    stopped = [s for s in solutions if s.status != "success"]
    for s in stopped:
        sys.stderr.write(one_line(f"{s.method}: run ended early with status '{s.status}': {s.message}") + "\n")
    if stopped:
        sys.exit(128 + signum if signum and any(s.status == "interrupted" for s in stopped) else 1)
