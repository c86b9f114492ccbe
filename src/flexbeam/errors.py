"""One family of errors for flexbeam (see DESIGN.md, *Conventions*).

* :class:`ParameterError` -- bad input; the message names the field, the bad value
  and what is allowed.  The CLI turns it into one line on stderr and exit code 2.
* :class:`ModelError` -- a request the model cannot represent (e.g. a Hertz stiffness
  for a contact whose geometry is not Hertzian).
* :class:`SolverError` -- a numerical failure; carries the time at which it happened.

Warnings: :class:`FlexbeamWarning` and its subclasses (:class:`SlenderBeamWarning`) -- accepted input that is near
the edge of the model's validity.  The CLI prints each as one line ``warning: ...`` on stderr.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable


class FlexbeamError(Exception):
    """Base class of every error raised on purpose by flexbeam."""


class ParameterError(FlexbeamError, ValueError):
    """Invalid input: the message names the field and the allowed range."""


class ModelError(FlexbeamError):
    """The model cannot represent what was asked."""


class SolverError(FlexbeamError, RuntimeError):
    """A numerical failure during integration.

    Parameters
    ----------
    message
        What went wrong.
    time
        Simulation time [s] at which it happened.
    """

    def __init__(self, message: str, time: float | None = None) -> None:
        self.time = time
        where = f" at t = {time:.6g} s" if time is not None else ""
        super().__init__(f"{message}{where}")


class FlexbeamWarning(UserWarning):
    """Base class of the warnings flexbeam emits on purpose (the CLI prints each as one line on stderr)."""


class SlenderBeamWarning(FlexbeamWarning):
    """The beam is thick enough for Euler-Bernoulli theory to be off by more than 1 % in its first bending
    frequency (:mod:`flexbeam.parameters.slenderness`)."""


def not_text(field: str, path: object, kind: str, exc: UnicodeDecodeError) -> str:
    """The one-line message for a file of ``field`` that should be ``kind`` text and is not UTF-8 (a binary file, a
    result.nc given as a case): where its first undecodable byte lies."""
    return f"{field}: '{path}' is not a {kind} file: not UTF-8 text ({exc.reason} at byte {exc.start})"


def closest(name: str, choices: Iterable[str]) -> str:
    """Return ``" (best matches: a, b)"`` for an unknown ``name``, or ``""``.

    Compared case-insensitively, as :func:`did_you_mean` (``CCFM`` finds ``ccfm``, ``Hertz`` finds ``hertz``:
    compared as typed, their similarity was 0 and no match was offered); the matches are shown as ``choices``
    spell them.
    """
    by_lower: dict[str, str] = {}
    for c in choices:
        by_lower.setdefault(c.lower(), c)
    matches = difflib.get_close_matches(name.lower(), list(by_lower), n=3, cutoff=0.5)
    return f" (best matches: {', '.join(by_lower[m] for m in matches)})" if matches else ""


def did_you_mean(name: str, choices: Iterable[str]) -> str:
    """Return ``", did you mean x?"`` with the closest of ``choices`` to ``name``, or ``""``.

    Closeness is :func:`difflib.get_close_matches` (Ratcliff-Obershelp similarity
    ``2 M / T``) with the cutoff 0.6 that difflib itself uses by default; it is compared
    case-insensitively, so ``Length`` finds ``length``.
    """
    by_lower = {c.lower(): c for c in choices}
    matches = difflib.get_close_matches(name.lower(), list(by_lower), n=1)
    return f", did you mean {by_lower[matches[0]]}?" if matches else ""
