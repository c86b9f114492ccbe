"""Hertz contact stiffness from the materials and curvatures of the two bodies.

Johnson, *Contact Mechanics* (1985), Sec. 4.2: for two bodies with effective modulus
1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 and principal relative radii R', R'', the
elliptical Hertz contact is approximated by a circular one of equivalent radius
R_e = sqrt(R' R'') (Johnson eq. 4.29; the correction factors F1, F2 of his Fig. 4.4
stay within a few per cent for R'/R'' < 3), giving F = K delta^(3/2) with

    K = 4/3 E* sqrt(R_e).

A sphere of radius R_s touching the lateral surface of a cylinder of radius R_c
(the beam section) at right angles to its axis has 1/R' = 1/R_s (along the beam
axis, where the cylinder is straight) and 1/R'' = 1/R_s + 1/R_c.
"""

from __future__ import annotations

import functools
import math

from .. import numerics as nm


def effective_modulus(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """Effective contact modulus E* [Pa]: 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2."""
    return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2)


def sphere_on_cylinder_stiffness(sphere_radius: float, cylinder_radius: float, E_star: float) -> float:
    """Hertz stiffness K [N/m^1.5] of a sphere on a cylinder (crossed at right angles).

    Equivalent-radius approximation R_e = sqrt(R' R''), Johnson (1985) eq. 4.29.
    A point obstacle (radius 0) or a flat section (radius inf) are not Hertzian.
    """
    if sphere_radius <= 0.0:
        raise ValueError("obstacle.radius: must be > 0 for a Hertz stiffness (give contact.stiffness)")
    curv1 = 1.0 / sphere_radius
    curv2 = 1.0 / sphere_radius + (1.0 / cylinder_radius if cylinder_radius > 0 else 0.0)
    r_e = math.sqrt(1.0 / (curv1 * curv2))
    return 4.0 / 3.0 * E_star * math.sqrt(r_e)


def rigid_hertz_impact(mass: float, speed: float, K: float, n: float = 1.5) -> tuple[float, float, float]:
    """Closed-form impact of a rigid mass on an undamped spring F = K delta^n.

    Energy: 1/2 m v^2 = K delta_max^(n+1)/(n+1); duration::

        t_c = (2 delta_max / v) int_0^1 (1 - s^(n+1))^(-1/2) ds
            = (2 delta_max / v) sqrt(pi) Gamma(1 + 1/(n+1)) / Gamma(1/2 + 1/(n+1))

    (= 2.9432 delta_max / v for Hertz, n = 3/2; Johnson 1985 Sec. 11.4).

    Returns
    -------
    delta_max, F_max, t_c
    """
    dmax = nm.pow((n + 1.0) * mass * speed * speed / (2.0 * K), 1.0 / (n + 1.0))
    return dmax, K * nm.pow(dmax, n), 2.0 * _duration_factor(n) * dmax / speed


@functools.lru_cache(maxsize=16)
def _duration_factor(n: float) -> float:
    """int_0^1 (1 - s^(n+1))^(-1/2) ds = sqrt(pi) Gamma(1 + a) / Gamma(1/2 + a), a = 1/(n+1) (rigid_hertz_impact;
    a law's exponent n takes a few values in a run: each contact's onset reads it here)."""
    a = 1.0 / (n + 1.0)
    return math.sqrt(math.pi) * nm.gamma(1.0 + a) / nm.gamma(0.5 + a)
