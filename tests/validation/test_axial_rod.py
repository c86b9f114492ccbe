"""The axial modes in motion (docs/formulation.md, "Axial deformation") against closed forms.

* **Saint-Venant's rod impact** (the ``rod-end`` preset, gravity off): a free rod falling along its axis at v0 onto a
  rigid plane through a linear spring k, kappa = k L / EA.  The continuum (exact delay equation of the free-free
  rod's end, v(t) = v(t - 2L/c) + [F(t) + F(t - 2L/c)] / Z, Z = EA / c, integrated here by the trapezoidal rule)
  gives, for kappa >> 1, the contact time t_c = 2L/c + sigma* EA/(k c), (1 + sigma*) e^-sigma* = 1/2, the rebound
  v+ = v0 (1 - c1 EA/(k L)), c1 = sigma* + (2 + sigma*)/(1 + sigma*) - 3, and the force plateau EA v0 / c; both
  tend to Saint-Venant's 2L/c and v0 as k grows.  N free-free axial modes lack the static end compliance of the
  modes left out, C_res = (2L / (pi^2 EA)) sum_{k > N} k^-2 ~ 2L/(pi^2 N EA), so in the resolved regime
  (N > kappa/pi) the modal contact is stiffer: t_c - 2 sigma* (L/c) / (pi^2 N) and v+ + 2 c1 v0 / (pi^2 N).
* **Free flight** with axial and bending vibration and spin, no gravity: the momentum and the angular momentum
  p_theta (with its axial terms 2 m_ta p + p^T M_aa p and p^T S q' - q^T S^T p') are conserved, and the energy.
* **The centrifugal stretch of a spinning rod** on a revolute joint (theta' = Omega prescribed): the static axial
  displacement of EA u'' + mu Omega^2 (r_h + x + u) = 0, u(0) = 0, u'(L) = 0, u = -(r_h + x) + r_h cos(beta x) +
  B sin(beta x), B = (1 + r_h beta sin(beta L)) / (beta cos(beta L)), beta = Omega sqrt(rho / E).

Tolerances are ten times the measured agreement (noted at each), or round-off bounds.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import flexbeam as fb
from flexbeam.model.system import BeamSystem

ROD = fb.load_case("rod-end")
L, EA = ROD.beam.length, ROD.beam.axial_stiffness
C0 = math.sqrt(ROD.beam.youngs_modulus / ROD.beam.density)
TIME = L / C0  # L/c
MASS = ROD.beam.mass
SIGMA = brentq(lambda s: (1.0 + s) * math.exp(-s) - 0.5, 0.5, 5.0, xtol=1e-15)
C1 = SIGMA + (2.0 + SIGMA) / (1.0 + SIGMA) - 3.0


def delay_equation(kappa: float, dt: float = 2e-4) -> tuple[float, float]:
    """(t_c c/L, v+/v0) of the continuum rod on a spring, in units L = c = EA = v0 = 1 (trapezoidal rule)."""
    n, lag = int(4.0 / dt), int(round(2.0 / dt))
    v, F, d = np.full(n + 1, -1.0), np.zeros(n + 1), np.zeros(n + 1)
    impulse = 0.0
    for i in range(n):
        j = i + 1 - lag
        vl, Fl = (v[j], F[j]) if j >= 0 else (-1.0, 0.0)
        d1 = (d[i] - 0.5 * dt * (v[i] + vl + Fl)) / (1.0 + 0.5 * dt * kappa)
        if d1 <= 0.0:  # the spring opens: the end's penetration at the crossing, linearly
            frac = d[i] / (d[i] - d1)
            return (i + frac) * dt, impulse + 0.5 * frac * dt * F[i] - 1.0
        d[i + 1], F[i + 1] = d1, kappa * d1
        v[i + 1] = vl + F[i + 1] + Fl
        impulse += 0.5 * dt * (F[i] + F[i + 1])
    raise AssertionError("no separation")


def test_the_closed_forms_are_the_continuums():
    """sigma* = 1.678347, c1 = 0.051712; the delay equation gives t_c and v+ of the closed forms (kappa >> 1):
    measured 2e-5 (kappa = 20) and 1e-5 (200) in t_c c/L, ~1e-7 in v+/v0 (the closed forms are kappa >> 1
    asymptotics)."""
    assert SIGMA == pytest.approx(1.678347, abs=1e-6) and C1 == pytest.approx(0.051712, abs=1e-6)
    for kappa in (20.0, 200.0):
        tc, vp = delay_equation(kappa)
        assert tc == pytest.approx(2.0 + SIGMA / kappa, abs=5e-4)
        assert vp == pytest.approx(1.0 - C1 / kappa, abs=5e-6)


def rod(kappa: float, modes: int):
    case = fb.load_case("rod-end", overrides={"model.gravity": 0.0, "model.axial_modes": modes,
                                              "contact.stiffness": kappa * EA / L, "solver.t_end": 1.2e-4})  # fmt: skip
    return case, fb.simulate(case)


@pytest.mark.parametrize(("kappa", "modes"), [(20.0, 16), (20.0, 32), (20.0, 60), (60.0, 60)])
def test_saint_venant_rod_impact(kappa, modes):
    """One contact; t_c and v+ of the closed forms with the truncated modes' stiffening (measured within 7e-5 and
    2.4e-4 L/c, 5e-4 v0 at N = 16, 3e-5 at 32, 1e-6 at 60, 1.1e-4 at kappa = 60); the plateau EA v0 / c (measured
    ripple 1.5 % at N = 16, 0.11 % at 32, 0.01 % at 60, 0.4 % at kappa = 60); the impulse m (v+ + v0) (no gravity:
    momentum, to round-off)."""
    case, sol = rod(kappa, modes)
    met = sol.metrics()
    assert met["contacts"] == 1
    v0 = -case.initial.impact_velocity
    tc = met["contact_duration"] / TIME
    vp = met["episodes"][0]["velocity_after"][1] / v0
    assert tc == pytest.approx(2.0 + SIGMA / kappa - 2.0 * SIGMA / (math.pi**2 * modes), abs=2.5e-3)
    tol = {(20.0, 16): 5e-3, (20.0, 32): 3e-4, (20.0, 60): 2e-5, (60.0, 60): 1.2e-3}[kappa, modes]
    assert vp == pytest.approx(1.0 - C1 / kappa + 2.0 * C1 / (math.pi**2 * modes), abs=tol)
    assert met["impulse"] == pytest.approx(MASS * (vp + 1.0) * v0, rel=1e-9)
    t, F = sol.time, sol["contact_force"]
    plateau = F[(t > 0.5 * TIME) & (t < 1.5 * TIME)] / (EA * v0 / C0)
    ripple = {16: 0.15, 32: 0.012, 60: 0.004 if kappa < 30 else 0.04}[modes]
    assert np.abs(plateau - 1.0).max() < ripple


def test_saint_venant_limit_as_modes_and_stiffness_grow():
    """The contact time's excess over 2L/c is the spring's sigma* EA/(k c) less the truncation's 2 sigma*/(pi^2 N):
    N (t_c - t_c,continuum) c/L = -0.3401 (measured -0.3373, -0.3386, -0.336 at N = 16, 32, 60); stiffer and finer,
    t_c -> 2L/c and v+ -> v0."""
    excess = []
    for modes in (16, 32, 60):
        met = rod(20.0, modes)[1].metrics()
        excess.append(modes * (met["contact_duration"] / TIME - (2.0 + SIGMA / 20.0)))
    assert np.allclose(excess, -2.0 * SIGMA / math.pi**2, atol=0.04)
    soft, stiff = rod(20.0, 60)[1].metrics(), rod(60.0, 60)[1].metrics()
    assert abs(stiff["contact_duration"] / TIME - 2.0) < 0.4 * abs(soft["contact_duration"] / TIME - 2.0)
    v_soft, v_stiff = (m["episodes"][0]["velocity_after"][1] for m in (soft, stiff))
    assert abs(v_stiff - 1.0) < 0.4 * abs(v_soft - 1.0)


def test_rod_end_preset_runs_with_gravity():
    """The preset as shipped (gravity on, 32 axial modes): one contact of the closed form's time with the truncation's
    share (measured 1e-4; gravity's share g t_c / v0 = 8e-4), the force's plateau 16 kN within 2 %."""
    sol = fb.simulate(ROD)
    met = sol.metrics()
    assert met["contacts"] == 1
    expected = 2.0 + SIGMA / 20.0 - 2.0 * SIGMA / (math.pi**2 * ROD.model.axial_modes)
    assert met["contact_duration"] == pytest.approx(TIME * expected, rel=2e-3)
    assert met["peak_force"] == pytest.approx(EA * 1.0 / C0, rel=0.02)
    assert abs(met["energy_drift"]) < 1e-7


def p_theta(system: BeamSystem, y: np.ndarray) -> float:
    zd = system.velocities(0.0, y)
    return float(system.mass_matrix(0.0, y)[2] @ zd)


def test_free_flight_with_axial_vibration_and_spin_conserves_momenta_and_energy():
    """No gravity, 20 rad/s, bending and axial vibration for 2 ms: momentum to round-off, p_theta and the energy to
    1e-8 relative at fast_rtol = 1e-10 (measured 4e-15 and 9e-15; 2e-9 and 7e-11 at the default 1e-6)."""
    case = fb.load_case("rod-end", overrides={
        "model.gravity": 0.0, "model.modes": 4, "model.axial_modes": 6, "initial.kind": "state",
        "initial.position": [0.0, 1.0], "initial.velocity": [0.3, 0.2], "initial.angle": 0.4, "initial.rate": 20.0,
        "initial.modal_displacement": [1e-4, -5e-5], "initial.modal_velocity": [0.0, 0.0, 0.1],
        "initial.axial_displacement": [2e-6, 0.0, -1e-6], "initial.axial_velocity": [0.0, 0.01],
        "solver.t_end": 2e-3, "solver.fast_rtol": 1e-10})  # fmt: skip
    sol = fb.simulate(case)
    system = BeamSystem.from_case(case)
    run = sol.source.run
    y0, y1 = run.segments[0].y0, run.segments[-1].y1
    nz = system.nz
    assert np.allclose(y1[nz : nz + 2], y0[nz : nz + 2], rtol=1e-14, atol=0.0)
    p0, p1 = p_theta(system, y0), p_theta(system, y1)
    assert abs(p1 - p0) < 1e-8 * abs(p0)
    e0, e1 = (sum(system.energies(0.0, y)[k] for k in ("kinetic", "elastic")) for y in (y0, y1))
    assert abs(e1 - e0) < 1e-8 * e0
    assert np.abs(y1[3 + 4 : nz]).max() > 1e-7  # the axial modes did move


def spinning(radius: float, spin: float, modes: int):
    return fb.load_case("seed-experiment", overrides={
        "model.gravity": 0.0, "model.modes": 2, "model.axial_modes": modes, "hub.radius": radius,
        "drive.kind": "prescribed", "drive.profile": "constant-rate", "drive.spin_rate": spin,
        "output.measuring_points": [0.35]})  # fmt: skip


def stretch(radius: float, modes: int) -> tuple[float, float, float, float]:
    """(u(L), u(L/2)) of the model's axial equilibrium at theta' = Omega (Q_p = 0, by Newton's method on the kernels'
    forces) and of the rotating bar, at beta L = 0.5."""
    L0 = 0.7
    c = math.sqrt(68.95e9 / 2767.0)
    spin = 0.5 * c / L0
    case = spinning(radius, spin, modes)
    system = BeamSystem.from_case(case)
    y = system.state(0.0, spin)
    nb, n = system.beam.n, system.n
    idx = np.arange(nb, n)
    for _ in range(3):  # Q_p is linear in p
        Q = system.generalized_forces(0.0, y)[1 + nb :]
        Jac = np.empty((n - nb, n - nb))
        for j, i in enumerate(idx):
            dy = np.zeros_like(y)
            dy[i] = 1e-6
            Jac[:, j] = (system.generalized_forces(0.0, y + dy)[1 + nb :] - Q) / 1e-6
        y[idx] -= np.linalg.solve(Jac, Q)
    beta = spin / c
    B = (1.0 + radius * beta * math.sin(beta * L0)) / (beta * math.cos(beta * L0))

    def u(x):
        return -(radius + x) + radius * math.cos(beta * x) + B * math.sin(beta * x)

    tip = np.hypot(*system.point_state(0.0, y, 1)[0]) - (radius + L0)
    mid = np.hypot(*system.point_state(0.0, y, 2)[0]) - (radius + 0.35)
    return tip, mid, u(L0), u(0.35)


@pytest.mark.parametrize("radius", [0.0, 0.2])
def test_centrifugal_stretch_of_a_spinning_rod(radius):
    """u(L) and u(L/2) of the model with 32 fixed-free modes within 1e-5 relative of the rotating bar's (measured
    1.1e-6 at worst); the truncation's error falls like N^-3 (a static load's modal coefficients ~ kappa_k^-4: measured
    ratios 7.8 and 7.9 from N = 8 to 16); the stiffening term mu Omega^2 u is 10 % of u(L) at beta L = 0.5."""
    tip, mid, u_tip, u_mid = stretch(radius, 32)
    assert tip == pytest.approx(u_tip, rel=1e-5)
    assert mid == pytest.approx(u_mid, rel=1e-5)
    coarse, fine = stretch(radius, 8)[0] - u_tip, stretch(radius, 16)[0] - u_tip
    assert 6.0 < coarse / fine < 10.0
    L0, beta = 0.7, 0.5 / 0.7
    linear = beta**2 * (radius * L0**2 / 2 + L0**3 / 3)  # without mu Omega^2 u: u'' = -beta^2 (r_h + x)
    assert abs(tip - linear) > 0.05 * abs(tip)
