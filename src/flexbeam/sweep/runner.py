"""The sweep: plan, reuse what the store holds, compute the rest on Dask, assemble the Dataset."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError, closest
from ..parameters.case import Case
from ..parameters.io import load_case
from .cluster import ProgressFn, cluster_client, compute
from .dataset import build_dataset
from .planning import Point, plan
from .spec import Distribution
from .store import Store

if TYPE_CHECKING:
    import xarray as xr


def sweep(
    case: Case | str | Path,
    grid: Mapping[str, Sequence[Any]] | None = None,
    samples: Mapping[str, str | Distribution] | None = None,
    n: int | None = None,
    seed: int = 0,
    method: str = "ccfm",
    scheduler: Any = None,
    workers: int | None = None,
    out: str | Path | None = None,
    histories: bool = False,
    overrides: Mapping[str, Any] | None = None,
    progress: ProgressFn | None = None,
) -> xr.Dataset:
    """Run a parameter sweep on Dask and return its metrics as an :class:`xarray.Dataset`.

    Parameters
    ----------
    case
        Base case: a :class:`Case`, a built-in name or a TOML path.
    grid
        ``{"contact.restitution": [0.6, 0.8], ...}``: every combination is run; the
        result has one dimension per field, in this order.
    samples, n, seed
        ``{"contact.stiffness": "loguniform(1e9, 1e10)", ...}`` (or :class:`Distribution`):
        ``n`` random cases, dimension ``case``; the field values are coordinates along it.
    method
        Impact method of every case.
    scheduler
        ``None``: a local cluster of ``workers`` (default: all cores) single-threaded
        worker processes; a scheduler address (``"tcp://host:8786"``); or a
        :class:`dask.distributed.Client`.
    out
        Store directory (see the module docstring); ``None`` keeps nothing on disk and
        cannot resume.
    histories
        Also keep each case's full history in ``out/cases/KEY.nc``.
    overrides
        Dotted overrides applied to the base case first.
    progress
        Called as ``progress(done, total)`` after each computed case.

    Returns
    -------
    xarray.Dataset
        One variable per scalar metric (see :data:`METRICS`), ``status`` (the
        solution's status, ``"error"`` when it raised, ``"invalid"`` for sampled values
        outside a field's range, ``"missing"`` when not computed), ``error`` and
        ``case_key``; attributes ``computed``, ``reused``, ``failed``, ``missing``.
    """
    from ..registry import METHOD_NAMES
    from ..version import __version__

    if method not in METHOD_NAMES:
        raise ParameterError(
            f"method: unknown impact method '{method}'; allowed: "
            f"{', '.join(METHOD_NAMES)}{closest(method, METHOD_NAMES)}"
        )
    base = load_case(case, dict(overrides) if overrides else None)
    pl = plan(base, grid, samples, n, seed, method)
    store = Store(out) if out is not None else None
    spec = {**pl.spec, "histories": bool(histories)}
    records: dict[str, dict[str, Any]] = {}
    lost: dict[str, str] = {}
    todo: list[Point] = []
    seen: set[str] = set()
    reused = invalid = 0
    if store is not None:
        store.write_manifest(spec)
    for p in pl.points:
        if p.key in seen:
            continue
        seen.add(p.key)
        rec = store.load(p.key, histories) if store is not None else None
        if rec is not None:
            rec.pop("case", None)
            records[p.key] = rec
            reused += 1
        elif p.data is None:
            rec = {
                "key": p.key,
                "method": method,
                "status": "invalid",
                "error": p.error,
                "message": p.error,
                "metrics": {},
                "overrides": p.overrides,
                "elapsed": 0.0,
                "flexbeam_version": __version__,
            }
            if store is not None:
                store.save(rec)
            records[p.key] = rec
            invalid += 1
        else:
            todo.append(p)
    if progress is not None:
        progress(0, len(todo))
    try:
        if todo:
            with cluster_client(scheduler, workers) as client:
                compute(client, todo, method, histories, store, records, lost, progress)
    finally:
        ds = build_dataset(spec, pl, records, lost)
        ds.attrs["computed"] = len(records) - reused - invalid
        ds.attrs["reused"] = reused
        if store is not None:
            store.write_result(ds)
    return ds
