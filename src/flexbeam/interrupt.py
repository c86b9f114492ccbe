"""Ctrl-C and SIGTERM during a sweep, delivered where the sweep can act on them."""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable, Iterator
from typing import Any


class Hit:
    """The signal a sweep was stopped by (``signum``, 0: none), raised by :meth:`deliver` where the sweep can act on
    it: SIGINT as KeyboardInterrupt, SIGTERM by the handler it replaced (the CLI's raises ``Terminated``)."""

    def __init__(self) -> None:
        self.signum = 0
        self.handlers: dict[int, Callable[..., Any]] = {}

    def __bool__(self) -> bool:
        return bool(self.signum)

    def deliver(self) -> None:
        handler = self.handlers.get(self.signum)
        if self.signum == signal.SIGTERM and callable(handler):
            self.signum = 0
            handler(signal.SIGTERM, None)  # (the CLI's raises; a handler that returns lets the sweep go on)
            return
        raise KeyboardInterrupt


@contextlib.contextmanager
def ctrl_c_flag() -> Iterator[Hit]:
    """Ctrl-C -- and SIGTERM where a Python handler takes it (the CLI's) -- recorded in a :class:`Hit` while a sweep
    collects its batches, for the loop to raise between them.  Python swallows a KeyboardInterrupt raised inside a
    finalizer (a Dask future released by the garbage collector), and the sweep would run on to its end; and an
    exception raised in the middle of a history's NetCDF write could leave xarray's file lock taken, so that the
    store's next write waited for it forever (SIGTERM with ``--histories``: the process hung).  Only in the main
    thread, and only over Python's default Ctrl-C handler."""
    hit = Hit()
    if threading.current_thread() is threading.main_thread():
        if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            hit.handlers[signal.SIGINT] = signal.default_int_handler
        if callable(term := signal.getsignal(signal.SIGTERM)):
            hit.handlers[signal.SIGTERM] = term
    for signum in hit.handlers:
        signal.signal(signum, lambda s, _frame: setattr(hit, "signum", hit.signum or s))
    try:
        yield hit
    finally:
        for signum, handler in hit.handlers.items():
            signal.signal(signum, handler)


__all__ = ["Hit", "ctrl_c_flag"]
