"""CCM's flights that start on a stop after a release: the event search misses no landing and no sinking in.

After a release (the multiplier crosses zero with the gap and its rate held at zero) the pair's point starts its
flight on the surface, a few pm beyond it at most (the held constraint's drift).  The search on each step of such a
flight (``kernels/src/events.c``) must report where the point, having lifted off, comes back (an impact) and where
it sinks in more than ``SURFACE_NOISE`` beyond its start; it skips its dense searches for both where a bound on the
gap's curvature proves neither can happen (``on_surface_quiet``).  Checked here independently of the search: the
pair's gap on the phase's exact dense output, sampled densely (``SAMPLES`` points per step), never returns to the
surface from above it and never sinks beyond that depth before the phase's end (its located event).  The cases:
the seed case (its flights stay on the surface: the skip applies), two stops under a beam and the free bar's drop
(flights whose searches find the landings: skipping them there changes those runs).
"""

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.integrate.phases import ContactMode
from flexbeam.model.system import BeamSystem
from tests.validation.fingerprints import DATA

SURFACE_NOISE = 1e-9  # [m] the search's sinking depth (events.c): an event only beyond it
SAMPLES = 400  # per step of a flight
#: [m] a sample counts as above the surface only beyond this: 10x the search's round-off allowance (GAP_ROUNDOFF,
#: itself 300x the ~3e-18 m by which the gap of one state differs between two evaluation paths)
ABOVE = 1e-14


def release_flights(sol, system):
    """(t, gap) samples of each pair's flight after its release, up to the phase's end (excluded)."""
    segments = sol.source.segments
    out = []
    for before, seg in zip(segments, segments[1:]):
        if seg.dense is None or seg.t1 <= seg.t0:
            continue
        ends = seg.breaks()
        t = np.concatenate([np.linspace(a, b, SAMPLES, endpoint=False) for a, b in zip(ends, ends[1:])])
        t = np.unique(t[t < seg.t1])
        Y = seg.states(t)
        for k, (m0, m1) in enumerate(zip(before.phase.modes, seg.phase.modes)):
            if m0 == ContactMode.CONSTRAINT and m1 == ContactMode.NONE:
                out.append((t, np.array([system.gap(ti, yi, k)[0] for ti, yi in zip(t, Y)])))
    return out


@pytest.mark.parametrize(
    "source, over",
    [
        ("seed-experiment", {"model.modes": 4}),
        ("seed-experiment", {}),
        ("two-stops", {}),
        (DATA / "free-bar-drop.toml", {}),
    ],
)
def test_no_landing_or_sinking_missed_after_a_release(source, over):
    case = fb.load_case(source, over)
    sol = fb.simulate(case, "ccm")
    flights = release_flights(sol, BeamSystem.from_case(case))
    assert flights
    for t, g in flights:
        depth = max(-g[0], 0.0) + SURFACE_NOISE
        assert np.all(-g <= depth), f"sinks in beyond {depth:g} m unnoticed in the flight from t = {t[0]:.9g} s"
        above = np.flatnonzero(g > ABOVE)
        if above.size:  # lifted off: from there on it stays above the surface until the phase's end (the landing)
            assert np.all(g[above[0] :] > 0.0), f"lands unnoticed in the flight from t = {t[0]:.9g} s"
