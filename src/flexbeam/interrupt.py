"""Ctrl-C and SIGTERM recorded, to be acted on where the program can: a sweep between its batches, a run that keeps
what it computed (``flexbeam run --keep-interrupted``) at its next step boundary."""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable, Iterator
from typing import Any

#: the words a run's message gives a signal by
SIGNAL_NAMES = {signal.SIGINT: "Ctrl-C", signal.SIGTERM: "SIGTERM"}


def interrupted_message(t: float, cause: str) -> str:
    """The message of a run ended at ``t`` by ``cause`` ("Ctrl-C", "SIGTERM"; :meth:`Hit.cause`) with what it
    computed kept (the modal methods' loop and the finite-element reference's)."""
    return f"interrupted at t = {t:.9g} s ({cause}); what was computed up to there is kept"


class Hit:
    """The signal a sweep or a run was stopped by (``signum``, 0: none), raised by :meth:`deliver` where the sweep
    can act on it: SIGINT as KeyboardInterrupt, SIGTERM by the handler it replaced (the CLI's raises
    ``Terminated``)."""

    def __init__(self) -> None:
        self.signum = 0
        self.handlers: dict[int, Callable[..., Any]] = {}

    def __bool__(self) -> bool:
        return bool(self.signum)

    def cause(self) -> str:
        """The signal in a run's words ("Ctrl-C", "SIGTERM"), "" if none came: a run's ``stop``
        (:func:`flexbeam.integrate.loop.run_phases`)."""
        return SIGNAL_NAMES.get(self.signum, "")

    def deliver(self) -> None:
        handler = self.handlers.get(self.signum)
        if self.signum == signal.SIGTERM and callable(handler):
            self.signum = 0
            handler(signal.SIGTERM, None)  # (the CLI's raises; a handler that returns lets the sweep go on)
            return
        raise KeyboardInterrupt


@contextlib.contextmanager
def ctrl_c_flag(second_raises: bool = False) -> Iterator[Hit]:
    """Ctrl-C -- and SIGTERM where a Python handler takes it (the CLI's) -- recorded in a :class:`Hit` while a sweep
    collects its batches, for the loop to raise between them.  Python swallows a KeyboardInterrupt raised inside a
    finalizer (a Dask future released by the garbage collector), and the sweep would run on to its end; and an
    exception raised in the middle of a history's NetCDF write could leave xarray's file lock taken, so that the
    store's next write waited for it forever (SIGTERM with ``--histories``: the process hung).  Only in the main
    thread, and only over Python's default Ctrl-C handler.

    ``second_raises``: a second signal, once one is recorded, goes to the handler it replaced at once (Ctrl-C raises
    KeyboardInterrupt): a run that ends at its next step boundary may be inside a long compiled call or a slow
    output, and a user who presses Ctrl-C twice means it."""
    hit = Hit()
    if threading.current_thread() is threading.main_thread():
        if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            hit.handlers[signal.SIGINT] = signal.default_int_handler
        if callable(term := signal.getsignal(signal.SIGTERM)):
            hit.handlers[signal.SIGTERM] = term

    def record(signum: int, frame: Any) -> None:
        if hit.signum and second_raises:
            hit.handlers[signum](signum, frame)
        hit.signum = hit.signum or signum

    for signum in hit.handlers:
        signal.signal(signum, record)
    try:
        yield hit
    finally:
        for signum, handler in hit.handlers.items():
            signal.signal(signum, handler)


@contextlib.contextmanager
def keeping_interrupted(keep: bool) -> Iterator[Hit | None]:
    """The flag of a run that keeps what it computed when stopped (``keep``: ``--keep-interrupted``,
    ``keep_interrupted=True``), a second signal stopping at once; None (nothing recorded) otherwise.  The run's
    ``stop`` is the flag's :meth:`Hit.cause`."""
    if not keep:
        yield None
        return
    with ctrl_c_flag(second_raises=True) as hit:
        yield hit


__all__ = ["SIGNAL_NAMES", "Hit", "ctrl_c_flag", "interrupted_message", "keeping_interrupted"]
