"""The grouping of contact records into collision episodes and the gap's default (flexbeam.results.episodes)."""

from __future__ import annotations

import math

import pytest

import flexbeam as fb
from flexbeam.model.system import BeamSystem
from flexbeam.results.episodes import FREE_FREE_ROOT, default_gap, first_free_free_period, group_episodes


def test_records_closer_than_the_gap_make_one_episode():
    onsets = [0.0, 1.0, 1.5, 10.0, 10.2, 30.0]
    ends = [0.5, 1.2, 1.6, 10.1, 10.3, 30.0]
    assert group_episodes(onsets, ends, 1.0) == [[0, 1, 2], [3, 4], [5]]
    assert group_episodes(onsets, ends, 0.4) == [[0], [1, 2], [3, 4], [5]]
    assert group_episodes(onsets, ends, 100.0) == [[0, 1, 2, 3, 4, 5]]
    assert group_episodes([], [], 1.0) == []


def test_the_gap_runs_from_the_latest_end_and_an_open_end_never_closes():
    """A long record that outlasts the next one: the gap is measured from the latest end so far; NaN (the run ended
    in contact) keeps the episode open."""
    assert group_episodes([0.0, 0.1, 4.5], [5.0, 0.2, 4.6], 1.0) == [[0, 1, 2]]
    assert group_episodes([0.0, 50.0], [math.nan, 50.0], 1.0) == [[0, 1]]


def test_the_default_gap_is_the_first_free_free_period():
    """T_1 = 2 pi / (4.73004^2 sqrt(EI / (mu L^4))): 0.70 ms for the 20 cm, 12.7 mm steel bar; the same for a rigid
    model of it (model.modes = 0)."""
    assert FREE_FREE_ROOT == pytest.approx(4.73004074486, abs=1e-11)
    case = fb.load_case("tests/validation/data/free-bar-drop.toml")
    E, rho, r, L = 200e9, 7870.0, 0.00635, 0.2
    expected = 2.0 * math.pi / (FREE_FREE_ROOT**2 * math.sqrt(E * r**2 / 4.0 / rho / L**4))
    beam = BeamSystem.from_case(case).beam
    assert first_free_free_period(beam) == pytest.approx(expected, rel=1e-12)
    assert expected == pytest.approx(7.0e-4, rel=0.02)
    rigid = BeamSystem.from_case(fb.load_case(case, {"model.modes": 0})).beam
    assert default_gap(rigid) == default_gap(beam)
