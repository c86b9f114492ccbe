"""What the command line prints reaches the terminal as written.

Typer's help and the Rich tables read their texts as Rich markup, where "[s]", "[px]", "[base]", "[rad/s]" or
"[[obstacles]]" look like style tags and vanish: ``flexbeam animate --help`` printed "time window t0,t1 (default:
all)", and a free bar's advice "repeat obstacle in [[obstacles]] with a fixed contact point at each end" lost its
key in the metrics table ("in []").  Each text below is printed as written now (every test fails before).
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from flexbeam.cli import app
from flexbeam.cli.tables import print_calibration, print_metrics


def _flat(text: str) -> str:
    return " ".join(text.split())  # the help's and the tables' wrapping undone


@pytest.mark.parametrize(
    "command, text",
    [
        (["animate", "--help"], "time window t0,t1 [s]"),
        (["animate", "--help"], "frame size WIDTHxHEIGHT [px]"),
        (["animate", "--help"], "flexbeam[video]"),
        (["bifurcation", "--help"], "with a [base] shaken by harmonics"),
        (["calibrate", "--help"], "velocity columns [s, N, m/s]"),
        (["frequencies", "--help"], "hub spin rate Omega [rad/s]"),
        (["--help"], "Natural frequencies [rad/s]"),
        # what compare writes and prints (it shared run's "result.nc, summary.json, plots" and "one JSON object")
        (["compare", "--help"], "directory for comparison.json, comparison.md and the figures"),
        (["compare", "--help"], "as a JSON list"),
        (["frequencies", "--help"], "spin, the first-order and zeroth-order frequencies [rad/s]"),
    ],
)
def test_help_prints_units_and_keys_as_written(command, text):
    r = CliRunner().invoke(app, command)
    assert r.exit_code == 0, r.output
    assert text in _flat(r.output), r.output


def test_metrics_table_prints_a_message_as_written(capsys):
    advice = "repeat obstacle in [[obstacles]] with a fixed contact point at each end"
    print_metrics({"message": advice, "peak_force": 1.0, "[unit]": "x"}, "my[case].toml (ccm)")
    out = _flat(capsys.readouterr().out.replace("│", " "))
    assert advice in out and "[unit]" in out and "my[case].toml (ccm)" in out, out


def test_calibration_report_prints_its_texts_as_written(capsys):
    report = {
        "parameters": {
            "contact.stiffness": {"at_bound": False, "initial": 1.0, "value": 2.0, "uncertainty": 0.1, "units": "[N/m]"}
        },
        "residuals": {"sigma": 1.0, "dof": 3},
        "nfev": 5,
        "message": "converged [ftol]",
    }
    print_calibration(report, "case [a]")
    out = _flat(capsys.readouterr().out.replace("│", " "))
    assert "[N/m]" in out and "converged [ftol]" in out and "case [a]: calibration" in out, out
