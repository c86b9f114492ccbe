"""Case input: round trip, overrides and one-line errors naming the field."""

from __future__ import annotations

import math

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


def test_overrides_change_the_named_fields():
    case = fb.load_case(
        "seed-experiment",
        parse_overrides(["beam.youngs_modulus=70e9", "model.modes=3", "contact.law=hunt_crossley",
                         "contact.stiffness=1e9", "initial.impact_velocity=-0.2", "solver.t_end=0.01"]),
    )
    assert case.beam.youngs_modulus == 70e9 and case.model.modes == 3
    assert case.contact.law == "hunt_crossley" and case.contact.stiffness == 1e9
    assert case.initial.impact_velocity == -0.2 and case.solver.t_end == 0.01


@pytest.mark.parametrize(
    ("key", "value", "field"),
    [
        ("beam.length", "-1", "beam.length"),
        ("beam.lenght", "1", "beam.length"),  # unknown key: best match named
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
