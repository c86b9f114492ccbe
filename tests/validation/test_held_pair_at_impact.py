"""A pair held on its obstacle when another pair impacts: the closed contact joins the impact problem.

A rigid bar (no modes, gravity) lies with its left end on a stop A and turns about it until its right end strikes a
stop B 2 cm lower (contact anywhere on both).  CCM holds A by its constraint from t = 0 (IMM: the resting phase of a
plastic first contact).  At B's impact the impulse at B alone would drive A into its stop (its normal velocity
-0.22 m/s under CCM, -0.32 m/s under IMM), where A's constraint on delta = 0 cannot start: both runs failed there
("no progress").  A held pair now takes part in the impact with e = 0 (Pfeiffer & Glocker 1996, Ch. 7).

Checked against a hand-built impact problem: the bar's mass matrix diag(m, m, m L^2 / 12) in (x_G, y_G, theta) and
each stop's row J = [n_x, n_y, s (n . u_perp)] at the centre line's point nearest the sphere's centre (s its arm from
G along u = (cos theta, sin theta); the gap of the capsule |rho(s) - C| - c - r_s has this rate by the envelope
theorem), both pairs active: W P = -(1 + e) v-, e = (0, e_B).  The post-impact velocities agree to 1e-10 relative
(the impact maps' round-off), A's normal velocity after is 0 and B's -e_B times its approach, both impulses >= 0, and
the kinetic energy does not grow (1e-12 relative).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.model.system import BeamSystem

L, C, R_STOP, RHO, YG, TILT = 0.2, 0.00635, 0.01, 7870.0, 0.1, 0.1
ARM = 0.4 * L  # the stops sit under the centre line's points at -+ARM from G


def plank(e: float) -> fb.Case:
    """The bar tilted by TILT with its lower surface touching stop A under s = -ARM, stop B 2 cm below the surface
    under s = +ARM, at rest."""
    ca, sa = math.cos(TILT), math.sin(TILT)
    below = ((C + R_STOP) * sa, -(C + R_STOP) * ca)  # from the centre line to the stop's centre, across the bar
    stop_a = [-ARM * ca + below[0], YG - ARM * sa + below[1]]
    stop_b = [ARM * ca + below[0], YG + ARM * sa + below[1] - 0.02]
    return fb.load_case({
        "name": "plank", "beam": {"length": L, "density": RHO, "youngs_modulus": 200e9, "poisson_ratio": 0.29,
                                   "section": "circle", "radius": C},
        "joint": {"kind": "free"}, "model": {"modes": 0, "gravity": 9.81},
        "obstacle": {"kind": "sphere", "centre": stop_a, "radius": R_STOP},
        "obstacles": [{"kind": "sphere", "centre": stop_b, "radius": R_STOP, "contact": {"position": 0.9 * L}}],
        "contact": {"law": "lankarani_nikravesh", "position": 0.1 * L, "stiffness": 1.16e10, "side": "below",
                    "restitution": e, "anywhere": True},
        "initial": {"kind": "state", "position": [0.0, YG], "velocity": [0.0, 0.0], "angle": TILT, "rate": 0.0},
        "solver": {"t_end": 0.2},
    })  # fmt: skip


def hand_built_rows(z: np.ndarray, centres: list[np.ndarray]) -> np.ndarray:
    """The stops' gap Jacobians of the rigid bar at z = (x_G, y_G, theta) (module docstring)."""
    G, th = z[:2], z[2]
    u, up = np.array([math.cos(th), math.sin(th)]), np.array([-math.sin(th), math.cos(th)])
    rows = []
    for c in centres:
        s = float(np.clip((c - G) @ u, -L / 2, L / 2))
        n = (G + s * u - c) / np.linalg.norm(G + s * u - c)
        rows.append([n[0], n[1], s * (n @ up)])
    return np.array(rows)


@pytest.mark.parametrize(("method", "e"), [("ccm", 0.0), ("imm", 0.5)])
def test_a_held_pair_joins_the_impact_of_another(method, e):
    case = plank(0.5)
    sol = fb.simulate(case, method)
    assert sol.status == "success", sol.message
    system = BeamSystem.from_case(case)
    first_b = next(ev for ev in sol.contacts if ev.pair == 1)
    before = next(s for s in sol.source.run.segments if s.t1 == first_b.onset)
    after = next(s for s in sol.source.run.segments if s.t0 == first_b.onset and s.t1 > s.t0)
    assert before.phase.modes[0].name == "CONSTRAINT"  # A is held when B strikes
    t, y_minus, y_plus = first_b.onset, before.y1, after.y0
    zd_minus, zd_plus = system.velocities(t, y_minus), system.velocities(t, y_plus)
    centres = [np.array(case.obstacle.centre), np.array(case.obstacles[0].centre)]
    J = hand_built_rows(y_minus[:3], centres)
    m = RHO * math.pi * C**2 * L
    Minv = np.diag([1 / m, 1 / m, 12 / (m * L**2)])
    v_minus = J @ zd_minus
    # B approaches; A slides on its stop, its normal velocity held to the integrator's tolerance (measured 2e-9 m/s)
    assert v_minus[1] < -0.5 and abs(v_minus[0]) < 1e-6
    P = np.linalg.solve(J @ Minv @ J.T, -(1.0 + np.array([0.0, e])) * v_minus)
    assert np.all(P >= 0.0)
    expected = zd_minus + Minv @ J.T @ P
    np.testing.assert_allclose(zd_plus, expected, rtol=1e-10, atol=1e-10 * np.max(np.abs(expected)))
    v_plus = [system.gap(t, y_plus, k)[1] for k in range(2)]
    assert abs(v_plus[0]) <= 1e-12 and v_plus[1] == pytest.approx(-e * v_minus[1], abs=1e-12)
    T = [0.5 * zd @ np.diag([m, m, m * L**2 / 12]) @ zd for zd in (zd_minus, zd_plus)]
    assert T[1] <= T[0] * (1.0 + 1e-12)
