"""The free bar drop (``tests/validation/data/free-bar-drop.toml``: a 20 cm steel bar, 12.7 mm across, striking a
rigid floor on its hemispherical end cap at 1.4 m/s, under gravity) by the modal model (CCFM) and the independent
finite-element reference (``--method fem``, :mod:`flexbeam.fem.free`): G's velocity and the spin after the first
collision episode and the largest contact force in it.  The issue's targets: G's velocity and the spin within 2 %,
the peak force within 3 %.

The FE beam stretches (its elements have EA = E A); the modal beam does so only with axial modes
(``model.axial_modes``).  The bar's first axial period, 2 L / c = 80 us, is shorter than the ~190 us contact, and at
steep inclinations the floor pushes the bar largely along its axis, so that its axial compliance softens the contact:

* on the **axially rigid twin** of the bar (the same mu, EI, cap radius and contact; the area x 1e4 and the density
  / 1e4, so that EA is 1e4 times the steel's -- the inextensible modal model does not read EA), the FE at its default
  32 elements and the modal model at 32 modes agree within the targets at 20, 45 and 70 degrees (measured: G's
  velocity 0.004 %, 0.02 %, 0.56 % -- at 70 degrees v_G+ = -0.065 m/s is a near cancellation of v0 = 1.4 m/s; the
  spin 0.004 %, 0.008 %, 0.03 %; the peak 0.03 %, 0.02 %, 0.01 %).  At the case's eight modes the modal model is not
  converged there: the peak 1.3 %, 1.0 %, 0.3 % above the FE's, the spin 0.1 %, 0.1 %, 0.3 % off, G's velocity
  0.09 %, 0.2 % and at 70 degrees 7 % of v_G+ (0.34 % of the velocity change): modes 8, 16, 32, 62 give
  v_G+ = -0.06080, -0.06446, -0.06500, -0.06507 m/s against the FE's -0.06536 (16 elements -0.06528, 64 -0.06535);
* on the **steel bar** without axial modes the targets hold at 20 degrees (G 0.2 %, spin 0.2 %, peak 2.4 % against
  eight modes), not at 45 degrees (G 2.6 %, spin 1.2 %, peak 6.6 % against 32 modes) nor at 70 (one contact instead
  of two in the FE; G 26 %, spin 1.6 %, peak 15 %);
* on the **steel bar with axial modes** (contact anywhere on the stretched centre line, ``kernels/src/nearest.c``)
  they hold at every angle once the modal model has converged (measured against 32 bending and 24 axial modes:
  G 0.002 %, 0.03 %, 1.0 %; spin 0.003 %, 0.01 %, 0.07 %; peak 0.04 %, 0.09 %, 0.12 %; the FE's 3, 2, 1 contacts).
  The axial modes converge like 1 / n_a, the static end compliance of the modes left out (as for Saint-Venant's rod,
  docs/formulation.md): at 70 degrees v_G+ = -0.08412, -0.08300, -0.08261, -0.08246 m/s for n_a = 8, 16, 24, 30,
  whose 1 / n_a extrapolation -0.0818 is the FE's -0.08176 (16, 64, 128 elements: -0.08187, -0.08174, -0.08174;
  time steps 0.5 and 0.25 us: -0.08178, -0.08179).  Eight bending modes are not enough at 70 degrees (with 16 axial
  modes G is 2.6 % off; 16 bending modes 1.6 %); at 20 and 45 degrees the case's eight with four axial modes meet
  the targets (G 0.1 %, 0.5 %; spin 0.1 %, 0.2 %; peak 1.3 %, 1.3 %).
"""

from __future__ import annotations

import functools
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
    assert sol.status == "success", sol.message
    ep = sol.episodes()[0]
    peak = max(sol.contacts[i].peak_force for i in ep.records)
    return np.array(ep.velocity_after), ep.spin_after, peak, len(ep.records)


@functools.cache
def fem_episode(angle: float, rigid_axially: bool = False) -> tuple[np.ndarray, float, float, int]:
    """:func:`first_episode` of the FE at its default mesh (run once per session: several tests compare with it)."""
    return first_episode(bar(angle, rigid_axially), "fem")


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
    fem = fem_episode(angle, True)
    modal = first_episode(bar(angle, True, model__modes=32), "ccfm")
    close(fem, modal)
    assert fem[3] == modal[3]
    eight = first_episode(bar(angle, True), "ccfm")
    v_before = np.array([0.0, -1.4])
    close(fem, eight, velocity=math.inf)
    assert np.linalg.norm(fem[0] - eight[0]) <= VELOCITY * np.linalg.norm(eight[0] - v_before)


