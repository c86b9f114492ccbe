"""Parameter sweeps on Dask with a resumable on-disk store.

A sweep runs one case many times with some of its fields changed -- on a grid (the
product of the given values) or at random samples drawn from distributions -- and
collects the scalar metrics of every run in an :class:`xarray.Dataset` with one
dimension per swept field (grid) or a ``case`` dimension (samples)::

    ds = fb.sweep("seed-experiment", grid={"contact.restitution": [0.6, 0.8],
                                           "contact.stiffness": [1e9, 2e9, 4e9]}, out="sweep")
    ds["peak_force"].sel({"contact.restitution": 0.8})

The cases run on a :mod:`dask.distributed` cluster: a ``LocalCluster`` with one
single-threaded worker process per core unless a scheduler address (or a
``Client``) is given.

The store
---------
A directory, not a Zarr array, because each finished case must reach the disk on its
own and completely or not at all, from whichever process sees it finish::

    STORE/sweep.json       the last sweep's definition (base case, method, swept fields,
                           the case keys in order)
    STORE/cases/KEY.json   one finished case: its overrides, full case, status, error,
                           every metric, worker and timing
    STORE/cases/KEY.nc     its full history (``histories=True``)
    STORE/result.nc        the consolidated Dataset, rewritten at the end of every run
                           (also after an interruption; missing cases have status "missing")

``KEY`` is a hash of the validated case (without its name and description) and the
impact method, so a case is recognised whatever sweep it came from.  Each file is
written to a temporary name and renamed (atomic on POSIX): a case is finished if and
only if its JSON exists, and its history is written before it.  The client writes
the files as the results arrive, so a remote cluster needs no shared file system,
and an interrupted client (Ctrl-C) or a killed worker loses only the cases that were
still running.  Running the same sweep again computes only the cases whose JSON is
missing.  A case whose simulation raises or ends with ``status == "failed"`` is a
finished case: it is recorded with its error and is not retried.  A case lost with
its worker (``KilledWorker`` after Dask's retries) is not recorded and is computed
by the next run.

Library imports stay light here: Dask and xarray are imported when a sweep runs.  The
local cluster starts its workers as new processes that import the calling script
again, so a script that sweeps on it needs the usual ``if __name__ == "__main__":``
guard (the ``flexbeam sweep`` command has it).
"""

from __future__ import annotations

import contextlib
import hashlib
import itertools
import json
import math
import os
import re
import time
import uuid
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .errors import ParameterError, closest
from .parameters.case import Case
from .parameters.io import load_case, parse_value, set_dotted, validate_case

if TYPE_CHECKING:
    import xarray as xr

#: scalar metric -> (units, long name); every one is a variable of the result (NaN when absent)
METRICS: dict[str, tuple[str, str]] = {
    "peak_force": ("N", "Peak force of the first contact"),
    "peak_time": ("s", "Time of the peak force after the first onset"),
    "contact_duration": ("s", "Duration of the first contact"),
    "second_peak_force": ("N", "Second-largest force peak of the first contact"),
    "contacts": ("1", "Number of contacts"),
    "impact_velocity": ("m/s", "Normal velocity of P before the first contact"),
    "post_impact_velocity": ("m/s", "Normal velocity of P at the end of the first contact"),
    "impulse": ("N s", "Impulse of the first contact"),
    "energy_before": ("J", "Mechanical energy before the first contact"),
    "energy_after": ("J", "Mechanical energy after the first contact"),
    "energy_drift": ("1", "Relative change of the total energy at the end"),
    "energy_drift_max": ("1", "Largest relative change of the total energy"),
    "tip_deflection_min": ("m", "Smallest tip deflection"),
    "tip_deflection_max": ("m", "Largest tip deflection"),
    "wall_time": ("s", "Integration wall time"),
    "steps": ("1", "Integrator steps"),
    "nfev": ("1", "Right-hand side evaluations"),
    "elapsed": ("s", "Wall time of the case on its worker (set-up, integration, metrics)"),
}

#: statuses that count as a failed case
FAILED = ("failed", "error", "invalid")

ProgressFn = Callable[[int, int], None]


# --------------------------------------------------------------------- sweep spec
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

    Values are comma-separated TOML values, or ``linspace(a, b, n)`` / ``geomspace(a, b, n)``.
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
            space = np.linspace if m.group(1) == "linspace" else np.geomspace
            values: list[Any] = [float(v) for v in space(a, b, int(n))]
        else:
            values = [parse_value(p.strip()) for p in text.split(",")]
        if key in grid:
            raise ParameterError(f"--grid {key}: given twice")
        grid[key] = values
    return grid


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


