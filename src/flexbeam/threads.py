"""One BLAS thread for the small linear algebra of a run.

A run's numerics go through the package's own single-threaded C kernels (:mod:`flexbeam.numerics`); the default
(exponential) integrator makes no BLAS call at all, the reference integrator (scipy's DOP853) ~19 000 small ones
per 5 ms of the seed case (its stages' ``np.dot``: matrices of a few tens of rows).  A BLAS thread pool sized to
the machine only adds threads that compete with the other runs of a sweep (one worker process per core), so
sweep workers and the ``flexbeam run`` command hold BLAS to one thread with :mod:`threadpoolctl`.
"""

from __future__ import annotations

from typing import Any


def single_threaded_blas() -> Any:
    """A context in which every BLAS library loaded in the process (OpenBLAS, MKL, BLIS) runs on one thread;
    the thread counts are restored on exit.  Usable as a plain call too, then it holds until the process ends.

    Libraries are looked up when it is called (~0.4 ms): enter it once per batch of runs, not per run.
    """
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=1, user_api="blas")
