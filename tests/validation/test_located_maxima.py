"""The contact records' peak forces and the tip's extremes, located in the kernels (``kernels/src/extremes.c``: a
grid that resolves the fastest mode still vibrating, then Brent's method), against brute force on the same dense
output: a zoom on a fine grid around each record's peak, and a dense grid of the whole run for the tip.

The located maximum is a value of the output, so it cannot exceed the true one, and what the brute force reaches
cannot exceed the located maximum by more than the round-off of the output's evaluation (1e-12 relative: the force
and the tip are sums of terms of their own size).  The brute force zooms to 1e-10 s from its best grid points
(the tip: the five largest samples of a 1e-7 s grid of each phase; the force: a 257-point grid over a tenth of the
contact around the located peak), so the two agree to 1e-9 relative unless one of them misses a maximum.
"""

from __future__ import annotations

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.results.peaks import PEAK_XTOL, zoom_max

RUNS = [
    ("seed-experiment", "ccfm", 0.1),
    ("seed-experiment", "ccm", 0.05),
    ("two-stops", "ccfm", 0.1),
    ("tip-wall", "ccfm", 0.05),
    ("spinning-stop", "ccfm", 0.6),
]


@pytest.mark.parametrize(("name", "method", "t_end"), RUNS)
def test_record_peaks_against_a_zoom_on_the_dense_output(name, method, t_end):
    sol = fb.simulate(fb.load_case(name, {"solver.t_end": t_end}), method)
    src = sol.source
    checked = 0
    for ev in sol.contacts:
        if not np.isfinite(ev.peak_force) or ev.peak_force <= 0.0:
            continue
        width = 0.1 * max(ev.end - ev.onset, 1e-6) if np.isfinite(ev.end) else 1e-5
        a, b = max(ev.onset, ev.peak_time - width), ev.peak_time + width
        if np.isfinite(ev.end):
            b = min(b, ev.end)
        t_z, f_z = zoom_max(lambda t, p=ev.pair: src.force_many(t, p), a, b, xtol=PEAK_XTOL, points=257)
        assert ev.peak_force >= f_z * (1.0 - 1e-9), (ev.onset, ev.peak_force, f_z)
        assert ev.peak_force <= f_z * (1.0 + 1e-9), (ev.onset, ev.peak_force, f_z)
        checked += 1
    assert checked >= 1


@pytest.mark.parametrize(("name", "method", "t_end"), [r for r in RUNS if r[2] <= 0.1])
def test_tip_extremes_against_a_dense_grid(name, method, t_end):
    sol = fb.simulate(fb.load_case(name, {"solver.t_end": t_end}), method)
    m = sol.metrics()
    src = sol.source
    best = {1.0: -np.inf, -1.0: -np.inf}
    for seg in src.segments:
        if seg.t1 <= seg.t0:
            continue
        t = np.linspace(seg.t0, seg.t1, max(3, int((seg.t1 - seg.t0) / 1e-7)))
        v = src.evaluate(seg, t)[0]["tip_deflection"]
        dt = t[1] - t[0]
        for sign in best:
            for i in np.argsort(-sign * v)[:5]:  # the five largest samples, each zoomed between its neighbours
                a, b = max(seg.t0, t[i] - dt), min(seg.t1, t[i] + dt)
                tip = lambda tt, s=seg, g=sign: g * src.evaluate(s, tt)[0]["tip_deflection"]  # noqa: E731
                best[sign] = max(best[sign], zoom_max(tip, a, b, xtol=PEAK_XTOL, points=65)[1])
    hi, lo = best[1.0], -best[-1.0]
    scale = max(abs(lo), abs(hi))
    # the located extremes against brute force on the same dense output, within the evaluation's round-off and
    # what a grid of 1e-7 s may still miss of the fastest modes' oscillation (both < 1e-9 relative)
    assert m["tip_deflection_max"] == pytest.approx(hi, rel=1e-9, abs=0.0)
    assert m["tip_deflection_min"] == pytest.approx(lo, rel=1e-9, abs=0.0)
    assert m["tip_deflection_max"] >= hi - 1e-12 * scale  # never short of a value the brute force reached
    assert m["tip_deflection_min"] <= lo + 1e-12 * scale
