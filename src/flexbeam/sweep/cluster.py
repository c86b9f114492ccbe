"""Running cases on Dask: batches of cases on a worker, the cluster or client, and collecting the results.

A task runs a *batch* of cases one after the other (:func:`run_batch`), so what a task costs -- the scheduler's
bookkeeping, sending the function and its arguments, returning the results, on the client and on the worker -- is
paid per batch, not per case (about 12 ms of processor time per task on this project's machine, client and worker
together, against 19 ms for a seed case: docs/performance.md, *Sweeps*).  Batches are sized as the sweep goes
(:func:`batch_size`): one case per task until the first cases have run, then about :data:`BATCH_SECONDS` of work
per task, and smaller again towards the end so that the workers finish together.  The client stores each case of
a batch as the batch's results arrive.

The local cluster (no ``scheduler`` given) is started once per process and reused by the later sweeps
(:func:`local_client`); it is closed when the process exits, or by :func:`close_local_cluster`.
"""

from __future__ import annotations

import atexit
import contextlib
import itertools
import os
import threading
import time
import uuid
from collections import deque
from collections.abc import Callable, Iterator
from typing import Any

from ..errors import ParameterError
from ..interrupt import Hit, ctrl_c_flag
from ..parameters.io import validate_case
from .case_warnings import Teller, exclusive, recorded, validating
from .planning import Point
from .scheduler import check_scheduler, check_workers
from .store import Store

ProgressFn = Callable[[int, int], None]


def run_case(data: dict[str, Any], method: str, histories: bool = False, aside: bool = False) -> tuple[dict, Any]:
    """Run one case on a worker: ``(record, history Dataset or None)``; ``aside``: its warnings in the record
    (:mod:`flexbeam.sweep.case_warnings`).  Every exception is caught and recorded (status ``"error"``): a failing
    case does not stop the sweep."""
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

        with validating(aside):
            case = validate_case(data)
        with recorded(record, aside):  # (said on the client, naming the case)
            sol = simulate(case, method)
            metrics = sol.metrics()
            for name in ("method", "status", "message"):
                metrics.pop(name, None)
            error = sol.message if sol.status == "failed" else ""
            record.update(status=sol.status, message=sol.message, metrics=metrics, error=error)
            if histories:  # as result.nc holds a run: its outputs rounded to the run's precision
                from ..results.export import result_dataset

                history = result_dataset(sol)
    except Exception as exc:  # noqa: BLE001 - recorded, the sweep goes on
        record["error"] = f"{type(exc).__name__}: {exc}"
        record["message"] = record["error"]
    record["elapsed"] = time.perf_counter() - t0
    return record, history


#: an automatic batch holds about this much work [s], timed on the cases finished so far ...
BATCH_SECONDS = 0.5
#: ... and at most this many cases
MAX_BATCH = 64
#: batches in flight per worker thread: one running and one waiting, so that no worker idles between two batches
IN_FLIGHT = 2

#: one case of a batch as sent to the worker: (store key, overrides, validated case)
BatchItem = tuple[str, dict[str, Any], dict[str, Any]]


def run_batch(cases: list[BatchItem], method: str, histories: bool = False, client_pid: int | None = None) -> list:
    """Run a batch of cases one after the other on a worker: ``(record, history or None)`` per case, in order; their
    warnings in the records where that is safe (:func:`~flexbeam.sweep.case_warnings.exclusive`).

    ``cases`` holds ``(key, overrides, validated case)``; each record is :func:`run_case`'s with the case's key,
    overrides and the time it finished.  A case that raises is recorded as such and the next one runs.  BLAS runs
    on one thread meanwhile (:func:`flexbeam.threads.single_threaded_blas`; restored after the batch, for a
    worker that is a thread of the calling process).
    """
    from ..threads import single_threaded_blas

    out, aside = [], exclusive(client_pid)
    with single_threaded_blas():
        for key, overrides, data in cases:
            record, history = run_case(data, method, histories, aside)
            record.update(key=key, overrides=overrides, finished=time.strftime("%Y-%m-%dT%H:%M:%S%z"))
            out.append((record, history))
    return out


