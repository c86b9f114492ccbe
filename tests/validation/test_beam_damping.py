"""The beam's structural damping (``beam.kelvin_voigt`` c, ``beam.viscous_damping`` eta) against independent truths.

* The base-excited cantilever in steady state against the continuum's closed form with the damped complex
  wavenumber.  With y_O = Y sin(w t) (complex amplitude Y e^{i w t}) and the deflection u relative to the base,
  Kelvin-Voigt and the viscous force on the relative velocity give
      EI (1 + i w c) u'''' - (mu w^2 - i w eta) u = mu w^2 Y,  u(0) = u'(0) = u''(L) = u'''(L) = 0,
  whose solution is u = u_p (1 - A(x) / A(0)) with the constant u_p = -mu w^2 Y / (mu w^2 - i w eta) and A the
  homogeneous solution of A'''' = beta^4 A, A'(0) = A''(L) = A'''(L) = 0, beta^4 = (mu w^2 - i w eta) / (EI (1 + i w
  c)); as for the undamped beam A(L) / A(0) = T(beta L) = (cos beta L + cosh beta L) / (1 + cos beta L cosh beta L),
  now at a complex beta L, so
      u(L) / Y = (T(beta L) - 1) mu w^2 / (mu w^2 - i w eta)
  (for eta = 0 the absolute tip motion W(L) / Y = T(beta L) of the undamped test, tests/validation/test_moving_base.py,
  with the complex beta).
* The free decay of a damped cantilever: the logarithmic decrement of the tip is 2 pi zeta_1 / sqrt(1 - zeta_1^2),
  zeta_1 = c w_1 / 2 + eta / (2 mu w_1), w_1 = 1.8751040687^2 sqrt(EI / mu) / L^2 (the continuum's first root).
* The FE reference's own damping (``flexbeam.fem.damping``) against the modal model's on a shaken cantilever, free
  and striking its stop.
* The energy balance with the dissipation booked, for every method.
"""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.model.system import BeamSystem

from .test_moving_base import CANTILEVER

SHAKER = "tests/validation/data/shaker-stop.toml"
BETA1 = 1.8751040687119611  # the first root of 1 + cos z cosh z = 0


def tip_response(case: fb.Case, w: float) -> complex:
    """u(L) / Y of the damped base-excited cantilever at the frequency w (module docstring)."""
    b = case.beam
    mu, EI, L, c, eta = b.line_density, b.bending_stiffness, b.length, b.kelvin_voigt, b.viscous_damping
    bL = ((mu * w * w - 1j * w * eta) / (EI * (1.0 + 1j * w * c))) ** 0.25 * L
    T = (cmath.cos(bL) + cmath.cosh(bL)) / (1.0 + cmath.cos(bL) * cmath.cosh(bL))
    return (T - 1.0) * mu * w * w / (mu * w * w - 1j * w * eta)


def damped_steady_run(z: float, over: dict, Y: float = 1e-3, periods: float = 3.0):
    """(times, tip deflection, w, case) of the cantilever shaken at beta L = z (undamped beta), started on the modal
    equations' own steady state Im(Q e^{i w t}), Q = (K - w^2 M + i w C)^-1 s_f Y w^2, so that no free vibration is
    superposed."""
    case = fb.load_case(CANTILEVER, {"model.gravity": 0.0, **over})
    system = BeamSystem.from_case(case)
    beam = system.beam
    mu, EI, L = case.beam.line_density, case.beam.bending_stiffness, case.beam.length
    w = z * z / L**2 * math.sqrt(EI / mu)
    A = np.asarray(beam.Kff) - w * w * np.asarray(beam.Mff) + 1j * w * system.damping
    Q = np.linalg.solve(A, np.asarray(beam.sf) * Y * w * w)
    period = 2.0 * math.pi / w
    case = fb.load_case(case.model_dump(), {
        "base.frequency": w / (2.0 * math.pi),
        "base.harmonics": [{"axis": "y", "amplitude": Y}],
        "initial.modal_displacement": [float(v) for v in Q.imag],
        "initial.modal_velocity": [float(v) for v in w * Q.real],
        "solver.t_end": periods * period,
        "output.interval": period / 50.0,
    })  # fmt: skip
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success" and not sol.contacts
    return sol.time, sol["tip_deflection"], w, case


