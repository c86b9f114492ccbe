"""The free bar drop (``tests/validation/data/free-bar-drop.toml``: a 20 cm steel bar, 12.7 mm across, striking a
rigid floor on its hemispherical end cap at 1.4 m/s, under gravity) by the modal model (CCFM) and the independent
finite-element reference (``--method fem``, :mod:`flexbeam.fem.free`): G's velocity and the spin after the first
collision episode and the largest contact force in it.  The issue's targets: G's velocity and the spin within 2 %,
the peak force within 3 %.

The two models differ in one piece of physics: the modal beam is inextensible, the FE beam is not (its elements
stretch, EA = E A).  The bar's first axial period, 2 L / c = 80 us, is shorter than the ~190 us contact, and at steep
inclinations the floor pushes the bar largely along its axis, so that its axial compliance softens the contact:

* on the **axially rigid twin** of the bar (the same mu, EI, cap radius and contact; the area x 1e4 and the density
  / 1e4, so that EA is 1e4 times the steel's -- the modal model does not read EA), the FE at its default 32 elements
  and the modal model at 32 modes agree within the targets at 20, 45 and 70 degrees (measured: G's velocity 0.004 %,
  0.02 %, 0.56 % -- at 70 degrees v_G+ = -0.065 m/s is a near cancellation of v0 = 1.4 m/s; the spin 0.004 %,
  0.008 %, 0.03 %; the peak 0.03 %, 0.02 %, 0.01 %).  At the case's eight modes the modal model is not converged
  there: the peak 1.3 %, 1.0 %, 0.3 % above the FE's, the spin 0.1 %, 0.1 %, 0.3 % off, G's velocity 0.09 %, 0.2 %
  and at 70 degrees 7 % of v_G+ (0.34 % of the velocity change): modes 8, 16, 32, 62 give v_G+ = -0.06080,
  -0.06446, -0.06500, -0.06507 m/s against the FE's -0.06536 (16 elements -0.06528, 64 -0.06535);
* on the **steel bar** itself the targets hold at 20 degrees (G 0.2 %, spin 0.2 %, peak 2.4 % against eight modes;
  1.2 % against 32), not at 45 degrees (G 2.6 %, spin 1.2 %, peak 6.6 % against 32 modes) nor at 70 (one contact
  instead of two in the FE; G 26 %, spin 1.6 %, peak 15 %): the FE converged (16, 32, 64 elements within 0.2 %),
  the difference is the axial compliance that the modal model leaves out (issue 26's axial modes).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb

CASE = Path(__file__).resolve().parent / "data" / "free-bar-drop.toml"
#: issue 26's targets: G's velocity and the spin after the first episode, the peak contact force in it (relative)
VELOCITY, SPIN, PEAK = 0.02, 0.02, 0.03


def bar(angle: float, rigid_axially: bool = False, **overrides) -> fb.Case:
    """The bar drop at ``angle`` degrees, 2 ms (the first episode ends by 0.5 ms), or its axially rigid twin."""
    values = {"solver.t_end": 0.002, "initial.impact_angle": math.radians(angle)}
    if rigid_axially:
        r = 0.00635
        values.update({
            "beam.section": "general", "beam.radius": None, "beam.area": 1e4 * math.pi * r * r,
            "beam.density": 7870.0 / 1e4, "beam.second_moment": math.pi * r**4 / 4.0, "beam.half_depth": r,
        })  # fmt: skip
    values.update({k.replace("__", "."): v for k, v in overrides.items()})
    return fb.load_case(CASE, values)


def first_episode(case: fb.Case, method: str) -> tuple[np.ndarray, float, float, int]:
    """(G's velocity, the spin after the first episode, its largest contact force, its records)."""
    sol = fb.simulate(case, method)
    assert sol.status == "success"
    ep = sol.episodes()[0]
    peak = max(sol.contacts[i].peak_force for i in ep.records)
    return np.array(ep.velocity_after), ep.spin_after, peak, len(ep.records)


def close(fem, modal, velocity=VELOCITY, spin=SPIN, peak=PEAK) -> None:
    """The FE's first episode within the targets of the modal model's (G's velocity relative to its magnitude)."""
    assert np.linalg.norm(fem[0] - modal[0]) <= velocity * np.linalg.norm(modal[0])
    assert fem[1] == pytest.approx(modal[1], rel=spin)
    assert fem[2] == pytest.approx(modal[2], rel=peak)


@pytest.mark.parametrize("angle", [pytest.param(20.0, marks=pytest.mark.slow), 45.0, 70.0])
def test_fe_and_modal_agree_on_the_axially_rigid_bar(angle):
    """The axially rigid twin (module docstring): the FE at its default mesh against the modal model at 32 modes
    within the targets, with the same number of records in the episode, and against the case's eight modes within
    the targets for the spin and the peak, and for G's velocity change (v_G+ - v_G-, 1.3 to 1.4 m/s: at 70 degrees
    v_G+ itself is a near cancellation, where eight modes are 7 % off and not converged)."""
    fem = first_episode(bar(angle, True), "fem")
    modal = first_episode(bar(angle, True, model__modes=32), "ccfm")
    close(fem, modal)
    assert fem[3] == modal[3]
    eight = first_episode(bar(angle, True), "ccfm")
    v_before = np.array([0.0, -1.4])
    close(fem, eight, velocity=math.inf)
    assert np.linalg.norm(fem[0] - eight[0]) <= VELOCITY * np.linalg.norm(eight[0] - v_before)


def test_fe_and_modal_agree_on_the_steel_bar_at_20_degrees():
    """The steel bar at 20 degrees, where the floor pushes it mostly across its axis: the FE at its default mesh
    against the case's eight modes within the targets (measured: G 0.2 %, spin 0.2 %, peak 2.4 %)."""
    close(first_episode(bar(20.0), "fem"), first_episode(bar(20.0), "ccfm"))


@pytest.mark.slow
@pytest.mark.parametrize(("angle", "softer"), [(45.0, 0.05), (70.0, 0.10)])
def test_the_steel_bars_axial_compliance_lowers_its_peak(angle, softer):
    """The FE alone: the steel bar's peak force lies more than 5 % (45 degrees; measured 6.6 %) and 10 % (70 degrees;
    measured 15 %) below its axially rigid twin's -- the difference from the (inextensible) modal model at those
    angles, which agrees with the twin (:func:`test_fe_and_modal_agree_on_the_axially_rigid_bar`)."""
    steel = first_episode(bar(angle), "fem")
    twin = first_episode(bar(angle, True), "fem")
    assert steel[2] < (1.0 - softer) * twin[2]
