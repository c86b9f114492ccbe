"""The phase loop's handling of a floating-point failure outside the compiled kernels (``integrate/loop.py``)."""

from __future__ import annotations

import numpy as np

import flexbeam as fb
from flexbeam.integrate.loop import run_phases
from flexbeam.integrate.modal import ModalStepper
from flexbeam.methods.ccfm import CCFM
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import initial_state


class _OverflowAtImpact(CCFM):
    """CCFM whose transition at the first impact overflows (as an impulse map on a state scaled beyond double
    precision would)."""

    def transition(self, phase, event, t, y, pair=0):
        np.multiply(np.float64(1e300), np.float64(1e300))
        return super().transition(phase, event, t, y, pair)


def test_an_overflow_ends_the_run_as_a_failure_at_its_time_keeping_what_was_computed():
    """The seed released 1 mm above its stop (state kind at rest, falling under gravity): the overflow at the first
    impact ends the run there with status 'failed', its time in the message, and the free flight before it kept."""
    case = fb.load_case("seed-experiment", {"initial.kind": "state", "initial.angle": 0.0017, "solver.t_end": 0.1})
    system = BeamSystem.from_case(case)
    y0, _ = initial_state(system, case)
    run = run_phases(_OverflowAtImpact(system, case), ModalStepper(system), y0, case.solver.t_end)
    assert run.status == "failed"
    assert run.message.startswith(f"floating-point failure at t = {run.t_final:.9g} s: overflow")
    assert 0.0 < run.t_final < case.solver.t_end
    assert run.segments and run.segments[-1].t1 == run.t_final


def test_a_storm_is_a_full_window_of_friction_switches_within_its_span():
    """:func:`storm` on hand-made windows: STORM_EVENTS switches within STORM_SPAN are one, one switch fewer or a
    span at the limit are not."""
    from collections import deque

    from flexbeam.integrate.loop import STORM_EVENTS, STORM_SPAN, storm

    fast = deque(np.linspace(0.5, 0.5 + 0.5 * STORM_SPAN, STORM_EVENTS), maxlen=STORM_EVENTS)
    assert storm(fast)
    short = deque(list(fast)[1:], maxlen=STORM_EVENTS)
    assert not storm(short)
    slow = deque(np.linspace(0.0, STORM_SPAN, STORM_EVENTS), maxlen=STORM_EVENTS)
    assert not storm(slow)


def test_impacts_coming_faster_than_a_storm_are_capped_as_contacts_not_as_a_storm():
    """IMM on the axially stiff rod-end: its impulses throw the struck end back 1e-13-1e-8 s apart (1013 events within
    7.1 us); impacts are contacts, and the run stops at solver.max_contacts with that cap's own advice, not as a storm
    of friction switches (which only friction events make)."""
    sol = fb.simulate(fb.load_case("rod-end", {"contact.friction": 0.3}), "imm")
    assert sol.status == "max-contacts", sol.message
    assert "solver.max_contacts" in sol.message
