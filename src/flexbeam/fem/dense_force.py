"""The FE contact force between the samples: each contact step's gap as the quintic Hermite interpolant of
(delta, delta', delta'') at its ends, through the pair's law -- the ``force_at`` by which a
:class:`~flexbeam.results.solution.Solution` refines the force peaks."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .contact_law import law_force
from .run_record import Record


def dense_force(rec: Record, pair: int = 0) -> Callable[[float], float] | None:
    """t -> contact force of ``pair`` on its contact steps, from the quintic Hermite interpolant
    of its gap through (delta, delta', delta'') at both ends of each step."""
    dense = [d for d in rec.dense if d[5] == pair]
    if not dense:
        return None
    t0 = np.array([d[0] for d in dense])
    t1 = np.array([d[1] for d in dense])

    def force_at(t: float) -> float:
        i = int(np.searchsorted(t1, t, side="left"))
        if i >= t1.size or t < t0[i]:
            return 0.0
        a, b, g0, g1, lawp, _ = dense[i]
        h = b - a
        if h <= 0.0:
            return float(law_force(lawp, -g0[0], -g0[1])[0])
        s = (t - a) / h
        d, dd = _quintic(s, h, g0, g1)
        return float(law_force(lawp, -d, -dd)[0])

    return force_at


def _quintic(s: float, h: float, g0, g1) -> tuple[float, float]:
    """Quintic Hermite value and derivative at s in [0, 1] from (f, f', f'') at the ends."""
    f0, v0, a0 = g0[0], g0[1] * h, g0[2] * h * h
    f1, v1, a1 = g1[0], g1[1] * h, g1[2] * h * h
    s2, s3, s4, s5 = s * s, s**3, s**4, s**5
    H = (
        1 - 10 * s3 + 15 * s4 - 6 * s5,
        s - 6 * s3 + 8 * s4 - 3 * s5,
        0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5,
        10 * s3 - 15 * s4 + 6 * s5,
        -4 * s3 + 7 * s4 - 3 * s5,
        0.5 * s3 - s4 + 0.5 * s5,
    )
    dH = (
        -30 * s2 + 60 * s3 - 30 * s4,
        1 - 18 * s2 + 32 * s3 - 15 * s4,
        s - 4.5 * s2 + 6 * s3 - 2.5 * s4,
        30 * s2 - 60 * s3 + 30 * s4,
        -12 * s2 + 28 * s3 - 15 * s4,
        1.5 * s2 - 4 * s3 + 2.5 * s4,
    )
    c = (f0, v0, a0, f1, v1, a1)
    val = sum(hk * ck for hk, ck in zip(H, c, strict=True))
    der = sum(hk * ck for hk, ck in zip(dH, c, strict=True)) / h
    return float(val), float(der)


def pair_force(dense: list[Callable[[float], float] | None]) -> Callable[[float, int], float]:
    """(t, pair) -> F_k(t), pair k's force on its dense output (0 for a pair that has no contact): the
    ``force_at`` of :class:`~flexbeam.results.solution.Solution`."""

    def force_at(t: float, pair: int = 0) -> float:
        f = dense[pair]
        return 0.0 if f is None else f(t)

    return force_at