def batch_size(remaining: int, slots: int, per_case: float | None, fixed: int | None = None) -> int:
    """How many of the ``remaining`` cases the next batch takes.

    ``fixed`` when given; else one case until a case's mean time ``per_case`` [s] is known, then about
    :data:`BATCH_SECONDS` of work (at most :data:`MAX_BATCH` cases), and at most an equal share of the remaining
    cases among the :data:`IN_FLIGHT` batches of each of the ``slots`` worker threads: the last batches shrink and
    the workers finish together.  A case of half a second or more runs alone, as without batches.
    """
    if fixed is not None:
        return max(1, min(fixed, remaining))
    if per_case is None:
        return 1
    by_time = int(BATCH_SECONDS / max(per_case, 1e-9))
    share = -(-remaining // (IN_FLIGHT * max(slots, 1)))
    return max(1, min(by_time, share, MAX_BATCH, remaining))


def cpu_count() -> int:
    """Cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


# ----------------------------------------------------------------------------------------------- the local cluster
#: the name a Dask nanny gives the worker process it starts (distributed.nanny)
_WORKER_PROCESS = "Dask Worker process (from Nanny)"
_skip_main = 0  # open workers_skip_main contexts
_skip_lock = threading.Lock()


_original_preparation_data: Callable[[str], dict[str, Any]] | None = None


def _preparation_data(name: str) -> dict[str, Any]:
    """:func:`multiprocessing.spawn.get_preparation_data`, without the main module for a Dask worker process while
    a :func:`workers_skip_main` context is open."""
    assert _original_preparation_data is not None
    data = _original_preparation_data(name)
    if _skip_main and str(name).startswith(_WORKER_PROCESS):
        data.pop("init_main_from_path", None)
        data.pop("init_main_from_name", None)
    return data


@contextlib.contextmanager
def workers_skip_main() -> Iterator[None]:
    """Start Dask worker processes that do not run the calling script again.

    A process started by the "spawn" method -- Dask's for its local workers -- first runs the parent's main
    module again, as ``__mp_main__`` (:func:`multiprocessing.spawn.get_preparation_data` sends its path, or its
    module name under ``python -m``).  A script that calls :func:`flexbeam.sweep` at module level, without
    ``if __name__ == "__main__":``, would so start a sweep inside each worker while it starts, and the local
    cluster fail with 200 lines ending in "Nanny failed to start".  A worker needs nothing from the script (it
    runs :func:`run_batch`), so while the context is open the preparation data of a Dask worker process (by the
    name its nanny gives it) carries neither the path nor the module name, as for an interactive session; other
    processes, and the main module itself, are left as they are.  The local cluster holds the context for its
    whole life, so a worker that its nanny restarts, during a sweep or between two, does not run the script
    either.
    """
    global _skip_main, _original_preparation_data
    import multiprocessing.spawn as spawn

    with _skip_lock:
        if spawn.get_preparation_data is not _preparation_data:
            _original_preparation_data = spawn.get_preparation_data
            spawn.get_preparation_data = _preparation_data
        _skip_main += 1
    try:
        yield
    finally:
        with _skip_lock:
            _skip_main -= 1


class _Local:
    """The process's local cluster: its client, cluster, number of workers and the context it holds."""

    client: Any = None
    cluster: Any = None
    workers = 0
    stack: contextlib.ExitStack | None = None
    at_exit = False
    lock = threading.RLock()


def local_client(workers: int | None = None) -> Any:
    """The client of the process's local cluster: ``workers`` (default: one per core) single-threaded worker
    processes, started on first use and reused by every later call with the same number of workers (another
    number closes it and starts a new one; so does a cluster found closed).

    The workers' statistical profiler is off (it samples the running task every 10 ms).  The client is not made
    Dask's default, so the caller's own ``dask.compute`` does not run on it.  It is closed when the process exits
    (:func:`close_local_cluster`).
    """
    n = workers or cpu_count()
    with _Local.lock:
        if _Local.client is None or _Local.workers != n or not _alive():
            _start_local(n)
        return _Local.client


def _start_local(n: int) -> None:
    import dask
    from dask.distributed import Client, LocalCluster

    from .quiet_close import QuietClose

    close_local_cluster()
    stack = contextlib.ExitStack()
    try:
        stack.enter_context(workers_skip_main())
        # no dashboard; the scheduler's HTTP endpoints on a free port rather than 8787, which may be taken
        with dask.config.set({"distributed.worker.profile.enabled": False}):
            cluster = stack.enter_context(
                LocalCluster(
                    n_workers=n,
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=None,
                    scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
                )
            )
        client = stack.enter_context(Client(cluster, set_as_default=False))
        client.register_plugin(QuietClose())
    except BaseException:
        stack.close()
        raise
    _Local.client, _Local.cluster, _Local.workers, _Local.stack = client, cluster, n, stack
    if not _Local.at_exit:
        atexit.register(close_local_cluster)
        _Local.at_exit = True


def _alive() -> bool:
    from distributed.core import Status

    return _Local.client.status == "running" and _Local.cluster.status == Status.running


def close_local_cluster() -> None:
    """Close the process's local cluster, if one runs (the next sweep without a scheduler starts a new one)."""
    with _Local.lock:
        stack = _Local.stack
        _Local.client = _Local.cluster = _Local.stack = None
        _Local.workers = 0
        if stack is not None:
            stack.close()


@contextlib.contextmanager
def cluster_client(scheduler: Any, workers: int | None) -> Iterator[Any]:
    """A Dask client: the given one, one connected to ``scheduler`` (closed on exit), or the process's local
    cluster's (:func:`local_client`, kept for the next sweep)."""
    from dask.distributed import Client

    check_workers(scheduler, workers)
    if isinstance(scheduler, Client):
        yield scheduler
        return
    if scheduler is not None:
        check_scheduler(scheduler)
        try:  # (not Dask's default: a connection that failed stayed the default, and the store's result.nc,
            # written after the failure, ended in a traceback through it)
            client = Client(str(scheduler), timeout="10s", set_as_default=False)
        except (OSError, TimeoutError, ValueError) as exc:
            raise ParameterError(f"--scheduler: cannot connect to '{scheduler}' ({exc})") from None
        with client:
            yield client
        return
    yield local_client(workers)


# ------------------------------------------------------------------------------------------------- the computation
class _Feed:
    """The cases of a sweep on their way through the cluster: those waiting (``queue``; ``alone``: the cases of a
    batch lost with its worker, to run one at a time), the batches in flight by task key (future, cases, whether
    it is such a lone case), and the mean time of a case so far."""

    def __init__(self, client: Any, todo: list[Point], method: str, histories: bool, batch: int | None) -> None:
        from dask.distributed import as_completed

        self.client, self.method, self.histories, self.batch = client, method, histories, batch
        self.slots = max(1, sum(client.nthreads().values()))
        self.queue: deque[Point] = deque(todo)
        self.alone: deque[Point] = deque()
        self.running: dict[str, tuple[Any, list[Point], bool]] = {}
        self.ac = as_completed(loop=client.loop, with_results=True, raise_errors=False)
        self.keys = (f"flexbeam-batch-{uuid.uuid4().hex[:8]}-{i}" for i in itertools.count())
        self.seconds, self.cases, self.teller = 0.0, 0, Teller()

    def submit(self, points: list[Point], alone: bool = False) -> None:
        items = [(p.key, p.overrides, p.data) for p in points]
        fut = self.client.submit(run_batch, items, self.method, self.histories, os.getpid(), key=next(self.keys))
        self.running[fut.key] = (fut, points, alone)
        self.ac.add(fut)

    def fill(self) -> None:
        """Keep :data:`IN_FLIGHT` batches per worker thread in flight, and at most one lone case."""
        if self.alone and not any(alone for _, _, alone in self.running.values()):
            self.submit([self.alone.popleft()], alone=True)
        while self.queue and len(self.running) < IN_FLIGHT * self.slots:
            per_case = self.seconds / self.cases if self.cases else None
            n = batch_size(len(self.queue), self.slots, per_case, self.batch)
            self.submit([self.queue.popleft() for _ in range(n)])

    def ran(self, record: dict[str, Any]) -> None:
        self.seconds += float(record.get("elapsed") or 0.0)
        self.cases += 1

    def cancel(self) -> None:
        """Cancel the batches still in flight (a sweep that stops early leaves the cluster idle for the next)."""
        if self.running:
            with contextlib.suppress(Exception):
                self.client.cancel([fut for fut, _, _ in self.running.values()])


def compute(
    client: Any,
    todo: list[Point],
    method: str,
    histories: bool,
    store: Store | None,
    records: dict[str, dict[str, Any]],
    lost: dict[str, str],
    progress: ProgressFn | None,
    batch: int | None = None,
) -> None:
    """Run the cases ``todo`` on ``client``'s workers in batches (:func:`batch_size`; ``batch``: a fixed size),
    :data:`IN_FLIGHT` batches per worker thread at a time, and file each case as its batch's results arrive:
    saved to ``store``, its record in ``records``.

    A batch lost with its worker (``KilledWorker`` after Dask's retries) is not lost whole: its cases run again,
    one per task and one at a time, so that a case that kills its worker takes no other with it.  A case lost so
    is not recorded (``lost`` holds the reason; the next run retries it).  Batches still in flight when this
    returns early (an interrupt) are cancelled.
    """
    feed = _Feed(client, todo, method, histories, batch)
    done = 0

    def tick() -> None:
        nonlocal done
        done += 1
        if progress is not None:
            progress(done, len(todo))

    with ctrl_c_flag() as hit:
        try:
            _collect(feed, store, records, lost, tick, hit)
        finally:
            feed.cancel()
            feed.teller.close()


def _collect(feed: _Feed, store: Store | None, records: dict, lost: dict, tick: Callable[[], None], hit: Hit) -> None:
    """File each batch's cases as they arrive (see :func:`compute`); a Ctrl-C or SIGTERM recorded in ``hit`` is
    raised between batches (:meth:`~flexbeam.interrupt.Hit.deliver`), and at the end if the sweep finished
    meanwhile."""
    feed.fill()
    for fut, result in feed.ac:
        _, points, _ = feed.running.pop(fut.key)
        if fut.status == "finished":
            for p, (record, history) in zip(points, result):
                record["case"] = p.data
                if store is not None:
                    store.save(record, history)
                record.pop("case")  # on disk; the result needs status, error and metrics
                records[p.key] = record
                feed.teller.say(p.key, record)
                feed.ran(record)
                tick()
        elif fut.status == "error" and len(points) > 1:  # lost with its worker: each case again, alone
            feed.alone.extend(points)
        else:  # lost with its worker (KilledWorker) or cancelled: not recorded, the next run retries
            exc = fut.exception() if fut.status == "error" else None
            for p in points:
                lost[p.key] = f"{type(exc).__name__}: {exc}" if exc is not None else fut.status
                tick()
        del fut, result
        if hit:
            hit.deliver()
        feed.fill()
    if hit:
        hit.deliver()
