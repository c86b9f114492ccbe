"""Seed experiment over 0.1 s: flexbeam's integrators against scipy's ``solve_ivp`` and Exudyn.

Run: ``python benchmarks/seed.py`` (Markdown tables on stdout; ``--json`` for one JSON
object; ``--quick`` for a smoke run of a few seconds: 2 modes, 2 ms, one repeat, no
cold compile, no Exudyn).  ``--help`` lists the knobs (modes, repeats, time budget, ...).

What is measured, all in this one run on this machine (the header names the machine, the
library versions and the load average -- timings on a loaded machine are noisy):

* **flexbeam** -- ``fb.simulate(case, method)`` of the ``seed-experiment`` case with
  ``model.modes`` = n (default 4, 8, 12, 16, 32) for the methods CCFM and CCM and
  ``solver.integrator`` = ``"reference"`` and ``"exponential"`` (the compiled modal
  integrator).  Each configuration is first run once over 2 ms (warm-up), then timed over
  ``--repeats`` runs, fewer if the runs of that row exceed ``--budget`` seconds (at least
  one; the ``runs`` column says how many).  ``wall`` is the median of the Solution's own
  ``metrics()["wall_time"]`` (the integration alone); ``simulate`` the median of the whole
  ``simulate()`` call (set-up, integration, the contact log's peaks and impulses on the
  dense output; the output samples are evaluated only when asked for); ``metrics`` the
  median of the ``metrics()`` call that follows.  ``free max`` is the most steps a free
  flight took, ``contact med/max`` the median and largest steps per contact phase.  ``ran`` is the
  integrator the Solution reports it used (``metrics()["integrator"]`` if present, else
  ``provenance["integrator"]``): a configuration may fall back to the reference path.
  ``peak`` is the first contact's peak force, ``d ref(n)`` its relative difference from
  the reference integrator at the same n (the integration error alone) and
  ``d conv`` from the converged value, which is the reference integrator
  (DOP853, rtol 1e-9, atol 1e-12) of the same method at the highest n of the table, or at
  ``--converged-modes`` if given (that difference includes the modal truncation).
* **scipy** -- a plain ``scipy.integrate.solve_ivp(method="DOP853")`` of the same CCFM
  model (``BeamSystem.rhs_function``, the same compiled right-hand side): the free phase
  until a terminal gap-closing event, then the contact phase with the law's parameters
  fixed at onset (as CCFM does) until the separation event, and so on to t_end, at
  ``--scipy-rtol``/``--scipy-atol``.  No step limit or other help from flexbeam's
  event machinery.  The peak force is found on its dense output.  The ratio column
  ``scipy/x`` is scipy's median integration time over the flexbeam row's ``wall``.
* **start-up** -- the first run after installing: ``flexbeam run seed-experiment --json``
  in a fresh process with ``NUMBA_CACHE_DIR`` pointed at an empty directory (the compiled
  kernels are built by pip; Numba serves only the finite-element reference), and a
  subprocess that times the first and second 2 ms ``simulate()`` per integrator.  The warm
  start-up is ``flexbeam run seed-experiment --json`` (and ``flexbeam --help``) timed from
  process start to exit, median of ``--startup-runs``.
* **kane-spinup** -- 20 s of the Kane spin-up on each integrator.
* **Exudyn** (if importable; ``pip install flexbeam[bench]``) -- the equivalent model:
  32 ``ObjectANCFCable2D`` elements, the first node pinned at O (a revolute joint),
  gravity, started straight at the contact configuration with the rigid rotation that
  gives P a normal velocity of -0.4 m/s, the sphere as a Lankarani-Nikravesh
  Hertz-type spring-damper (the same K, exponent and restitution as flexbeam's law)
  between P on the cable and the sphere's centre, 0.1 s of Exudyn's default implicit
  solver (generalized-alpha) at a fixed 1e-5 s step.  Timed: the solve alone (median
  of the repeats), ratio ``exudyn/x`` against the flexbeam CCFM row at 16 modes.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from collections.abc import Callable
from typing import Any

import numpy as np

import flexbeam as fb
from flexbeam.integrate.phases import ContactMode
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import initial_state

CASE = "seed-experiment"
METHODS = ("ccfm", "ccm")
INTEGRATORS = ("reference", "exponential")
COLUMNS = (
    "method",
    "n",
    "integrator",
    "ran",
    "runs",
    "wall [ms]",
    "simulate [ms]",
    "metrics [ms]",
    "steps",
    "free max",
    "contact med/max",
    "peak [N]",
    "d ref(n)",
    "d conv",
    "scipy [ms]",
    "scipy/x",
)


# ---------------------------------------------------------------------------- helpers
def timed(fn: Callable[[], Any], repeats: int, budget: float) -> list[tuple[float, Any]]:
    """(seconds, result) of up to ``repeats`` calls, stopping once ``budget`` s are spent."""
    out = []
    start = time.perf_counter()
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = fn()
        out.append((time.perf_counter() - t0, res))
        if time.perf_counter() - start > budget:
            break
    return out


def median(values: list[float]) -> float:
    values = [v for v in values if v is not None and math.isfinite(v)]
    return statistics.median(values) if values else math.nan


def rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b) if b and math.isfinite(a) and math.isfinite(b) else math.nan


def integrator_ran(sol) -> str:
    """Which integrator the Solution says it used: 'exponential' or 'reference'."""
    text = str(sol.metrics().get("integrator") or sol.provenance.get("integrator", "?"))
    low = text.lower()
    if "exponential" in low or "modal" in low:
        return "exponential"
    if "reference" in low or "dop853" in low:
        return "reference"
    return text


def case_for(n: int, integrator: str, t_end: float):
    return fb.load_case(CASE, {"model.modes": n, "solver.integrator": integrator, "solver.t_end": t_end})


def environment() -> dict[str, Any]:
    import numba
    import scipy

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), cpu)
    except OSError:
        pass
    return {
        "machine": f"{platform.machine()} {cpu}".strip(),
        "cores": cores,
        "python": platform.python_version(),
        "flexbeam": fb.__version__,
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
        "exudyn": _exudyn_version(),
        "load_average": os.getloadavg()[0] if hasattr(os, "getloadavg") else math.nan,
    }


def _exudyn_version() -> str | None:
    try:
        import exudyn
    except ImportError:
        return None
    return str(getattr(exudyn, "__version__", None) or exudyn.GetVersionString())


# --------------------------------------------------------------------- flexbeam rows
def flexbeam_row(method: str, n: int, integrator: str, args) -> dict[str, Any]:
    row: dict[str, Any] = {"method": method, "n": n, "integrator": integrator}
    try:
        fb.simulate(case_for(n, integrator, min(2e-3, args.t_end)), method)  # compile / load the kernels
        case = case_for(n, integrator, args.t_end)
        runs = timed(lambda: fb.simulate(case, method), args.repeats, args.budget)
    except Exception as exc:  # the integrator under development may fail: report, keep going
        row["error"] = f"{type(exc).__name__}: {exc}"
        return row
    sols = [s for _, s in runs]
    metrics, metric_times = [], []
    for s in sols:
        t0 = time.perf_counter()
        metrics.append(s.metrics())
        metric_times.append(time.perf_counter() - t0)
    m = metrics[-1]
    phase_steps = getattr(getattr(sols[-1], "source", None), "run", None)
    phase_steps = phase_steps.phase_steps if phase_steps is not None else []
    free = [k for name, k in phase_steps if name == "free"]
    contact = [k for name, k in phase_steps if name != "free"]
    row.update(
        ran=integrator_ran(sols[-1]),
        runs=len(runs),
        status=m["status"],
        wall=median([x["wall_time"] for x in metrics]),
        simulate=median([t for t, _ in runs]),
        metrics=median(metric_times),
        steps=m["steps"],
        nfev=m["nfev"],
        peak=m["peak_force"],
        contacts=m["contacts"],
        duration=m["contact_duration"],
        free_max=max(free) if free else None,
        contact_median=statistics.median(contact) if contact else None,
        contact_max=max(contact) if contact else None,
    )
    return row


# ----------------------------------------------------------- plain scipy solve_ivp (CCFM)
def scipy_ccfm(case, rtol: float, atol: float) -> dict[str, Any]:
    """The CCFM model integrated by ``solve_ivp(method="DOP853")`` with terminal gap events."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import minimize_scalar

    system = BeamSystem.from_case(case)
    y, _ = initial_state(system, case)
    t, t_end = 0.0, case.solver.t_end
    free = system.rhs_function()

    def gap(t: float, y: np.ndarray) -> float:
        return system.gap(t, y)[0]

    onset = lambda t, y: gap(t, y)
    onset.terminal, onset.direction = True, -1
    separation = lambda t, y: gap(t, y)
    separation.terminal, separation.direction = True, +1

    delta, vn, _, _ = system.gap(t, y)
    in_contact = delta <= 1e-12 and vn < 0.0
    steps = nfev = contacts = 0
    first_contact = None
    start = time.perf_counter()
    while t < t_end:
        if in_contact:
            vn = system.gap(t, y)[1]
            p = system.law.parameters(-vn, system.effective_mass(t, y))
            contact = system.contacts([ContactMode.FORCE], p[None, :])
            fun, event = system.rhs_function(contact), separation
            contacts += 1
        else:
            fun, event = free, onset
        sol = solve_ivp(
            fun,
            (t, t_end),
            y,
            method="DOP853",
            rtol=rtol,
            atol=atol,
            events=[event],
            dense_output=in_contact and contacts == 1,
        )
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {sol.t[-1]}: {sol.message}")
        steps += sol.t.size - 1
        nfev += sol.nfev
        if in_contact and contacts == 1:
            first_contact = (t, sol.t[-1], sol.sol, p)
        if sol.status == 1:
            t, y = float(sol.t_events[0][0]), sol.y_events[0][0]
            in_contact = not in_contact
        else:
            t = t_end
    wall = time.perf_counter() - start
    peak = math.nan
    if first_contact is not None:  # peak force on the dense output of the first contact
        t0, t1, dense, p = first_contact
        contact = system.contacts([ContactMode.FORCE], p[None, :])
        force = lambda s: float(system.rhs(s, dense(s), contact)[1][0])
        grid = np.linspace(t0, t1, 401)
        forces = [force(s) for s in grid]
        i = int(np.argmax(forces))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        res = minimize_scalar(lambda s: -force(s), bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
        peak = max(forces[i], -res.fun)
    return {"wall": wall, "steps": steps, "nfev": nfev, "peak": peak, "contacts": contacts}


def scipy_row(n: int, args) -> dict[str, Any]:
    case = case_for(n, "reference", args.t_end)
    try:
        scipy_ccfm(case_for(n, "reference", min(2e-3, args.t_end)), args.scipy_rtol, args.scipy_atol)
        runs = timed(lambda: scipy_ccfm(case, args.scipy_rtol, args.scipy_atol), args.repeats, args.budget)
    except Exception as exc:
        return {"n": n, "error": f"{type(exc).__name__}: {exc}"}
    last = runs[-1][1]
    return {
        "n": n,
        "runs": len(runs),
        "wall": median([r["wall"] for _, r in runs]),
        "steps": last["steps"],
        "nfev": last["nfev"],
        "peak": last["peak"],
        "contacts": last["contacts"],
    }


# ------------------------------------------------------------------------ start-up
COLD_SCRIPT = textwrap.dedent("""
    import json, sys, time
    t_start = time.perf_counter()
    import flexbeam as fb
    t_import = time.perf_counter() - t_start
    import flexbeam.integrate.modal, flexbeam.simulation
    out = {"import": t_import, "import_simulation": time.perf_counter() - t_start - t_import}
    for integrator in ("reference", "exponential"):
        case = fb.load_case("seed-experiment", {"model.modes": 4, "solver.t_end": 2e-3,
                                                 "solver.integrator": integrator})
        times = []
        for _ in range(2):
            t0 = time.perf_counter()
            fb.simulate(case, "ccfm")
            times.append(time.perf_counter() - t0)
        out[integrator] = times
    print(json.dumps(out))
""")


def first_call_times(cache_dir: str | None) -> dict[str, Any]:
    """First and second simulate() per integrator in a fresh process (cold if cache_dir is empty)."""
    env = dict(os.environ)
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = cache_dir
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", COLD_SCRIPT], env=env, capture_output=True, text=True)
    total = time.perf_counter() - t0
    if proc.returncode != 0:
        return {"error": proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else "failed"}
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    out["process"] = total
    for integrator in ("reference", "exponential"):
        first, second = out[integrator]
        out[f"{integrator}_first_call"] = first - second
    return out


def cli_time(argv: list[str], runs: int, env: dict[str, str] | None = None) -> dict[str, Any]:
    exe = shutil.which("flexbeam", path=os.path.dirname(sys.executable)) or shutil.which("flexbeam")
    cmd = [exe, *argv] if exe else [sys.executable, "-m", "flexbeam.cli", *argv]
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, **(env or {})})
        times.append(time.perf_counter() - t0)
        if proc.returncode != 0:
            return {"command": "flexbeam " + " ".join(argv), "error": proc.stderr.strip()[-200:]}
    return {"command": "flexbeam " + " ".join(argv), "median": median(times), "runs": runs}


