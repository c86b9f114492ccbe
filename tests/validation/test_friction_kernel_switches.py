"""CCFM's Coulomb switches taken by the compiled stepper are the phase loop's, to the bit (issue 28).

A slip's stop and a stick's end that :mod:`flexbeam.methods.coulomb` and :mod:`flexbeam.methods.stick_start` decide
alone -- pairs under their laws, at most one of them sticking -- are taken inside the kernel's phase
(``kernels/src/friction_switch.c``): the pair's new row, the stick test at the stop with the same multipliers, and the
phase started again as the stepper starts one.  Those rules are written twice, in Python for every case and in C for
that one, so each frictional run here is made both ways -- with the kernel's switches, and without them
(:meth:`~flexbeam.methods.ccfm.CCFM.kernel_switches` returning None: every switch a transition of the phase loop, as
all of them were taken before) -- and the two runs must be the same to the bit: every segment's ends, states,
friction rows and step records, the steps, node evaluations and events, the contact records and the metrics.  The
cases make the kernel take every kind of switch (a stop whose stick holds, a stop whose stick breaks at once, the end
of a stick) on one pair, on two pairs (two-stops: the other pair's slip and stick leave some switches to the loop),
on a free bar's pair anywhere, on the seed beam against its compliant support (the support's coordinate one more mode
of the state) and with mu_k = 0 < mu_s; the threlfall law (no switches) is the same either way.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.integrate import modal
from flexbeam.integrate.phases import EventKind
from flexbeam.methods.ccfm import CCFM

from .kernel_switch_runs import both_ways, recorded_run

DATA = Path(__file__).parent / "data"
CASES = {
    "tip-wall": ("tip-wall", {"contact.friction": 0.3}),
    "two-stops": ("two-stops", {"contact.friction": 0.5, "solver.t_end": 0.3}),
    "seed": ("seed-experiment", {"contact.friction": 0.3, "solver.t_end": 0.1}),
    "seed, mu_k = 0": (
        "seed-experiment",
        {"contact.friction": 0.0, "contact.friction_static": 0.3, "solver.t_end": 0.1},
    ),
    "free-bar-drop": (str(DATA / "free-bar-drop.toml"), {"contact.friction": 0.3}),
    "compliant support": ("seed-experiment-calibrated", {"contact.friction": 0.3, "solver.t_end": 0.1}),
    "threlfall": (
        "seed-experiment",
        {"contact.friction": 0.3, "contact.friction_model": "threlfall", "solver.t_end": 0.02},
    ),
}


def run(name: str, monkeypatch, kernel: bool):
    """The case's CCFM run, with the kernel's friction switches or without; and the switches the kernel took."""
    source, overrides = CASES[name]
    off = None if kernel else (CCFM, "kernel_switches", lambda self: None)
    out = recorded_run(source, overrides, "ccfm", monkeypatch, off)
    assert out[0].status == "success", out[0].message
    return out


@pytest.mark.parametrize("name", list(CASES))
def test_the_kernels_switches_give_the_phase_loops_run(monkeypatch, name: str) -> None:
    taken = both_ways(run, name, monkeypatch)
    if name == "threlfall":
        assert not taken
    else:
        assert taken, "the kernel took no switch: nothing is compared"


def test_the_kernel_takes_every_kind_of_switch(monkeypatch) -> None:
    """tip-wall's ringing tip stops and sticks, stops and slips back at once, and slips out of its sticks: each kind
    is taken in the kernel (its Switch names the event and the row after it)."""
    taken = run("tip-wall", monkeypatch, kernel=True)[3]
    held = [s for s in taken if s.event == EventKind.STOP and s.row[1] == 1.0]
    broke = [s for s in taken if s.event == EventKind.STOP and s.row[1] == 0.0]
    ended = [s for s in taken if s.event in (EventKind.UNSTICK_PLUS, EventKind.UNSTICK_MINUS)]
    assert held and broke and ended
    for s in broke + ended:  # slipping on against the multiplier, from the stick's residual slip
        assert s.row[4] in (-1.0, 1.0) and s.row[0] == -0.3 * s.row[4] and s.row[3] >= 0.0
    for s in held:
        np.testing.assert_array_equal(s.row, [0.0, 1.0, 0.3, 0.0, 0.0])


def test_a_full_switch_buffer_hands_the_event_to_the_phase_loop(monkeypatch) -> None:
    """With room for one switch per kernel call, every other switch of tip-wall (mu = 1: 446 events over 0.2 s) goes
    back to the phase loop when the buffer is full: the run is the same to the bit as with room for 64 and as the
    phase loop's own."""
    case = fb.load_case("tip-wall", {"contact.friction": 1.0, "solver.t_end": 0.2})

    def digest() -> tuple:
        run = fb.simulate(case, "ccfm").source.run
        ends = np.array([(s.t0, s.t1) for s in run.segments]).ravel()
        return run.steps, run.events, ends.tobytes(), np.concatenate([s.y1 for s in run.segments]).tobytes()

    wide = digest()
    monkeypatch.setattr(modal, "_SWITCH_ROWS", 1)
    narrow = digest()
    monkeypatch.setattr(CCFM, "kernel_switches", lambda self: None)
    assert wide == narrow == digest()
