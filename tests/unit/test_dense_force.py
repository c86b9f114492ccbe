"""A contact's force on a compiled phase computed alone in the kernels (``results/dense_force.py``,
``fb_pair_force_many``) against the outputs' (``BeamSystem.outputs`` on the dense output's states, which evaluates every
column): the same numbers to the bit, since both apply the contact law to the same positions and rates (and take a held
pair's multiplier, or a prescribed drive's forces, from the same equations), and the phase's exact end states at its
ends.  Presets with a law's force (CCFM), held pairs (CCM's constrained phases) and a prescribed hub angle."""

from __future__ import annotations

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.results.dense_force import compiled_pair_force
from tests.conftest import PRESCRIBED_SPIN


@pytest.mark.parametrize(
    ("name", "method", "over"),
    [
        ("seed-experiment", "ccfm", {}),
        ("seed-experiment", "ccm", {}),
        ("two-stops", "ccfm", {}),
        (  # a hub turning at a prescribed rate: the outputs take the forces from the equations
            "seed-experiment",
            "ccfm",
            PRESCRIBED_SPIN,
        ),  # fmt: skip
        ("tip-wall", "ccm", {}),
    ],
)
def test_the_kernels_force_equals_the_outputs(name, method, over):
    case = fb.load_case(name, {"solver.t_end": 0.05, **over})
    sol = fb.simulate(case, method)
    src, checked = sol.source, 0
    for seg in src.segments:
        if seg.t1 <= seg.t0 or seg.dense is None:
            continue
        for pair in range(src.system.pairs):
            if seg.phase.modes[pair] == 0:
                continue
            t = np.concatenate(([seg.t0], np.linspace(seg.t0, seg.t1, 41), [seg.t1]))
            alone = compiled_pair_force(seg, t, pair)
            assert alone is not None
            expected = src.evaluate_pairs(seg, t)[2][:, pair, 2]
            np.testing.assert_array_equal(alone, expected)
            checked += 1
    assert checked >= 1
