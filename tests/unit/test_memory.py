"""The memory estimate of a run (``flexbeam.memory``) against what runs actually hold.

Truth: the runs themselves -- the bytes of their dense-output records, their number of phases and output samples
-- for every built-in case and impact method, and the seed experiment for 0.1, 0.5 and 2 s (the runs the rates
were measured on).  No assertion depends on the machine's memory: the limits are set explicitly, or the physical
memory is replaced.
"""

from __future__ import annotations

import math

import pytest

import flexbeam as fb
from flexbeam import memory
from flexbeam.errors import ParameterError
from flexbeam.model.joints import JOINTS
from flexbeam.results import limits
from flexbeam.results.arrays import sample_count


def held(sol) -> tuple[float, int, int]:
    """(bytes of the dense-output records, phases, output samples) of a modal run; for scipy's DOP853 (a compliant
    support with CCM or IMM) its steps at the bytes the estimate takes per step (its rate is what is checked)."""
    run = sol.source.run
    per_step = memory.REFERENCE_BYTES_PER_STATE * sol.source.system.size + memory.REFERENCE_STEP_BYTES
    records = sum(
        (s.dense.records.nbytes if hasattr(s.dense, "records") else len(s.dense.pieces) * per_step)
        for s in run.segments
        if s.dense is not None
    )
    samples = sum(sample_count(s.t0, s.t1, s.phase.sample_step) for s in run.segments)
    return float(records), len(run.segments), samples


PRESET_RUNS = [
    (name, m)
    for name in fb.parameters.builtin_cases()
    for m in ("ccfm", "ccm", "imm")
    if m not in JOINTS[fb.load_case(name).joint.kind].unsupported_methods
]


@pytest.mark.parametrize("name, method", PRESET_RUNS)
def test_estimate_bounds_what_each_preset_holds(name, method):
    """Records, phases and the samples every run has: the estimate is above what the run holds (records: measured
    3x - 1000x above; a wrong rate or record size would fall below), and below the run's samples for those (the
    pre-run count is the coarse grid alone)."""
    slow = name == "seed-experiment-calibrated" and method != "ccfm"  # scipy's DOP853: 60 ms per simulated ms
    case = fb.load_case(name, {"solver.t_end": min(fb.load_case(name).solver.t_end, 0.02 if slow else 0.2)})
    est = memory.estimate(case, method, outputs=True)
    sol = fb.simulate(case, method)
    records, phases, samples = held(sol)
    assert records <= est.records
    assert phases * memory.SEGMENT_BYTES <= est.segments
    assert est.samples <= limits.sample_bytes(case, sol.source.system.pairs, samples)


@pytest.mark.parametrize("t_end, factor", [(0.1, 100.0), (0.5, 60.0), (2.0, 15.0)])
def test_seed_experiment_rates(t_end, factor):
    """The seed experiment's records over 0.1, 0.5 and 2 s (CCFM): bounded by the estimate, which is within a
    factor of them that shrinks as the beam comes to rest on the stop (measured 52x, 33x, 8.6x; the step counts
    are the compiled kernels', the same on every machine)."""
    case = fb.load_case("seed-experiment", {"solver.t_end": t_end})
    est = memory.estimate(case, "ccfm")
    records, _, _ = held(fb.simulate(case))
    assert records <= est.records <= factor * records


def test_reference_integrator_steps_are_bounded():
    """scipy's DOP853 (1e-9): its steps over 10 ms of the seed against the estimate's rate (measured 1.8e5 steps
    per second of the 0.5 s run, 2.0e5 on the compliant support; the estimate takes 3e5)."""
    case = fb.load_case("seed-experiment", {"solver.t_end": 0.01, "solver.integrator": "reference"})
    est = memory.estimate(case, "ccfm")
    sol = fb.simulate(case)
    steps = sum(len(s.dense.pieces) for s in sol.source.run.segments if s.dense is not None)
    per_step = memory.REFERENCE_BYTES_PER_STATE * sol.source.system.size + memory.REFERENCE_STEP_BYTES
    assert steps * per_step <= est.records


def test_fe_steps_are_bounded():
    """The FE reference's steps over 2 ms of the seed (one output row each) against the estimate, which sizes
    the step as ``fem.step_size`` does (the run's steps: 2.2e-6 s in contact, 4.4e-6 s in flight)."""
    case = fb.load_case("seed-experiment", {"solver.t_end": 2e-3})
    est = memory.estimate(case, "fem")
    sol = fb.simulate(case, "fem")
    assert sol.time.size * memory.FE_STEP_BYTES <= est.records <= 3.0 * sol.time.size * memory.FE_STEP_BYTES


def test_the_issue_run_is_refused_before_it_starts(monkeypatch):
    """solver.t_end = 1e9: refused with the estimate, the limit and the largest t_end, without integrating."""

    def no_integration(*args, **kwargs):
        raise AssertionError("the estimate must not integrate")

    monkeypatch.setattr("flexbeam.simulation.run_phases", no_integration)
    case = fb.load_case("seed-experiment", {"solver.t_end": 1e9, "solver.memory_limit": 8e9})
    with pytest.raises(ParameterError) as err:
        fb.simulate(case)
    msg = str(err.value)
    assert msg.startswith("solver.t_end: a run of 1e+09 s would hold about ")
    assert "more than the limit of 8 GB (solver.memory_limit)" in msg
    assert "allowed here: solver.t_end <= " in msg and "or raise solver.memory_limit" in msg
    assert "--stream" in msg  # the way out for a run of any length
    assert "\n" not in msg


