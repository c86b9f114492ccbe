"""Runs streamed to their result file (``flexbeam run CASE --stream``, ``simulate(..., stream=path)``).

A streamed run must write what the same run held in memory writes -- the same samples bit for bit, the same contact
records and metrics -- while the memory it holds does not grow with its length.  The long-run paths (a phase handed
on in parts, a contact completed stretch by stretch) are reached in a short run by making their thresholds small:
in-memory and streamed runs share the stepper's block size, so they take the same steps.
"""

from __future__ import annotations

import json
import math
import re
import signal
import subprocess
import sys
import tracemalloc

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

import flexbeam as fb
from flexbeam import memory
from flexbeam.integrate import modal
from flexbeam.results import stream
from tests.conftest import seed, signal_a_streaming_run

COMPLIANT = {"obstacle__support__stiffness": 3e7, "obstacle__support__mass": 0.02, "obstacle__support__damping": 50.0}


def read(path):
    import xarray as xr

    with xr.open_dataset(path) as ds:
        return ds.load()


def same_value(a, b, rel: float = 0.0) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b)) or math.isclose(a, b, rel_tol=rel, abs_tol=0.0)
    return a == b


def assert_same_records(streamed, in_memory, rel: float = 0.0):
    """The contact records equal (``rel``: the impulse of a record completed stretch by stretch, summed part by
    part, to round-off)."""
    assert len(streamed.contacts) == len(in_memory.contacts)
    for a, b in zip(streamed.contacts, in_memory.contacts, strict=True):
        for key, value in vars(b).items():
            assert same_value(getattr(a, key), value, rel if key == "impulse" else 0.0), (b.index, key, value)


def assert_same_metrics(got, want, key="", rel: float = 0.0):
    """Equal metrics but the wall time (``rel``: impulses to round-off)."""
    if isinstance(want, dict):
        assert set(got) == set(want), key
        for k in want:
            if k != "wall_time":
                assert_same_metrics(got[k], want[k], f"{key}.{k}", rel)
    elif isinstance(want, list):
        assert len(got) == len(want), key
        for g, w in zip(got, want, strict=True):
            assert_same_metrics(g, w, key, rel)
    else:
        assert same_value(got, want, rel if key.endswith(".impulse") else 0.0), (key, got, want)


def assert_same_files(streamed, in_memory, rel: float = 0.0):
    """Every variable of the in-memory run's file in the streamed one, equal bit for bit (NaN where NaN; ``rel``:
    ``contact_impulse`` to round-off)."""
    a, b = read(streamed), read(in_memory)
    assert set(a.variables) == set(b.variables)
    for name in b.variables:
        assert a[name].dims == b[name].dims, name
        assert a[name].attrs == b[name].attrs, name
        if name == "contact_impulse" and rel:
            np.testing.assert_allclose(a[name].values, b[name].values, rtol=rel, atol=0.0, err_msg=name)
        elif b[name].dtype.kind == "f":
            np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)
        else:
            assert np.array_equal(a[name].values, b[name].values), name
    for key in ("status", "message", "method", "case_toml"):
        assert a.attrs[key] == b.attrs[key], key


@pytest.mark.parametrize(
    ("name", "method", "overrides"),
    [
        ("seed-experiment", "ccfm", {"solver__t_end": 0.1}),
        ("seed-experiment", "imm", {"solver__t_end": 0.05, "model__modes": 4}),
        ("seed-experiment", "ccfm", {"solver__t_end": 0.03, **COMPLIANT}),  # the sensor pulse
        ("two-stops", "ccfm", {"solver__t_end": 0.1, "model__modes": 4}),  # per-pair variables
        # friction: in memory the compiled stepper takes the switches, streamed the phase loop (friction_switch.c)
        ("tip-wall", "ccfm", {"solver__t_end": 0.03, "contact__friction": 0.3}),
    ],
    ids=["seed", "imm", "compliant", "two-stops", "friction"],
)
def test_a_streamed_run_writes_what_the_run_in_memory_writes(tmp_path, name, method, overrides):
    case = fb.load_case(name, {k.replace("__", "."): v for k, v in overrides.items()})
    in_memory = fb.simulate(case, method)
    metrics = in_memory.metrics()
    streamed = fb.simulate(case, method, stream=tmp_path / "streamed.nc")
    assert streamed.file == tmp_path / "streamed.nc" and streamed.source is None
    assert [p.name for p in tmp_path.iterdir()] == ["streamed.nc"]  # no temporary file left
    assert_same_files(streamed.file, in_memory.to_netcdf(tmp_path / "memory.nc"))
    assert_same_records(streamed, in_memory)
    assert_same_metrics(streamed.metrics(), metrics)
    assert json.loads(read(streamed.file).attrs["metrics"])["contact_records"] == metrics["contact_records"]
    # the Solution reads its samples from the file: the in-memory samples within the file's rounding
    np.testing.assert_array_equal(streamed.time, in_memory.time)
    np.testing.assert_array_equal(streamed.phase.astype(str), in_memory.phase.astype(str))
    np.testing.assert_allclose(streamed["contact_force"], in_memory["contact_force"], rtol=2**-24, atol=0.0)


