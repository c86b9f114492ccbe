"""What an FE run records besides its samples: the contact log, the dense contact data, and the run's status and
statistics."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..results.records import ContactEvent
from .beam import FemBeam
from .integrator import State
from .pairs import ContactState


@dataclass
class Record:
    """Contact log and dense contact data of one run (the samples go to ``sample``)."""

    contacts: list[ContactEvent] = field(default_factory=list)
    # dense force on contact steps, per pair in contact: (t0, t1, (d, d', d'')_0, (d, d', d'')_1, lawp, pair)
    dense: list[tuple] = field(default_factory=list)

    def add_contact_step(self, beam: FemBeam, s0: State, s1: State, cs: ContactState) -> None:
        """Store the dense-force data of a contact step for each pair in contact: its gap's (delta, delta',
        delta'') at both ends."""
        if beam.npairs == 1:
            g0 = beam.gap(s0.z, s0.zd, s0.zdd)[:3]
            g1 = beam.gap(s1.z, s1.zd, s1.zdd)[:3]
            self.dense.append((s0.t, s1.t, g0, g1, cs.laws[0], 0))
            return
        gaps0 = beam.gaps(s0.z, s0.zd, s0.zdd)
        gaps1 = beam.gaps(s1.z, s1.zd, s1.zdd)
        for k, p in enumerate(cs.laws):
            if p is not None:
                self.dense.append((s0.t, s1.t, gaps0[k][:3], gaps1[k][:3], p, k))


@dataclass
class RunInfo:
    """Status, statistics and the step sizes used by :func:`flexbeam.fem.eventdriven.run`."""

    status: str
    message: str
    steps: int
    rejected: int
    iterations: int
    wall_time: float
    h_contact: float
    h_free: float
