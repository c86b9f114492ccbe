"""CCM on the seed case after its bouncing: the constrained phases of a beam pressed onto its stop by gravity.

The compiled integrator runs a long phase in blocks of step records (``flexbeam.integrate.modal.BLOCK_RECORDS``,
from 64 records, doubling) and resumes it from its state buffer after each block; a held constraint's error control
scales its multiplier's error by the largest multiplier of the phase so far, which the state buffer carries across
blocks: the steps, and so every result, do not depend on the block size.
"""

import flexbeam as fb
import flexbeam.integrate.modal as modal
from tests.validation.fingerprints import digest


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
