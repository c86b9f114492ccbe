"""The friction outputs of a run with Coulomb friction under CCFM (:mod:`flexbeam.methods.coulomb`): per pair its
tangential force, slip velocity and friction state at the samples, and its tangential impulse over a contact."""

from __future__ import annotations

import math

import numpy as np

from ..contact.laws import threlfall as regularised
from ..integrate.loop import Segment
from ..model.system import BeamSystem


def has_friction(segments: list[Segment]) -> bool:
    """Did some phase of the run carry friction (CCFM's and CCM's contacts, IMM's held pairs)?"""
    return any(s.phase.friction is not None for s in segments)


def _multipliers(seg: Segment, pair: int, times: np.ndarray) -> np.ndarray:
    """The pair's tangential multiplier at ``times`` in ``seg`` (zero where the dense output holds none)."""
    if seg.dense is None or not hasattr(seg.dense, "multipliers") or not times.size:
        return np.zeros(times.size)
    return seg.dense.multipliers(pair, times)


def friction_columns(system: BeamSystem, seg: Segment, times: np.ndarray, Y: np.ndarray, F: np.ndarray):
    """(tangential force, slip velocity, friction state), each samples x pairs, of segment ``seg`` at ``times``
    (states Y, the pairs' normal forces F): F_t = sigma F + lambda_t; the slip velocity of every pair in contact (0
    for a free one); the state 0 (no frictional contact), 1 (slip) or 2 (stick: a follower's force is its
    holder's)."""
    S = system.pairs
    Ft, vt, state = np.zeros((times.size, S)), np.zeros((times.size, S)), np.zeros((times.size, S))
    fr = seg.phase.friction
    for k in range(S):
        if seg.phase.modes[k] == 0:
            continue
        vt[:, k] = [system.tangent(t, y, k)[2] for t, y in zip(times, Y)]
        if fr is None:
            continue
        sigma, stick = fr[k, 0], fr[k, 1]
        if stick < 0.0:  # the regularised law: [mu_k, -1, v_0]
            sigma = regularised(sigma, fr[k, 2], vt[:, k])
        Ft[:, k] = sigma * F[:, k] + (_multipliers(seg, k, times) if stick == 1.0 else 0.0)
        state[:, k] = 2.0 if stick > 0.0 else (1.0 if fr[k, 0] != 0.0 or fr[k, 4] != 0.0 else 0.0)
    return Ft, vt, state


def tangential_impulse(segments: list[Segment], t0: float, t1: float, pair: int) -> float:
    """int F_t dt of ``pair`` over the whole frictional phases inside [t0, t1] (each step's Gauss quadrature of its
    nodal sigma F + F_t, :meth:`~flexbeam.integrate.dense.ModalDense.tangential_impulse`); NaN when no phase
    there had friction."""
    total, seen = 0.0, False
    for s in segments:
        if s.t0 < t0 or s.t1 > t1 or s.t1 <= s.t0 or s.phase.friction is None or s.phase.modes[pair] == 0:
            continue
        seen = True
        if s.dense is None or not hasattr(s.dense, "tangential_impulse"):
            continue
        law = s.phase.friction[pair, 1] < 0.0  # the regularised law: a nodal tangential unknown (kernels/src/nodal.c)
        total += s.dense.tangential_impulse(pair, 0.0 if law else float(s.phase.friction[pair, 0]))
    return total if seen else math.nan
