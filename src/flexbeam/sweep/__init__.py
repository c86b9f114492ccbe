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
``Client``) is given.  The local cluster is started by the first sweep of a process and
reused by the next ones (:func:`local_client`; closed at exit or by
:func:`close_local_cluster`).  A task runs a batch of cases (:func:`run_batch`), so the
cost of a task is paid per batch: batches are sized as the sweep goes, about half a
second of work each (``batch_size`` fixes it), and BLAS runs on one thread in them.

The store
---------
A directory, not a Zarr array, because each finished case must reach the disk on its
own and completely or not at all, from whichever process sees it finish::

    STORE/sweep.json       the last sweep's definition (base case, method, swept fields,
                           the case keys in order)
    STORE/cases/KEY.json   one finished case: its overrides, full case, status, error,
                           every metric, worker and timing
    STORE/cases/KEY.nc     its full history (``histories=True``), stored as a run's result.nc
                           is: outputs rounded to the integrator's precision, deflated in
                           chunks (~3 MB a seed case; 10.3 MB before 2026-11-28)
    STORE/result.nc        the consolidated Dataset, rewritten at the end of every run
                           (also after an interruption; missing cases have status "missing")

``KEY`` is a hash of the validated case (without its name and description) and the
impact method, so a case is recognised whatever sweep it came from.  Each file is
written to a temporary name and renamed (atomic on POSIX): a case is finished if and
only if its JSON exists, and its history is written before it.  The client writes
the files as the results arrive (every case of a batch when the batch returns), so a
remote cluster needs no shared file system, and an interrupted client (Ctrl-C) or a
killed worker loses only the batches that were still running (about half a second of
work each; a case of half a second or more is a batch of its own).  Running the same sweep
again computes only the cases whose JSON is missing.  A case whose simulation raises or
ends with ``status == "failed"`` is a finished case: it is recorded with its error and is
not retried, and the other cases of its batch run on.  A batch lost with its worker
(``KilledWorker`` after Dask's retries) runs again one case at a time; a case lost so is
not recorded and is computed by the next run.

Library imports stay light here: Dask and xarray are imported when a sweep runs.  The
local cluster starts its workers as new processes without running the calling script
again (:func:`~flexbeam.sweep.cluster.workers_skip_main`), so a plain script may sweep at
module level, without an ``if __name__ == "__main__":`` guard.

Modules
-------
* :mod:`~flexbeam.sweep.spec` -- grids and :class:`Distribution` (parsing the command line);
* :mod:`~flexbeam.sweep.planning` -- :func:`plan`: the cases and their :func:`case_key`;
* :mod:`~flexbeam.sweep.store` -- :class:`Store`, the resumable directory;
* :mod:`~flexbeam.sweep.cluster` -- :func:`run_case` and :func:`run_batch` on a Dask worker,
  the batches, the cluster;
* :mod:`~flexbeam.sweep.scheduler` -- a scheduler's address checked before anything runs;
* :mod:`~flexbeam.sweep.dataset` -- the result Dataset, :func:`load`, :func:`summary`,
  :func:`open_history`;
* :mod:`~flexbeam.sweep.runner` -- :func:`sweep`.
"""

from __future__ import annotations

from .._namespace import public_dir
from .cluster import ProgressFn, close_local_cluster, local_client, run_batch, run_case
from .dataset import METRICS, load, open_history, summary
from .planning import Plan, Point, case_key, plan
from .runner import sweep
from .spec import Distribution, parse_grid, parse_samples
from .store import FAILED, Store

__all__ = [
    "FAILED",
    "METRICS",
    "Distribution",
    "Plan",
    "Point",
    "ProgressFn",
    "Store",
    "case_key",
    "close_local_cluster",
    "load",
    "local_client",
    "open_history",
    "parse_grid",
    "parse_samples",
    "plan",
    "run_batch",
    "run_case",
    "summary",
    "sweep",
]

__dir__ = public_dir(globals())
