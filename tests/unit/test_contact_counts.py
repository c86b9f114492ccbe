"""What one contact is (flexbeam.results.counts): constructed record lists whose classification is known by
construction, and the robustness of the counts to round-off."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

import flexbeam as fb
from flexbeam.results.counts import MICRO_IMPACT_FRACTION, classify_contacts

#: a relative change of one value in its last bits, and far more (float64 round-off is 1.1e-16)
BITS = 1e-12


def counts(pairs, impulses, speeds, n_pairs=None):
    return classify_contacts(pairs, impulses, speeds, n_pairs)


def test_fraction_is_the_documented_one_percent():
    assert MICRO_IMPACT_FRACTION == 0.01


def test_a_zeno_tail_is_one_chatter_episode_and_a_later_tail_another():
    # impulses of one pair, approach speeds proportional (an impact's impulse is m_eff (1 + e) v): the
    # records at 0.9 %, 0.4 %, then 0.8 % and 0.99 % of the largest are micro-impacts, in two runs
    impulses = [1.0, 0.5, 0.02, 0.009, 0.004, 0.3, 0.008, 0.0099, 0.5]
    c = counts([0] * 9, impulses, [0.4 * j for j in impulses])
    assert c.micro == (False, False, False, True, True, False, True, True, False)
    assert c.episode == (None, None, None, 0, 0, None, 1, 1, None)
    assert c.of_pair(None) == {"contacts": 5, "contact_records": 9, "micro_impacts": 4, "chatter_episodes": 2}
    assert c.of_pair(0) == c.of_pair(None)
    assert [c.kind(i) for i in (0, 3)] == ["contact", "micro-impact"]


def test_each_pair_is_measured_against_its_own_largest_and_its_episodes_run_through_other_pairs_records():
    # pair 0's largest impulse is 1, pair 1's 2: 0.01 is a contact of pair 0 but a micro-impact of pair 1;
    # pair 0's micro-impacts at records 2 and 4 are consecutive among pair 0's records (record 3 is pair 1's)
    pairs = [0, 1, 0, 1, 0, 1, 0, 1]
    impulses = [1.0, 2.0, 0.005, 0.01, 0.004, 0.001, 0.01, 0.001]
    c = counts(pairs, impulses, impulses, n_pairs=3)
    assert c.micro == (False, False, True, True, True, True, False, True)
    assert c.episode == (None, None, 0, 1, 0, 1, None, 1)  # numbered by their first record
    assert c.of_pair(0) == {"contacts": 2, "contact_records": 4, "micro_impacts": 2, "chatter_episodes": 1}
    assert c.of_pair(1) == {"contacts": 1, "contact_records": 4, "micro_impacts": 3, "chatter_episodes": 1}
    assert c.of_pair(2) == {"contacts": 0, "contact_records": 0, "micro_impacts": 0, "chatter_episodes": 0}
    assert c.of_pair(None)["chatter_episodes"] == 2


def test_a_record_is_a_micro_impact_only_when_both_slow_and_weak():
    # 0: the first impact; 1: slow (0.5 %) but strong (a contact loaded by the vibrating beam); 2: weak (0.5 %) but
    # fast; 3: a long resting contact whose impulse is 50 times the first impact's; 4: an impact at 5 % of the
    # largest speed, weak against the resting contact's impulse; 5: slow and weak against both largest
    pairs = [0] * 6
    impulses = [1.0, 0.8, 0.005, 50.0, 0.05, 0.005]
    speeds = [0.4, 0.002, 0.2, 1e-7, 0.02, 0.002]
    c = counts(pairs, impulses, speeds)
    assert c.micro == (False, False, False, False, False, True)


def test_an_unknown_impulse_or_speed_cannot_make_a_micro_impact():
    nan = math.nan
    c = counts([0, 0, 0, 0], [1.0, nan, 0.001, 0.001], [1.0, 0.001, nan, 0.001])
    assert c.micro == (False, False, False, True)
    # nothing to compare against: no finite value, or none positive
    assert counts([0, 0], [nan, nan], [nan, nan]).micro == (False, False)
    assert counts([0, 0], [0.0, 0.0], [0.0, 0.0]).micro == (False, False)


def test_no_records():
    c = counts([], [], [], n_pairs=2)
    assert c.of_pair(None) == {"contacts": 0, "contact_records": 0, "micro_impacts": 0, "chatter_episodes": 0}


def test_lengths_must_agree():
    with pytest.raises(ValueError, match="differ in length"):
        classify_contacts([0, 0], [1.0], [1.0, 1.0])


def _perturbed(values, i, factor):
    return [v * factor if j == i else v for j, v in enumerate(values)]


@pytest.mark.parametrize("factor", [1.0 + BITS, 1.0 - BITS])
def test_round_off_in_any_impulse_or_speed_changes_no_count(factor):
    # the Zeno tail of the first test and a second pair: no record within 5 % of its thresholds
    pairs = [0, 0, 0, 1, 0, 0, 1, 0, 0, 1]
    impulses = [1.0, 0.5, 0.02, 3.0, 0.009, 0.004, 0.02, 0.3, 0.008, 0.5]
    speeds = [0.4, 0.2, 0.008, 0.9, 0.0036, 0.0016, 0.012, 0.12, 0.0032, 0.2]
    reference = counts(pairs, impulses, speeds)
    for i in range(len(pairs)):  # the largest ones too: every ratio moves by the same factor
        assert counts(pairs, _perturbed(impulses, i, factor), speeds) == reference
        assert counts(pairs, impulses, _perturbed(speeds, i, factor), n_pairs=2) == reference


def test_a_record_exactly_at_the_threshold_counts_and_crosses_it_by_construction():
    # 0.01 = 1 % of 1.0 exactly in binary64 (0.01 * 1.0 == 0.01): "at least 1 %" is a contact
    at = counts([0, 0], [1.0, 0.01], [1.0, 0.01])
    assert at.micro == (False, False)
    below = counts([0, 0], [1.0, 0.01 * (1 - BITS)], [1.0, 0.01 * (1 - BITS)])
    assert below.micro == (False, True)


magnitudes = st.floats(min_value=1e-6, max_value=1.0, allow_nan=False)


@given(
    records=st.lists(st.tuples(st.integers(0, 2), magnitudes, magnitudes), min_size=1, max_size=40),
    i=st.integers(0, 39),
    up=st.booleans(),
)
def test_a_perturbation_changes_the_counts_only_of_a_record_that_straddles_its_threshold(records, i, up):
    """Any record list: scaling one impulse by 1 +- 1e-12 changes the classification only if some record of that
    pair lies within 3e-12 (relative) of 1 % of the pair's largest impulse -- the perturbed record itself, or any
    record when the largest one moves."""
    pairs = [k for k, _, _ in records]
    impulses = [j for _, j, _ in records]
    speeds = [v for _, _, v in records]
    i %= len(records)
    factor = 1.0 + BITS if up else 1.0 - BITS
    before = counts(pairs, impulses, speeds)
    after = counts(pairs, _perturbed(impulses, i, factor), speeds)
    if after != before:
        k = pairs[i]
        largest = max(j for p, j in zip(pairs, impulses) if p == k)
        threshold = MICRO_IMPACT_FRACTION * largest
        assert any(abs(j - threshold) <= 3 * BITS * threshold for p, j in zip(pairs, impulses) if p == k), (
            "a count changed although no record was at its threshold"
        )


def test_a_run_stopped_after_one_contact_says_contact():
    """'stopped at t = ... s after 1 contacts' (found by exploratory testing)."""
    sol = fb.simulate(fb.load_case("seed-experiment", {"solver.max_contacts": 1}), "imm")
    assert sol.status == "max-contacts" and " after 1 contact (solver.max_contacts)" in sol.message, sol.message
