"""Ctrl-C during a sweep, delivered where the sweep can act on it."""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator


@contextlib.contextmanager
def ctrl_c_flag() -> Iterator[list[bool]]:
    """Ctrl-C recorded in a flag (``[True]``) while a sweep collects its batches, for the loop to raise: Python
    swallows a KeyboardInterrupt raised inside a finalizer (a Dask future released by the garbage collector), and the
    sweep would run on to its end.  Only in the main thread, and only over Python's default handler."""
    hit = [False]
    own = threading.current_thread() is threading.main_thread()
    own = own and signal.getsignal(signal.SIGINT) is signal.default_int_handler
    previous = signal.signal(signal.SIGINT, lambda *_: hit.__setitem__(0, True)) if own else None
    try:
        yield hit
    finally:
        if own:
            signal.signal(signal.SIGINT, previous)


__all__ = ["ctrl_c_flag"]
