"""What one contact is: a run's contact records sorted into contacts and micro-impacts (docs/methods.md,
*What one contact is*).

The impact methods log one record per located contact of a pair (onset to end; IMM: an instantaneous impact,
``end == onset``, or a resting contact).  An IMM Zeno sequence -- impacts whose speeds shrink by e each time,
down to ``solver.rest_velocity`` -- logs dozens of them in a fraction of a millisecond, and how many depends on
``solver.rest_velocity`` and on the round-off of the trajectory, not on the physics.  So the number of records is
not a count that means something; this module defines one that does:

* a **micro-impact** is a record of a pair whose impulse *and* approach speed are both below
  :data:`MICRO_IMPACT_FRACTION` (1 %) of the largest impulse and the largest approach speed among that pair's
  records in the run;
* every other record is a **contact** (a record whose impulse or approach speed is unknown -- NaN -- counts as a
  contact: it cannot be shown to be negligible);
* a **chatter episode** is a maximal run of consecutive micro-impacts of one pair (consecutive among that pair's
  records; a lone micro-impact is an episode of one).  Episodes are numbered 0, 1, ... over the run in the order
  of their first record.

Either measure alone would fail somewhere.  Approach speed alone calls a CCM contact that starts slowly but is then
loaded by the vibrating beam a micro-impact (the seed case's largest CCM impulse comes from a record that
approaches at 2 mm/s); impulse alone lets a long resting contact, whose impulse grows with its duration, turn
every impact before it into a micro-impact (the seed beam resting on its stop under gravity bears
m g x_G / x_P = 7.5 N: 7.5 N s per second of rest, a hundred times its largest IMM impact).  A record is
negligible only when it is both slow and weak.

A count changes only when a record's impulse or approach speed crosses its threshold: a change of a record's
impulse in its last bits changes no count unless the record lies within that change of the threshold.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

#: a record is a micro-impact when its impulse and its approach speed are both below this share of the largest
#: of its pair: an impact at 1 % of the largest approach speed carries 1e-4 of its kinetic energy and, under a
#: Hertz law (F_max ~ v^(6/5)), 0.4 % of its peak force.  A Zeno sequence of restitution e that starts with the
#: pair's largest impact has floor(ln(0.01) / ln(e)) + 1 contacts (21 for e = 0.8), set by e alone as long as
#: ``solver.rest_velocity`` stays below 1 % of its first speed; the rest are micro-impacts
MICRO_IMPACT_FRACTION = 0.01

#: ``kind`` of a record: a contact or a micro-impact
CONTACT, MICRO_IMPACT = "contact", "micro-impact"


@dataclass(frozen=True)
class ContactCounts:
    """The records of a run sorted into contacts and micro-impacts.

    Attributes
    ----------
    pairs
        Contact pair of each record.
    micro
        Whether each record is a micro-impact.
    episode
        Chatter episode of each record (None for a contact).
    n_pairs
        Number of contact pairs of the case.
    """

    pairs: tuple[int, ...]
    micro: tuple[bool, ...]
    episode: tuple[int | None, ...]
    n_pairs: int

    def kind(self, i: int) -> str:
        """``"contact"`` or ``"micro-impact"`` for record ``i``."""
        return MICRO_IMPACT if self.micro[i] else CONTACT

    def of_pair(self, pair: int | None = None) -> dict[str, int]:
        """``contacts``, ``contact_records``, ``micro_impacts`` and ``chatter_episodes`` of one pair (None: the
        whole run)."""
        sel = [i for i, k in enumerate(self.pairs) if pair is None or k == pair]
        micro = sum(self.micro[i] for i in sel)
        return {
            "contacts": len(sel) - micro,
            "contact_records": len(sel),
            "micro_impacts": micro,
            "chatter_episodes": len({self.episode[i] for i in sel} - {None}),
        }


def _below(value: float, largest: float, fraction: float) -> bool:
    """Is ``value`` below ``fraction`` x ``largest``?  False when either is NaN or ``largest`` is not positive
    (nothing to compare against)."""
    return largest > 0.0 and value < fraction * largest


def classify_contacts(
    pairs: Sequence[int],
    impulses: Sequence[float],
    approach_speeds: Sequence[float],
    n_pairs: int | None = None,
    fraction: float = MICRO_IMPACT_FRACTION,
) -> ContactCounts:
    """Sort contact records into contacts and micro-impacts and group the micro-impacts into chatter episodes
    (the definition of the module docstring; docs/methods.md, *What one contact is*).

    Parameters
    ----------
    pairs
        Contact pair of each record, the records in the order of their onsets.
    impulses
        Impulse of each record [N s].
    approach_speeds
        Normal speed of approach of each record, -delta' before its onset [m/s].
    n_pairs
        Number of contact pairs of the case (default: one more than the largest pair of a record).
    fraction
        Threshold share of the pair's largest impulse and approach speed (:data:`MICRO_IMPACT_FRACTION`).

    Returns
    -------
    ContactCounts
    """
    if not len(pairs) == len(impulses) == len(approach_speeds):
        raise ValueError("classify_contacts: pairs, impulses and approach_speeds differ in length")
    pairs = tuple(int(k) for k in pairs)
    n = max(pairs, default=-1) + 1 if n_pairs is None else int(n_pairs)

    def largest(values: Sequence[float], k: int) -> float:
        finite = [float(v) for v, p in zip(values, pairs) if p == k and math.isfinite(v)]
        return max(finite, default=math.nan)

    big_j = {k: largest(impulses, k) for k in set(pairs)}
    big_v = {k: largest(approach_speeds, k) for k in set(pairs)}
    micro = tuple(
        _below(float(j), big_j[k], fraction) and _below(float(v), big_v[k], fraction)
        for k, j, v in zip(pairs, impulses, approach_speeds)
    )
    episode: list[int | None] = [None] * len(pairs)
    open_episode: dict[int, int | None] = {}
    count = 0
    for i, (k, m) in enumerate(zip(pairs, micro)):
        if not m:
            open_episode[k] = None
            continue
        if open_episode.get(k) is None:
            open_episode[k] = count
            count += 1
        episode[i] = open_episode[k]
    return ContactCounts(pairs, micro, tuple(episode), n)
