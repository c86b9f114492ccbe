"""A free beam's collision episodes found while a streamed run goes on (:mod:`flexbeam.results.stream`), the same as
:func:`~flexbeam.results.episodes.find_episodes` finds on the run held in memory.

The records are grouped as :func:`~flexbeam.results.episodes.group_episodes` groups them, each as soon as it is
logged: a record joins the open episode when its onset is less than the gap after the latest end of the episode's
records (an open record's end counts as infinite: it will end after the new onset), else the open episode closes --
no later record can join it -- and a new one opens.  What an episode needs of the run is read while the stream still
keeps it:

* the values at instants -- G's velocity and the spin before (the first onset) and after (the end t_1), the striking
  point's normal and lever arm frozen at the onset, each record's contact point (the one-point test) and a jump's
  normal velocities on either side -- once the stream has moved past the instant (every segment holding it is
  there); the stream keeps the segments from the earliest instant still to be read (:meth:`EpisodeStream.cut`), so
  at most the segment that holds it and the one after;
* the impulses and works of compression and restitution (:class:`~flexbeam.results.restitution.Phases`), from each
  segment as it leaves the stream, or at the episode's close, in the order in which the run held in memory sums them
  (record by record, each record's segments in time order): a long contact -- a bar resting on a floor -- is one
  open episode whose segments are summed and dropped as they go.

An episode's numbers are those of the run held in memory, bit for bit, but where a contact outlasts the steps the
stream keeps (:data:`~flexbeam.results.stream.WINDOW_RECORDS`) or a phase reaches it in parts
(:data:`~flexbeam.integrate.modal.BLOCK_RECORDS` steps each): then the records' impulses are summed part by part
(:mod:`flexbeam.results.long_contact`), and a jump at a long record's onset is summed with the impulse it has then --
a pair held in a resting contact takes a share of each later impact's impulse, which the run held in memory sums at
the record's onset -- and the rest added when the episode closes (the jump's impulse and work are linear in it): equal
to round-off (measured 2e-16 relative, ``tests/test_stream_free.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .episodes import STREAMED, default_gap, same_point
from .parts import as_whole, holding
from .restitution import Phases, RigidMotion, SegmentPiece, restitution_record

if TYPE_CHECKING:
    from ..integrate.loop import Segment
    from .stream import RunStream


class WindowMotion(RigidMotion):
    """:class:`~flexbeam.results.restitution.RigidMotion` on the segments the stream keeps, a phase handed on in
    parts evaluated as the whole phase is (:func:`~flexbeam.results.parts.holding`)."""

    def segment(self, t: float, after: bool) -> Segment:
        return holding(self.source.segments, t, after)


@dataclass
class OpenEpisode:
    """An episode while the run goes on: its records (indices) and what has been read of it."""

    records: list[int]
    pair: int
    onset: float
    strike: tuple[np.ndarray, float] | None = None  #: the frozen normal and lever arm
    before: np.ndarray | None = None  #: (v_Gx, v_Gy, Omega) before the onset
    v_before: float = math.nan
    acc: Phases | None = None
    positions: dict[int, float] = field(default_factory=dict)
    jumps: dict[int, tuple[float, float]] = field(default_factory=dict)
    #: the jumps added to ``acc``: record -> (its jump impulse then, 0 for none; compressing then)
    applied: dict[int, tuple[float, bool]] = field(default_factory=dict)
    unread: int = 0  #: the records before this one (in ``records``) are read
    running: list[int] = field(default_factory=list)  #: the records not known to have ended
    live: int = 0  #: the records before this one are summed whole
    closed: float = -math.inf  #: the latest onset or end of the records that have ended
    end: float = math.nan  #: t_1 when ``after`` was read
    after: tuple[np.ndarray, float] | None = None  #: (v_Gx, v_Gy, Omega) and v at t_1
    next: int = 0  #: the number of the next segment to sum


class EpisodeStream:
    """The collision episodes of a streamed free beam's run (see the module docstring): :meth:`update` after each
    segment (the records completed that ended before it), :meth:`cut` for the stream's trim, :meth:`absorb` for each
    segment it drops, :meth:`finish` at the end."""

    def __init__(self, stream: RunStream) -> None:
        self.stream = stream
        self.gap = default_gap(stream.system.beam)
        self.seen = 0  # the records grouped so far
        self.open: OpenEpisode | None = None
        self.found: list[dict[str, Any]] = []

    def _motion(self, ep: OpenEpisode, t_final: float = math.nan) -> WindowMotion:
        motion = WindowMotion(self.stream.source([s for _, s in self.stream.window], t_final))
        if ep.strike is not None:
            motion.normal, motion.lever, motion.t0 = ep.strike[0], ep.strike[1], ep.onset
        return motion

    def _latest(self, ep: OpenEpisode) -> float:
        """The latest end of ``ep``'s records (an open one's: inf), as :func:`group_episodes` takes it."""
        return math.inf if not self._ended(ep) else ep.closed

    def _end(self, ep: OpenEpisode, t_final: float) -> float:
        """t_1 as :func:`find_episodes` takes it at the run's end (an open record's end: ``t_final``)."""
        evs = [self.stream.contacts[i] for i in ep.records]
        ends = [ev.end if math.isfinite(ev.end) else t_final for ev in evs]
        return max(max(ends), evs[-1].onset)

    # ----------------------------------------------------------------- as the run goes on
    def update(self, now: float, t_final: float | None = None) -> None:
        """Group the records logged since the last call; read what the stream has moved past (before ``now``; all of
        it at the end, ``t_final``)."""
        contacts = self.stream.contacts
        while self.seen < len(contacts):
            ev = contacts[self.seen]
            ep = self.open
            if ep is not None and ev.onset - self._latest(ep) < self.gap:
                ep.records.append(self.seen)
                ep.running.append(self.seen)
            else:
                if ep is not None:
                    self._close(ep, now, math.nan)
                self.open = OpenEpisode([self.seen], ev.pair, ev.onset, running=[self.seen])
            self.seen += 1
        if self.open is not None:
            self._read(self.open, now, t_final)

    def _read(self, ep: OpenEpisode, now: float, t_final: float | None) -> None:
        """Read the instants of ``ep`` the stream has moved past (as :func:`apparent_restitution` and
        :func:`find_episodes` read them): the strike, each record's contact point and, on the striking pair, the
        normal velocities on either side of its onset (for a jump there, which a held pair may take later), t_1."""
        final = t_final is not None
        motion = self._motion(ep, math.nan if t_final is None else t_final)
        if ep.strike is None:
            if not (final or ep.onset < now):
                return
            motion.strike(ep.onset, ep.pair)
            ep.strike = (motion.normal, motion.lever)
            ep.v_before = motion.at(ep.onset, after=False)
            ep.before = motion.state(ep.onset, after=False)
            ep.acc = Phases(ep.v_before < 0.0, ep.onset)
        while ep.unread < len(ep.records):  # in the order of their onsets
            i = ep.records[ep.unread]
            ev = self.stream.contacts[i]
            if not (final or ev.onset < now):
                break
            ep.positions[i] = motion.contact_position(ev.onset, ev.pair)
            if ev.pair == ep.pair:
                ep.jumps[i] = (motion.at(ev.onset, after=False), motion.at(ev.onset, after=True))
            ep.unread += 1
        t1 = self._end(ep, t_final) if final else (ep.closed if self._ended(ep) else math.nan)
        if math.isfinite(t1) and t1 != ep.end and (final or t1 < now):
            ep.end, ep.after = t1, (motion.state(t1, after=True), motion.at(t1, after=True))

    def _ended(self, ep: OpenEpisode) -> bool:
        """Have all of ``ep``'s records ended?  (``ep.closed``: the latest onset or end of those that have.)"""
        contacts = self.stream.contacts
        running = []
        for i in ep.running:
            ev = contacts[i]
            if math.isfinite(ev.end):
                ep.closed = max(ep.closed, ev.end, ev.onset)
            else:
                running.append(i)
        ep.running = running
        return not running

    def cut(self) -> float:
        """The earliest instant of the open episode still to be read (inf: none): the stream keeps the segments from
        there on."""
        ep = self.open
        if ep is None:
            return math.inf
        times = [ep.onset] if ep.strike is None else []
        if ep.unread < len(ep.records):
            times.append(self.stream.contacts[ep.records[ep.unread]].onset)
        if self._ended(ep) and ep.closed != ep.end:  # t_1
            times.append(ep.closed)
        return min(times, default=math.inf)

    def absorb(self, number: int, seg: Segment, t_final: float = math.nan) -> None:
        """Add segment ``number`` (each once, in order) to the open episode's impulses and works: its jumps and the
        striking pair's force over each of its records (as :func:`apparent_restitution` sums them)."""
        ep = self.open
        if ep is None or number < ep.next:
            return
        ep.next = number + 1
        if ep.acc is None:  # a segment before the onset
            return
        motion = self._motion(ep, t_final)
        contacts = self.stream.contacts
        while ep.live < len(ep.records) and self._past(ep, ep.records[ep.live], seg.t0):
            ep.live += 1
        for i in ep.records[ep.live :]:
            ev = contacts[i]
            if ev.onset > seg.t1:  # nor any later record
                break
            if ev.pair != ep.pair:
                continue
            if i not in ep.applied:
                J = 0.0 if math.isnan(ev.jump_impulse) else ev.jump_impulse
                ep.applied[i] = (J, ep.acc.compressing)
                if not math.isnan(ev.jump_impulse):
                    ep.acc.jump(ev.onset, J, *ep.jumps[i])
            end = ev.end if math.isfinite(ev.end) else (t_final if math.isfinite(t_final) else math.inf)
            if end > ev.onset and seg.phase.modes[ep.pair] != 0 and seg.t1 > seg.t0 and seg.t0 <= end:
                piece = SegmentPiece(motion, as_whole(seg), ep.pair)
                ep.acc.steps(piece, max(ev.onset, seg.t0), min(end, seg.t1))

    def _past(self, ep: OpenEpisode, i: int, t: float) -> bool:
        """Is record ``i`` summed whole before t (ended before it, its jump summed)?"""
        ev = self.stream.contacts[i]
        return math.isfinite(ev.end) and ev.end < t and (ev.pair != ep.pair or i in ep.applied)

    def _close(self, ep: OpenEpisode, now: float, t_final: float) -> None:
        """Sum the kept segments into ``ep`` and keep its numbers (its records are completed: they ended before
        ``now``, or the run did)."""
        self._read(ep, now, None if math.isnan(t_final) else t_final)
        for number, seg in self.stream.window:
            self.absorb(number, seg, t_final)
        self._held_impulses(ep)
        assert ep.acc is not None and ep.before is not None and ep.after is not None, "an episode read whole"
        evs = [self.stream.contacts[i] for i in ep.records]
        same = all(ev.pair == ep.pair for ev in evs) and same_point(
            [ep.positions[i] for i in ep.records], self.stream.system.beam.length
        )
        after, v_after = ep.after
        coeffs = restitution_record(ep.acc, evs, ep.pair, ep.v_before, v_after, same)
        self.found.append(
            {
                "records": tuple(ep.records),
                "pair": ep.pair,
                "onset": ep.onset,
                "end": ep.end,
                "before": ep.before,
                "after": after,
                "coeffs": coeffs,
            }
        )
        self.open = None

    def _held_impulses(self, ep: OpenEpisode) -> None:
        """Add what a record's jump impulse gained after its jump was summed -- a pair held in a resting contact takes
        a share of every later impact's impulse (:meth:`~flexbeam.methods.base.ImpactMethod.held_impact`), which the
        run held in memory sums at the record's onset --: the jump's impulse and work are linear in it, so the sum
        is that of the whole impulse to round-off (only a long contact's jump is summed before its end)."""
        assert ep.acc is not None
        for i, (J, compressing) in ep.applied.items():
            ev = self.stream.contacts[i]
            J_now = 0.0 if math.isnan(ev.jump_impulse) else ev.jump_impulse
            if J_now != J:
                more = Phases(compressing, ev.onset)
                more.jump(ev.onset, J_now - J, *ep.jumps[i])
                for phase in (0, 1):
                    ep.acc.add(phase, more.P[phase], more.W[phase])

    def finish(self, t_final: float) -> tuple[float, list[dict[str, Any]]]:
        """Close the open episode at the run's end (every record completed); the episodes found, as
        :data:`~flexbeam.results.episodes.STREAMED` holds them."""
        self.update(math.inf, t_final)
        if self.open is not None:
            self._close(self.open, math.inf, t_final)
        return self.gap, self.found


__all__ = ["STREAMED", "EpisodeStream", "OpenEpisode", "WindowMotion"]
