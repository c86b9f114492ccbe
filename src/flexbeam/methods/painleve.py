"""Painlevé's paradox in a held contact's sustained sliding (CCM, IMM at rest), resolved by a tangential impact.

While a held pair slips (Coulomb friction under CCM or in IMM's resting contact,
:mod:`flexbeam.methods.held_friction`) its constraint force acts along
(J_n + sigma J_t)^T with sigma = -mu_k sign(v_t) (under Threlfall's regularised law sigma(v_t), the law's coefficient
at the slip speed of the moment), so the normal multiplier solves a lambda_n = -(free normal acceleration), with the
slip's effective inverse mass

    a = W_nn + sigma W_nt,        W = [J_t; J_n] M^-1 [J_t; J_n]^T.

For a <= 0 the acceleration-level contact problem has no solution or several (Painlevé 1895; Génot & Brogliato,
Eur. J. Mech. A/Solids 18 (1999) 653-677: the rigid rod sliding on its end, a = (1 + 3 cos^2 th - 3 mu s sin th
cos th) / m).  A slip reaching a -> 0 arrives there with lambda_n = -(free normal acceleration) / a either unbounded
(a dynamic jam: friction's impulse stops the slip) or finite at Génot & Brogliato's singular point, where the free
normal acceleration vanishes too; either way the collocation's multiplier system turns singular, so the slip is
resolved where a falls to :data:`SHARE` W_nn (a located event, ``kernels/src/friction.c``), and at a slip phase's
start with a <= SHARE W_nn.

**Resolution** (as methods/friction.py resolves a jam inside an impact): a *tangential impact* (impact without
collision) -- the tangential impulse P_t = -v_t / W_tt along J_t stops the slip at once, as if mu were unbounded
for that instant; if that leaves the point approaching the obstacle (v_n < 0, by W_nt P_t) the impulse
P = -W^-1 v brings both velocities to zero instead (an e = 0 impact of the stuck point).  The kinetic energy falls by
1/2 v_t^2 / W_tt, or by 1/2 v^T W^-1 v, both >= 0 (booked as dissipation): the resolution never adds energy.  The
pair then sticks or slips per mu_s (:func:`flexbeam.methods.coulomb.onset_row`; a reversed slip has
a = W_nn - sigma W_nt > 0), or leaves the obstacle if it moves off it or its multiplier would pull
(:meth:`flexbeam.methods.held_friction.HeldFriction.leaving`); a :class:`~flexbeam.errors.FlexbeamWarning` names
Painlevé, the time and the pair.  IMM's resting contact slips the same way (the same code).

**Neither stick nor slip.**  A slip that starts from a stick whose multiplier has left the cone has v_t ~ 0: its
tangential impact stops nothing, and the pair may stick again where the stick still cannot hold -- neither sticking
nor the slip the load drives (a <= SHARE W_nn) is consistent.  Where the pair's free normal acceleration delta''
(under the other pairs' forces) separates it, Painlevé's indeterminate case, the rigid problem admits both that
slip and lift-off, and a compliant contact resolves it by an impact without collision or by lift-off (Hogan &
Kristiansen, Proc. R. Soc. A 473 (2017) 20160773, who give the criterion between them; Champneys & Várkonyi,
IMA J. Appl. Math. 81 (2016) 538, a review): flexbeam lifts the pair off, the solution that needs no contact force
(no impulse, no change of energy), with a second warning, without evaluating that criterion.  Where delta'' presses
the pair in, no contact force is consistent (the inconsistent case) and the run stops with a message naming
Painlevé (:meth:`~flexbeam.methods.held_friction.HeldFriction.lifted`).
"""

from __future__ import annotations

import warnings

import numpy as np

from .. import numerics as nm
from ..errors import FlexbeamWarning
from ..model.delassus import inverse_mass
from ..model.system import BeamSystem
from .impulse import _apply

#: the slip's a is resolved where it falls to this share of W_nn (the kernel's PAINLEVE_SHARE, friction.c): the
#: collocation's multiplier system turns singular as a -> 0 (its step size underflows at a ~ 1e-5 W_nn on the rod of
#: tests/validation/test_friction_ccm.py)
SHARE = 1e-3


def slip_inverse_mass(system: BeamSystem, t: float, y: np.ndarray, pair: int, sigma: float) -> tuple[float, float]:
    """(a, W_nn) of a held pair slipping with the tangential force sigma lambda_n, a = W_nn + sigma W_nt [1/kg]."""
    W = inverse_mass(system, t, y, [pair])  # [[W_tt, W_tn], [W_nt, W_nn]]
    return float(W[1, 1] + sigma * W[1, 0]), float(W[1, 1])


def _stop_slip(W: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The impulse (P_t, P_n) of the tangential impact: P_t = -v_t / W_tt; both velocities to zero if that leaves
    v_n < 0."""
    Pt = -v[0] / W[0, 0]
    if v[1] + W[1, 0] * Pt >= 0.0:
        return np.array([Pt, 0.0])
    return -nm.solve(W, np.ascontiguousarray(v))


def tangential_impact(system: BeamSystem, t: float, y: np.ndarray, pair: int) -> tuple[np.ndarray, float, float]:
    """The state after the tangential impact of ``pair`` at (t, y) (module docstring), its impulses (P_t, P_n) [N s];
    the energy the impulses remove goes to the dissipated-energy integral."""
    _, rate, vt, Jn, Jt = system.tangent(t, y, pair)
    zd = system.velocities(t, y)
    J = np.vstack((Jt, Jn))
    v = np.array([vt, rate])
    drift = v - nm.matmul(J, zd)
    y_plus, P, _, _, _ = _apply(system, t, y, J, zd, v, drift, _stop_slip)
    return y_plus, float(P[0]), float(P[1])


def warn(t: float, pair: int, a: float) -> None:
    """The FlexbeamWarning that names Painlevé's paradox at (t, pair)."""
    warnings.warn(
        f"contact.friction: Painlevé's paradox at t = {t:.9g} s, pair {pair}: the slip's effective inverse mass "
        f"W_nn - mu_k s W_nt = {a:.3g} 1/kg reached zero (no or several contact forces beyond); resolved by a "
        "tangential impact stopping the slip",
        FlexbeamWarning,
        stacklevel=4,
    )


def warn_lift(t: float, pair: int, bn: float) -> None:
    """The FlexbeamWarning of a pair that leaves its obstacle after its tangential impact: it can neither stick nor
    slip, and its free normal acceleration ``bn`` [m/s^2] separates it (Painlevé's indeterminate case)."""
    warnings.warn(
        f"contact.friction: Painlevé's paradox at t = {t:.9g} s, pair {pair}: after the tangential impact the pair "
        f"can neither stick nor slip; its free normal acceleration {bn:.3g} m/s^2 lifts it off the obstacle",
        FlexbeamWarning,
        stacklevel=4,
    )


def inconsistent(t: float, pair: int, a: float, bn: float) -> str:
    """The message of a run stopped where no contact force of ``pair`` is consistent (Painlevé's inconsistent case:
    no stick, the slip's a <= 0, the free normal acceleration ``bn`` <= 0 pressing it in)."""
    return (
        f"contact.friction: Painlevé's paradox at t = {t:.9g} s, pair {pair}: no contact force is consistent there "
        f"(the stick cannot hold, the slip's W_nn - mu_k s W_nt = {a:.3g} 1/kg, the free normal acceleration "
        f"{bn:.3g} m/s^2 presses it in); a smaller contact.friction, or CCFM (a compliant contact, which has no such "
        "paradox), may carry the run on"
    )
