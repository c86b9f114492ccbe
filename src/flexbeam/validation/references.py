"""Independent references of the validation report: closed forms, series and published values.

None of these shares code with flexbeam's model:

* :func:`reference_flapwise`: bending frequencies of a rotating uniform cantilever by a
  Frobenius power series of the exact ODE (the method of Wright et al. 1982), written
  independently of flexbeam's assumed-mode code (:func:`series_tip`,
  :func:`frequency_determinant`), and :func:`published_rotating_values` to check it;
* :func:`kane_hub_rates` (the Kane, Ryan & Banerjee 1987 spin-up profile) and
  :func:`quasi_static_tip`: quasi-static tip deflection of the spinning cantilever under
  the hub acceleration, by :func:`scipy.integrate.solve_bvp`;
* :func:`hunt_crossley_restitution`: the exact 1-DOF restitution of the Hunt-Crossley
  force form for a given chi (Carvalho & Martins 2019), :func:`kelvin_voigt_restitution`
  of the clipped linear spring-dashpot, and :func:`law_restitution` for each law;
* :func:`two_mass_chain`: a rigid body hitting a mass on a spring through a linear contact
  spring, by the normal modes of the two-mass chain.
"""

from __future__ import annotations

import functools
import math
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_bvp
from scipy.optimize import brentq

#: published rotating-cantilever values (in the source tree; absent from an installed wheel)
ROTATING_DATA = Path(__file__).resolve().parents[3] / "tests" / "validation" / "data" / "rotating_cantilever.toml"

#: beta_k L of the clamped-free beam to nine significant figures (tabulated e.g. by
#: R. D. Blevins, Formulas for Natural Frequency and Mode Shape, 1979, Table 8-1)
PUBLISHED_ROOTS = (1.87510407, 4.69409113, 7.85475744, 10.99554073, 14.13716839)

#: exact Hertz impact-duration constant 2 sqrt(pi) Gamma(7/5) / Gamma(9/10)
HERTZ_DURATION_CONSTANT = 2.0 * math.sqrt(math.pi) * math.gamma(1.4) / math.gamma(0.9)


def series_tip(lam: np.ndarray, gamma: float, delta: float, nterms: int = 160) -> np.ndarray:
    """w''(1), w'''(1) of the two clamped-root solutions of the rotating beam, for each lam.

    Dimensionless (L = 1, xi in [0, 1], lam = omega_bar^2), flapwise:
    w'''' = (tau w')' + lam w with tau = gamma^2 [delta (1 - xi) + (1 - xi^2)/2], i.e.
    w'''' = gamma^2 [(delta + 1/2 - delta xi - xi^2/2) w'' - (delta + xi) w'] + lam w.
    With w = sum a_k xi^k, a_0 = a_1 = 0 and (a_2, a_3) = (1, 0) or (0, 1):
    (n+1)(n+2)(n+3)(n+4) a_{n+4} = gamma^2 [(delta + 1/2)(n+1)(n+2) a_{n+2}
        - delta (n+1)^2 a_{n+1} - n(n+1)/2 a_n] + lam a_n.
    Returns an array (len(lam), 2, 2): [.., row (w'', w'''), column (basis)].
    """
    lam = np.atleast_1d(np.asarray(lam, float))
    g2, c0 = gamma * gamma, delta + 0.5
    k = np.arange(nterms + 4)[:, None]
    out = np.empty((lam.size, 2, 2))
    for j, basis in enumerate(((1.0, 0.0), (0.0, 1.0))):
        a = np.zeros((nterms + 4, lam.size))
        a[2], a[3] = basis
        for n in range(nterms):
            rhs = (
                g2 * (c0 * (n + 1) * (n + 2) * a[n + 2] - delta * (n + 1) ** 2 * a[n + 1] - 0.5 * n * (n + 1) * a[n])
                + lam * a[n]
            )
            a[n + 4] = rhs / ((n + 1) * (n + 2) * (n + 3) * (n + 4))
        out[:, 0, j] = np.sum(k * (k - 1) * a, axis=0)
        out[:, 1, j] = np.sum(k * (k - 1) * (k - 2) * a, axis=0)
    return out


