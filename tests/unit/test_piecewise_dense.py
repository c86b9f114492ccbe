"""The reference integrator's dense output over a phase (:class:`flexbeam.integrate.reference.PiecewiseDense`): one
scipy dense output per step, called on an array of times in any order.

The truth is independent of the grouping under test: a piecewise function whose pieces are known in closed form
(each step's piece a different polynomial, so a time evaluated on the wrong piece shows), evaluated time by time.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from flexbeam.integrate.reference import PiecewiseDense


class _Piece:
    """A step's dense output as scipy's: called on an array of times, it returns (components x times)."""

    def __init__(self, k: int) -> None:
        self.k = k

    def __call__(self, t):
        t = np.asarray(t, float)
        return np.array([self.k + 0.0 * t, (self.k + 1.0) * t**2, np.sin(self.k * t)])


BREAKS = [0.0, 0.1, 0.25, 0.3, 0.7, 1.0]


def _truth(t: float) -> np.ndarray:
    """The piece of t's step (the step whose interval (t_k, t_k+1] holds t; the first step also holds t_0)."""
    k = max(0, min(len(BREAKS) - 2, int(np.searchsorted(BREAKS, t, side="left")) - 1))
    return _Piece(k)(np.array([t]))[:, 0]


@settings(max_examples=50, deadline=None)
@given(st.lists(st.sampled_from(BREAKS) | st.floats(0.0, 1.0), max_size=40))
def test_each_time_is_evaluated_on_its_own_step_in_the_order_given(times):
    dense = PiecewiseDense(BREAKS, [_Piece(k) for k in range(len(BREAKS) - 1)])
    out = dense(np.array(times, float))
    assert out.shape == (len(times), 3)
    for row, t in zip(out, times):
        assert np.array_equal(row, _truth(t))


def test_a_call_on_no_times_gives_no_rows():
    dense = PiecewiseDense(BREAKS, [_Piece(k) for k in range(len(BREAKS) - 1)])
    assert dense(np.empty(0)).shape == (0, 3)
