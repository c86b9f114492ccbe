"""The ``flexbeam run --json`` output against the JSON Schema shipped with the package (draft 2020-12), for every
built-in case under each impact method; the schema against the metrics registry; what the counts, ``pairs`` and
``events`` of one output say about each other."""

from __future__ import annotations

import json
from typing import Any

import pytest
from jsonschema import Draft202012Validator

import flexbeam as fb
from flexbeam.cli import main
from flexbeam.model.joints import JOINTS
from flexbeam.results.metrics import METRICS, OPTIONAL_SCOPES
from flexbeam.schemas import run_schema

COUNTS = ("contacts", "contact_records", "micro_impacts", "chatter_episodes")
#: the compliant-support case under CCM and IMM: ~10 s each (its sensor metrics sample the whole run)
SLOW = {("seed-experiment-calibrated", "ccm"), ("seed-experiment-calibrated", "imm")}
#: runs that are not a case's: a method its joint kind refuses (JOINTS[kind].unsupported_methods), and IMM on
#: rod-end, whose every impulse meets the rod end's effective mass m/(1 + 2 n_a) so that the impacts accumulate
#: (Zeno, status max-contacts; docs/formulation.md, "Axial deformation")
NOT_RUN = {("rod-end", "imm")}
RUNS = [
    pytest.param(case, method, marks=[pytest.mark.slow] if (case, method) in SLOW else [])
    for case in sorted(fb.builtin_cases())
    for method in ("ccfm", "ccm", "imm")
    if (case, method) not in NOT_RUN and method not in JOINTS[fb.load_case(case).joint.kind].unsupported_methods
]


def strict_json(text: str) -> Any:
    """Parse JSON, refusing the NaN / Infinity that Python's json module would accept."""

    def refuse(name: str) -> Any:
        raise ValueError(f"not strict JSON: {name}")

    return json.loads(text, parse_constant=refuse)


def run_json(capsys, *args: str) -> dict[str, Any]:
    """What ``flexbeam run ARGS --json`` prints (the CLI in this process)."""
    main(["run", *args, "--json"])
    out = capsys.readouterr()
    assert out.err == ""
    return strict_json(out.out)


@pytest.fixture(scope="module")
def validator() -> Draft202012Validator:
    schema = run_schema()
    Draft202012Validator.check_schema(schema)
    return Draft202012Validator(schema)


def assert_consistent(data: dict[str, Any]) -> None:
    """The counts, the per-pair records and the events of one output agree."""
    events, pairs = data["events"], data["pairs"]
    assert data["contacts"] + data["micro_impacts"] == data["contact_records"] == len(events)
    assert [ev["index"] for ev in events] == list(range(len(events)))
    assert [ev["onset"] for ev in events] == sorted(ev["onset"] for ev in events)
    assert [p["pair"] for p in pairs] == list(range(len(pairs)))
    for key in COUNTS:
        assert sum(p[key] for p in pairs) == data[key], key
    for p in pairs:
        mine = [ev for ev in events if ev["pair"] == p["pair"]]
        assert all(ev["obstacle"] == p["obstacle"] for ev in mine)
        assert p["contact_records"] == len(mine)
        assert p["contacts"] == sum(ev["kind"] == "contact" for ev in mine)
        # an episode is a run of consecutive micro-impacts of this pair; a contact ends it
        runs: list[int] = []
        for prev, ev in zip([None, *mine], mine):
            if ev["kind"] == "micro-impact" and (prev is None or prev["kind"] == "contact"):
                runs.append(ev["chatter_episode"])
            elif ev["kind"] == "micro-impact":
                assert ev["chatter_episode"] == prev["chatter_episode"]
        assert p["chatter_episodes"] == len(runs) == len(set(runs))
    firsts = [ev["chatter_episode"] for ev in events if ev["chatter_episode"] is not None]
    assert list(dict.fromkeys(firsts)) == list(range(data["chatter_episodes"]))  # numbered in order of onset
    for key in ("impact_velocity", "peak_force", "contact_duration", "impulse", "force_peaks"):
        assert pairs[0][key] == data[key], key  # the first pair's first contact is the top level's