def test_largest_t_end_is_where_the_estimate_meets_the_limit():
    """The estimate grows in proportion to t_end (segments aside): the t_end the message allows passes, 1 % more
    does not."""
    limit = 2e8
    case = fb.load_case("seed-experiment", {"solver.t_end": 100.0, "solver.memory_limit": limit})
    t_max = memory.estimate(case, "ccm").max_t_end
    assert 0.0 < t_max < 100.0
    ok = fb.load_case("seed-experiment", {"solver.t_end": 0.99 * t_max, "solver.memory_limit": limit})
    bad = fb.load_case("seed-experiment", {"solver.t_end": 1.01 * t_max, "solver.memory_limit": limit})
    memory.check(ok, "ccm")
    with pytest.raises(ParameterError, match=r"^solver\.t_end: "):
        memory.check(bad, "ccm")


def test_max_step_and_tolerances_raise_the_estimate():
    """A bound on the step sets the rate (1 / max_step) and is named as a way out; tighter tolerances scale the
    rate as (1e-6 / rtol)^(1/3)."""
    base = fb.load_case("seed-experiment")
    est = memory.estimate(fb.load_case("seed-experiment", {"solver.max_step": 1e-9, "solver.memory_limit": 1e9}))
    assert est.records == pytest.approx(base.solver.t_end / 1e-9 * est.records / (est.t_end / 1e-9))
    assert est.max_step_bound and "or a larger solver.max_step" in est.message()
    tight = memory.estimate(fb.load_case("seed-experiment", {"solver.fast_rtol": 1e-9}))
    assert tight.records == pytest.approx(10.0 * memory.estimate(base).records)


def test_an_obstacle_out_of_reach_means_free_flight_rates():
    """Kane's spin-up: the sphere 100 m from O is outside the 10 m beam's reach, so the whole run is free flight;
    moved to 9 m it is within reach."""
    kane = fb.load_case("kane-spinup")
    assert not memory.reachable(kane)
    assert memory.reachable(fb.load_case("kane-spinup", {"obstacle.centre": [0.0, -9.0]}))
    assert memory.estimate(kane).records == pytest.approx(
        memory.RATE_FREE * kane.solver.t_end * (memory.estimate(kane).records / (memory.RATE_FREE * 20.0))
    )


def test_default_limit_is_half_the_physical_memory(monkeypatch):
    monkeypatch.setattr(limits, "physical_memory", lambda: 4e9)
    limit, source = limits.memory_limit(fb.load_case("seed-experiment"))
    assert limit == 2e9 and source.startswith("50 % of the physical memory")
    monkeypatch.setattr(limits, "physical_memory", lambda: None)
    assert limits.memory_limit(fb.load_case("seed-experiment"))[0] == limits.FALLBACK_LIMIT


def test_the_physical_memory_is_read_from_sysconf():
    import os

    phys = limits.physical_memory()
    assert phys is None or phys == os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")


def test_samples_of_a_finished_run_are_counted_before_they_are_evaluated():
    """0.5 s of the seed: the run itself fits in 130 MB, its 178 000 samples (most in contact, on the 0.2 us
    grid) would hold ~150 MB at peak: refused when they are asked for, naming the contact sample step."""
    case = fb.load_case("seed-experiment", {"solver.t_end": 0.5, "solver.memory_limit": 1.3e8})
    sol = fb.simulate(case)
    assert sol.metrics()["peak_force"] > 0.0  # the metrics need no samples
    with pytest.raises(ParameterError, match=r"^solver\.contact_sample_step: the \d+ output samples of this run"):
        _ = sol.arrays
    assert math.isfinite(fb.simulate(fb.load_case(case, {"solver.memory_limit": 1e9})).time[-1])


def test_the_refusal_offers_only_ways_out_that_fit():
    """A limit the phases alone exceed said "allowed here: solver.t_end <= 0 s" (t_end must be > 0) and offered the
    stream, whose estimate was larger still; the 0.1 s seed run streamed was refused at 100 MB where the run held in
    memory with all its outputs passed: the stream counted 3 chunks of 32 768 samples where the whole run has 23 571.
    A stream never holds more samples than the whole run, and is offered only when it fits."""
    case = fb.load_case("seed-experiment", {"solver.memory_limit": 3e7})
    tight = memory.estimate(case, outputs=True)
    with pytest.raises(ParameterError) as err:
        memory.check(case, outputs=True)
    msg = str(err.value)
    assert tight.total > tight.limit and "t_end <= " not in msg and "--stream" not in msg
    assert "a smaller solver.max_contacts" in msg
    case = fb.load_case("seed-experiment", {"solver.memory_limit": 1e8})
    held, streamed = memory.estimate(case, outputs=True), memory.estimate(case, outputs=True, stream=True)
    assert streamed.samples <= held.samples and streamed.total <= held.total <= held.limit
    memory.check(case, outputs=True, stream=True)


def test_samples_that_hold_most_name_their_spacing_first():
    """``output.interval = 1e-300``: the samples hold ~1e290 TB, and the message named solver.t_end (allowed <=
    1.5e-293 s) with a coarser output.interval last (an exploratory hunt).  The field that spaces the samples leads
    where they hold most; solver.t_end where the dense output and the phases do."""
    fine = memory.MemoryEstimate(0.1, 1e7, 3e7, 1e20, 1e10, "the default", sample_field="output.interval")
    assert fine.message().startswith("output.interval: a run of 0.1 s would hold about ")
    assert "allowed here: a coarser output.interval, or solver.t_end <= " in fine.message()
    long = memory.MemoryEstimate(1e9, 1e17, 3e7, 1e16, 1e10, "the default", sample_field="output.interval")
    assert long.message().startswith("solver.t_end: a run of 1e+09 s")
    assert "allowed here: solver.t_end <= " in long.message()