def in_parts(monkeypatch) -> tuple[list[int], list[bool]]:
    """Blocks of 256 steps and 1024 kept, so that long phases reach the stream in parts and long contacts are
    completed stretch by stretch; returns the lists the run fills: the records completed as long contacts and each
    segment's ``closes`` (False: a part of a phase)."""
    monkeypatch.setattr(modal, "BLOCK_RECORDS", 256)
    monkeypatch.setattr(stream, "WINDOW_RECORDS", 1024)
    made, parts = [], []
    init, call = stream.LongContact.__init__, stream.RunStream.__call__

    def long_contact(self, s, i, src):
        made.append(i)
        init(self, s, i, src)

    def segment(self, seg):
        parts.append(seg.closes)
        call(self, seg)

    monkeypatch.setattr(stream.LongContact, "__init__", long_contact)
    monkeypatch.setattr(stream.RunStream, "__call__", segment)
    return made, parts


def test_long_phases_in_parts_and_a_long_contact_stretch_by_stretch(tmp_path, monkeypatch):
    """1.2 s of the seed case: the beam rests on its stop from 0.71 s, one contact record to the end.  With blocks
    of 256 steps and 1024 steps kept, that phase is handed on in parts and the open record completed stretch by
    stretch: the same samples, records and metrics as in memory (taking the same steps: the block size is the
    stepper's in both), but for the open record's impulse, summed part by part (~1e-16 relative)."""
    made, parts = in_parts(monkeypatch)
    case = seed(solver__t_end=1.2, output__interval=1e-4)
    in_memory = fb.simulate(case)
    metrics = in_memory.metrics()
    streamed = fb.simulate(case, stream=tmp_path / "streamed.nc")
    assert made and parts.count(False) > 10  # both paths were taken
    assert_same_files(streamed.file, in_memory.to_netcdf(tmp_path / "memory.nc"), rel=1e-14)
    assert_same_records(streamed, in_memory, rel=1e-14)
    assert_same_metrics(streamed.metrics(), metrics, rel=1e-14)


def test_a_resting_part_searches_no_tip_extreme_it_cannot_raise(tmp_path, monkeypatch):
    """3 s of the seed case handed on in parts: the tip's extremes of each part are searched above those the run has
    reached already, so the parts of the resting contact (its tip within ~1e-4 of the impacts' extremes, flat)
    refine no bracket -- searched from scratch each part's flat tip left every interval within reach of the part's
    own best: 17 s of a 40 s streamed run's 21 s.  The extremes equal the in-memory run's exactly."""
    in_parts(monkeypatch)
    from flexbeam.results.arrays import RunSource
    from flexbeam.results.extremes import TIP

    refine, late = RunSource.refine_max, []

    def counted(self, seg, column, *args, **kwargs):
        found = refine(self, seg, column, *args, **kwargs)
        if seg.t0 > 1.0 and column == TIP:  # brackets refined, not skipped (value -inf); not the records' peaks
            late.extend(found[1][np.isfinite(found[1])])
        return found

    monkeypatch.setattr(RunSource, "refine_max", counted)
    case = seed(solver__t_end=3.0, output__interval=1e-3)
    streamed = fb.simulate(case, stream=tmp_path / "streamed.nc").metrics()
    assert not late
    in_memory = fb.simulate(case).metrics()
    assert streamed["tip_deflection_max"] == in_memory["tip_deflection_max"]
    assert streamed["tip_deflection_min"] == in_memory["tip_deflection_min"]


