"""CCM's contacts on one pair taken by the compiled stepper are the phase loop's, to the bit (issue 25).

A single frictionless pair's e = 0 onset (the jump, the held test) and its release, where
:meth:`~flexbeam.methods.base.ImpactMethod.contact_transition` and :meth:`~flexbeam.methods.ccm.CCM.on_impact` decide
alone, are taken inside the kernel's phase (``kernels/src/held_switch.c``): the rules are written twice, in Python
for every case and in C for that one, so each run here is made both ways -- with the kernel's switches, and without
them (:meth:`~flexbeam.methods.ccm.CCM.switch_coef` returning None: every onset and release a transition of the
phase loop, as before) -- and the two must be the same to the bit: every segment's ends, states, modes, contacts
buffer and step records, the steps, node evaluations and events, the contact records and the metrics.  The cases:
the seed beam (24 contacts in 0.1 s), its tip on a wall with and without axial modes, two stops (the other pair's
gap checked at each onset), a free bar, contact anywhere on a spinning stop, the held pair without Baumgarte
stabilisation (no held step bound), a run stopped by solver.max_contacts (its last onset the loop's), and a case the
kernel leaves to the loop (a compliant support)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.integrate.phases import EventKind
from flexbeam.methods.ccm import CCM

from .kernel_switch_runs import both_ways, recorded_run

DATA = Path(__file__).parent / "data"
CASES = {
    "seed": ("seed-experiment", {}),
    "tip-wall": ("tip-wall", {"solver.t_end": 0.05}),
    "tip-wall, axial modes": ("tip-wall", {"solver.t_end": 0.02, "model.axial_modes": 4}),
    "two-stops": ("two-stops", {"solver.t_end": 0.1}),
    "free-bar-drop": (str(DATA / "free-bar-drop.toml"), {}),
    "spinning-stop": ("spinning-stop", {}),
    "no Baumgarte": ("seed-experiment", {"solver.baumgarte_frequency": 0.0, "solver.t_end": 0.02}),
    "max-contacts": ("seed-experiment", {"solver.max_contacts": 5}),
    "compliant support": ("seed-experiment-calibrated", {"solver.t_end": 0.02}),
}


def run(name: str, monkeypatch, kernel: bool):
    """The case's CCM run, with the kernel's switches or without; and the switches the kernel took."""
    source, overrides = CASES[name]
    off = None if kernel else (CCM, "switch_coef", lambda self, phase: None)
    return recorded_run(source, overrides, "ccm", monkeypatch, off)


@pytest.mark.parametrize("name", list(CASES))
def test_the_kernels_onsets_and_releases_give_the_phase_loops_run(monkeypatch, name: str) -> None:
    taken = both_ways(run, name, monkeypatch)
    if name == "compliant support":
        assert not taken
    else:
        assert {s.event for s in taken} == {EventKind.IMPACT, EventKind.RELEASE}, "nothing is compared"


def test_an_onset_whose_pair_pulls_at_once_is_taken_too(monkeypatch) -> None:
    """tip-wall's chatter has onsets after which the pair is held, and (the multiplier pulling at once) onsets whose
    record ends at the onset: both kinds are taken in the kernel (row[0] 1 and 0), each record as the phase loop
    writes it (above)."""
    taken = run("tip-wall", monkeypatch, kernel=True)[3]
    onsets = [s for s in taken if s.event == EventKind.IMPACT]
    assert {s.row[0] for s in onsets} == {0.0, 1.0}


def test_the_phase_a_failure_names_is_the_switched_one(monkeypatch) -> None:
    """A failure in the part of a phase after a switch names the phase of that part, which the stepper asks of
    :meth:`~flexbeam.methods.ccm.CCM.switched_phase` (no records touched): at every switch of the seed run it is the
    phase :meth:`~flexbeam.methods.ccm.CCM.kernel_switched` gives -- name, modes, step bound, sampling, buffer."""
    pairs = []
    switched = CCM.kernel_switched

    def both(self, phase, switch):
        pure = self.switched_phase(phase, switch)
        out = switched(self, phase, switch)
        pairs.append((pure, out[0]))
        return out

    monkeypatch.setattr(CCM, "kernel_switched", both)
    fb.simulate(fb.load_case("seed-experiment", {}), "ccm")
    assert len(pairs) > 30
    for pure, real in pairs:
        assert (pure.name, pure.modes, pure.max_step, pure.sample_step) == (
            real.name, real.modes, real.max_step, real.sample_step)  # fmt: skip
        np.testing.assert_array_equal(pure.buffer, real.buffer)