def test_fe_and_modal_agree_on_the_steel_bar_at_20_degrees():
    """The steel bar at 20 degrees, where the floor pushes it mostly across its axis: the FE at its default mesh
    against the case's eight modes without axial modes within the targets (measured: G 0.2 %, spin 0.2 %, peak
    2.4 %)."""
    close(fem_episode(20.0), first_episode(bar(20.0), "ccfm"))


@pytest.mark.parametrize(
    ("angle", "modes", "axial"), [(20.0, 8, 4), (45.0, 8, 4), (20.0, 32, 24), (45.0, 32, 24), (70.0, 32, 24)]
)
def test_fe_and_modal_agree_on_the_steel_bar_with_axial_modes(angle, modes, axial):
    """The steel bar with axial modes against the FE at its default mesh: within the targets, with the same number
    of contacts in the episode (3, 2, 1; each carries at least 16 % of the episode's impulse and starts 15 us or
    more after the one before ends: not a count that round-off can change).  Measured (module docstring): the case's
    eight modes with four axial ones at 20 and 45 degrees G 0.1 %, 0.5 %, spin 0.1 %, 0.2 %, peak 1.3 %, 1.3 %; 32
    and 24 at 20, 45, 70 degrees G 0.002 %, 0.03 %, 1.0 %, spin 0.003 %, 0.01 %, 0.07 %, peak 0.04 %, 0.09 %,
    0.12 %."""
    fem = fem_episode(angle)
    modal = first_episode(bar(angle, model__modes=modes, model__axial_modes=axial), "ccfm")
    close(fem, modal)
    assert fem[3] == modal[3]


@pytest.mark.slow
def test_the_axial_modes_converge_to_the_fe_at_70_degrees():
    """At 70 degrees G's velocity after the episode (v_G+ ~ -0.082 m/s, a near cancellation of v0 = 1.4 m/s)
    converges like 1 / n_a, the static end compliance of the axial modes left out: with 32 bending modes the error
    against the FE falls with n_a = 8, 16, 24, 30 (measured 2.8, 1.5, 1.0, 0.84 %), the 1 / n_a extrapolation
    (Richardson, from 16 and 24) lies within 0.3 % of the FE's (measured 0.09 %), and the FE is converged in its
    mesh and step to 0.2 % (16, 32, 64 elements: measured 0.13 %, 0.02 %; its step halved: 0.02 %)."""
    fem = fem_episode(70.0)
    v = {na: first_episode(bar(70.0, model__modes=32, model__axial_modes=na), "ccfm")[0] for na in (8, 16, 24, 30)}
    errors = [np.linalg.norm(v[na] - fem[0]) for na in (8, 16, 24, 30)]
    assert all(a > b for a, b in zip(errors, errors[1:]))
    richardson = (24.0 * v[24] - 16.0 * v[16]) / 8.0
    assert np.linalg.norm(richardson - fem[0]) <= 0.003 * np.linalg.norm(fem[0])
    for over in ({"fem__elements": 16}, {"fem__elements": 64}, {"fem__time_step": 5e-7}):
        other = first_episode(bar(70.0, **over), "fem")
        assert np.linalg.norm(other[0] - fem[0]) <= 0.002 * np.linalg.norm(fem[0])


@pytest.mark.slow
@pytest.mark.parametrize(("angle", "softer"), [(45.0, 0.05), (70.0, 0.10)])
def test_the_steel_bars_axial_compliance_lowers_its_peak(angle, softer):
    """The FE alone: the steel bar's peak force lies more than 5 % (45 degrees; measured 6.6 %) and 10 % (70 degrees;
    measured 15 %) below its axially rigid twin's -- the difference from the inextensible modal model at those angles,
    which agrees with the twin (:func:`test_fe_and_modal_agree_on_the_axially_rigid_bar`), and which the modal model's
    axial modes close (:func:`test_fe_and_modal_agree_on_the_steel_bar_with_axial_modes`)."""
    steel = fem_episode(angle)
    twin = fem_episode(angle, True)
    assert steel[2] < (1.0 - softer) * twin[2]
