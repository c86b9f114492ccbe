"""A moving base (``[base]``): the joint O moves as prescribed and the beam feels g_eff = (0, -g) - a_O(t).

* The base-excited cantilever against the Euler-Bernoulli closed form (not modal): a cantilever clamped to a base
  moving as y_O = Y sin(w t) vibrates in steady state with the absolute tip motion T(beta L) Y sin(w t),

      T(z) = (cos z + cosh z) / (1 + cos z cosh z),   beta^4 = mu w^2 / EI,

  (the boundary-value problem EI w'''' = mu w^2 w, w(0) = Y, w'(0) = w''(L) = w'''(L) = 0; /work/research/moving_base.md
  section 5, checked there with sympy), so the model's tip deflection relative to the base is (T - 1) Y sin(w t).
* A constant base acceleration a is gravity changed by -a (the field (0, -g) - a): the same motion to round-off.
* No base motion: the fixed joint's code paths (the fingerprints of tests/validation/fingerprints.py are unchanged).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.errors import ModelError
from flexbeam.model.system import BeamSystem

#: a steel-like cantilever, 1 m, no gravity, clamped (theta held at 0 by a prescribed drive: the hub frame), a
#: sphere far out of reach (the case needs one)
CANTILEVER = {
    "name": "shaker",
    "beam": {"length": 1.0, "density": 7800.0, "youngs_modulus": 2e11, "section": "general", "area": 1e-4,
             "second_moment": 1e-10, "half_depth": 0.0},
    "drive": {"kind": "prescribed", "spin_rate": 0.0},
    "obstacle": {"kind": "sphere", "centre": [0.5, 5.0], "radius": 0.01},
    "contact": {"law": "hertz", "position": 1.0, "stiffness": 1e9},
    "initial": {"kind": "state", "angle": 0.0, "rate": 0.0},
}  # fmt: skip


def transmissibility(z: float) -> float:
    """T(z) of the base-excited Euler-Bernoulli cantilever, z = beta L (module docstring)."""
    return (math.cos(z) + math.cosh(z)) / (1.0 + math.cos(z) * math.cosh(z))


def steady_run(z: float, modes: int, Y: float = 1e-3, periods: float = 3.0) -> tuple[np.ndarray, np.ndarray, float]:
    """(times, tip deflection, w) of the cantilever shaken at beta L = z, started on its steady state: q(0) = 0 and
    q'(0) = w (K - w^2 M)^-1 s_f Y w^2, the forced response of the model's equations M q'' + K q = s_f Y w^2 sin(w t)
    (so that no free vibration is superposed; the comparison is with the continuum's closed form)."""
    case = fb.load_case(CANTILEVER, {"model.modes": modes, "model.gravity": 0.0})
    beam = BeamSystem.from_case(case).beam
    mu, EI, L = case.beam.line_density, case.beam.youngs_modulus * case.beam.second_moment, case.beam.length
    w = z * z / L**2 * math.sqrt(EI / mu)
    amp = np.linalg.solve(np.asarray(beam.Kff) - w * w * np.asarray(beam.Mff), np.asarray(beam.sf) * Y * w * w)
    period = 2.0 * math.pi / w
    case = fb.load_case(case.model_dump(), {
        "base.frequency": w / (2.0 * math.pi),
        "base.harmonics": [{"axis": "y", "amplitude": Y}],
        "initial.modal_velocity": [float(v) for v in w * amp],
        "solver.t_end": periods * period,
        "output.interval": period / 50.0,
    })  # fmt: skip
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success" and not sol.contacts
    return sol.time, sol["tip_deflection"], w


@pytest.mark.parametrize("z", [1.0, 3.0, 6.0, 9.0, 12.5])
def test_base_excited_cantilever_transmissibility(z):
    """Five frequencies off the resonances (beta L = 1.875, 4.694, 7.855, 10.996, 14.137), below, between and above
    the first four, 24 modes: the relative tip motion equals (T - 1) Y sin(w t) to 2e-4 Y over three periods (the
    modal series' truncation: measured 5e-8 ... 2e-5 Y at 24 modes, 7e-8 ... 6e-4 Y at 12, a 10x margin), and at
    beta L >= 3 the error falls more than 10-fold from 12 to 24 modes (the truncation, not the integration)."""
    Y = 1e-3
    errors = {}
    for modes in (12, 24):
        t, tip, w = steady_run(z, modes, Y)
        ref = (transmissibility(z) - 1.0) * Y * np.sin(w * t)
        errors[modes] = float(np.max(np.abs(tip - ref)))
    assert errors[24] < 2e-4 * Y
    if z >= 3.0:
        assert errors[24] < errors[12] / 10.0


def test_a_constant_base_acceleration_is_gravity_changed():
    """seed-experiment with O accelerating upward at 2 m/s^2 against the same case with gravity g + 2: the field
    (0, -g) - a_O is the same, reached by another code path (the field's components instead of g cos theta, g sin
    theta): the free flight and the first contact agree to 1e-12 relative (measured 1e-13 for the first peak force;
    the two paths round differently, and later impacts amplify that), and both balance their energies (the base's
    work booked) to 1e-5."""
    g = fb.load_case("seed-experiment").model.gravity
    base = fb.simulate(fb.load_case("seed-experiment", {"base.acceleration": [0.0, 2.0]}), "ccfm")
    heavier = fb.simulate(fb.load_case("seed-experiment", {"model.gravity": g + 2.0}), "ccfm")
    a, b = base.contacts[0], heavier.contacts[0]
    assert a.onset == pytest.approx(b.onset, rel=1e-12)
    assert a.peak_force == pytest.approx(b.peak_force, rel=1e-12)
    assert a.velocity_before == pytest.approx(b.velocity_before, rel=1e-12)
    assert abs(base.metrics()["energy_drift_max"]) < 1e-5
    assert abs(heavier.metrics()["energy_drift_max"]) < 1e-5


@pytest.mark.parametrize("method", ["ccfm", "ccm", "imm"])
def test_a_shaken_seed_case_balances_its_energy(method):
    """seed-experiment on a base shaken sideways and vertically (two harmonics, 0.5 mm at 30 Hz and 0.2 mm at 90 Hz):
    every method runs, and the energy balance with the base's work booked (W_b = -[a_O . A s] + int j_O . A s dt)
    holds to 3e-5 relative (measured 1.1e-6, 1.3e-6 and 2.7e-6 under CCFM, CCM and IMM: a 10x margin): the work is the
    base's and the equations' forcing is the field's."""
    case = fb.load_case("seed-experiment", {
        "base.frequency": 30.0,
        "base.harmonics": [
            {"axis": "x", "amplitude": 5e-4},
            {"axis": "y", "amplitude": 2e-4, "order": 3, "phase": 0.3},
        ],
    })  # fmt: skip
    sol = fb.simulate(case, method)
    assert sol.status == "success"
    assert abs(sol.metrics()["energy_drift_max"]) < 3e-5


def test_zero_amplitude_is_a_fixed_joint_bit_for_bit():
    """Harmonics of zero amplitude do not move O: the fixed joint's code paths, the same bits."""
    fixed = fb.simulate(fb.load_case("seed-experiment"), "ccfm")
    still = fb.simulate(fb.load_case("seed-experiment", {
        "base.frequency": 10.0, "base.harmonics": [{"axis": "y", "amplitude": 0.0}]}), "ccfm")  # fmt: skip
    assert [c.peak_force for c in still.contacts] == [c.peak_force for c in fixed.contacts]
    assert np.array_equal(still.source.run.segments[-1].y1, fixed.source.run.segments[-1].y1)


@pytest.mark.parametrize(
    ("overrides", "field"),
    [
        ({"base.harmonics": [{"axis": "y", "amplitude": 1e-3}]}, "base.frequency"),
        ({"base.frequency": 0.0, "base.harmonics": [{"axis": "y", "amplitude": 1e-3}]}, "base.frequency"),
        ({"base.frequency": 10.0, "base.harmonics": [{"axis": "z", "amplitude": 1e-3}]}, "base.harmonics"),
        ({"base.frequency": 10.0, "base.harmonics": [{"axis": "y", "amplitude": 1e-3, "order": 0}]}, "base.harmonics"),
    ],
)
def test_bad_base_input_names_the_field(overrides, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        fb.load_case("seed-experiment", overrides)


def test_the_fe_reference_refuses_a_ground_obstacle_and_a_free_beam_a_moving_base():
    moving = {"base.acceleration": [0.0, 1.0]}
    with pytest.raises(ModelError, match=r"^obstacle\.fixed_to: the FE reference carries"):
        fb.simulate(fb.load_case("seed-experiment", {**moving, "obstacle.fixed_to": "ground"}), "fem")
    with pytest.raises(ValueError, match=r"base: a free beam"):
        fb.load_case("seed-experiment", {**moving, "joint.kind": "free", "hub.radius": 0.0, "hub.inertia": 0.0})


def test_axial_modes_on_a_moving_base_are_refused():
    with pytest.raises(ValueError, match=r"model\.axial_modes: a moving base"):
        fb.load_case("seed-experiment", {"base.acceleration": [0.0, 1.0], "model.axial_modes": 2})
