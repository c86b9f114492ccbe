"""Every phase the impact methods hand the integrator carries the contacts buffer of its own modes and parameters.

The methods build a phase's buffer once and share it (the free phase is built once per run; a held phase takes the
buffer its held set was just tested with: :meth:`flexbeam.methods.base.ImpactMethod.phase`).  Packing the phase's
fields afresh (:func:`flexbeam.kernels.pack_contacts`, the layout the kernels read) must give the same buffer, entry
for entry: a shared buffer of other modes would run the phase under the wrong contacts.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.integrate import modal
from flexbeam.kernels import pack_contacts

DATA = Path(__file__).parents[1] / "validation" / "data"


@pytest.mark.parametrize("preset", ["seed-experiment", "two-stops", str(DATA / "free-bar-drop.toml")])
def test_each_phase_runs_under_its_own_contacts(monkeypatch, preset: str) -> None:
    """CCM (whose held phases take the buffer of their held set) on one pair, two pairs and a free bar: the phases
    handed to the stepper, and those of every segment (a phase the compiled stepper switched to inside its call, a
    single pair's onset or release, is built by the method afterwards for its segment, whose outputs read its
    buffer)."""
    phases = []
    advance = modal.ModalStepper.advance

    def recording(self, phase, t, y, t_end):
        phases.append(phase)
        return advance(self, phase, t, y, t_end)

    monkeypatch.setattr(modal.ModalStepper, "advance", recording)
    sol = fb.simulate(fb.load_case(preset, {"solver.t_end": 0.05}), "ccm")
    assert sol.status == "success"
    phases += [seg.phase for seg in sol.source.segments]
    held = [p for p in phases if any(m == 2 for m in p.modes)]
    assert held, "the run has no held phase: nothing is checked"
    for p in phases:
        fresh = pack_contacts([int(m) for m in p.modes], p.parameters, *p.baumgarte, friction=p.friction)
        np.testing.assert_array_equal(p.buffer, fresh)


def test_a_phase_of_other_modes_packs_its_own() -> None:
    """After a held-set test of both pairs of two-stops, phases of one held pair (or none, or both) with the same
    parameters array take the buffer of their own modes."""
    from flexbeam.methods.ccm import CCM
    from flexbeam.model.system import BeamSystem
    from flexbeam.simulation import initial_state

    case = fb.load_case("two-stops")
    system = BeamSystem.from_case(case)
    method = CCM(system, case)
    y = initial_state(system, case)[0]
    params = np.zeros((system.pairs, 4))
    base = method.phase([0, 0], params, [None, None])
    for modes in ([2, 0], [0, 2], [2, 2], [0, 0]):
        method.held_set(0.0, y, [0, 1], base)  # tests [2, 2] (and its subsets) with base.parameters
        p = method.phase(modes, base.parameters, [None, None])
        fresh = pack_contacts(modes, p.parameters, *p.baumgarte)
        np.testing.assert_array_equal(p.buffer, fresh)


def test_a_friction_switch_copies_every_other_field() -> None:
    """Phase.with_friction (built field by field for speed) is dataclasses.replace with new friction rows: a field
    added to Phase and not passed on would fail here."""
    import dataclasses

    from flexbeam.methods.ccfm import CCFM
    from flexbeam.model.system import BeamSystem

    case = fb.load_case("tip-wall", {"contact.friction": 0.3})
    method = CCFM(BeamSystem.from_case(case), case)
    rows = np.array([[0.0, 1.0, 0.3, 0.0, 0.0]])
    phase = method.phase([1], np.array([[1e9, 1.5, 0.1, 0.0]]), [None], rows)
    switched = np.array([[-0.3, 0.0, 0.3, 1e-9, 1.0]])
    got, want = phase.with_friction(switched), dataclasses.replace(phase, friction=switched)
    for f in dataclasses.fields(phase):
        a, b = getattr(got, f.name), getattr(want, f.name)
        assert np.array_equal(a, b) if isinstance(a, np.ndarray) else a == b, f.name
