"""Planning a sweep: the list of cases, their overrides and store keys (no computation)."""

from __future__ import annotations

import hashlib
import itertools
import json
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..errors import ParameterError
from ..parameters.case import Case
from ..parameters.io import set_dotted, validate_case
from .spec import MAX_CASES, Distribution


def case_key(case: Case, method: str, without: tuple[str, ...] = ()) -> str:
    """The store key of a case run with ``method``: a hash of its validated fields.

    Name and description do not enter (renaming a case does not change its results), nor the dotted fields
    ``without`` (the key as if they were not given: a bifurcation's branch, whose points each set
    ``base.frequency``).
    """
    data = case.model_dump(mode="json", exclude_none=True)
    for dotted in without:
        *path, name = dotted.split(".")
        table = data
        for key in path:
            table = table.get(key, {})
        table.pop(name, None)
    return _hash(data, method)


def _hash(data: dict[str, Any], method: str) -> str:
    data = {k: v for k, v in data.items() if k not in ("name", "description")}
    text = json.dumps({"case": data, "method": method}, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


@dataclass
class Point:
    """One case of a sweep: its overrides, store key and validated case (or the error)."""

    overrides: dict[str, Any]
    key: str
    data: dict[str, Any] | None  # validated case as a plain dict (None when invalid)
    error: str = ""


@dataclass
class Plan:
    """A planned sweep: its definition (``sweep.json``), cases and coordinates."""

    spec: dict[str, Any]
    points: list[Point]
    coords: dict[str, list[Any]] = field(default_factory=dict)


def _rng(seed: int, key: str):
    import numpy as np

    salt = int.from_bytes(hashlib.sha256(key.encode()).digest()[:8], "little")
    return np.random.default_rng([seed, salt])


def _point(base: dict[str, Any], overrides: dict[str, Any], method: str, strict: bool) -> Point:
    data = json.loads(json.dumps(base))
    for key, value in overrides.items():
        set_dotted(data, key, value)
    try:
        case = validate_case(data)
    except ParameterError as exc:
        if strict:
            raise
        return Point(overrides, _hash(data, method), None, f"ParameterError: {exc}")
    return Point(overrides, case_key(case, method), case.model_dump(mode="json", exclude_none=True))


def plan(
    case: Case,
    grid: Mapping[str, Sequence[Any]] | None = None,
    samples: Mapping[str, str | Distribution] | None = None,
    n: int | None = None,
    seed: int = 0,
    method: str = "ccfm",
) -> Plan:
    """The list of cases of a sweep (no computation).

    Grid values that make an invalid case raise :class:`ParameterError` (they were
    typed in); invalid *sampled* values become cases with status ``"invalid"``.  Each
    field's samples come from their own stream seeded by (``seed``, field name), so
    adding a field or raising ``n`` keeps the values already drawn.
    """
    from ..parameters.io import dump_case

    if (grid is None) == (samples is None):
        raise ParameterError("sweep: give either grid (--grid) or samples (--sample), not both or neither")
    for name, given in (("grid", grid), ("samples", samples)):
        if given is not None and not isinstance(given, Mapping):
            raise ParameterError(f"{name}: a mapping of dotted field names, e.g. {{'contact.restitution': ...}} "
                                 f"(got a {type(given).__name__})")  # fmt: skip
    base = case.model_dump(mode="json", exclude_none=True)
    spec: dict[str, Any] = {"method": method, "base_case": dump_case(case)}
    points: list[Point] = []
    coords: dict[str, list[Any]] = {}
    if grid is not None:
        if not grid:
            raise ParameterError("--grid: give at least one KEY=v1,v2,...")
        for key, values in grid.items():
            if isinstance(values, (str, bytes, Mapping)) or not isinstance(values, Iterable):
                raise ParameterError(f"--grid {key}: give a list of values, e.g. [0.5, 0.6] (got {values!r})")
            values = list(values)
            if not values:
                raise ParameterError(f"--grid {key}: no values")
            if len({_same(v) for v in values}) != len(values):
                raise ParameterError(f"--grid {key}: repeated values {values}")
            coords[key] = [plain(v) for v in values]
        total = math.prod(len(v) for v in coords.values())
        if total > MAX_CASES:
            raise ParameterError(
                f"--grid: {' x '.join(str(len(v)) for v in coords.values())} = {total} cases; at most {MAX_CASES} in "
                "one sweep (split it into several stores)"
            )
        spec.update(kind="grid", keys=list(coords), grid=coords)
        for combo in itertools.product(*coords.values()):
            points.append(_point(base, dict(zip(coords, combo)), method, strict=True))
    else:
        assert samples is not None
        if not samples:
            raise ParameterError("--sample: give at least one KEY=DIST")
        if n is None or isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise ParameterError(f"n: the number of samples must be an integer >= 1 (got {n!r})")
        if n > MAX_CASES:
            raise ParameterError(
                f"n: {n} samples; allowed 1 <= n <= {MAX_CASES} in one sweep (split it into several stores)"
            )
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ParameterError(f"seed: must be an integer >= 0 (got {seed!r})")
        dists = {k: d if isinstance(d, Distribution) else Distribution.parse(str(d), k) for k, d in samples.items()}
        draws = {k: d.draw(_rng(seed, k), n) for k, d in dists.items()}
        coords = {k: v for k, v in draws.items()}
        spec.update(
            kind="samples",
            keys=list(dists),
            samples={k: str(d) for k, d in dists.items()},
            n=n,
            seed=seed,
            values=coords,
        )
        for i in range(n):
            points.append(_point(base, {k: draws[k][i] for k in dists}, method, strict=False))
        if all(p.error for p in points):  # (a sweep of nothing but "invalid" cases exited 0)
            raise ParameterError(f"--sample: every one of the {n} cases is invalid; the first: {points[0].error}")
    spec["cases"] = [p.key for p in points]
    return Plan(spec, points, coords)


def _same(value: Any) -> str:
    """What two grid values that make the same case share: a number's value (4 and 4.0: one case, two rows of the
    Dataset before), anything else its JSON text."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return repr(float(value))
    return json.dumps(value, default=str)


def plain(value: Any) -> Any:
    """A NumPy scalar as the Python value (for JSON and coordinates); other values unchanged."""
    import numpy as np

    if isinstance(value, np.generic):
        return value.item()
    return value
