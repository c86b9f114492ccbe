"""Energy bookkeeping: undamped runs conserve T + V_e + V_g + U_c exactly (to tolerance)."""

from __future__ import annotations

import pytest

import flexbeam as fb
from tests.conftest import seed


def _check(case, tol):
    sol = fb.simulate(case)
    assert sol.status == "success"
    assert sol.contacts, "the run must include an impact"
    end, worst = sol.energy_drift()
    assert abs(end) < tol and worst < tol


def test_seed_run_without_damping_conserves_energy_reduced():
    """Reduced form for CI: 4 modes, first contact and some flight (the full run is `slow`)."""
    _check(seed(model__modes=4, contact__law="hertz", solver__t_end=0.01), 1e-6)


@pytest.mark.slow
def test_seed_run_without_damping_conserves_energy():
    _check(seed(contact__law="hertz"), 1e-6)


def test_damped_run_books_the_dissipated_energy():
    """With damping the energy lost equals the dissipated integral: total stays constant."""
    sol = fb.simulate(seed(model__modes=2, contact__law="hunt_crossley", contact__restitution=0.5,
                           solver__t_end=0.003))
    assert sol["dissipated_energy"][-1] > 1e-3 * sol["kinetic_energy"][0]
    assert abs(sol.energy_drift()[1]) < 1e-6


def test_torque_drive_work_is_booked():
    case = seed(model__modes=2, drive__kind="torque", drive__torque=-2.0, initial__kind="state",
                initial__angle=0.3, initial__rate=0.0, contact__law="hertz", solver__t_end=0.2)
    sol = fb.simulate(case)
    assert abs(sol["drive_work"][-1]) > 0.01
    assert abs(sol.energy_drift()[1]) < 1e-6
