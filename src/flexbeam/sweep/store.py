"""The resumable on-disk store of a sweep: one JSON record (and NetCDF history) per finished case.

See :mod:`flexbeam.sweep` for the layout and why each file is written atomically.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError
from ..results.files import check_output_dir

if TYPE_CHECKING:
    import xarray as xr

#: statuses that count as a failed case
FAILED = ("failed", "error", "invalid")
#: statuses of a case that ran but ended before solver.t_end without failing (the Zeno guard, solver.max_contacts):
#: its metrics cover the run up to there
INCOMPLETE = ("max-contacts",)


#: the files and the directory a store holds (what must not be in their way: check_output_dir)
STORE_FILES, STORE_DIRS = ("result.nc", "sweep.json"), ("cases",)


class Store:
    """The on-disk store of a sweep (see the module docstring for the layout)."""

    def __init__(self, path: str | Path) -> None:
        self.path = check_output_dir(path, "out", files=STORE_FILES, dirs=STORE_DIRS)
        self.cases = self.path / "cases"

    def record_path(self, key: str) -> Path:
        return self.cases / f"{key}.json"

    def history_path(self, key: str) -> Path:
        return self.cases / f"{key}.nc"

    def load(self, key: str, need_history: bool = False) -> dict[str, Any] | None:
        """The finished record of ``key``, or None (also when its history is needed and absent)."""
        path = self.record_path(key)
        try:
            record = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        if not isinstance(record, dict) or "status" not in record or "metrics" not in record:
            return None
        if need_history and record.get("status") not in FAILED and not self.history_path(key).exists():
            return None
        return record

    def save(self, record: dict[str, Any], history: Any = None) -> None:
        """History first, then the record: the record's presence marks the case finished."""
        from ..results.export import write_dataset
        from ..results.files import jsonable, write_text_atomic

        key = record["key"]
        if history is not None:  # stored as result.nc is (compressed in chunks, atomically)
            write_dataset(history, self.history_path(key))
        write_text_atomic(self.record_path(key), json.dumps(jsonable(record), indent=1, sort_keys=True))

    def write_manifest(self, spec: dict[str, Any]) -> None:
        from ..results.files import jsonable, write_text_atomic

        write_text_atomic(self.path / "sweep.json", json.dumps(jsonable(spec), indent=1))

    def read_manifest(self) -> dict[str, Any]:
        try:
            return json.loads((self.path / "sweep.json").read_text(encoding="utf-8"))
        except (OSError, ValueError):
            raise ParameterError(f"store: no sweep in '{self.path}' (sweep.json missing or unreadable)") from None

    def write_result(self, ds: xr.Dataset) -> Path:
        from ..results.files import atomic_path

        path = self.path / "result.nc"
        with atomic_path(path) as tmp:
            ds.to_netcdf(tmp)
        return path
