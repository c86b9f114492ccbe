"""The friction outputs of a run with Coulomb friction under CCFM (:mod:`flexbeam.methods.coulomb`): per pair its
tangential force, slip velocity and friction state at the samples, and its tangential impulse over a contact.

A group of sticking pairs whose tangential rows depend on one another (two points of a rigid bar on a floor or an
incline: :func:`flexbeam.methods.coulomb.grouped`) is held by one multiplier lambda, its holder's, acting along the
holder's row; each follower's row is c times the holder's (c = W_fh / W_hh of the tangential Delassus matrix W, 1 for
the holder).  How lambda divides among the group is statically indeterminate; the outputs share it in proportion to
the normal forces, F_t,i = lambda sign(c_i) F_i / sum_j abs(c_j) F_j: the shares sum to lambda along the holder's row
(sum_i c_i F_t,i = lambda), each pair's abs(F_t,i) / F_i is the group's abs(lambda) / sum_j abs(c_j) F_j, and the
group sticks while that is within mu_s (with abs(c) = 1, as on a rigid line, the kernel's stick condition: the
holder's multiplier within mu_s times the group's summed normal forces, ``kernels/src/friction.c``).  Written whole
to the holder before, one end of a bar on an incline read abs(F_t) / F = 0.77 against mu_s = 0.5, the other 0."""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from ..contact.laws import threlfall as regularised
from ..integrate.loop import Segment
from ..model.delassus import inverse_mass
from ..model.system import BeamSystem


def has_friction(segments: list[Segment]) -> bool:
    """Did some phase of the run carry friction (CCFM's and CCM's contacts, IMM's held pairs)?"""
    return any(s.phase.friction is not None for s in segments)


def _multipliers(seg: Segment, pair: int, times: np.ndarray) -> np.ndarray:
    """The pair's tangential multiplier at ``times`` in ``seg`` (zero where the dense output holds none)."""
    if seg.dense is None or not hasattr(seg.dense, "multipliers") or not times.size:
        return np.zeros(times.size)
    return seg.dense.multipliers(pair, times)


def groups(system: BeamSystem, seg: Segment) -> dict[int, tuple[int, dict[int, float]]]:
    """{pair: (holder, {member: c})} for each pair of a group of sticking pairs in ``seg``'s phase (a holder with
    followers, stick = 2 + h), c its row over the holder's, c = W_ih / W_hh of the tangential Delassus matrix at the
    segment's start (where the group was formed; exact for rows that depend on one another, as a group's do).  Pinned
    pairs (stick = 2 + k: their friction is indeterminate, reported 0) and lone holders are not in it."""
    fr = seg.phase.friction
    if fr is None:
        return {}
    follows = {k: int(fr[k, 1]) - 2 for k in range(fr.shape[0]) if fr[k, 1] >= 2.0 and fr[k, 1] != 2.0 + k}
    out: dict[int, tuple[int, dict[int, float]]] = {}
    for h in sorted(set(follows.values())):
        members = [h] + [k for k in sorted(follows) if follows[k] == h]
        W = inverse_mass(system, seg.t0, seg.y0, members)
        c = {k: float(W[i, 0] / W[0, 0]) for i, k in enumerate(members)}
        out.update({k: (h, c) for k in members})
    return out


def shares(group: tuple[int, dict[int, float]], pair: int, F: np.ndarray) -> np.ndarray:
    """``pair``'s share sign(c_i) F_i / sum_j abs(c_j) F_j of its group's multiplier (module docstring), F the normal
    forces (... x pairs); where the group bears no normal force, the holder's whole (1) and the followers' none."""
    holder, c = group
    total = sum(abs(ck) * F[..., k] for k, ck in c.items())
    whole = np.full(np.shape(total), 1.0 if pair == holder else 0.0)
    return np.divide(np.sign(c[pair]) * F[..., pair], total, out=whole, where=total > 0.0)


def friction_columns(system: BeamSystem, seg: Segment, times: np.ndarray, Y: np.ndarray, F: np.ndarray):
    """(tangential force, slip velocity, friction state), each samples x pairs, of segment ``seg`` at ``times``
    (states Y, the pairs' normal forces F): F_t = sigma F + lambda_t, a group's lambda shared among its pairs
    (:func:`shares`); the slip velocity of every pair in contact (0 for a free one); the state 0 (no frictional
    contact), 1 (slip) or 2 (stick)."""
    S = system.pairs
    Ft, vt, state = np.zeros((times.size, S)), np.zeros((times.size, S)), np.zeros((times.size, S))
    fr = seg.phase.friction
    grouped = groups(system, seg) if times.size else {}
    for k in range(S):
        if seg.phase.modes[k] == 0:
            continue
        vt[:, k] = [system.tangent(t, y, k)[2] for t, y in zip(times, Y)]
        if fr is None:
            continue
        sigma, stick = fr[k, 0], fr[k, 1]
        if stick < 0.0:  # the regularised law: [mu_k, -1, v_0]
            sigma = regularised(sigma, fr[k, 2], vt[:, k])
        Ft[:, k] = sigma * F[:, k]
        if k in grouped:
            Ft[:, k] += _multipliers(seg, grouped[k][0], times) * shares(grouped[k], k, F)
        elif stick == 1.0:
            Ft[:, k] += _multipliers(seg, k, times)
        state[:, k] = 2.0 if stick > 0.0 else (1.0 if fr[k, 0] != 0.0 or fr[k, 4] != 0.0 else 0.0)
    return Ft, vt, state


def tangential_impulse(system: BeamSystem, segments: list[Segment], t0: float, t1: float, pair: int) -> float:
    """int F_t dt of ``pair`` over the whole frictional phases inside [t0, t1] (each step's Gauss quadrature of its
    nodal sigma F + F_t, :meth:`~flexbeam.integrate.dense.ModalDense.tangential_impulse`; a group's pair its share of
    the nodal multiplier, :func:`shares`); NaN when no phase there had friction."""
    total, seen = 0.0, False
    for s in segments:
        if s.t0 < t0 or s.t1 > t1 or s.t1 <= s.t0 or s.phase.friction is None or s.phase.modes[pair] == 0:
            continue
        seen = True
        if s.dense is None or not hasattr(s.dense, "tangential_impulse"):
            continue
        law = s.phase.friction[pair, 1] < 0.0  # the regularised law: a nodal tangential unknown (kernels/src/nodal.c)
        group = groups(system, s).get(pair) if s.phase.friction[pair, 1] > 0.0 else None
        if group is not None:  # its share of the group's multiplier, node by node
            total += s.dense.shared_tangential_impulse(group[0], partial(shares, group, pair))
        else:
            total += s.dense.tangential_impulse(pair, 0.0 if law else float(s.phase.friction[pair, 0]))
    return total if seen else math.nan
