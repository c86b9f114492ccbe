"""IMM's rebounds on one pair taken by the compiled stepper are the phase loop's, to the bit (issue 25).

A single frictionless pair's rebound from free flight (the impact with its restitution, where
:meth:`~flexbeam.methods.imm.IMM.on_impact` decides alone: a rebound above solver.rest_velocity and above the rise
limit of :meth:`~flexbeam.methods.imm.IMM.unresolvable`), and the release of a resting contact, are taken inside the
kernel's phase (``kernels/src/held_switch.c``, ``FB_SWITCH_REBOUND``).  Each run is made both ways, with the kernel's
switches and without them (``switch_coef`` returning None), and the two must be the same to the bit (as
tests/validation/test_held_kernel_switches.py for CCM): the seed beam's rebounds and its chatter coming to rest
(restitution 0.2: resting contacts and their releases, low rebounds left to the loop), a wall, two stops with their
own restitutions, a free bar, e = 1, and a run stopped by solver.max_contacts."""

from __future__ import annotations

from pathlib import Path

import pytest

from flexbeam.integrate.phases import EventKind
from flexbeam.methods.imm import IMM

from .kernel_switch_runs import both_ways, recorded_run

DATA = Path(__file__).parent / "data"
CASES = {
    "seed": ("seed-experiment", {}),
    "seed, e = 0.2": ("seed-experiment", {"contact.restitution": 0.2, "solver.t_end": 0.3}),
    "seed, e = 1": ("seed-experiment", {"contact.restitution": 1.0}),
    "tip-wall": ("tip-wall", {"solver.t_end": 0.05}),
    "two-stops": ("two-stops", {"solver.t_end": 0.1, "obstacles[0].contact.restitution": 0.3}),
    "free-bar-drop": (str(DATA / "free-bar-drop.toml"), {}),
    "max-contacts": ("seed-experiment", {"solver.max_contacts": 5}),
}


def run(name: str, monkeypatch, kernel: bool):
    source, overrides = CASES[name]
    off = None if kernel else (IMM, "switch_coef", lambda self, phase: None)
    return recorded_run(source, overrides, "imm", monkeypatch, off)


@pytest.mark.parametrize("name", list(CASES))
def test_the_kernels_rebounds_give_the_phase_loops_run(monkeypatch, name: str) -> None:
    taken = both_ways(run, name, monkeypatch)
    assert EventKind.IMPACT in {s.event for s in taken}, "nothing is compared"


def test_a_resting_contacts_release_is_taken_too(monkeypatch) -> None:
    """At e = 0.2 the seed beam's rebounds fall below solver.rest_velocity: the loop rests the pair (IMM's resting
    phase, a constraint), and the kernel takes its releases (compared above)."""
    taken = run("seed, e = 0.2", monkeypatch, kernel=True)[3]
    assert EventKind.RELEASE in {s.event for s in taken}
