"""The FE reference's own evaluation of the CCFM contact force (Numba), independent of the modal code.

Every contact law of flexbeam has the form (penetration d = -delta >= 0, rate d' = -delta')

    F = max(0,  K d^n (1 + chi d'/d'_0) + C d'),

with the elastic part F_k = K d^n and its potential U_c = K d^(n+1)/(n+1): Hertz (1882)
for chi = C = 0, the Hunt & Crossley (1975) family for chi > 0 (d'_0 > 0 the penetration
rate at the onset of the contact), the linear spring-dashpot for n = 1, chi = 0.  The law's
*parameters* -- the vector p = [K, n, chi/d'_0, C] -- are the case's inputs and come from
:mod:`flexbeam.contact.laws` (each law's chi(e) formula, the Kelvin-Voigt damping); the
force, its derivatives and the potential are evaluated here, so that the finite-element
reference does not run the modal model's force kernel (``tests/fem/test_contact_law.py``
checks them against the published expressions and the exact restitution).
"""

from __future__ import annotations

import math

from .jit import fem_jit


@fem_jit
def law_force(p, d, dd):
    """Contact force and its partial derivatives at penetration ``d`` [m] and rate ``dd`` [m/s].

    Parameters
    ----------
    p
        [K, n, chi/d'_0, C]: stiffness [N/m^n], exponent, hysteresis factor over the onset
        rate [s/m], linear damping [N s/m].
    d, dd
        Penetration d = -delta and its rate d' = -delta'.

    Returns
    -------
    F, F_k, dF/dd, dF/dd'
        The force F = max(0, K d^n (1 + chi d'/d'_0) + C d') [N], its elastic part
        F_k = K d^n (also when F is clipped to zero) and the derivatives of F (zero
        where F is clipped or the bodies are apart).
    """
    if d <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    K, n, h, C = p[0], p[1], p[2], p[3]
    elastic = K * d**n
    force = elastic * (1.0 + h * dd) + C * dd
    if force <= 0.0:
        return 0.0, elastic, 0.0, 0.0
    return force, elastic, n * K * d ** (n - 1.0) * (1.0 + h * dd), elastic * h + C


@fem_jit
def law_potential(p, d):
    """Elastic contact potential U_c = K d^(n+1)/(n+1) [J] at penetration ``d`` (0 when apart)."""
    if d <= 0.0:
        return 0.0
    return p[0] * d ** (p[1] + 1.0) / (p[1] + 1.0)


@fem_jit
def friction_law(mu_k, mu_s, vs, v, model=0.0):
    """Friction coefficient phi(v) of a regularised Coulomb law and its derivative d phi / dv.

    ``model`` 0: Brown & McPhee (2016), J. Comput. Nonlinear Dynam. 11(5) 054502, without its viscous term,

        phi(v) = mu_k tanh(4 v / v_s) + (mu_s - mu_k) (v / v_s) / ((v / v_s)^2 / 4 + 3 / 4)^2,

    odd in the slip velocity v, rising to about mu_s at v = v_s (its second term peaks there at mu_s - mu_k;
    tanh(4) = 0.9993) and tending to mu_k in sliding: Coulomb's law with static and kinetic coefficients as the
    transition velocity v_s -> 0 (the FE's stand-in for exact stick and slip).  ``model`` 1: Threlfall's law
    (Mechanism and Machine Theory 13 (1978) 475), phi(v) = mu_k (1 - exp(-3 abs(v) / v_s)) sign(v), the case's
    ``contact.friction_model = "threlfall"`` with v_s its ``contact.friction_velocity``.  The tangential force on the
    beam is -N phi(v_t) along the contact's tangent.
    """
    if model == 1.0:
        e = math.exp(-3.0 * abs(v) / vs)
        return mu_k * math.copysign(1.0 - e, v), 3.0 * mu_k * e / vs
    u = v / vs
    th = math.tanh(4.0 * u)
    D = 0.25 * u * u + 0.75
    phi = mu_k * th + (mu_s - mu_k) * u / (D * D)
    dphi = (4.0 * mu_k * (1.0 - th * th) + (mu_s - mu_k) * (D - u * u) / (D * D * D)) / vs
    return phi, dphi
