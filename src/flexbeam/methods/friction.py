"""A planar impact with Coulomb friction and Stronge's energetic coefficient of restitution (IMM with friction).

At one contact point with normal n and tangent t = (-n_y, n_x), the inverse mass W = [J_t; J_n] M^-1 [J_t; J_n]^T
(2 x 2, positive definite) maps the impulse (P_t, P_n) to the change of the contact point's velocity (v_t, v_n).
Following Stronge (Impact Mechanics, 2000, ch. 5; Proc. R. Soc. A 431 (1990) 169), the impact is resolved as a
process in the normal impulse p >= 0, along which

* **slip** in the direction s = sign(v_t): dP_t/dp = -mu_k s, so dv/dp = W (-mu_k s, 1);
* **stick** (v_t = 0 held): dP_t/dp = r = -W_tn / W_tt, allowed while abs(r) <= mu_s; then
  dv_n/dp = W_nn - W_nt W_tn / W_tt;
* slip that brings v_t to zero either **sticks** (abs(r) <= mu_s) or **reverses** (slips on in the direction
  sign(W_tn), the only one the impulse can sustain).

v is piecewise linear in p.  **Compression** ends where v_n = 0, after the normal force did the work W_c = int v_n dp
< 0; **restitution** ends where it has done -e^2 W_c (Stronge's energetic coefficient e).  Coulomb friction
dissipates and the normal force returns no more than it absorbed, so the kinetic energy never increases, whatever
the slip process (unlike Newton's kinematic coefficient with friction: Kane's paradox, Kane & Levinson 1985; Stronge
1991).  Without friction this is Newton's P_n = -(1 + e) v_n / W_nn.

**Painlevé.** While slipping, the normal velocity may at first fall (dv_n/dp = W_nn - mu s W_tn < 0: friction drives
the contact point into the obstacle).  With a positive definite W that slip always stops first (a jam would need
dv_t/dp = W_tn - mu s W_tt to keep the slip going as well, i.e. W_tn^2 >= W_tt W_nn), after which the point sticks or
reverses and v_n recovers: the impulse stays finite.  Should a singular W (round-off, dependent constraints) jam it
all the same, it is resolved as a tangential impact -- a tangential impulse stops the slip at once, as if mu were
unbounded for that instant -- and a :class:`~flexbeam.errors.FlexbeamWarning` names it.  Painlevé's paradox proper
belongs to sustained sliding (the acceleration-level contact problem of CCFM and CCM with friction).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from ..errors import FlexbeamWarning

#: at most this many slip/stick transitions in one impact (each moves to a stick or reverses the slip: two suffice
#: for a constant W; the bound only guards against a cycle)
MAX_SEGMENTS = 16


@dataclass(frozen=True)
class FrictionalImpulse:
    """The impulse of a frictional impact: normal and tangential components, and how the slip went."""

    normal: float
    tangential: float
    #: the sequence of modes the contact point went through: "slip+", "slip-", "stick"
    modes: tuple[str, ...]
    painleve: bool = False


def _slopes(W: tuple[float, float, float], mode: str, mu_k: float) -> tuple[float, float, float]:
    """(dP_t/dp, dv_t/dp, dv_n/dp) of a mode; W = (W_tt, W_tn, W_nn)."""
    Wtt, Wtn, Wnn = W
    if mode == "stick":
        r = -Wtn / Wtt
        return r, 0.0, Wnn + Wtn * r
    s = 1.0 if mode == "slip+" else -1.0
    dPt = -mu_k * s
    return dPt, Wtt * dPt + Wtn, Wtn * dPt + Wnn


def _after_stop(W: tuple[float, float, float], mu_s: float) -> str:
    """The mode once v_t = 0: stick if the required ratio abs(W_tn / W_tt) <= mu_s, else slip in sign(W_tn)."""
    Wtt, Wtn, _ = W
    if abs(Wtn) <= mu_s * Wtt:
        return "stick"
    return "slip+" if Wtn > 0.0 else "slip-"


def frictional_impulse(W: tuple[float, float, float], v_t: float, v_n: float, e: float, mu_s: float,
                       mu_k: float) -> FrictionalImpulse:  # fmt: skip
    """The impulse (P_n, P_t) of an impact with approach velocity v_n < 0 and slip velocity v_t, for the inverse
    mass W = (W_tt, W_tn, W_nn) (the module docstring's process).

    Parameters
    ----------
    W
        (W_tt, W_tn, W_nn) of the 2 x 2 inverse mass in the contact's (t, n) axes [1/kg].
    v_t, v_n
        The contact point's tangential and normal velocity before the impact [m/s] (v_n < 0 approaching).
    e
        Stronge's energetic coefficient of restitution, in [0, 1].
    mu_s, mu_k
        Static and kinetic coefficients of friction (mu_s >= mu_k >= 0).
    """
    Wtt, Wtn, Wnn = W
    if v_n >= 0.0 or Wnn <= 0.0:
        return FrictionalImpulse(0.0, 0.0, ())
    mode = ("slip+" if v_t > 0.0 else "slip-") if v_t != 0.0 else _after_stop(W, mu_s)
    p = Pt = work_c = work_r = 0.0
    compressing, painleve, modes = True, False, [mode]
    for _ in range(MAX_SEGMENTS):
        dPt, at, an = _slopes(W, mode, mu_k)
        if mode != "stick" and an <= 0.0 and at * v_t >= 0.0:  # the normal velocity cannot recover: it jams
            painleve = True
            dP = -v_t / Wtt  # a tangential impulse stopping the slip at once
            Pt, v_n, v_t = Pt + dP, v_n + Wtn * dP, 0.0
            mode = _after_stop(W, mu_s)
            modes.append(mode)
            continue
        steps = [math.inf, math.inf, math.inf]  # slip stops, compression ends, restitution ends
        if mode != "stick" and at * v_t < 0.0:
            steps[0] = -v_t / at
        if compressing and an > 0.0:
            steps[1] = -v_n / an
        if not compressing:
            left = e * e * -work_c - work_r  # the work the normal force has yet to return
            if left <= 0.0:
                break
            steps[2] = _work_step(v_n, an, left)
            if an < 0.0:  # slip lowering v_n: the restitution ends where v_n returns to zero, if it comes first
                steps[2] = min(steps[2], -v_n / an)
        dp = min(steps)
        if not math.isfinite(dp):
            break
        work = v_n * dp + 0.5 * an * dp * dp
        if compressing:
            work_c += work
        else:
            work_r += work
        p, Pt, v_t, v_n = p + dp, Pt + dPt * dp, v_t + at * dp, v_n + an * dp
        event = steps.index(dp)
        if event == 2:
            break
        if event == 1:
            compressing, v_n = False, 0.0
            if e == 0.0:
                break
        if event == 0:
            v_t = 0.0
            mode = _after_stop(W, mu_s)
            modes.append(mode)
    if painleve:
        warnings.warn(
            "contact.friction: Painlevé's jam at an impact (the slip drove the contact point into the obstacle); "
            "resolved by a tangential impulse stopping the slip",
            FlexbeamWarning,
            stacklevel=3,
        )
    return FrictionalImpulse(p, Pt, tuple(modes), painleve)


def _work_step(v_n: float, an: float, left: float) -> float:
    """The impulse dp >= 0 over which the normal force does the work ``left`` > 0: v_n dp + a_n dp^2 / 2 = left."""
    if an == 0.0:
        return left / v_n if v_n > 0.0 else math.inf
    disc = v_n * v_n + 2.0 * an * left
    if disc < 0.0:
        return math.inf  # it cannot (a_n < 0): the caller ends the restitution where v_n returns to zero
    root = math.sqrt(disc)
    # the smaller positive root, written to avoid cancellation
    return 2.0 * left / (v_n + root) if v_n + root > 0.0 else (-v_n + root) / an
