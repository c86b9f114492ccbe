"""Case input: round trip, overrides and one-line errors naming the field."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.errors import ParameterError
from flexbeam.parameters.io import dump_case, parse_overrides


def test_every_builtin_case_round_trips_through_toml(tmp_path):
    for name in fb.builtin_cases():
        case = fb.load_case(name)
        path = tmp_path / f"{name}.toml"
        path.write_text(dump_case(case))
        assert fb.load_case(path) == case


def test_a_dumped_case_takes_the_obstacles_tables_the_usage_guide_appends(tmp_path):
    """``flexbeam cases show seed-experiment > my.toml``, then docs/usage.md's ``[[obstacles]]`` block appended: the
    dump wrote ``obstacles = []``, which TOML does not let a later ``[[obstacles]]`` extend ("Cannot mutate immutable
    namespace"), so the documented way to add a stop failed with a message pointing at the user's block."""
    block = (
        '\n[[obstacles]]\nkind = "sphere"\nradius = 0.01\ncentre = [0.585, 0.0265]\n'
        '\n[obstacles.contact]\nside = "above"\n'
    )
    path = tmp_path / "my.toml"
    path.write_text(dump_case(fb.load_case("seed-experiment")) + block)
    case = fb.load_case(path)
    assert len(case.obstacles) == 1 and case.obstacles[0].centre == (0.585, 0.0265)


def test_overrides_change_the_named_fields():
    case = fb.load_case(
        "seed-experiment",
        parse_overrides(
            [
                "beam.youngs_modulus=70e9",
                "model.modes=3",
                "contact.law=hunt_crossley",
                "contact.stiffness=1e9",
                "initial.impact_velocity=-0.2",
                "solver.t_end=0.01",
            ]
        ),
    )
    assert case.beam.youngs_modulus == 70e9 and case.model.modes == 3
    assert case.contact.law == "hunt_crossley" and case.contact.stiffness == 1e9
    assert case.initial.impact_velocity == -0.2 and case.solver.t_end == 0.01


@pytest.mark.parametrize(
    ("key", "value", "field"),
    [
        ("beam.length", "-1", "beam.length"),
        ("beam.lenght", "1", "beam.lenght"),  # unknown key: named first, best match after
        ("contact.position", "0.9", "contact.position"),
        ("model.modes", "-1", "model.modes"),
        ("contact.restitution", "1.5", "contact.restitution"),
        ("beam.youngs_modulus", "abc", "beam.youngs_modulus"),
        ("beam.youngs_modulus", "nan", "beam.youngs_modulus"),
        ("contact.law", "hertzz", "contact.law"),
    ],
)
def test_bad_input_names_the_field_in_one_line(key, value, field):
    with pytest.raises(ParameterError) as info:
        fb.load_case("seed-experiment", parse_overrides([f"{key}={value}"]))
    msg = str(info.value)
    assert field in msg and "\n" not in msg


def test_nan_is_parsed_as_a_number():
    assert math.isnan(parse_overrides(["a=nan"])["a"])


def test_unknown_case_suggests_names():
    with pytest.raises(ParameterError, match="seed-experiment"):
        fb.load_case("seed-experimnt")


def _seed_dict() -> dict:
    return fb.load_case("seed-experiment").model_dump(mode="json", exclude_none=True)


def _message(source, overrides=None) -> str:
    with pytest.raises(ParameterError) as info:
        fb.load_case(source, overrides)
    msg = str(info.value)
    assert "\n" not in msg
    return msg


def test_misspelt_key_is_named_before_the_field_it_leaves_missing():
    data = _seed_dict()
    data["beam"]["lenght"] = data["beam"].pop("length")
    assert _message(data) == "beam.lenght: unknown field, did you mean length?"


def test_unknown_key_has_the_same_message_from_a_dict_and_from_an_override():
    assert _message("seed-experiment", {"solver.tend": 0.01}) == "solver.tend: unknown field, did you mean t_end?"
    data = _seed_dict()
    data["solver"]["tend"] = 0.01
    assert _message(data) == "solver.tend: unknown field, did you mean t_end?"


def test_unknown_section_is_named_with_its_closest_match():
    data = _seed_dict()
    data["bem"] = data.pop("beam")
    assert _message(data) == "bem: unknown section, did you mean beam?"
    assert _message("seed-experiment", {"bem.length": 0.7}) == "bem.length: unknown section 'bem', did you mean beam?"
    data = _seed_dict()
    data["obstacle"]["suport"] = {"stiffness": 3e7}
    assert _message(data) == "obstacle.suport: unknown section, did you mean support?"


def test_unknown_key_without_a_close_match_lists_the_section():
    msg = _message("seed-experiment", {"hub.xyz": 1.0})
    assert msg == "hub.xyz: unknown field; hub has: radius, inertia"


def test_load_case_leaves_a_given_dict_unchanged():
    data = _seed_dict()
    before = repr(data)
    case = fb.load_case(data, {"beam.length": 0.8})
    assert case.beam.length == 0.8 and repr(data) == before
    assert fb.load_case(data) == fb.load_case("seed-experiment")


def test_too_few_gauss_points_for_the_modes_are_rejected():
    # n modes and theta: the mass matrix is a sum of one rank-one term per point, so n + 1 are needed
    assert "model.modes + 1 = 5" in _message("seed-experiment", {"model.modes": 4, "model.quadrature_points": 4})
    # n + 1 points is the least that builds a regular mass matrix: the run integrates (it raised before)
    sol = fb.simulate("seed-experiment", model__modes=2, model__quadrature_points=3, solver__t_end=0.002)
    assert sol.status == "success"


def test_point_obstacle_is_rejected_but_a_half_plane_needs_no_radius():
    assert _message("seed-experiment", {"obstacle.radius": 0.0}).startswith("obstacle.radius: must be > 0")
    case = fb.load_case(
        "seed-experiment", {"obstacle.kind": "half-plane", "obstacle.radius": 0.0, "contact.stiffness": 1e9}
    )
    assert case.obstacle.radius == 0.0


def test_an_obstacle_field_is_set_by_its_index():
    """``obstacles[i].a.b`` names a field of entry i of [[obstacles]] (as the error messages do), so sweeps and
    calibration reach the further obstacles' fields."""
    case = fb.load_case("two-stops", {"obstacles[0].contact.stiffness": 2.5e9, "obstacles[0].radius": 0.005})
    assert case.obstacles[0].contact.stiffness == 2.5e9 and case.obstacles[0].radius == 0.005
    assert fb.load_case("two-stops").obstacles[0].contact.stiffness is None  # the preset itself is untouched


@pytest.mark.parametrize(
    "key, message",
    [
        ("obstacles[1].radius", "obstacles[1].radius: obstacles[1] does not exist (the case has 1 obstacles)"),
        ("obstacles[0].contact.stifness", "obstacles[0].contact.stifness: unknown field, did you mean stiffness?"),
        ("obstacles[0]", "obstacles[0]: name a field of obstacles[0]"),
        ("beam[0].length", "beam[0].length: 'beam' is not a list of sections"),
    ],
)
def test_bad_indexed_keys_are_named(key, message):
    with pytest.raises(fb.ParameterError) as err:
        fb.load_case("two-stops", {key: 1.0})
    assert str(err.value).startswith(message)


def test_an_indexed_field_has_its_schema_limits_for_calibration():
    from flexbeam.calibrate.fields import _field

    assert _field("obstacles[0].contact.restitution")[:2] == (0.0, 1.0)
    assert _field("obstacles[0].contact.stiffness")[3] == "N/m^n"


@pytest.mark.parametrize(
    "field, value",
    [("contact.friction", True), ("model.modes", True), ("beam.density", False), ("initial.angle", True),
     ("output.measuring_points", [0.2, True]),
     ("obstacles", [{"kind": "sphere", "centre": [0.5, True], "radius": 0.01}])],
)  # fmt: skip
def test_true_or_false_where_a_number_belongs_is_refused_naming_the_field(field, value):
    """Pydantic's lax mode read true as 1 (a friction coefficient of 1, one mode) and false as 0."""
    with pytest.raises(ParameterError) as err:
        fb.load_case("two-stops", {field: value})
    assert "must be a number, not true or false" in str(err.value)
    assert str(err.value).startswith(field if field != "obstacles" else "obstacles[0].centre"), str(err.value)


@pytest.mark.parametrize(
    "field, value",
    [("beam.length", "0.7"), ("contact.restitution", "0.5"), ("solver.t_end", "1e-3"), ("model.modes", "3"),
     ("initial.impact_angle", "0.1"), ("output.measuring_points", [0.2, "0.3"]),
     ("obstacles", [{"kind": "sphere", "centre": [0.5, "0.1"], "radius": 0.01}])],
)  # fmt: skip
def test_text_where_a_number_belongs_is_refused_naming_the_field(field, value):
    """Pydantic's lax mode read ``length = "0.7"`` in a case file (or ``--set 'beam.length="0.7"'``) as 0.7, where
    usage.md says a number field takes numbers only (found by exploratory testing)."""
    with pytest.raises(ParameterError) as err:
        fb.load_case("two-stops", {field: value})
    assert "must be a number, not text" in str(err.value)
    assert str(err.value).startswith(field if field != "obstacles" else "obstacles[0].centre"), str(err.value)


@pytest.mark.parametrize("item", ["contact.stiffness=.5e10", "initial.impact_velocity=-.4", "contact.stiffness=5.e9",
                                  "model.modes=08", "contact.restitution=.5"])  # fmt: skip
def test_a_number_python_reads_but_toml_does_not_says_how_to_write_it(item):
    """``--set initial.impact_velocity=-.4`` said "must be a number, not text" -- of a number (found by exploratory
    testing): --set reads TOML, whose numbers need a digit on each side of the point and no leading zero."""
    key = item.partition("=")[0]
    with pytest.raises(ParameterError, match=rf"^{re.escape(key)}: must be a number as TOML writes one: .*e.g. -0.4"):
        fb.load_case("seed-experiment", parse_overrides([item]))


@pytest.mark.parametrize("value", ["yes", "true", 1, 0, 1.0])
def test_a_switch_takes_true_or_false_only(value):
    """``contact.anywhere = "yes"``, ``= 1`` or ``--set contact.anywhere=yes`` ran as true (pydantic's lax mode)."""
    with pytest.raises(ParameterError, match=r"^contact.anywhere: must be true or false"):
        fb.load_case("seed-experiment", {"contact.anywhere": value})


def test_true_or_false_still_set_a_switch_and_integers_still_set_a_float():
    case = fb.load_case("seed-experiment", {"contact.anywhere": True, "contact.restitution": 1, "model.modes": 3})
    assert case.contact.anywhere is True and case.contact.restitution == 1.0 and case.model.modes == 3


def test_numpys_true_and_false_are_a_switchs_and_no_number():
    """An override taken from an array's entry: ``np.bool_(True)`` was refused for a switch ("must be true or false
    (got np.True_)") while numpy's integers and floats set numbers; it sets the switch now (as Python's bool), and is
    still no number."""
    case = fb.load_case("seed-experiment", {"contact.anywhere": np.bool_(True), "model.modes": np.int64(3)})
    assert case.contact.anywhere is True and case.model.modes == 3
    with pytest.raises(ParameterError, match=r"^contact.friction: must be a number, not true or false"):
        fb.load_case("seed-experiment", {"contact.friction": np.True_})


def test_the_reference_integrators_rtol_stops_at_100_machine_epsilons():
    """scipy's DOP853 raises an rtol below 100 eps to that itself, with a UserWarning that reached the terminal raw
    before the run's line: the field now says its range."""
    with pytest.raises(ParameterError, match=r"^solver.rtol: must be >= 2.22e-14 \(100 machine epsilons"):
        fb.load_case("seed-experiment", {"solver.integrator": "reference", "solver.rtol": 1e-16})
    assert fb.load_case("seed-experiment", {"solver.rtol": 100 * np.finfo(float).eps}).solver.rtol > 0


@pytest.mark.parametrize(
    "source, overrides, says",
    [(123, None, "case: a built-in case name, a TOML path"), (None, None, "case: a built-in case name"),
     ("seed-experiment", ["model.modes=3"], "overrides: a mapping of dotted keys"),
     ("seed-experiment", {1: 2}, "overrides: each key is a dotted field name")],
)  # fmt: skip
def test_load_case_of_the_wrong_type_is_one_parameter_error(source, overrides, says):
    """A TypeError or an AttributeError ('list' object has no attribute 'items'; 'int' object has no attribute
    'split' for a key that is no string) before."""
    with pytest.raises(ParameterError, match=says):
        fb.load_case(source, overrides)


@pytest.mark.parametrize("method", [None, 3, ["ccfm"], "cfm"])
def test_simulate_with_a_method_that_is_no_name_is_one_parameter_error(method):
    """None gave a TypeError ('NoneType' object is not iterable) before; a misspelt name keeps its closest match."""
    with pytest.raises(ParameterError, match="method: unknown impact method") as err:
        fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 1e-4}), method)
    assert ("best matches: ccfm" in str(err.value)) == (method == "cfm")


