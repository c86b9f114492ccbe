"""A run made with the compiled stepper's switches and without them (tests/validation/test_*_kernel_switches.py):
the rules are written twice, in Python for every case and in C where they decide alone, so the two runs must be the
same to the bit."""

from __future__ import annotations

import json

import numpy as np

import flexbeam as fb
from flexbeam.integrate import modal


def recorded_run(source: str, overrides: dict, method: str, monkeypatch, off: tuple | None = None):
    """(the run, repr of its contact records, its metrics' JSON without wall times, the switches the kernel took) of
    the case under ``method``; ``off`` = (class, attribute, replacement) patched for the run: the switches off."""
    taken = []
    advance = modal.ModalStepper.advance

    def recording(self, phase, t, y, t_end):
        out = advance(self, phase, t, y, t_end)
        taken.extend(out.switches)
        return out

    with monkeypatch.context() as m:
        m.setattr(modal.ModalStepper, "advance", recording)
        if off is not None:
            m.setattr(*off)
        sol = fb.simulate(fb.load_case(source, overrides), method)
        contacts = repr(sol.contacts)
        metrics = json.dumps({k: v for k, v in sol.metrics().items() if "wall" not in k}, sort_keys=True, default=str)
    return sol.source.run, contacts, metrics, taken


def assert_same_run(ours, loops) -> None:
    """Two runs' steps, node evaluations, events, status and message, and every segment -- its ends, states, phase
    (name, modes, step bound, sampling, friction rows, contacts buffer) and step records -- the same to the bit."""
    assert (ours.steps, ours.nfev, ours.events, ours.status, ours.message) == (
        loops.steps, loops.nfev, loops.events, loops.status, loops.message)  # fmt: skip
    assert ours.phase_steps == loops.phase_steps
    assert len(ours.segments) == len(loops.segments)
    for a, b in zip(ours.segments, loops.segments):
        assert (a.t0, a.t1, a.phase.name, a.phase.modes) == (b.t0, b.t1, b.phase.name, b.phase.modes)
        assert (a.phase.max_step, a.phase.sample_step) == (b.phase.max_step, b.phase.sample_step)
        np.testing.assert_array_equal(a.y0, b.y0)
        np.testing.assert_array_equal(a.y1, b.y1)
        if a.phase.friction is None or b.phase.friction is None:
            assert a.phase.friction is b.phase.friction is None
        else:
            np.testing.assert_array_equal(a.phase.friction, b.phase.friction)
        np.testing.assert_array_equal(a.phase.buffer, b.phase.buffer)
        assert (a.dense is None) == (b.dense is None)
        if a.dense is not None:
            np.testing.assert_array_equal(a.dense.records, b.dense.records)


def both_ways(run, name: str, monkeypatch) -> list:
    """Case ``name`` run with the kernel's switches and without them (``run(name, monkeypatch, kernel)``), compared
    to the bit (:func:`assert_same_run`, the contact records, the metrics); returns the switches the kernel took."""
    ours, contacts, metrics, taken = run(name, monkeypatch, kernel=True)
    loops, contacts_loop, metrics_loop, none = run(name, monkeypatch, kernel=False)
    assert not none
    assert_same_run(ours, loops)
    assert contacts == contacts_loop
    assert metrics == metrics_loop
    return taken
