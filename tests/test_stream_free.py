"""A free beam's run streamed to its result file (``flexbeam run CASE --stream`` with ``joint.kind = "free"``).

The streamed run must write what the same run held in memory writes -- the samples (G's position and velocity and
the free beam's long names included) bit for bit, the same contact records and the same collision episodes (records,
G's velocity and spin before and after, the apparent restitution, compression end, impulses, works) -- while the
memory it holds does not grow with its length.  Truth: the in-memory run, whose episodes are tested against rigid-body
impact theory and the momentum balance in tests/validation.  As in tests/test_stream.py the long-run paths (a phase
handed on in parts, a contact completed stretch by stretch, an episode summed as its segments leave) are reached in a
short run by making the block and the window small; in-memory and streamed runs share the stepper's block size, so
they take the same steps.
"""

from __future__ import annotations

import json
import math
import tracemalloc
from pathlib import Path

import pytest

import flexbeam as fb
from flexbeam.integrate import modal
from flexbeam.results import stream
from flexbeam.results.files import jsonable
from tests.test_stream import assert_same_files, assert_same_metrics, assert_same_records, in_parts, read
from tests.validation.test_repeated_obstacle import C, floor_case

DROP = Path(__file__).parent / "validation" / "data" / "free-bar-drop.toml"
#: the impulses of a contact completed stretch by stretch are summed part by part (each part's correctly rounded),
#: and so are an episode's impulses and works over a phase handed on in parts: equal to round-off, measured 2e-16
#: relative; a 50x margin
PARTS_REL = 1e-14


def tilted_drop(t_end: float):
    """The steel bar on a floor touched at both ends (two pairs), dropped from 2 mm tilted by 0.01 rad: it bounces
    from end to end (a score of episodes) and comes to rest on both ends (one open record per pair to the end)."""
    case = floor_case({"kind": "state", "position": [0.0, C + 2e-3], "velocity": [0.0, 0.0], "angle": 0.01,
                       "rate": 0.0}, t_end=t_end)  # fmt: skip
    case["output"] = {"interval": 1e-3}
    return fb.load_case(case)


def assert_same_episodes(streamed, in_memory, rel: float = 0.0):
    """The episodes' JSON text equal (``rel``: their impulses, works and what follows from them, to round-off)."""
    got, want = streamed.metrics()["episodes"], in_memory.metrics()["episodes"]
    assert want and len(got) == len(want)
    if rel == 0.0:
        assert json.dumps(jsonable(got)) == json.dumps(jsonable(want))
        return
    for g, w in zip(got, want, strict=True):
        for key, value in w.items():
            if isinstance(value, float) and math.isfinite(value):
                assert math.isclose(g[key], value, rel_tol=rel, abs_tol=0.0), (w["index"], key, g[key], value)
            else:
                assert json.dumps(jsonable(g[key])) == json.dumps(jsonable(value)), (w["index"], key)


def compare(tmp_path, case, method, rel: float = 0.0):
    in_memory = fb.simulate(case, method)
    metrics = in_memory.metrics()
    streamed = fb.simulate(case, method, stream=tmp_path / "streamed.nc")
    assert streamed.source is None and streamed.is_free
    assert_same_files(streamed.file, in_memory.to_netcdf(tmp_path / "memory.nc"), rel)
    assert_same_records(streamed, in_memory, rel)
    assert_same_episodes(streamed, in_memory, rel)
    got = streamed.metrics()
    if rel:  # the episodes' numbers compared to round-off above (the first's coefficients among them)
        for key in ("episodes", "restitution_newton", "restitution_poisson", "restitution_energetic"):
            got.pop(key), metrics.pop(key)
    assert_same_metrics(got, metrics, rel=rel)
    ds = read(streamed.file)
    assert ds["centre_of_mass_velocity"].dims == ("time", "axis")
    assert ds["theta"].attrs["long_name"] == "Angle of the free beam's mean axis"
    return streamed, in_memory