@pytest.mark.parametrize("z", [1.0, 1.8, BETA1, 3.0, 6.0])
def test_damped_transmissibility_against_the_complex_wavenumber(z):
    """Five frequencies, below, near and at the first resonance (beta L = 1.875) and beyond it, c = 1e-3 s and eta =
    0.5 N s/m^2 (zeta_1 = 0.0089 + 0.018; the highest of the 24 modes overdamped, zeta = 14): the least-squares
    amplitude and phase of the tip deflection relative to the base equal the closed form's to 3e-4 relative and
    3e-4 rad (measured <= 1.4e-6 and 1.2e-5 rad, at beta L = 6, the modal series' truncation; <= 3e-8 elsewhere), and
    at resonance the response is the damping's: within 1 % of Y / (2 zeta_1) times the undamped beam's participation."""
    Y = 1e-3
    t, tip, w, case = damped_steady_run(z, {"model.modes": 24, "beam.kelvin_voigt": 1e-3, "beam.viscous_damping": 0.5})
    basis = np.column_stack([np.sin(w * t), np.cos(w * t)])  # tip = Re U sin(w t) + Im U cos(w t)
    (re, im), *_ = np.linalg.lstsq(basis, tip, rcond=None)
    U = complex(re, im)
    ref = tip_response(case, w) * Y
    assert abs(abs(U) - abs(ref)) < 3e-4 * abs(ref)
    assert abs(cmath.phase(U / ref)) < 3e-4
    if z == BETA1:  # the peak is set by the damping: ~ 1.566 Y / (2 zeta_1) (1.566: the first mode's tip factor)
        b = case.beam
        w1 = BETA1**2 * math.sqrt(b.bending_stiffness / b.line_density) / b.length**2
        zeta1 = b.kelvin_voigt * w1 / 2.0 + b.viscous_damping / (2.0 * b.line_density * w1)
        assert abs(U) == pytest.approx(1.566 * Y / (2.0 * zeta1), rel=0.01)


@pytest.mark.parametrize(
    ("over", "start"),
    [
        ({"beam.kelvin_voigt": 2e-3}, [1e-3, 2e-4]),
        ({"beam.viscous_damping": 1.0}, [1e-3]),
        ({"beam.kelvin_voigt": 1e-3, "beam.viscous_damping": 0.5}, [1e-3]),
    ],
)
def test_logarithmic_decrement_of_the_first_mode(over, start):
    """Free decay from the first mode's shape, with some of the second's under Kelvin-Voigt (which damps it ~6x
    faster; viscous damping would leave it ringing, ~6x slower, with maxima of its own): over the 3rd to
    the 8th period the tip's successive maxima shrink by exp(2 pi zeta_1 / sqrt(1 - zeta_1^2)), zeta_1 of the
    continuum's w_1, to 1e-4 relative in the decrement (measured 2.4e-6 with the second mode's remnant, 4e-15
    without; the peaks located by a parabola through samples 1/400 of a period apart)."""
    case = fb.load_case(CANTILEVER, {"model.gravity": 0.0, "model.modes": 6, **over})
    b = case.beam
    w1 = BETA1**2 * math.sqrt(b.bending_stiffness / b.line_density) / b.length**2
    zeta1 = b.kelvin_voigt * w1 / 2.0 + b.viscous_damping / (2.0 * b.line_density * w1)
    period = 2.0 * math.pi / (w1 * math.sqrt(1.0 - zeta1 * zeta1))
    case = fb.load_case(case.model_dump(), {
        "initial.modal_displacement": start, "solver.t_end": 9.0 * period, "output.interval": period / 400.0,
    })  # fmt: skip
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success"
    t, x = sol.time, sol["tip_deflection"]
    peaks = []
    for i in range(1, x.size - 1):
        if x[i] > x[i - 1] and x[i] >= x[i + 1] and t[i] > 2.0 * period:
            a, b2, c = x[i - 1], x[i], x[i + 1]
            peaks.append(b2 + 0.125 * (a - c) ** 2 / (2.0 * b2 - a - c))  # the parabola's vertex
    decrements = np.log(np.array(peaks[:-1]) / np.array(peaks[1:]))
    assert len(decrements) >= 5
    expected = 2.0 * math.pi * zeta1 / math.sqrt(1.0 - zeta1 * zeta1)
    assert np.max(np.abs(decrements - expected)) < 1e-4 * expected