def startup(args) -> dict[str, Any]:
    out: dict[str, Any] = {}
    if args.cold:
        with tempfile.TemporaryDirectory(prefix="flexbeam-numba-cold-") as tmp:
            out["cold"] = first_call_times(tmp)
    if not args.quick:
        out["warm"] = first_call_times(None)
    extra = [] if args.t_end == 0.1 else ["--set", f"solver.t_end={args.t_end}"]
    if args.cold:  # a whole first run of the command line in a fresh process with an empty Numba cache
        with tempfile.TemporaryDirectory(prefix="flexbeam-numba-cold-") as tmp:
            out["cli_cold"] = cli_time(["run", CASE, "--json", *extra], 1, {"NUMBA_CACHE_DIR": tmp})
    out["cli"] = [cli_time(["run", CASE, "--json", *extra], args.startup_runs)]
    if not args.quick:
        out["cli"] += [cli_time(["--help"], args.startup_runs)]
    return out


# --------------------------------------------------------------------- kane spin-up
def kane(args) -> list[dict[str, Any]]:
    rows = []
    t_end = 20.0 if not args.quick else 0.5
    for integrator in INTEGRATORS:
        case = fb.load_case("kane-spinup", {"solver.integrator": integrator, "solver.t_end": t_end})
        try:
            fb.simulate(fb.load_case("kane-spinup", {"solver.integrator": integrator, "solver.t_end": 0.1}))
            runs = timed(lambda c=case: fb.simulate(c), args.repeats, args.budget)
        except Exception as exc:
            rows.append({"integrator": integrator, "error": f"{type(exc).__name__}: {exc}"})
            continue
        metrics = [s.metrics() for _, s in runs]
        rows.append(
            {
                "integrator": integrator,
                "ran": integrator_ran(runs[-1][1]),
                "t_end": t_end,
                "runs": len(runs),
                "wall": median([m["wall_time"] for m in metrics]),
                "simulate": median([t for t, _ in runs]),
                "steps": metrics[-1]["steps"],
                "tip_deflection_min": metrics[-1].get("tip_deflection_min", math.nan),
            }
        )
    return rows


