"""Friction's share of the joint torque with the hub angle prescribed (issue 28, outputs).

With theta(t) given, the ``joint_torque`` output is the joint's reaction: the residual of the theta row of
M z'' = Q + J^T F + Jt^T F_t (kernels/src/rhs.c).  The work it does, int tau theta' dt, must equal the drive's work
W that the integrator books step by step (``drive_work``, kernels/src/bookkeeping.c, whose rates hold friction's
share; its energy balance is checked in test_friction_ccfm.py).  The reaction left out the tangential forces of
CCFM's pairs (slipping: sigma F along Jt; sticking: the multiplier), so their work was missing from int tau theta' dt:
0.1-3 mJ of the drive's 1.4-22 J in the runs below.
"""

from __future__ import annotations

import numpy as np
import pytest

import flexbeam as fb


def work_mismatch(mu: float, rate: float) -> tuple[float, float, set[float]]:
    """(max over the samples of abs(int_0^t tau theta' dt - W(t)), W(t_end), the friction states seen) of the seed
    beam turned at the constant ``rate`` [rad/s] into its sphere for 30 ms, friction mu, sampled every 2 us (the
    trapezoidal rule on those samples)."""
    case = fb.load_case(
        "seed-experiment",
        {
            "drive.kind": "prescribed", "drive.profile": "constant-rate", "drive.spin_rate": rate,
            "initial.rate": rate, "contact.friction": mu, "solver.t_end": 0.03, "solver.sample_step": 2e-6,
            "solver.contact_sample_step": 2e-6,
        },
    )  # fmt: skip
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    a, t = sol.arrays, sol.time
    power = a["joint_torque"] * a["theta_rate"]
    work = np.concatenate(([0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))))
    states = set(np.unique(a["pair_friction_state"]).tolist()) if "pair_friction_state" in a else set()
    return float(np.max(np.abs(work - a["drive_work"]))), float(a["drive_work"][-1]), states


@pytest.mark.parametrize(("mu", "rate"), [(0.0, -2.0), (0.3, -2.0), (0.6, -2.0), (0.3, -0.5)])
def test_the_joint_torque_does_the_drives_work_with_friction(mu, rate):
    """int tau theta' dt equals the booked drive work within 1e-6 of it (the trapezoidal rule's error on 2 us
    samples: measured 0.5-1.0e-7 of W, friction or not; 10x that).  Before friction's share entered the reaction the
    frictional runs missed by 2e-5 to 1.6e-4 of W.  Each frictional run slips and sticks (states 1 and 2)."""
    mismatch, W, states = work_mismatch(mu, rate)
    assert W > 0.0
    assert mismatch <= 1e-6 * W, (mismatch, W)
    if mu > 0.0:
        assert {1.0, 2.0} <= states, states