@pytest.mark.parametrize(
    ("call", "says"),
    [(lambda: fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 1e-4}), "CCFM"), "best matches: ccfm"),
     (lambda: fb.load_case("SEED-EXPERIMENT"), "best matches: seed-experiment")],
)  # fmt: skip
def test_a_name_in_other_letter_case_is_refused_with_its_match(call, says):
    """Names are case-sensitive (the CLI and --json contract), but the refusal offers the name as spelt: compared as
    typed, 'CCFM' and 'ccfm' share no character and no match was offered."""
    with pytest.raises(ParameterError, match=says):
        call()


def test_the_experiment_is_the_reference_of_its_own_set_up_only():
    """``compare`` and ``run --out`` score a run against the reference numbers shipped with the preset of its name; a
    case that keeps the name but changes the beam, the start or where the obstacle is struck was scored against the
    2013 experiment all the same (a 597 % "error").  The model's choices (law, stiffness, modes, t_end) keep it, and a
    calibrated variant keeps its base case's numbers, whatever support it fits."""
    from flexbeam.parameters.references import reference_for
    from flexbeam.views.report import compare_table, markdown_table

    assert reference_for(fb.load_case("seed-experiment"))["experiment"]["peak_force"] == 584.0
    same = {"contact.law": "hunt_crossley", "contact.stiffness": 3e9, "model.modes": 4, "solver.t_end": 1e-3}
    assert reference_for(fb.load_case("seed-experiment", same))
    assert reference_for(fb.load_case("seed-experiment-calibrated", {"obstacle.support.stiffness": 5e7}))  # fitted
    for changed in ({"beam.length": 1.5}, {"initial.impact_velocity": -1.0}, {"contact.position": 0.3},
                    {"obstacle.radius": 0.02}):  # fmt: skip
        assert reference_for(fb.load_case("seed-experiment", changed)) == {}, changed
    sol = fb.simulate(fb.load_case("seed-experiment", {"beam.length": 1.5, "solver.t_end": 1e-4}), "ccfm")
    table = markdown_table(compare_table([sol], {}), {})
    assert "%" not in table and "Experiment" not in table  # no error against nothing ("- %" before)


