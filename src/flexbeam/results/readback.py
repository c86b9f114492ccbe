"""Parts of a result file read without the rest: its span, a window of its samples, one variable's envelope.

A streamed run's file may hold more samples than the memory (a CCFM contact at rest, sampled at
``solver.contact_sample_step``, writes 5e6 samples a simulated second).  These readers touch the chunks they need:
times are found by bisection on the file's ``time`` variable (each probe reads one chunk, through netCDF4, which
xarray would read whole to index it), and the samples of a window, or of one slice of whole bins, are read by
position through xarray -- so that the figures and the notebook display of a run of any length
(:mod:`flexbeam.views.plotting`, :mod:`flexbeam.views.display`) hold a window, a slice and an envelope, not the
run.
"""

from __future__ import annotations

import bisect
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from .envelope import BINS, bin_size, reduce_bins
from .export import TIME_CHUNK, sampled_names


@contextmanager
def _opened(path: str | Path) -> Iterator[tuple[object, object]]:
    """(the file's ``time`` variable, unindexed (netCDF4), and the Dataset of the rest, without ``time`` (xarray))."""
    import netCDF4
    import xarray as xr

    with netCDF4.Dataset(path) as nc, xr.open_dataset(path, drop_variables=["time"]) as ds:
        time = nc.variables["time"]
        time.set_auto_maskandscale(False)  # (its fill value is NaN: the same numbers as xarray's)
        yield time, ds


def read_span(path: str | Path) -> tuple[float, float, int]:
    """(first time, last time, samples) of the result file at ``path``."""
    with _opened(path) as (time, _):
        n = time.shape[0]
        return (float(time[0]), float(time[n - 1]), n) if n else (np.nan, np.nan, 0)


def read_names(path: str | Path) -> list[str]:
    """The sampled variables' names of the result file at ``path`` (its samples not read)."""
    with _opened(path) as (_, ds):
        return sampled_names(ds)


def read_window(path: str | Path, t_a: float, t_b: float) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """(time, phase, arrays) of the samples with ``t_a`` <= time <= ``t_b`` of the result file at ``path``, read
    alone (the figures of a streamed run, :func:`flexbeam.views.plotting._drawn`)."""
    with _opened(path) as (time, ds):
        i0, i1 = bisect.bisect_left(time, t_a), bisect.bisect_right(time, t_b)  # (a sample a probe)
        part = ds.isel(time=slice(i0, i1)).load()
        t = np.asarray(time[i0:i1], dtype=float)
    return t, part["phase"].values.astype(object), {n: part[n].values for n in sampled_names(part)}


def read_envelope(
    path: str | Path, name: str, bins: int = BINS, read: int = TIME_CHUNK
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`~flexbeam.results.envelope.envelope` of the 1-D sampled variable ``name`` of the result file at
    ``path``, read in slices of whole bins of at most ``read`` samples (one bin where a bin is longer): the same
    numbers as the envelope of the variable read whole."""
    with _opened(path) as (time, ds):
        n, var = time.shape[0], ds[name]
        size = bin_size(n, bins)
        if size == 0:
            return np.asarray(time[:], dtype=float), var.values
        step = max(1, read // size) * size
        parts = [
            reduce_bins(np.asarray(time[i : i + step], dtype=float), var[i : i + step].values, size)
            for i in range(0, n, step)
        ]
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


__all__ = ["read_envelope", "read_names", "read_span", "read_window"]