def case_key(case: Case, method: str) -> str:
    """The store key of a case run with ``method``: a hash of its validated fields.

    Name and description do not enter (renaming a case does not change its results).
    """
    data = case.model_dump(mode="json", exclude_none=True)
    return _hash(data, method)


def _hash(data: dict[str, Any], method: str) -> str:
    data = {k: v for k, v in data.items() if k not in ("name", "description")}
    text = json.dumps({"case": data, "method": method}, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


@dataclass
class _Point:
    overrides: dict[str, Any]
    key: str
    data: dict[str, Any] | None  # validated case as a plain dict (None when invalid)
    error: str = ""


@dataclass
class _Plan:
    spec: dict[str, Any]
    points: list[_Point]
    coords: dict[str, list[Any]] = field(default_factory=dict)


def _rng(seed: int, key: str):
    import numpy as np

    salt = int.from_bytes(hashlib.sha256(key.encode()).digest()[:8], "little")
    return np.random.default_rng([seed, salt])


def _point(base: dict[str, Any], overrides: dict[str, Any], method: str, strict: bool) -> _Point:
    data = json.loads(json.dumps(base))
    for key, value in overrides.items():
        set_dotted(data, key, value)
    try:
        case = validate_case(data)
    except ParameterError as exc:
        if strict:
            raise
        return _Point(overrides, _hash(data, method), None, f"ParameterError: {exc}")
    return _Point(overrides, case_key(case, method), case.model_dump(mode="json", exclude_none=True))


def plan(
    case: Case,
    grid: Mapping[str, Sequence[Any]] | None = None,
    samples: Mapping[str, str | Distribution] | None = None,
    n: int | None = None,
    seed: int = 0,
    method: str = "ccfm",
) -> _Plan:
    """The list of cases of a sweep (no computation).

    Grid values that make an invalid case raise :class:`ParameterError` (they were
    typed in); invalid *sampled* values become cases with status ``"invalid"``.  Each
    field's samples come from their own stream seeded by (``seed``, field name), so
    adding a field or raising ``n`` keeps the values already drawn.
    """
    from .parameters.io import dump_case

    if (grid is None) == (samples is None):
        raise ParameterError("sweep: give either grid (--grid) or samples (--sample), not both or neither")
    base = case.model_dump(mode="json", exclude_none=True)
    spec: dict[str, Any] = {"method": method, "base_case": dump_case(case)}
    points: list[_Point] = []
    coords: dict[str, list[Any]] = {}
    if grid is not None:
        if not grid:
            raise ParameterError("--grid: give at least one KEY=v1,v2,...")
        for key, values in grid.items():
            values = list(values)
            if not values:
                raise ParameterError(f"--grid {key}: no values")
            if len({json.dumps(v, default=str) for v in values}) != len(values):
                raise ParameterError(f"--grid {key}: repeated values {values}")
            coords[key] = [_plain(v) for v in values]
        spec.update(kind="grid", keys=list(coords), grid=coords)
        for combo in itertools.product(*coords.values()):
            points.append(_point(base, dict(zip(coords, combo)), method, strict=True))
    else:
        assert samples is not None
        if not samples:
            raise ParameterError("--sample: give at least one KEY=DIST")
        if n is None or isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise ParameterError(f"n: the number of samples must be an integer >= 1 (got {n!r})")
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ParameterError(f"seed: must be an integer >= 0 (got {seed!r})")
        dists = {k: d if isinstance(d, Distribution) else Distribution.parse(str(d), k) for k, d in samples.items()}
        draws = {k: d.draw(_rng(seed, k), n) for k, d in dists.items()}
        coords = {k: v for k, v in draws.items()}
        spec.update(kind="samples", keys=list(dists), samples={k: str(d) for k, d in dists.items()}, n=n, seed=seed,
                    values=coords)
        for i in range(n):
            points.append(_point(base, {k: draws[k][i] for k in dists}, method, strict=False))
    spec["cases"] = [p.key for p in points]
    return _Plan(spec, points, coords)


def _plain(value: Any) -> Any:
    import numpy as np

    if isinstance(value, np.generic):
        return value.item()
    return value


# ----------------------------------------------------------------------- one case
def run_case(data: dict[str, Any], method: str, histories: bool = False) -> tuple[dict[str, Any], Any]:
    """Run one case on a worker: ``(record, history Dataset or None)``.

    Every exception is caught and recorded (status ``"error"``): a failing case does
    not stop the sweep.
    """
    import socket

    from . import __version__

    t0 = time.perf_counter()
    record: dict[str, Any] = {"method": method, "status": "error", "error": "", "message": "", "metrics": {},
                              "worker": f"{socket.gethostname()}:{os.getpid()}", "flexbeam_version": __version__}
    history = None
    try:
        from .simulation import simulate

        sol = simulate(validate_case(data), method)
        metrics = sol.metrics()
        for name in ("method", "status", "message"):
            metrics.pop(name, None)
        record.update(status=sol.status, message=sol.message, metrics=metrics,
                      error=sol.message if sol.status == "failed" else "")
        if histories:
            history = sol.to_xarray()
    except Exception as exc:  # noqa: BLE001 - recorded, the sweep goes on
        record["error"] = f"{type(exc).__name__}: {exc}"
        record["message"] = record["error"]
    record["elapsed"] = time.perf_counter() - t0
    return record, history


# -------------------------------------------------------------------------- store
class Store:
    """The on-disk store of a sweep (see the module docstring for the layout)."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        if self.path.exists() and not self.path.is_dir():
            raise ParameterError(f"out: '{self.path}' exists and is not a directory")
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
        from .solution import _jsonable, atomic_path, write_text_atomic

        key = record["key"]
        if history is not None:
            with atomic_path(self.history_path(key)) as tmp:
                history.to_netcdf(tmp)
        write_text_atomic(self.record_path(key), json.dumps(_jsonable(record), indent=1, sort_keys=True))

    def write_manifest(self, spec: dict[str, Any]) -> None:
        from .solution import _jsonable, write_text_atomic

        write_text_atomic(self.path / "sweep.json", json.dumps(_jsonable(spec), indent=1))

    def read_manifest(self) -> dict[str, Any]:
        try:
            return json.loads((self.path / "sweep.json").read_text(encoding="utf-8"))
        except (OSError, ValueError):
            raise ParameterError(f"store: no sweep in '{self.path}' (sweep.json missing or unreadable)") from None

    def write_result(self, ds: xr.Dataset) -> Path:
        from .solution import atomic_path

        path = self.path / "result.nc"
        with atomic_path(path) as tmp:
            ds.to_netcdf(tmp)
        return path


# ------------------------------------------------------------------------- result
def _dataset(spec: dict[str, Any], plan_: _Plan | None, records: dict[str, dict[str, Any]],
             lost: dict[str, str]) -> xr.Dataset:
    import numpy as np
    import xarray as xr

    keys = spec["cases"]
    if spec["kind"] == "grid":
        dims = tuple(spec["keys"])
        shape = tuple(len(spec["grid"][k]) for k in dims)
        coords: dict[str, Any] = {k: (k, _coord(spec["grid"][k]), {"long_name": k}) for k in dims}
    else:
        dims = ("case",)
        shape = (len(keys),)
        values = plan_.coords if plan_ is not None else spec["values"]
        coords = {"case": ("case", np.arange(len(keys)), {"long_name": "Case index"})}
        coords.update({k: ("case", _coord(values[k]), {"long_name": k}) for k in spec["keys"]})
    names = list(METRICS)
    extra = sorted({m for r in records.values() for m, v in r.get("metrics", {}).items()
                    if m not in METRICS and isinstance(v, (int, float)) and not isinstance(v, bool)})
    arrays = {m: np.full(len(keys), np.nan) for m in names + extra}
    status = np.empty(len(keys), dtype=object)
    error = np.empty(len(keys), dtype=object)
    for i, key in enumerate(keys):
        rec = records.get(key)
        if rec is None:
            status[i], error[i] = "missing", lost.get(key, "not computed")
            continue
        status[i], error[i] = str(rec.get("status", "")), str(rec.get("error", "") or "")
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
    data_vars["case_key"] = (dims, np.asarray(keys, dtype=str).reshape(shape),
                             {"long_name": "Store key of the case (cases/KEY.json)"})
    n_missing = int(np.count_nonzero(status == "missing"))
    n_failed = int(sum(1 for s in status if s in FAILED))
    attrs = {
        "title": "flexbeam sweep",
        "method": spec["method"],
        "kind": spec["kind"],
        "swept": json.dumps(spec["keys"]),
        "sweep": json.dumps({k: spec[k] for k in ("grid", "samples", "n", "seed") if k in spec}),
        "base_case": spec["base_case"],
        "flexbeam_version": _version(),
        "cases": len(keys),
        "failed": n_failed,
        "missing": n_missing,
    }
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def _coord(values: Sequence[Any]) -> Any:
    import numpy as np

    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=float if any(isinstance(v, float) for v in values) else int)
    return np.asarray([str(v) for v in values], dtype=str)


def _version() -> str:
    from . import __version__

    return __version__


def load(store: str | Path) -> xr.Dataset:
    """Rebuild the Dataset of the last sweep in ``store`` from its case files.

    Useful after a client was killed before it wrote ``result.nc``.
    """
    st = Store(store)
    spec = st.read_manifest()
    records = {k: r for k in spec["cases"] if (r := st.load(k)) is not None}
    return _dataset(spec, None, records, {})


def summary(ds: xr.Dataset) -> dict[str, Any]:
    """Counts of a sweep result and its failed cases with their swept values and errors."""
    import numpy as np

    info: dict[str, Any] = {k: int(ds.attrs.get(k, 0)) for k in ("cases", "computed", "reused", "failed", "missing")}
    swept = json.loads(ds.attrs["swept"])
    status = ds["status"].values
    failures = []
    for idx in zip(*np.nonzero(np.isin(status, FAILED))):
        point = dict(zip(ds["status"].dims, idx))
        params = {k: _plain(ds[k].values[point[ds[k].dims[0]]]) for k in swept}
        failures.append({"key": str(ds["case_key"].values[idx]), "parameters": params,
                         "status": str(status[idx]), "error": str(ds["error"].values[idx])})
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


# ------------------------------------------------------------------------ cluster
def _cpu_count() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


@contextlib.contextmanager
def _client(scheduler: Any, workers: int | None) -> Iterator[Any]:
    from dask.distributed import Client, LocalCluster

    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ParameterError(f"workers: must be an integer >= 1 (got {workers!r})")
    if scheduler is not None and workers is not None:
        raise ParameterError("workers: only for the local cluster (a scheduler has its own workers)")
    if isinstance(scheduler, Client):
        yield scheduler
        return
    if scheduler is not None:
        try:
            client = Client(str(scheduler), timeout="10s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise ParameterError(f"scheduler: cannot connect to '{scheduler}' ({exc})") from None
        with client:
            yield client
        return
    # no dashboard; the scheduler's HTTP endpoints on a free port rather than 8787, which may be taken
    with LocalCluster(n_workers=workers or _cpu_count(), threads_per_worker=1, processes=True,
                      dashboard_address=None, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"}) as cluster, \
            Client(cluster) as client:
        yield client


def _compute(client: Any, todo: list[_Point], method: str, histories: bool, store: Store | None,
             records: dict[str, dict[str, Any]], lost: dict[str, str], progress: ProgressFn | None) -> None:
    from dask.distributed import as_completed

    token = uuid.uuid4().hex[:8]
    ac = as_completed()
    point_of: dict[str, _Point] = {}
    for p in todo:
        fkey = f"flexbeam-case-{p.key}-{token}"
        point_of[fkey] = p
        ac.add(client.submit(run_case, p.data, method, histories, key=fkey))
    done = 0
    for fut in ac:
        p = point_of[fut.key]
        if fut.status == "finished":
            record, history = fut.result()
            record.update(key=p.key, overrides=p.overrides, case=p.data,
                          finished=time.strftime("%Y-%m-%dT%H:%M:%S%z"))
            if store is not None:
                store.save(record, history)
            record.pop("case")  # on disk; the result needs status, error and metrics
            records[p.key] = record
        else:  # lost with its worker (KilledWorker) or cancelled: not recorded, the next run retries
            exc = fut.exception() if fut.status == "error" else None
            lost[p.key] = f"{type(exc).__name__}: {exc}" if exc is not None else fut.status
        del fut
        done += 1
        if progress is not None:
            progress(done, len(todo))


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
    from .simulation import METHOD_NAMES

    if method not in METHOD_NAMES:
        raise ParameterError(f"method: unknown impact method '{method}'; allowed: "
                             f"{', '.join(METHOD_NAMES)}{closest(method, METHOD_NAMES)}")
    base = load_case(case, dict(overrides) if overrides else None)
    pl = plan(base, grid, samples, n, seed, method)
    store = Store(out) if out is not None else None
    spec = {**pl.spec, "histories": bool(histories)}
    records: dict[str, dict[str, Any]] = {}
    lost: dict[str, str] = {}
    todo: list[_Point] = []
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
            rec = {"key": p.key, "method": method, "status": "invalid", "error": p.error, "message": p.error,
                   "metrics": {}, "overrides": p.overrides, "elapsed": 0.0, "flexbeam_version": _version()}
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
            with _client(scheduler, workers) as client:
                _compute(client, todo, method, histories, store, records, lost, progress)
    finally:
        ds = _dataset(spec, pl, records, lost)
        ds.attrs["computed"] = len(records) - reused - invalid
        ds.attrs["reused"] = reused
        if store is not None:
            store.write_result(ds)
    return ds
