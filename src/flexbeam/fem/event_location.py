"""Finding and locating the FE run's contact events within a step.

A step whose end state has crossed (the gap delta of a free pair below zero, or of a pair in contact above zero)
is cut back: the crossing is located by the Illinois variant of regula falsi on the step size (each trial is a
complete implicit step from the last accepted state) until |delta| is below a tolerance on the penetrated side
(onset) or the open side (separation).  A free step whose ends both have delta > 0 is also checked for a dip below
zero by the cubic Hermite interpolant of (delta, delta') at its ends (:func:`flexbeam.fem.gap.hermite_dip`), so
that a grazing impact inside a step is not missed.  When several pairs have an event within one step, the first
by its linear (or, for a dip, Hermite) estimate of the crossing is taken.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import SolverError
from .beam import FemBeam
from .gap import hermite_dip
from .integrator import FemIntegrator, NewtonFailure, State
from .pairs import ContactState


def hermite_fraction(g0: float, v0: float, g1: float, v1: float, h: float) -> float | None:
    """Fraction s in (0, 1) where the cubic Hermite of the gap dips below zero, if any."""
    s = hermite_dip(g0, v0, g1, v1, h)
    return s if s > 0.0 else None


def crossing_candidates(
    gaps0: np.ndarray, rates0: np.ndarray, ends: Sequence[tuple[float, float]], cs: ContactState, h: float
) -> list[tuple[float, int, bool]]:
    """The pairs whose gap crosses zero in a step of size h, from (``gaps0``, ``rates0``) at its start to ``ends``
    [(delta, delta')] at its end: (estimated fraction of the step, pair, a Hermite dip?) -- a free pair closing or
    dipping, a pair in contact opening."""
    candidates = []
    for k in range(len(cs.laws)):
        d0, v0 = float(gaps0[k]), float(rates0[k])
        d1, v1 = ends[k]
        if cs.laws[k] is None:
            if d1 < 0.0 and d0 >= 0.0:
                candidates.append((d0 / (d0 - d1), k, False))
            elif d0 > 0.0 and d1 > 0.0:
                frac = hermite_fraction(d0, v0, d1, v1, h)
                if frac is not None:
                    candidates.append((frac, k, True))
        elif d1 > 0.0 and d0 <= 0.0:
            candidates.append((d0 / (d0 - d1), k, False))
    return candidates


def first_crossing(
    beam: FemBeam,
    integ: FemIntegrator,
    s0: State,
    s1: State,
    ends: Sequence[tuple[float, float]],
    h: float,
    candidates: list[tuple[float, int, bool]],
    cs: ContactState,
) -> tuple[int, State, float, float] | None:
    """The earliest of ``candidates`` that is a crossing, as (pair, a state past it, its gap there, the step to that
    state from ``s0``); a Hermite dip counts when the step to its estimated instant finds the gap negative."""
    for frac, k, dip in sorted(candidates):
        if not dip:
            return k, s1, ends[k][0], h
        s_dip = step_with_halving(integ, s0, frac * h, cs)
        d_dip = beam.gap(s_dip.z, s_dip.zd, s_dip.zdd, pair=k)[0]
        if d_dip < 0.0:
            return k, s_dip, d_dip, frac * h
    return None


def locate_crossing(
    beam: FemBeam,
    integ: FemIntegrator,
    s0: State,
    f0: float,
    s1: State,
    f1: float,
    h: float,
    sign: float,
    cs: ContactState,
    tol: float,
    pair: int,
) -> State:
    """Cut the step back to where f = sign * gap of ``pair`` crosses zero downwards (f0 > 0 >= f1): Illinois
    regula falsi on the step size from ``s0``, until -f <= ``tol`` on the crossed side."""
    lo, flo = 0.0, f0
    hi, fhi, shi = h, f1, s1
    side = 0
    for _ in range(100):
        if -fhi <= tol or hi - lo <= 1e-9 * h:
            return shi
        hm = (lo * fhi - hi * flo) / (fhi - flo)
        hm = min(max(hm, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
        sm = step_with_halving(integ, s0, hm, cs)
        fm = sign * beam.gap(sm.z, sm.zd, sm.zdd, pair=pair)[0]
        if fm <= 0.0:
            hi, fhi, shi = hm, fm, sm
            if side == -1:
                flo *= 0.5
            side = -1
        else:
            lo, flo = hm, fm
            if side == 1:
                fhi *= 0.5
            side = 1
    return shi


def step_with_halving(integ: FemIntegrator, s: State, h: float, lawp: ContactState | np.ndarray | None) -> State:
    """A step of exactly h, taken as 2^k sub-steps if Newton fails."""
    for k in range(12):
        n = 2**k
        try:
            st = s
            for _ in range(n):
                st = integ.step(st, h / n, lawp)
            return st
        except NewtonFailure:
            continue
    raise SolverError("fem: Newton failed while locating a contact event", s.t)
