"""The case-file reference page's rows (docs/_ext/case_fields.py) cover the schema exactly."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest
from pydantic import BaseModel

from flexbeam.parameters import CONTACT_LAWS, Case
from flexbeam.parameters.io import set_dotted

SOURCE = Path(__file__).resolve().parents[2] / "docs" / "_ext" / "case_fields.py"


@pytest.fixture(scope="module")
def rows():
    spec = importlib.util.spec_from_file_location("case_fields", SOURCE)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return {r.key: r for s in module.case_sections() for r in s.rows}


def _leaves(model: type[BaseModel], prefix: str = "") -> list[str]:
    out = []
    for name, info in model.model_fields.items():
        ann = info.annotation
        if isinstance(ann, type) and issubclass(ann, BaseModel):
            out += _leaves(ann, f"{prefix}{name}.")
        else:
            out.append(prefix + name)
    return out


def test_every_field_once_and_every_key_valid(rows):
    assert sorted(rows) == sorted(_leaves(Case))
    for key in rows:
        set_dotted({}, key, 0)  # raises ParameterError for a key the case does not have


@pytest.mark.parametrize(
    ("key", "type_", "default", "allowed"),
    [
        ("beam.length", "float", "required", "> 0"),
        ("beam.poisson_ratio", "float", "0.3", "(-1, 0.5)"),
        ("contact.restitution", "float", "0.8", "[0, 1]"),
        ("contact.stiffness", "float (optional)", "omitted", "> 0"),
        ("model.modes", "integer", "8", "[0, 64]"),
        ("solver.t_end", "float", "0.1", "> 0"),
        ("solver.max_contacts", "integer", "1000", ">= 1"),
        ("obstacle.support.damping", "float", "0", ">= 0"),
        ("obstacle.centre", "[float, float] (optional)", "omitted", "finite"),
        ("output.measuring_points", "list of float", "[]", ">= 0"),
    ],
)
def test_types_defaults_and_ranges(rows, key, type_, default, allowed):
    r = rows[key]
    assert (r.type, r.default, r.allowed) == (type_, default, allowed)


def test_choices_and_descriptions(rows):
    assert rows["contact.law"].choices == tuple(f'"{law}"' for law in CONTACT_LAWS)
    assert rows["model.coupling"].choices == ('"first-order"', '"zeroth-order"')
    assert rows["contact.law"].default == '"lankarani_nikravesh"'
    assert rows["beam.youngs_modulus"].description == "Young's modulus E [Pa]"
