"""The arguments of a :class:`~flexbeam.results.solution.Solution`'s methods, checked: one ParameterError naming the
argument and what is allowed (a bare IndexError, or a silent empty answer, before)."""

from __future__ import annotations

import math
import numbers
from typing import Any

from ..errors import ParameterError


def record_index(i: Any, n: int, name: str = "contact") -> int:
    """A contact record's index ``i`` among ``n`` (a negative one counts from the end, as a list's), as an int."""
    if isinstance(i, bool) or not isinstance(i, numbers.Integral):
        raise ParameterError(f"{name}: a contact record's index, an integer (got {i!r})")
    if n == 0:
        raise ParameterError(f"{name}: this run has no contact records (got {name} = {i})")
    if not -n <= int(i) < n:
        raise ParameterError(f"{name}: {i} is not a record of this run; allowed {-n} <= {name} <= {n - 1}")
    return int(i) % n


def nonnegative(value: Any, name: str) -> float:
    """A finite number >= 0 (a fraction of the peak, ...)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not (math.isfinite(value) and value >= 0):
        raise ParameterError(f"{name}: must be a finite number >= 0 (got {value!r})")
    return float(value)


def positive_or_none(value: Any, name: str) -> float | None:
    """None, or a finite number > 0 (a duration [s], ...)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not (math.isfinite(value) and value > 0):
        raise ParameterError(f"{name}: must be a finite number > 0 [s], or None for the default (got {value!r})")
    return float(value)
