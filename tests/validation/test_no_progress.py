"""A run that cannot make progress stops, within a bounded effort, as a failure naming the time and the cause, and
keeps what it computed (issue 23, item 8).

Each integrator is given a right-hand side it cannot follow, on purpose:

* the compiled modal integrator: the flexible frequencies it propagates (its modal basis) doubled, while the
  elastic energy each step's energy balance is checked against keeps the true stiffness -- every step of the
  contact fails the balance unless it is tiny, as with the faults the issue injected (a gravity sign in the
  compiled forces only, a Hertz exponent in the force but not in its potential, a sign of the support's damping);
* the reference integrator (DOP853): dry friction on the joint far above gravity, -mu sign(theta'): once theta'
  reaches zero it chatters about it, every step a few round-offs long (a switching right-hand side no
  explicit method can cross).

Without the bound both runs go on for hours; the suite's per-test time limit would name them.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.integrate import modal
from flexbeam.integrate import reference as ref
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import impact_method
from tests.conftest import seed

NO_PROGRESS = re.compile(
    r"no progress at t = (?P<t>\S+) s \((?P<phase>\w+) phase\): (?P<attempts>\d+) step(?: attempt)?s advanced the "
    r"phase (?P<dt>\S+) s from t = (?P<t0>\S+) s"
)


def _stopped(sol) -> re.Match:
    """The failure message of a stalled run, checked against what the run kept."""
    assert sol.status == "failed"
    match = NO_PROGRESS.match(sol.message)
    assert match, sol.message
    t = float(match["t"])
    # what was computed up to the failure is kept: the samples end there, finite
    assert sol.time[-1] == pytest.approx(t, rel=1e-9)
    assert np.all(np.isfinite(sol["theta"]))
    assert float(match["t0"]) + float(match["dt"]) == pytest.approx(t, rel=1e-2)
    return match


def test_modal_integrator_stops_on_forcing_inconsistent_with_the_energy(monkeypatch):
    """The contact phase of the seed impact (4 modes) on doubled modal frequencies: the run stops in that phase at
    its step budget (kernels/src/phase.c: 1e4 attempts plus 4e4 per step bound t_c / 8 of progress; 8.7e4
    attempts, 7.3e-5 s measured) with the steps rejected by the energy balance, instead of crawling through the
    contact at ~2e-9 s per step."""
    of = modal.ModalBasis.of.__func__

    def doubled(cls, system):
        b = of(cls, system)
        return modal.ModalBasis(2.0 * b.omega, b.Psi, b.toM, b.row0, b.inv00, b.nz, b.diagonal)

    monkeypatch.setattr(modal.ModalBasis, "of", classmethod(doubled))
    sol = fb.simulate(seed(model__modes=4), "ccfm")
    match = _stopped(sol)
    assert match["phase"] == "contact" and sol.contacts[0].onset == 0.0
    assert "by the energy balance" in sol.message
    assert int(match["attempts"]) < 10**6


def test_reference_integrator_stops_on_a_chattering_right_hand_side(monkeypatch):
    """Dry friction 1e3 rad/s^2 at the joint (gravity gives 21 rad/s^2): theta' reaches zero within ~1e-3 s of the
    rebound and DOP853's steps collapse to ~1e-14 s there; the phase stops at its step budget
    (integrate/reference.py: 2000 steps plus 100 per 1 / omega_max of progress)."""
    rhs_function = BeamSystem.rhs_function

    def with_friction(self, contacts=None):
        fun, i = rhs_function(self, contacts), self.n + 1  # y[i] = theta', dy[i] = theta''

        def f(t, y):
            dy = fun(t, y)
            dy[i] -= 1e3 * np.sign(y[i])
            return dy

        return f

    monkeypatch.setattr(BeamSystem, "rhs_function", with_friction)
    sol = fb.simulate(seed(model__modes=2, solver__integrator="reference"), "ccfm")
    match = _stopped(sol)
    assert match["phase"] == "free"
    case = seed(model__modes=2)
    system = BeamSystem.from_case(case)
    rate = ref.ReferenceStepper(system).rate(impact_method("ccfm")(system, case).free_phase())
    assert int(match["attempts"]) <= ref.EFFORT_BASE + ref.EFFORT_RATE * rate * float(match["dt"]) + 1
