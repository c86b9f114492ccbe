"""The sweep: plan, reuse what the store holds, compute the rest on Dask, assemble the Dataset.

:func:`sweep` plans the cases (:func:`~flexbeam.sweep.planning.plan`), sorts them (:func:`_triage`: reused from
the store, invalid, or to compute), computes the rest on the cluster (:func:`~flexbeam.sweep.cluster.compute`) and
writes the Dataset (:func:`_result`) -- also after an interruption.
"""

from __future__ import annotations

import contextlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError
from ..parameters.case import Case
from ..parameters.io import load_case
from .cluster import ProgressFn, cluster_client, compute
from .dataset import build_dataset
from .planning import Plan, Point, plan
from .scheduler import check_scheduler, check_workers
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
    batch_size: int | None = None,
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
        ``None``: the process's local cluster of ``workers`` (default: all cores) single-threaded
        worker processes, started by the first sweep and reused by the next ones
        (:func:`~flexbeam.sweep.cluster.local_client`, closed at exit); a scheduler address
        (``"tcp://host:8786"``); or a :class:`dask.distributed.Client`.
    out
        Store directory (see the module docstring); ``None`` keeps nothing on disk and
        cannot resume.
    histories
        Also keep each case's full history in ``out/cases/KEY.nc``.
    overrides
        Dotted overrides applied to the base case first.
    progress
        Called as ``progress(done, total)`` after each computed case.
    batch_size
        Cases per Dask task.  ``None``: sized as the sweep goes, about half a second of
        work per task (:func:`~flexbeam.sweep.cluster.batch_size`); 1: one task per case.
        A batch's cases are stored as its results arrive.

    Returns
    -------
    xarray.Dataset
        One variable per scalar metric (see :data:`METRICS`), ``status`` (the
        solution's status, ``"error"`` when it raised, ``"invalid"`` for sampled values
        outside a field's range, ``"missing"`` when not computed), ``error`` and
        ``case_key``; attributes ``computed``, ``reused``, ``failed``, ``missing``.
    """
    from ..registry import check_method

    check_method(method)
    if batch_size is not None and (isinstance(batch_size, bool) or not isinstance(batch_size, int) or batch_size < 1):
        raise ParameterError(f"batch_size: must be an integer >= 1 (got {batch_size!r})")
    check_scheduler(scheduler)
    check_workers(scheduler, workers)
    base = load_case(case, dict(overrides) if overrides else None)
    pl = plan(base, grid, samples, n, seed, method)
    store = Store(out) if out is not None else None
    spec = {**pl.spec, "histories": bool(histories)}
    cases = _triage(pl, method, store, histories)
    lost: dict[str, str] = {}
    # the cluster first: a scheduler that cannot be reached is refused before the store is written (its manifest,
    # the invalid cases, and result.nc -- a finished sweep's was replaced by one of missing cases)
    with cluster_client(scheduler, workers) if cases.todo else contextlib.nullcontext() as client:
        if store is not None:
            store.write_manifest(spec)
            for key in cases.invalid_keys:
                store.save(cases.records[key])
        if progress is not None:
            progress(0, len(cases.todo))
        try:
            if cases.todo:
                compute(client, cases.todo, method, histories, store, cases.records, lost, progress, batch_size)
        finally:
            ds = _result(spec, pl, cases, lost, store)
    return ds


@dataclass
class _Triage:
    """A plan's distinct cases before computing: the finished records by key (reused from the store, or invalid:
    sampled values outside a field's range), the cases still to compute, and how many were reused and invalid."""

    records: dict[str, dict[str, Any]] = field(default_factory=dict)
    todo: list[Point] = field(default_factory=list)
    reused: int = 0
    invalid_keys: list[str] = field(default_factory=list)

    @property
    def invalid(self) -> int:
        return len(self.invalid_keys)


def _triage(pl: Plan, method: str, store: Store | None, histories: bool) -> _Triage:
    """Sort the distinct cases of ``pl`` (first occurrence of each key): a finished record in ``store`` is reused
    (with its history when ``histories``), an invalid case is recorded (and saved) as such, the rest is to do."""
    out = _Triage()
    seen: set[str] = set()
    for p in pl.points:
        if p.key in seen:
            continue
        seen.add(p.key)
        rec = store.load(p.key, histories) if store is not None else None
        if rec is not None:
            rec.pop("case", None)
            out.records[p.key] = rec
            out.reused += 1
        elif p.data is None:
            out.records[p.key] = _invalid_record(p, method)
            out.invalid_keys.append(p.key)
        else:
            out.todo.append(p)
    return out


def _invalid_record(p: Point, method: str) -> dict[str, Any]:
    """The finished record of a case whose values fail validation: status ``"invalid"`` with the error, no
    metrics."""
    from ..version import __version__

    return {
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


def _result(spec: dict[str, Any], pl: Plan, cases: _Triage, lost: dict[str, str], store: Store | None) -> xr.Dataset:
    """The sweep's Dataset from every record so far (missing cases: status ``"missing"``), with the counts
    ``computed`` and ``reused``; written to ``store`` as ``result.nc``."""
    ds = build_dataset(spec, pl, cases.records, lost)
    ds.attrs["computed"] = len(cases.records) - cases.reused - cases.invalid
    ds.attrs["reused"] = cases.reused
    if store is not None:
        store.write_result(ds)
    return ds
