"""CCM's flights that start on a stop after a release: the event search misses no landing and no sinking in.

After a release (the multiplier crosses zero with the gap and its rate held at zero) the pair's point starts its
flight on the surface, a few pm beyond it at most (the held constraint's drift).  The search on each step of such a
flight (``kernels/src/events.c``) must report where the point, having lifted off, comes back (an impact) and where
it sinks in more than ``SURFACE_NOISE`` beyond its start; it skips its dense searches for both where a bound on the
gap's curvature proves neither can happen (``on_surface_quiet``).  Checked here independently of the search: the
pair's gap on the phase's exact dense output, sampled densely (``SAMPLES`` points per step), never returns to the
surface from above it and never sinks beyond that depth before the phase's end (its located event).  The cases:
the seed case (its flights stay on the surface: the skip applies), two stops under a beam and the free bar's drop
(flights whose searches find the landings: skipping them there changes those runs).  The same check on every free
flight of the seed case under each method covers the search's finer levels, which sample only past the stretch a
coarser level proved free.
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


def flights(sol, system, after_release: bool = True):
    """(t, gap) samples of each pair's free flight, up to the phase's end (excluded): the flights that start at a
    release (``after_release``), or every free phase's (the first phase's too)."""
    segments = sol.source.segments
    out = []
    for before, seg in zip([None, *segments], segments):
        if seg.dense is None or seg.t1 <= seg.t0 or (after_release and before is None):
            continue
        ends = seg.breaks()
        t = np.concatenate([np.linspace(a, b, SAMPLES, endpoint=False) for a, b in zip(ends, ends[1:])])
        t = np.unique(t[t < seg.t1])
        Y = None
        for k, m1 in enumerate(seg.phase.modes):
            released = before is not None and before.phase.modes[k] == ContactMode.CONSTRAINT
            if m1 == ContactMode.NONE and (released or not after_release):
                Y = seg.states(t) if Y is None else Y
                out.append((t, np.array([system.gap(ti, yi, k)[0] for ti, yi in zip(t, Y)])))
    return out


def assert_nothing_missed(found):
    """No sinking in beyond the start's depth + SURFACE_NOISE, no return to the surface after lifting off."""
    assert found
    for t, g in found:
        depth = max(-g[0], 0.0) + SURFACE_NOISE
        assert np.all(-g <= depth), f"sinks in beyond {depth:g} m unnoticed in the flight from t = {t[0]:.9g} s"
        above = np.flatnonzero(g > ABOVE)
        if above.size:  # lifted off: from there on it stays above the surface until the phase's end (the landing)
            assert np.all(g[above[0] :] > 0.0), f"lands unnoticed in the flight from t = {t[0]:.9g} s"


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
    assert_nothing_missed(flights(sol, BeamSystem.from_case(case)))


@pytest.mark.parametrize("method", ["ccfm", "ccm", "imm"])
def test_no_landing_missed_in_any_flight(method):
    """Every free flight of the seed case (0.1 s), from the rest, a rebound or a release: the steps that approach a
    landing are searched on finer levels of samples only past the stretch a coarser level proved free
    (``fb_find_gap_event``); sampled densely here, none of them crosses the surface before its located landing."""
    case = fb.load_case("seed-experiment", {})
    sol = fb.simulate(case, method)
    assert_nothing_missed(flights(sol, BeamSystem.from_case(case), after_release=False))
