"""The FEM Solution has the modal path's shape, log, status and provenance."""

from __future__ import annotations

import math

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.errors import ParameterError
from flexbeam.fem import FemBeam, build_mesh, simulate_fem
from flexbeam.model.system import SUPPORT_COLUMNS
from flexbeam.results.records import CENTRE_VARIABLES, FRICTION_VARIABLES, PAIR_VARIABLES, VARIABLES
from tests.fem.cases import seed


def solution_case():
    return seed(solver__t_end=1e-3, fem__elements=16)


@pytest.fixture(scope="module")
def solution():
    return simulate_fem(solution_case())


def test_arrays_match_the_modal_contract(solution):
    sol = solution
    m = sol.time.size
    # one rigid obstacle, no friction, a beam on a joint
    no_pairs = set(PAIR_VARIABLES) | set(FRICTION_VARIABLES) | set(CENTRE_VARIABLES)
    assert set(sol.arrays) == set(VARIABLES) - set(SUPPORT_COLUMNS) - no_pairs
    assert sol["q"].shape == (m, 0) and sol["q_rate"].shape == (m, 0)
    assert sol["measuring_velocity"].shape == (m, 3)
    for name in sol.arrays:
        if name not in ("q", "q_rate", "measuring_velocity"):
            assert sol[name].shape == (m,), name
        assert np.all(np.isfinite(sol[name])), name
    assert np.all(np.diff(sol.time) >= 0.0)
    assert set(sol.phase) == {"free", "contact"}
    assert sol.status == "success"
    # the contact point is the first measuring point (x = x_P): its velocity along e2 starts at v0
    assert math.isclose(sol["measuring_velocity"][0, 0], -0.4, rel_tol=1e-9)
    assert math.isclose(sol["normal_velocity"][0], -0.4, rel_tol=1e-12)
    assert sol["gap"][0] == 0.0


def test_contact_log_and_metrics(solution):
    sol = solution
    assert len(sol.contacts) == 1
    ev = sol.contacts[0]
    assert ev.onset == 0.0 and 5e-4 < ev.end < 7e-4
    assert ev.velocity_before == -0.4 and 0.0 < ev.velocity_after < 0.4
    assert ev.peak_force > 900.0 and ev.onset < ev.peak_time < ev.end
    assert ev.impulse > 0.0 and ev.energy_after < ev.energy_before
    m = sol.metrics()
    assert m["method"] == "fem"
    assert m["peak_force"] == pytest.approx(ev.peak_force)
    assert m["contact_duration"] == pytest.approx(ev.end - ev.onset)
    # the impulse lies between the rigid rod's perfectly plastic and perfectly elastic values, m_eff v0 (1 + e)
    # with e = 0 and 1, m_eff = J_O / x_P^2 (0.244 and 0.488 N s; measured 0.328)
    b, x_p = solution_case().beam, solution_case().contact.position
    m_eff = b.line_density * b.length**3 / 3.0 / x_p**2
    assert m_eff * 0.4 < m["impulse"] < 2.0 * m_eff * 0.4
    assert m["steps"] > 200 and m["nfev"] >= m["steps"] and m["wall_time"] > 0.0


def test_provenance_and_export(solution):
    p = solution.provenance
    assert p["method"] == "fem" and p["elements"] == 16 and p["contact_node"] == 13
    assert "generalized-alpha" in p["scheme"]
    assert p["rho_inf"] == 0.9
    ds = solution.to_xarray()
    assert ds["contact_force"].attrs["units"] == "N"
    assert ds.sizes["mode"] == 0 and ds.sizes["contact"] == 1


def test_simulate_dispatches_to_fem():
    sol = fb.simulate(seed(solver__t_end=2e-4, fem__elements=4), method="fem")
    assert sol.method == "fem"


def test_mesh_has_a_node_at_the_contact_point():
    x = build_mesh(0.7, 32, 0.585)
    assert x.size == 33 and np.any(x == 0.585)
    assert np.all(np.diff(x) > 0.0)
    assert build_mesh(0.7, 1, 0.3).size == 3  # raised to two elements
    assert np.allclose(build_mesh(0.7, 4, 0.7), np.linspace(0.0, 0.7, 5))
    beam = FemBeam.from_case(seed(fem__elements=10))
    assert beam.x_nodes[beam.pnode] == 0.585


def test_bad_input_names_the_field():
    with pytest.raises(ParameterError, match="fem.elements"):
        seed(fem__elements=0)
    with pytest.raises(ParameterError, match="fem.rho_inf"):
        seed(fem__rho_inf=1.5)
    with pytest.raises(ParameterError, match="model.gravity"):
        simulate_fem(seed(initial__kind="release", model__gravity=0.0))


def test_release_from_given_angle_starts_in_static_equilibrium():
    case = seed(initial__kind="release", initial__release_angle=0.0, solver__t_end=2e-4, fem__elements=16)
    sol = simulate_fem(case)
    b = case.beam
    sag = b.line_density * 9.81 * b.length**4 / (8.0 * b.bending_stiffness)  # uniform load, clamped
    assert sol["tip_deflection"][0] == pytest.approx(-sag, rel=1e-4)
    assert sol["theta_rate"][0] == 0.0 and sol["kinetic_energy"][0] == 0.0
    assert sol.provenance["release_angle"] == 0.0


@pytest.mark.slow
def test_release_angle_is_solved_by_shooting():
    case = seed(initial__kind="release", solver__t_end=0.04, fem__elements=16)
    sol = simulate_fem(case)
    assert sol.contacts and sol.contacts[0].velocity_before == pytest.approx(-0.4, rel=1e-6)


def test_progress_is_reported():
    times: list[float] = []
    simulate_fem(seed(solver__t_end=3e-4, fem__elements=4), progress=times.append)
    assert times and times == sorted(times) and times[-1] <= 3e-4
