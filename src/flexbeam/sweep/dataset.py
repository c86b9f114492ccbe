"""The result of a sweep as an :class:`xarray.Dataset`, rebuilt from a store, summarised, histories."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError
from ..parameters.io import field_units
from ..results.metrics import METRICS as REGISTRY
from ..results.metrics import SCALARS
from .planning import Plan, plain
from .store import FAILED, INCOMPLETE, Store

if TYPE_CHECKING:
    import xarray as xr

#: scalar metric -> (units, long name); every one is a variable of the result (NaN when absent): the registry's
#: scalar metrics, and the case's own elapsed time on its worker
METRICS: dict[str, tuple[str, str]] = {
    **{k: (REGISTRY[k].units, REGISTRY[k].long_name) for k in SCALARS},
    "elapsed": ("s", "Wall time of the case on its worker (set-up, integration, metrics)"),
}


def build_dataset(
    spec: dict[str, Any], plan_: Plan | None, records: dict[str, dict[str, Any]], lost: dict[str, str]
) -> xr.Dataset:
    """The Dataset of a sweep from its definition ``spec`` and the finished ``records`` by key.

    ``plan_`` gives the sampled coordinates (else ``spec["values"]``); ``lost`` the reason
    a case is missing (a lost worker) by key.
    """
    import numpy as np
    import xarray as xr

    from ..version import __version__

    keys = spec["cases"]
    if spec["kind"] == "grid":
        dims = tuple(spec["keys"])
        shape = tuple(len(spec["grid"][k]) for k in dims)
        coords: dict[str, Any] = {k: (k, _coord(spec["grid"][k]), _field_attrs(k)) for k in dims}
    else:
        dims = ("case",)
        shape = (len(keys),)
        values = plan_.coords if plan_ is not None else spec["values"]
        coords = {"case": ("case", np.arange(len(keys)), {"long_name": "Case index"})}
        coords.update({k: ("case", _coord(values[k]), _field_attrs(k)) for k in spec["keys"]})
    names = list(METRICS)
    extra = sorted(
        {
            m
            for r in records.values()
            for m, v in r.get("metrics", {}).items()
            if m not in METRICS and isinstance(v, (int, float)) and not isinstance(v, bool)
        }
    )
    arrays = {m: np.full(len(keys), np.nan) for m in names + extra}
    status = np.empty(len(keys), dtype=object)
    error = np.empty(len(keys), dtype=object)
    warning = np.full(len(keys), "", dtype=object)
    for i, key in enumerate(keys):
        rec = records.get(key)
        if rec is None:
            status[i], error[i] = "missing", lost.get(key, "not computed")
            continue
        status[i], error[i] = str(rec.get("status", "")), str(rec.get("error", "") or "")
        warning[i] = " | ".join(rec.get("warnings") or [])
        metrics = dict(rec.get("metrics", {}))
        metrics["elapsed"] = rec.get("elapsed")
        for m in arrays:
            v = metrics.get(m)
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                arrays[m][i] = float(v)
    data_vars: dict[str, Any] = {}
    for m, arr in arrays.items():
        units, long_name = METRICS.get(m, ("", m.replace("_", " ")))
        data_vars[m] = (dims, arr.reshape(shape), {"units": units, "long_name": long_name})
    data_vars["status"] = (dims, status.astype(str).reshape(shape), {"long_name": "Case status"})
    data_vars["error"] = (dims, error.astype(str).reshape(shape), {"long_name": "Error of a failed case"})
    data_vars["warning"] = (
        dims,
        warning.astype(str).reshape(shape),
        {"long_name": "Warnings of the case's run, one line each, separated by ' | ' (empty: none)"},
    )
    data_vars["case_key"] = (
        dims,
        np.asarray(keys, dtype=str).reshape(shape),
        {"long_name": "Store key of the case (cases/KEY.json)"},
    )
    n_missing = int(np.count_nonzero(status == "missing"))
    n_failed = int(sum(1 for s in status if s in FAILED))
    n_incomplete = int(sum(1 for s in status if s in INCOMPLETE))
    attrs = {
        "title": "flexbeam sweep",
        "method": spec["method"],
        "kind": spec["kind"],
        "swept": json.dumps(spec["keys"]),
        "sweep": json.dumps({k: spec[k] for k in ("grid", "samples", "n", "seed") if k in spec}),
        "base_case": spec["base_case"],
        "flexbeam_version": __version__,
        "cases": len(keys),
        "failed": n_failed,
        "incomplete": n_incomplete,
        "missing": n_missing,
    }
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def _field_attrs(key: str) -> dict[str, str]:
    """A swept case field's coordinate attributes: its dotted name and, where the case schema gives them, its units."""
    try:
        units = field_units(key)
    except ParameterError:  # (a store written by another version, whose field this one does not know)
        units = ""
    return {"long_name": key, "units": units} if units else {"long_name": key}


def _coord(values: Sequence[Any]) -> Any:
    import numpy as np

    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=float if any(isinstance(v, float) for v in values) else int)
    return np.asarray([str(v) for v in values], dtype=str)


def load(store: str | Path) -> xr.Dataset:
    """Rebuild the Dataset of the last sweep in ``store`` from its case files.

    Useful after a client was killed before it wrote ``result.nc``.
    """
    st = Store(store)
    spec = st.read_manifest()
    records = {k: r for k in spec["cases"] if (r := st.load(k)) is not None}
    return build_dataset(spec, None, records, {})


def summary(ds: xr.Dataset) -> dict[str, Any]:
    """Counts of a sweep result and its failed cases with their swept values and errors; ``incomplete`` counts the
    cases that ended before solver.t_end without failing (status ``max-contacts``: reported as complete before),
    ``warned`` those whose run warned (their variable ``warning``), ``repeated`` the rows that repeat an earlier
    row's case (random samples drawn twice: one case, computed once)."""
    import numpy as np

    names = ("cases", "computed", "reused", "failed", "missing")
    info: dict[str, Any] = {k: int(ds.attrs.get(k, 0)) for k in names}
    info["incomplete"] = int(np.isin(ds["status"].values, INCOMPLETE).sum())
    info["warned"] = int(np.count_nonzero(ds["warning"].values != "")) if "warning" in ds else 0
    info["repeated"] = int(ds["case_key"].size - np.unique(ds["case_key"].values).size)  # (samples drawn twice)
    swept = json.loads(ds.attrs["swept"])
    status = ds["status"].values
    failures = []
    for idx in zip(*np.nonzero(np.isin(status, FAILED))):
        point = dict(zip(ds["status"].dims, idx))
        params = {k: plain(ds[k].values[point[ds[k].dims[0]]]) for k in swept}
        failures.append(
            {
                "key": str(ds["case_key"].values[idx]),
                "parameters": params,
                "status": str(status[idx]),
                "error": str(ds["error"].values[idx]),
            }
        )
    info["failures"] = failures
    return info


def open_history(store: str | Path, key: str) -> xr.Dataset:
    """The full history of one case of a sweep run with ``histories=True``."""
    import xarray as xr

    path = Store(store).history_path(key)
    if not path.exists():
        raise ParameterError(f"key: no history for case '{key}' in '{store}' (run the sweep with histories)")
    with xr.open_dataset(path) as ds:
        return ds.load()
