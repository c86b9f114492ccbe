"""Bad arguments of the Python API get one ParameterError naming the argument and what is allowed (an exploratory
hunt found a bare IndexError, silent empty answers, negative thresholds and gaps taken, AttributeError and
TypeError from wrong types)."""

from __future__ import annotations

import pytest

import flexbeam as fb
from flexbeam.errors import ParameterError


@pytest.fixture(scope="module")
def run():
    return fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 2e-3}), "ccfm")


def test_a_record_index_out_of_range_or_not_an_integer_is_named(run):
    n = len(run.contacts)
    assert n == 1 and run.contact(-1) is run.contact(0)  # (a negative index counts from the end, as a list's)
    for call, text in [
        (lambda: run.contact(5), "contact: 5 is not a record of this run; allowed -1 <= contact <= 0"),
        (lambda: run.force_peaks(contact=3), "contact: 3 is not a record"),  # (an empty list before)
        (lambda: run.contact(1.0), "contact: a contact record's index, an integer"),
        (lambda: run.contact(True), "contact: a contact record's index, an integer"),
        (lambda: run.force_peaks(threshold=-1), "threshold: must be a finite number >= 0"),
        (lambda: run.force_peaks(threshold=float("nan")), "threshold: must be a finite number >= 0"),
        (lambda: run.episodes(gap=-1.0), "gap: must be a finite number > 0"),
        (lambda: run.animate("a.gif", window="0,1e-4"), "window: two times (t0, t1)"),
    ]:
        with pytest.raises(ParameterError) as err:
            call()
        assert str(err.value).startswith(text), str(err.value)


def test_a_run_without_records_says_so():
    quiet = fb.simulate(fb.load_case("kane-spinup", {"solver.t_end": 0.01}), "ccfm")  # (no obstacle within reach)
    assert quiet.contacts == []
    with pytest.raises(ParameterError, match=r"^contact: this run has no contact records"):
        quiet.force_peaks()


def test_a_stream_path_and_a_sweep_grid_of_the_wrong_kind_are_named(tmp_path):
    case = fb.load_case("seed-experiment", {"solver.t_end": 1e-4})
    for stream in (True, 123, ""):
        with pytest.raises(ParameterError, match=r"^stream: the path of the result file"):
            fb.simulate(case, "ccfm", stream=stream)
    with pytest.raises(ParameterError, match=r"^grid: a mapping of dotted field names"):
        fb.sweep("seed-experiment", grid=[("contact.restitution", [0.5])])
    assert list(tmp_path.iterdir()) == []