def test_the_fe_beam_is_damped_as_the_modal_beam_is():
    """The shaker case with its stop out of reach, 0.05 s, c = 4e-4 s and eta = 2 N s/m^2 (zeta_1 = 0.023 + 0.028):
    the FE's tip deflection (32 elements, flexbeam.fem.damping) against the modal model's at 12 modes to 2e-4 of its
    largest value (measured 1.6e-5 over 0.1 s), their dissipated energies to 1e-4 relative (measured 4e-6), and the
    damping matters: it takes more than 10 % off the undamped tip's largest deflection.  Both balance their energy
    with the dissipation booked (FE 1e-7, measured 3e-9; modal 1e-6, measured 3e-10)."""
    over = {"solver.t_end": 0.1, "obstacle.centre": [0.3, -1.0], "output.interval": 1e-4}
    damped = {**over, "beam.kelvin_voigt": 4e-4, "beam.viscous_damping": 2.0}
    fe = fb.simulate(fb.load_case(SHAKER, damped), "fem")
    modal = fb.simulate(fb.load_case(SHAKER, {**damped, "model.modes": 12}), "ccfm")
    undamped = fb.simulate(fb.load_case(SHAKER, {**over, "model.modes": 12}), "ccfm")
    assert fe.status == "success" and not fe.contacts
    tip = modal["tip_deflection"]
    error = np.max(np.abs(np.interp(modal.time, fe.time, fe["tip_deflection"]) - tip)) / np.max(np.abs(tip))
    assert error < 2e-4
    assert np.max(np.abs(tip)) < 0.9 * np.max(np.abs(undamped["tip_deflection"]))
    assert fe["dissipated_energy"][-1] == pytest.approx(modal["dissipated_energy"][-1], rel=1e-4)
    assert abs(fe.metrics()["energy_drift_max"]) < 1e-7
    assert abs(modal.metrics()["energy_drift_max"]) < 1e-6


@pytest.mark.slow
def test_the_damped_beam_strikes_the_stop_as_the_fe_beam_does():
    """The shaker case with its stop 1 mm under the tip, c = 4e-4 s, eta = 2 N s/m^2, 0.06 s (~25 s of FE): the first
    impact's onset agrees to 1e-6 s (measured 3e-8 s at 12 modes; the damping delays it by 1.4e-3 s) and the tip's
    approach speed to 2e-4 relative (measured 1.2e-5); both energy balances hold with the dissipation booked (FE 2e-4,
    measured 2e-5; modal 2e-6, measured 1.4e-7)."""
    over = {"solver.t_end": 0.06, "beam.kelvin_voigt": 4e-4, "beam.viscous_damping": 2.0}
    fe = fb.simulate(fb.load_case(SHAKER, over), "fem")
    modal = fb.simulate(fb.load_case(SHAKER, {**over, "model.modes": 12}), "ccfm")
    a, b = fe.contacts[0], modal.contacts[0]
    assert a.onset == pytest.approx(b.onset, abs=1e-6)
    assert a.velocity_before == pytest.approx(b.velocity_before, rel=2e-4)
    assert abs(fe.metrics()["energy_drift_max"]) < 2e-4
    assert abs(modal.metrics()["energy_drift_max"]) < 2e-6


@pytest.mark.parametrize("method", ["ccfm", "ccm", "imm"])
@pytest.mark.parametrize(
    ("case", "over"),
    [("seed-experiment", {"beam.kelvin_voigt": 1e-4}),
     (SHAKER, {"beam.viscous_damping": 3.0, "solver.t_end": 0.3})],
    ids=["seed-kelvin-voigt", "shaker-viscous"],
)  # fmt: skip
def test_every_method_books_the_dissipation(method, case, over):
    """seed-experiment with Kelvin-Voigt damping c = 1e-4 s (its high modes overdamped: zeta_12 ~ 5) and the shaker
    case with viscous damping (every mode damped alike, the fast ones turning many times in a step: their exact
    dissipation is booked, damped.c fb_damping_books): every method runs, dissipates more than the undamped run, and
    balances its energy with the damping's dissipation booked to 3e-5 relative (measured <= 2.2e-6; the undamped
    runs' drifts are 2e-7 ... 2e-6)."""
    damped = fb.simulate(fb.load_case(case, over), method)
    undamped = fb.simulate(fb.load_case(case, {k: v for k, v in over.items() if k.startswith("solver")}), method)
    assert damped.status == "success"
    assert damped["dissipated_energy"][-1] > undamped["dissipated_energy"][-1]
    assert abs(damped.metrics()["energy_drift_max"]) < 3e-5


