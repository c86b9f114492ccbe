"""Case builders shared by the finite-element reference tests."""

from __future__ import annotations

import flexbeam as fb
from flexbeam.parameters.case import Case


def seed(**overrides) -> Case:
    """The seed-experiment case with dotted-key overrides given as ``a__b=value``."""
    return fb.load_case("seed-experiment", {k.replace("__", "."): v for k, v in overrides.items()})


def general_beam(**overrides) -> Case:
    """A generic slender beam (L = 1 m, EI = 1 N m^2, nearly inextensible), no gravity.

    The obstacle is far away so that no contact happens unless a test moves it.
    """
    values = {
        "beam.section": "general",
        "beam.radius": None,
        "beam.length": 1.0,
        "beam.density": 1000.0,
        "beam.youngs_modulus": 1.0e7,
        "beam.area": 1.0e-2,
        "beam.second_moment": 1.0e-7,
        "beam.half_depth": 0.0,
        "model.gravity": 0.0,
        "obstacle.centre": [50.0, 50.0],
        "contact.stiffness": 1.0e6,
        "contact.position": 1.0,
        "output.measuring_points": [],
    }
    values.update({k.replace("__", "."): v for k, v in overrides.items()})
    return fb.load_case("seed-experiment", values)
