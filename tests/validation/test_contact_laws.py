"""Contact force laws on a 1-DOF mass: effective restitution, Hertz closed form, impulse.

A rigid mass m hits the law with speed v_in: m d'' = -F(d, d'), d(0) = 0, d'(0) = v_in,
integrated here with scipy's ``solve_ivp`` (DOP853, rtol 1e-12) until d returns to 0, using
flexbeam's own force evaluation (``law_force`` with the parameters the law derives from e).
The effective restitution is e_eff = v_out / v_in.

References (each checked against the number it gives here):

* Hunt-Crossley form F = K d^n (1 + chi d'/v_in): integrating m v dv/dd over a whole
  contact gives the exact, n-, K-, m- and v_in-independent relation
  (1 + e) chi = ln[(1 + chi) / (1 - e chi)] between chi and the resulting e
  (A. S. Carvalho, J. M. Martins, "Exact restitution and generalizations for the
  Hunt-Crossley contact model", Mech. Mach. Theory 139 (2019) 174-194,
  doi:10.1016/j.mechmachtheory.2019.04.018).  It is solved here
  for e given each law's chi, an analytic reference independent of any integrator.
* chi(e) of each law: Hunt & Crossley, J. Appl. Mech. 42 (1975) 440 (3(1-e)/2);
  Lankarani & Nikravesh, J. Mech. Des. 112 (1990) 369 (3(1-e^2)/4); Gonthier, McPhee, Lange
  & Piedboeuf, Multibody Syst. Dyn. 11 (2004) 209 ((1-e^2)/e); Flores, Machado, Silva &
  Martins, Multibody Syst. Dyn. 25 (2011) 357 (8(1-e)/(5e)); Carvalho & Martins (2019)
  (exact root of the relation above).
* Linear Kelvin-Voigt F = k d + c d' with c = 2 zeta sqrt(k m),
  zeta = -ln e / sqrt(pi^2 + ln^2 e): e is exact for the unclipped oscillator; with the
  force clipped at zero (no adhesion) the mass separates when F = 0, before d = 0, and
  leaves faster (T. Schwager, T. Poeschel, "Coefficient of restitution and linear-dashpot
  model revisited", Granular Matter 9 (2007) 465-469); the clipped value is computed
  here in closed form from the damped oscillator.
* Hertz impact of a rigid mass (K. L. Johnson, Contact Mechanics, CUP 1985, Sec. 11.4):
  delta_max = (5 m v^2 / (4 K))^(2/5), F_max = K delta_max^(3/2),
  t_c = 2.9432 delta_max / v (exactly 2 sqrt(pi) Gamma(7/5)/Gamma(9/10) = 2.943275).
* Impulse-momentum: int F dt = m (v_in + v_out) for every law.

What was found (e_eff for nominal e = 0.3, 0.5, 0.7, 0.9; the whole range is the table
``EXPECTED`` below, asserted to 5e-5):

=====================  ======  ======  ======  ======  ===========================================
law                    0.3     0.5     0.7     0.9     verdict
=====================  ======  ======  ======  ======  ===========================================
carvalho_martins       0.3000  0.5000  0.7000  0.9000  exact (1e-9 here), also for e < 1/3
hertz                  1       1       1       1       elastic, ignores e (by design)
kelvin_voigt unclipped 0.3000  0.5000  0.7000  0.9000  exact
kelvin_voigt (clipped) 0.3971  0.5503  0.7182  0.9020  too elastic: +32 %, +10 %, +2.6 %, +0.23 %
hunt_crossley          0.5813  0.6630  0.7680  0.9090  only near e = 1: +94 % ... +1.0 %
lankarani_nikravesh    0.6842  0.7252  0.7960  0.9132  only near e = 1: +128 % ... +1.5 %
flores                 0.2562  0.4704  0.6832  0.8939  whole range, low: -15 %, -6 %, -2.4 %, -0.7 %
gonthier               0.3042  0.4877  0.6696  0.8764  whole range within 4.4 % (+1.4 % ... -4.3 %)
=====================  ======  ======  ======  ======  ===========================================

flexbeam clips every law at F = 0, so its Kelvin-Voigt law restitutes more than the nominal e.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from flexbeam.contact.hertz import rigid_hertz_impact
from flexbeam.contact.laws import LAWS, exact_hunt_crossley_chi, law_force, make_law

RESTITUTIONS = (0.3, 0.5, 0.7, 0.9)
HC_FAMILY = ("hunt_crossley", "lankarani_nikravesh", "flores", "gonthier", "carvalho_martins")

#: e_eff found for each law (4 decimals) -- the table of the module docstring
EXPECTED = {
    "carvalho_martins": (0.3, 0.5, 0.7, 0.9),
    "hertz": (1.0, 1.0, 1.0, 1.0),
    "kelvin_voigt": (0.3971, 0.5503, 0.7182, 0.9020),
    "hunt_crossley": (0.5813, 0.6630, 0.7680, 0.9090),
    "lankarani_nikravesh": (0.6842, 0.7252, 0.7960, 0.9132),
    "flores": (0.2562, 0.4704, 0.6832, 0.8939),
    "gonthier": (0.3042, 0.4877, 0.6696, 0.8764),
}


def impact(p, m: float, v_in: float, clip: bool = True):
    """Integrate m d'' = -F from d = 0, d' = v_in to separation (d = 0 again).

    Returns (v_out, impulse int F dt, t_c, d_max, F at d_max).
    ``clip=False`` evaluates the unclipped linear force k d + c d' (Kelvin-Voigt check).
    """

    def force(d, dd):
        if clip:
            return law_force(p, d, dd)[0]
        return p[0] * d ** p[1] * (1.0 + p[2] * dd) + p[3] * dd

    def rhs(t, y):
        f = force(y[0], y[1])
        return [y[1], -f / m, f]

    def back(t, y):
        return y[0]

    def turn(t, y):
        return y[1]

    back.terminal, back.direction = True, -1
    turn.direction = -1
    # scales from the undamped contact (d_max, t_c) for the tolerances and the time span
    k, n = p[0], p[1]
    dmax = ((n + 1.0) * m * v_in**2 / (2.0 * k)) ** (1.0 / (n + 1.0))
    atol = 1e-15 * np.array([dmax, v_in, m * v_in])
    sol = solve_ivp(
        rhs, (0.0, 100.0 * dmax / v_in), [0.0, v_in, 0.0], method="DOP853", rtol=1e-12, atol=atol, events=(back, turn)
    )
    assert sol.status == 1, "no separation"
    t_c, (_, v_end, imp) = sol.t_events[0][0], sol.y_events[0][0]
    d_top = sol.y_events[1][0][0]
    return -v_end, imp, t_c, d_top, force(d_top, 0.0)


def restitution_from_chi(chi: float) -> float:
    """e solving (1 + e) chi = ln[(1 + chi)/(1 - e chi)] (Carvalho & Martins 2019)."""
    if chi == 0.0:
        return 1.0
    f = lambda e: (1.0 + e) * chi - math.log1p(chi) + math.log1p(-e * chi)  # noqa: E731
    return brentq(f, 1e-12, min(1.0, (1.0 - 1e-15) / chi), xtol=1e-15, rtol=1e-15)


def kelvin_voigt_clipped(e: float) -> float:
    """Restitution of the linear spring-dashpot whose force may not turn tensile.

    d = (v/w_d) exp(-s t) sin(w_d t), s = zeta w_n; F = -m d'' vanishes first at
    w_d t* = pi - atan2(2 s w_d, w_d^2 - s^2); then e_eff = -d'(t*)/v.
    """
    le = math.log(e)
    zeta = -le / math.sqrt(math.pi**2 + le**2)
    s, wd = zeta, math.sqrt(1.0 - zeta**2)  # w_n = 1
    phi = math.pi - math.atan2(2.0 * s * wd, wd * wd - s * s)
    return -math.exp(-s * phi / wd) * (math.cos(phi) - (s / wd) * math.sin(phi))


def e_eff(
    name: str, e: float, m: float = 1.0, K: float = 1.0, v: float = 1.0, n: float = 1.5, clip: bool = True
) -> tuple[float, float]:
    law = make_law(name, K, n, e)
    p = law.parameters(v, m)
    v_out, imp, *_ = impact(p, m, v, clip)
    return v_out / v, imp


# ------------------------------------------------------------------------------ restitution
@pytest.mark.parametrize("e", RESTITUTIONS)
@pytest.mark.parametrize("name", list(LAWS))
def test_effective_restitution_and_impulse(name, e):
    m, v = 0.37, 0.4
    got, imp = e_eff(name, e, m=m, K=4.4e9, v=v)
    # the documented value: the table rounds to four decimals, half a unit is 5e-5 (measured 4.5e-5, the rounding
    # of one entry); the integration's own error, ~1e-9, rides on top
    assert got == pytest.approx(EXPECTED[name][RESTITUTIONS.index(e)], abs=5e-5 + 1e-8)
    # impulse-momentum: int F dt = m (v_in + v_out)
    assert imp == pytest.approx(m * v * (1.0 + got), rel=1e-9)
    # analytic references
    if name in HC_FAMILY:
        chi = make_law(name, 1.0, 1.5, e).chi()
        assert got == pytest.approx(restitution_from_chi(chi), rel=1e-8)
    elif name == "hertz":
        assert got == pytest.approx(1.0, rel=1e-9)
    elif name == "kelvin_voigt":
        assert got == pytest.approx(kelvin_voigt_clipped(e), rel=1e-8)
        assert got > e
        unclipped, _ = e_eff(name, e, m=m, K=4.4e9, v=v, clip=False)
        assert unclipped == pytest.approx(e, rel=1e-8)


@pytest.mark.parametrize("e", RESTITUTIONS)
def test_carvalho_martins_is_exact(e):
    assert e_eff("carvalho_martins", e)[0] == pytest.approx(e, abs=1e-6)


@pytest.mark.parametrize("e", [0.05, 0.1, 0.3, 0.5, 0.9, 0.99])
def test_exact_chi_solves_the_restitution_relation(e):
    """flexbeam's chi(e) against an independent root of f(chi) = (1 - e chi) - (1 + chi) exp(-(1 + e) chi) = 0.
    Either root is only as good as f's round-off allows: eps (1 + e chi + (1 + chi) exp(-(1 + e) chi)) /
    |f'(chi)|, relative to chi 4e-16 at e = 0.05 but 2e-10 at e = 0.99, where f is flat (measured 3.1e-11
    there); bound 10 times that."""
    chi = exact_hunt_crossley_chi(e)

    def f(c):
        return (1 - e * c) - (1 + c) * math.exp(-(1 + e) * c)

    ref = brentq(f, (1 - e) / e, 1 / e, xtol=1e-15, rtol=1e-15)
    decay = math.exp(-(1 + e) * ref)
    slope = -e - decay + (1 + e) * (1 + ref) * decay
    roundoff = np.finfo(float).eps * (1 + e * ref + (1 + ref) * decay) / abs(slope) / ref
    assert chi == pytest.approx(ref, rel=10 * roundoff)
    assert e * chi < 1.0  # the force never turns tensile: clipping does not spoil exactness


@pytest.mark.parametrize("name", HC_FAMILY)
def test_hunt_crossley_family_is_independent_of_mass_stiffness_speed_and_exponent(name):
    ref = e_eff(name, 0.6)[0]
    for m, K, v, n in ((2.5, 1e7, 3.0, 1.5), (0.01, 5e10, 0.05, 1.5), (1.0, 1.0, 1.0, 1.0)):
        assert e_eff(name, 0.6, m, K, v, n)[0] == pytest.approx(ref, rel=1e-8)


def test_approximate_laws_are_ordered_as_documented():
    """HC and LN are accurate only near e = 1; Flores and Gonthier over the whole range."""
    for name in ("hunt_crossley", "lankarani_nikravesh"):
        errs = [abs(e_eff(name, e)[0] - e) / e for e in RESTITUTIONS]
        assert errs == sorted(errs, reverse=True) and errs[0] > 0.5 and errs[-1] < 0.02
    for name, bound in (("flores", 0.15), ("gonthier", 0.05)):
        errs = [abs(e_eff(name, e)[0] - e) / e for e in RESTITUTIONS]
        assert max(errs) < bound and errs[-1] < 0.03


# ------------------------------------------------------------------------------ Hertz impact
def _johnson(m, v, K):
    dmax = (5.0 * m * v**2 / (4.0 * K)) ** 0.4
    return dmax, K * dmax**1.5, 2.9432 * dmax / v


@pytest.mark.parametrize("m, v, K", [(1.0, 1.0, 1.0), (0.37, 0.4, 4.4e9), (12.0, 3.0, 2e8)])
def test_hertz_impact_closed_form(m, v, K):
    dmax, fmax, tc = rigid_hertz_impact(m, v, K)
    j_dmax, j_fmax, j_tc = _johnson(m, v, K)
    assert dmax == pytest.approx(j_dmax, rel=1e-12)
    assert fmax == pytest.approx(j_fmax, rel=1e-12)
    # 2.9432 is the constant 2.943275 cut to four decimals: up to 1e-4 / 2.9432 = 3.4e-5 (measured 2.55e-5)
    assert tc == pytest.approx(j_tc, rel=5e-5)
    assert tc * v / dmax == pytest.approx(2.0 * math.sqrt(math.pi) * math.gamma(1.4) / math.gamma(0.9), rel=1e-14)
    # against the integrated 1-DOF impact
    v_out, imp, t_c, d_top, f_top = impact(np.array([K, 1.5, 0.0, 0.0]), m, v)
    assert d_top == pytest.approx(dmax, rel=1e-9)
    assert f_top == pytest.approx(fmax, rel=1e-9)
    assert t_c == pytest.approx(tc, rel=1e-9)
    assert v_out == pytest.approx(v, rel=1e-9)
    assert imp == pytest.approx(2.0 * m * v, rel=1e-9)


def test_rigid_impact_on_a_linear_spring_lasts_half_a_period():
    m, K, v = 2.0, 5e5, 0.7
    dmax, fmax, tc = rigid_hertz_impact(m, v, K, n=1.0)
    assert tc == pytest.approx(math.pi * math.sqrt(m / K), rel=1e-13)
    assert dmax == pytest.approx(v * math.sqrt(m / K), rel=1e-13)
    assert fmax == pytest.approx(K * dmax, rel=1e-13)