@pytest.mark.parametrize(
    "over",
    [{"hub.inertia": 0.05, "beam.viscous_damping": 3.0}, {"model.frame": "hub", "beam.viscous_damping": 3.0},
     {"model.frame": "hub", "beam.kelvin_voigt": 1e-4}],
    ids=["system-frame-hub-inertia-viscous", "hub-frame-viscous", "hub-frame-kelvin-voigt"],
)  # fmt: skip
def test_the_exact_propagation_agrees_with_the_reference_integrator(over):
    """seed-experiment's free hub, 0.01 s, with the damping not diagonal in the modes (the system frame with a hub
    inertia: C's viscous part couples the modes by 27 %; the hub frame's coupled theta: by 13 %, its remainder through
    the Sherman-Morrison row) and Kelvin-Voigt in the hub frame: the exponential integrator (the damped propagation,
    the off-diagonal damping in the remainder) against DOP853 on the compiled right-hand side (the damping force in
    Q): the first peak force to 1e-6 relative (measured <= 7e-8), the dissipated energy to 1e-4 (measured 3.5e-6)
    and the final tip deflection to 1e-5 (measured 4.6e-7)."""
    runs = [
        fb.simulate(fb.load_case("seed-experiment", {**over, "solver.t_end": 0.01, "solver.integrator": i}), "ccfm")
        for i in ("exponential", "reference")
    ]
    fast, ref = runs
    assert fast.status == ref.status == "success"
    assert fast.contacts[0].peak_force == pytest.approx(ref.contacts[0].peak_force, rel=1e-6)
    assert fast["dissipated_energy"][-1] == pytest.approx(ref["dissipated_energy"][-1], rel=1e-4)
    assert fast["tip_deflection"][-1] == pytest.approx(ref["tip_deflection"][-1], rel=1e-5)


@pytest.mark.parametrize(
    ("over", "peak_tol", "energy_tol"),
    [({"beam.kelvin_voigt": 1e-4}, 0.03, 2e-3), ({"beam.viscous_damping": 3.0}, 0.03, 0.05)],
    ids=["kelvin-voigt", "viscous"],
)
def test_the_fe_beam_on_a_free_hub_is_damped_as_the_modal_beam_is(over, peak_tol, energy_tol):
    """seed-experiment's free hub in the hub frame (the FE's frame: its viscous force relative to the hub, with the
    reaction on theta), 4 ms through the first impact: the FE (flexbeam.fem.damping) and the modal model at 12 modes
    agree on the first peak force to 3 % (measured 0.33 % and 0.23 %; Kelvin-Voigt raises the peak by 21 %) and on the
    dissipated energy, the contact law's and the damping's, to 0.2 % under Kelvin-Voigt (measured 2e-4) and 5 % under
    viscous damping (measured 0.45 %: the FE also damps the centre line's axial and foreshortening velocities relative
    to the hub, which the modal model's q do not carry); the damping dissipates more than the contact law (the
    undamped run's dissipation is less than half)."""
    over = {**over, "model.frame": "hub", "solver.t_end": 0.004}
    fe = fb.simulate(fb.load_case("seed-experiment", over), "fem")
    modal = fb.simulate(fb.load_case("seed-experiment", {**over, "model.modes": 12}), "ccfm")
    plain = fb.simulate(fb.load_case("seed-experiment", {**over, "beam.kelvin_voigt": 0.0, "beam.viscous_damping": 0.0,
                                                          "model.modes": 12}), "ccfm")  # fmt: skip
    assert fe.status == modal.status == "success"
    assert fe.contacts[0].peak_force == pytest.approx(modal.contacts[0].peak_force, rel=peak_tol)
    assert fe["dissipated_energy"][-1] == pytest.approx(modal["dissipated_energy"][-1], rel=energy_tol)
    assert plain["dissipated_energy"][-1] < 0.5 * modal["dissipated_energy"][-1]