@pytest.mark.parametrize("method", ["ccfm", "ccm", "imm"])
def test_a_streamed_free_bar_drop_writes_what_the_run_in_memory_writes(tmp_path, method):
    compare(tmp_path, fb.load_case(str(DROP)), method)


@pytest.mark.parametrize(("method", "t_end"), [("ccfm", 0.3), ("imm", 0.1)])
def test_a_bar_bouncing_on_a_floor_touched_at_both_ends_streams_its_episodes(tmp_path, method, t_end):
    """Two pairs, episodes on either end and across them, bit for bit."""
    streamed, _ = compare(tmp_path, tilted_drop(t_end), method)
    assert len({ep.pair for ep in streamed.episodes()}) == 2


@pytest.mark.parametrize("method", ["ccfm", "ccm", "imm"])
def test_episodes_across_parts_and_one_open_at_the_end(tmp_path, monkeypatch, method):
    """1 s of the tilted drop (IMM: to its max-contacts stop): with blocks of 256 steps and 1024 kept, the phases
    reach the stream in parts and the contacts that last are completed stretch by stretch; the bar's last episode --
    resting on its ends, its records open -- is open at the run's end (no end, no coefficients: it read the run's end
    as its end before).  The same as in memory, the impulses and works to round-off."""
    made, parts = in_parts(monkeypatch)
    streamed, in_memory = compare(tmp_path, tilted_drop(1.0), method, rel=PARTS_REL)
    if method != "imm":  # both paths were taken (IMM's chatter stops at max_contacts: its phases' lengths vary)
        assert made and parts.count(False) >= 3
    last = streamed.episodes()[-1]
    if method == "ccfm":  # resting on both ends to the end: open, so no end (as its open records), no coefficients
        assert in_memory.source.run.t_final == 1.0 and math.isnan(last.end)
        assert not math.isfinite(streamed.contacts[last.records[-1]].end)
        assert math.isnan(last.restitution_newton) and math.isnan(in_memory.episodes()[-1].restitution_newton)


def _peak(case, path) -> int:
    tracemalloc.start()
    try:
        fb.simulate(case, stream=path)
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_the_memory_of_a_streamed_free_bar_does_not_grow_with_its_length(tmp_path, monkeypatch):
    """tracemalloc's peak over 3 s and 30 s of the tilted drop (CCFM; resting on both ends from ~0.3 s: one open
    episode of two open records; blocks of 1024 steps, 4096 kept, chunks of 2048 samples): the longer run holds ~6x
    the steps of the shorter in memory (30 s: its resting contacts collocated at Radau's nodes take ~1 500 steps a
    second, where 15 s held only 1.9x the short run's streamed peak), streamed the same peak within 10 %."""
    monkeypatch.setattr(modal, "BLOCK_RECORDS", 1024)
    monkeypatch.setattr(stream, "WINDOW_RECORDS", 4096)
    monkeypatch.setattr(stream, "BATCH", 2048)
    monkeypatch.setattr(stream.export, "TIME_CHUNK", 2048)
    fb.simulate(tilted_drop(0.01), stream=tmp_path / "warm.nc")  # imports and caches
    short = _peak(tilted_drop(3.0), tmp_path / "short.nc")
    long = _peak(tilted_drop(30.0), tmp_path / "long.nc")
    run = fb.simulate(tilted_drop(30.0)).source.run  # in memory
    records = sum(s.dense.records.nbytes for s in run.segments if s.dense is not None)
    assert records > 2 * short, (records, short)
    assert long < 1.1 * short, (short, long)


def test_a_streamed_run_gives_its_episodes_for_the_default_gap_only(tmp_path):
    streamed = fb.simulate(fb.load_case(str(DROP)), stream=tmp_path / "r.nc")
    assert streamed.episodes(gap=streamed.summaries["episodes"][0]) == streamed.episodes()
    with pytest.raises(ValueError, match=r"^episodes: a streamed run's episodes were found with gap"):
        streamed.episodes(gap=1.0)