@pytest.mark.parametrize(("case", "method"), RUNS)
def test_run_json_of_every_builtin_case_matches_the_schema(capsys, validator, case, method):
    data = run_json(capsys, case, "--method", method)
    errors = sorted(validator.iter_errors(data), key=lambda e: list(e.absolute_path))
    assert not errors, [f"{list(e.absolute_path)}: {e.message}" for e in errors[:5]]
    assert data["method"] == method and data["status"] == "success"
    assert_consistent(data)


def test_a_pair_that_never_touched_has_every_key_with_null_values(capsys, validator):
    # two-stops for 2 ms: the beam lands on the lower stop (pair 0) at t = 0 and cannot reach the upper one
    data = run_json(capsys, "two-stops", "--method", "ccfm", "--set", "solver.t_end=0.002")
    validator.validate(data)
    touched, untouched = data["pairs"]
    assert touched["contacts"] >= 1 and set(untouched) == set(touched)
    assert {k: untouched[k] for k in COUNTS} == dict.fromkeys(COUNTS, 0)
    for key, value in untouched.items():
        if key not in ("pair", "obstacle", *COUNTS):
            assert value is None or value == [], (key, value)
    assert all(ev["pair"] == 0 for ev in data["events"])


def test_schema_lists_every_metric_with_the_type_of_its_kind():
    schema = run_schema()
    props, defs = schema["properties"], schema["$defs"]
    assert set(props) == set(METRICS)
    assert set(schema["required"]) == {k for k, m in METRICS.items() if m.scope not in OPTIONAL_SCOPES}
    assert schema["additionalProperties"] is False
    expected = {
        "count": {"$ref": "#/$defs/count"},
        "number": {"$ref": "#/$defs/number"},
        "text": {"type": "string"},
        "numbers": {"type": "array", "items": {"type": "number"}},
    }
    for name, metric in METRICS.items():
        spec = {k: v for k, v in props[name].items() if k != "description"}
        if metric.kind == "records":
            refs = ("#/$defs/pair", "#/$defs/event", "#/$defs/episode")
            assert spec["type"] == "array" and spec["items"]["$ref"] in refs, name
        else:
            assert spec == expected[metric.kind], name
    assert defs["count"] == {"type": "integer", "minimum": 0}
    assert defs["number"] == {"type": ["number", "null"]}
    for record in ("pair", "event", "episode"):
        assert set(defs[record]["required"]) == set(defs[record]["properties"])
        assert defs[record]["additionalProperties"] is False


@pytest.mark.parametrize("method", ["ccfm", "imm"])
def test_a_free_beam_adds_its_collision_episodes(capsys, validator, method):
    """The free bar drop (tests/validation/data): the schema holds with the episode keys, every record is in exactly
    one episode (in the order of onsets) and each episode's counts are those of its events; a revolute case has
    none of the episode keys."""
    from pathlib import Path

    case = Path(__file__).parent / "validation" / "data" / "free-bar-drop.toml"
    data = run_json(capsys, str(case), "--method", method)
    validator.validate(data)
    assert_consistent(data)
    episodes, events = data["episodes"], data["events"]
    assert data["collision_episodes"] == len(episodes) >= 1
    assert [i for ep in episodes for i in ep["records"]] == list(range(len(events)))
    for ep in episodes:
        kinds = [events[i]["kind"] for i in ep["records"]]
        assert ep["contacts"] == kinds.count("contact") and ep["micro_impacts"] == kinds.count("micro-impact")
        assert ep["onset"] == events[ep["records"][0]]["onset"]
    first = episodes[0]
    assert data["episode_contacts"] == first["contacts"]
    for key in ("restitution_newton", "restitution_poisson", "restitution_energetic"):
        assert data[key] == first[key] and 0.0 < data[key] < 1.0
    revolute = run_json(capsys, "tip-wall", "--method", method, "--set", "solver.t_end=0.01")
    assert not {k for k, m in METRICS.items() if m.scope == "free"} & set(revolute)
