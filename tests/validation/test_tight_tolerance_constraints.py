"""Held contacts at tight tolerances: a flexible bar landing flat on two stops (e = 0), held there by CCM's constraints
or IMM's resting contact, converges as ``solver.fast_rtol`` goes to 1e-11.

Two faults stopped it before.  A multiplier is a velocity defect over the step's response ~ h / m_eff, so the state's
round-off puts ~ m_eff eps |x| / h into its nodal values: held to its relative tolerance (1e-7 at fast_rtol <= 1e-9),
every step was rejected down to a step-size underflow, at t = 0 or at the first release.  Its round-off is now told
from its error by its effect on the state (``kernels/src/collocation.c``, multiplier_error).  And when two held pairs
release at one instant (the symmetric landing), the second one's multiplier could start the next phase already
tensile, where no crossing is ever found: a release now ends every held pair whose multiplier it turns tensile
(:meth:`~flexbeam.methods.base.ImpactMethod.contact_transition`); the missed one pulled at -34 N.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_simultaneous import steel_bar_on_stops  # noqa: E402

#: (modes, mu, v_x): the symmetric drop (its two ends release together), and sliding with friction
CASES = [(2, 0.0, 0.0), (2, 0.3, 0.5), (4, 0.3, 0.5)]


def final(method: str, modes: int, mu: float, vx: float, rtol: float) -> tuple[fb.Solution, np.ndarray]:
    """The run over 2 ms at ``fast_rtol`` = rtol (fast_atol = 1e-3 rtol) and its final (q, tip deflection)."""
    case = fb.load_case(
        steel_bar_on_stops(modes=modes, mu=mu, e=0.0, vx=vx).model_dump(),
        {"solver.fast_rtol": rtol, "solver.fast_atol": rtol * 1e-3, "solver.t_end": 2e-3},
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = fb.simulate(case, method)
    assert sol.status == "success", f"fast_rtol {rtol:g}: {sol.message}"
    return sol, np.concatenate([sol.arrays["q"][-1], [sol.arrays["tip_deflection"][-1]]])


@pytest.mark.parametrize("method", ["ccm", "imm"])
@pytest.mark.parametrize(("modes", "mu", "vx"), CASES)
def test_held_contacts_converge_at_tight_tolerances(method, modes, mu, vx):
    """Every run reaches t_end (main failed at fast_rtol 1e-9 and 1e-10 on the first two cases); the final modal
    coordinates and tip deflection at fast_rtol 1e-9 and 1e-10 agree with the 1e-11 run within 2e-14 (10x the largest
    difference measured, 1.1e-15; the values are ~1e-6), and at the default 1e-6 within 1e-10 (measured 7.1e-12):
    convergence, not a run stopped early. At the tight tolerances no held pair's sampled multiplier pulls beyond 1e-4
    N (samples at a located release: measured down to -3.7e-6 N of forces ~1 N; the missed release of the symmetric
    drop pulled at -34 N), and the energy balance closes within 1e-9 (test_energy.py's bound at fast_rtol 1e-10;
    measured <= 1.7e-11)."""
    _, ref = final(method, modes, mu, vx, 1e-11)
    for rtol, bound in ((1e-10, 2e-14), (1e-9, 2e-14), (1e-6, 1e-10)):
        sol, y = final(method, modes, mu, vx, rtol)
        assert np.max(np.abs(y - ref)) < bound, (rtol, np.max(np.abs(y - ref)))
        if rtol < 1e-8:
            assert np.min(sol.arrays["pair_contact_force"]) > -1e-4
            assert sol.energy_drift()[1] < 1e-9
