"""One branch of a bifurcation diagram: a moving-base case run at a sequence of drive frequencies, each run continuing
from the state the previous one reached (numerical continuation by sweeping, as in experiments: up and down the
frequency, so that coexisting responses and their hysteresis show; Wagg & Bishop, J. Sound Vib. 256 (2002) 803).

At each frequency f the run lasts ``periods`` drive periods; the first ``discard`` of them are the transient.  Its
Poincaré section (:mod:`flexbeam.results.poincare`) at the drive phase ``phase`` gives the tip's deflection and the
contact point's normal velocity once per period, its contact records the impact velocities and their phases of the
drive.  The next frequency starts from the state at the last section in free flight (gap > 0), so that no run starts
inside an obstacle, with the harmonics' phases advanced so that its start is at the same phase of the drive: the
base's motion continues in phase and the sections of every run lie at that phase.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..parameters.case import Case
from ..results.poincare import drive_phase, poincare

#: the Zeno guard (solver.max_contacts) of a point allows at least this many contact records per drive period
CONTACTS_PER_PERIOD = 20


@dataclass
class Point:
    """The response at one drive frequency of a branch."""

    frequency: float
    status: str
    message: str
    #: the Poincaré section after the transient: tip deflection [m] and the contact point's normal velocity [m/s]
    tip: np.ndarray = field(default_factory=lambda: np.zeros(0))
    velocity: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: the contact records after the transient: approach velocity [m/s] (negative approaching) and phase of the drive
    impact_velocity: np.ndarray = field(default_factory=lambda: np.zeros(0))
    impact_phase: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: the largest absolute tip deflection after the transient (the frequency response) [m]
    amplitude: float = math.nan
    #: the state the next frequency starts from (None: the branch cannot continue)
    state: np.ndarray | None = None

    def record(self) -> dict[str, Any]:
        """A JSON-able dict of the point (the store's file)."""
        return {
            "frequency": self.frequency, "status": self.status, "message": self.message,
            "tip": self.tip.tolist(), "velocity": self.velocity.tolist(),
            "impact_velocity": self.impact_velocity.tolist(), "impact_phase": self.impact_phase.tolist(),
            "amplitude": self.amplitude, "state": None if self.state is None else self.state.tolist(),
        }  # fmt: skip

    @classmethod
    def from_record(cls, r: dict[str, Any]) -> Point:
        arrays = ("tip", "velocity", "impact_velocity", "impact_phase")
        state = None if r["state"] is None else np.asarray(r["state"], float)
        return cls(r["frequency"], r["status"], r["message"], *(np.asarray(r[k], float) for k in arrays),
                   r["amplitude"], state)  # fmt: skip


def shifted(case: Case, frequency: float, phase: float) -> Case:
    """``case`` driven at ``frequency`` for its length, its harmonics' phases advanced by 2 pi k ``phase`` (a run that
    starts at that phase of the drive)."""
    base = case.base
    harmonics = [h.model_copy(update={"phase": h.phase + 2.0 * math.pi * h.order * phase}) for h in base.harmonics]
    return case.model_copy(update={"base": base.model_copy(update={"frequency": frequency, "harmonics": harmonics})})


def run_point(case: Case, method: str, frequency: float, periods: int, discard: int, phase: float,
              state: np.ndarray | None, simulate: Callable[..., Any]) -> Point:  # fmt: skip
    """The response at ``frequency`` over ``periods`` periods from ``state`` (None: the case's own start at phase 0
    of the drive, sampled at ``phase``; else a start at ``phase``, sampled at its own phase 0)."""
    start = 0.0 if state is None else phase
    run_case = shifted(case, frequency, start)
    # the Zeno guard scaled to the run's length: a stop struck a few times per period for hundreds of periods is
    # not an accumulation of contacts (at least CONTACTS_PER_PERIOD per period, or the case's own limit if larger)
    limit = max(case.solver.max_contacts, CONTACTS_PER_PERIOD * periods)
    solver = run_case.solver.model_copy(update={"t_end": periods / frequency, "max_contacts": limit})
    run_case = run_case.model_copy(update={"solver": solver})
    sol = simulate(run_case, method, state=state)
    local = (phase - start) % 1.0
    sec = poincare(sol, phase=local, discard=discard) if sol.source is not None else None
    point = Point(frequency, sol.status, sol.message)
    if sec is None or sec["time"].size == 0:
        return point
    point.tip, point.velocity = sec["tip_deflection"], sec["normal_velocity"]
    t_discard = discard / frequency
    late = [c for c in sol.records if c.onset >= t_discard]
    point.impact_velocity = np.array([c.velocity_before for c in late], float)
    point.impact_phase = np.array([drive_phase(c.onset, frequency) + start for c in late], float) % 1.0
    # the frequency response: the largest |tip deflection| after the transient, located on the dense output (the
    # Poincaré samples are one phase of each period: they miss the peaks unless the section happens to meet them)
    low, high = sol.source.extremes("tip_deflection", window=(t_discard, run_case.solver.t_end))
    point.amplitude = max(-low, high)
    free = np.nonzero(sec["gap"] > 0.0)[0]
    if sol.status == "success" and free.size:
        t_next = float(sec["time"][free[-1]])
        seg = next(s for s in sol.source.segments if s.t0 <= t_next <= s.t1)
        y = np.array(seg.states(np.array([t_next]))[0], float)
        y[-2:] = 0.0  # E_d and W start again at zero
        point.state = y
    return point


def branch(case: Case, method: str, frequencies: Iterable[float], periods: int, discard: int, phase: float,
           simulate: Callable[..., Any], done: list[Point] | None = None) -> Iterator[Point]:  # fmt: skip
    """The points of one branch in the order of ``frequencies``, each continuing from the previous one's state;
    ``done``: the points already computed (a resumed branch), which are yielded as they are."""
    state = None
    done = done or []
    for i, f in enumerate(frequencies):
        if i < len(done):
            point = done[i]
        else:
            point = run_point(case, method, f, periods, discard, phase, state, simulate)
        state = point.state if point.state is not None else state
        yield point