# -------------------------------------------------------------------------- Exudyn
def exudyn_seed(t_end: float, elements: int = 32, step: float = 1e-5) -> dict[str, Any]:
    """The seed experiment as an Exudyn ANCF cable model; returns solve time and peak force."""
    import exudyn as exu
    from exudyn.itemInterface import (
        Cable2D,
        CoordinateConstraint,
        LoadMassProportional,
        MarkerBodyMass,
        MarkerBodyPosition,
        MarkerNodeCoordinate,
        NodePoint2DSlope1,
        NodePointGround,
        ObjectConnectorSpringDamper,
        ObjectGround,
        SensorObject,
    )

    case = fb.load_case(CASE)
    system = BeamSystem.from_case(case)
    b = case.beam
    L, r = b.length, b.radius
    area, second_moment = math.pi * r**2, math.pi * r**4 / 4.0
    E, rho, g = b.youngs_modulus, b.density, case.model.gravity
    x_P, c, R = case.contact.position, b.surface_offset, case.obstacle.radius
    law = system.law
    rate0 = abs(case.initial.impact_velocity)
    omega = case.initial.impact_velocity / x_P  # rigid rotation: P's normal velocity = omega x_P
    centre = system.contact.obstacle.centre  # the sphere touches P on the straight beam at theta = 0

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(ObjectGround(referencePosition=[0, 0, 0]))
    h = L / elements
    nodes = [
        mbs.AddNode(
            NodePoint2DSlope1(
                referenceCoordinates=[i * h, 0.0, 1.0, 0.0], initialVelocities=[0.0, omega * i * h, 0.0, omega]
            )
        )
        for i in range(elements + 1)
    ]
    elems = []
    for i in range(elements):
        elems.append(
            mbs.AddObject(
                Cable2D(
                    physicsLength=h,
                    physicsMassPerLength=rho * area,
                    physicsBendingStiffness=E * second_moment,
                    physicsAxialStiffness=E * area,
                    nodeNumbers=[nodes[i], nodes[i + 1]],
                )
            )
        )
        if g:
            mm = mbs.AddMarker(MarkerBodyMass(bodyNumber=elems[-1]))
            mbs.AddLoad(LoadMassProportional(markerNumber=mm, loadVector=[0.0, -g, 0.0]))
    # revolute joint at O: the first node's position held, its slope free
    gnode = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=gnode, coordinate=0))
    for k in (0, 1):
        mk = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=k))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mk]))
    # contact: P on the centreline against the sphere's centre, penetration (R + c) - distance,
    # Lankarani-Nikravesh force K d^n (1 + chi d'/d'_0) with flexbeam's K, n and chi
    e_P = min(int(x_P / h), elements - 1)
    mP = mbs.AddMarker(MarkerBodyPosition(bodyNumber=elems[e_P], localPosition=[x_P - e_P * h, 0.0, 0.0]))
    mC = mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[centre[0], centre[1], 0.0]))
    K, expo, chi = law.stiffness, law.exponent, law.chi()

    def contact_force(mbs, t, itemNumber, deltaL, deltaL_t, stiffness, damping, force):
        if deltaL >= 0.0:
            return 0.0
        f = K * (-deltaL) ** expo * (1.0 - chi * deltaL_t / rate0)
        return -f if f > 0.0 else 0.0  # negative spring force = compression: pushes P off the sphere

    conn = mbs.AddObject(
        ObjectConnectorSpringDamper(
            markerNumbers=[mC, mP], referenceLength=R + c, springForceUserFunction=contact_force
        )
    )
    sensor = mbs.AddSensor(
        SensorObject(objectNumber=conn, storeInternal=True, outputVariableType=exu.OutputVariableType.Force)
    )
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = int(round(t_end / step))
    settings.timeIntegration.endTime = t_end
    settings.timeIntegration.verboseMode = 0
    settings.solutionSettings.writeSolutionToFile = False
    settings.solutionSettings.sensorsWritePeriod = step
    settings.displayComputationTime = False
    t0 = time.perf_counter()
    mbs.SolveDynamic(settings)
    wall = time.perf_counter() - t0
    data = np.asarray(mbs.GetSensorStoredData(sensor))
    force = np.linalg.norm(data[:, 1:], axis=1) if data.size else np.empty(0)
    return {"wall": wall, "peak": float(force.max()) if force.size else math.nan, "steps": int(round(t_end / step))}


