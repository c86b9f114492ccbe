"""Measurements a calibration fits: histories read from CSV files and named summary features."""

from __future__ import annotations

import csv
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import ParameterError, closest, not_text
from ..parameters.io import parse_value

if TYPE_CHECKING:
    import numpy as np

#: CSV column roles and the column names tried when ``columns`` does not name them
ROLES = {
    "time": ("time", "t"),
    "force": ("force", "contact_force", "F"),
    "velocity": ("velocity", "normal_velocity", "v"),
}


@dataclass
class Measured:
    """Measured histories: time [s], contact force [N] and/or normal velocity [m/s].  Checked as built (from a file
    by :func:`read_measured` or in Python): arrays of finite numbers of the time's length, a force or a velocity,
    the time increasing strictly -- one-line :class:`~flexbeam.errors.ParameterError` naming ``data``."""

    time: np.ndarray
    force: np.ndarray | None = None
    velocity: np.ndarray | None = None
    source: str = ""

    def __post_init__(self) -> None:
        import numpy as np

        where = f" of '{self.source}'" if self.source else ""
        for name in ("time", "force", "velocity"):
            value = getattr(self, name)
            if value is None:
                continue
            try:
                arr = np.array(value, dtype=float)
            except (TypeError, ValueError):
                raise ParameterError(f"data: the {name}{where} must be an array of numbers") from None
            if arr.ndim != 1 or (name != "time" and arr.size != self.time.size):
                raise ParameterError(f"data: the {name}{where} has {arr.size} values, the time {self.time.size}")
            if not np.all(np.isfinite(arr)):
                raise ParameterError(f"data: the {name}{where} holds a value that is no finite number")
            setattr(self, name, arr)
        if self.force is None and self.velocity is None:
            raise ParameterError(f"data: a measurement{where} needs a force or a velocity history")
        if self.time.size < 2 or np.any(np.diff(self.time) <= 0):
            raise ParameterError(f"data: the time{where} must increase strictly (at least two samples)")

    @property
    def channels(self) -> list[str]:
        return [c for c in ("force", "velocity") if getattr(self, c) is not None]

    def scale(self, channel: str) -> float:
        """Largest measured magnitude of ``channel`` (1 for an all-zero channel): the residuals' unit."""
        import numpy as np

        return float(np.max(np.abs(getattr(self, channel)))) or 1.0


def parse_columns(text: str | None) -> dict[str, str]:
    """``"time=t,force=F"`` -> ``{"time": "t", "force": "F"}`` (roles: time, force, velocity)."""
    out: dict[str, str] = {}
    for item in (text or "").split(","):
        if not item.strip():
            continue
        role, sep, name = item.partition("=")
        role = role.strip()
        if not sep or not name.strip():
            raise ParameterError(f"--columns: expected ROLE=COLUMN,... (got '{item}')")
        if role not in ROLES:
            raise ParameterError(f"--columns: unknown role '{role}'; allowed: {', '.join(ROLES)}{closest(role, ROLES)}")
        if role in out:  # (the last one won: a second force=... fitted the velocity as a force)
            raise ParameterError(f"--columns: the role {role} is given twice ('{out[role]}', '{name.strip()}')")
        if name.strip() in out.values():
            other = next(r for r, n in out.items() if n == name.strip())
            raise ParameterError(f"--columns: the column '{name.strip()}' is given for both {other} and {role}")
        out[role] = name.strip()
    return out


def parse_features(text: str | None) -> dict[str, float]:
    """``"peak_force=584,contact_duration=0.6e-3"`` -> dict of measured values."""
    out: dict[str, float] = {}
    for item in (text or "").split(","):
        if not item.strip():
            continue
        name, sep, value = item.partition("=")
        name = name.strip()
        v = parse_value(value.strip()) if sep else None
        if not sep or isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ParameterError(f"--features: expected NAME=NUMBER,... (got '{item}')")
        if name in out:  # (the last value won, silently)
            raise ParameterError(f"--features: {name} is given twice ({out[name]:g}, {float(v):g})")
        out[name] = float(v)
    return out


def read_measured(path: str | Path, columns: Mapping[str, str] | None = None) -> Measured:
    """Read a CSV file with a header row (``#`` lines are comments) into :class:`Measured`.

    ``columns`` maps roles (time, force, velocity) to column names; a role it does not
    name is looked up under the names in :data:`ROLES`, except that naming force or
    velocity selects just the channels named.
    """
    import numpy as np

    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as f:  # (a spreadsheet's byte-order mark: not a name)
            rows = [r for r in csv.reader(line for line in f if not line.lstrip().startswith("#")) if r]
    except OSError as exc:
        raise ParameterError(f"data: cannot read '{path}': {exc.strerror}") from None
    except UnicodeDecodeError as exc:
        raise ParameterError(not_text("data", path, "CSV", exc)) from None
    if len(rows) < 3:
        raise ParameterError(f"data: '{path}' needs a header row and at least two data rows")
    header = [h.strip() for h in rows[0]]
    columns = dict(columns or {})
    named_channels = {"force", "velocity"} & set(columns)
    chosen: dict[str, int] = {}
    for role, candidates in ROLES.items():
        if named_channels and role != "time" and role not in named_channels:
            continue  # --columns names the channels to fit: only those
        if role in columns:
            name = columns[role]
            if name not in header:
                raise ParameterError(
                    f"--columns {role}: no column '{name}' in '{path}'; columns: "
                    f"{', '.join(header)}{closest(name, header)}"
                )
            chosen[role] = header.index(name)
        else:
            for name in candidates:
                if name in header:
                    chosen[role] = header.index(name)
                    break
    if "time" not in chosen:
        raise ParameterError(
            f"data: no time column in '{path}' (columns: {', '.join(header)}); name it with --columns time=NAME"
        )
    if "force" not in chosen and "velocity" not in chosen:
        raise ParameterError(
            f"data: no force or velocity column in '{path}' (columns: {', '.join(header)}); "
            "name them with --columns force=NAME,velocity=NAME"
        )
    values: dict[str, np.ndarray] = {}
    for role, j in chosen.items():
        col = []
        for i, row in enumerate(rows[1:], 2):
            try:
                col.append(float(row[j]))
            except (ValueError, IndexError):
                raise ParameterError(f"data: '{path}' row {i}, column '{header[j]}': not a number") from None
        values[role] = np.asarray(col)
    ok = np.all([np.isfinite(v) for v in values.values()], axis=0)
    t = values["time"][ok]
    if t.size < 2:  # (a column of NaN emptied every row: the time's order was blamed)
        names = ", ".join(f"'{header[j]}'" for j in chosen.values())
        raise ParameterError(f"data: fewer than two rows of '{path}' have a finite number in each of {names}")
    return Measured(
        t,
        values["force"][ok] if "force" in values else None,
        values["velocity"][ok] if "velocity" in values else None,
        str(path),
    )
