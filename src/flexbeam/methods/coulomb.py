"""Coulomb friction under CCFM: slip, stop, stick and unstick as located events.

A pair in contact under its law carries, besides its normal force F >= 0, a tangential force F_t along the contact's
tangent t = (-n_y, n_x) (the normal turned by +90 degrees), acting on the beam as the generalised force Jt^T F_t
(Jt = d(t . r_P)/dz, :meth:`~flexbeam.model.system.BeamSystem.tangent`).  With the slip velocity v_t = Jt z' (relative
to the obstacle):

* **slip** (v_t != 0): F_t = -mu_k F sign(v_t), the sign fixed for the phase; the slip **stops** where v_t reaches
  zero, an event located on the step's dense output (``kernels/src/friction.c``);
* **stick**: v_t = 0 held by a multiplier lambda_t (a bilateral tangential constraint, its normal force still the
  law's); the stick **ends** where abs(lambda_t) reaches mu_s F, an event located on the collocated multiplier's
  interpolant, and the pair slips on with F_t = mu_k F sign(lambda_t) (Pfeiffer & Glocker, Multibody Dynamics with
  Unilateral Contacts, Wiley 1996, Ch. 5; Glocker & Pfeiffer, Nonlinear Dynamics 7 (1995) 471-497).

A stop enters the stick only if the multiplier that would hold it is within mu_s F there; else the pair slips on at
once against lambda_t (the direction of lambda_t is the only one the force can sustain), decided at the stop by
:mod:`flexbeam.methods.stick_start` as the unstick event would have ended the stick before its first step.  A
contact whose onset slip speed is below :data:`REST_SPEED` starts sticking if the stick's ratio lambda_t / F =
-W_tn / W_tt of its inverse mass matrix [J_t; J] M^-1 [J_t; J]^T is within mu_s (Stronge's stick condition at the
onset of an impact), else slips in the direction the normal force drives it (:func:`onset_row`).

Each row of :attr:`~flexbeam.integrate.phases.Phase.friction` is [sigma, stick, mu_s, v_rest, s] with s = sign(v_t)
the slip's direction (0 unless slipping), sigma = -mu_k s and v_rest the residual slip speed a slip starting from a
stick may run back by (:func:`unstick`).  The direction is kept apart from sigma so that a pair with mu_k = 0 <
mu_s, which slips without friction, is still watched for its stop and sticks there (:func:`slip_row`).

The compiled stepper takes the stops and stick ends that these rules decide alone -- pairs under their laws, at most
one of them sticking -- without a transition of the phase loop (``kernels/src/friction_switch.c``, the same rows from
the same numbers; ``tests/validation/test_friction_kernel_switches.py`` runs every frictional preset both ways): a
change to :func:`stop`, :func:`unstick`, :func:`after_event` or :mod:`~flexbeam.methods.stick_start`'s test is made
there too.

``contact.friction_model = "threlfall"`` replaces the switching by Threlfall's regularised law (Threlfall,
Mechanism and Machine Theory 13 (1978) 475-483), F_t = -mu_k F (1 - exp(-3 abs(v_t) / v_0)) sign(v_t) with
v_0 = ``contact.friction_velocity``: no events, no stick (a body on an incline creeps at a speed ~ v_0 tan(alpha) /
(3 mu_k)); its row is [mu_k, -1, v_0, 0, 0].
"""

from __future__ import annotations

import numpy as np

from .. import numerics as nm
from ..integrate.phases import ContactMode, EventKind, Phase
from ..model.delassus import inverse_mass
from ..model.system import BeamSystem

#: [m/s] a contact whose slip speed at its onset is below this starts sticking (the stick's multiplier then decides)
REST_SPEED = 1e-9
#: a sticking pair follows another when the part of its tangential Delassus diagonal Jt M^-1 Jt^T not explained by the
#: pairs holding before it is below this share (as :attr:`~flexbeam.methods.base.ImpactMethod.REDUNDANT` for CCM)
DEPENDENT = 1e-9