def test_an_instantaneous_impact_gets_no_duration_error():
    """IMM's impact has no duration: ``compare`` reported its 0 ms as a -100 % error against the experiment's 0.6 ms
    (its peak, NaN, got none).  No error for a quantity the method does not resolve; CCFM's errors unchanged."""
    from flexbeam.parameters.references import reference_for
    from flexbeam.views.report import compare_table, markdown_table

    case = fb.load_case("seed-experiment", {"solver.t_end": 2e-3})
    ref = reference_for(case)
    rows = compare_table([fb.simulate(case, "imm"), fb.simulate(case, "ccfm")], ref)
    imm, ccfm = rows
    assert imm["contact_duration"] == 0.0 and imm["contact_duration_error"] is None and imm["peak_force_error"] is None
    measured = ref["experiment"]["contact_duration"]
    assert ccfm["contact_duration_error"] == (ccfm["contact_duration"] - measured) / measured
    imm_line = next(line for line in markdown_table(rows, ref).splitlines() if line.startswith("| imm"))
    assert "%" not in imm_line and "-100" not in imm_line


def test_every_compare_row_has_every_key_and_its_runs_status():
    """``compare --json`` for programs: a row's keys varied (the FE's had no paper_peak_force, IMM's no errors) and
    none said that a run had stopped early (found by exploratory testing).  Every row has every key now (null where
    there is nothing), and its run's status."""
    from flexbeam.parameters.references import reference_for
    from flexbeam.views.report import compare_table

    case = fb.load_case("tip-wall", {"solver.max_contacts": 2, "solver.t_end": 0.02})
    sols = [fb.simulate(case, m) for m in ("ccfm", "imm")]
    rows = compare_table(sols, reference_for(case))
    assert rows[0].keys() == rows[1].keys()
    assert {"status", "peak_force_error", "paper_peak_force"} <= rows[0].keys()
    assert [r["status"] for r in rows] == [s.status for s in sols] and "max-contacts" in [s.status for s in sols]


