"""Collision episodes of a free beam (``joint.kind = "free"``): which contact records make one collision, and what
the collision did to the beam's rigid-body motion (docs/free-beam.md, *Collision episodes*).

An **episode** is a maximal group of contact records -- micro-impacts included (:mod:`flexbeam.results.counts`) --
in which each record begins less than ``gap`` of free flight after the end of every record before it in the group.
The default gap is one period T_1 of the beam's first free-free bending mode (:func:`default_gap`): a bar whose
vibration brings a struck end back to the ground does so within the period of its slowest mode, while the next
collision of a bouncing bar comes after a flight of order (rebound speed) / g, hundreds of T_1 later.

Per episode: the velocity of G and the spin before (at the first record's onset, before any jump) and after (at the
last record's end); and the apparent coefficients of restitution of Newton, Poisson and Stronge
(:mod:`flexbeam.results.restitution`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from .restitution import FREE_FREE_ROOT as FREE_FREE_ROOT
from .restitution import Motion, RigidMotion, apparent_restitution, free_free_period

if TYPE_CHECKING:
    from ..model.beam import ModalBeam
    from .counts import ContactCounts
    from .records import ContactEvent
    from .solution import Solution

#: the default gap of free flight that ends an episode, in periods of the first free-free bending mode
GAP_PERIODS = 1.0
#: the apparent coefficients are given when every record of an episode strikes within this share of L of the first
#: record's contact point on the same pair (else null: no one point of the rigid body describes the collision)
SAME_POINT = 0.1


def first_free_free_period(beam: ModalBeam) -> float:
    """T_1 = 2 pi / ((beta_1 L)^2 sqrt(EI / (mu L^4))) [s]: the continuum's first free-free bending period, whatever
    ``model.modes`` is (so that a rigid model and a flexible one of the same bar group their records alike)."""
    return free_free_period(beam.length, beam.bending_stiffness, beam.line_density)


def default_gap(beam: ModalBeam) -> float:
    """The default gap of free flight that separates two episodes: :data:`GAP_PERIODS` x T_1 [s]."""
    return GAP_PERIODS * first_free_free_period(beam)


def group_episodes(onsets: Sequence[float], ends: Sequence[float], gap: float) -> list[list[int]]:
    """Group records (in the order of their onsets) into episodes: record i joins the open episode when its onset
    is less than ``gap`` after the latest end of that episode's records (an end that is NaN -- the run ended during
    the contact -- never closes it)."""
    groups: list[list[int]] = []
    latest = -math.inf
    for i, (t0, t1) in enumerate(zip(onsets, ends)):
        if groups and t0 - latest < gap:
            groups[-1].append(i)
        else:
            groups.append([i])
            latest = -math.inf
        latest = max(latest, t1 if math.isfinite(t1) else math.inf, t0)
    return groups


@dataclass(frozen=True)
class Episode:
    """One collision episode of a free beam (SI units; see the module docstring and
    :mod:`flexbeam.results.restitution`).

    ``records``: indices in :attr:`Solution.contacts <flexbeam.results.solution.Solution.contacts>`;
    ``velocity_before``/``velocity_after``: G's (x, y) velocity; ``spin_*``: p_theta / J_G, the spin of the rigid
    body with the beam's angular momentum about G; ``normal_velocity_*``: the striking point's normal velocity in
    that rigid-body motion, the contact forces' share alone (gravity's m g t taken out); ``compression_end``: when it
    reached zero (NaN: never); impulses [N s] and works [J] of the striking pair's normal force in compression and
    restitution.
    """

    index: int
    records: tuple[int, ...]
    pair: int
    onset: float
    end: float
    contacts: int
    micro_impacts: int
    velocity_before: tuple[float, float]
    velocity_after: tuple[float, float]
    spin_before: float
    spin_after: float
    normal_velocity_before: float
    normal_velocity_after: float
    compression_end: float
    compression_impulse: float
    restitution_impulse: float
    compression_work: float
    restitution_work: float
    restitution_newton: float
    restitution_poisson: float
    restitution_energetic: float

    @property
    def impulse(self) -> float:
        """The striking pair's whole impulse over the episode [N s]."""
        return self.compression_impulse + self.restitution_impulse

    def record(self, labels: Sequence[str]) -> dict[str, Any]:
        """The episode as one entry of the metrics' ``episodes`` (``obstacle``: the pair's label)."""
        return {
            "index": self.index,
            "records": list(self.records),
            "pair": self.pair,
            "obstacle": labels[self.pair],
            "onset": self.onset,
            "end": self.end,
            "duration": self.end - self.onset,
            "contact_records": len(self.records),
            "contacts": self.contacts,
            "micro_impacts": self.micro_impacts,
            "velocity_before": list(self.velocity_before),
            "velocity_after": list(self.velocity_after),
            "spin_before": self.spin_before,
            "spin_after": self.spin_after,
            "normal_velocity_before": self.normal_velocity_before,
            "normal_velocity_after": self.normal_velocity_after,
            "compression_end": self.compression_end,
            "impulse": self.impulse,
            "compression_impulse": self.compression_impulse,
            "restitution_impulse": self.restitution_impulse,
            "compression_work": self.compression_work,
            "restitution_work": self.restitution_work,
            "restitution_newton": self.restitution_newton,
            "restitution_poisson": self.restitution_poisson,
            "restitution_energetic": self.restitution_energetic,
        }


