"""Shared fixtures: small cases built from the seed experiment."""

from __future__ import annotations

import math

import pytest

import flexbeam as fb


def seed(**overrides):
    """The seed case with dotted overrides given as keyword args with '__' for '.'."""
    return fb.load_case("seed-experiment", {k.replace("__", "."): v for k, v in overrides.items()})


def rigid_rod_mass_inertia(case) -> tuple[float, float]:
    """(mass, J_O) of the uniform rod of ``case`` about O, from the textbook formulas."""
    m = case.beam.density * math.pi * case.beam.radius**2 * case.beam.length
    return m, m * case.beam.length**2 / 3.0


@pytest.fixture
def seed_case():
    return seed()
