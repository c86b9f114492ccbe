"""Continuous contact force laws (CCFM), one small class each.

Every law here has the form (penetration d = -delta >= 0, rate d' = -delta')

    F = max(0,  K d^n (1 + chi d'/d'_0) + C d'),

where d'_0 > 0 is the penetration rate at the onset of the current contact.  The
elastic part F_k = K d^n has the potential K d^(n+1)/(n+1); the rest dissipates,
at the rate (F - F_k) d'.  Each law fixes chi (or C) from the coefficient of
restitution e by its own published formula; at e = 1 all reduce to Hertz.
The force acts on the beam as the generalised force J^T F.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .. import numerics as nm
from ..errors import ParameterError, closest


def law_force(p: np.ndarray, d: float, dd: float) -> tuple[float, float]:
    """Contact force F and its elastic part F_k for parameters p = [K, n, chi/d'_0, C] at penetration d >= 0
    and rate d' (the compiled ``fb_law_force`` the integrators use)."""
    from ..kernels import core

    F, Fk, _, _ = core.law_force(np.ascontiguousarray(p, float), float(d), float(dd))
    return F, Fk


@dataclass(frozen=True)
class ContactLaw:
    """Base class: Hertz-type spring K d^n with hysteresis damping chi(e).

    Parameters
    ----------
    stiffness
        K [N/m^n].
    exponent
        n [-].
    restitution
        Coefficient of restitution e in [0, 1].
    """

    name: ClassVar[str] = ""
    #: the law's damping is infinite at e = 0 (its chi or C diverges), so e must be > 0
    needs_restitution: ClassVar[bool] = False
    stiffness: float
    exponent: float = 1.5
    restitution: float = 1.0

    def chi(self) -> float:
        """Dimensionless hysteresis damping factor chi(e)."""
        return 0.0

    def parameters(self, onset_rate: float, effective_mass: float) -> np.ndarray:
        """Parameter vector [K, n, chi/d'_0, C] for a contact that starts at rate ``onset_rate``.

        ``effective_mass`` = 1/(J M^-1 J^T) at onset; only the linear law needs it.
        A contact that starts at rest (``onset_rate`` <= 1e-9 m/s: resting, not an
        impact) has no reference speed and gets no hysteresis damping.
        """
        if onset_rate <= 1e-9:
            return np.array([self.stiffness, self.exponent, 0.0, 0.0])
        return np.array([self.stiffness, self.exponent, self.chi() / onset_rate, 0.0])

    def force(self, d: float, dd: float, onset_rate: float, effective_mass: float = 1.0) -> float:
        """Contact force [N] at penetration ``d`` [m] and rate ``dd`` [m/s]."""
        return law_force(self.parameters(onset_rate, effective_mass), d, dd)[0]


@dataclass(frozen=True)
class Hertz(ContactLaw):
    """Hertz (1882): F = K d^n, no dissipation (n = 3/2 for point contact)."""

    name: ClassVar[str] = "hertz"


@dataclass(frozen=True)
class HuntCrossley(ContactLaw):
    """Hunt & Crossley (1975), J. Appl. Mech. 42, 440: F = K d^n (1 + 3(1-e)/2 d'/d'_0)."""

    name: ClassVar[str] = "hunt_crossley"

    def chi(self) -> float:
        return 1.5 * (1.0 - self.restitution)


@dataclass(frozen=True)
class LankaraniNikravesh(ContactLaw):
    """Lankarani & Nikravesh (1990), J. Mech. Des. 112, 369: chi = 3(1 - e^2)/4."""

    name: ClassVar[str] = "lankarani_nikravesh"

    def chi(self) -> float:
        return 0.75 * (1.0 - self.restitution * self.restitution)


@dataclass(frozen=True)
class Flores(ContactLaw):
    """Flores, Machado, Silva & Martins (2011), Multibody Syst. Dyn. 25, 357: chi = 8(1-e)/(5e)."""

    name: ClassVar[str] = "flores"
    needs_restitution: ClassVar[bool] = True

    def chi(self) -> float:
        return 8.0 * (1.0 - self.restitution) / (5.0 * self.restitution)


@dataclass(frozen=True)
class Gonthier(ContactLaw):
    """Gonthier, McPhee, Lange & Piedboeuf (2004), Multibody Syst. Dyn. 11, 209: chi = (1-e^2)/e."""

    name: ClassVar[str] = "gonthier"
    needs_restitution: ClassVar[bool] = True

    def chi(self) -> float:
        return (1.0 - self.restitution * self.restitution) / self.restitution


def exact_hunt_crossley_chi(e: float) -> float:
    """chi giving exactly restitution e for F = K d^n (1 + chi d'/d'_0) in 1-DOF.

    From m v dv/dd = -K d^n (1 + chi v/v0) integrated over a whole contact
    (d from 0 back to 0, v from v0 to -e v0) the n-, K- and m-independent relation

        (1 - e chi) = (1 + chi) exp(-(1 + e) chi)

    follows (Carvalho & Martins 2019, Mech. Mach. Theory); its non-zero root in
    (0, 1/e) is found with :func:`scipy.optimize.brentq`.
    """
    if e >= 1.0:
        return 0.0
    if e <= 0.0:
        raise ParameterError("contact.restitution: must be > 0 for carvalho_martins")

    def f(chi: float) -> float:
        return nm.log1p(-e * chi) - nm.log1p(chi) + (1.0 + e) * chi

    # f(0) = f'(0) = 0, f'' > 0 and f' = 0 again only at chi* = (1 - e)/e, so f > 0 on
    # (0, root) and the root lies in [chi*, 1/e).  For small e it sits within round-off
    # of 1/e (1 - e chi = O(exp(-1/e))), which is then returned.
    chi_star = (1.0 - e) / e
    hi = (1.0 - 1e-15) / e
    if f(hi) >= 0.0:
        return hi
    from scipy.optimize import brentq

    return float(brentq(f, chi_star, hi, xtol=1e-15, rtol=1e-14))


@dataclass(frozen=True)
class CarvalhoMartins(ContactLaw):
    """Carvalho & Martins (2019): Hunt-Crossley form with chi from the exact 1-DOF restitution."""

    name: ClassVar[str] = "carvalho_martins"
    needs_restitution: ClassVar[bool] = True

    def chi(self) -> float:
        return exact_hunt_crossley_chi(self.restitution)


@dataclass(frozen=True)
class KelvinVoigt(ContactLaw):
    """Linear Kelvin-Voigt: F = max(0, k d + C d'), the exponent is 1.

    C = 2 zeta sqrt(k m_eff) with zeta = -ln e / sqrt(pi^2 + ln^2 e): exact restitution
    of a linear oscillator of mass m_eff (ignoring the tensile force that clipping removes).
    """

    name: ClassVar[str] = "kelvin_voigt"
    needs_restitution: ClassVar[bool] = True

    def parameters(self, onset_rate: float, effective_mass: float) -> np.ndarray:
        le = nm.log(self.restitution)
        zeta = -le / math.sqrt(math.pi * math.pi + le * le)
        damping = 2.0 * zeta * math.sqrt(self.stiffness * effective_mass)
        return np.array([self.stiffness, 1.0, 0.0, damping])


#: the contact laws by name: the one registry the case schema, the CLI and the documentation read
LAWS: dict[str, type[ContactLaw]] = {
    cls.name: cls for cls in (Hertz, KelvinVoigt, HuntCrossley, LankaraniNikravesh, Flores, Gonthier, CarvalhoMartins)
}
LAW_NAMES = tuple(LAWS)
#: laws whose damping is infinite at e = 0
NEEDS_RESTITUTION = tuple(name for name, cls in LAWS.items() if cls.needs_restitution)


def make_law(name: str, stiffness: float, exponent: float, restitution: float) -> ContactLaw:
    """Contact law by snake_case name."""
    try:
        cls = LAWS[name]
    except KeyError:
        raise ParameterError(
            f"contact.law: unknown law '{name}'; allowed: {', '.join(LAWS)}{closest(name, LAWS)}"
        ) from None
    return cls(stiffness=stiffness, exponent=exponent, restitution=restitution)


def law_potential(p: np.ndarray, d: float) -> float:
    """Elastic contact potential U_c = K d^(n+1)/(n+1) [J] of parameters p at penetration d."""
    if d <= 0.0:
        return 0.0
    return p[0] * nm.pow(d, p[1] + 1.0) / (p[1] + 1.0)


def threlfall(mu: float, v0: float, vt):
    """Threlfall's regularised friction coefficient -mu_k (1 - exp(-3 abs(v_t) / v_0)) sign(v_t) (Threlfall,
    Mechanism and Machine Theory 13 (1978) 475-483): 95 % of mu_k at abs(v_t) = v_0, linear below."""
    vt = np.asarray(vt, float)
    return mu * np.expm1(-3.0 * np.abs(vt) / v0) * np.sign(vt)