def exudyn_row(args) -> dict[str, Any]:
    version = _exudyn_version()
    if version is None:
        return {"skipped": "exudyn is not installed (pip install 'flexbeam[bench]' or pip install exudyn)"}
    try:
        exudyn_seed(min(2e-3, args.t_end))
        runs = timed(lambda: exudyn_seed(args.t_end), args.repeats, args.budget)
    except Exception as exc:
        return {"error": f"{type(exc).__name__}: {exc}", "version": version}
    return {
        "version": version,
        "runs": len(runs),
        "wall": median([r["wall"] for _, r in runs]),
        "build+solve": median([t for t, _ in runs]),
        "peak": runs[-1][1]["peak"],
        "steps": runs[-1][1]["steps"],
    }


# ---------------------------------------------------------------------------- report
def fmt(v: Any, spec: str = ".4g") -> str:
    if v is None:
        return "-"
    if isinstance(v, float):
        return "-" if not math.isfinite(v) else format(v, spec)
    return str(v)


def pct(v: float) -> str:
    return "-" if not math.isfinite(v) else f"{100 * v:.3g} %"


def ms(v: float | None) -> str:
    return "-" if v is None or not math.isfinite(v) else f"{1e3 * v:.4g}"


def run(args) -> dict[str, Any]:
    env = environment()
    rows: list[dict[str, Any]] = []
    modes = sorted(args.modes)
    for method in args.methods:
        for n in modes:
            for integrator in args.integrators:
                rows.append(flexbeam_row(method, n, integrator, args))
                print(f"  done {method} n={n} {integrator}", file=sys.stderr, flush=True)
    conv_n = args.converged_modes or modes[-1]
    converged: dict[str, dict[str, Any]] = {}
    for method in args.methods:
        ref = next(
            (
                r
                for r in rows
                if r["method"] == method and r["n"] == conv_n and r["integrator"] == "reference" and "error" not in r
            ),
            None,
        )
        if ref is None:
            ref = flexbeam_row(method, conv_n, "reference", argparse.Namespace(**{**vars(args), "repeats": 1}))
        converged[method] = {
            "n": conv_n,
            "peak": ref.get("peak", math.nan),
            "source": f"reference integrator (DOP853, rtol 1e-9, atol 1e-12), {conv_n} modes",
        }
    scipy_rows = {}
    if args.scipy and "ccfm" in args.methods:
        for n in modes:
            scipy_rows[n] = scipy_row(n, args)
            print(f"  done scipy n={n}", file=sys.stderr, flush=True)
    for r in rows:
        if "error" in r:
            continue
        ref = next(
            (
                x
                for x in rows
                if x["method"] == r["method"]
                and x["n"] == r["n"]
                and x["integrator"] == "reference"
                and "error" not in x
            ),
            None,
        )
        r["d_ref"] = rel(r["peak"], ref["peak"]) if ref else math.nan
        r["d_conv"] = rel(r["peak"], converged[r["method"]]["peak"])
        s = scipy_rows.get(r["n"]) if r["method"] == "ccfm" else None
        if s and "error" not in s:
            r["scipy_wall"] = s["wall"]
            r["scipy_ratio"] = s["wall"] / r["wall"] if r["wall"] > 0 else math.nan
    for s in scipy_rows.values():
        if "error" not in s:
            s["d_conv"] = rel(s["peak"], converged["ccfm"]["peak"])
    result = {
        "environment": env,
        "case": CASE,
        "t_end": args.t_end,
        "repeats": args.repeats,
        "budget": args.budget,
        "rows": rows,
        "converged": converged,
        "scipy": {"rtol": args.scipy_rtol, "atol": args.scipy_atol, "rows": list(scipy_rows.values())},
    }
    result["startup"] = startup(args) if args.startup else {"skipped": "--no-startup"}
    result["kane"] = kane(args) if args.kane else []
    result["exudyn"] = exudyn_row(args) if args.exudyn else {"skipped": "--no-exudyn"}
    ex = result["exudyn"]
    base = next(
        (
            r
            for r in rows
            if r["method"] == "ccfm" and r["n"] == 16 and "error" not in r and r["integrator"] == "exponential"
        ),
        None,
    ) or next((r for r in rows if r["method"] == "ccfm" and "error" not in r), None)
    if "wall" in ex and base:
        ex["ratio_against"] = f"ccfm n={base['n']} {base['integrator']}"
        ex["ratio"] = ex["wall"] / base["wall"] if base["wall"] > 0 else math.nan
        ex["d_conv"] = rel(ex["peak"], converged["ccfm"]["peak"])
    return result


