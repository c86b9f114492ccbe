"""Where CCFM locates a slip's stop on a flexible beam (issue 28): the slip velocity reaches zero there, and nowhere
before it inside the slip.

``kernels/src/friction.c`` watches a slipping pair's slip velocity v_t on each accepted step's exact dense output
(samples between exact hops, then Brent's method on the dense output) and ends the slip where v_t reaches zero, its
root passed; a slip that starts from rest may first run back by its residual v_rest (at least VT_NOISE = 1e-9 m/s).
Checked on the tip of a ringing beam against a wall (``tip-wall``, 8 modes, mu = 0.3), whose slip stops and reverses
dozens of times:

* inside every slipping segment v_t keeps its direction -- sigma = -mu_k sign(v_t) -- at 64 points of the segment's
  dense output, up to the run back max(1e-9 m/s, v_rest) (a stop stepped over would show v_t of the order of the slip
  speeds, up to 0.07 m/s; 1e-12 m/s is its round-off);
* where a slip ends and the pair sticks, |v_t| <= 1e-6 m/s: v_t is zero (to 1e-15 of the step) on the dense output
  of the step that found the stop, which is then retaken to end there; the retaken step's end differs from that
  dense output by the step's error, rtol = 1e-6 of the state (tip speeds ~0.4 m/s): ~4e-7 m/s; measured at most
  9.2e-8 m/s over the run's 32 stops, 1e-6 m/s is 10x that.  A stop stepped over would leave v_t of the order of
  the slip speeds (up to 0.07 m/s).
"""

from __future__ import annotations

import numpy as np

import flexbeam as fb
from flexbeam.methods import coulomb

VT_NOISE = 1e-9  # [m/s] friction.c's VT_NOISE
ROUNDOFF = 1e-12  # [m/s] the slip velocity's round-off (1e-16 of the tip's speeds, times 1e4 for the modal sums)
AT_STOP = 1e-6  # [m/s] see the module docstring


def slip_velocity(system, t: float, y: np.ndarray, pair: int) -> float:
    return float(system.tangent(t, y, pair)[2])


def test_a_slip_keeps_its_direction_and_stops_at_zero_slip_velocity():
    sol = fb.simulate(fb.load_case("tip-wall", {"contact.friction": 0.3}), "ccfm")
    assert sol.source.run.status == "success"
    system, segments = sol.source.system, sol.source.segments
    slips = stops = 0
    for i, seg in enumerate(segments):
        rows = seg.phase.friction
        if rows is None or seg.t1 <= seg.t0:
            continue
        for pair, row in enumerate(rows):
            if not coulomb.slipping(row):
                continue
            slips += 1
            back = max(VT_NOISE, row[3]) + ROUNDOFF
            times = np.linspace(seg.t0, seg.t1, 66)[1:-1]
            along = [row[4] * slip_velocity(system, t, y, pair) for t, y in zip(times, seg.states(times))]
            assert min(along) >= -back, (seg.t0, seg.t1, min(along))
            after = next((s for s in segments[i + 1 :] if s.phase.friction is not None), None)
            if after is not None and after.phase.friction[pair, 1] != 0.0:  # the slip stopped: the pair sticks
                stops += 1
                assert abs(slip_velocity(system, seg.t1, seg.y1, pair)) <= AT_STOP, seg.t1
    assert slips >= 20 and stops >= 10  # the case does exercise the search
