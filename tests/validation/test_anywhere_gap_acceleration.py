"""The gap acceleration gamma of a contact found anywhere: the true gap's, not the nearest point's as a material point.

For a pair with ``contact.anywhere`` the gap is D(q) = min over the surface of delta(x, q).  By the envelope theorem
D' = delta_q q' at the minimiser x*, but D'' = delta''(x*) - (delta_xq q')^2 / delta_xx (x* moves along the beam);
``kernels/src/anywhere_gamma.c`` applies the correction.

**A bar sliding over two stops.**  The rigid bar of ``test_friction_ccm.py`` slides along its axis over two
hemispherical stops with CCM holding both gaps closed: its centre of mass moves horizontally at a constant height,
so the normal forces carry the weight, F_1 + F_2 = m g, at every sample.  The material point's gamma v_t^2 / rho
made the Dataset's sampled force ~10 % too large; the true gap's gamma is 0 (a straight bar translating along itself
over a sphere keeps its distance).  Asserted within the fast integrator's relative tolerance (measured 2e-8).

**gamma against the true gap's second difference.**  Along the path z(t) = z0 + t z0' (z'' = 0) the true gap's
second derivative is gamma itself: D''(0) = J z'' + gamma = gamma.  D is the kernel's gap at the nearest point (the
minimum over the surface), so the central difference (D(h) - 2 D(0) + D(-h)) / h^2 is independent of gamma.  Its
truncation error h^2 D'''' / 12 is estimated by the difference between the steps 2h and h (which is 3 times it), and
its round-off by 4 eps |r| / h^2 (|r| the beam's reach); the tolerance is 10 times their sum.  The cases: the free
bar of ``free-bar-drop.toml`` with 8 bending and 4 axial modes, bent, spinning and sliding, over its half-plane and
over a sphere, with the nearest point inside the beam and on an end cap.  Main's material-point gamma was off by
5e-3 to 4.7 m/s^2 against tolerances of ~3e-5.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.model.system import BeamSystem

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_ccfm import G, bar_on_stops  # noqa: E402
from test_friction_ccm import MASS, RTOL, run  # noqa: E402

DATA = Path(__file__).resolve().parent / "data" / "free-bar-drop.toml"
SPHERE = {"obstacle.kind": "sphere", "obstacle.radius": 0.02, "obstacle.centre": [0.1, -0.03]}


@pytest.mark.parametrize("mu", [0.0, 0.3])
def test_the_sampled_normal_forces_of_a_bar_sliding_over_two_stops_carry_its_weight(mu):
    """F_1 + F_2 = m g at every sample (CCM holds the gaps; G moves horizontally) within fast_rtol, frictionless at
    constant speed and frictional while slipping to rest and then sticking."""
    sol = run(bar_on_stops(mu, 0.1, 0.05))
    total = sol["pair_contact_force"].sum(axis=1)
    np.testing.assert_allclose(total, MASS * G, rtol=RTOL)


def straight_path(y0: np.ndarray, nz: int, t: float) -> np.ndarray:
    """The state at time t on the path z = z0 + t z0', z' = z0' (z'' = 0)."""
    y = y0.copy()
    y[:nz] = y0[:nz] + t * y0[nz : 2 * nz]
    return y


def bent_spinning_state(nz: int, size: int, sag: float) -> np.ndarray:
    """The free bar at 1 cm, tilted 0.05 rad, bent by ``sag`` in its first mode, sliding at 0.5 m/s, falling at
    0.3 m/s and spinning at 2 rad/s, its modes vibrating."""
    y = np.zeros(size)
    y[:5] = [0.0, 0.01, 0.05, sag, 1e-3]
    y[11] = 1e-4  # the first axial mode's stretch
    y[nz : nz + 3] = [0.5, -0.3, 2.0]
    y[nz + 3 : 2 * nz] = 0.02 * np.sin(np.arange(nz - 3) + 1.0)
    return y


@pytest.mark.parametrize("sag", [2e-3, -2e-3], ids=["inside", "end-cap"])
@pytest.mark.parametrize("obstacle", ["half-plane", "sphere"])
def test_gamma_is_the_true_gaps_second_derivative_at_zero_acceleration(obstacle, sag):
    """gamma = D'' along z'' = 0 (the second difference of the kernel's minimum gap), within 10 x (truncation +
    round-off)."""
    case = fb.load_case(DATA, {"model.axial_modes": 4, **(SPHERE if obstacle == "sphere" else {})})
    system = BeamSystem.from_case(case)
    nz = system.nfull  # the free joint gives no coordinate
    y0 = bent_spinning_state(nz, 2 * nz + 2, sag)
    x = system.contact_coordinate(0.0, y0)
    length = case.beam.length
    assert (0.0 < x < length) if sag > 0 else x in (0.0, length)  # the case is the one named
    D0, _, gamma, _ = system.gap(0.0, y0)
    h = 1e-4

    def second_difference(step: float) -> float:
        Dm, Dp = (system.gap(t, straight_path(y0, nz, t))[0] for t in (-step, step))
        return (Dp - 2.0 * D0 + Dm) / step**2

    fd, fd2 = second_difference(h), second_difference(2.0 * h)
    truncation = abs(fd2 - fd) / 3.0
    rounding = 4.0 * np.finfo(float).eps * 2.0 * length / h**2
    assert abs(fd - gamma) <= 10.0 * (truncation + rounding), (fd, gamma, truncation, rounding)
