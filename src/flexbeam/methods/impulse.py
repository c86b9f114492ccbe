"""Impulse-momentum map of an instantaneous impact, at one contact pair or several at once (IMM; Khulief &
Shabana 1987; several contacts: Pfeiffer & Glocker 1996, Ch. 7).

With generalised mass M, the impacting pairs' Jacobians J (rows; delta' = J z'), their restitution e_i and the
Delassus matrix W = J M^-1 J^T, the impulses P solve the linear complementarity problem

    v+ = v- + W P,    P >= 0,    v+_i + e_i v-_i >= 0,    P_i (v+_i + e_i v-_i) = 0,

and z'^+ = z'^- + M^-1 J^T P; the coordinates do not change (v: the normal velocities relative to the obstacles,
J z' plus an obstacle's own n . v_O on a moving base).  For one pair this is P = -(1 + e) v- / W, so that v+ = -e v-,
and the impulse does the work W_c = -(1 - e^2) (v-)^2 / (2 W) <= 0.  For several pairs with one common
e the impulses are (1 + e) times those of the plastic (e = 0) problem, whose map is a projection in the kinetic
metric, so the energy never increases (Glocker's energetic consistency); with different e_i it can (a known limit
of Newton's law at simultaneous impacts).  A pair that the solution leaves with v+_i > -e_i v-_i separates
without impulse.  The LCP is solved by enumerating the active sets (at most 8 pairs).  When theta(t) is
prescribed only the modal velocities jump (M and J restricted to the modal block) and the joint's impulsive torque
does the rest of the kinetic-energy change.
One frictionless pair's map -- IMM's every impact and CCM's every onset on a single stop -- runs compiled
(``kernels/src/impulse_map.c``): the same operations in the same order, the same bits, a fifth of the time.

With Coulomb friction (:func:`frictional_jump`) one pair follows Stronge's process
(:mod:`flexbeam.methods.friction`); several pairs at once obey Newton's law with the same e on their normal and
tangential rows (:mod:`flexbeam.methods.frictional_lcp`), whose impulses' work P . xi / (1 + e) -
(1 - e) P . W P / (2 (1 + e)) is never positive; with different e_i, should it be, the smallest e_i is applied to all.
"""

from __future__ import annotations

import itertools
import warnings
from dataclasses import dataclass

import numpy as np

from .. import numerics as nm
from ..errors import FlexbeamWarning
from ..model.system import BeamSystem
from .friction import frictional_impulse
from .frictional_lcp import impulse_work, solve_frictional_impact


@dataclass(frozen=True)
class Jump:
    """Result of an impulse-momentum step (arrays over the pairs given)."""

    y: np.ndarray  # state after the jump (bookkeeping integrals updated)
    impulses: np.ndarray  # P_i [N s]
    velocities_before: np.ndarray  # J z'^- [m/s]
    velocities_after: np.ndarray  # J z'^+ [m/s]
    kinetic_before: float  # [J]
    kinetic_after: float  # [J]
    tangential: np.ndarray | None = None  # the frictional impulses along each pair's tangent [N s] (None: none)

    @property
    def impulse(self) -> float:
        """The first pair's impulse [N s] (the only one for a single pair)."""
        return float(self.impulses[0])

    @property
    def velocity_before(self) -> float:
        return float(self.velocities_before[0])

    @property
    def velocity_after(self) -> float:
        return float(self.velocities_after[0])


