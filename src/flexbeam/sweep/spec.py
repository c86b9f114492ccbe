"""What a sweep varies: value grids and the distributions random samples are drawn from."""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ..errors import ParameterError, closest
from ..parameters.io import parse_value

#: the most cases one sweep plans: its plan holds every case validated (~7 kB each, measured: 0.7 GB here) before the
#: first runs -- linspace(0.5, 0.9, 1e9) took the machine's 21 GB and was killed by the operating system
MAX_CASES = 100_000


@dataclass(frozen=True)
class Distribution:
    """A distribution to sample a case field from.

    ``uniform(a, b)``, ``normal(mu, sigma)``, ``loguniform(a, b)`` (0 < a < b) or
    ``choice(v1, v2, ...)``.
    """

    kind: str
    args: tuple[Any, ...]

    KINDS = {"uniform": 2, "normal": 2, "loguniform": 2, "choice": -1}

    @classmethod
    def parse(cls, text: str, key: str = "") -> Distribution:
        where = f"--sample {key}" if key else "distribution"
        m = re.fullmatch(r"\s*([A-Za-z_]+)\s*\((.*)\)\s*", text)
        kinds = ", ".join(f"{k}(...)" for k in cls.KINDS)
        if not m:
            raise ParameterError(f"{where}: expected NAME(ARGS), one of {kinds} (got '{text}')")
        kind, body = m.group(1).lower(), m.group(2)
        if kind not in cls.KINDS:
            raise ParameterError(f"{where}: unknown distribution '{kind}'; allowed: {kinds}{closest(kind, cls.KINDS)}")
        parts = [p.strip() for p in body.split(",")] if body.strip() else []
        if kind == "choice":
            if not parts:
                raise ParameterError(f"{where}: choice(...) needs at least one value")
            return cls(kind, tuple(parse_value(p) for p in parts))
        try:
            args = tuple(float(p) for p in parts)
        except ValueError:
            raise ParameterError(f"{where}: {kind}(...) takes numbers (got '{text}')") from None
        if len(args) != 2 or not all(math.isfinite(a) for a in args):
            raise ParameterError(f"{where}: {kind}(...) takes two finite numbers (got '{text}')")
        a, b = args
        if kind == "uniform" and not a < b:
            raise ParameterError(f"{where}: uniform(a, b) needs a < b (got '{text}')")
        if kind == "loguniform" and not 0 < a < b:
            raise ParameterError(f"{where}: loguniform(a, b) needs 0 < a < b (got '{text}')")
        if kind == "normal" and not b > 0:
            raise ParameterError(f"{where}: normal(mu, sigma) needs sigma > 0 (got '{text}')")
        return cls(kind, args)

    def draw(self, rng: Any, n: int) -> list[Any]:
        """``n`` values from ``rng`` (a :class:`numpy.random.Generator`)."""
        import numpy as np

        if self.kind == "choice":
            return [self.args[i] for i in rng.integers(len(self.args), size=n)]
        a, b = self.args
        if self.kind == "uniform":
            x = rng.uniform(a, b, n)
        elif self.kind == "normal":
            x = rng.normal(a, b, n)
        else:
            x = np.exp(rng.uniform(math.log(a), math.log(b), n))
        return [float(v) for v in x]

    def __str__(self) -> str:
        return f"{self.kind}({', '.join(repr(a) for a in self.args)})"


def parse_grid(items: Sequence[str]) -> dict[str, list[Any]]:
    """``["contact.restitution=0.6,0.8", "model.modes=linspace(2,8,4)"]`` -> dict of value lists.

    Values are comma-separated TOML values (an array's own commas, within its brackets, do not separate: a list
    field's values ``[0.585, 0.03],[0.585, 0.04]``), or ``linspace(a, b, n)`` / ``geomspace(a, b, n)``.
    """
    import numpy as np

    grid: dict[str, list[Any]] = {}
    for item in items:
        key, sep, text = item.partition("=")
        key = key.strip()
        if not sep or not key or not text.strip():
            raise ParameterError(f"--grid: expected KEY=v1,v2,... (got '{item}')")
        m = re.fullmatch(r"\s*(linspace|geomspace)\s*\((.*)\)\s*", text)
        if m:
            try:
                a, b, n = (float(p) for p in m.group(2).split(","))
            except ValueError:
                raise ParameterError(
                    f"--grid {key}: {m.group(1)}(a, b, n) takes three numbers (got '{text}')"
                ) from None
            if not (n >= 1 and n == int(n)) or (m.group(1) == "geomspace" and not a * b > 0):
                raise ParameterError(f"--grid {key}: bad {m.group(1)}(a, b, n) (got '{text}')")
            if n > MAX_CASES:
                raise ParameterError(
                    f"--grid {key}: {m.group(1)}(a, b, n) with n = {n:g}; allowed 1 <= n <= {MAX_CASES}"
                )
            space = np.linspace if m.group(1) == "linspace" else np.geomspace
            values: list[Any] = [float(v) for v in space(a, b, int(n))]
        else:
            values = [parse_value(p.strip()) for p in _top_level(text)]
        if key in grid:
            raise ParameterError(f"--grid {key}: given twice")
        grid[key] = values
    return grid


def _top_level(text: str) -> list[str]:
    """``text`` split at its commas outside brackets and quotes: ``[0.585, 0.03],[0.585, 0.04]`` is two values (a
    list field's, such as an obstacle's centre), ``"a,b",c`` two."""
    parts, depth, quote, start = [], 0, "", 0
    for i, ch in enumerate(text):
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    return [*parts, text[start:]]


def parse_samples(items: Sequence[str]) -> dict[str, Distribution]:
    """``["contact.restitution=uniform(0.5,0.9)"]`` -> ``{"contact.restitution": Distribution}``."""
    out: dict[str, Distribution] = {}
    for item in items:
        key, sep, text = item.partition("=")
        key = key.strip()
        if not sep or not key:
            raise ParameterError(
                f"--sample: expected KEY=DIST, e.g. contact.restitution=uniform(0.5,0.9) (got '{item}')"
            )
        if key in out:
            raise ParameterError(f"--sample {key}: given twice")
        out[key] = Distribution.parse(text, key)
    return out
