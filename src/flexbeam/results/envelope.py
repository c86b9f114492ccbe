"""A run's sampled variable reduced for a small figure: each bin's smallest and largest sample.

The notebook display (:mod:`flexbeam.views.display`) draws a whole run's line in a figure a few hundred pixels wide;
a run of 1000 s at 1 ms holds 10^6 samples of it.  :func:`envelope` keeps, of each of at most ``bins`` bins of equal
sample counts, the smallest and the largest sample, in the order they occur (min-max decimation: every bin's extremes
are drawn, so no peak between two drawn samples is lost and the line's range is the data's).  A line of at most
2 ``bins`` samples is kept whole.  Bins reduce one by one (:func:`reduce_bins`), so a file's variable reduces slice by
slice to the same numbers (:func:`flexbeam.results.readback.read_envelope`).
"""

from __future__ import annotations

import numpy as np

#: the bins of a drawn line (a notebook figure is ~400 pixels wide: 2000 points are more than it shows)
BINS = 1000


def bin_size(n: int, bins: int) -> int:
    """Samples a bin of ``n`` samples in at most ``bins`` bins (0: the line is kept whole)."""
    if bins < 1:
        raise ValueError(f"bins must be at least 1, got {bins}")
    return 0 if n <= 2 * bins else -(-n // bins)


def reduce_bins(time: np.ndarray, values: np.ndarray, size: int) -> tuple[np.ndarray, np.ndarray]:
    """Each bin's (of ``size`` samples from the first, the last one possibly shorter) smallest and largest sample in
    their order; NaN samples count neither as a bin's smallest nor its largest (an all-NaN bin keeps a NaN: the
    line's gap)."""
    n = values.shape[0]
    m = -(-n // size)
    missing = np.isnan(values)
    lo = np.full(m * size, np.inf)
    hi = np.full(m * size, -np.inf)
    lo[:n] = np.where(missing, np.inf, values)
    hi[:n] = np.where(missing, -np.inf, values)
    start = np.arange(m) * size
    i_lo = np.argmin(lo.reshape(m, size), axis=1) + start
    i_hi = np.argmax(hi.reshape(m, size), axis=1) + start
    idx = np.stack([np.minimum(i_lo, i_hi), np.maximum(i_lo, i_hi)], axis=1).ravel()
    return time[idx], values[idx]


def envelope(time: np.ndarray, values: np.ndarray, bins: int = BINS) -> tuple[np.ndarray, np.ndarray]:
    """The line (``time``, ``values``) of one sampled variable reduced to each bin's extremes (module docstring).

    Parameters
    ----------
    time, values
        The samples' times [s] and values (1-D, the same length).
    bins
        The bins at most; a line of at most ``2 bins`` samples is returned as it is.

    Returns
    -------
    (time, values)
        Two samples a bin (the bin's smallest and largest value, in time order; one sample twice where they are the
        same), or the arrays themselves.
    """
    size = bin_size(values.shape[0], bins)
    return (time, values) if size == 0 else reduce_bins(time, values, size)


__all__ = ["BINS", "bin_size", "envelope", "reduce_bins"]
