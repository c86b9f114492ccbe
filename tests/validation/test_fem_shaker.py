"""FE vs modal on the shaker case in a periodic impacting regime (issue 27).

The cantilever of tests/validation/data/shaker-stop.toml (assumed numbers: a steel strip, 0.3 m, first mode ~18 Hz,
on a base shaken 0.5 mm at 15 Hz, a steel sphere 1 mm under its tip) with Kelvin-Voigt damping c = 7e-4 s (the
first mode's damping ratio c w_1 / 2 = 4 %) settles into a period-1 orbit with two impacts per drive period: a main
one (~19.4 N) and a smaller one 3 ms later (~2.8 N).  The modal model at 24 modes (CCFM) and the independent FE
reference at 16 elements are run for 30 periods from rest, and every impact of the last 20 is compared.  Issue 27's
targets: the impacts' phases of the drive within 1 % of the period, their peak forces within 3 %.  Measured: the
same 40 impacts, phases within 1.8e-5 of the period, peak forces within 0.41 % (the main impacts' 0.19 %); and over
the transient before (the first 20 periods) as closely.  At the case's own six modes the modal model is not
converged here: three impacts per period, the main one's peak 18 % high (12 modes: 2.3 %).
"""

from __future__ import annotations

import numpy as np
import pytest

import flexbeam as fb

SHAKER = "tests/validation/data/shaker-stop.toml"
F_DRIVE, PERIODS, COMPARED = 15.0, 30, 20


def impacts(method: str, **overrides) -> np.ndarray:
    """(onset [s], drive phase, peak force [N]) of every contact record of the damped shaker over 30 periods."""
    values = {"solver.t_end": PERIODS / F_DRIVE, "beam.kelvin_voigt": 7e-4}
    values.update({k.replace("__", "."): v for k, v in overrides.items()})
    sol = fb.simulate(fb.load_case(SHAKER, values), method)
    assert sol.status == "success", sol.message
    return np.array([(e["onset"], e["drive_phase"], e["peak_force"]) for e in sol.metrics()["events"]])


@pytest.mark.slow
@pytest.mark.timeout(1800)  # the FE's 2 s of contacts at a microsecond step: ~4 min on the 2-core machine
def test_fe_and_modal_agree_on_the_periodic_impacts_of_the_shaker():
    """The last 20 periods (module docstring): the same impacts, each one's phase within 1 % of the period and its
    peak within 3 % (the issue's targets); the regime is periodic there (each period's main impact within 1 % of the
    period and 3 % of the force of the next: measured 6e-4 and 1.1 %, the orbit settling at the window's start)."""
    fem = impacts("fem", fem__elements=16)
    modal = impacts("ccfm", model__modes=24)
    start = (PERIODS - COMPARED) / F_DRIVE
    fem, modal = fem[fem[:, 0] >= start], modal[modal[:, 0] >= start]
    assert len(fem) == len(modal) >= COMPARED
    assert np.max(np.abs(fem[:, 0] - modal[:, 0])) * F_DRIVE <= 0.01
    assert np.max(np.abs(fem[:, 2] / modal[:, 2] - 1.0)) <= 0.03
    main = modal[modal[:, 2] > 0.5 * np.max(modal[:, 2])]
    assert len(main) == COMPARED  # one main impact per period
    assert np.max(np.abs(np.diff(main[:, 1]))) <= 0.01 and np.max(np.abs(np.diff(main[:, 2]) / main[1:, 2])) <= 0.03