def test_a_support_axis_left_to_its_default_away_from_an_impact_start_is_warned():
    """The default axis of a compliant support is the outward contact normal of the straight beam at
    initial.impact_angle, at the pair's point: where an ``impact`` start strikes [obstacle].  A ``state`` start (a
    sensor added under spinning-stop's sphere, struck at 0.951 rad) or an obstacle of [[obstacles]] is struck
    elsewhere -- 26.7 degrees off there -- and the schema promised "its outward contact normal at impact"."""
    import warnings

    from flexbeam.errors import FlexbeamWarning

    sensor = {"obstacle.support.stiffness": 2e7, "obstacle.support.mass": 0.02}
    with pytest.warns(FlexbeamWarning, match=r"obstacle.support.direction: omitted"):
        fb.load_case("spinning-stop", sensor)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fb.load_case("spinning-stop", {**sensor, "obstacle.support.direction": [0.8, -0.6]})
        fb.load_case("seed-experiment-calibrated")  # an impact start: the default is the normal where it strikes


def test_an_impact_start_anywhere_against_a_surface_along_the_beam_says_why():
    """tip-wall's wall lies along the straight beam: with contact.anywhere every point is nearest and the tie falls
    at x = 0, the joint, which moves 0 m per radian -- the refusal blamed impact_velocity and contact.position (0.7 m,
    which moves 0.7 m per radian) alone.  It names the nearest point and the ways out (a helper's hunt)."""
    from flexbeam.errors import ParameterError

    with pytest.raises(ParameterError, match=r"with contact.anywhere P is the straight beam's nearest .* x = 0 m"):
        fb.simulate(fb.load_case("tip-wall", {"contact.anywhere": True, "solver.t_end": 1e-4}))


