"""How slender a beam must be for the Euler-Bernoulli model: Timoshenko's correction of the first bending mode.

The modal model is an Euler-Bernoulli beam: it neglects the shear deformation and the rotary inertia of the
sections, and so overestimates the bending frequencies of a thick beam.  Timoshenko's beam (S. P. Timoshenko,
Phil. Mag. 41 (1921) 744-746; the clamped-free frequency equation in S. M. Han, H. Benaroya, T. Wei, J. Sound Vib.
225 (1999) 935-988) keeps both.  Its frequencies depend on two numbers: the slenderness s = r_g / L (r_g = sqrt(I/S)
the radius of gyration of the section; r_g = r/2 for a circle of radius r) and the ratio E / (kappa G) =
2 (1 + nu) / kappa of the bending to the shear stiffness, with Cowper's shear coefficient kappa (G. R. Cowper,
J. Appl. Mech. 33 (1966) 335-340): 6 (1 + nu) / (7 + 6 nu) for a solid circle, 10 (1 + nu) / (12 + 11 nu) for a
rectangle (taken for ``section = "general"``).

The error of the Euler-Bernoulli first frequency of the cantilever, e = omega_EB / omega_T - 1, is

    e = 1/2 I_1 (1 + E / (kappa G)) s^2 + O(s^4),   I_1 = int phi'^2 / int phi^2 = 4.6478  (first clamped-free mode)

(Rayleigh's quotient with the rotary inertia int rho I phi'^2 and the shear energy of the force EI phi''' added;
int phi'''^2 / int phi''^2 = I_1 too), and the exact e, from Timoshenko's frequency equation (:func:`frequency_ratio`),
stays below this leading term.  For a solid circle with nu = 0.3 (E / (kappa G) = 2.933) the exact e reaches 1 % at
r / L = 0.0664 (L / r = 15.1) and 10 % at r / L = 0.217 (L / r = 4.6).  Above the 1 % slenderness a case is
accepted with a :class:`~flexbeam.errors.SlenderBeamWarning`; above the 10 % one it is refused: an Euler-Bernoulli
beam that far from Timoshenko's is no model of the beam (the higher modes, which an impact excites, are off by
much more).
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np

from ..errors import SlenderBeamWarning

#: beta_1 L of the first clamped-free mode: 1 + cos(bL) cosh(bL) = 0
BETA1_L = 1.8751040687119611
#: int phi'^2 dx / int phi^2 dx of the first clamped-free mode on a unit length (Gauss-Legendre quadrature of the
#: mode shape; tests/unit/test_slenderness.py checks it against flexbeam.model.modes)
I1 = 4.647778318678607
#: EB first-frequency errors above which a case is warned about, and refused
WARN_ERROR, REFUSE_ERROR = 0.01, 0.10


def shear_ratio(section: str, poisson_ratio: float) -> float:
    """E / (kappa G) = 2 (1 + nu) / kappa with Cowper's (1966) kappa of a solid circle, or of a rectangle for a
    general section."""
    nu = poisson_ratio
    kappa = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu) if section == "circle" else 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)
    return 2.0 * (1.0 + nu) / kappa


def leading_error(s: float, shear: float) -> float:
    """The leading term 1/2 I_1 (1 + E/(kappa G)) s^2 of the Euler-Bernoulli first-frequency error (an upper
    bound of the exact error)."""
    return 0.5 * I1 * (1.0 + shear) * s * s


def _determinant(w: float, s: float, shear: float) -> float:
    """Timoshenko's clamped-free frequency determinant at the frequency w (units L = EI = rho S = 1, below the
    cut-off w^2 < kappa G S / (rho I)): w = C1 cosh(a x) + C2 sinh(a x) + C3 cos(b x) + C4 sin(b x) with the
    section rotation psi = C1 p sinh + C2 p cosh + C3 r sin - C4 r cos; rows w(0) = 0, psi(0) = 0, psi'(1) = 0
    (no moment) and w'(1) - psi(1) = 0 (no shear force, divided by rho S w^2 / (kappa G S))."""
    kgs, ri = 1.0 / (s * s * shear), s * s
    b, c = kgs * ri * w * w + w * w, w * w * (ri * w * w - kgs)
    disc = math.sqrt(b * b - 4.0 * kgs * c)
    alpha = math.sqrt((-b + disc) / (2.0 * kgs))
    beta = math.sqrt((b + disc) / (2.0 * kgs))
    p = alpha + w * w / (kgs * alpha)
    r = w * w / (kgs * beta) - beta
    ch, sh, co, si = math.cosh(alpha), math.sinh(alpha), math.cos(beta), math.sin(beta)
    m = np.array(
        [
            [1.0, 0.0, 1.0, 0.0],
            [0.0, p, 0.0, -r],
            [p * alpha * ch, p * alpha * sh, r * beta * co, r * beta * si],
            [-sh / alpha, -ch / alpha, -si / beta, co / beta],
        ]
    )
    return float(np.linalg.det(m))


