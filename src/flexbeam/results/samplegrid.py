"""The output samples' time grid of a phase: the multiples of the sample step inside it and its two ends, and their
count without building the grid (for the memory limits)."""

from __future__ import annotations

import math

import numpy as np


def sample_grid(t0: float, t1: float, step: float) -> np.ndarray:
    """t0, the multiples of ``step`` strictly inside (t0, t1), and t1 (t0 alone for a zero-length phase)."""
    if t1 <= t0:
        return np.array([t0])
    k0, k1 = math.floor(t0 / step) + 1, math.floor(t1 / step)
    grid = np.arange(k0, k1 + 1) * step if k1 >= k0 else np.empty(0)
    grid = grid[(grid > t0) & (grid < t1)]
    return np.concatenate(([t0], grid, [t1]))


#: the sample count reported for a grid too fine to count (2^62: more than any machine holds)
TOO_MANY_SAMPLES = 2**62


def sample_count(t0: float, t1: float, step: float) -> int:
    """The number of samples :func:`sample_grid` gives (or at most 2 more), without building it; a step so fine
    that the count is not a float's integer (a subnormal step) gives :data:`TOO_MANY_SAMPLES`, which every memory
    limit refuses."""
    if t1 <= t0:
        return 1
    a, b = t0 / step, t1 / step
    if not (math.isfinite(a) and math.isfinite(b)) or b - a > TOO_MANY_SAMPLES:
        return TOO_MANY_SAMPLES
    return max(0, math.floor(b) - math.floor(a)) + 2


__all__ = ["TOO_MANY_SAMPLES", "sample_count", "sample_grid"]
