"""The FE run's initial state: the straight beam in rigid rotation (a given state, or the rate that gives P the
impact velocity), a prescribed drive's start, or the static equilibrium under gravity from which the released beam
reaches the obstacle at the impact velocity (found by shooting on the FE free flight)."""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from ..errors import ParameterError
from .beam import FemBeam
from .eventdriven import run
from .integrator import FemIntegrator, State, StepResult


def _impact_rate(beam: FemBeam, theta: float, velocity: float) -> float:
    """Rigid rotation rate of the straight beam giving P the normal velocity ``velocity``."""
    z, _ = beam.straight(theta, 0.0)
    return beam.case.initial.impact_rate(beam.rotation_jacobian(z), velocity)


def release_state(beam: FemBeam, angle: float) -> tuple[np.ndarray, np.ndarray]:
    """At rest in the static equilibrium under gravity with the hub held at ``angle``."""
    z = beam.static_equilibrium(angle, steps=1)
    return z, np.zeros_like(z)


def _first_impact_velocity(beam: FemBeam, angle: float) -> float:
    """The normal velocity delta' of the pair that closes first, released from rest at ``angle`` (the shooting
    function of :func:`solve_release_angle`); a ParameterError if the beam does not reach an obstacle in 10 s."""
    integ = FemIntegrator(beam, beam.case.fem.rho_inf)
    z, zd = release_state(beam, angle)
    out: list[StepResult] = []

    def sample(s: State, res: StepResult, phase: str, lawp) -> None:
        out.append(res)

    _, info, _ = run(beam, integ, z, zd, 10.0, sample, stop_at_impact=True)
    if info.status != "impact":
        raise ParameterError(f"initial.release_angle: released at {angle:.6g} rad the beam does not reach the obstacle")
    last = out[-1]
    pair = int(np.argmin(last.pair_gap))  # the pair whose gap closed (the others are open)
    return float(last.pair_gap_rate[pair])


def solve_release_angle(beam: FemBeam) -> float:
    """Release angle from rest at which P reaches the obstacle at the impact velocity.

    Shooting on the finite-element free flight (:func:`scipy.optimize.brentq`), started
    from the rigid-rod estimate g m1 (sin th_r - sin th_i) = 1/2 J rate^2.
    """
    case = beam.case
    init = case.initial
    th_i = init.impact_angle
    rate = _impact_rate(beam, th_i, init.impact_velocity)
    L, rh, mu, g = case.beam.length, beam.hub_radius, beam.mu, beam.gravity
    m1 = mu * ((rh + L) ** 2 - rh**2) / 2.0
    J = beam.hub_inertia + mu * ((rh + L) ** 3 - rh**3) / 3.0
    if g <= 0.0:
        raise ParameterError("initial.kind: 'release' needs gravity (model.gravity > 0)")
    s = math.sin(th_i) + 0.5 * J * rate**2 / (g * m1)
    if s >= 1.0:
        raise ParameterError(
            f"initial.impact_velocity: {init.impact_velocity:g} m/s cannot be reached by release "
            "from rest under gravity"
        )
    guess = math.asin(s)
    lo, hi = th_i + 0.8 * (guess - th_i), min(th_i + 1.25 * (guess - th_i), 0.5 * math.pi)
    try:
        return float(
            brentq(
                lambda a: _first_impact_velocity(beam, a) - init.impact_velocity,
                lo,
                hi,
                xtol=1e-10,
                rtol=1e-8,
            )
        )
    except ValueError:
        raise ParameterError(
            "initial.release_angle: no release angle near the rigid estimate "
            f"{guess:.6g} rad gives the impact velocity; give initial.release_angle"
        ) from None


def initial_state(beam: FemBeam) -> tuple[np.ndarray, np.ndarray, dict[str, float]]:
    """(z, z', info) for ``case.initial`` (see :func:`flexbeam.simulation.initial_state`)."""
    init = beam.case.initial
    if beam.free:
        return beam.free_initial_state()
    if beam.prescribed:
        th, thd, _ = beam.drive.motion(0.0)
        z, zd = beam.straight(th, thd)
        return z, zd, {}
    if init.kind == "state":
        z, zd = beam.straight(init.angle, init.rate)
        return z, zd, {}
    if init.kind == "impact":
        rate = _impact_rate(beam, init.impact_angle, init.impact_velocity)
        z, zd = beam.straight(init.impact_angle, rate)
        return z, zd, {"impact_rate": rate}
    angle = init.release_angle
    if angle is None:
        angle = solve_release_angle(beam)
    z, zd = release_state(beam, angle)
    return z, zd, {"release_angle": float(angle)}
