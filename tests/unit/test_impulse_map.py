"""One frictionless pair's impulse-momentum map compiled (``kernels/src/impulse_map.c``, ``BeamSystem.normal_jump``)
against the Python map it stands in for (:func:`flexbeam.methods.impulse.lcp_jump`): the same operations in the same
order, so the same bits -- the state after the jump, the impulse, the normal velocities and kinetic energies -- on
states of real runs (every phase's ends, and the same states with their velocities reversed so that half of them
approach), for a beam on a revolute joint, with axial modes, a free bar and a contact anywhere, at e = 0, 0.5 and 1.
The physics of the map (v+ = -e v-, the energy it removes) is tested in test_properties.py and
tests/validation/test_impact_methods.py; this file checks that the fast path changes none of it."""

from __future__ import annotations

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.methods.impulse import impulse_jump, lcp_jump
from flexbeam.model.system import BeamSystem
from tests.conftest import PRESCRIBED_SPIN

FREE_BAR = "tests/validation/data/free-bar-drop.toml"


def _states(name: str, method: str, over: dict) -> tuple[BeamSystem, list[tuple[float, np.ndarray]]]:
    """The system of a run and (t, y) at its phases' ends, each also with its velocities reversed."""
    sol = fb.simulate(fb.load_case(name, over), method)
    system = sol.source.system
    nz = system.nz
    out = []
    for seg in sol.source.segments:
        for t, y in ((seg.t0, seg.y0), (seg.t1, seg.y1)):
            back = np.array(y, float)
            back[nz : 2 * nz] *= -1.0
            out += [(t, np.array(y, float)), (t, back)]
    return system, out


@pytest.mark.parametrize(
    ("name", "method", "over"),
    [
        ("seed-experiment", "ccm", {"solver.t_end": 0.03}),
        ("tip-wall", "imm", {"solver.t_end": 0.02, "model.axial_modes": 4}),
        (FREE_BAR, "ccm", {}),
        ("spinning-stop", "imm", {}),  # (its stop is met after 0.2 s)
    ],
)
def test_the_compiled_map_equals_the_python_map(name, method, over):
    system, states = _states(name, method, over)
    approached = 0
    for t, y in states:
        for e in (0.0, 0.5, 1.0):
            fast = system.normal_jump(t, y, 0, e)
            assert fast is not None
            y_plus, (P, v_minus, v_plus, T_minus, T_plus) = fast
            ref = lcp_jump(system, t, y, np.array([e]), [0])
            np.testing.assert_array_equal(y_plus, ref.y)
            assert (P, v_minus, v_plus) == (ref.impulse, ref.velocity_before, ref.velocity_after)
            assert (T_minus, T_plus) == (ref.kinetic_before, ref.kinetic_after)
            approached += P > 0.0
            # and impulse_jump, which takes the fast path, returns exactly the Python map's Jump
            jump = impulse_jump(system, t, y, e)
            np.testing.assert_array_equal(jump.y, ref.y)
            assert jump.impulses.tolist() == ref.impulses.tolist()
            assert jump.velocities_after.tolist() == ref.velocities_after.tolist()
    assert approached >= 3  # some of the states approach: the impulse's branch is compared, not only P = 0


@pytest.mark.parametrize(
    ("name", "over"),
    [
        (  # theta prescribed: only the modal velocities jump (M and J restricted)
            "seed-experiment",
            PRESCRIBED_SPIN,
        ),  # fmt: skip
        ("seed-experiment-calibrated", {}),  # a compliant support: M bordered by m_s
        (  # an obstacle still in the plane on a moving base: its velocity enters v-
            "seed-experiment",
            {
                "base.frequency": 20.0,
                "base.harmonics": [{"axis": "y", "amplitude": 1e-4}],
                "obstacle.fixed_to": "ground",
            },
        ),  # fmt: skip
    ],
)
def test_the_python_map_takes_what_the_compiled_one_leaves(name, over):
    """The states the compiled map does not cover are handed to the Python map (None), whose result impulse_jump
    returns."""
    case = fb.load_case(name, over)
    system = BeamSystem.from_case(case)
    sol = fb.simulate(fb.load_case(name, {**over, "solver.t_end": 0.005}), "imm")
    t, y = sol.source.segments[-1].t1, sol.source.segments[-1].y1
    assert system.normal_jump(t, y, 0, 0.5) is None
    jump, ref = impulse_jump(system, t, y, 0.5), lcp_jump(system, t, y, np.array([0.5]), [0])
    np.testing.assert_array_equal(jump.y, ref.y)


def test_an_overflowing_jump_is_the_python_maps_floating_point_error():
    """Velocities of ~1e200 m/s overflow the impulse's work: the Python map raises FloatingPointError under the run's
    np.errstate (the run ends "failed" at that time); the compiled map hands such a state to it rather than
    returning infinities."""
    system, states = _states("seed-experiment", "ccm", {"solver.t_end": 0.01})
    t, y = states[0]
    y = np.array(y)
    nz = system.nz
    y[nz : 2 * nz] = -1e200  # (theta' and every q' towards the stop)
    assert system.normal_jump(t, y, 0, 0.0) is None
    with np.errstate(over="raise", invalid="raise", divide="raise"), pytest.raises(FloatingPointError):
        impulse_jump(system, t, y, 0.0)
