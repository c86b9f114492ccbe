"""Bad input through the real CLI: one line on stderr naming the field, exit code 2, no traceback.

Every case here is rejected while the case is read, before any simulation, so each run
is a bare interpreter start (< 1 s).
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import tomli_w

import flexbeam as fb


def flexbeam(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "flexbeam.cli", *args], capture_output=True, text=True, timeout=600)


def assert_one_line_error(r: subprocess.CompletedProcess, field: str, *fragments: str) -> str:
    """Exit 2, nothing on stdout, exactly one stderr line that starts with the field."""
    assert "Traceback" not in r.stderr, r.stderr
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1, r.stderr
    line = lines[0]
    # the field first ("error: FIELD: ..."), so that grep finds it
    assert line.startswith(f"error: {field}"), line
    for fragment in fragments:
        assert fragment in line, line
    return line


def seed_data() -> dict[str, Any]:
    """The seed case as the plain dict a TOML file holds."""
    return fb.load_case("seed-experiment").model_dump(mode="json", exclude_none=True)


def write_toml(path: Path, data: dict[str, Any]) -> Path:
    path.write_text(tomli_w.dumps(data), encoding="utf-8")
    return path


# (--set KEY=VALUE, field named first, what the line must also say: the allowed range)
SET_CASES = [
    # not finite: inf, -inf (TOML spells them inf / +inf / -inf)
    ("beam.youngs_modulus=inf", "beam.youngs_modulus", "finite"),
    ("beam.youngs_modulus=+inf", "beam.youngs_modulus", "finite"),
    ("beam.youngs_modulus=-inf", "beam.youngs_modulus", "greater than 0"),
    ("contact.position=inf", "contact.position", "finite"),
    ("initial.impact_velocity=-inf", "initial.impact_velocity", "finite"),
    ("drive.torque=-inf", "drive.torque", "finite"),
    ("solver.t_end=inf", "solver.t_end", "finite"),
    # t_end <= 0
    ("solver.t_end=0", "solver.t_end", "greater than 0"),
    ("solver.t_end=-0.01", "solver.t_end", "greater than 0"),
    # zero or negative where the field must be positive
    ("contact.stiffness=0", "contact.stiffness", "greater than 0"),
    ("contact.stiffness=-1e9", "contact.stiffness", "greater than 0"),
    ("beam.length=0", "beam.length", "greater than 0"),
    ("beam.density=0", "beam.density", "greater than 0"),
    ("beam.radius=0", "beam.radius", "greater than 0"),
    ("beam.youngs_modulus=0", "beam.youngs_modulus", "greater than 0"),
    ("obstacle.youngs_modulus=-1", "obstacle.youngs_modulus", "greater than 0"),
    ("obstacle.radius=0", "obstacle.radius", "> 0"),  # a point obstacle's gap never closes
    ("solver.sample_step=0", "solver.sample_step", "greater than 0"),
    ("solver.contact_sample_step=0", "solver.contact_sample_step", "greater than 0"),
    # the output interval: in (0, solver.t_end]
    ("output.interval=0", "output.interval", "must be in 0 < output.interval <= solver.t_end"),
    ("output.interval=-1e-3", "output.interval", "must be in 0 < output.interval <= solver.t_end"),
    # NaN, inf and text were named without the range ("must be a finite number", "Input should be a valid number");
    # inf's expected text was "finite" before
    ("output.interval=nan", "output.interval", "must be in 0 < output.interval <= solver.t_end"),
    ("output.interval=abc", "output.interval", "must be in 0 < output.interval <= solver.t_end"),
    ("output.interval=inf", "output.interval", "must be in 0 < output.interval <= solver.t_end"),
    ("output.interval=0.5", "output.interval", "allowed: 0 < output.interval <= solver.t_end = 0.1 s"),
    ("solver.max_step=0", "solver.max_step", "greater than 0"),
    ("solver.rtol=0", "solver.rtol", "greater than 0"),
    ("solver.fast_atol=0", "solver.fast_atol", "greater than 0"),
    ("solver.max_contacts=0", "solver.max_contacts", "greater than or equal to 1"),
    ("fem.elements=0", "fem.elements", "greater than or equal to 1"),
    ("fem.time_step=0", "fem.time_step", "greater than 0"),
    ("drive.spin_up_time=0", "drive.spin_up_time", "greater than 0"),
    ("hub.inertia=-1", "hub.inertia", "greater than or equal to 0"),
    # the beam's structural damping (issue 27)
    ("beam.kelvin_voigt=-1e-5", "beam.kelvin_voigt", "greater than or equal to 0"),
    ("beam.kelvin_voigt=1e300", "beam.kelvin_voigt", "less than or equal to 1000"),
    ("beam.viscous_damping=1e300", "beam.viscous_damping", "less than or equal to 1000000000"),
    ("beam.viscous_damping=-0.1", "beam.viscous_damping", "greater than or equal to 0"),
    ("beam.viscous_damping=inf", "beam.viscous_damping", "finite"),
    ("model.gravity=-9.81", "model.gravity", "greater than or equal to 0"),
    ("beam.poisson_ratio=-1", "beam.poisson_ratio", "greater than -1"),
    ("model.quadrature_points=3", "model.quadrature_points", ">= model.modes + 1"),
    # found by the schema fuzz (tests/test_fuzz_case.py): values that overflowed, divided by zero or hung a run
    ("beam.radius=1e300", "beam.radius", "section area S of inf"),
    ("beam.radius=1e-300", "beam.radius", "section area S of 0"),
    ("hub.radius=1e300", "hub.radius", "less than or equal to 1000"),
    ("obstacle.radius=1e-300", "obstacle.radius", "at least 1e-06 m"),
    ("model.gravity=1e300", "model.gravity", "less than or equal to 10000"),
    ("initial.angle=1e300", "initial.angle", "less than or equal to 1000"),
    ("initial.impact_velocity=nan", "initial.impact_velocity", "finite"),
    ("contact.position=5e-324", "initial.impact_velocity", "needs a hub rate above 10000 rad/s"),
    # P on the joint: the position is the cause, and no rate would do (blamed initial.impact_velocity before)
    ("contact.position=0", "contact.position", "no hub rate gives initial.impact_velocity = -0.4 m/s"),
    ("obstacle.youngs_modulus=5e-324", "obstacle.youngs_modulus", "Hertz contact stiffness of 0"),
    ("beam.density=1e300", "beam.density", "less than or equal to 1000000"),
    # true or false where a number belongs (pydantic's lax mode read true as 1: a friction coefficient of 1, one mode)
    ("contact.friction=true", "contact.friction", "must be a number, not true or false"),
    ("model.modes=true", "model.modes", "must be a number, not true or false"),
    ("solver.t_end=false", "solver.t_end", "must be a number, not true or false"),
    ("output.measuring_points=[0.1, true]", "output.measuring_points", "must be a number, not true or false"),
    # the axial modes
    ("model.axial_modes=-1", "model.axial_modes", "greater than or equal to 0"),
    ("model.axial_modes=53", "model.axial_modes", "model.modes + model.axial_modes must be at most 64"),
    # a field bounded on both sides names its whole range (pydantic names the side that failed alone: a negative
    # restitution said "greater than or equal to 0", a sphere's negative radius not that 1000 m is the most)
    ("contact.restitution=-1", "contact.restitution", "(got -1); allowed range [0, 1]"),
    ("contact.restitution=1.5", "contact.restitution", "(got 1.5); allowed range [0, 1]"),
    ("obstacle.radius=-1", "obstacle.radius", "allowed range [0, 1000]"),
    ("model.modes=65", "model.modes", "allowed range [0, 64]"),
    ("beam.poisson_ratio=0.6", "beam.poisson_ratio", "allowed range (-1, 0.5)"),
    ("initial.axial_displacement=[1e-6]", "initial.axial_displacement", "1 values for model.axial_modes = 0"),
    # a value of the wrong shape says what the field holds (pydantic said "Input should be a valid tuple" only)
    ("obstacle.centre=0.3", "obstacle.centre", "expected a list of 2 numbers, obstacle centre [m]"),
    ("initial.modal_velocity=3", "initial.modal_velocity", "expected initial modal velocities"),
    # an exponent without a stiffness (Hertz theory's 1.5 replaced it without a word)
    ("contact.exponent=1.4", "contact.exponent", "1.4 needs a stiffness K [N/m^n] (contact.stiffness)"),
    # a finite-element step longer than the run (two steps reported a "success" at 5x the peak)
    ("fem.time_step=1", "fem.time_step", "longer than the run; allowed: 0 < fem.time_step <= solver.t_end"),
]


@pytest.mark.parametrize(
    ("case", "assignments", "field", "allowed"),
    [
        ("seed-experiment", ["model.axial_modes=4", "model.coupling=zeroth-order"], "model.axial_modes",
         "need model.coupling = 'first-order'"),
        ("rod-end", ["model.axial_modes=61"], "model.axial_modes", "at most 62 for a free beam"),
        ("tests/validation/data/shaker-stop.toml", ["model.axial_modes=4"], "model.axial_modes", "a moving base"),
        ("rod-end", ["initial.kind=impact", "initial.axial_velocity=[0.1]"], "initial.axial_velocity",
         "only for initial.kind = 'state'"),
    ],
)  # fmt: skip
def test_bad_axial_modes(case, assignments, field, allowed):
    """The axial modes with the zeroth-order model, too many of them, on a moving base, or an axial initial value
    without ``initial.kind = "state"``: one line naming the field, exit 2."""
    args = [a for x in assignments for a in ("--set", x)]
    assert_one_line_error(flexbeam("run", case, "--json", *args), field, allowed)


@pytest.mark.parametrize(("assignment", "field", "allowed"), SET_CASES, ids=[c[0] for c in SET_CASES])
def test_bad_value_on_the_command_line(assignment, field, allowed):
    r = flexbeam("run", "seed-experiment", "--json", "--set", assignment)
    assert_one_line_error(r, field, allowed)


@pytest.mark.parametrize(
    ("key", "value"),
    [("obstacle.support.stiffness", 0.0), ("obstacle.support.mass", 0.0), ("obstacle.support.damping", -1.0)],
)
def test_bad_compliant_support(key, value):
    support = {"obstacle.support.stiffness": "3e7", "obstacle.support.mass": "0.02", "obstacle.support.damping": "50"}
    support[key] = repr(value)
    sets = [a for k, v in support.items() for a in ("--set", f"{k}={v}")]
    r = flexbeam("run", "seed-experiment", "--json", *sets)
    assert_one_line_error(r, key, "greater than")


@pytest.mark.parametrize("law", ["flores", "gonthier", "carvalho_martins", "kelvin_voigt"])
def test_zero_restitution_with_a_law_whose_damping_is_infinite_there(law):
    r = flexbeam("run", "seed-experiment", "--json", "--set", f"contact.law={law}", "--set", "contact.restitution=0")
    assert_one_line_error(r, "contact.restitution", "(0, 1]", law)


@pytest.mark.parametrize("law", ["flores", "kelvin_voigt"])
def test_zero_restitution_in_a_case_file(tmp_path, law):
    data = seed_data()
    data["contact"].update(law=law, restitution=0.0)
    r = flexbeam("run", str(write_toml(tmp_path / "case.toml", data)), "--json")
    assert_one_line_error(r, "contact.restitution", "(0, 1]")


@pytest.mark.parametrize(
    ("section", "key", "value", "allowed"),
    [
        ("beam", "youngs_modulus", math.inf, "finite"),
        ("beam", "youngs_modulus", -math.inf, "greater than 0"),
        ("solver", "t_end", math.inf, "finite"),
        ("solver", "t_end", 0.0, "greater than 0"),
        ("solver", "t_end", -1.0, "greater than 0"),
        ("contact", "stiffness", 0.0, "greater than 0"),
        ("initial", "impact_velocity", -math.inf, "finite"),
    ],
)
def test_bad_value_in_a_case_file(tmp_path, section, key, value, allowed):
    data = seed_data()
    data[section][key] = value
    path = write_toml(tmp_path / "case.toml", data)
    if math.isinf(value):  # written as TOML's own spelling
        assert f"\n{key} = {'-' if value < 0 else ''}inf\n" in path.read_text()
    assert_one_line_error(flexbeam("run", str(path), "--json"), f"{section}.{key}", allowed)


def test_misspelt_key_in_a_case_file_is_named_before_the_field_it_leaves_missing(tmp_path):
    data = seed_data()
    data["beam"]["lenght"] = data["beam"].pop("length")  # beam.length is now missing too
    r = flexbeam("run", str(write_toml(tmp_path / "case.toml", data)), "--json")
    line = assert_one_line_error(r, "beam.lenght", "did you mean length?")
    assert "missing" not in line


def test_misspelt_key_on_the_command_line_has_the_same_form():
    r = flexbeam("run", "seed-experiment", "--json", "--set", "beam.lenght=0.7")
    assert_one_line_error(r, "beam.lenght", "unknown field, did you mean length?")


@pytest.mark.parametrize(
    ("edit", "field", "hint"),
    [
        (lambda d: d.__setitem__("bem", d.pop("beam")), "bem", "unknown section, did you mean beam?"),
        (
            lambda d: d["obstacle"].__setitem__("suport", d["obstacle"].pop("support")),
            "obstacle.suport",
            "unknown section, did you mean support?",
        ),
        (lambda d: d.__setitem__("solvr", {"t_end": 0.01}), "solvr", "did you mean solver?"),
        # no close match: the known names of the section are listed instead
        (lambda d: d["contact"].__setitem__("zzz", 1.0), "contact.zzz", "contact has: law, position"),
    ],
    ids=["section", "subsection", "extra-section", "no-close-match"],
)
def test_unknown_section_or_key_in_a_case_file(tmp_path, edit, field, hint):
    data = seed_data()
    edit(data)
    r = flexbeam("run", str(write_toml(tmp_path / "case.toml", data)), "--json")
    assert_one_line_error(r, field, hint)


@pytest.mark.parametrize(
    ("text", "where"),
    [
        ('name = "x"\n[beam\nlength = 0.7\n', "line 2"),
        ('name = "x"\n[beam]\nlength = 0.7\nlength = 0.8\n', "line 4"),
        ('name = "x"\n[beam]\nlength = \n', "line 3"),
    ],
    ids=["unclosed-table", "duplicate-key", "missing-value"],
)
def test_malformed_toml(tmp_path, text, where):
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    assert_one_line_error(flexbeam("run", str(path), "--json"), "case", "not valid TOML", where)


def test_missing_case_file(tmp_path):
    assert_one_line_error(flexbeam("run", str(tmp_path / "absent.toml"), "--json"), "case", "cannot read")


def test_a_newline_in_a_quoted_key_stays_on_one_line(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text('name = "x"\n[beam]\n"len\\ngth" = 0.7\n', encoding="utf-8")  # TOML's own escape
    assert_one_line_error(flexbeam("run", str(path), "--json"), "beam.len\\ngth", "did you mean length?")


# [[obstacles]]: one line naming the obstacle's field, exit 2 (the overlap and start-inside checks run when the
# case's contact pairs are set up, before the run)
OBSTACLE_CASES = [
    # a pair with no law: a half-plane has no Hertz default (a cylinder on a plane is a line contact)
    (
        {"kind": "half-plane", "centre": [0.3, -0.05], "normal": [0.0, 1.0], "contact": {"position": 0.3}},
        "obstacles[0].contact.stiffness",
        "required",
    ),
    # a sphere 5 mm from the seed's (placed at [0.585, -0.0245], radius 10 mm)
    ({"kind": "sphere", "radius": 0.01, "centre": [0.59, -0.0245]}, "obstacles[0].centre", "overlaps obstacle"),
    # the beam's lower surface at x = 0.3 is at y = -0.0145: a sphere reaching 1 mm above it
    (
        {"kind": "sphere", "radius": 0.01, "centre": [0.3, -0.0235], "contact": {"position": 0.3}},
        "obstacles[0].centre",
        "inside this obstacle",
    ),
    ({"kind": "sphere", "radius": 0.01, "centre": [0.3, -0.03], "contact": {"position": 0.9}}, "obstacles[0]", "0.7"),
    (
        {
            "kind": "half-plane",
            "centre": [0.3, -0.03],
            "normal": [0.0, 1.0],
            "contact": {"position": 0.3, "stiffness": 1e9},
        },
        "obstacles[0].centre",
        "overlaps obstacle",
    ),
    # the entry's own fields are named by index, as --set takes them (not "obstacles.0.centre")
    ({"kind": "sphere", "radius": 0.01}, "obstacles[0].centre", "required field is missing"),
    (
        {"kind": "half-plane", "centre": [0.3, -0.03], "normal": [1.0, 1.0], "contact": {"stiffness": 1e9}},
        "obstacles[0].normal",
        "unit vector",
    ),
    ({"kind": "sphere", "radius": 0.0, "centre": [0.3, -0.03]}, "obstacles[0].radius", "> 0 m"),
    (
        {"kind": "sphere", "radius": 0.01, "centre": [0.3, -0.03], "contact": {"postion": 0.3}},
        "obstacles[0].contact.postion",
        "did you mean position?",
    ),
    # friction on a pair with no normal law (issue 28): the half-plane's law is required first
    (
        {
            "kind": "half-plane",
            "centre": [0.3, -0.05],
            "normal": [0.0, 1.0],
            "contact": {"position": 0.3, "friction": 0.3},
        },
        "obstacles[0].contact.stiffness",
        "required",
    ),
    # a pair's own friction law (issue 28)
    (
        {"kind": "sphere", "radius": 0.01, "centre": [0.3, -0.03], "contact": {"friction_model": "viscous"}},
        "obstacles[0].contact.friction_model",
        "coulomb",
    ),
    (
        {"kind": "sphere", "radius": 0.01, "centre": [0.3, -0.03], "contact": {"friction_velocity": 0.0}},
        "obstacles[0].contact.friction_velocity",
        "0",
    ),
]


@pytest.mark.parametrize("obstacle, field, fragment", OBSTACLE_CASES)
def test_bad_obstacle_in_a_case_file(tmp_path, obstacle, field, fragment):
    data = seed_data()
    data["obstacles"] = [obstacle]
    r = flexbeam("run", str(write_toml(tmp_path / "case.toml", data)), "--json")
    assert_one_line_error(r, field, fragment)


def test_more_than_seven_obstacles(tmp_path):
    data = seed_data()
    data["obstacles"] = [{"kind": "sphere", "radius": 0.001, "centre": [0.05 * k, -0.03]} for k in range(1, 9)]
    assert_one_line_error(flexbeam("run", str(write_toml(tmp_path / "c.toml", data)), "--json"), "obstacles", "7")


# the start overlap, the memory estimate and the slender-beam range (issue 23): refused before the run, one line
@pytest.mark.parametrize(
    "case, assignment, field",
    [
        ("two-stops", "obstacles[0].centre=[0.585,0.0]", "obstacles[0].centre"),  # the upper stop inside the beam
        ("seed-experiment", "obstacle.centre=[0.585,0.0]", "obstacle.centre"),  # deep inside the hemisphere
    ],
)
def test_an_obstacle_overlapping_the_beam_at_the_start(case, assignment, field):
    """The sphere's centre on the beam's centre line: it reaches r_s + c = 0.01 + 0.0145 m into the beam."""
    r = flexbeam("run", case, "--json", "--set", assignment)
    assert_one_line_error(r, field, "the beam starts 0.0245 m inside this obstacle", "x = 0.585 m")


def test_a_run_too_long_for_the_memory(tmp_path):
    r = flexbeam("run", "seed-experiment", "--json", "--set", "solver.t_end=1e9", "--out", str(tmp_path / "out"))
    assert_one_line_error(r, "solver.t_end", "would hold about", "allowed here: solver.t_end <= ", "memory_limit")
    assert not (tmp_path / "out").exists()


def test_output_samples_too_many_for_the_memory_are_refused_before_anything_is_written(tmp_path):
    """0.5 s of the seed runs within 130 MB, but its samples (178 000, most on the 0.2 us contact grid) need
    ~150 MB: exit 2 after the run, before the output directory is made."""
    sets = ("--set", "solver.t_end=0.5", "--set", "solver.memory_limit=1.3e8")
    r = flexbeam("run", "seed-experiment", "--json", *sets, "--out", str(tmp_path / "out"))
    assert_one_line_error(r, "solver.contact_sample_step", "output samples", "solver.memory_limit")
    assert not (tmp_path / "out").exists()


def test_a_beam_too_thick_for_euler_bernoulli_theory():
    r = flexbeam("run", "seed-experiment", "--json", "--set", "beam.radius=0.5")
    assert_one_line_error(r, "beam.radius", "r/L = 0.7143", "r/L <= 0.217")


def test_a_thick_beam_runs_with_one_warning_line():
    """r/L = 0.071 (1.2 % above Timoshenko's first frequency): exit 0, the metrics on stdout, one stderr line."""
    r = flexbeam("run", "seed-experiment", "--json", "--set", "beam.radius=0.05", "--set", "solver.t_end=1e-3")
    assert r.returncode == 0, r.stderr
    assert r.stderr.splitlines() == [r.stderr.strip()] and r.stderr.startswith("warning: beam.radius: r/L = 0.07143")
    assert '"status": "success"' in r.stdout


FREE_BAR = Path(__file__).resolve().parent / "validation" / "data" / "free-bar-drop.toml"


@pytest.mark.parametrize(
    ("args", "field", "fragment"),
    [
        (("--set", "drive.kind=torque", "--set", "drive.torque=1"), "drive.kind", "no joint to drive"),
        (("--set", "initial.kind=state", "--set", "initial.position=[0, 0.001]"), "obstacle.centre", "inside"),
        (
            ("--method", "fem", "--set", "initial.kind=state", "--set", "initial.position=[0, 0.2]",
             "--set", "initial.modal_displacement=[1e-4]"),
            "initial.modal_displacement", "no modes",
        ),
        (("--method", "fem", "--set", "beam.viscous_damping=1"), "beam.viscous_damping", "hub's frame"),
        # G thrown at 1e300 m/s ran "success" with its kinetic energy inf (energy_drift null) and numpy's warnings
        (("--set", "initial.kind=state", "--set", "initial.velocity=[1e300, 0]"), "initial.velocity[0]", "10000"),
        (("--set", "initial.kind=state", "--set", "initial.velocity=[0, -2e4]"), "initial.velocity[1]", "-10000"),
    ],
)  # fmt: skip
def test_what_a_free_beam_refuses(args, field, fragment):
    """A free beam (joint.kind = "free"): a drive torque, a start inside the floor, the method that does not model it
    yet (CCM), a modal start for the FE reference (which has no modes), viscous damping relative to a frame the FE
    reference's free beam has not, G's speed beyond 1e4 m/s -- one line naming the field, exit 2."""
    r = flexbeam("run", str(FREE_BAR), "--json", *args)
    assert_one_line_error(r, field, fragment)


def test_a_subnormal_sample_step_is_refused_by_the_sample_limit():
    """Found by the fuzz test: a compliant support's metrics read the output samples (the sensor pulse), and a
    contact sample step of 5e-324 s made their count overflow a float: one line naming the field, exit 2."""
    r = flexbeam(
        "run", "seed-experiment-calibrated", "--json", "--set", "solver.t_end=1e-3",
        "--set", "solver.contact_sample_step=5e-324",
    )  # fmt: skip
    assert_one_line_error(r, "solver.contact_sample_step", "coarser")


def test_files_that_are_not_utf8_text_are_refused_in_one_line(tmp_path):
    """A binary file given as a case (a result.nc, say), a measured CSV or a base table: a UnicodeDecodeError's
    traceback before (only OSError was caught)."""
    binary = tmp_path / "case.toml"
    binary.write_bytes(b"\xff\xfe\x00binary")
    assert_one_line_error(flexbeam("run", str(binary)), "case", "not UTF-8 text")
    table = tmp_path / "table.csv"
    table.write_bytes(b"t,F\n0,1\n\xff,2\n3,4\n")
    r = flexbeam("calibrate", "seed-experiment", "--fit", "contact.stiffness", "--data", str(table))
    assert_one_line_error(r, "data", "not a CSV file: not UTF-8 text")
    shaker = Path(__file__).resolve().parent / "validation" / "data" / "shaker-stop.toml"
    assert_one_line_error(flexbeam("run", str(shaker), "-s", f"base.table={table}"), "base.table", "not UTF-8 text")


def test_frequencies_of_a_free_beam_are_refused_in_one_line():
    """A free beam has no hub to spin about (a ValueError's traceback before)."""
    assert_one_line_error(flexbeam("frequencies", "rod-end"), "joint.kind", "clamped to a hub", "'free'")


@pytest.mark.parametrize("methods", ["", " , "])
def test_compare_without_a_method_is_refused(methods):
    """It ran nothing, printed an empty table and exited 0."""
    assert_one_line_error(flexbeam("compare", "seed-experiment", "--methods", methods), "--methods", "at least one")


def test_compare_refuses_a_case_the_fe_reference_does_not_model_before_running():
    """``compare seed-experiment-calibrated`` ran CCFM and CCM, then refused the FE's compliant support (exit 2, no
    table, the runs lost); refused first now, naming the methods that can compare it."""
    r = flexbeam("compare", "seed-experiment-calibrated")
    assert_one_line_error(r, "obstacle.support", "FE reference", "--methods ccfm,ccm")


def test_compare_refuses_a_method_given_twice():
    """``--methods ccfm,ccfm`` ran CCFM twice and printed two identical rows (``calibrate --fit`` refuses a field
    given twice)."""
    assert_one_line_error(flexbeam("compare", "seed-experiment", "--methods", "ccfm,ccfm"), "--methods", "twice")


def test_an_obstacles_exponent_without_a_stiffness_names_its_pair():
    """two-stops' second stop under Hertz theory (no stiffness anywhere) given its own exponent: its field is named."""
    r = flexbeam("run", "two-stops", "--set", "obstacles[0].contact.exponent=1.2")
    assert_one_line_error(r, "obstacles[0].contact.exponent", "1.2 needs a stiffness")
