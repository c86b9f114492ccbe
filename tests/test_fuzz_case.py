"""Fuzz the whole case schema through the command line: every input either runs or is refused in one line.

Cases are drawn from the real schema (:class:`flexbeam.parameters.case.Case`, read by introspection): a built-in
case with one to four of its fields -- any leaf of any table, ``[[obstacles]]`` entries included -- replaced by a
value of the field's own type and range, by a value near the old one, or by a bad one (wrong type, NaN, +-inf, 0,
negative, huge, tiny, an empty table, a list where a number belongs); tables emptied or given unknown keys; and
``[[obstacles]]`` lists of 0 - 9 entries (at most 7 are allowed) drawn field by field.  Each case is written as
TOML and run in-process through :func:`flexbeam.cli.main` with ``--json``, some of its fields also given by
``--set``, and ``solver.t_end`` capped at 2 ms so that a case that runs finishes fast.

Every example must end with exit code 0 (a complete run), 1 (a run that ended early: one line on stderr saying
why) or 2 (bad input: exactly one line on stderr naming a field), never with a traceback or an exception escaping
``main``, and within :data:`WALL_LIMIT` seconds (a SIGALRM at twice that stops a hang).
"""

from __future__ import annotations

import contextlib
import copy
import io
import math
import signal
import tempfile
import time
import typing
from pathlib import Path
from typing import Any, Literal

import pytest
import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pydantic import BaseModel

import flexbeam as fb
from flexbeam.cli import main
from flexbeam.parameters.case import Case, ExtraObstacle

#: a run of a fuzzed case must end within this [s].  Raised from 10 s (2026-11-26): the slowest of ~5000 random
#: examples had been 3.4 s (43 modes, on a loaded 2-core machine), but a case that failed at t = 0 before the reference
#: integrator's first-step retry (flexbeam.integrate.reference) now runs: seed-experiment-calibrated with a beam of
#: density 1 kg/m^3 under CCM (its compliant support on the reference path, the modes ~50x faster), 21 000 explicit
#: steps, 7.1 s on the idle machine and 19.4 s under CI's load.
WALL_LIMIT = 30.0
#: simulated time of a fuzzed case that runs [s]
T_CAP = 2e-3
PRESETS = tuple(fb.parameters.builtin_cases())
BAD = (
    "text", "", True, False, [], {}, [1.0], [1.0, 2.0, 3.0], ["a", "b"], {"x": 1.0}, [math.nan, 0.0],
    math.nan, math.inf, -math.inf, 0, 0.0, -0.0, -1, -1.0, -1e300, 1e300, 1e-300, 5e-324, 2**62, 1e20, -7,
)  # fmt: skip


# ----------------------------------------------------------------------------------------- the schema
def _unwrap(ann: Any) -> tuple[Any, list[Any]]:
    metas: list[Any] = []
    while typing.get_origin(ann) is typing.Annotated:
        ann, *extra = typing.get_args(ann)
        for m in extra:
            metas.extend(getattr(m, "metadata", [m]))
    return ann, metas


def _bounds(metas: list[Any]) -> tuple[float, float]:
    lo, hi = -1e6, 1e6
    for m in metas:
        for name, side in (("gt", "lo"), ("ge", "lo"), ("lt", "hi"), ("le", "hi")):
            v = getattr(m, name, None)
            if v is not None:
                lo, hi = (float(v), hi) if side == "lo" else (lo, float(v))
    return lo, hi


