"""A bifurcation diagram of a moving-base case: its branches up and down the drive frequency on Dask, each a task
that continues from point to point (:mod:`~flexbeam.bifurcation.continuation`), stored point by point so that an
interrupted diagram resumes where it stopped.

The store (``out``) holds ``branch-up.json`` and ``branch-down.json`` (``{"key": ..., "points": [...]}``: the points
computed so far, each written atomically by the worker as it finishes it -- the store is on a file system the
workers share, as the sweep's is --, and the key of the settings they were computed with, :func:`branch_key`: a
command with other settings computes its branches afresh) and the result, ``bifurcation.nc`` (:func:`build_dataset`).
"""

from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..errors import ParameterError
from ..parameters.case import Case
from ..parameters.io import validate_case
from ..results.files import atomic_path, write_text_atomic
from ..sweep.planning import case_key
from .continuation import Point, branch

BRANCHES = ("up", "down")


def check(case: Case, lo: float, hi: float, count: int, periods: int, discard: int, phase: float) -> None:
    """One line naming the option for what a diagram cannot be made of."""
    if not case.base.harmonics or not any(h.amplitude != 0.0 for h in case.base.harmonics):
        raise ParameterError("base.harmonics: a bifurcation diagram needs a base shaken by at least one harmonic")
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo and 0.0 < hi):
        raise ParameterError(f"--param: the frequencies must be finite and > 0 Hz (got {lo!r}:{hi!r})")
    if not 1 <= count <= 100_000:
        raise ParameterError(f"--param: the number of frequencies must be 1 to 100000 (got {count})")
    if (count == 1) != (lo == hi) or lo > hi:  # (the up branch climbs from lo to hi; N frequencies, ends included)
        raise ParameterError(f"--param: lo < hi for N >= 2 frequencies, lo = hi for N = 1 (got {lo!r}:{hi!r}:{count})")
    if not 1 <= periods <= 1_000_000:
        raise ParameterError(f"--periods: must be 1 to 1000000 (got {periods})")
    if not 0 <= discard < periods:
        raise ParameterError(f"--discard: must be >= 0 and below --periods = {periods} (got {discard})")
    if not 0.0 <= phase < 1.0:
        raise ParameterError(f"--phase: a fraction of the drive period in [0, 1) (got {phase})")


def branch_key(case: Case, method: str, periods: int, discard: int, phase: float) -> str:
    """What a branch's points depend on besides their frequencies: the case (its own ``base.frequency`` aside, which
    each point replaces), the method, ``periods``, ``discard`` and ``phase`` -- a hash (:func:`flexbeam.sweep.case_key`
    of the case), so that a store made with other settings is not resumed."""
    text = json.dumps([case_key(case, method, without=("base.frequency",)), periods, discard, repr(float(phase))])
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def stored_points(store: Path | None, key: str, frequencies: list[float]) -> list[Point]:
    """The points of the branch store ``store`` made with the settings ``key``, as far as they follow
    ``frequencies``; none from a store made with other settings (or unreadable, or of an earlier layout without the
    key), which is then computed afresh and overwritten point by point."""
    try:
        stored = json.loads(store.read_text(encoding="utf-8")) if store is not None and store.exists() else None
    except (OSError, ValueError):
        stored = None
    if not isinstance(stored, dict) or stored.get("key") != key:
        return []
    done = [Point.from_record(r) for r in stored["points"]]
    return [p for p, f in zip(done, frequencies) if p.frequency == f]  # the same grid only


def run_branch(data: dict[str, Any], method: str, frequencies: list[float], periods: int, discard: int, phase: float,
               path: str | None) -> list[dict[str, Any]]:  # fmt: skip
    """On a worker: one branch, resumed from the records at ``path`` (made with the same settings, :func:`branch_key`)
    and each new point added there as it ends."""
    from ..simulation import simulate

    case = validate_case(data)
    store = Path(path) if path else None
    key = branch_key(case, method, periods, discard, phase)
    done = stored_points(store, key, frequencies)
    records = [p.record() for p in done]
    for i, point in enumerate(branch(case, method, frequencies, periods, discard, phase, simulate, done)):
        if i >= len(done):
            records.append(point.record())
            if store:
                write_text_atomic(store, json.dumps({"key": key, "points": records}))
    return records


