"""The half-plane's warm station scan of contact anywhere (``kernels/src/nearest_scan.c``) is the full scan.

The search for the beam's point nearest a half-plane scans all the stations for the lowest one and runs Newton's
method around it.  Consecutive searches within one kernel call start instead from the last full scan's least values,
and evaluate only the stations that a bound on how far each station's value can have moved leaves as candidates (the
full scan runs where too many are).  That bound is a proof, not a heuristic: the warm scan picks the full scan's
station, and from it the same arithmetic follows, so the gap, the contact point and the normal must be the full
scan's to the bit -- the tolerance is zero, no round-off allowance is derived because none is needed, on any
machine.  Checked on paths of states (one kernel call each, ``_core.nearest_path``) with the warm scan on and off:

* random paths: small steps (where the warm scan serves), large ones and random jumps of the frame's angle and the
  modes (where it must fall back), from any angle and from nearly flat on the floor (every station nearly as low:
  the fallback), on the capsule, with flat end faces, and with axial modes;
* a bent bar turned through the angle where its two ends are equally low: the nearest point jumps from one end to
  the other (0.2 m along the beam) within the path, and the warm scan must follow that jump.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import flexbeam as fb
from flexbeam.kernels import _core
from flexbeam.model.clearance import centre_line
from flexbeam.model.system import BeamSystem

DATA = "tests/validation/data/free-bar-drop.toml"
VARIANTS = {
    "caps": {},
    "flat": {"beam.end_caps": "flat"},
    "axial": {"model.axial_modes": 3},
}


@cache
def _system(variant: str) -> BeamSystem:
    return BeamSystem.from_case(fb.load_case(DATA, VARIANTS[variant]))


def _path(system: BeamSystem, frames: np.ndarray, q: np.ndarray) -> np.ndarray:
    """States (rows): the frame (G_x, G_y, theta) and the flexible coordinates of each row, at rest."""
    Y = np.zeros((frames.shape[0], system.size))
    nr = system.nz - system.n
    Y[:, :nr], Y[:, nr : system.nz] = frames, q
    return Y


def _searches(system: BeamSystem, Y: np.ndarray, warm: bool) -> tuple[np.ndarray, int]:
    """Rows [gap, x, n_x, n_y] of the floor's pair along the path, in one kernel call; and the full scans made."""
    out = np.empty((Y.shape[0], 4))
    full = _core.nearest_path(system.kernel, 0, 0.0, np.ascontiguousarray(Y), int(warm), out)
    return out, full


@settings(max_examples=60, deadline=None)
@given(
    variant=st.sampled_from(sorted(VARIANTS)),
    theta0=st.one_of(st.floats(-math.pi, math.pi), st.floats(-0.01, 0.01)),
    bend=st.floats(0.0, 0.05),
    step=st.floats(1e-8, 0.1),
    jumps=st.floats(0.0, 0.3),
    seed=st.integers(0, 2**32 - 1),
)
def test_the_warm_scan_finds_the_full_scans_point_along_random_paths(variant, theta0, bend, step, jumps, seed):
    """Along a random walk of the frame's angle and the modes (steps of ``step`` rad and ``step`` times 2 % of the
    length, a share ``jumps`` of the rows jumping anywhere), the warm scan's gap, point and normal are the full
    scan's, bit for bit."""
    system = _system(variant)
    rng = np.random.default_rng(seed)
    L, rows, n = system.beam.length, 40, system.n
    weights = rng.normal(size=n) / np.arange(1, n + 1) ** 2  # the lower modes bend the most
    q0 = bend * L * weights / max(float(np.abs(weights).sum()), 1e-300)
    frames, q = np.empty((rows, 3)), np.empty((rows, n))
    frames[0], q[0] = (0.0, 0.05, theta0), q0
    for i in range(1, rows):
        if rng.random() < jumps:
            frames[i] = (0.0, 0.05, rng.uniform(-math.pi, math.pi))
            q[i] = bend * L * rng.normal(size=n) / n
        else:
            frames[i] = frames[i - 1] + (0.0, 0.0, step * rng.normal())
            q[i] = q[i - 1] + step * 0.02 * L * rng.normal(size=n) / n
    Y = _path(system, frames, q)
    cold, full = _searches(system, Y, warm=False)
    warm, _ = _searches(system, Y, warm=True)
    assert full == rows  # the reference: every search scanned every station
    assert np.all(np.isfinite(cold))
    np.testing.assert_array_equal(warm, cold)


def test_the_warm_scan_follows_the_nearest_point_from_one_end_to_the_other():
    """A bar bent by its first mode into a U (the middle 2 mm above the ends) turned through the angle theta* where
    both ends are equally low (tan theta* = -(rho_y(L) - rho_y(0)) / (rho_x(L) - rho_x(0)), from the independent
    centre line of flexbeam.model.clearance): the nearest point is at one end before theta* and at the other after
    it.  The warm scan must give the full scan's answer, jump included, while scanning in full at most half of the
    searches (that it served the others; measured: 12 full scans of 81, where both ends' stations crowd the
    candidates near theta*)."""
    system = _system("caps")
    L, n = system.beam.length, system.n
    x = np.linspace(0.0, L, 201)
    unit = np.zeros(n)
    unit[0] = 1.0
    rx, ry, _ = centre_line(system.beam, unit, x)
    rise = ry[100] - 0.5 * (ry[0] + ry[-1])  # the middle over the ends, per unit of q_1
    q = unit * 2e-3 / rise  # a U: the middle 2 mm above the ends
    rx, ry, _ = centre_line(system.beam, q, x)
    theta_star = math.atan2(-(ry[-1] - ry[0]), rx[-1] - rx[0])
    thetas = theta_star + np.linspace(-2e-3, 2e-3, 81)
    frames = np.column_stack((np.zeros(81), np.full(81, 0.05), thetas))
    Y = _path(system, frames, np.tile(q, (81, 1)))
    cold, full_cold = _searches(system, Y, warm=False)
    warm, full_warm = _searches(system, Y, warm=True)
    ends = sorted((cold[0, 1], cold[-1, 1]))
    assert ends[0] < 1e-3 * L and ends[1] > (1 - 1e-3) * L  # the point has jumped from one end to the other
    np.testing.assert_array_equal(warm, cold)
    assert full_cold == 81
    assert full_warm <= 81 // 2
