"""Messages on stderr: one line each, whatever the text they quote; and how a run that was stopped says so."""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager


class Terminated(BaseException):
    """SIGTERM (``kill``, ``timeout``, a job scheduler's stop) raised as an exception, so that it cleans up what an
    interrupt does: a streamed run's temporary file (Python's default action for SIGTERM ends the process at once:
    the file was left), the stores' "the same command resumes".  Not a KeyboardInterrupt, which Typer turns into a
    silent exit 130 inside a command; like one (and SystemExit), not an Exception: no ``except Exception`` takes it."""


def interrupt_code(exc: BaseException) -> int:
    """The exit code of a run stopped by ``exc``: 143 (128 + SIGTERM) terminated, 130 (128 + SIGINT) interrupted."""
    return 128 + (signal.SIGTERM if isinstance(exc, Terminated) else signal.SIGINT)


def _terminate(signum: int, frame: object) -> None:
    raise Terminated


@contextmanager
def sigterm_as_interrupt() -> Iterator[None]:
    """Within the block, SIGTERM raises :class:`Terminated` (in the main thread, where its default action was
    left); the handler before is restored after it."""
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGTERM) != signal.SIG_DFL:
        yield
        return
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def one_line(message: object) -> str:
    """``message`` (an exception or text) on one line: a newline, e.g. in a quoted TOML key, is escaped."""
    return str(message).replace("\r", "\\r").replace("\n", "\\n")
