"""The FE reference on a moving base against the modal model: the shaker case (tests/validation/data/shaker-stop.toml,
0.5 mm at 15 Hz).  The FE works in the base frame with the field (0, -g) - a_O(t) on its elements (fem/element.py,
the field's components; a_O from the case's [base], fem/beam.py FemBeam.field) and books the base's work
-int a_O . (int mu r' dx) dt on its own momentum (fem/outputs.py): its code shares nothing with the modal model's
(the kernels' base_motion.c, the modal field forces)."""

from __future__ import annotations

import numpy as np
import pytest

import flexbeam as fb

SHAKER = "tests/validation/data/shaker-stop.toml"


def test_the_fe_beam_follows_the_shaken_base_as_the_modal_beam_does():
    """The stop 1 m away, 0.03 s (the tip's first half swing): the FE's tip deflection (32 elements) against the
    modal model's at 12 modes to 2e-4 of its largest value (measured 6.7e-5 over 0.2 s), and the FE's energy balance
    with the base's work booked to 1e-7 (measured 2.4e-9 over 0.2 s; without it the base's work is ~the kinetic
    energy)."""
    over = {"solver.t_end": 0.03, "obstacle.centre": [0.3, -1.0], "output.interval": 1e-4}
    fe = fb.simulate(fb.load_case(SHAKER, over), "fem")
    modal = fb.simulate(fb.load_case(SHAKER, {**over, "model.modes": 12}), "ccfm")
    assert fe.status == "success" and not fe.contacts
    tip = modal["tip_deflection"]
    assert np.max(np.abs(tip)) > 5e-4
    error = np.max(np.abs(np.interp(modal.time, fe.time, fe["tip_deflection"]) - tip)) / np.max(np.abs(tip))
    assert error < 2e-4
    assert abs(fe.metrics()["energy_drift_max"]) < 1e-7


@pytest.mark.slow
def test_the_first_impact_on_the_shaken_stop():
    """0.06 s (~25 s of FE): the first impact of the tip on the stop, the FE (32 elements) and the modal model (6
    modes, the case's) agree on its onset to 1e-5 s, 0.015 % of the drive's period (measured 0.050663 s both).  Their
    peak forces do not agree (measured 13.5 N FE, 33.5 N modal at 6 modes) and the later impacts of the cluster
    differ in number and timing: the local dynamics of a tip impact on a stiff sphere."""
    over = {"solver.t_end": 0.06}
    fe = fb.simulate(fb.load_case(SHAKER, over), "fem")
    modal = fb.simulate(fb.load_case(SHAKER, over), "ccfm")
    assert fe.contacts[0].onset == pytest.approx(modal.contacts[0].onset, abs=1e-5)
