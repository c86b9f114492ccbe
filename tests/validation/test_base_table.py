"""A base motion given as a table (``base.table``): rows (t, x, y), or a CSV file of them, interpolated by the
not-a-knot C2 cubic spline, so that a_O is continuous and the jerk (constant between rows) exists for the base's
work; the exponential integrator's steps end at the rows.

* The shaker's harmonic (0.5 mm at 15 Hz) sampled at 50 and 100 rows per period reproduces the harmonic run: the
  tip far from the stop to the spline's interpolation error, falling with the row spacing; with the stop, every
  contact's onset and peak force.
* A CSV file next to the case gives the same case as the rows inline.
* Bad input: one line naming ``base.table``, exit 2.
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
import tomli_w

import flexbeam as fb

SHAKER = "tests/validation/data/shaker-stop.toml"
F, A = 15.0, 5e-4  # the shaker's harmonic: 0.5 mm at 15 Hz along y


def sampled(per_period: int, t_end: float) -> list[list[float]]:
    """The shaker's harmonic y = A sin(2 pi F t) at ``per_period`` rows a period, from before 0 to past t_end."""
    dt = 1.0 / F / per_period
    t = np.arange(-3, math.ceil(t_end / dt) + 4) * dt
    return [[float(s), 0.0, float(A * math.sin(2.0 * math.pi * F * s))] for s in t]


def table_run(per_period: int, over: dict) -> fb.Solution:
    t_end = over["solver.t_end"]
    return fb.simulate(fb.load_case(SHAKER, {**over, "base.harmonics": [], "base.table": sampled(per_period, t_end)}))


def test_a_sampled_harmonic_reproduces_the_harmonic_run_far_from_the_stop():
    """The stop moved 1 m away, 0.3 s (4.5 periods): the tip deflection of the tables' runs against the harmonic
    run's, relative to its largest value, below 5e-6 at 50 rows a period and 4x smaller at 100 (measured 5.5e-7 and
    8.2e-8: the spline's second derivative errs by (w h)^2 / 12 at the rows and by as much the other way between them,
    so that the error the slow modes feel falls faster than h^2); the energy balance (the jerk constant within each
    step) to 1e-8 (measured 3e-10)."""
    over = {"solver.t_end": 0.3, "obstacle.centre": [0.3, -1.0]}
    harmonic = fb.simulate(fb.load_case(SHAKER, over))
    tip = harmonic["tip_deflection"]
    errors = {}
    for per in (50, 100):
        sol = table_run(per, over)
        assert sol.status == "success" and not sol.contacts
        assert sol.stats["steps"] <= 1.05 * per * F * 0.3 + 10  # one step per row (harmonic: 71 steps)
        errors[per] = float(np.max(np.abs(sol["tip_deflection"] - tip)) / np.max(np.abs(tip)))
        assert abs(sol.metrics()["energy_drift_max"]) < 1e-8
    assert errors[50] < 5e-6
    assert errors[100] < errors[50] / 4.0


def test_a_sampled_harmonic_reproduces_the_impacts():
    """The shaker on its stop, 0.3 s, 50 rows a period: the same 24 contacts; the first cluster of impacts (the ten
    before 0.06 s, before their sensitivity to the state amplifies the differences) to 2e-7 s in onset and, in peak
    force, to the spline's pointwise acceleration error (w h)^2 / 12 = 1.3e-3 (measured 1.1e-7 s and 2.7e-4); the
    energy balance to 1e-5 (measured 8e-7)."""
    over = {"solver.t_end": 0.3}
    harmonic, table = fb.simulate(fb.load_case(SHAKER, over)), table_run(50, over)
    assert len(table.contacts) == len(harmonic.contacts) > 20
    first = [k for k, c in enumerate(harmonic.contacts) if c.onset < 0.06]
    assert len(first) == 10
    for k in first:
        a, b = table.contacts[k], harmonic.contacts[k]
        assert a.onset == pytest.approx(b.onset, abs=2e-7)
        assert a.peak_force == pytest.approx(b.peak_force, rel=(2.0 * math.pi / 50) ** 2 / 12.0)
    assert abs(table.metrics()["energy_drift_max"]) < 1e-5


def test_a_csv_file_beside_the_case(tmp_path):
    rows = sampled(20, 0.05)
    (tmp_path / "motion.csv").write_text("t,x,y\n# the shaker\n" + "".join(f"{t!r},{x!r},{y!r}\n" for t, x, y in rows))
    data = fb.load_case(SHAKER, {"solver.t_end": 0.05}).model_dump(mode="json", exclude_none=True)
    data["base"] = {"table": "motion.csv"}
    (tmp_path / "case.toml").write_text(tomli_w.dumps(data), encoding="utf-8")
    case = fb.load_case(tmp_path / "case.toml")
    inline = fb.load_case(SHAKER, {"solver.t_end": 0.05, "base.table": rows, "base.harmonics": []})
    assert case.base.moving and case.base.table == inline.base.table


def _bad(rows):
    return {"base.harmonics": [], "base.table": rows, "solver.t_end": 0.1}


GOOD = [[0.0, 0.0, 0.0], [0.05, 0.0, 1e-3], [0.1, 0.0, 0.0], [0.15, 0.0, -1e-3]]


@pytest.mark.parametrize(
    ("rows", "fragment"),
    [
        ([GOOD[0], GOOD[2], GOOD[1], GOOD[3]], "the times must increase"),
        ([GOOD[0], GOOD[1], [0.1, 0.0, math.nan], GOOD[3]], "row 2: must be finite"),
        (GOOD[:3], "at least 4 rows"),
        ([[t - 0.05, x, y] for t, x, y in GOOD], "covers t = -0.05 .. 0.1 s; the run needs 0 .. solver.t_end = 0.1"),
        ([[0.0, 0.0], *GOOD[1:]], "row 0: expected three numbers"),
    ],
)
def test_bad_tables_are_one_line_naming_the_field(tmp_path, rows, fragment):
    with pytest.raises(ValueError, match=r"^base\.table: "):
        fb.load_case(SHAKER, _bad(rows))
    data = fb.load_case(SHAKER).model_dump(mode="json", exclude_none=True)
    data["base"] = {"table": [[str(v) if isinstance(v, float) and math.isnan(v) else v for v in r] for r in rows]}
    data["solver"]["t_end"] = 0.1
    path = tmp_path / "bad.toml"
    text = tomli_w.dumps(data).replace('"nan"', "nan")
    path.write_text(text, encoding="utf-8")
    r = subprocess.run([sys.executable, "-m", "flexbeam.cli", "run", str(path), "-o", str(tmp_path / "out")],
                       capture_output=True, text=True, timeout=600)  # fmt: skip
    assert r.returncode == 2 and r.stdout == "" and "Traceback" not in r.stderr, r.stderr
    assert len(r.stderr.splitlines()) == 1 and r.stderr.startswith("error: base.table: ") and fragment in r.stderr


def test_a_missing_csv_file_is_one_line():
    with pytest.raises(ValueError, match=r"^base\.table: cannot read"):
        fb.load_case(SHAKER, {"base.table": "/nonexistent/motion.csv"})