def solve_impact_lcp(W: np.ndarray, v_minus: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Impulses P >= 0 with v+ = v- + W P, v+ + e v- >= 0 and P (v+ + e v-) = 0 (see the module docstring).

    Every active set A (P_A > 0 solving W_AA P_A = -(1 + e_A) v-_A) is tried; of the consistent ones the impulse
    of least norm is returned: for a positive definite W the solution is unique, and when W is singular (more
    contacts than the motion can tell apart, e.g. two stops on a rigid rod) the post-impact velocities still are,
    while the impulses are split as the Moore-Penrose (least-norm) solution does -- equally between identical
    pairs.
    """
    s = v_minus.size
    target = -(1.0 + e) * v_minus  # W P must reach this on the active set
    if s == 1:  # one pair: P = -(1 + e) v- / W when it approaches
        return np.array([target[0] / W[0, 0] if target[0] > 0.0 and W[0, 0] > 0.0 else 0.0])
    scale = max(float(np.max(np.abs(target), initial=0.0)), 1e-300)
    tol = 1e-10 * scale
    best: np.ndarray | None = None
    for size in range(s + 1):
        for active in itertools.combinations(range(s), size):
            idx = list(active)
            P = np.zeros(s)
            if idx:
                Waa = W[np.ix_(idx, idx)]
                P[idx] = nm.lstsq_symmetric(Waa, target[idx], rcond=1e-12)
                if np.any(P[idx] < -tol / max(float(np.max(np.abs(Waa))), 1e-300)):
                    continue
                P[idx] = np.maximum(P[idx], 0.0)
            slack = nm.matmul(W, P) - target  # = v+ + e v-
            if np.any(slack < -tol) or (idx and np.any(np.abs(slack[idx]) > tol)):
                continue
            if best is None or nm.dot(P, P) < nm.dot(best, best) - 1e-30:
                best = P
    if best is None:
        raise ValueError("no solution of the impact LCP (W not positive semi-definite?)")
    return best


def obstacle_drift(system: BeamSystem, pairs, gaps, v_beam: np.ndarray) -> np.ndarray:
    """Each pair's normal velocity of the beam relative to its obstacle less the beam's own, J z': n . v_O for an
    obstacle fixed to the ground on a moving base (its gap rate less J z'), else exactly 0."""
    ground = [system.contact.obstacles[system.contact.pairs[k].obstacle].ground for k in pairs]
    return np.array([g[1] - v if on else 0.0 for g, v, on in zip(gaps, v_beam, ground)])


def impulse_jump(system: BeamSystem, t: float, y: np.ndarray, restitution, pairs=(0,)) -> Jump:
    """Apply the impulse-momentum map at the given contact ``pairs`` with their coefficients of ``restitution``
    (one number for all, or one per pair).

    The energy the impulses remove is added to the dissipated-energy integral and the impulsive joint work
    (prescribed theta only) to the drive-work integral, so that the total energy stays continuous across the jump.
    Against an obstacle fixed to the ground on a moving base the normal velocities are relative to the obstacle
    (J z' + n . v_O, the gap's rate), and the work -P n . v_O its motion does goes to the work integral.
    """
    pairs = list(pairs)
    e = np.empty(len(pairs))
    e[:] = restitution  # one number for all, or one per pair
    if any(system.contact.pairs[k].frictional for k in pairs):
        return frictional_jump(system, t, y, e, pairs)
    return _normal_jump(system, t, y, e, pairs)


def _normal_jump(system: BeamSystem, t: float, y: np.ndarray, e: np.ndarray, pairs: list[int]) -> Jump:
    """The frictionless map of :func:`impulse_jump`: one pair's compiled (:meth:`BeamSystem.normal_jump
    <flexbeam.model.system.BeamSystem.normal_jump>`, the same bits) where it applies, else :func:`lcp_jump`."""
    if len(pairs) == 1 and (fast := system.normal_jump(t, y, pairs[0], e[0])) is not None:
        y_plus, (P, v_minus, v_plus, T_minus, T_plus) = fast[0], fast[1]
        return Jump(y_plus, np.array([P]), np.array([v_minus]), np.array([v_plus]), float(T_minus), float(T_plus))
    return lcp_jump(system, t, y, e, pairs)


def lcp_jump(system: BeamSystem, t: float, y: np.ndarray, e: np.ndarray, pairs: list[int]) -> Jump:
    """The frictionless map of :func:`impulse_jump` for any number of pairs, in Python: the impact LCP
    (:func:`solve_impact_lcp`) of the pairs' normal velocities relative to their obstacles."""
    gaps = [system.gap(t, y, k) for k in pairs]
    J = np.array([g[3] for g in gaps])
    zd = system.velocities(t, y)
    v_minus = nm.matmul(J, zd)
    drift = obstacle_drift(system, pairs, gaps, v_minus)
    v_minus = v_minus + drift
    y_plus, P, v_plus, T_minus, T_plus = _apply(system, t, y, J, zd, v_minus, drift,
                                                lambda W, v: solve_impact_lcp(W, v, e))  # fmt: skip
    return Jump(y_plus, P, v_minus, v_plus, T_minus, T_plus)


def _apply(system: BeamSystem, t: float, y: np.ndarray, J: np.ndarray, zd: np.ndarray, v_minus: np.ndarray,
           drift: np.ndarray, solve) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, float]:  # fmt: skip
    """The jump of impulses P = solve(W, v-) along the rows of J (velocities v = J z' + drift, relative to the
    obstacles), W = J M^-1 J^T over the state's coordinates: (y+, P, v+, T-, T+), with the impulses' work on the
    dissipated energy and the change of T it does not explain (the joint's or a moving obstacle's) on the work."""
    M, T_minus = system.mass_and_kinetic(t, y)
    free = slice(system.ngiven, None)
    Mr, Jr = M[free, free], J[:, free]
    if Jr.shape[1] == 0:
        return y.copy(), np.zeros(J.shape[0]), v_minus, T_minus, T_minus
    MinvJ = nm.solve(Mr, np.ascontiguousarray(Jr.T))
    P = solve(nm.matmul(Jr, MinvJ), v_minus)
    zd_plus = zd.copy()
    zd_plus[free] += nm.matmul(MinvJ, P)
    y_plus = system.with_velocities(t, y, zd_plus)
    v_plus = nm.matmul(J, zd_plus) + drift
    T_plus = system.kinetic(t, y_plus)
    work_contact = 0.5 * nm.dot(P, v_minus + v_plus)
    y_plus[-2] += -work_contact
    y_plus[-1] += (T_plus - T_minus) - work_contact
    return y_plus, P, v_plus, T_minus, T_plus


def frictional_jump(system: BeamSystem, t: float, y: np.ndarray, e: np.ndarray, pairs: list[int]) -> Jump:
    """The impulse-momentum map with Coulomb friction: one pair by Stronge's process (energetic restitution ``e``
    along the slip: :func:`~flexbeam.methods.friction.frictional_impulse`), several pairs at once by Newton's law with
    a common normal and tangential restitution (:func:`frictional_impulses`; :mod:`flexbeam.methods.frictional_lcp`).
    """
    if len(pairs) > 1:
        return _simultaneous_frictional_jump(system, t, y, e, pairs)
    pair = system.contact.pairs[pairs[0]]
    _, rate, vt, Jn, Jt = system.tangent(t, y, pairs[0])
    zd = system.velocities(t, y)
    J = np.vstack((Jt, Jn))
    # relative to the obstacle (its own velocity on a moving base when fixed to the ground, as in _normal_jump)
    v_minus = np.array([vt, rate])
    drift = v_minus - nm.matmul(J, zd)

    def stronge(W: np.ndarray, v: np.ndarray) -> np.ndarray:
        imp = frictional_impulse((W[0, 0], W[0, 1], W[1, 1]), float(v[0]), float(v[1]), float(e[0]),
                                 pair.friction_static, pair.friction)  # fmt: skip
        return np.array([imp.tangential, imp.normal])

    y_plus, P, v_plus, T_minus, T_plus = _apply(system, t, y, J, zd, v_minus, drift, stronge)
    return Jump(y_plus, P[1:], v_minus[1:], v_plus[1:], T_minus, T_plus, P[:1])


def _simultaneous_frictional_jump(system: BeamSystem, t: float, y: np.ndarray, e: np.ndarray,
                                  pairs: list[int]) -> Jump:  # fmt: skip
    """:func:`frictional_jump` of several pairs at once: the rows of J are the pairs' normals, then their tangents."""
    s = len(pairs)
    rows = [system.tangent(t, y, k) for k in pairs]  # (delta, rate, v_t, J, J_t), relative to the obstacles
    J = np.vstack([r[3] for r in rows] + [r[4] for r in rows])
    zd = system.velocities(t, y)
    v_minus = np.array([r[1] for r in rows] + [r[2] for r in rows])
    drift = v_minus - nm.matmul(J, zd)
    mu_s = np.array([system.contact.pairs[k].friction_static for k in pairs])
    mu_k = np.array([system.contact.pairs[k].friction for k in pairs])
    y_plus, P, v_plus, T_minus, T_plus = _apply(system, t, y, J, zd, v_minus, drift,
                                                lambda W, v: frictional_impulses(W, v, e, mu_s, mu_k))  # fmt: skip
    return Jump(y_plus, P[:s], v_minus[:s], v_plus[:s], T_minus, T_plus, P[s:])


def frictional_impulses(W: np.ndarray, v_minus: np.ndarray, e: np.ndarray, mu_s: np.ndarray,
                        mu_k: np.ndarray) -> np.ndarray:  # fmt: skip
    """The impulses (normal rows, then tangential) of several frictional pairs impacting at once, by
    :func:`~flexbeam.methods.frictional_lcp.solve_frictional_impact`, never gaining energy.

    With different e_i Newton's law may gain energy (Glocker 2013, Part I): should the impulses' work
    P . v- + P . W P / 2 exceed round-off (1e-9 of its terms), the smallest e_i is applied to every pair (one e: no
    gain), with a :class:`~flexbeam.errors.FlexbeamWarning`.  Should no mode pattern be consistent (not met for a
    W = J M^-1 J^T; see the solver), the frictionless impulses are applied, with a warning naming it.
    """
    P = solve_frictional_impact(W, v_minus, e, mu_s, mu_k)
    if np.ptp(e) > 0.0 and (P is None or _gains(W, v_minus, P)):
        e = np.full(e.size, float(np.min(e)))
        warnings.warn(
            "contact.restitution: pairs with different restitution impact at once with friction, where Newton's law "
            f"would gain energy (or has no solution); their smallest, e = {e[0]:g}, is applied to all of them",
            FlexbeamWarning,
            stacklevel=4,
        )
        P = solve_frictional_impact(W, v_minus, e, mu_s, mu_k)
    if P is None:
        warnings.warn(
            "contact.friction: no consistent frictional impulses for the pairs impacting at once; their frictionless "
            "impulses are applied",
            FlexbeamWarning,
            stacklevel=4,
        )
        s = e.size
        P = np.concatenate((solve_impact_lcp(W[:s, :s], v_minus[:s], e), np.zeros(s)))
    return P


def _gains(W: np.ndarray, v_minus: np.ndarray, P: np.ndarray) -> bool:
    """Whether the impulses' work P . v- + P . W P / 2 is positive beyond round-off (1e-9 of its terms)."""
    PWP = nm.dot(P, nm.matmul(W, P))
    return impulse_work(W, v_minus, P) > 1e-9 * (abs(nm.dot(P, v_minus)) + 0.5 * PWP)
