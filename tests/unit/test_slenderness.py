"""The slender-beam check (``flexbeam.parameters.slenderness``): Timoshenko's first clamped-free frequency.

Independent truth: a Rayleigh-Ritz solution of the Timoshenko cantilever (energies 1/2 int EI psi'^2 + 1/2 int
kappa G S (w' - psi)^2 and 1/2 int rho S w'^2 + 1/2 int rho I psi'^2, w and psi each on 12 shifted Legendre
polynomials vanishing at the clamp), which shares nothing with the frequency equation of the module; and, for
s -> 0, Rayleigh's leading term with the integral I_1 from flexbeam's own mode shapes.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.linalg import eigh

import flexbeam as fb
from flexbeam.errors import ParameterError, SlenderBeamWarning
from flexbeam.model.modes import mode_shapes
from flexbeam.parameters import slenderness as sl

CIRCLE_03 = sl.shear_ratio("circle", 0.3)  # E / (kappa G) = (7 + 6 nu) / 3 = 2.933


def ritz_ratio(s: float, shear: float, terms: int = 12) -> float:
    """omega_T / omega_EB of the first clamped-free mode by Rayleigh-Ritz (L = EI = rho S = 1)."""
    x, wq = np.polynomial.legendre.leggauss(64)
    x, wq = 0.5 * (x + 1.0), 0.5 * wq
    basis = [np.polynomial.Legendre.basis(k, domain=[0.0, 1.0]) for k in range(1, terms + 1)]
    P = np.array([b(x) - b(0.0) for b in basis]).T
    D = np.array([b.deriv()(x) for b in basis]).T
    Z = np.zeros_like(P)
    W, Wd, Psi, Psid = np.hstack([P, Z]), np.hstack([D, Z]), np.hstack([Z, P]), np.hstack([Z, D])
    kgs = 1.0 / (s * s * shear)

    def gram(A, B):
        return (A * wq[:, None]).T @ B

    K = gram(Psid, Psid) + kgs * gram(Wd - Psi, Wd - Psi)
    M = gram(W, W) + s * s * gram(Psi, Psi)
    return math.sqrt(eigh(K, M, eigvals_only=True)[0]) / sl.BETA1_L**2


def test_rayleigh_integral_from_the_mode_shapes():
    """I_1 = int phi'^2 / int phi^2 = int phi'''^2 / int phi''^2 of flexbeam's first cantilever mode (Gauss-Legendre,
    64 points: exact to round-off, measured 9e-15 relative; bound 1e-12)."""
    shape = mode_shapes(1, 1.0)
    x, w = np.polynomial.legendre.leggauss(64)
    x, w = 0.5 * (x + 1.0), 0.5 * w
    d = [shape(x, k)[:, 0] for k in range(4)]
    assert np.sum(w * d[1] ** 2) / np.sum(w * d[0] ** 2) == pytest.approx(sl.I1, rel=1e-12)
    assert np.sum(w * d[3] ** 2) / np.sum(w * d[2] ** 2) == pytest.approx(sl.I1, rel=1e-12)


@pytest.mark.parametrize("s", [0.02, 0.05, 0.1, 0.2])
@pytest.mark.parametrize("shear", [CIRCLE_03, sl.shear_ratio("general", 0.3), sl.shear_ratio("circle", -0.5)])
def test_frequency_equation_against_rayleigh_ritz(s, shear):
    """The frequency equation's root against the Ritz bound with 12 + 12 functions (converged: measured within
    5e-12 relative for these s and shear ratios; bound 1e-9)."""
    assert sl.frequency_ratio(s, shear) == pytest.approx(ritz_ratio(s, shear), rel=1e-9)


def test_slender_limit_is_rayleighs_leading_term():
    """For s = 1e-3 the exact error is the leading term 1/2 I_1 (1 + E/(kappa G)) s^2 = 9.14e-6 up to its O(s^4)
    correction (measured 7e-6 relative; bound 1e-4)."""
    assert sl.error(1e-3, CIRCLE_03) == pytest.approx(sl.leading_error(1e-3, CIRCLE_03), rel=1e-4)


@pytest.mark.parametrize("section", ["circle", "general"])
@pytest.mark.parametrize("nu", [-0.9, 0.0, 0.3, 0.49])
def test_leading_term_bounds_the_exact_error_so_slender_beams_need_no_root(section, nu):
    """The check skips the root-finding when the leading term is below 1 %: it must bound the exact error from
    above over the whole range of s the check meets below the refusal (0.005 - 0.15)."""
    shear = sl.shear_ratio(section, nu)
    for s in np.geomspace(0.005, 0.15, 12):
        assert sl.error(s, shear) <= sl.leading_error(s, shear)


def test_thresholds_are_where_ritz_gives_1_and_10_percent():
    """The 1 % and 10 % slenderness of a solid circle with nu = 0.3 (r/L = 2 s: 0.066 and 0.217), checked with
    the Ritz frequencies (measured 2e-13 from 1 % and 10 %; bound 1e-8)."""
    s1, s10 = sl.limits(CIRCLE_03)
    assert 1.0 / ritz_ratio(s1, CIRCLE_03) - 1.0 == pytest.approx(0.01, abs=1e-8)
    assert 1.0 / ritz_ratio(s10, CIRCLE_03) - 1.0 == pytest.approx(0.10, abs=1e-8)
    assert (2 * s1, 2 * s10) == pytest.approx((0.0664, 0.2173), abs=1e-4)  # docs/usage.md quotes these


@pytest.mark.parametrize("name", list(fb.parameters.builtin_cases()))
def test_presets_are_below_the_warning(name):
    """Every built-in case is well inside Euler-Bernoulli theory (leading error, an upper bound: 0.098 % for the
    seed beam, 0.005 % for Kane's; bound 0.2 %) and loads without a warning (pytest turns warnings into errors)."""
    beam = fb.load_case(name).beam
    s = math.sqrt(beam.section_second_moment / beam.section_area) / beam.length
    # rod-end: SDNV100's stocky rod (L/a = 10, 0.79 %) strikes along its axis, which does not excite its bending
    bound = 0.01 if name == "rod-end" else 0.002
    assert sl.leading_error(s, sl.shear_ratio(beam.section, beam.poisson_ratio)) < bound


def test_a_thick_beam_is_warned_about_and_a_very_thick_one_refused():
    """r = 0.05 m on the 0.7 m beam (r/L = 0.071, exact error 1.2 %): a SlenderBeamWarning naming the ratio and
    the range; r = 0.5 m (r/L = 0.71, the issue's case): refused, one line naming beam.radius and the range."""
    with pytest.warns(SlenderBeamWarning, match=r"^beam\.radius: r/L = 0\.07143 .* r/L <= 0\.0664 .* 1\.2 %"):
        fb.load_case("seed-experiment", {"beam.radius": 0.05})
    with pytest.raises(ParameterError, match=r"^beam\.radius: r/L = 0\.7143 is outside .* r/L <= 0\.217 "):
        fb.load_case("seed-experiment", {"beam.radius": 0.5})


def test_a_general_section_is_judged_by_its_radius_of_gyration():
    """sqrt(I/S)/L = 0.2 with a rectangle's shear coefficient: refused, naming beam.second_moment; the same beam
    at 0.01 passes silently."""
    base = {"beam.section": "general", "beam.radius": None, "beam.area": 1e-3, "beam.half_depth": 0.01}
    L = 0.7
    with pytest.raises(ParameterError, match=r"^beam\.second_moment: sqrt\(I/S\)/L = 0\.2 is outside"):
        fb.load_case("seed-experiment", {**base, "beam.second_moment": 1e-3 * (0.2 * L) ** 2})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fb.load_case("seed-experiment", {**base, "beam.second_moment": 1e-3 * (0.01 * L) ** 2})