def frequency_determinant(wbar, gamma: float, delta: float) -> np.ndarray:
    """Determinant of the free-end conditions w''(1) = w'''(1) = 0 at omega_bar = ``wbar``."""
    m = series_tip(np.asarray(wbar, float) ** 2, gamma, delta)
    return m[:, 0, 0] * m[:, 1, 1] - m[:, 0, 1] * m[:, 1, 0]


@functools.cache
def reference_flapwise(gamma: float, delta: float, nmodes: int = 3) -> tuple[float, ...]:
    """First ``nmodes`` dimensionless flapwise frequencies omega T of the rotating cantilever.

    T = sqrt(rho A L^4 / EI), gamma = Omega T, delta = r_h / L.  The chordwise (in-plane)
    frequencies of the inextensible beam follow as sqrt(omega_flap^2 - gamma^2).
    """
    grid = np.arange(0.5, 120.0, 0.25)
    d = frequency_determinant(grid, gamma, delta)
    brackets = np.nonzero(np.sign(d[:-1]) != np.sign(d[1:]))[0][:nmodes]
    if brackets.size != nmodes:
        raise RuntimeError("power series: not enough roots bracketed")
    f = lambda w: float(frequency_determinant(w, gamma, delta)[0])  # noqa: E731
    return tuple(brentq(f, grid[i], grid[i + 1], xtol=1e-13, rtol=1e-13) for i in brackets)


def published_rotating_values() -> list[dict[str, Any]]:
    """Published flapwise values (``tests/validation/data/rotating_cantilever.toml``); [] if absent."""
    if not ROTATING_DATA.is_file():
        return []
    return list(tomllib.loads(ROTATING_DATA.read_text("utf-8"))["flapwise"])


def kane_hub_rates(t: float, W: float, Ts: float) -> tuple[float, float]:
    """(theta', theta'') of the Kane, Ryan & Banerjee (1987) spin-up profile."""
    if t < Ts:
        a = 2.0 * math.pi / Ts
        return (W / Ts) * (t - math.sin(a * t) / a), (W / Ts) * (1.0 - math.cos(a * t))
    return W, 0.0


def quasi_static_tip(mu: float, EI: float, L: float, rate: float, accel: float, hub_radius: float = 0.0) -> float:
    """Static in-plane tip deflection [m] of a cantilever spinning at ``rate`` under ``accel``.

    EI w'''' - (N w')' - mu rate^2 w = -mu accel (r_h + x), N the centrifugal tension;
    dimensionless (xi = x/L, u = w/L, T^2 = mu L^4/EI, g2 = rate^2 T^2, d = r_h/L):
    u'''' = (tau u')' + g2 u - accel T^2 (d + xi), tau = g2 [d (1 - xi) + (1 - xi^2)/2],
    u(0) = u'(0) = 0, u''(1) = u'''(1) = 0 (solve_bvp).
    """
    T2 = mu * L**4 / EI
    g2, d, f = rate * rate * T2, hub_radius / L, -accel * T2

    def fun(x, y):
        tau = g2 * (d * (1 - x) + 0.5 * (1 - x * x))
        dtau = -g2 * (d + x)
        return np.vstack((y[1], y[2], y[3], dtau * y[1] + tau * y[2] + g2 * y[0] + f * (d + x)))

    def bc(ya, yb):
        return np.array([ya[0], ya[1], yb[2], yb[3]])

    x = np.linspace(0.0, 1.0, 41)
    sol = solve_bvp(fun, bc, x, np.zeros((4, x.size)), tol=1e-8, max_nodes=100_000)
    if not sol.success:
        raise RuntimeError(f"quasi-static spin-up deflection: {sol.message}")
    return L * float(sol.sol(1.0)[0])


