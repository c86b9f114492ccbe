"""The explicit reference integrator refuses structural damping that would make it stiff beyond use.

A run on the reference integrator (scipy's DOP853, ``solver.integrator = "reference"``; CCM and IMM on a compliant
support, and theta(t) prescribed on one, took it by default before 2026-11-27) has its step bounded by the fastest
root of the linearised modes; Kelvin-Voigt damping c makes a high mode's fastest root about c w^2.  A fuzzed case
(c = 6.4 s on the calibrated seed experiment) put it 7e5 times the fastest frequency: a run of hours.  It is refused
in one line naming the field (exit 2), while moderate damping runs.
"""

from __future__ import annotations

import pytest

import flexbeam as fb
from flexbeam.cli import main


def test_damping_too_stiff_for_the_reference_integrator_is_refused_in_one_line(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["run", "seed-experiment-calibrated", "--set", "beam.kelvin_voigt=6.4", "--set", "solver.t_end=0.002",
              "--set", "solver.integrator=reference", "--method", "imm"])  # fmt: skip
    err = capsys.readouterr().err.strip().splitlines()
    assert exit_.value.code == 2 and len(err) == 1 and err[0].startswith("error: beam.kelvin_voigt:")


def test_moderate_damping_runs_on_the_reference_integrator():
    """c = 1e-7 s (the highest of the 12 modes' damping ratios ~0.03): the same case runs to its end."""
    case = fb.load_case("seed-experiment-calibrated", {"beam.kelvin_voigt": 1e-7, "solver.t_end": 0.002,
                                                        "solver.integrator": "reference"})  # fmt: skip
    sol = fb.simulate(case, "imm")
    assert sol.status == "success" and "DOP853" in sol.provenance["integrator"]
