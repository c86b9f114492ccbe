"""The FE run's step sizes, from the Hertz duration of the contacts it has to resolve.

``fem.time_step`` fixes the step.  Otherwise, during contact h_c = t_c / 200 with t_c
the Hertz duration 2 delta_max / v int_0^1 (1 - s^(n+1))^(-1/2) ds of the approach
speed v and a reference effective mass (the rigid-body one, (J_h + J_beam)/J_theta^2
for a free or torque-driven joint, 1/(1/m + a^2/J_G) at lever arm a about G for a free beam;
the first clamped mode's mu L / phi_1(x_P)^2 when theta(t) is prescribed), and in free
flight h_f = 2 h_c (t_c estimated with the impact velocity of the case; with several
pairs each pair's own estimate with its law and J_theta at its point, the smallest of them
for h_f, and while several pairs are in contact the smallest of theirs).  The free-flight
factor is kept small because the vibration that an impact excites has the contact's own time scale, and the phase of
that vibration decides the next contact: later contacts converge slowly with the
step, so set ``fem.time_step`` for converged multi-contact histories.
"""

from __future__ import annotations

import math

import numpy as np

from ..contact.hertz import rigid_hertz_impact
from .beam import FemBeam

#: steps per estimated contact duration, and free/contact step ratio
STEPS_PER_CONTACT = 200
FREE_STEP_FACTOR = 2.0


def reference_mass(beam: FemBeam, z: np.ndarray, pair: int = 0) -> float:
    """Effective mass used only to size the contact step of ``pair`` (see the module docstring)."""
    case = beam.case
    xP = beam.pairs[pair].position
    if beam.free:
        return beam.rigid_effective_mass(z, pair)
    if not beam.prescribed:
        J_theta = beam.rotation_jacobian(z, pair)
        L, rh, mu = case.beam.length, beam.hub_radius, beam.mu
        inertia = beam.hub_inertia + mu * ((rh + L) ** 3 - rh**3) / 3.0
        if abs(J_theta) > 0.0:
            return inertia / J_theta**2
        return math.inf
    bl = 1.8751040687119611
    L = case.beam.length
    s = (math.cosh(bl) + math.cos(bl)) / (math.sinh(bl) + math.sin(bl))
    x = bl * xP / L
    phi = math.cosh(x) - math.cos(x) - s * (math.sinh(x) - math.sin(x))
    return beam.mu * L / max(phi * phi, 1e-12)


def contact_step(beam: FemBeam, mass: float, speed: float, pair: int = 0) -> float:
    """h_c = t_c / STEPS_PER_CONTACT from the rigid Hertz impact estimate with the law of ``pair``."""
    law = beam.pairs[pair].law
    mass = min(mass, 1e6 * beam.mu * beam.case.beam.length)
    speed = max(abs(speed), 1e-6)
    _, _, tc = rigid_hertz_impact(mass, speed, law.stiffness, law.exponent)
    return tc / STEPS_PER_CONTACT


def initial_step_sizes(beam: FemBeam, z0: np.ndarray, t_end: float) -> tuple[float, float, list[float]]:
    """(h_c, h_f, the pairs' reference masses) at the start of a run from ``z0`` to ``t_end``: the smallest of the
    pairs' contact steps at the case's impact speed, h_f = FREE_STEP_FACTOR h_c (both ``fem.time_step`` if set),
    neither above t_end / 20 and h_c <= h_f."""
    h_fixed = beam.case.fem.time_step
    v_ref = abs(beam.case.initial.impact_velocity)
    m_ref = [reference_mass(beam, z0, k) for k in range(beam.npairs)]
    h_c = contact_step(beam, m_ref[0], v_ref)
    for k in range(1, beam.npairs):
        h_c = min(h_c, contact_step(beam, m_ref[k], v_ref, k))
    h_free = FREE_STEP_FACTOR * h_c
    if h_fixed is not None:
        h_c = h_free = h_fixed
    h_free = min(h_free, t_end / 20.0)
    h_c = min(h_c, h_free)
    return h_c, h_free, m_ref
