"""CCM on the seed case after its bouncing: the constrained phases of a beam pressed onto its stop by gravity.

The beam settles on the sphere by ~0.5 s but does not come to rest: the e = 0 jumps excite every mode, and the
constrained beam (pinned at O, propped at P) has no damping, so its multiplier rings about the static force with
every propped mode (measured at 2.4-2.9 s: 162 Hz 2.7 N, 582 Hz 1.5 N, 1023 Hz 1.2 N, 6076 Hz 1.9 N, ...,
together about F_s).  Where the ringing's dips reach zero the multiplier turns tensile, P lifts off by ~1e-10 m
and lands again at 1e-5-3e-4 m/s (micro-impacts, docs/methods.md) some 20-50 us later: a real release and impact
of CCM's model (docs/performance.md, "CCM at rest").  Each e = 0 landing takes a little energy, too little to
still the ringing within the run (the multiplier's 99th percentile 15.7 N at 0.3-0.4 s, 13.8 N at 1-1.5 s, 13.7 N
at 2.5-3 s): from 1 s on the releases go on at ~40 phases per half second.

The compiled integrator runs a long phase in blocks of step records (``flexbeam.integrate.modal.BLOCK_RECORDS``,
from 64 records, doubling) and resumes it from its state buffer after each block; a held constraint's error control
scales its multiplier's error by the largest multiplier of the phase so far, which the state buffer carries across
blocks: the steps, and so every result, do not depend on the block size.
"""

import math

import numpy as np
import pytest
import scipy.linalg as sl

import flexbeam as fb
import flexbeam.integrate.modal as modal
from flexbeam.integrate.dense import gauss_nodes
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import initial_state
from tests.validation.fingerprints import digest
from tests.validation.test_resting_contact import static_force

T_END = 3.0
SETTLED = 1.0  # [s] the bouncing is over (the last landing faster than 1 % of the first approach speed: 0.276 s)


def test_results_do_not_depend_on_the_block_size(monkeypatch):
    """0.3 s of the seed case under CCM: constrained phases of up to ~400 steps (the beam settling on its stop),
    run in blocks of at most 64, 128 and 16384 records: the same digest (contacts, steps, final state, metrics).
    Before the multiplier's scale was kept in the state buffer the three differed (9731, 9807, 9746 steps)."""
    case = fb.load_case("seed-experiment", {"solver.t_end": 0.3})
    digests = set()
    for cap in (modal.BLOCK_RECORDS, 64, 128):
        monkeypatch.setattr(modal, "BLOCK_RECORDS", cap)
        digests.add(digest(fb.simulate(case, "ccm")))
    assert len(digests) == 1


@pytest.fixture(scope="module")
def rest():
    case = fb.load_case("seed-experiment", {"solver.t_end": T_END, "solver.memory_limit": 2e10})
    return case, fb.simulate(case, "ccm")


def _propped_frequencies(case) -> np.ndarray:
    """The natural frequencies [Hz] of the linearised beam (the integrator's M0, K0) held at P: the modes in the
    null space of the gap's Jacobian at the start (P on the sphere, the beam level)."""
    system = BeamSystem.from_case(case)
    M0, K0, _ = system.joint.linear_model(system.beam)
    y0, _ = initial_state(system, case)
    J = system.gap(0.0, y0, 0)[3][system.ngiven :]
    Z = sl.null_space(J[None, :])
    w2 = sl.eigh(Z.T @ K0 @ Z, Z.T @ M0 @ Z, eigvals_only=True)
    return np.sqrt(np.maximum(w2, 0.0)) / (2.0 * math.pi)


def test_the_rest_costs_bounded_steps_and_phases(rest):
    """The run's cost is the constrained phases' steps: the collocated multiplier carries the ringing of every
    propped mode, and resolving the fastest (f_max = 17.0 kHz at 12 modes) takes ~7 steps a period (measured
    349 134 steps in 3 s); bound 20 steps per period of f_max over the run.  Once settled, the releases come at the
    ringing's deepest dips, which the fundamental propped mode (162 Hz, the largest term) spaces: measured 154
    phases over 1-3 s, 0.24 per period of it; bound 2 (a release and a landing every period)."""
    case, sol = rest
    run = sol.source.run
    assert sol.status == "success"
    f = _propped_frequencies(case)
    assert run.steps < 20 * f[-1] * T_END
    late = [s for s in run.segments if s.t0 >= SETTLED]
    assert len(late) < 2 * f[0] * (T_END - SETTLED)


def test_the_rest_force_is_the_static_force(rest):
    """The multiplier's mean over the last second (its impulse over the time, the free flights counting as zero
    force) is F_s = m g L / (2 x_P): the moments about O of the weight and of the contact force balance on average
    while the beam rings about the level rest.  Tolerance 0.5 %: a ringing term of amplitude a at f moves a mean
    over T by <= a / (pi f T) (2.7 N at 162 Hz: 5e-3 N, 0.07 %, the other terms less), the angular momentum the
    ringing holds at the window's ends is of that order too, and the moment arms change by O(theta^2) < 1e-8
    (measured 9e-5)."""
    case, sol = rest
    _, w = gauss_nodes()
    start, impulse = math.inf, 0.0
    for seg in sol.source.run.segments:
        if seg.phase.name != "constrained" or seg.dense is None or seg.t1 <= T_END - 1.0:
            continue
        rec = seg.dense.records
        inside = rec[:, 0] >= T_END - 1.0
        if inside.any():
            start = min(start, float(rec[inside, 0].min()))
            impulse += float(np.sum(rec[inside, 1] * (seg.dense._forces(0)[inside] @ w)))
    assert T_END - start > 0.99
    assert impulse / (T_END - start) == pytest.approx(static_force(case), rel=5e-3)
