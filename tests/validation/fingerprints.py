"""Fingerprints of runs of the built-in presets: a digest of everything a run reports.

Run as a script (``python -m tests.validation.fingerprints``) it prints one JSON object, case -> digest, for the
runs of :data:`RUNS`; ``test_same_answer.py`` runs it in child processes under different BLAS kernels, SIMD
levels and libm variants and compares the digests: the modal model must give the same bits everywhere
(``docs/methods.md``, "The same answer on every machine").
"""

from __future__ import annotations

import hashlib
import json
import struct
import sys
from pathlib import Path

import numpy as np

import flexbeam as fb
from flexbeam.results.metrics import METRICS

#: (preset, method, overrides): every preset with every method that runs on the compiled integrator, at lengths
#: that reach each preset's contacts (seed-experiment-calibrated's CCM and IMM, and theta(t) prescribed on it, among
#: them since they left scipy's DOP853, which calls the BLAS and agrees to a tolerance, not to the bit)
RUNS: list[tuple[str, str, dict]] = [
    ("seed-experiment", "ccfm", {}),
    ("seed-experiment", "ccm", {}),
    ("seed-experiment", "imm", {}),
    ("seed-experiment-calibrated", "ccfm", {}),
    ("seed-experiment-calibrated", "ccm", {}),
    ("seed-experiment-calibrated", "imm", {}),
    (
        "seed-experiment-calibrated",
        "ccfm",
        {"drive.kind": "prescribed", "drive.profile": "constant-rate", "drive.spin_rate": -1.0, "solver.t_end": 0.03},
    ),  # fmt: skip
    ("two-stops", "ccfm", {}),
    ("two-stops", "ccm", {}),
    ("two-stops", "imm", {}),
    ("spinning-stop", "ccfm", {"solver.t_end": 0.2}),
    ("spinning-stop", "ccm", {"solver.t_end": 0.2}),
    ("spinning-stop", "imm", {"solver.t_end": 0.2}),
    ("tip-wall", "ccfm", {}),
    ("tip-wall", "ccm", {}),
    ("tip-wall", "imm", {}),
    ("kane-spinup", "ccfm", {"solver.t_end": 4.0}),
    ("seed-experiment", "ccfm", {"initial.kind": "release", "solver.t_end": 0.02}),
    # the free beam (joint.kind = "free"): no preset yet, a case of tests/validation/data
    ("free-bar-drop.toml", "ccfm", {}),
    ("free-bar-drop.toml", "imm", {}),
    ("free-bar-drop.toml", "ccm", {}),
    # the axial modes (model.axial_modes): Saint-Venant's rod (a free beam) and the tip wall's revolute beam
    ("rod-end", "ccfm", {}),
    ("tip-wall", "ccfm", {"model.axial_modes": 8}),
    ("tip-wall", "ccm", {"model.axial_modes": 8}),
    ("tip-wall", "imm", {"model.axial_modes": 8}),
    # contact anywhere on the stretched centre line: the free bar at 70 degrees, the spinning stop's revolute beam
    ("free-bar-drop.toml", "ccfm", {"model.axial_modes": 8, "initial.impact_angle": 1.2217304763960306}),
    ("spinning-stop", "ccfm", {"solver.t_end": 0.2, "model.axial_modes": 4}),
]

#: where a run's case named by a file (not a preset) is
DATA = Path(__file__).resolve().parent / "data"


#: the metrics of a free beam's collision episodes (scope "free"): digested apart (:func:`episode_digest`), so that
#: adding them left the digests of the runs that existed before unchanged
EPISODE_METRICS = tuple(k for k, m in METRICS.items() if m.scope == "free")


def digest(sol) -> str:
    """SHA-256 (first 16 hex digits) of the contact records, the step count, the final state and the metrics (but
    those of :data:`EPISODE_METRICS`)."""
    h = hashlib.sha256()
    for c in sol.contacts:
        h.update(struct.pack("<8d", c.onset, c.end, c.velocity_before, c.velocity_after, c.impulse, c.peak_force,
                             c.peak_time, float(c.pair)))  # fmt: skip
    run = sol.source.run
    h.update(struct.pack("<2q", run.steps, len(sol.contacts)))
    if run.segments:
        h.update(np.ascontiguousarray(run.segments[-1].y1, float).tobytes())
    metrics = {k: v for k, v in sol.metrics().items() if k not in ("wall_time", "message", *EPISODE_METRICS)}
    h.update(json.dumps(metrics, sort_keys=True, default=repr).encode())
    return h.hexdigest()[:16]


def episode_digest(sol) -> str | None:
    """SHA-256 (first 16 hex digits) of a free beam's episode metrics; None for a beam on a joint."""
    metrics = sol.metrics()
    if "episodes" not in metrics:
        return None
    episodes = {k: metrics[k] for k in EPISODE_METRICS}
    return hashlib.sha256(json.dumps(episodes, sort_keys=True, default=repr).encode()).hexdigest()[:16]


def fingerprints() -> dict[str, str]:
    out = {}
    for name, method, over in RUNS:
        key = f"{name}/{method}" + "".join(f" {k}={v}" for k, v in over.items())
        source = DATA / name if name.endswith(".toml") else name
        sol = fb.simulate(fb.load_case(source, over), method)
        out[key] = digest(sol)
        episodes = episode_digest(sol)
        if episodes is not None:
            out[key + " episodes"] = episodes
    return out


if __name__ == "__main__":
    json.dump(fingerprints(), sys.stdout, indent=1, sort_keys=True)
