"""Energy bookkeeping: T + V_e + V_g + U_c (+ E_d - W with damping or a drive) is conserved.

At the default fast_rtol = 1e-6 the relative drift is the integrator's error: measured up to 6.2e-7 (the full seed
run, 12 modes, 0.1 s; 1.9e-6 before each step's energy balance entered the step control), 5.5e-7 on the reduced
runs; bound 1e-5 (16x; issue 9's target is < 1e-6).  That it is integration error and not bookkeeping shows at
fast_rtol = 1e-10, where the drift falls to <= 6e-11 on every run here; bound 1e-9.
"""

from __future__ import annotations

import pytest

import flexbeam as fb
from flexbeam.results.solution import Solution
from tests.conftest import seed

TIGHT = {"solver__fast_rtol": 1e-10, "solver__fast_atol": 1e-13}
DEFAULT_DRIFT, TIGHT_DRIFT = 1e-5, 1e-9


def _drifts(**case) -> list[Solution]:
    """The run at the default and at the tight tolerance, each within its drift bound."""
    out = []
    for extra, bound in (({}, DEFAULT_DRIFT), (TIGHT, TIGHT_DRIFT)):
        sol = fb.simulate(seed(**case, **extra))
        assert sol.status == "success"
        end, worst = sol.energy_drift()
        assert abs(end) < bound and worst < bound, (extra, end, worst)
        out.append(sol)
    return out


def test_seed_run_without_damping_conserves_energy_reduced():
    """Reduced form for CI: 4 modes, first contact and some flight (the full run is `slow`)."""
    for sol in _drifts(model__modes=4, contact__law="hertz", solver__t_end=0.01):
        assert sol.contacts, "the run must include an impact"


@pytest.mark.slow
def test_seed_run_without_damping_conserves_energy():
    for sol in _drifts(contact__law="hertz"):
        assert sol.contacts, "the run must include an impact"


def test_damped_run_books_the_dissipated_energy():
    """With damping the energy lost equals the dissipated integral: total stays constant."""
    for sol in _drifts(model__modes=2, contact__law="hunt_crossley", contact__restitution=0.5, solver__t_end=0.003):
        assert sol["dissipated_energy"][-1] > 1e-3 * sol["kinetic_energy"][0]


def test_torque_drive_work_is_booked():
    for sol in _drifts(
        model__modes=2,
        drive__kind="torque",
        drive__torque=-2.0,
        initial__kind="state",
        initial__angle=0.3,
        initial__rate=0.0,
        contact__law="hertz",
        solver__t_end=0.2,
    ):
        assert abs(sol["drive_work"][-1]) > 0.01
