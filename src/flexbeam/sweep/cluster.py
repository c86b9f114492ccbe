"""Running cases on Dask: one case on a worker, the cluster or client, and collecting the results."""

from __future__ import annotations

import contextlib
import os
import sys
import time
import uuid
from collections.abc import Callable, Iterator
from typing import Any

from ..errors import ParameterError
from ..parameters.io import validate_case
from .planning import Point
from .store import Store

ProgressFn = Callable[[int, int], None]


def run_case(data: dict[str, Any], method: str, histories: bool = False) -> tuple[dict[str, Any], Any]:
    """Run one case on a worker: ``(record, history Dataset or None)``.

    Every exception is caught and recorded (status ``"error"``): a failing case does
    not stop the sweep.
    """
    import socket

    from ..version import __version__

    t0 = time.perf_counter()
    record: dict[str, Any] = {
        "method": method,
        "status": "error",
        "error": "",
        "message": "",
        "metrics": {},
        "worker": f"{socket.gethostname()}:{os.getpid()}",
        "flexbeam_version": __version__,
    }
    history = None
    try:
        from ..simulation import simulate

        sol = simulate(validate_case(data), method)
        metrics = sol.metrics()
        for name in ("method", "status", "message"):
            metrics.pop(name, None)
        record.update(
            status=sol.status, message=sol.message, metrics=metrics, error=sol.message if sol.status == "failed" else ""
        )
        if histories:
            history = sol.to_xarray()
    except Exception as exc:  # noqa: BLE001 - recorded, the sweep goes on
        record["error"] = f"{type(exc).__name__}: {exc}"
        record["message"] = record["error"]
    record["elapsed"] = time.perf_counter() - t0
    return record, history


def cpu_count() -> int:
    """Cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


@contextlib.contextmanager
def workers_skip_main() -> Iterator[None]:
    """Start worker processes that do not run the calling script again.

    A process started by the "spawn" method -- Dask's for its local workers -- first runs the parent's main
    module again, as ``__mp_main__`` (:func:`multiprocessing.spawn.get_preparation_data` sends its path, or its
    module name under ``python -m``).  A script that calls :func:`flexbeam.sweep` at module level, without
    ``if __name__ == "__main__":``, would so start a sweep inside each worker while it starts, and the local
    cluster fail with 200 lines ending in "Nanny failed to start".  A worker needs nothing from the script (it
    runs :func:`run_case`), so while the context is open the main module shows spawn neither a path nor a module
    name (``__file__`` removed, ``__spec__`` None, as in an interactive session); both are restored on exit.  The
    context spans the cluster's life, so a worker that its nanny restarts does not run the script either.
    """
    main = sys.modules.get("__main__")
    hidden = {k: main.__dict__[k] for k in ("__file__", "__spec__") if k in main.__dict__} if main else {}
    try:
        if main is not None:
            main.__dict__.pop("__file__", None)
            main.__spec__ = None
        yield
    finally:
        if main is not None:
            main.__dict__.pop("__spec__", None)
            main.__dict__.update(hidden)


@contextlib.contextmanager
def cluster_client(scheduler: Any, workers: int | None) -> Iterator[Any]:
    """A Dask client: the given one, one connected to ``scheduler``, or a new local cluster's."""
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
    with (
        workers_skip_main(),
        LocalCluster(
            n_workers=workers or cpu_count(),
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        ) as cluster,
        Client(cluster) as client,
    ):
        yield client


def compute(
    client: Any,
    todo: list[Point],
    method: str,
    histories: bool,
    store: Store | None,
    records: dict[str, dict[str, Any]],
    lost: dict[str, str],
    progress: ProgressFn | None,
) -> None:
    from dask.distributed import as_completed

    token = uuid.uuid4().hex[:8]
    ac = as_completed()
    point_of: dict[str, Point] = {}
    for p in todo:
        fkey = f"flexbeam-case-{p.key}-{token}"
        point_of[fkey] = p
        ac.add(client.submit(run_case, p.data, method, histories, key=fkey))
    done = 0
    for fut in ac:
        p = point_of[fut.key]
        if fut.status == "finished":
            record, history = fut.result()
            record.update(key=p.key, overrides=p.overrides, case=p.data, finished=time.strftime("%Y-%m-%dT%H:%M:%S%z"))
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