def typed(ann: Any, metas: list[Any] | None = None) -> st.SearchStrategy:
    """A value of the annotation's type, inside its constraints (for the fields without them, |x| <= 1e6)."""
    ann, more = _unwrap(ann)
    metas = (metas or []) + more
    origin = typing.get_origin(ann)
    if origin in (typing.Union, __import__("types").UnionType):
        return st.one_of([typed(a, metas) for a in typing.get_args(ann) if a is not type(None)])
    if origin is Literal:
        return st.sampled_from(typing.get_args(ann))
    if origin is tuple:
        return st.tuples(*(typed(a) for a in typing.get_args(ann))).map(list)
    if origin is list:
        (item,) = typing.get_args(ann)
        if isinstance(item, type) and issubclass(item, BaseModel):
            return st.lists(section(item), max_size=3)
        return st.lists(typed(item), max_size=4)
    if isinstance(ann, type) and issubclass(ann, BaseModel):
        return section(ann)
    if ann is bool:
        return st.booleans()
    lo, hi = _bounds(metas)
    if ann is int:
        return st.integers(int(max(lo, -100)), int(min(hi, 100)))
    if ann is float:
        return st.floats(max(lo, -1e6), min(hi, 1e6), allow_nan=False, exclude_min=True, exclude_max=True)
    return st.text(max_size=8)


def section(model: type[BaseModel]) -> st.SearchStrategy:
    """A table of ``model``: each field present with a value of its type, or absent."""
    fields = {name: st.one_of(st.none(), typed(info.annotation)) for name, info in model.model_fields.items()}
    return st.fixed_dictionaries(fields).map(lambda d: {k: v for k, v in d.items() if v is not None})


def leaves(model: type[BaseModel], prefix: tuple = ()) -> list[tuple[tuple, Any]]:
    """(path, annotation) of every field, tables included, descending into nested sections."""
    out = []
    for name, info in model.model_fields.items():
        path = (*prefix, name)
        ann, _ = _unwrap(info.annotation)
        out.append((path, info.annotation))
        if isinstance(ann, type) and issubclass(ann, BaseModel):
            out += leaves(ann, path)
    return out


CASE_LEAVES = leaves(Case)
OBSTACLE_LEAVES = leaves(ExtraObstacle)


# --------------------------------------------------------------------------------------- mutations
def _get(data: dict, path: tuple) -> Any:
    node: Any = data
    for p in path:
        if not isinstance(node, dict) or p not in node:
            return None
        node = node[p]
    return node


def _set(data: dict, path: tuple, value: Any) -> None:
    node = data
    for p in path[:-1]:
        if not isinstance(node.get(p), dict):
            node[p] = {}
        node = node[p]
    if value is _DELETE:
        node.pop(path[-1], None)
    else:
        node[path[-1]] = value


_DELETE = object()


@st.composite
def value_for(draw, ann: Any, old: Any) -> Any:
    """A new value for a field: of its type, near the old one, bad, or deleted."""
    kind = draw(st.sampled_from(["typed", "near", "bad", "delete"]))
    if kind == "near" and isinstance(old, (int, float)) and not isinstance(old, bool):
        factor = draw(st.sampled_from([0.0, 0.5, 0.9, 1.1, 2.0, -1.0, 10.0, 1e3]))
        return type(old)(old * factor) if math.isfinite(old * factor) else old
    if kind == "bad":
        return draw(st.sampled_from(BAD).map(copy.deepcopy))
    if kind == "delete":
        return _DELETE
    return draw(typed(ann))


