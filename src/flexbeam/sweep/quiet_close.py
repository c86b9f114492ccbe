"""The local cluster's workers close without printing a heartbeat's traceback.

A Dask worker that closes (``Worker.close``: its status set to *closing* first, its connections closed later) cuts
a heartbeat to the scheduler that is still on its way, and ``distributed.worker`` logs that as an error with the
whole traceback: ~30 lines of "Failed to communicate with scheduler during heartbeat ... CommClosedError" on the
stderr of a script whose sweep succeeded (dask/distributed issue 7105, open; 1 of 30 runs of a plain script's
2-case sweep on this project's machine, distributed 2026.8).  :class:`QuietClose` is a worker plugin of the local
cluster (imported where the cluster starts: it needs ``distributed``) that drops that one record while the worker
is closing or closed; a heartbeat that fails while the worker runs (a scheduler lost) is still logged as before.
"""

from __future__ import annotations

import logging
from typing import Any

from distributed.diagnostics.plugin import WorkerPlugin

#: the message ``distributed.worker`` logs for a heartbeat whose connection failed (``Worker.heartbeat``)
HEARTBEAT_FAILED = "Failed to communicate with scheduler during heartbeat."
#: the worker's statuses in which it is shutting down (``distributed.core.Status`` values)
CLOSING = frozenset({"closing", "closing_gracefully", "closed"})


class _HeartbeatAtClose(logging.Filter):
    """Drops :data:`HEARTBEAT_FAILED` while ``worker`` is closing (:data:`CLOSING`)."""

    def __init__(self, worker: Any) -> None:
        super().__init__()
        self.worker = worker

    def filter(self, record: logging.LogRecord) -> bool:
        if record.getMessage() != HEARTBEAT_FAILED:
            return True
        status = getattr(self.worker, "status", None)
        return getattr(status, "value", status) not in CLOSING


class QuietClose(WorkerPlugin):
    """Worker plugin (``Client.register_plugin``): installs :class:`_HeartbeatAtClose` on ``distributed.worker``'s
    logger of the worker's process, once per worker."""

    name = "flexbeam-quiet-close"
    idempotent = True

    def setup(self, worker: Any) -> None:
        logger = logging.getLogger("distributed.worker")
        if not any(isinstance(f, _HeartbeatAtClose) and f.worker is worker for f in logger.filters):
            logger.addFilter(_HeartbeatAtClose(worker))

    def teardown(self, worker: Any) -> None:
        """The filter stays: a worker's plugins are torn down before its connections close."""