def _peak(case, path) -> int:
    tracemalloc.start()
    try:
        fb.simulate(case, stream=path)
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_the_memory_of_a_streamed_run_does_not_grow_with_its_length(tmp_path, monkeypatch):
    """tracemalloc's peak over 1.5 s and 4.5 s of the seed case (blocks of 1024 steps, 4096 kept, chunks of 2048
    samples): the longer run holds 2.6x the steps of the shorter in memory, streamed the same peak.  (In memory its
    step records alone are more than twice the streamed peak; 5x before the resting contact's step cap was lifted
    after 20 contact durations, which cut its steps 2.5x.)"""
    monkeypatch.setattr(modal, "BLOCK_RECORDS", 1024)
    monkeypatch.setattr(stream, "WINDOW_RECORDS", 4096)
    monkeypatch.setattr(stream, "BATCH", 2048)
    monkeypatch.setattr(stream.export, "TIME_CHUNK", 2048)
    fb.simulate(seed(solver__t_end=0.01), stream=tmp_path / "warm.nc")  # imports and caches
    short = _peak(seed(solver__t_end=1.5, output__interval=1e-4), tmp_path / "short.nc")
    long = _peak(seed(solver__t_end=4.5, output__interval=1e-4), tmp_path / "long.nc")
    run = fb.simulate(seed(solver__t_end=4.5)).source.run  # in memory
    records = sum(s.dense.records.nbytes for s in run.segments if s.dense is not None)
    assert records > 2 * short, (records, short)
    assert long < 1.1 * short, (short, long)


def test_the_estimate_of_a_streamed_run_does_not_grow_with_its_length():
    cases = [fb.load_case("seed-experiment", {"solver.t_end": t, "output.interval": 1e-3}) for t in (100, 1e3, 1e6)]
    est = [memory.estimate(case, stream=True) for case in cases]
    assert est[0].total == est[1].total == est[2].total < 0.5e9
    assert est[0].streamed and est[0].max_t_end == math.inf
    assert memory.estimate(cases[1]).total > 10e9  # in memory: the run's dense output


def test_a_streamed_run_over_the_limit_is_refused_naming_the_limit():
    case = fb.load_case("seed-experiment", {"solver.t_end": 1e6, "solver.memory_limit": 1e6})
    with pytest.raises(fb.ParameterError, match=r"^solver\.memory_limit: a streamed run holds about .* whatever"):
        fb.simulate(case, stream="unused.nc")


def test_the_finite_element_reference_is_not_streamed(tmp_path):
    with pytest.raises(fb.ParameterError, match=r"^--stream: the finite-element reference"):
        fb.simulate(seed(solver__t_end=1e-3), "fem", stream=tmp_path / "r.nc")
    assert not any(tmp_path.iterdir())


def test_an_interrupted_streamed_run_leaves_no_file(tmp_path, monkeypatch):
    def stop(self, seg):
        raise KeyboardInterrupt

    monkeypatch.setattr(stream.RunStream, "_tally", stop)
    with pytest.raises(KeyboardInterrupt):
        fb.simulate(seed(solver__t_end=0.01), stream=tmp_path / "r.nc")
    assert not any(tmp_path.iterdir())


def flexbeam(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "flexbeam.cli", *args], capture_output=True, text=True, timeout=600)


def test_cli_stream_writes_the_outputs_and_the_same_metrics(tmp_path):
    sets = ("--set", "solver.t_end=0.05", "--set", "output.interval=1e-5")
    r = flexbeam("run", "seed-experiment", "--json", "--stream", "--out", str(tmp_path / "out"), *sets)
    assert r.returncode == 0, r.stderr
    out = tmp_path / "out"
    assert sorted(p.name for p in out.iterdir()) == [
        "contact_force.png", "normal_velocity.png", "result.nc", "summary.json",
    ]  # fmt: skip
    metrics = json.loads(r.stdout)
    want = json.loads(flexbeam("run", "seed-experiment", "--json", *sets).stdout)
    assert_same_metrics(metrics, want)
    ds = read(out / "result.nc")
    assert ds.sizes["time"] == len(fb.simulate(seed(solver__t_end=0.05, output__interval=1e-5)).time)


