"""A free, flexible beam landing on an obstacle that stands on a mass-spring-damper support (``obstacle.support``).

The steel bar of tests/validation/data/free-bar-drop.toml (8 modes, under gravity) strikes the floor with its end at
t = 0.  Under IMM the impact is Newton's along n with the contact point's inverse mass: on a rigid floor the bar's
W_nn alone, P_rigid = (1 + e) v0 / W_nn; on a floor of mass m_s on a spring the two bodies' inverse masses add,

    P = (1 + e) v0 / (W_nn + 1 / m_s),

whatever W_nn is (the flexible bar's, its modes included): W_nn is read from the rigid floor's run.  The run on the
sprung floor used to fail at its first step on the reference path (the explicit integrator's own first-step guess
diverged in the bar's fast modes; it now retries from its stability bound).  With e < 1 the bar's end and the sprung
floor then chatter toward a joint motion that IMM has no resting phase for on a compliant support: the run ends as
failed ("events keep recurring without progress"), not yet a persistent contact.
"""

from __future__ import annotations

import pytest

import flexbeam as fb

BAR = "tests/validation/data/free-bar-drop.toml"
MS = 0.5


@pytest.mark.parametrize("e", [1.0, 0.5])
def test_imm_on_a_sprung_floor_is_the_two_body_impact(e):
    """The first impulses on the rigid and the sprung floor satisfy 1/P = (W_nn + 1/m_s) / ((1 + e) v0) to 1e-12
    (an impulse map: round-off), Newton's normal velocity after, and the run goes on to its end (with e = 0.5 the
    end and the sprung floor chattered into "events keep recurring without progress" at 36 us while IMM's resting
    contact on a compliant support took the reference integrator; it rests now, on the compiled one)."""
    over = {"contact.law": "hertz", "contact.restitution": e, "solver.t_end": 2e-3}
    rigid = fb.simulate(fb.load_case(BAR, over), "imm")
    sprung = fb.simulate(fb.load_case(BAR, {**over, "obstacle.support.mass": MS, "obstacle.support.stiffness": 1e6,
                                            "obstacle.support.damping": 10.0}), "imm")  # fmt: skip
    assert rigid.status == sprung.status == "success", sprung.message
    v0 = -rigid.contacts[0].velocity_before
    Wnn = (1.0 + e) * v0 / rigid.contacts[0].impulse
    first = sprung.contacts[0]
    assert first.velocity_before == pytest.approx(-v0, rel=1e-15)
    assert first.impulse == pytest.approx((1.0 + e) * v0 / (Wnn + 1.0 / MS), rel=1e-12)
    assert first.velocity_after == pytest.approx(e * v0, rel=1e-9)