#: the columns of a friction row: [sigma, stick, mu_s, v_rest, s]
COLUMNS = 5


def rows(phase: Phase, pairs: int) -> np.ndarray:
    """A copy of ``phase``'s friction rows (pairs x :data:`COLUMNS`; zeros without friction)."""
    return np.zeros((pairs, COLUMNS)) if phase.friction is None else phase.friction.copy()


def slip_row(mu_k: float, mu_s: float, direction: float) -> np.ndarray:
    """The row of a pair slipping with sign(v_t) = ``direction`` (+-1): sigma = -mu_k sign(v_t), watched for its stop
    whatever mu_k."""
    return np.array([-mu_k * direction, 0.0, mu_s, 0.0, direction])


def slipping(row: np.ndarray) -> bool:
    """Does the pair of friction ``row`` slip under Coulomb's switching law (a direction, no stick)?"""
    return bool(row[4] != 0.0 and row[1] == 0.0)


def onset_row(system: BeamSystem, t: float, y: np.ndarray, pair: int) -> np.ndarray:
    """The friction row of a pair whose contact starts at (t, y): slip against its slip velocity; when it barely
    slips, stick if the stick's ratio -W_tn / W_tt is within mu_s, else slip in the direction sign(W_tn) the normal
    force drives it (Stronge 2000, Impact Mechanics, ch. 5); zeros for a frictionless pair."""
    p = system.contact.pairs[pair]
    if not p.frictional:
        return np.zeros(COLUMNS)
    if p.friction_model == "threlfall":
        return np.array([p.friction, -1.0, p.friction_velocity, 0.0, 0.0])
    vt = system.tangent(t, y, pair)[2]
    if abs(vt) > REST_SPEED:
        return slip_row(p.friction, p.friction_static, float(np.sign(vt)))
    W = inverse_mass(system, t, y, [pair])  # [[W_tt, W_tn], [W_nt, W_nn]]
    r = -W[0, 1] / W[0, 0] if W[0, 0] > 0.0 else 0.0
    if abs(r) <= p.friction_static:  # the stick's ratio lambda_t / F (Stronge's stick condition)
        return np.array([0.0, 1.0, p.friction_static, 0.0, 0.0])
    return slip_row(p.friction, p.friction_static, -float(np.sign(r)))


def after_event(system: BeamSystem, event: EventKind, pair: int) -> np.ndarray:
    """The friction row of ``pair`` after one of its friction events: a stop sticks, an unstick slips with the
    kinetic force in the direction of the multiplier that last held it (the slip against it)."""
    p = system.contact.pairs[pair]
    if event == EventKind.STOP:
        return np.array([0.0, 1.0, p.friction_static, 0.0, 0.0])
    return slip_row(p.friction, p.friction_static, -1.0 if event == EventKind.UNSTICK_PLUS else 1.0)


def stop(system: BeamSystem, phase: Phase, t: float, y: np.ndarray, pair: int) -> np.ndarray:
    """The friction rows after ``pair``'s slip stopped at (t, y): it sticks, and so does every other slipping pair whose
    slip speed is below :data:`REST_SPEED` there (two points of a rigid bar sliding on two stops stop together)."""
    out = rows(phase, system.pairs)
    out[pair] = after_event(system, EventKind.STOP, pair)
    for k in range(system.pairs):
        if k != pair and slipping(out[k]) and abs(system.tangent(t, y, k)[2]) <= REST_SPEED:
            out[k] = after_event(system, EventKind.STOP, k)
    return out