@pytest.mark.parametrize(
    ("args", "field", "fragment"),
    [
        (("--stream",), "--stream", "needs --out DIR"),
        (("--stream", "--out", "OUT", "--method", "fem"), "--stream", "finite-element reference"),
    ],
)
def test_cli_stream_bad_use(tmp_path, args, field, fragment):
    args = tuple(str(tmp_path / "out") if a == "OUT" else a for a in args)
    r = flexbeam("run", "seed-experiment", "--json", *args)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.splitlines() == [r.stderr.strip()] and r.stderr.startswith(f"error: {field}"), r.stderr
    assert fragment in r.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("signum", "code", "line"), [(signal.SIGTERM, 143, "terminated"), (signal.SIGINT, 130, "interrupted")]
)
def test_a_terminated_streamed_run_leaves_no_file(tmp_path, signum, code, line):
    """SIGTERM (``kill``, ``timeout``, a job scheduler) ends a streamed run as Ctrl-C does: exit 143, one line, and
    no file in --out (before: Python's default action for SIGTERM ended the process at once, exit -15, and left the
    6 MB temporary file ``.result.nc.XXXX`` behind).  Ctrl-C (SIGINT): exit 130 and one line too (before: none)."""
    out = tmp_path / "out"
    args = ["run", "seed-experiment", "--stream", "--out", str(out), "--set", "solver.t_end=1000",
            "--set", "output.interval=1e-3"]  # fmt: skip
    returncode, _, err = signal_a_streaming_run(args, out, signum)
    assert returncode == code, err
    assert err.strip().splitlines()[-1:] == [line], err
    assert not out.exists()  # (nor the directory the run made for it: it was left empty)


def test_a_streamed_run_whose_file_was_replaced_refuses_to_read_it(tmp_path):
    """Two runs streamed to one path in turn: the first's arrays, read afterwards, were the second's samples (988 N
    metrics against a 487 N force), and its to_netcdf copied them under its name.  Its file is checked to be the
    one it wrote (inode, size, time), before the samples and before each array is read."""
    path = tmp_path / "same.nc"
    a = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 2e-3}), stream=path)
    _ = a.time  # the samples' index read; the arrays are read one by one, later
    fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 2e-3, "initial.impact_velocity": -0.2}), stream=path)
    for read_it in (lambda: a["contact_force"], lambda: a.to_netcdf(tmp_path / "copy.nc"), a.to_xarray):
        with pytest.raises(RuntimeError, match="was replaced or removed since it was written"):
            read_it()
    assert not (tmp_path / "copy.nc").exists()


def test_a_streamed_run_cannot_be_written_unrounded(tmp_path):
    """``to_netcdf(path, quantize=False)`` of a streamed run copied its rounded file (quantization_nsb 23, 5.9e-8
    off the exact force): its samples were rounded as they were written, so it is refused; the default copy is
    the file."""
    sol = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 2e-3}), stream=tmp_path / "s.nc")
    with pytest.raises(ValueError, match="quantize=False: this run was streamed"):
        sol.to_netcdf(tmp_path / "exact.nc", quantize=False)
    assert sol.to_netcdf(tmp_path / "copy.nc").read_bytes() == (tmp_path / "s.nc").read_bytes()


@pytest.mark.parametrize(("name", "t_end"), [("seed-experiment", 0.1), ("two-stops", 0.1)])
def test_the_figures_of_a_streamed_run_read_their_window_alone(tmp_path, monkeypatch, name, t_end):
    """``flexbeam run --stream`` drew its figures from every sample of the file (the whole run read back: 90 MB more
    at 1000 s): they read the window they draw (readback.read_window) and draw what the run held in memory draws,
    its samples within the file's rounding; the Solution's samples stay in the file."""
    from flexbeam.views import plotting, report

    drawn: dict[str, list] = {}

    def keep(fig, path):
        drawn[str(path)] = [(ln.get_label(), ln.get_xdata(), ln.get_ydata()) for ln in fig.axes[0].lines]
        plotting.pyplot().close(fig)
        return path

    monkeypatch.setattr(plotting, "save_figure", keep)
    case = fb.load_case(name, {"solver.t_end": t_end, "model.modes": 4})
    report.write_run_outputs(fb.simulate(case), case, tmp_path / "memory")
    streamed = fb.simulate(case, stream=tmp_path / "streamed" / "result.nc")
    report.write_run_outputs(streamed, case, tmp_path / "streamed")
    assert streamed.samples_in_file
    for figure in ("contact_force.png", "normal_velocity.png"):
        want, got = drawn[str(tmp_path / "memory" / figure)], drawn[str(tmp_path / "streamed" / figure)]
        assert [g[0] for g in got] == [w[0] for w in want] and len(want[0][1]) > 100
        for (_, xg, yg), (_, xw, yw) in zip(got, want, strict=True):
            np.testing.assert_array_equal(xg, xw)
            np.testing.assert_allclose(yg, yw, rtol=2**-24, atol=0.0)


