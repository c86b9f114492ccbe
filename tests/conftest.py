"""Shared fixtures: small cases built from the seed experiment."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

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


def signal_a_streaming_run(args: list[str], out: Path, signum: int) -> tuple[int, str, str]:
    """``flexbeam ARGS`` (a run streaming to ``out``/result.nc) in a subprocess, sent ``signum`` once the stream's
    temporary file is being written (not the probe of --out's check, made and removed before it): its exit code,
    stdout and stderr.  Ctrl-C's default action as a terminal gives it: a suite started in the background (``cmd &``
    without job control, nohup) ignores SIGINT, and so would the run it starts."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "flexbeam.cli", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )  # fmt: skip
    try:
        deadline = time.monotonic() + 120
        while not (out.is_dir() and any(p.name.startswith(".result.nc.") for p in out.iterdir())):
            assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
            time.sleep(0.05)
        proc.send_signal(signum)
        stdout, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    return proc.returncode, stdout, err