def is_free(sol: Solution) -> bool:
    """Is the run's beam a free one (a run with a dense output and ``joint.kind = "free"``, a streamed one whose
    episodes were found as it went, or a Solution given its rigid-body motion: the finite-element reference's free
    beam)?"""
    if sol.source is not None:
        return sol.source.system.joint.kind == "free"
    return sol.motion is not None or STREAMED in sol.summaries


#: the key of a streamed run's episodes in :attr:`Solution.summaries` (:mod:`flexbeam.results.episode_stream`):
#: ``(gap, [found, ...])``, each found episode the keyword arguments of :func:`make_episode` but ``index`` and
#: ``counts``
STREAMED = "episodes"


def rigid_motion(sol: Solution) -> Motion | None:
    """The rigid-body motion of a free beam's Solution (:func:`is_free`), else None."""
    if not is_free(sol) or (sol.source is None and sol.motion is None):
        return None
    return RigidMotion(sol.source) if sol.source is not None else sol.motion


def find_episodes(sol: Solution, counts: ContactCounts, gap: float | None = None) -> list[Episode]:
    """The collision episodes of a free beam's run (:func:`group_episodes` with ``gap``, default
    :func:`default_gap`) with their rigid-body velocities and apparent restitution; [] for any other run.  A streamed
    run's were found as it went, with the default gap (another gap: a ValueError)."""
    if sol.source is None and STREAMED in sol.summaries:
        found_gap, found = sol.summaries[STREAMED]
        if gap is not None and float(gap) != found_gap:
            raise ValueError(f"episodes: a streamed run's episodes were found with gap = {found_gap:g} s only")
        return unfinished_open(sol, [make_episode(k, counts, **one) for k, one in enumerate(found)])
    motion = rigid_motion(sol)
    if motion is None:
        return []
    gap = GAP_PERIODS * motion.period if gap is None else float(gap)
    records = sol.contacts
    ends = [ev.end if math.isfinite(ev.end) else math.nan for ev in records]
    out = []
    for k, group in enumerate(group_episodes([ev.onset for ev in records], ends, gap)):
        first, last = records[group[0]], records[group[-1]]
        t1 = max((ev.end if math.isfinite(ev.end) else motion.t_final) for ev in (records[i] for i in group))
        t1 = max(t1, last.onset)
        same = _one_point(motion, [records[i] for i in group])
        coeffs = apparent_restitution(motion, [records[i] for i in group], first.pair, first.onset, t1, same)
        before, after = motion.state(first.onset, after=False), motion.state(t1, after=True)
        out.append(make_episode(k, counts, tuple(group), first.pair, first.onset, t1, before, after, coeffs))
    return unfinished_open(sol, out)


def unfinished_open(sol: Solution, episodes: list[Episode]) -> list[Episode]:
    """``episodes`` with those the run ended in -- one of its records still in contact at the run's end, or the last
    episode of a run that stopped before ``solver.t_end`` -- given no end and no apparent coefficients (NaN): the
    collision is not over, and its "after" is only the run's last state (a rod still pressed on the plane at the
    run's end read e_N = -0.04, and IMM's stopped at max-contacts, G still moving into the floor, e_N = -0.82)."""
    records = sol.contacts
    stopped = sol.status != "success"
    out = []
    for ep in episodes:
        last = ep is episodes[-1]
        if any(not math.isfinite(records[i].end) for i in ep.records) or (last and stopped):
            nan = math.nan
            ep = replace(ep, end=nan, restitution_newton=nan, restitution_poisson=nan, restitution_energetic=nan)
        out.append(ep)
    return out


def make_episode(
    index: int,
    counts: ContactCounts,
    records: tuple[int, ...],
    pair: int,
    onset: float,
    end: float,
    before: Sequence[float],
    after: Sequence[float],
    coeffs: dict[str, Any],
) -> Episode:
    """Episode ``index`` of ``records`` (indices), striking ``pair`` from ``onset`` to ``end``, with G's velocity
    and the spin ``before`` and ``after`` ((v_Gx, v_Gy, Omega)), the counts of the run's records and the apparent
    restitution ``coeffs`` (:func:`~flexbeam.results.restitution.apparent_restitution`)."""
    micro = sum(counts.micro[i] for i in records)
    return Episode(
        index=index,
        records=tuple(records),
        pair=pair,
        onset=onset,
        end=end,
        contacts=len(records) - micro,
        micro_impacts=micro,
        velocity_before=(float(before[0]), float(before[1])),
        velocity_after=(float(after[0]), float(after[1])),
        spin_before=float(before[2]),
        spin_after=float(after[2]),
        **coeffs,
    )


def _one_point(motion: Motion, records: list[ContactEvent]) -> bool:
    """Do all ``records`` strike the first one's pair within :data:`SAME_POINT` L of its point?"""
    pair = records[0].pair
    if any(ev.pair != pair for ev in records):
        return False
    return same_point([motion.contact_position(ev.onset, pair) for ev in records], motion.length)


def same_point(xs: Sequence[float], length: float) -> bool:
    """Are the contact points ``xs`` (material coordinates [m], on one pair) within :data:`SAME_POINT` ``length`` of
    the first?"""
    return all(abs(x - xs[0]) <= SAME_POINT * length for x in xs)