def test_a_window_of_a_result_file_holds_the_samples_at_its_ends(tmp_path):
    """read_window finds its ends by bisection on the file's time, whose phase boundaries are two samples each: a
    window from one phase boundary to the same instant holds both, as a mask on the whole time does."""
    from flexbeam.results.readback import read_window

    sol = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 0.02, "model.modes": 4}))
    onset = float(sol.time[np.nonzero(np.diff(sol.time) == 0.0)[0][0]])  # the first phase boundary
    assert (sol.time == onset).sum() == 2
    path = sol.to_netcdf(tmp_path / "w.nc")
    for a, b in ((onset, onset), (0.0, onset), (onset, 1.0), (-1.0, -0.5), (sol.time[5], sol.time[40])):
        time, phase, arrays = read_window(path, a, b)
        sel = (sol.time >= a) & (sol.time <= b)
        np.testing.assert_array_equal(time, sol.time[sel])
        assert phase.tolist() == sol.phase[sel].tolist()
        np.testing.assert_allclose(arrays["contact_force"], sol["contact_force"][sel], rtol=2**-24, atol=0.0)


@pytest.mark.parametrize(
    ("name", "method", "overrides"),
    [
        ("seed-experiment", "ccfm", {"solver.t_end": 0.1}),
        ("two-stops", "ccfm", {"solver.t_end": 0.1}),
        ("seed-experiment", "imm", {"solver.t_end": 0.3}),  # (a resting contact's force, away from the first)
        ("kane-spinup", "ccfm", {"solver.t_end": 0.5, "output.interval": 1e-4}),
    ],
)
def test_the_notebook_display_of_a_streamed_run_reads_a_window_and_an_envelope(
    tmp_path, monkeypatch, name, method, overrides
):
    """``_repr_html_`` of a streamed run read its time and phase labels whole (60 MB a 10^6 samples) and drew its
    whole-run lines from every sample (1.6 GB for 20 s of the seed case at the default sampling, 10^8 samples).  It
    reads the first contact's window as the figures do, and a whole run's line as its envelope, slice by slice
    (results.readback); it draws what the run held in memory draws, within the file's 2^-24 rounding, and the
    run's samples stay in its file."""
    from flexbeam.results.envelope import envelope
    from flexbeam.views import display

    drawn: list[list] = []

    def keep(draw, *args, **kwargs):
        ax = Figure().add_subplot()
        alt = draw(ax)
        drawn.append([alt] + [(ln.get_xdata(), ln.get_ydata()) for ln in ax.lines])
        return ""

    monkeypatch.setattr(display, "_png", keep)
    case = fb.load_case(name, {**overrides, "model.modes": 4})
    in_memory = fb.simulate(case, method)
    streamed = fb.simulate(case, method, stream=tmp_path / "s.nc")
    html = [sol._repr_html_() for sol in (in_memory, streamed)]
    assert streamed.samples_in_file
    spans = [re.search(r"[^>]* to [^<]* samples", h).group(0) for h in html]
    assert spans[0] == spans[1] and spans[0].endswith(f"{in_memory.time.size} samples")
    want, got = drawn
    assert got[0] == want[0] and len(got) == len(want) > 1
    whole = {"normal velocity of the contact point": "normal_velocity", "tip deflection": "tip_deflection"}.get(want[0])
    assert whole is not None or want[0].startswith("contact force")
    for (xg, yg), (xw, yw) in zip(got[1:], want[1:], strict=True):
        if whole:  # the envelope of the file's samples, reduced (2 a bin) and within the rounding of the run's
            assert len(in_memory.time) > 2 * 1000 and len(xw) <= 2000
            with xr.open_dataset(streamed.file) as ds:
                xs, ys = envelope(ds["time"].values, ds[whole].values)
            np.testing.assert_array_equal(xg, xs)
            np.testing.assert_array_equal(yg, ys)
            np.testing.assert_allclose([np.nanmin(yg), np.nanmax(yg)], [np.nanmin(yw), np.nanmax(yw)], rtol=2**-24)
        else:
            np.testing.assert_array_equal(xg, xw)
            np.testing.assert_allclose(yg, yw, rtol=2**-24, atol=0.0)
