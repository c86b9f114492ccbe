"""A sweep's run-time warnings, case by case.

A worker records the warnings of each case's run with the case's record (``warnings``: one line each, distinct); the
client says them as one :class:`~flexbeam.errors.FlexbeamWarning` each naming the case -- those of the first
:data:`SAID` cases that warned, then how many more did -- and the result keeps every case's in its ``warning``
variable (:func:`flexbeam.sweep.dataset.build_dataset`).  A worker process printed them raw before, in Python's
two-line format, once per case: a thousand cases, two thousand lines.  The warnings of a case's validation are the
planning's, which the client says once (:func:`validating`).  Taken aside only where that is safe
(:func:`exclusive`): elsewhere they go to Python's warning machinery, as any warning does.
"""

from __future__ import annotations

import contextlib
import os
import warnings
from collections.abc import Iterator
from typing import Any

from ..errors import FlexbeamWarning

#: the cases whose warnings the client says one by one; the rest are counted
SAID = 10


def exclusive(client_pid: int | None) -> bool:
    """May a case's warnings be taken aside here?  ``warnings.catch_warnings`` changes the whole process's filters,
    not one thread's: on a worker of one thread in a process other than the client's (the local cluster's), yes; in
    the client's own process (``Client(processes=False)``: its warnings are said there anyway) or beside other
    threads running cases, no."""
    if client_pid is None or os.getpid() == client_pid:
        return False
    try:
        from distributed import get_worker

        return get_worker().state.nthreads == 1
    except (ImportError, ValueError, AttributeError):  # (not on a Dask worker)
        return False


@contextlib.contextmanager
def validating(aside: bool = True) -> Iterator[None]:
    """A case validated again on its worker: its warnings were the planning's (said once, on the client)."""
    if not aside:
        yield
        return
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexbeamWarning)
        yield


@contextlib.contextmanager
def recorded(record: dict[str, Any], aside: bool = True) -> Iterator[None]:
    """Record the warnings raised inside in ``record["warnings"]`` (also when it raises), none printed; nothing
    when not ``aside``."""
    if not aside:
        yield
        return
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield
        finally:
            record["warnings"] = lines(caught)


def lines(caught: list[warnings.WarningMessage]) -> list[str]:
    """The distinct warnings of ``caught``, one line each (a warning that is not flexbeam's named by its class)."""
    out: list[str] = []
    for w in caught:
        text = " ".join(str(w.message).split())
        if not issubclass(w.category, FlexbeamWarning):
            text = f"{w.category.__name__}: {text}"
        if text not in out:
            out.append(text)
    return out


class Teller:
    """The client's side: each case's warnings said as they arrive (:meth:`say`), then the count of the cases
    beyond :data:`SAID` (:meth:`close`)."""

    def __init__(self) -> None:
        self.cases = 0

    def say(self, key: str, record: dict[str, Any]) -> None:
        messages = record.get("warnings") or []
        if not messages:
            return
        self.cases += 1
        if self.cases <= SAID:
            for text in messages:
                warnings.warn(f"case {key}: {text}", FlexbeamWarning, stacklevel=2)

    def close(self) -> None:
        if self.cases > SAID:
            more = self.cases - SAID
            warnings.warn(
                f"{more} more case{'s' if more > 1 else ''} warned: the result's variable 'warning' holds every "
                "case's warnings",
                FlexbeamWarning,
                stacklevel=2,
            )
