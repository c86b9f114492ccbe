"""Obstacles fixed to the ground on a moving base (``fixed_to = "ground"``): the beam sees one at C - r_O(t).

* A plane rising toward a clamped cantilever whose base accelerates downward (a_O = (0, -a), no gravity): the beam
  feels the field (0, a) and the ground plane comes at it as -h + a t^2 / 2 in the base frame.  The first contact
  starts where the tip's free path (a run with the obstacle out of reach) meets that parabola, with the normal
  velocity of the tip relative to the plane, v_tip - a t (/work/research/moving_base.md section 4).
* A base shaken along a plane's tangent moves a ground plane within itself: the same run as a carried plane.
* The shaker case with its stop fixed to the ground: every method balances the energy with the ground's work
  W_g = -int F n . v_O dt booked (without it the step control's energy checks fail the run).
* A base motion that puts the beam inside a ground obstacle at t = 0 is refused in one line (exit 2).
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
import tomli_w
from scipy.optimize import brentq

import flexbeam as fb
from flexbeam.errors import ParameterError

SHAKER = "tests/validation/data/shaker-stop.toml"


def falling_plane(h: float, a: float, fixed_to: str) -> dict:
    """The shaker's cantilever, its tip's centre line as the contact point, over a plane h below it (or far away),
    the base accelerating downward at a."""
    return {
        "base.harmonics": [], "base.acceleration": [0.0, -a],
        "obstacle.kind": "half-plane", "obstacle.centre": [0.0, -h], "obstacle.normal": [0.0, 1.0],
        "obstacle.fixed_to": fixed_to, "contact.side": "centre", "contact.law": "hertz", "contact.stiffness": 1e9,
        "solver.t_end": 0.06,
    }  # fmt: skip


def test_a_ground_plane_meets_the_tip_where_its_free_path_crosses_the_planes():
    """The free run's tip y(t) (obstacle 10 m away) against the plane at -h + a t^2 / 2: the onset and the relative
    normal velocity of the ground run's first contact agree with the crossing to 1e-9 s and 1e-7 relative (the two
    runs' step sequences may differ; measured: equal onsets, 8e-16)."""
    h, a = 1e-3, 2.0
    free = fb.simulate(fb.load_case(SHAKER, falling_plane(10.0, a, "base")), "ccfm")
    assert free.status == "success" and not free.contacts
    system, seg = free.source.system, free.source.segments[-1]

    def tip(t: float) -> tuple[np.ndarray, np.ndarray]:
        r, v, _, _ = system.point_state(t, seg.states(np.array([t]))[0], 1)
        return r, v

    onset = brentq(lambda t: tip(t)[0][1] + h - 0.5 * a * t * t, 0.0, 0.06, xtol=1e-15)
    relative = tip(onset)[1][1] - a * onset  # n . (v_tip + v_O), v_O = (0, -a t)
    ground = fb.simulate(fb.load_case(SHAKER, falling_plane(h, a, "ground")), "ccfm")
    first = ground.contacts[0]
    assert first.onset == pytest.approx(onset, abs=1e-9)
    assert first.velocity_before == pytest.approx(relative, rel=1e-7)
    assert relative < -0.05  # the plane overtakes the tip, not the tip the plane


def test_a_base_shaken_along_a_plane_moves_a_ground_plane_within_itself():
    """Shaken along x (and accelerating along x) over a plane with normal (0, 1), under gravity: the ground plane's
    motion relative to the base is tangential, the gap and its rate unchanged, the same bits as the carried plane."""
    over = {"base.harmonics": [{"axis": "x", "amplitude": 2e-3}], "base.acceleration": [-3.0, 0.0],
            "model.gravity": 9.81, "obstacle.kind": "half-plane", "obstacle.centre": [0.0, -2e-3],
            "obstacle.normal": [0.0, 1.0], "contact.stiffness": 1e9, "solver.t_end": 0.3}  # fmt: skip
    runs = [fb.simulate(fb.load_case(SHAKER, {**over, "obstacle.fixed_to": f}), "ccfm") for f in ("base", "ground")]
    assert len(runs[0].contacts) > 3
    assert [c.peak_force for c in runs[0].contacts] == [c.peak_force for c in runs[1].contacts]


@pytest.mark.parametrize("method", ["ccfm", "ccm", "imm"])
def test_the_shaker_on_a_ground_stop_balances_its_energy(method):
    """The shaker case (0.5 mm at 15 Hz) with its sphere fixed to the ground, 0.3 s: impacts of the tip on a stop
    the base shakes relative to it, the energy balance (the base's and the ground's work booked) to 5e-5 (measured
    1.6e-6, 8.7e-6 and 8e-7 under CCFM, CCM, IMM); the first onset differs from the carried stop's."""
    case = fb.load_case(SHAKER, {"obstacle.fixed_to": "ground", "solver.t_end": 0.3})
    sol = fb.simulate(case, method)
    carried = fb.simulate(fb.load_case(SHAKER, {"solver.t_end": 0.1}), method)
    assert sol.status == "success" and len(sol.contacts) > 5
    assert abs(sol.metrics()["energy_drift_max"]) < 5e-5
    assert abs(sol.contacts[0].onset - carried.contacts[0].onset) > 1e-3


def test_the_reference_integrator_agrees_on_a_ground_stop():
    """The same shaker case on scipy's DOP853 (its W rate: -a_O . d/dt[A s] - F n . v_O): the first contact agrees
    with the exponential integrator's to 1e-8 s and its peak force to 1e-5 (measured 2e-11 s, 4e-7), and its energy
    balances to 1e-6 (measured 2.7e-9)."""
    over = {"obstacle.fixed_to": "ground", "solver.t_end": 0.06}
    fast = fb.simulate(fb.load_case(SHAKER, over), "ccfm")
    ref = fb.simulate(fb.load_case(SHAKER, {**over, "solver.integrator": "reference"}), "ccfm")
    assert ref.contacts[0].onset == pytest.approx(fast.contacts[0].onset, abs=1e-8)
    assert ref.contacts[0].peak_force == pytest.approx(fast.contacts[0].peak_force, rel=1e-5)
    assert abs(ref.metrics()["energy_drift_max"]) < 1e-6


#: the shaker moved 5 mm down at t = 0 (phase -pi/2): its ground sphere, 1 mm under the tip, is then 4 mm into it
INSIDE = {"obstacle.fixed_to": "ground", "base.harmonics": [{"axis": "y", "amplitude": 5e-3, "phase": -1.5707963}]}


def test_a_base_that_starts_the_beam_inside_a_ground_obstacle_is_refused(tmp_path):
    with pytest.raises(ParameterError, match=r"^obstacle\.centre: the beam starts"):
        fb.simulate(fb.load_case(SHAKER, INSIDE), "ccfm")
    data = fb.load_case(SHAKER, INSIDE).model_dump(mode="json", exclude_none=True)
    path = tmp_path / "inside.toml"
    path.write_text(tomli_w.dumps(data), encoding="utf-8")
    r = subprocess.run([sys.executable, "-m", "flexbeam.cli", "run", str(path), "-o", str(tmp_path / "out")],
                       capture_output=True, text=True, timeout=600)  # fmt: skip
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert len(r.stderr.splitlines()) == 1 and r.stderr.startswith("error: obstacle.centre: the beam starts")
    carried = fb.load_case(SHAKER, {**INSIDE, "obstacle.fixed_to": "base"})
    assert fb.simulate(carried, "ccfm").status == "success"  # carried, the sphere moves with the base
