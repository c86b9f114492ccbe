"""Progress bars on the terminal: one Rich bar on stderr, shown only on a terminal (never in a pipe, a test or CI)."""

from __future__ import annotations

import sys
import time
from typing import Any


class StderrProgress:
    """A Rich progress bar on stderr for work measured in ``unit``.

    Called as ``progress(done)`` or ``progress(done, total)``; shown on a terminal once the work has taken
    ``delay`` seconds (so that short runs print nothing), with the elapsed time.  ``unit = "s"`` shows the
    simulated time ``t = ... s`` (a run up to ``total = t_end``); any other unit a count ``done/total unit``
    (frames, cases).
    """

    def __init__(self, label: str, unit: str, total: float = 0.0, delay: float = 1.0) -> None:
        self.label, self.unit, self.total, self.delay = label, unit, total, delay
        self.start = time.perf_counter()
        self.bar: Any = None
        self.task: Any = None
        self.enabled = sys.stderr.isatty()

    def __call__(self, done: float, total: float | None = None) -> None:
        total = self.total if total is None else total
        if not self.enabled or not total:
            return
        if self.bar is None:
            if time.perf_counter() - self.start < self.delay:
                return
            from rich.console import Console
            from rich.markup import escape
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

            counter = (
                [TextColumn("t = {task.completed:.4g} s")]
                if self.unit == "s"
                else [MofNCompleteColumn(), TextColumn(self.unit)]
            )
            self.bar = Progress(
                TextColumn("{task.description}"), BarColumn(), *counter, TimeElapsedColumn(),
                console=Console(stderr=True), transient=True,
            )  # fmt: skip
            self.bar.start()
            self.task = self.bar.add_task(escape(self.label), total=total)  # a case file's name as written
        self.bar.update(self.task, completed=done)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
