"""A run ended early by Ctrl-C or SIGTERM keeps what it computed when asked to (``flexbeam run --keep-interrupted``,
``fb.simulate(..., keep_interrupted=True)``): status "interrupted", its samples and contact records those of the
uninterrupted run up to where it stopped, streamed or held in memory, the metrics over that stretch, and the exit
code of an interrupted command (130, 143).  Without the option nothing changes (tests/test_stream.py: an
interrupted streamed run leaves no file).
"""

from __future__ import annotations

import json
import math
import os
import signal
import threading

import numpy as np
import pytest
import xarray as xr

import flexbeam as fb
from flexbeam.simulation import simulate
from tests.conftest import seed, signal_a_streaming_run

#: the sampled variables compared (the state, its angle, the force, the energy balance's total)
COMPARED = ("q", "theta", "contact_force", "total_energy")


def after(calls: int):
    """A ``stop`` that says "Ctrl-C" from its (calls + 1)-th question on, as the flag of a signal does once hit."""
    asked = [0]

    def stop() -> str:
        asked[0] += 1
        return "Ctrl-C" if asked[0] > calls else ""

    return stop


def assert_the_start_of(full, part) -> None:
    """``part`` is ``full`` up to where it stopped: each sample at a time both hold equal to the bit, each record
    that ended before the stop the same (onset, end, peak, impulse), and a record open at the stop left open."""
    t_stop = part.time[-1]
    _, i, j = np.intersect1d(full.time, part.time, return_indices=True)
    assert j.size >= np.unique(part.time).size - 1  # (all but the stop's own sample)
    for name in COMPARED:
        a, b = np.asarray(full[name])[i], np.asarray(part[name])[j]
        assert np.array_equal(a, b, equal_nan=True), name
    done = [r for r in part.records if math.isfinite(r.end)]
    for r, s in zip(done, full.records, strict=False):
        assert (r.onset, r.end, r.peak_force, r.impulse) == (s.onset, s.end, s.peak_force, s.impulse)
    assert all(r.onset <= t_stop for r in part.records)
    if len(done) < len(part.records):  # one still in contact: its end is the run's, unknown
        assert len(done) == len(part.records) - 1 and full.records[len(done)].end > t_stop


@pytest.mark.parametrize(("method", "calls"), [("ccfm", 1), ("ccfm", 2), ("ccm", 0), ("ccm", 1)])
def test_a_stopped_run_is_the_uninterrupted_runs_start(method, calls):
    """The seed case to 0.05 s, stopped at the compiled stepper's block boundaries or phase ends: what it keeps is
    the whole run's to the bit (the steps of a phase are those of one long kernel call, whatever its blocks)."""
    case = seed(solver__t_end=0.05)
    full, part = simulate(case, method), simulate(case, method, stop=after(calls))
    assert part.status == "interrupted" and part.time[-1] < case.solver.t_end
    assert part.message.startswith(f"interrupted at t = {part.time[-1]:.9g} s (Ctrl-C)")
    assert_the_start_of(full, part)
    metrics = part.metrics()
    assert metrics["status"] == "interrupted" and metrics["message"] == part.message


def test_the_reference_integrator_and_the_finite_element_reference_stop_at_a_step():
    """scipy's DOP853 (``solver.integrator = "reference"``) is asked after each step, the FE reference too."""
    for case, method in ((seed(solver__t_end=0.01, solver__integrator="reference"), "ccfm"),
                         (seed(solver__t_end=2e-3), "fem")):  # fmt: skip
        full, part = simulate(case, method), simulate(case, method, stop=after(200))
        assert part.status == "interrupted" and 0.0 < part.time[-1] < case.solver.t_end, method
        _, i, j = np.intersect1d(full.time, part.time, return_indices=True)
        for name in ("theta", "contact_force", "total_energy"):
            assert np.array_equal(np.asarray(full[name])[i], np.asarray(part[name])[j]), (method, name)


def test_a_stopped_streamed_run_writes_what_the_stopped_run_in_memory_holds(tmp_path, monkeypatch):
    """Streamed in parts of 2048 steps (so that the stop falls inside a long phase handed on in parts), stopped at
    its third question: the file holds the run in memory stopped alike, and says it was interrupted."""
    monkeypatch.setattr(fb.integrate.modal, "BLOCK_RECORDS", 2048)
    case = seed(solver__t_end=2.0, output__interval=1e-4)
    held = simulate(case, "ccfm", stop=after(3))
    path = tmp_path / "r.nc"
    streamed = simulate(case, "ccfm", stream=path, stop=after(3))
    assert held.status == streamed.status == "interrupted" and held.message == streamed.message
    with xr.open_dataset(path) as ds:
        assert ds.attrs["status"] == "interrupted"
        assert np.array_equal(ds["time"].values, held.time)
        np.testing.assert_allclose(ds["contact_force"].values, held["contact_force"], rtol=2**-22, atol=0)
    assert [(r.onset, r.end) for r in streamed.records] == [(r.onset, r.end) for r in held.records]


@pytest.fixture
def ctrl_c():
    """Python's default Ctrl-C handler (a suite started in the background inherits SIGINT ignored)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def test_ctrl_c_in_the_python_api_returns_what_was_computed_when_asked(tmp_path, ctrl_c):
    """``fb.simulate(..., keep_interrupted=True)``: a Ctrl-C 0.5 s into a 1000 s run (streamed: ~25 s whole) returns
    the Solution, status "interrupted", and the handler before it is back; the option takes a bool only.  (Without
    it a Ctrl-C raises, as always: tests/test_stream.py's interrupted runs.)"""
    case = seed(solver__t_end=1000.0, output__interval=1e-3)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        sol = fb.simulate(case, stream=tmp_path / "r.nc", keep_interrupted=True)
    finally:
        timer.cancel()
    assert sol.status == "interrupted" and 0.0 < sol.time[-1] < 1000.0
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # restored
    with pytest.raises(fb.ParameterError, match="keep_interrupted: True or False"):
        fb.simulate(seed(), keep_interrupted="yes")


@pytest.mark.parametrize(
    ("signum", "code", "cause"), [(signal.SIGTERM, 143, "SIGTERM"), (signal.SIGINT, 130, "Ctrl-C")]
)
def test_cli_keep_interrupted_writes_the_outputs_and_exits_as_interrupted(tmp_path, signum, code, cause):
    """``flexbeam run --stream --keep-interrupted``, signalled while it streams a 1000 s run: exit 128 + signum, one
    line saying where it stopped, and --out holding result.nc (status "interrupted") and summary.json."""
    out = tmp_path / "out"
    args = ["run", "seed-experiment", "--stream", "--keep-interrupted", "--json", "--out", str(out),
            "--set", "solver.t_end=1000", "--set", "output.interval=1e-3"]  # fmt: skip
    returncode, stdout, err = signal_a_streaming_run(args, out, signum)
    assert returncode == code, err
    assert err.strip().splitlines()[-1].startswith("ccfm: run ended early with status 'interrupted': interrupted at")
    assert f"({cause})" in err
    metrics = json.loads(stdout)
    assert metrics["status"] == "interrupted"
    assert json.loads((out / "summary.json").read_text())["metrics"]["status"] == "interrupted"
    with xr.open_dataset(out / "result.nc") as ds:
        assert ds.attrs["status"] == "interrupted" and 0.0 < float(ds["time"][-1]) < 1000.0