def hunt_crossley_restitution(chi: float) -> float:
    """Exact 1-DOF restitution of F = K d^n (1 + chi d'/d'_0): the root e of
    (1 + e) chi = ln[(1 + chi)/(1 - e chi)] (Carvalho & Martins 2019), from m v dv/dd = -F
    integrated over a whole contact; independent of m, K, n and the impact speed."""
    if chi == 0.0:
        return 1.0
    f = lambda e: (1.0 + e) * chi - math.log1p(chi) + math.log1p(-e * chi)  # noqa: E731
    hi = min(1.0, (1.0 - 1e-15) / chi)
    if f(hi) > 0.0:  # chi >~ 35 (e <~ 0.05): 1 - e chi = (1 + chi) exp(-(1 + e) chi) is below round-off
        return hi
    return brentq(f, 1e-12, hi, xtol=1e-15, rtol=1e-15)


def kelvin_voigt_restitution(e: float) -> float:
    """Restitution of the spring-dashpot with zeta(e) of the linear oscillator, force clipped at 0.

    d = (v/w_d) exp(-s t) sin(w_d t) (w_n = 1, s = zeta); the force -m d'' first vanishes at
    w_d t* = pi - atan2(2 s w_d, w_d^2 - s^2), where the mass separates with -d'(t*)
    (the effect described by Schwager & Poeschel, Granular Matter 9, 2007).
    """
    le = math.log(e)
    zeta = -le / math.sqrt(math.pi**2 + le**2)
    s, wd = zeta, math.sqrt(1.0 - zeta**2)
    phi = math.pi - math.atan2(2.0 * s * wd, wd * wd - s * s)
    return -math.exp(-s * phi / wd) * (math.cos(phi) - (s / wd) * math.sin(phi))


def law_restitution(name: str, e: float) -> float:
    """Exact 1-DOF restitution of flexbeam's law ``name`` set up for nominal ``e``."""
    from ..contact.laws import make_law

    if name == "hertz":
        return 1.0
    if name == "kelvin_voigt":
        return kelvin_voigt_restitution(e)
    return hunt_crossley_restitution(make_law(name, 1.0, 1.5, e).chi())


def two_mass_chain(m1: float, m2: float, kc: float, ks: float, v0: float) -> tuple[float, float, float, float]:
    """Body m1 (speed v0 < 0) hitting m2 on a spring ks to ground through a linear contact spring kc.

    While in contact the chain m1 -- kc -- m2 -- ks -- ground is linear and is solved by its
    normal modes (:func:`scipy.linalg.eigh` of K, M); after separation m2 rings freely at
    sqrt(ks/m2).  Returns (peak contact force [N], contact duration [s], peak sensor force
    -ks x2 [N], sensor pulse duration [s], ending at the first zero of x2).
    """
    from scipy.linalg import eigh
    from scipy.optimize import brentq

    M = np.diag([m1, m2])
    K = np.array([[kc, -kc], [-kc, kc + ks]])
    w2, Phi = eigh(K, M)  # mass-normalised modes
    w = np.sqrt(w2)
    a = Phi.T @ M @ np.array([v0, 0.0]) / w

    def x(t: float) -> np.ndarray:
        return Phi @ (a * np.sin(w * t))

    def force(t: float) -> float:  # compression of the contact spring
        xt = x(t)
        return kc * (xt[1] - xt[0])

    grid = np.linspace(1e-9, 2 * math.pi / w.min(), 20001)
    f = np.array([force(t) for t in grid])
    k = int(np.argmax(f < 0))
    t_c = brentq(force, grid[k - 1], grid[k], xtol=1e-15)
    F_max = max(force(t) for t in np.linspace(0.0, t_c, 20001))
    x2c = Phi[1] @ (a * np.sin(w * t_c))
    v2c = Phi[1] @ (a * w * np.cos(w * t_c))
    ws = math.sqrt(ks / m2)

    def x2(t: float) -> float:
        if t <= t_c:
            return float(x(t)[1])
        return x2c * math.cos(ws * (t - t_c)) + v2c / ws * math.sin(ws * (t - t_c))

    grid = np.linspace(1e-9, t_c + 2 * math.pi / ws, 40001)
    vals = np.array([x2(t) for t in grid])
    k = int(np.argmax(vals > 0))
    t_s = brentq(x2, grid[k - 1], grid[k], xtol=1e-15)
    return F_max, t_c, -ks * float(vals[:k].min()), t_s
