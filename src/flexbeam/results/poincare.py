"""Poincaré sections of a run on a moving base: the state once per drive period, at a fixed phase of the drive.

A base shaken at the fundamental frequency f (``base.frequency``) makes the equations periodic in time with period
1/f; sampling the run at t_k = (k + phase) / f, k = 0, 1, ..., gives its Poincaré map (Moon & Shaw 1983; Wagg &
Bishop 2002): a periodic response of period m shows m points, a quasi-periodic one a closed curve, a chaotic one a
fractal set.  The samples are read from the run's dense output (their cost is the number of periods), with the
columns an impact oscillator is drawn in: the tip's deflection, the contact point's gap and normal velocity (of the
first pair, ``[contact]``), and the joint's angle and rate.  A contact record's phase of the drive is frac(f t_onset).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .solution import Solution

#: the output columns of a Poincaré section
SECTION_COLUMNS = ("tip_deflection", "gap", "normal_velocity", "theta", "theta_rate")


def section_times(t0: float, t1: float, frequency: float, phase: float) -> tuple[np.ndarray, np.ndarray]:
    """(periods k, times (k + phase) / f) of the sections within [t0, t1], k >= 0."""
    if not (frequency > 0.0 and math.isfinite(frequency)):
        return np.zeros(0, int), np.zeros(0)
    k0 = max(0, math.ceil(t0 * frequency - phase - 1e-9))
    k1 = math.floor(t1 * frequency - phase + 1e-9)
    k = np.arange(k0, k1 + 1)
    t = (k + phase) / frequency
    keep = (t >= t0 - 1e-12 / frequency) & (t <= t1 + 1e-12 / frequency)
    return k[keep], np.clip(t[keep], t0, t1)


def drive_frequency(sol: Solution) -> float:
    """The run's drive frequency f [Hz] (``base.frequency``), NaN without one (or without a dense output)."""
    if sol.source is None:
        return math.nan
    f = sol.source.system.case.base.frequency
    return math.nan if f is None or not sol.source.system.case.base.moving else float(f)


def poincare(sol: Solution, phase: float = 0.0, discard: int = 0) -> dict[str, np.ndarray]:
    """The Poincaré section of a run on a moving base at ``phase`` (a fraction of the drive period, in [0, 1)).

    Parameters
    ----------
    sol
        A run held in memory (its dense output; not a streamed or finite-element run).
    phase
        Where in the period to sample: t_k = (k + phase) / f.
    discard
        Periods to leave out at the start (the transient): k >= ``discard``.

    Returns
    -------
    dict
        ``period`` (k), ``time`` [s] and the columns of :data:`SECTION_COLUMNS` at each section, in time order.

    Raises
    ------
    ValueError
        Without a moving base with a frequency, or without the run's dense output, or a phase outside [0, 1), or a
        ``discard`` that is not a whole number >= 0.
    """
    if not 0.0 <= phase < 1.0:
        raise ValueError(f"phase: a fraction of the drive period in [0, 1), not {phase!r}")
    if isinstance(discard, bool) or not isinstance(discard, (int, np.integer)) or discard < 0:
        raise ValueError(f"discard: a number of periods >= 0, not {discard!r}")
    f = drive_frequency(sol)
    if not math.isfinite(f):
        raise ValueError(
            "base.frequency: a Poincaré section needs a base shaken at a frequency (and a run's dense output)"
        )
    src = sol.source
    assert src is not None
    segs = [s for s in src.segments if s.t1 > s.t0 or len(src.segments) == 1]
    k, t = section_times(segs[0].t0, segs[-1].t1, f, phase)
    keep = k >= discard
    k, t = k[keep], t[keep]
    out: dict[str, list[np.ndarray]] = {name: [] for name in SECTION_COLUMNS}
    times: list[np.ndarray] = []
    starts = np.array([s.t0 for s in segs])
    owner = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(segs) - 1)
    for i in np.unique(owner):
        ti = t[owner == i]
        cols = src.evaluate(segs[i], ti)[0]
        times.append(ti)
        for name in SECTION_COLUMNS:
            out[name].append(np.asarray(cols[name], float))
    result = {"period": k, "time": np.concatenate(times) if times else np.zeros(0)}
    result.update({name: np.concatenate(v) if v else np.zeros(0) for name, v in out.items()})
    return result


def drive_phase(onset: float, frequency: float) -> float:
    """The phase of the drive, frac(f t) in [0, 1), at which a contact began."""
    x = frequency * onset
    return float(x - math.floor(x))