@st.composite
def cases(draw) -> tuple[dict, list[str]]:
    """(case data, --set arguments)."""
    data = fb.load_case(draw(st.sampled_from(PRESETS))).model_dump(mode="json", exclude_none=True)
    for _ in range(draw(st.integers(1, 4))):
        what = draw(st.sampled_from(["field", "field", "field", "obstacles", "obstacle-field", "unknown", "empty"]))
        if what == "field":
            path, ann = draw(st.sampled_from(CASE_LEAVES))
            _set(data, path, draw(value_for(ann, _get(data, path))))
        elif what == "obstacles":
            entries = st.one_of(section(ExtraObstacle), st.sampled_from(BAD).map(copy.deepcopy))
            data["obstacles"] = draw(st.lists(entries, max_size=9))
        elif what == "obstacle-field" and isinstance(data.get("obstacles"), list) and data["obstacles"]:
            dicts = [i for i, e in enumerate(data["obstacles"]) if isinstance(e, dict)]
            if not dicts:
                continue
            entry = data["obstacles"][draw(st.sampled_from(dicts))]
            path, ann = draw(st.sampled_from(OBSTACLE_LEAVES))
            _set(entry, path, draw(value_for(ann, _get(entry, path))))
        elif what == "unknown":
            table = draw(st.sampled_from([None, *Case.model_fields]))
            key = draw(st.sampled_from(["zzz", "lenght", "t_ned", "Radius", "modes "]))
            if table is None:
                data[key] = 1.0
            elif isinstance(data.get(table), dict):
                data[table][key] = draw(st.sampled_from(BAD).map(copy.deepcopy))
        else:
            data[draw(st.sampled_from([*Case.model_fields]))] = {}
    sets = []
    if draw(st.booleans()):  # also a field given on the command line
        path, ann = draw(st.sampled_from(CASE_LEAVES))
        text = draw(st.sampled_from(["1", "0", "-1", "nan", "inf", "-inf", "1e300", "x", "[1, 2]", "{}", "true"]))
        sets = ["--set", f"{'.'.join(path)}={text}"]
    solver = data.setdefault("solver", {})
    t_end = solver.get("t_end", math.inf) if isinstance(solver, dict) else None
    if isinstance(t_end, (int, float)) and not isinstance(t_end, bool) and t_end > T_CAP:
        solver["t_end"] = T_CAP  # a case that runs finishes fast (its default, 0.1 s, too; a bad t_end stays bad)
    if sets and sets[1].startswith("solver.t_end="):
        sets = []
    return data, sets


# ------------------------------------------------------------------------------------------ the runs
class Hang(Exception):
    pass


def _alarm(signum, frame):
    raise Hang(f"a fuzzed case ran longer than {2 * WALL_LIMIT} s")


def run_cli(args: list[str]) -> tuple[int, str, str, float]:
    """(exit code, stdout, stderr, wall time) of ``flexbeam ARGS`` in-process."""
    out, err = io.StringIO(), io.StringIO()
    code = 0
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, 2 * WALL_LIMIT)
    t0 = time.perf_counter()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                main(args)
            except SystemExit as exc:
                code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)
    return code, out.getvalue(), err.getvalue(), time.perf_counter() - t0


def check_case(data: dict, sets: list[str], method: str = "ccfm") -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "case.toml"
        try:
            path.write_text(tomli_w.dumps(data), encoding="utf-8")
        except (TypeError, ValueError):  # not representable in TOML (a nested empty list of tables, ...)
            return
        code, out, err, wall = run_cli(["run", str(path), "--json", "--method", method, *sets])
    lines = [line for line in err.splitlines() if not line.startswith("warning: ")]
    assert "Traceback" not in err, err
    assert wall <= WALL_LIMIT, (wall, data, sets)
    assert code in (0, 1, 2), (code, err, data, sets)
    if code == 2:
        assert len(lines) == 1 and lines[0].startswith("error: "), (err, data, sets)
        assert out == ""
    elif code == 1:
        assert len(lines) == 1, err
        assert '"status"' in out
    else:
        assert lines == [], err
        assert '"status": "success"' in out


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(case=cases(), method=st.sampled_from(["ccfm", "ccm", "imm"]))
def test_every_case_runs_or_is_refused_in_one_line(case, method):
    """400 fuzzed cases (~10 s; the explore profile draws new ones)."""
    check_case(*case, method=method)


@pytest.fixture(scope="module")
def fe_compiled():
    """The FE reference's Numba kernels compiled (or loaded from their cache) before the timed examples."""
    fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 1e-4}), "fem")


@pytest.mark.slow
@settings(max_examples=3000, deadline=None, suppress_health_check=list(HealthCheck))
@given(case=cases(), method=st.sampled_from(["ccfm", "ccm", "imm", "fem"]))
def test_every_case_runs_or_is_refused_in_one_line_many(fe_compiled, case, method):
    """3000 fuzzed cases, the FE reference among the methods."""
    check_case(*case, method=method)