def bifurcation(
    case: Case,
    lo: float,
    hi: float,
    count: int,
    periods: int,
    discard: int,
    method: str = "ccfm",
    phase: float = 0.0,
    out: str | Path | None = None,
    scheduler: Any = None,
    workers: int | None = None,
) -> xr.Dataset:
    """The bifurcation diagram of ``case`` over ``count`` drive frequencies from ``lo`` to ``hi`` [Hz], swept up and
    down, ``periods`` periods each of which the first ``discard`` are the transient.

    Returns the :func:`build_dataset` Dataset, also written to ``out``/bifurcation.nc when a store is given.
    """
    from ..sweep.cluster import cluster_client
    from ..sweep.scheduler import check_scheduler, check_workers

    check(case, lo, hi, count, periods, discard, phase)
    check_workers(scheduler, workers)  # (before the store is made: -w 0 left an empty one)
    check_scheduler(scheduler)
    grid = [float(f) for f in np.linspace(lo, hi, count)]
    plans = {"up": grid, "down": grid[::-1]}
    store = Path(out) if out is not None else None
    if store is not None:
        store.mkdir(parents=True, exist_ok=True)
    data = case.model_dump(mode="json")
    with cluster_client(scheduler, workers) as client:
        futures = {
            name: client.submit(
                run_branch,
                data,
                method,
                freqs,
                periods,
                discard,
                phase,
                str(store / f"branch-{name}.json") if store else None,
                pure=False,
            )  # fmt: skip
            for name, freqs in plans.items()
        }
        results = {name: [Point.from_record(r) for r in fut.result()] for name, fut in futures.items()}
    ds = build_dataset(results, grid, case, method, periods, discard, phase)
    if store is not None:
        with atomic_path(store / "bifurcation.nc") as tmp:
            ds.to_netcdf(tmp)
    return ds


def build_dataset(results: dict[str, list[Point]], grid: list[float], case: Case, method: str, periods: int,
                  discard: int, phase: float) -> xr.Dataset:  # fmt: skip
    """Dims ``branch`` (up, down), ``frequency`` (ascending), ``section`` (the sections k = ``discard`` ..
    ``periods`` after the transient, the last at the run's end; NaN where a point has fewer: the first point of a
    branch sampled at ``phase`` > 0 has no section at its end) and ``impact`` (the contact records after it,
    NaN-padded): the Poincaré samples ``tip`` [m] and ``velocity`` [m/s], the impacts' ``impact_velocity`` [m/s] and
    ``impact_phase``, the frequency response ``amplitude`` [m] (the largest absolute tip deflection after the transient)
    and each point's ``status``."""
    nb, nf, ns = len(BRANCHES), len(grid), periods - discard + 1
    ni = max([1] + [p.impact_velocity.size for pts in results.values() for p in pts])
    tip, vel = np.full((nb, nf, ns), np.nan), np.full((nb, nf, ns), np.nan)
    iv, ip = np.full((nb, nf, ni), np.nan), np.full((nb, nf, ni), np.nan)
    amp = np.full((nb, nf), np.nan)
    status = np.full((nb, nf), "missing", dtype=object)
    index = {f: i for i, f in enumerate(grid)}
    for b, name in enumerate(BRANCHES):
        for p in results.get(name, []):
            j = index[p.frequency]
            k = min(ns, p.tip.size)
            tip[b, j, :k], vel[b, j, :k] = p.tip[:k], p.velocity[:k]
            iv[b, j, : p.impact_velocity.size], ip[b, j, : p.impact_phase.size] = p.impact_velocity, p.impact_phase
            amp[b, j], status[b, j] = p.amplitude, p.status
    return xr.Dataset(
        {
            "tip": (("branch", "frequency", "section"), tip,
                    {"units": "m", "long_name": "tip deflection at the section"}),
            "velocity": (("branch", "frequency", "section"), vel,
                         {"units": "m/s", "long_name": "contact point's normal velocity at the section"}),
            "impact_velocity": (("branch", "frequency", "impact"), iv,
                                {"units": "m/s", "long_name": "approach velocity of each impact (negative)"}),
            "impact_phase": (("branch", "frequency", "impact"), ip, {"units": "1", "long_name": "phase of the drive"}),
            "amplitude": (("branch", "frequency"), amp,
                          {"units": "m", "long_name": "largest |tip deflection| after the transient"}),
            "status": (("branch", "frequency"), status.astype(str)),
        },
        coords={"branch": list(BRANCHES), "frequency": ("frequency", np.asarray(grid), {"units": "Hz"})},
        attrs={"case": case.name, "method": method, "periods": periods, "discard": discard, "phase": phase},
    )  # fmt: skip
