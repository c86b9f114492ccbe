"""Shared fixtures: small cases built from the seed experiment."""

from __future__ import annotations

import math
import os

import pytest
from hypothesis import settings

import flexbeam as fb

# Hypothesis explores the same examples on every run and machine (a test suite that passes where it was written
# must pass everywhere); HYPOTHESIS_PROFILE=explore draws new ones, to hunt for cases worth pinning.
settings.register_profile("deterministic", derandomize=True, print_blob=True)
settings.register_profile("explore", derandomize=False, max_examples=500, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "deterministic"))


#: the seed beam's hub turned at a prescribed rate (theta given, not in the state), from just above the stop
PRESCRIBED_SPIN = {
    "drive.kind": "prescribed",
    "drive.profile": "constant-rate",
    "drive.spin_rate": -1.0,
    "initial.kind": "state",
    "initial.angle": 1e-3,
}


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
