"""examples/contact_laws.py: in the rigid limit each law restitutes and peaks as its closed form says."""

from __future__ import annotations

import math

import pytest
from scipy.optimize import brentq

import flexbeam as fb
from tests.examples.loader import load_example

#: chi(e) as published by each law's authors (written out here, not taken from flexbeam)
CHI = {
    "hunt_crossley": lambda e: 1.5 * (1 - e),  # Hunt & Crossley 1975
    "lankarani_nikravesh": lambda e: 0.75 * (1 - e * e),  # Lankarani & Nikravesh 1990
    "flores": lambda e: 8 * (1 - e) / (5 * e),  # Flores et al. 2011
    "gonthier": lambda e: (1 - e * e) / e,  # Gonthier et al. 2004
}


def restitution_of(chi: float) -> float:
    """Exact 1-DOF restitution of F = K d^n (1 + chi d'/d'_0): the root of
    (1 + e) chi = ln[(1 + chi) / (1 - e chi)] in (0, min(1, 1/chi)) (Carvalho & Martins 2019)."""
    f = lambda e: (1 + e) * chi - math.log((1 + chi) / (1 - e * chi))
    return brentq(f, 1e-9, min(1.0, 1.0 / chi) * (1 - 1e-12), xtol=1e-14)


@pytest.fixture(scope="module")
def ex():
    return load_example("contact_laws")


def _effective_mass() -> float:
    """Uniform rod pinned at its end (no hub): J_O = m L^2 / 3, seen at x_P as J_O / x_P^2."""
    case = fb.load_case("seed-experiment")
    b = case.beam
    m = b.density * math.pi * b.radius**2 * b.length
    return m * b.length**2 / 3 / case.contact.position**2


def test_rigid_limit_of_hertz_is_johnsons_closed_form(ex):
    """Johnson (1985) Sec. 11.4; t_c factor 2 sqrt(pi) Gamma(7/5) / Gamma(9/10).  The closed form is for a point
    mass on a line; P moves on an arc of radius x_P and slides over the sphere: corrections of relative order
    delta_max / x_P (1e-4 here) at most, plus the integrator's ~1e-6.  Measured 8.7e-8 (peak) and 3.9e-6
    (duration, the same at fast_rtol 1e-10: geometric)."""
    sol = ex.rigid["hertz"]
    m = sol.metrics()
    K, v = sol.provenance["contact_stiffness"], abs(m["impact_velocity"])
    d_max = (5 * _effective_mass() * v**2 / (4 * K)) ** 0.4
    t_c = 2 * math.sqrt(math.pi) * math.gamma(1.4) / math.gamma(0.9) * d_max / v
    bound = d_max / fb.load_case("seed-experiment").contact.position + 1e-6
    assert m["peak_force"] == pytest.approx(K * d_max**1.5, rel=bound)
    assert m["contact_duration"] == pytest.approx(t_c, rel=bound)
    assert ex.effective_restitution["hertz"] == pytest.approx(1.0, rel=1e-5)  # elastic


@pytest.mark.parametrize("law", [*CHI, "carvalho_martins"])
def test_rigid_limit_restitution_is_the_exact_hunt_crossley_value(law, ex):
    """Measured agreement 8.6e-7 (relative); bound 1e-5 (11.6x)."""
    e = ex.rigid[law].metrics()
    nominal = 0.8
    exact = nominal if law == "carvalho_martins" else restitution_of(CHI[law](nominal))
    assert ex.effective_restitution[law] == pytest.approx(exact, rel=1e-5)
    assert e["contacts"] == 1


def test_flexible_beam_peaks_below_the_rigid_rod(ex):
    """The beam's compliance acts in series with the contact spring and only the beam near P is
    reached during the contact, so every law peaks lower on the flexible beam than on the rigid rod."""
    for law in ex.LAWS:
        assert ex.peak_force[law] < ex.rigid[law].metrics()["peak_force"]
