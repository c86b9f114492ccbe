"""A Dask scheduler given by its address (``sweep --scheduler``, ``bifurcation --scheduler``): its form checked
before anything is written or connected."""

from __future__ import annotations

from typing import Any

from ..errors import ParameterError


def check_scheduler(scheduler: Any) -> None:
    """A scheduler given by its address: the address's form checked before anything is written (``--scheduler foo``,
    no port, wrote the store's sweep.json and then ended in a traceback)."""
    from dask.distributed import Client
    from distributed.comm.addressing import get_address_host_port, normalize_address, parse_address

    if scheduler is None or isinstance(scheduler, Client):
        return
    try:
        address = normalize_address(str(scheduler))
        if parse_address(address)[0] != "inproc":  # (a network address needs its host and port)
            get_address_host_port(address)
    except (TypeError, ValueError) as exc:
        raise ParameterError(f"--scheduler: cannot connect to '{scheduler}' ({exc})") from None


def check_workers(scheduler: Any, workers: Any) -> None:
    """``workers``: an integer >= 1, and only for the local cluster (one line naming the option as the CLI names it,
    ``--workers``, as the runners name ``--periods``, ``--grid``)."""
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ParameterError(f"--workers: must be an integer >= 1 (got {workers!r})")
    if scheduler is not None and workers is not None:
        raise ParameterError("--workers: only for the local cluster (a scheduler has its own workers)")