def markdown(res: dict[str, Any]) -> str:
    env = res["environment"]
    lines = [
        f"machine: {env['machine']}, {env['cores']} cores, load {env['load_average']:.2f}; python "
        f"{env['python']}, flexbeam {env['flexbeam']}, numpy {env['numpy']}, scipy {env['scipy']}, "
        f"numba {env['numba']}, exudyn {env['exudyn'] or 'not installed'}",
        f"case: {res['case']}, t_end = {res['t_end']} s; median of up to {res['repeats']} runs "
        f"(fewer past {res['budget']} s per row), after a warm-up run",
        "",
    ]
    lines.append("| " + " | ".join(COLUMNS) + " |")
    lines.append("|" + "---|" * len(COLUMNS))
    for r in res["rows"]:
        if "error" in r:
            lines.append(
                f"| {r['method']} | {r['n']} | {r['integrator']} | error: {r['error'][:120]} |"
                + " |" * (len(COLUMNS) - 4)
            )
            continue
        contact = (
            f"{fmt(r.get('contact_median'))}/{fmt(r.get('contact_max'))}" if r.get("contact_max") is not None else "-"
        )
        cells = [
            r["method"],
            r["n"],
            r["integrator"],
            r["ran"],
            r["runs"],
            ms(r["wall"]),
            ms(r["simulate"]),
            ms(r.get("metrics")),
            r["steps"],
            fmt(r.get("free_max")),
            contact,
            fmt(r["peak"], ".6g"),
            pct(r.get("d_ref", math.nan)),
            pct(r.get("d_conv", math.nan)),
            ms(r.get("scipy_wall")),
            fmt(r.get("scipy_ratio"), ".3g"),
        ]
        lines.append("| " + " | ".join(str(c) for c in cells) + " |")
    lines.append("")
    for method, c in res["converged"].items():
        lines.append(f"converged peak ({method}): {fmt(c['peak'], '.7g')} N -- {c['source']}")
    sc = res["scipy"]
    if sc["rows"]:
        lines += [
            "",
            f"scipy solve_ivp DOP853 on the CCFM model (rtol {sc['rtol']:g}, atol {sc['atol']:g}), "
            "terminal gap events:",
            "",
            "| n | runs | wall [ms] | steps | nfev | contacts | peak [N] | d conv |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for s in sc["rows"]:
            if "error" in s:
                lines.append(f"| {s['n']} | error: {s['error'][:120]} | | | | | | |")
            else:
                lines.append(
                    f"| {s['n']} | {s['runs']} | {ms(s['wall'])} | {s['steps']} | {s['nfev']} | "
                    f"{s['contacts']} | {fmt(s['peak'], '.6g')} | {pct(s.get('d_conv', math.nan))} |"
                )
    st = res["startup"]
    lines += ["", "start-up:"]
    if "skipped" in st:
        lines.append(f"  skipped ({st['skipped']})")
    else:
        for label in ("cold", "warm"):
            if label not in st:
                lines.append(f"  {label}: skipped")
                continue
            d = st[label]
            if "error" in d:
                lines.append(f"  {label}: error {d['error']}")
                continue
            what = "first call, empty NUMBA_CACHE_DIR" if label == "cold" else "first call, warm"
            lines.append(
                f"  {label}: import flexbeam {ms(d['import'])} ms, then flexbeam.simulation and the "
                f"integrators {ms(d['import_simulation'])} ms; first simulate() minus second = {what}: "
                f"reference {ms(d['reference_first_call'])} ms, exponential "
                f"{ms(d['exponential_first_call'])} ms; whole process {d['process']:.3g} s"
            )
        if "cli_cold" in st:
            c = st["cli_cold"]
            lines.append(
                f"  `{c['command']}` with an empty Numba cache (the first run after installing): "
                + (f"error {c['error']}" if "error" in c else f"{c['median']:.3g} s")
            )
        for c in st["cli"]:
            if "error" in c:
                lines.append(f"  `{c['command']}`: error {c['error']}")
            else:
                lines.append(
                    f"  `{c['command']}`: {c['median']:.3g} s from process start to exit (median of {c['runs']})"
                )
    if res["kane"]:
        lines += ["", "kane-spinup:", ""]
        lines += [
            "| integrator | ran | t_end [s] | runs | wall [ms] | simulate [ms] | steps |",
            "|---|---|---|---|---|---|---|",
        ]
        for k in res["kane"]:
            if "error" in k:
                lines.append(f"| {k['integrator']} | error: {k['error'][:120]} | | | | | |")
            else:
                lines.append(
                    f"| {k['integrator']} | {k['ran']} | {k['t_end']:g} | {k['runs']} | {ms(k['wall'])} | "
                    f"{ms(k['simulate'])} | {k['steps']} |"
                )
    ex = res["exudyn"]
    lines += [""]
    if "skipped" in ex:
        lines.append(f"exudyn: skipped ({ex['skipped']})")
    elif "error" in ex:
        lines.append(f"exudyn {ex.get('version')}: error {ex['error']}")
    else:
        lines.append(
            f"exudyn {ex['version']}: 32 ANCF cable elements, 1e-5 s step, {ex['steps']} steps: solve "
            f"{ms(ex['wall'])} ms (build + solve {ms(ex['build+solve'])} ms, median of {ex['runs']}), "
            f"peak {fmt(ex['peak'], '.6g')} N (d conv {pct(ex.get('d_conv', math.nan))}); "
            f"exudyn/x = {fmt(ex.get('ratio'), '.3g')} against {ex.get('ratio_against', '-')}"
        )
    return "\n".join(lines) + "\n"


def jsonable(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, (float, np.floating)):
        return float(obj) if math.isfinite(obj) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def parse(argv: list[str] | None = None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument(
        "--quick",
        action="store_true",
        help="smoke run: 2 modes, 2 ms, 1 repeat, one CLI start-up, no compile/cache-load subprocesses, "
        "no Exudyn, 0.5 s of Kane",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the tables")
    p.add_argument("--modes", type=int, nargs="+", default=[4, 8, 12, 16, 32])
    p.add_argument("--methods", nargs="+", default=list(METHODS), choices=METHODS)
    p.add_argument("--integrators", nargs="+", default=list(INTEGRATORS), choices=INTEGRATORS)
    p.add_argument("--t-end", type=float, default=0.1, help="simulated time [s]")
    p.add_argument("--repeats", type=int, default=5, help="timed runs per row (median)")
    p.add_argument("--budget", type=float, default=30.0, help="stop repeating a row after this many seconds")
    p.add_argument(
        "--converged-modes",
        type=int,
        default=None,
        help="modes of the converged reference run (default: the highest of --modes)",
    )
    p.add_argument("--scipy-rtol", type=float, default=1e-8)
    p.add_argument("--scipy-atol", type=float, default=1e-11)
    p.add_argument("--no-scipy", dest="scipy", action="store_false")
    p.add_argument("--no-exudyn", dest="exudyn", action="store_false")
    p.add_argument("--no-kane", dest="kane", action="store_false")
    p.add_argument("--no-startup", dest="startup", action="store_false")
    p.add_argument("--no-cold", dest="cold", action="store_false", help="skip the cold-compile subprocess")
    p.add_argument("--startup-runs", type=int, default=3)
    args = p.parse_args(argv)
    if args.quick:
        args.modes, args.t_end, args.repeats, args.startup_runs = [2], 2e-3, 1, 1
        args.cold, args.exudyn = False, False
    return args


def main(argv: list[str] | None = None) -> None:
    args = parse(argv)
    res = run(args)
    if args.json:
        print(json.dumps(jsonable(res), indent=2))
    else:
        print(markdown(res), end="")


if __name__ == "__main__":
    main()
