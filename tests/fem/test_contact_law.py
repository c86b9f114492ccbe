"""The FE reference's own contact-force kernel against the published laws and their restitution.

:func:`flexbeam.fem.contact_law.law_force` evaluates F = max(0, K d^n (1 + chi d'/d'_0) + C d')
for the parameter vector each law of :mod:`flexbeam.contact.laws` sets up.  Checked at random
inputs (Hypothesis) against

* the published force expressions: Hertz (1882) F = K d^(3/2); Hunt & Crossley (1975)
  F = K d^n (1 + 3(1 - e)/2 d'/d'_0); Lankarani & Nikravesh (1990) chi = 3(1 - e^2)/4;
  Flores et al. (2011) chi = 8(1 - e)/(5 e); Gonthier et al. (2004) chi = (1 - e^2)/e; the
  linear spring-dashpot F = max(0, k d + c d') with c = 2 zeta sqrt(k m),
  zeta = -ln e / sqrt(pi^2 + ln^2 e);
* its own derivatives (central differences) and the potential (quadrature of F_k);
* the exact restitution of a 1-DOF impact, m d'' = -F, integrated with
  :func:`scipy.integrate.solve_ivp`: the root e of (1 + e) chi = ln[(1 + chi)/(1 - e chi)]
  for the Hunt-Crossley form (Carvalho & Martins 2019, for any m, K, n and speed), and
  the Schwager & Poeschel (2007) closed form of the clipped spring-dashpot.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from flexbeam.contact.laws import make_law
from flexbeam.fem.contact_law import law_force, law_potential

#: chi(e) of each hysteresis law as published (not flexbeam's code)
PUBLISHED_CHI = {
    "hunt_crossley": lambda e: 1.5 * (1.0 - e),
    "lankarani_nikravesh": lambda e: 0.75 * (1.0 - e * e),
    "flores": lambda e: 8.0 * (1.0 - e) / (5.0 * e),
    "gonthier": lambda e: (1.0 - e * e) / e,
}

stiffness = st.floats(1e4, 1e10)
exponent = st.floats(1.0, 2.0)
restitution = st.floats(0.2, 0.99)
penetration = st.floats(1e-9, 1e-3)
onset_rate = st.floats(1e-3, 10.0)
#: penetration rate as a fraction of the onset rate (negative: restitution phase)
rate_fraction = st.floats(-1.0, 1.0)

# Tolerances.  Force: the kernel and the expected value are a handful of rounded products and
# one power, a few ulps (measured <= 3.6e-16 relative over 20000 random draws); 1e-12 keeps a margin > 1000.
RTOL_FORMULA = 1e-12


@settings(max_examples=60, deadline=None)
@given(
    name=st.sampled_from(sorted(PUBLISHED_CHI)),
    K=stiffness,
    n=exponent,
    e=restitution,
    d=penetration,
    v0=onset_rate,
    frac=rate_fraction,
)
def test_hysteresis_laws_give_the_published_force(name, K, n, e, d, v0, frac):
    dd = frac * v0
    p = make_law(name, K, n, e).parameters(v0, 1.0)
    F, Fk, _, _ = law_force(p, d, dd)
    chi = PUBLISHED_CHI[name](e)
    expected = max(0.0, K * d**n * (1.0 + chi * dd / v0))
    # near the clipping point 1 + chi d'/d'_0 = 0 the error is relative to the terms, not their sum
    assert_allclose(F, expected, rtol=RTOL_FORMULA, atol=RTOL_FORMULA * K * d**n * (1.0 + chi))
    assert_allclose(Fk, K * d**n, rtol=RTOL_FORMULA)


@settings(max_examples=40, deadline=None)
@given(K=stiffness, e=restitution, d=penetration, v0=onset_rate, frac=rate_fraction)
def test_hertz_is_k_d_to_three_halves_whatever_the_rate(K, e, d, v0, frac):
    p = make_law("hertz", K, 1.5, e).parameters(v0, 1.0)
    F, Fk, dFd, dFdd = law_force(p, d, frac * v0)
    assert_allclose(
        [F, Fk, dFd], [K * d * math.sqrt(d), K * d * math.sqrt(d), 1.5 * K * math.sqrt(d)], rtol=RTOL_FORMULA
    )
    assert dFdd == 0.0


@settings(max_examples=40, deadline=None)
@given(k=stiffness, e=restitution, m=st.floats(1e-3, 10.0), d=penetration, dd=st.floats(-10.0, 10.0))
def test_kelvin_voigt_is_a_clipped_spring_dashpot(k, e, m, d, dd):
    p = make_law("kelvin_voigt", k, 1.0, e).parameters(1.0, m)
    zeta = -math.log(e) / math.sqrt(math.pi**2 + math.log(e) ** 2)
    c = 2.0 * zeta * math.sqrt(k * m)
    F, Fk, _, _ = law_force(p, d, dd)
    assert_allclose(F, max(0.0, k * d + c * dd), rtol=RTOL_FORMULA, atol=RTOL_FORMULA * (k * d + abs(c * dd)))
    assert_allclose(Fk, k * d, rtol=RTOL_FORMULA)


@settings(max_examples=20, deadline=None)
@given(K=stiffness, n=exponent, e=restitution, v0=onset_rate, dd=st.floats(-10.0, 10.0))
def test_no_force_when_apart(K, n, e, v0, dd):
    p = make_law("hunt_crossley", K, n, e).parameters(v0, 1.0)
    for d in (0.0, -1e-6, -1.0):
        assert law_force(p, d, dd) == (0.0, 0.0, 0.0, 0.0)
        assert law_potential(p, d) == 0.0


@settings(max_examples=60, deadline=None)
@given(
    name=st.sampled_from(sorted(PUBLISHED_CHI)),
    K=stiffness,
    n=exponent,
    e=st.floats(0.5, 0.99),
    d=penetration,
    v0=onset_rate,
    frac=st.floats(-0.5, 1.0),
)
def test_derivatives_are_central_differences(name, K, n, e, d, v0, frac):
    """dF/dd and dF/dd' (Newton's tangent) against central differences of F.

    Steps of 1e-6 of d and v0: truncation ~(1e-6)^2 relative, round-off ~1e-16/1e-6 = 1e-10;
    measured <= 2.5e-10 relative over 5000 draws, tolerance 1e-7 (margin 400).  e >= 0.5 and d'/d'_0 >= -0.5
    keep the force away from its clipping kink: chi(e >= 0.5) <= 1.6, so 1 + chi d'/d'_0 >= 0.2.
    """
    p = make_law(name, K, n, e).parameters(v0, 1.0)
    dd = frac * v0
    F, _, dFd, dFdd = law_force(p, d, dd)
    assert F > 0.0
    h, hv = 1e-6 * d, 1e-6 * v0
    num_d = (law_force(p, d + h, dd)[0] - law_force(p, d - h, dd)[0]) / (2 * h)
    num_v = (law_force(p, d, dd + hv)[0] - law_force(p, d, dd - hv)[0]) / (2 * hv)
    scale = F / d  # the size of dF/dd
    assert_allclose(dFd, num_d, rtol=1e-7, atol=1e-7 * scale)
    assert_allclose(dFdd, num_v, rtol=1e-7, atol=1e-7 * F / v0)


@settings(max_examples=30, deadline=None)
@given(K=stiffness, n=exponent, d=penetration)
def test_potential_is_the_integral_of_the_elastic_force(K, n, d):
    """U_c(d) = int_0^d F_k (adaptive quadrature, relative error ~1e-14; tolerance 1e-10)."""
    p = np.array([K, n, 0.7, 0.0])
    U, _ = quad(lambda x: law_force(p, x, 0.0)[1], 0.0, d, epsabs=0.0, epsrel=1e-13)
    assert_allclose(law_potential(p, d), U, rtol=1e-10)


def _rebound(p: np.ndarray, m: float, v0: float) -> float:
    """e_eff = rebound / impact speed of a mass m hitting the law at v0 (d' = v0 at d = 0)."""
    d_max = ((p[1] + 1.0) * m * v0**2 / (2.0 * p[0])) ** (1.0 / (p[1] + 1.0))  # undamped bound

    def rhs(t, y):
        return [y[1], -law_force(p, y[0], y[1])[0] / m]

    def leaves(t, y):
        return y[0]

    leaves.terminal, leaves.direction = True, -1.0
    sol = solve_ivp(
        rhs,
        (0.0, 50.0 * d_max / v0),
        [0.0, v0],
        method="DOP853",
        events=leaves,
        rtol=1e-11,
        atol=1e-14 * d_max,
        first_step=1e-4 * d_max / v0,
    )
    assert sol.status == 1, "the mass did not leave the contact"
    return -float(sol.y_events[0][0][1]) / v0


def _carvalho_martins_restitution(chi: float) -> float:
    """Root e of (1 + e) chi = ln[(1 + chi)/(1 - e chi)] in (0, min(1, 1/chi))."""
    f = lambda e: (1.0 + e) * chi - math.log1p(chi) + math.log1p(-e * chi)  # noqa: E731
    return brentq(f, 1e-12, min(1.0, (1.0 - 1e-15) / chi), xtol=1e-15, rtol=1e-15)


@settings(max_examples=15, deadline=None)
@given(
    name=st.sampled_from(sorted(PUBLISHED_CHI)),
    K=stiffness,
    n=exponent,
    e=st.floats(0.35, 0.95),
    m=st.floats(1e-2, 10.0),
    v0=st.floats(0.05, 5.0),
)
def test_hunt_crossley_form_restitutes_by_the_exact_relation(name, K, n, e, m, v0):
    """Integrated 1-DOF impact against Carvalho & Martins' relation: whatever m, K, n, v0.

    DOP853 at rtol 1e-11 with the exit located by its event: measured |error| <= 3.2e-10 over 60
    draws; tolerance 1e-6 (margin > 1000).
    """
    p = make_law(name, K, n, e).parameters(v0, m)
    chi = p[2] * v0
    assert_allclose(_rebound(p, m, v0), _carvalho_martins_restitution(chi), atol=1e-6)


@pytest.mark.parametrize("e", [0.3, 0.6, 0.9])
def test_clipped_spring_dashpot_restitutes_by_the_closed_form(e):
    """Schwager & Poeschel (2007): the clipped linear law separates when the force vanishes,
    at w_d t* = pi - atan2(2 s w_d, w_d^2 - s^2), e_eff = exp(-s phi/w_d)(...) (w_n = 1).

    Tolerance 1e-6 as above (measured <= 7e-11)."""
    k, m, v0 = 2.0e6, 0.4, 0.8
    p = make_law("kelvin_voigt", k, 1.0, e).parameters(v0, m)
    le = math.log(e)
    s = -le / math.sqrt(math.pi**2 + le**2)
    wd = math.sqrt(1.0 - s * s)
    phi = math.pi - math.atan2(2.0 * s * wd, wd * wd - s * s)
    expected = -math.exp(-s * phi / wd) * (math.cos(phi) - (s / wd) * math.sin(phi))
    assert_allclose(_rebound(p, m, v0), expected, atol=1e-6)
