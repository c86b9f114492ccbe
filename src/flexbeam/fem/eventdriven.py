"""The event-driven run of the finite-element beam: contact phases, located events, step sizes.

Contact
-------
Each contact pair (a point of the beam against an obstacle under its law; pair 0 is P
against ``[obstacle]``, one more per ``[[obstacles]]`` entry) has its own phases.
As in the modal CCFM path the contact force acts only in a contact phase, which
starts when the gap delta of P crosses zero downwards with P approaching, and ends
when it crosses zero upwards.  A step whose end state has crossed is cut back to the
crossing, and a free step is checked for a grazing dip inside it
(:mod:`flexbeam.fem.event_location`).

Step size
---------
``fem.time_step``, else h_c = t_c / 200 in contact and h_f = 2 h_c in free flight
from the Hertz contact duration t_c (:mod:`flexbeam.fem.step_size`).  A step whose
Newton iteration fails is halved and retried (down to 2^-30 of the nominal step).
The onset/separation tolerance on |delta| is 1e-3 |delta'| h_c, i.e. the contact
instants are located to ~1e-3 of a contact step.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np
from scipy.linalg import solve_banded

from ..errors import SolverError
from ..interrupt import interrupted_message
from ..results.records import ContactEvent
from .banded import BAND, fix_first_dof
from .beam import FemBeam
from .event_location import crossing_candidates, first_crossing, locate_crossing
from .gap import hermite_dip
from .integrator import FemIntegrator, NewtonFailure, State, StepResult
from .pairs import ContactState
from .run_record import Record, RunInfo
from .step_size import contact_step, initial_step_sizes

#: contact onsets with |delta'| below this are grazing touches, not impacts [m/s]
GRAZING_SPEED = 1e-9
#: how many halvings of a failing step before giving up
MAX_HALVINGS = 30
#: the onset/separation tolerance on |delta|, in units of |delta'| h_c
LOCATE_TOLERANCE = 1e-3

Sampler = Callable[[State, StepResult, str, ContactState], None]


def run(
    beam: FemBeam,
    integ: FemIntegrator,
    z0: np.ndarray,
    zd0: np.ndarray,
    t_end: float,
    sample: Sampler,
    progress: Callable[[float], None] | None = None,
    stop_at_impact: bool = False,
    stop: Callable[[], str] | None = None,
) -> tuple[Record, RunInfo, State]:
    """Integrate from (z0, zd0) at t = 0 to ``t_end``, recording samples.

    ``sample(state, result, phase, contacts)`` is called at every accepted state (twice
    at a change of the contact state, once before and once after; ``contacts`` is the
    :class:`~flexbeam.fem.pairs.ContactState` -- which pairs are in contact, under which
    law parameters; the phase is "contact" while some pair is).  With ``stop_at_impact``
    the run ends at the first contact onset of any pair (status "impact").  ``stop``: asked after each accepted
    step for a cause that ends the run there ("Ctrl-C", :mod:`flexbeam.interrupt`; "" goes on), with status
    "interrupted" and what was computed.

    Each pair k has its own contact phase, which starts when its gap delta_k crosses zero
    downwards with its point approaching and ends when delta_k crosses zero upwards.
    When several pairs have an event within one step, the step is cut back to the one
    whose linear (or, for a dip, Hermite) estimate of the crossing comes first; a pair
    found already past its crossing at a located event is switched there too.  The step
    is the contact step h_c while any pair is in contact (the smallest of the open
    pairs' estimates), else h_f.
    """
    loop = _EventLoop(beam, integ, sample, initial_step_sizes(beam, z0, t_end), stop_at_impact)
    s = integ.initial(0.0, z0, zd0, None)
    res = integ.evaluate(s, None)
    _warm_up(integ, s, loop.h_c)
    wall0 = time.perf_counter()
    status, message = "success", "integration reached t_end"
    try:
        loop.start(s, res)
        loop.integrate(t_end, progress, stop)
    except _Stop as ended:
        status, message = ended.status, ended.message
    except SolverError as err:
        status, message = "failed", str(err)
    wall = time.perf_counter() - wall0
    info = RunInfo(status, message, loop.steps, loop.rejected, integ.iterations, wall, loop.h_c, loop.h_free)
    return loop.rec, info, loop.s


class _EventLoop:
    """One run's state between its steps: the accepted state ``s`` and its outputs ``res``, which pairs are in
    contact (``cs``, with their open ``events``), the step sizes, the contact log ``rec`` and the counts."""

    def __init__(
        self,
        beam: FemBeam,
        integ: FemIntegrator,
        sample: Sampler,
        sizes: tuple[float, float, list[float]],
        stop_at_impact: bool,
    ) -> None:
        self.beam, self.integ, self.sample, self.stop_at_impact = beam, integ, sample, stop_at_impact
        self.h_c, self.h_free, self.m_ref = sizes
        self.h_fixed = beam.case.fem.time_step
        self.h_now = self.h_c
        self.rec = Record()
        self.cs = beam.free_state
        self.events: list[ContactEvent | None] = [None] * beam.npairs
        self.steps = self.rejected = 0
        self.s: State | None = None
        self.res: StepResult | None = None

    # ------------------------------------------------------------ the loop
    def start(self, s: State, res: StepResult) -> None:
        """Take (s, res) as the first state: the pairs touching and approaching there start their contact."""
        self.s, self.res = s, res
        started = False
        for k in range(self.beam.npairs):
            if res.pair_gap[k] <= 1e-15 and res.pair_gap_rate[k] < -GRAZING_SPEED:
                self.open_pair(k)
                started = True
        if started:
            self.res = self.integ.evaluate(self.s, self.cs)
        self.sample(self.s, self.res, _phase(self.cs), self.cs)

    def integrate(
        self, t_end: float, progress: Callable[[float], None] | None, stop: Callable[[], str] | None = None
    ) -> None:
        """Step to ``t_end``, each step cut back to the first contact event in it; ``stop``: see :func:`run`."""
        next_progress = 0.0
        while self.s.t < t_end * (1.0 - 1e-12):
            trial = self._trial_step(t_end)
            if trial is None:
                continue
            s1, h = trial
            ends = [(d, vn) for d, vn, _, _ in self.beam.gaps(s1.z, s1.zd, s1.zdd)]
            candidates = crossing_candidates(self.res.pair_gap, self.res.pair_gap_rate, ends, self.cs, h)
            hit = first_crossing(self.beam, self.integ, self.s, s1, ends, h, candidates, self.cs)
            if hit is not None:
                self._event(*hit, end_rate=ends[hit[0]][1])
                continue
            self._accept(s1)
            if stop is not None and self.s.t < t_end * (1.0 - 1e-12) and (cause := stop()):
                raise _Stop("interrupted", interrupted_message(self.s.t, cause))
            if progress is not None and self.s.t >= next_progress:
                progress(self.s.t)
                next_progress = self.s.t + t_end / 200.0

    def _trial_step(self, t_end: float) -> tuple[State, float] | None:
        """A step of the nominal size (h_c in contact, else h_f) from ``s``, or after a failed Newton iteration
        None and the next try halved."""
        h_nom = self.h_c if self.cs.any else self.h_free
        h = min(self.h_now, h_nom, t_end - self.s.t)
        try:
            s1 = self.integ.step(self.s, h, self.cs)
        except NewtonFailure as err:
            self.rejected += 1
            self.h_now = 0.5 * h
            if self.h_now < h_nom * 2.0**-MAX_HALVINGS:
                raise SolverError(f"fem: step failed ({err}); step size underflow", self.s.t) from None
            return None
        self.h_now = h_nom
        return s1, h

    def _event(self, k: int, s_hit: State, d1: float, h_hit: float, end_rate: float) -> None:
        """Pair k's gap crosses zero before ``s_hit`` (gap ``d1``, a step ``h_hit`` from ``s``): locate the crossing,
        accept the state there and switch the pair (and any other found past its own crossing)."""
        d0, v0 = float(self.res.pair_gap[k]), float(self.res.pair_gap_rate[k])
        tol = max(LOCATE_TOLERANCE * max(abs(v0), abs(end_rate), 1e-6) * self.h_c, 1e-15)
        if self.cs.laws[k] is None:
            self._accept(locate_crossing(self.beam, self.integ, self.s, d0, s_hit, d1, h_hit, 1.0, self.cs, tol, k))
            if self.res.pair_gap_rate[k] < -GRAZING_SPEED:
                self.open_pair(k)
                self._resample()
        else:
            self._accept(locate_crossing(self.beam, self.integ, self.s, -d0, s_hit, -d1, h_hit, -1.0, self.cs, tol, k))
            self.close_pair(k)
            self._resample()
        self._switch_others(k)

    def _accept(self, s1: State) -> None:
        """Accept ``s1``: its outputs, the dense data of a contact step, a sample."""
        res1 = self.integ.evaluate(s1, self.cs)
        if self.cs.any:
            self.rec.add_contact_step(self.beam, self.s, s1, self.cs)
        self.steps += 1
        self.s, self.res = s1, res1
        self.sample(self.s, self.res, _phase(self.cs), self.cs)

    def _resample(self) -> None:
        """After a change of the contact state: the outputs at ``s`` again, and a second sample there."""
        self.res = self.integ.evaluate(self.s, self.cs)
        self.sample(self.s, self.res, _phase(self.cs), self.cs)

    # ------------------------------------------------------ contact phases
    def open_pair(self, k: int) -> None:
        """Pair k starts its contact at the current state (s, res)."""
        s, res = self.s, self.res
        if self.stop_at_impact:
            raise _Stop("impact", "impact at t = 0" if s.t == 0.0 else f"impact at t = {s.t:.12g} s")
        if len(self.rec.contacts) >= self.beam.case.solver.max_contacts:
            raise _Stop(
                "max-contacts",
                f"stopped at t = {s.t:.9g} s after {len(self.rec.contacts)} contacts "
                "(solver.max_contacts); the contacts accumulate (Zeno-like)",
            )
        rate = -float(res.pair_gap_rate[k])
        law = self.beam.pairs[k].law
        m_eff = _effective_mass(self.beam, s.z, k) if law.name == "kelvin_voigt" else 1.0
        p = law.parameters(rate, m_eff)
        ev = ContactEvent(index=len(self.rec.contacts), onset=s.t, velocity_before=float(res.pair_gap_rate[k]), pair=k)
        self.rec.contacts.append(ev)
        if self.h_fixed is not None:
            h = self.h_fixed
        else:
            h = min(contact_step(self.beam, self.m_ref[k], rate, k), self.h_free)
        self.h_c = min(self.h_c, h) if self.cs.any else h
        self.cs = self.cs.with_pair(k, p)
        self.events[k] = ev

    def close_pair(self, k: int) -> None:
        """Pair k ends its contact at the current state (s, res)."""
        ev = self.events[k]
        if ev is not None:
            ev.end = self.s.t
            ev.velocity_after = float(self.res.pair_gap_rate[k])
        self.cs = self.cs.with_pair(k, None)
        self.events[k] = None

    def _switch_others(self, k: int) -> None:
        """At a located event of pair k: another pair already penetrating and approaching starts its contact,
        another pair in contact found open ends it (two events closer than the location tolerance)."""
        for j in range(self.beam.npairs):
            if j == k:
                continue
            d, vn = float(self.res.pair_gap[j]), float(self.res.pair_gap_rate[j])
            if self.cs.laws[j] is None and d < 0.0 and vn < -GRAZING_SPEED:
                self.open_pair(j)
            elif self.cs.laws[j] is not None and d > 0.0:
                self.close_pair(j)
            else:
                continue
            self._resample()


def _phase(cs: ContactState) -> str:
    """The sample's phase: "contact" while some pair is in contact, else "free"."""
    return "contact" if cs.any else "free"


def _warm_up(integ: FemIntegrator, s: State, h: float) -> None:
    """Compile (or load from Numba's cache) every kernel before the clock starts."""
    its = integ.iterations
    try:
        integ.step(s, 1e-3 * h, None)
    except NewtonFailure:
        pass
    integ.iterations = its
    hermite_dip(1.0, 0.0, 1.0, 0.0, 1.0)
    integ.beam.energies(s.z, s.zd)
    integ.beam.measuring_velocities(s.z, s.zd)


class _Stop(Exception):
    """Ends a run before t_end with its ``status`` ("impact", "max-contacts") and ``message``."""

    def __init__(self, status: str, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


def _effective_mass(beam: FemBeam, z: np.ndarray, pair: int = 0) -> float:
    """1/(J M^-1 J^T) at a pair's point with the banded FE mass matrix (theta held if prescribed)."""
    zero = np.zeros_like(z)
    _, ab, _ = beam.residual(0.0, z, zero, zero, (1.0, 0.0, 0.0))
    J = beam.gap_jacobian(z, pair)
    if beam.prescribed:
        fix_first_dof(ab)
        J[0] = 0.0
    x = solve_banded((BAND, BAND), ab[BAND:], J)
    return float(1.0 / (J @ x))


__all__ = ["run"]
