"""The memory a run will hold, estimated before it starts, against the limit ``solver.memory_limit``.

A run keeps its dense output until it ends: the compiled integrator one record per step (start state, nodal
forcing: ``core.sizes`` floats), scipy's DOP853 one interpolant per step, the finite-element reference one row of
outputs per step; plus one :class:`~flexbeam.integrate.loop.Segment` per phase.  Its output samples -- the grid of
``solver.sample_step`` in free flight and ``solver.contact_sample_step`` in contact, evaluated for arrays, NetCDF,
figures and animations -- come on top when they are asked for.  :func:`estimate` predicts these from the case alone,
without integrating; :func:`check` refuses a case whose estimate exceeds the limit with one line naming
``solver.t_end``, the estimate, the limit and what to change.

The step rates are measured (2 cores, x86-64; ``seed-experiment`` for 0.1, 0.5 and 2 s, the other presets at their
``t_end``, each impact method; records per simulated second):

=========================  ==================  =====================================================
integrator                 free flight         in contact
=========================  ==================  =====================================================
exponential, CCFM          460 - 1900          4.7e4 - 9.2e4 (short contacts), 1.7e4 (resting, 2 s)
exponential, CCM / IMM     640 - 7400          1.2e5 - 3.3e5 (constrained / resting)
reference (DOP853, 1e-9)   1.8e5 - 2.0e5       1.5e5 - 2.0e5
FE (generalized-alpha)     1 / (2 h_c)         1 / h_c, h_c = t_c / 200 (``fem.step_size``)
=========================  ==================  =====================================================

and the bytes held: 800 B per record of the seed case (752 B of record), 2.6 KB per DOP853 step, 0.5 - 1.6 KB
per FE step (peak while the Solution is built), ~6 KB per segment with its contact record; an output sample holds
one float per output column, modal coordinate and rate, measuring point and pair column (400 B for the seed case),
and twice that while the samples are joined (peak 816 B measured).

The estimate of the dense output is an upper bound of the usual case rather than a fit: a run whose beam can reach
an obstacle is taken to spend all of ``t_end`` in contact (a falling beam ends resting on its stop: 71 % of the
seed's 2 s), at the upper end of the measured contact rates; tighter tolerances than the defaults scale the rates as
(rtol_default / rtol)^(1/3) (measured: x8 in free flight and x4 in contact for 1e-9 against 1e-6), and
``solver.max_step`` bounds the step.  It overestimates short runs (the seed's 0.1 s: 8 MB of records estimated,
0.15 MB held) and is within ~9x of long ones (the seed's 2 s: 0.16 GB estimated, 0.019 GB held); it exists to
stop a run that would exhaust the machine (``solver.t_end = 1e9``: 8e16 B), not to size one exactly.

The output samples are counted twice.  Before the run, the samples every run has: all of ``t_end`` on the coarser
of the two spacings (how long the beam stays in contact, where the fine spacing applies, only the run tells; the
seed's 2 s hold 7.1 million samples, 5.9 GB at peak, 99 % of them in its 1.4 s of contact).  After the run, before
they are evaluated, their exact number (:func:`check_samples`, from the phases' lengths): a run whose samples
would not fit is refused then, naming the sample step, before anything is written.  ``output.interval`` spaces the
samples evenly in every phase.

A run streamed to its result file (``stream``; :mod:`flexbeam.results.stream`) holds neither: the compiled
integrator hands a long phase on in blocks of :data:`~flexbeam.integrate.modal.BLOCK_RECORDS` steps, the stream keeps
the steps an open contact record may still need (at most :data:`~flexbeam.results.stream.WINDOW_RECORDS`, then the
record is completed stretch by stretch) and two chunks of samples (:data:`~flexbeam.results.export.TIME_CHUNK` each)
with one batch being evaluated.  Its estimate does not grow with ``solver.t_end``: 0.22 GB for the seed case, whose
process peaks at 0.20, 0.26 and 0.27 GB for 10, 100 and 1000 s, ~0.11 GB of it the interpreter and its libraries
(``benchmarks/long_run.py``).  scipy's DOP853 (the reference integrator) hands on whole phases only: a streamed run
on it is estimated as one that is not.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .contact.setup import OBSTACLE_SPHERE, ContactSetup
from .errors import ParameterError
from .kernels import core
from .parameters.case import Case
from .results.limits import memory_limit, sample_bytes
from .results.limits import size_text as _size

#: compiled (exponential) integrator: records per simulated second at the default tolerances
RATE_FREE = 2.0e3
RATE_CONTACT = {"ccfm": 1.0e5, "ccm": 3.5e5, "imm": 3.5e5}
#: scipy's DOP853 at the default tolerances (any phase), and the bytes of one step's interpolant per state entry
RATE_REFERENCE = 3.0e5
REFERENCE_BYTES_PER_STATE = 64.0
REFERENCE_STEP_BYTES = 800.0
#: bytes held per record beside its floats (the chunked arrays, amortised)
RECORD_OVERHEAD = 48.0
#: bytes per segment: the Segment, its two states, phase, dense-output object and contact record
SEGMENT_BYTES = 8192.0
#: FE reference: bytes per step (one output row, peak while the Solution is built; more with per-pair rows)
FE_STEP_BYTES, FE_PAIR_STEP_BYTES = 1200.0, 700.0
#: steps per contact a run may take whatever its length (measured: rod-end 189 steps in its one contact, IMM's
#: 1000 micro-impacts there 1978): a floor of the estimate
CONTACT_STEPS = 4.0
#: the tolerance scaling of the step rates: (rtol_default / rtol) ** RATE_EXPONENT (measured 0.19 - 0.31)
RATE_EXPONENT = 1.0 / 3.0
#: a streamed run: blocks of steps held besides the kept ones (the stepper's, under 2 blocks, and the part handed on)
STREAM_BLOCKS = 3


@dataclass(frozen=True)
class MemoryEstimate:
    """What a run of ``t_end`` seconds will hold [B]: the integrator's dense output (``records``), its phases
    (``segments``) and, when asked for, the output samples (``samples``, at peak while they are joined); the
    ``limit`` and how it was set."""

    t_end: float
    records: float
    segments: float
    samples: float
    limit: float
    limit_source: str
    max_step_bound: bool = False  #: ``solver.max_step`` sets the step count
    streamed: bool = False  #: streamed to disk: the estimate does not grow with ``t_end``
    sample_field: str = "solver.sample_step"  #: the case field that spaces the samples counted
    #: the same run streamed to its file would fit the limit (offered as a way out only then; :func:`check` asks)
    stream_fits: bool = True

    @property
    def total(self) -> float:
        return self.records + self.segments + self.samples

    @property
    def max_t_end(self) -> float:
        """The ``solver.t_end`` at which the estimate reaches the limit (it grows in proportion to t_end; a
        streamed run's does not)."""
        if self.streamed:
            return math.inf if self.total <= self.limit else 0.0
        rate = (self.records + self.samples) / self.t_end
        return max(0.0, (self.limit - self.segments) / rate) if rate > 0.0 else math.inf

    def message(self) -> str:
        """One line: the estimate, the limit and the way out."""
        parts = f"dense output {_size(self.records)}, phases {_size(self.segments)}"
        if self.samples:
            parts += f", output samples {_size(self.samples)}"
        if self.streamed:
            return (
                f"solver.memory_limit: a streamed run holds about {_size(self.total)} in memory ({parts}) whatever "
                f"its length, more than the limit of {_size(self.limit)} ({self.limit_source}); raise "
                f"solver.memory_limit [B]"
            )
        shorter = self.max_t_end > 0.0  # (else the phases, which solver.max_contacts bounds, fill it)
        ways = [f"solver.t_end <= {self.max_t_end:.3g} s" if shorter else "a smaller solver.max_contacts"]
        if self.max_step_bound:
            ways.append("a larger solver.max_step")
        # the samples' spacing named first where they hold most (output.interval = 1e-300 named solver.t_end)
        field = self.sample_field if self.samples > self.records + self.segments else "solver.t_end"
        if self.samples > self.records:
            ways.insert(0 if field == self.sample_field else len(ways), f"a coarser {self.sample_field}")
        if self.stream_fits:
            ways.append("stream the run to its file (flexbeam run --stream --out DIR; simulate(case, stream=path))")
        way = "allowed here: " + ", or ".join(ways)
        return (
            f"{field}: a run of {self.t_end:g} s would hold about {_size(self.total)} in memory ({parts}), more "
            f"than the limit of {_size(self.limit)} ({self.limit_source}); {way}, or raise solver.memory_limit [B]"
        )


def reachable(case: Case, contact: ContactSetup | None = None) -> bool:
    """Can the beam reach an obstacle?  Not when every obstacle is rigidly held outside the disc swept by the beam
    about O: radius r_h + L + c for the first-order model, whose beam does not stretch (2 L in place of L for the
    zeroth-order one, whose centre line lengthens as it bends)."""
    contact = contact or ContactSetup.from_case(case)
    L = case.beam.length
    reach = case.hub.radius + (L if case.model.coupling == "first-order" else 2.0 * L) + case.beam.surface_offset
    for ob in contact.obstacles:
        if ob.compliant:
            return True
        if ob.kind == OBSTACLE_SPHERE:
            clearance = float(np.hypot(*ob.centre)) - ob.radius
        else:  # the distance of O from the plane, on its outward side
            clearance = -float(ob.normal @ ob.centre)
        if clearance < reach:
            return True
    return False


def estimate(case: Case, method: str = "ccfm", outputs: bool = False, stream: bool = False) -> MemoryEstimate:
    """The memory a run of ``case`` with ``method`` will hold (see the module docstring); with ``outputs`` its
    output samples too (arrays, NetCDF, figures, animations); ``stream``: streamed to its result file, what the
    stream keeps.

    Parameters
    ----------
    case
        The validated case; ``solver.t_end``, the tolerances, ``max_step``, the sample steps, the contact pairs,
        ``model.modes``, ``output.measuring_points`` and ``fem`` enter.
    method
        ``"ccfm"``, ``"ccm"``, ``"imm"`` or ``"fem"``.
    outputs
        Whether the output samples will be evaluated.
    stream
        Whether the run is streamed to its result file (:func:`flexbeam.simulation.simulate`'s ``stream``).

    Returns
    -------
    MemoryEstimate
    """
    s, t_end = case.solver, case.solver.t_end
    contact = ContactSetup.from_case(case)
    touching = reachable(case, contact)
    limit, source = memory_limit(case)
    pairs = len(contact.pairs)
    if method == "fem":
        steps = t_end / _fe_step(case, contact, touching)
        per_step = FE_STEP_BYTES + (FE_PAIR_STEP_BYTES if pairs > 1 or any(p.anywhere for p in contact.pairs) else 0)
        return MemoryEstimate(t_end, steps * per_step, 0.0, 0.0, limit, source)
    n = case.model.modes + case.model.axial_modes
    prescribed = case.drive.kind == "prescribed"
    compliant = case.obstacle.support.compliant
    nz = n if prescribed else n + (3 if case.joint.kind == "free" else 1)
    size = 2 * nz + (2 if compliant else 0) + 2
    exponential = s.integrator == "exponential" and (not compliant or (method == "ccfm" and not prescribed))
    if exponential:
        rate = RATE_CONTACT.get(method, max(RATE_CONTACT.values())) if touching else RATE_FREE
        rate *= max(1.0, 1e-6 / s.fast_rtol) ** RATE_EXPONENT
        record = 8.0 * core.sizes(nz + (1 if compliant else 0), pairs)[0] + RECORD_OVERHEAD
    else:
        rate = RATE_REFERENCE * max(1.0, 1e-9 / s.rtol) ** RATE_EXPONENT
        record = REFERENCE_BYTES_PER_STATE * size + REFERENCE_STEP_BYTES
    bound = s.max_step is not None and 1.0 / s.max_step > rate
    if bound:
        rate = 1.0 / s.max_step
    steps = rate * t_end
    if touching:  # a short run of stiff contacts (the rod-end's axial wave: ~2e6 steps/s) is bounded by its contacts
        steps = max(steps, CONTACT_STEPS * (s.max_contacts + 1))
    phases = min(4.0 * (s.max_contacts + 1), 2.0 * steps + 4.0)
    samples = 0.0
    if stream:  # two chunks of samples and a batch being evaluated; the steps kept for the open contacts
        from .integrate.modal import BLOCK_RECORDS
        from .results.export import TIME_CHUNK
        from .results.stream import WINDOW_RECORDS

        # (never more than the same run held in memory: a short run's whole samples are fewer than its buffers')
        samples = min(sample_bytes(case, pairs, 3 * TIME_CHUNK), _whole_samples(case, pairs))
        if exponential:
            steps = min(steps, WINDOW_RECORDS + STREAM_BLOCKS * BLOCK_RECORDS)
        return MemoryEstimate(t_end, steps * record, phases * SEGMENT_BYTES, samples, limit, source, bound, True)
    if outputs:  # the samples every run has: no instant is sampled more sparsely than this
        samples = _whole_samples(case, pairs)
    field = case.sample_step_field(case.sample_steps()[1] > case.sample_steps()[0])
    return MemoryEstimate(t_end, steps * record, phases * SEGMENT_BYTES, samples, limit, source, bound, False, field)


def _whole_samples(case: Case, pairs: int) -> float:
    """The bytes of a whole run's output samples: no instant is sampled more sparsely than the sparser spacing."""
    return sample_bytes(case, pairs, case.solver.t_end / max(case.sample_steps()))


def _fe_step(case: Case, contact: ContactSetup, touching: bool) -> float:
    """The FE reference's step: ``fem.time_step``, else h_c = t_c / STEPS_PER_CONTACT (in contact; twice that in
    free flight) from the rigid Hertz impact of the reference mass at the impact speed, as
    ``fem.step_size.contact_step`` sizes it (the mass for the straight beam at the contact point)."""
    from .contact.hertz import rigid_hertz_impact
    from .fem.step_size import FREE_STEP_FACTOR, STEPS_PER_CONTACT

    if case.fem.time_step is not None:
        return min(case.fem.time_step, case.solver.t_end / 20.0)
    beam, hub = case.beam, case.hub
    L, mu, rh = beam.length, beam.line_density, hub.radius
    speed = max(abs(case.initial.impact_velocity), 1e-6)
    h = math.inf
    for pair in contact.pairs:
        if case.drive.kind == "prescribed":  # the first clamped mode's mass at x_P
            bl = 1.8751040687119611
            sr = (math.cosh(bl) + math.cos(bl)) / (math.sinh(bl) + math.sin(bl))
            x = bl * pair.position / L
            phi = math.cosh(x) - math.cos(x) - sr * (math.sinh(x) - math.sin(x))
            mass = mu * L / max(phi * phi, 1e-12)
        else:
            lever2 = (rh + pair.position) ** 2
            inertia = hub.inertia + mu * ((rh + L) ** 3 - rh**3) / 3.0
            mass = inertia / lever2 if lever2 > 0.0 else math.inf
        mass = min(mass, 1e6 * mu * L)
        h = min(h, rigid_hertz_impact(mass, speed, pair.law.stiffness, pair.law.exponent)[2] / STEPS_PER_CONTACT)
    if not touching:
        h *= FREE_STEP_FACTOR
    return min(h, case.solver.t_end / 20.0)


def check(case: Case, method: str = "ccfm", outputs: bool = False, stream: bool = False) -> MemoryEstimate:
    """:func:`estimate`, and a one-line :class:`~flexbeam.errors.ParameterError` when it exceeds the limit."""
    est = estimate(case, method, outputs, stream)
    if est.total > est.limit:
        if not stream:  # (the stream is offered only if its own estimate fits: asked here, not on every run)
            est = replace(est, stream_fits=estimate(case, method, outputs, stream=True).total <= est.limit)
        raise ParameterError(est.message())
    return est


__all__ = ["MemoryEstimate", "check", "estimate", "reachable"]