def grouped(system: BeamSystem, t: float, y: np.ndarray, friction: np.ndarray, modes=()) -> np.ndarray:
    """The friction rows with the sticking pairs sorted into holders (stick = 1, a multiplier of their own) and
    followers (stick = 2 + h: the pair's tangential row depends on holder h's -- two points of a rigid bar on two
    stops move together -- so h holds both, within mu_s times their summed normal forces), by the Schur complement of
    the tangential Delassus matrix on the holders kept so far.  First the held pairs (CONSTRAINT in ``modes``) that
    their constraints pin (:func:`pinned`) stick as their own followers (stick = 2 + k), whatever their rows said."""
    out = np.array(friction, float)
    for k in range(out.shape[0]):
        if out[k, 1] == 2.0 + k:  # pinned before: decided again
            out[k, 1] = 1.0
    held = [k for k, m in enumerate(modes) if m == ContactMode.CONSTRAINT]
    rough = [k for k in held if out[k, 1] > 0.0 or out[k, 4] != 0.0]  # Coulomb's rows: a stick or a slip
    for k in pinned(system, t, y, rough, held) if rough else ():
        out[k] = [0.0, 2.0 + k, out[k, 2], 0.0, 0.0]
    sticking = [k for k in range(out.shape[0]) if out[k, 1] > 0.0 and out[k, 1] != 2.0 + k]
    if len(sticking) < 2:
        out[sticking, 1] = 1.0
        return out
    n = len(sticking)
    W = inverse_mass(system, t, y, sticking)[:n, :n]
    kept: list[int] = []
    for i, k in enumerate(sticking):
        w = W[i, i]
        if kept:
            w -= nm.dot(W[i, kept], nm.solve(W[np.ix_(kept, kept)], W[kept, i]))
        if w > DEPENDENT * W[i, i]:
            kept.append(i)
            out[k, 1] = 1.0
        else:  # follows the holder it depends on most
            h = max(kept, key=lambda j: abs(W[i, j]) / np.sqrt(W[j, j]))
            out[k, 1] = 2.0 + sticking[h]
    return out


def pinned(system: BeamSystem, t: float, y: np.ndarray, pairs: list[int], held: list[int]) -> list[int]:
    """The ``pairs`` whose tangential rows depend on the normal rows of the ``held`` pairs (the part of J_t M^-1 J_t^T
    not explained by them below :data:`DEPENDENT` of it): their constraints pin them, v_t = 0 whenever the held gaps
    are still, so they stick without a multiplier of their own and their friction force is indeterminate (reported
    0).  A rigid beam pinned at O and held at P has one coordinate, which the normal constraint fixes: a tangential
    multiplier made the collocation singular (a step-size underflow at the first stop), and a slip there moves
    nothing."""
    rows = sorted(set(pairs) | set(held))
    W = inverse_mass(system, t, y, rows)  # [J_t; J] M^-1 [J_t; J]^T of rows
    n = [len(rows) + rows.index(h) for h in held]
    Wnn = W[np.ix_(n, n)]
    out = []
    for k in pairs:
        i = rows.index(k)
        w = W[i, i] - nm.dot(W[i, n], nm.solve(Wnn, W[n, i]))
        if w <= DEPENDENT * W[i, i]:
            out.append(k)
    return out


def unstick(system: BeamSystem, phase: Phase, event: EventKind, pair: int, t: float, y: np.ndarray) -> np.ndarray:
    """The friction rows after holder ``pair``'s stick ended at (t, y): it and its followers slip on
    (:func:`after_event`), each from the stick's residual slip speed, which its slip may run back by twice before
    a stop is declared (v_rest: the stick holds v_t only to its collocation error, 3e-11 m/s on a rigid bar, up to
    1e-6 m/s at a flexible beam's ringing tip)."""
    out = rows(phase, system.pairs)
    for k in range(system.pairs):
        if k == pair or out[k, 1] == 2.0 + pair:
            out[k] = after_event(system, event, k)
            out[k, 3] = 2.0 * abs(system.tangent(t, y, k)[2])
    return out


def state(phase: Phase, pair: int) -> int:
    """The pair's friction state in ``phase``: 0 no frictional contact, 1 slip (or the regularised law), 2 stick."""
    if phase.friction is None:
        return 0
    row = phase.friction[pair]
    return 2 if row[1] > 0.0 else (1 if row[0] != 0.0 or row[4] != 0.0 else 0)