def frequency_ratio(s: float, shear: float) -> float:
    """omega_T / omega_EB of the first clamped-free mode for the slenderness s = r_g / L and E / (kappa G):
    the lowest root of Timoshenko's frequency equation (:func:`_determinant`), bracketed by a scan of (0, omega_EB]
    and refined by Brent's method; NaN if it lies above the cut-off frequency."""
    from scipy.optimize import brentq

    w_eb = BETA1_L**2
    cutoff = 1.0 / (s * s * math.sqrt(shear))
    grid = np.linspace(0.02 * w_eb, min(1.0001 * w_eb, (1.0 - 1e-9) * cutoff), 121)
    values = [_determinant(w, s, shear) for w in grid]
    for a, b, fa, fb in zip(grid[:-1], grid[1:], values[:-1], values[1:]):
        if fa == 0.0:
            return float(a / w_eb)
        if fa * fb < 0.0:
            return float(brentq(_determinant, a, b, args=(s, shear), xtol=1e-15, rtol=1e-14) / w_eb)
    return math.nan


def error(s: float, shear: float) -> float:
    """The Euler-Bernoulli first-frequency error omega_EB / omega_T - 1 (exact, from Timoshenko's equation)."""
    return 1.0 / frequency_ratio(s, shear) - 1.0


@functools.lru_cache(maxsize=64)
def limits(shear: float) -> tuple[float, float]:
    """The slenderness s = r_g / L at which the EB first-frequency error reaches :data:`WARN_ERROR` and
    :data:`REFUSE_ERROR` (roots of :func:`error`; the leading term, an upper bound, brackets them from below)."""
    from scipy.optimize import brentq

    def slenderness_at(target: float) -> float:
        lo = math.sqrt(target / (0.5 * I1 * (1.0 + shear)))
        return float(brentq(lambda s: error(s, shear) - target, lo, 2.0 * lo, xtol=1e-12))

    return slenderness_at(WARN_ERROR), slenderness_at(REFUSE_ERROR)


def check(beam) -> None:
    """Warn (:class:`~flexbeam.errors.SlenderBeamWarning`) about a beam whose Euler-Bernoulli first frequency is
    more than 1 % above Timoshenko's, and raise ValueError (one line naming the field, the ratio and the range)
    when it is more than 10 % above; ``beam`` is a :class:`~flexbeam.parameters.case.Beam`."""
    L, area, second = beam.length, beam.section_area, beam.section_second_moment
    s = math.sqrt(second / area) / L
    shear = shear_ratio(beam.section, beam.poisson_ratio)
    if not leading_error(s, shear) > WARN_ERROR:  # the exact error is below its leading term
        return
    s_warn, s_refuse = limits(round(shear, 12))
    if beam.section == "circle":
        field, name, scale = "beam.radius", "r/L", 2.0
    else:
        field, name, scale = "beam.second_moment", "sqrt(I/S)/L", 1.0
    theory = "Euler-Bernoulli theory (shear and rotary inertia neglected)"
    if s > s_refuse:
        raise ValueError(
            f"{field}: {name} = {scale * s:.4g} is outside the range of {theory}, {name} <= {scale * s_refuse:.3g} "
            f"(first bending frequency within {100 * REFUSE_ERROR:g} % of Timoshenko's); use a more slender beam"
        )
    if s > s_warn:
        warnings.warn(
            f"{field}: {name} = {scale * s:.4g} is above the slender-beam range {name} <= {scale * s_warn:.3g} of "
            f"{theory}: its first bending frequency is {100 * error(s, shear):.2g} % above Timoshenko's (refused "
            f"above {name} = {scale * s_refuse:.3g}, {100 * REFUSE_ERROR:g} %)",
            SlenderBeamWarning,
            stacklevel=2,
        )


__all__ = ["I1", "REFUSE_ERROR", "WARN_ERROR", "check", "error", "frequency_ratio", "leading_error", "limits"]