def test_an_optional_switch_or_number_still_takes_none():
    """A dumped case (model_dump) holds None for an optional field not given (an obstacle's own contact.anywhere):
    loading it back must not read None as a bad switch."""
    data = fb.load_case("two-stops").model_dump()
    assert data["obstacles"][0]["contact"]["anywhere"] is None
    assert fb.load_case(data).obstacles[0].contact.anywhere is None


def test_an_index_that_does_not_count_from_zero_is_named():
    """``obstacles[-1].radius`` answered "unknown section 'obstacles[-1]', did you mean obstacles?" (an exploratory
    hunt): the index is what is wrong."""
    from flexbeam.errors import ParameterError

    for index in ("-1", "a", ""):
        with pytest.raises(ParameterError, match=rf"^obstacles\[{index}\]\.radius: '{index}' is no index of obstacles"):
            fb.load_case("two-stops", {f"obstacles[{index}].radius": 0.02})
    with pytest.raises(ParameterError, match=r"^beam\[-1\]\.length: unknown section"):  # not a list: as before
        fb.load_case("two-stops", {"beam[-1].length": 0.5})


def test_a_copy_with_an_update_is_validated():
    """pydantic's ``model_copy(update=...)`` takes the update as it is: a case copied with ``solver.t_end = -1`` ran
    "success" with no sample.  The copy is validated as an assignment is: the field named, the range said; an
    unknown key is refused too; a valid update gives the case that the same overrides load."""
    import pydantic

    case = fb.load_case("seed-experiment")
    with pytest.raises(pydantic.ValidationError, match=r"t_end\n.*greater than 0"):
        case.model_copy(update={"solver": case.solver.model_copy(update={"t_end": -1.0})})
    with pytest.raises(pydantic.ValidationError, match="t_endd"):
        case.solver.model_copy(update={"t_endd": 1.0})
    copied = case.model_copy(update={"solver": case.solver.model_copy(update={"t_end": 0.02})})
    assert copied == fb.load_case("seed-experiment", {"solver.t_end": 0.02})
    assert case.solver.t_end == 0.1  # the original untouched
    assert case.model_copy() == case and case.model_copy(deep=True) == case
