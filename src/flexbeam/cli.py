"""Command-line interface (thin: it parses, calls the library and prints).

The command and ``--json`` key names are a contract users script against: add new
ones, never rename.  Exit codes: 0 for a complete run; 2 for bad input (one line on
stderr naming the field); 1 when a run ends before ``solver.t_end`` (status "failed" or
"max-contacts": the metrics are still printed, one line on stderr says why), a
calibration does not converge, or a sweep leaves cases missing; 130 when interrupted.
"""

from __future__ import annotations

import json
import math
import sys
import warnings
from pathlib import Path
from typing import Annotated, Any

import typer

try:  # typer >= 0.22 vendors click
    from typer._click import exceptions as click_exc
except ImportError:  # pragma: no cover - older typer with click as a dependency
    from click import exceptions as click_exc

from .errors import FlexbeamError, FlexbeamWarning, ParameterError, SolverError
from .progress import StderrProgress
from .registry import METHOD_NAMES

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    help="flexbeam: impact dynamics of flexible beams with large overall motion.",
)
cases_app = typer.Typer(add_completion=False, help="List or show the built-in cases.")
app.add_typer(cases_app, name="cases")

MethodOpt = Annotated[str, typer.Option("--method", "-m", help=f"impact method: {', '.join(METHOD_NAMES)}")]
SetOpt = Annotated[
    list[str] | None,
    typer.Option("--set", "-s", help="override a case field: KEY=VALUE (dotted key, repeatable)"),
]
OutOpt = Annotated[Path | None, typer.Option("--out", "-o", help="directory for result.nc, summary.json, plots")]
JsonOpt = Annotated[bool, typer.Option("--json", help="print the metrics as one JSON object")]


def _load(case: str, sets: list[str] | None):
    from .parameters.io import load_case, parse_overrides

    return load_case(case, parse_overrides(sets or []))


def _run_progress(t_end: float, label: str) -> StderrProgress:
    """A run's progress bar: the simulated time, shown for runs longer than ~1 s on a terminal."""
    return StderrProgress(label, "s", total=t_end)


def _simulate(case, method: str, outputs: bool = False):
    """Run a case (``outputs``: its output samples will be written or drawn, so the memory estimate counts them)."""
    from .simulation import simulate
    from .threads import single_threaded_blas

    progress = _run_progress(case.solver.t_end, f"{case.name} [{method}]")
    try:
        with single_threaded_blas():  # small linear algebra: a BLAS thread pool only adds threads
            return simulate(case, method, progress=progress, outputs=outputs)
    finally:
        progress.close()


@app.command()
def run(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    method: MethodOpt = "ccfm",
    set_: SetOpt = None,
    out: OutOpt = None,
    json_: JsonOpt = False,
) -> None:
    """Simulate one case and print its metrics."""
    c = _load(case, set_)
    sol = _simulate(c, method, outputs=out is not None)
    metrics = sol.metrics()
    if out is not None:
        from .views.report import write_run_outputs

        write_run_outputs(sol, c, out)
    if json_:
        from .results.files import metrics_json

        typer.echo(metrics_json(metrics))
    else:
        _print_metrics(metrics, f"{c.name} [{method}]")
    _exit_unless_complete([sol])


def _exit_unless_complete(solutions: list[Any]) -> None:
    """Exit with code 1 unless every run reached ``solver.t_end`` (status "success").

    A run that stops early -- a numerical failure ("failed") or the Zeno guard
    ``solver.max_contacts`` ("max-contacts") -- still prints its metrics (computed over
    what was integrated), but a script must not take them for a complete run: one line
    per such run on stderr and exit code 1.
    """
    stopped = [s for s in solutions if s.status != "success"]
    for s in stopped:
        sys.stderr.write(_one_line(f"{s.method}: run ended early with status '{s.status}': {s.message}") + "\n")
    if stopped:
        sys.exit(1)


def _print_metrics(metrics: dict[str, Any], title: str) -> None:
    from rich.console import Console
    from rich.table import Table

    table = Table(title=title)
    table.add_column("metric")
    table.add_column("value", justify="right")
    for key, value in metrics.items():
        if key == "pairs":  # one row per contact pair with several: its contacts and first peak
            for p in value if len(value) > 1 else []:
                peak = p["peak_force"]
                text = _contacts_text(p) + ", first peak " + ("-" if math.isnan(peak) else f"{peak:.6g} N")
                table.add_row(f"pair {p['pair']} ({p['obstacle']})", text)
            continue
        if key == "events":  # one per contact record: in --json only (their counts are rows)
            continue
        if isinstance(value, float):
            text = "-" if math.isnan(value) else f"{value:.6g}"
        elif isinstance(value, list):
            text = ", ".join(f"{v:.4g}" for v in value)
        else:
            text = str(value)
        table.add_row(key, text)
    Console().print(table)


def _contacts_text(counts: dict[str, Any]) -> str:
    """``"3 contacts"``, with ``" (+37 micro-impacts in 1 chatter episode)"`` when there are micro-impacts."""
    text = f"{counts['contacts']} contacts"
    micro, episodes = counts["micro_impacts"], counts["chatter_episodes"]
    if micro:
        text += f" (+{micro} micro-impacts in {episodes} chatter episode{'s' if episodes != 1 else ''})"
    return text


@app.command()
def compare(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    set_: SetOpt = None,
    out: OutOpt = None,
    methods: Annotated[str, typer.Option("--methods", help="comma-separated methods")] = "ccfm,ccm,fem",
    json_: JsonOpt = False,
) -> None:
    """Run CCFM, CCM and the FE reference on one case; figures and a table against the paper."""
    from .parameters.io import reference_data
    from .views.report import compare as run_compare
    from .views.report import markdown_table

    c = _load(case, set_)
    chosen = tuple(m.strip() for m in methods.split(",") if m.strip())
    for m in chosen:
        if m not in METHOD_NAMES:
            raise ParameterError(f"--methods: unknown method '{m}'; allowed: {', '.join(METHOD_NAMES)}")
    solutions, rows = run_compare(c, out, chosen, lambda m: _run_progress(c.solver.t_end, f"{c.name} [{m}]"))
    if json_:
        from .results.files import jsonable

        typer.echo(json.dumps(jsonable(rows), indent=2))
    else:
        typer.echo(markdown_table(rows, reference_data(c.name)), nl=False)
    _exit_unless_complete(solutions)


@cases_app.callback(invoke_without_command=True)
def cases(ctx: typer.Context) -> None:
    """List the built-in cases."""
    if ctx.invoked_subcommand is None:
        from .parameters.io import builtin_cases

        for name, desc in builtin_cases().items():
            typer.echo(f"{name:28s} {desc}")


@cases_app.command("show")
def cases_show(name: Annotated[str, typer.Argument(help="built-in case name")]) -> None:
    """Print a built-in case as TOML (``flexbeam run`` accepts it back unchanged)."""
    from .parameters.io import dump_case, load_case

    typer.echo(dump_case(load_case(name)), nl=False)


@app.command()
def frequencies(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    spin: Annotated[float, typer.Option("--spin", help="hub spin rate Omega [rad/s]")] = 0.0,
    modes: Annotated[int | None, typer.Option("--modes", help="number of assumed modes")] = None,
    set_: SetOpt = None,
    json_: JsonOpt = False,
) -> None:
    """Natural frequencies [rad/s] of in-plane vibration about steady spin, hub clamped."""
    from .model.frequencies import case_frequencies

    sets = list(set_ or [])
    if modes is not None:
        sets.append(f"model.modes={modes}")
    if not math.isfinite(spin):
        raise ParameterError(f"--spin: must be a finite number (got {spin})")
    c = _load(case, sets)
    freqs = case_frequencies(c, spin)
    w1 = case_frequencies(c, 0.0)["first-order"]
    stable = {k: bool(v.size == 0 or v[0] > 0) for k, v in freqs.items()}
    note = ""
    if w1.size and abs(spin) > w1[0]:
        note = (
            f"spin {abs(spin):.6g} rad/s exceeds the first bending frequency {w1[0]:.6g} rad/s: "
            "the zeroth-order model (no coupling deformation) softens and loses stability there"
        )
    if json_:
        payload = {
            "spin": spin,
            "first-order": [float(v) for v in freqs["first-order"]],
            "zeroth-order": [float(v) for v in freqs["zeroth-order"]],
            "stable": stable,
            "note": note,
        }
        typer.echo(json.dumps(payload, indent=2))
        return
    typer.echo(f"{'mode':>4s} {'first-order [rad/s]':>22s} {'zeroth-order [rad/s]':>22s}")
    for i, (a, b) in enumerate(zip(freqs["first-order"], freqs["zeroth-order"]), 1):
        bt = f"{b:22.6f}" if b > 0 else f"{'unstable (w^2<0)':>22s}"
        typer.echo(f"{i:4d} {a:22.6f} {bt}")
    if note:
        typer.echo(note)


@app.command()
def sweep(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    out: Annotated[
        Path,
        typer.Option(
            "--out", "-o", help="store directory (cases/KEY.json, result.nc); a re-run computes only the missing cases"
        ),
    ],
    grid: Annotated[
        list[str] | None,
        typer.Option(
            "--grid", "-g", help="KEY=v1,v2,... or KEY=linspace(a,b,n) / geomspace(a,b,n); repeated: their product"
        ),
    ] = None,
    sample: Annotated[
        list[str] | None,
        typer.Option("--sample", help="KEY=DIST: uniform(a,b), normal(mu,sigma), loguniform(a,b), choice(v1,...)"),
    ] = None,
    count: Annotated[int | None, typer.Option("-n", help="number of random samples (with --sample)")] = None,
    seed: Annotated[int, typer.Option("--seed", help="random seed of the samples")] = 0,
    method: MethodOpt = "ccfm",
    scheduler: Annotated[
        str | None,
        typer.Option("--scheduler", help="Dask scheduler address, e.g. tcp://host:8786 (default: a local cluster)"),
    ] = None,
    workers: Annotated[
        int | None, typer.Option("--workers", "-w", help="worker processes of the local cluster (default: all cores)")
    ] = None,
    histories: Annotated[
        bool, typer.Option("--histories", help="also keep each case's history (cases/KEY.nc)")
    ] = False,
    batch_size: Annotated[
        int | None,
        typer.Option(
            "--batch-size", help="cases per Dask task (default: sized as the sweep goes, ~0.5 s of work per task)"
        ),
    ] = None,
    set_: SetOpt = None,
    json_: Annotated[bool, typer.Option("--json", help="print the summary as one JSON object")] = False,
) -> None:
    """Run a case over a grid or random samples of its fields on Dask (metrics in STORE/result.nc)."""
    from .sweep import parse_grid, parse_samples, summary
    from .sweep import sweep as run_sweep

    if bool(grid) == bool(sample):
        raise ParameterError("--grid, --sample: give the fields to sweep with one of them (not both)")
    if grid and count is not None:
        raise ParameterError("-n: only with --sample")
    c = _load(case, set_)
    progress = StderrProgress(f"{c.name} [{method}]", "cases", delay=0.0)
    # sys.exit rather than typer.Exit: main() runs the app with standalone_mode=False, where
    # typer turns Exit and Ctrl-C into a returned code instead of raising them
    try:
        ds = run_sweep(
            c,
            grid=parse_grid(grid) if grid else None,
            samples=parse_samples(sample) if sample else None,
            n=count,
            seed=seed,
            method=method,
            scheduler=scheduler,
            workers=workers,
            out=out,
            histories=histories,
            progress=progress,
            batch_size=batch_size,
        )
    except KeyboardInterrupt:
        progress.close()
        sys.stderr.write(f"interrupted: the finished cases are kept in {out}; the same command resumes\n")
        sys.exit(130)
    finally:
        progress.close()
    info = summary(ds)
    info["result"] = str(out / "result.nc")
    if json_:
        from .results.files import jsonable

        typer.echo(json.dumps(jsonable(info), indent=2))
    else:
        typer.echo(
            f"{info['cases']} cases: {info['computed']} computed, {info['reused']} reused, "
            f"{info['failed']} failed, {info['missing']} missing -> {info['result']}"
        )
        for f in info["failures"][:20]:
            where = ", ".join(f"{k}={v}" for k, v in f["parameters"].items())
            typer.echo(f"  {f['status']}: {where}: {f['error']}")
    if info["missing"]:
        sys.exit(1)


@app.command()
def calibrate(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file (starting values)")],
    fit: Annotated[
        str,
        typer.Option("--fit", help="case fields to fit, comma-separated, e.g. contact.stiffness,contact.restitution"),
    ],
    data: Annotated[
        Path | None, typer.Option("--data", help="CSV with a time column and force and/or velocity columns [s, N, m/s]")
    ] = None,
    columns: Annotated[
        str | None, typer.Option("--columns", help="CSV column names by role: time=t,force=F,velocity=v")
    ] = None,
    features: Annotated[
        str | None,
        typer.Option(
            "--features", help="measured metrics: peak_force=584,second_peak_force=297,contact_duration=0.6e-3"
        ),
    ] = None,
    method: MethodOpt = "ccfm",
    set_: SetOpt = None,
    out: Annotated[
        Path | None,
        typer.Option("--out", "-o", help="directory for calibration.json, fitted.toml, overlay.png, residuals.csv"),
    ] = None,
    json_: Annotated[bool, typer.Option("--json", help="print the report as one JSON object")] = False,
) -> None:
    """Fit case fields (e.g. contact stiffness and restitution) to measured histories or features."""
    from .calibrate import calibrate as run_calibrate
    from .calibrate import parse_columns, parse_features

    c = _load(case, set_)
    result = run_calibrate(
        c, fit=fit, data=data, features=parse_features(features), method=method, columns=parse_columns(columns), out=out
    )
    report = result.to_dict()
    if json_:
        typer.echo(json.dumps(report, indent=2))
    else:
        _print_calibration(report, f"{c.name} [{method}]")
    if not report["success"]:
        sys.exit(1)


def _print_calibration(report: dict[str, Any], title: str) -> None:
    from rich.console import Console
    from rich.table import Table

    def num(v: Any) -> str:
        return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.6g}"

    from rich.markup import escape

    table = Table(title=escape(f"{title}: calibration"))
    for col in ("parameter", "initial", "fitted", "std. uncertainty", "units"):
        table.add_column(col, justify="left" if col in ("parameter", "units") else "right")
    for key, p in report["parameters"].items():
        table.add_row(
            key + (" (at bound)" if p["at_bound"] else ""),
            num(p["initial"]),
            num(p["value"]),
            num(p["uncertainty"]),
            p["units"],
        )
    console = Console()
    console.print(table)
    if "features" in report:
        ft = Table(title="features")
        for col in ("feature", "measured", "initial model", "fitted model"):
            ft.add_column(col, justify="left" if col == "feature" else "right")
        for key, f in report["features"].items():
            ft.add_row(key, num(f["measured"]), num(f["initial"]), num(f["fitted"]))
        console.print(ft)
    if "data" in report:
        d = report["data"]
        for chan, rms in d["rms"].items():
            console.print(f"{chan} residual rms: {num(rms)} (initial {num(d['rms_initial'][chan])})")
        console.print(
            f"time shift: {num(d['time_shift'])} s +- {num(d['time_shift_uncertainty'])} s, "
            f"{d['samples']} samples of {d['file']}"
        )
    r = report["residuals"]
    console.print(
        f"residual sigma {num(r['sigma'])} (dof {r['dof']}), {report['nfev']} evaluations: {report['message']}"
    )


@app.command()
def animate(
    source: Annotated[str, typer.Argument(help="built-in case name, TOML file (simulated first) or a result.nc")],
    out: Annotated[Path, typer.Option("--out", "-o", help="output file: .gif or .mp4 (MP4 needs flexbeam[video])")],
    scale: Annotated[str, typer.Option("--scale", help="deflection magnification: auto or a number")] = "auto",
    window: Annotated[str | None, typer.Option("--window", help="time window t0,t1 [s] (default: all)")] = None,
    frames: Annotated[int, typer.Option("--frames", help="number of frames")] = 200,
    fps: Annotated[float, typer.Option("--fps", help="frames per second of the file")] = 25.0,
    size: Annotated[str, typer.Option("--size", help="frame size WIDTHxHEIGHT [px]")] = "800x600",
    method: MethodOpt = "ccfm",
    set_: SetOpt = None,
) -> None:
    """Animate a run: deformed beam (magnified deflection), hub, obstacle and contact force, slow motion in
    contacts."""
    import warnings

    from .views.animation import VideoFallbackWarning, parse_scale, parse_size, parse_window
    from .views.animation import animate as render

    options = {
        "scale": parse_scale(scale),
        "window": parse_window(window),
        "frames": frames,
        "fps": fps,
        "size": parse_size(size),
    }
    if source.endswith(".nc"):
        if set_:
            raise ParameterError("--set: only with a case, not with a result file")
        if not Path(source).is_file():
            raise ParameterError(f"source: no such result file '{source}'")
        result: Any = Path(source)
    else:
        c = _load(source, set_)
        result = _simulate(c, method, outputs=True)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", VideoFallbackWarning)
        path = render(result, out, **options)
    for w in caught:
        if issubclass(w.category, VideoFallbackWarning):
            sys.stderr.write(f"note: {_one_line(w.message)}\n")
        else:
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    typer.echo(f"wrote {path}")


def _one_line(message: object) -> str:
    """``message`` (an exception or text) on one line: a newline, e.g. in a quoted TOML key, is escaped."""
    return str(message).replace("\r", "\\r").replace("\n", "\\n")


def main(argv: list[str] | None = None) -> None:
    """Console-script entry point: one-line errors with exit code 2 for bad input; flexbeam's warnings
    (:class:`~flexbeam.errors.FlexbeamWarning`) as one line ``warning: ...`` on stderr, each once."""
    with warnings.catch_warnings():
        shown = warnings.showwarning

        def show(message, category, filename, lineno, file=None, line=None) -> None:
            if issubclass(category, FlexbeamWarning):
                sys.stderr.write(f"warning: {_one_line(message)}\n")
            else:
                shown(message, category, filename, lineno, file, line)

        warnings.simplefilter("default", FlexbeamWarning)  # whatever filters the caller set
        warnings.showwarning = show
        _main(argv)


def _main(argv: list[str] | None) -> None:
    try:
        rc = app(args=argv, standalone_mode=False, prog_name="flexbeam")
        if isinstance(rc, int) and rc != 0:
            sys.exit(rc)
    except typer.Exit as exc:
        sys.exit(exc.exit_code)
    except typer.Abort:
        sys.stderr.write("aborted\n")
        sys.exit(130)
    except click_exc.ClickException as exc:
        sys.stderr.write(f"error: {_one_line(exc.format_message())}\n")
        sys.exit(exc.exit_code if exc.exit_code else 2)
    except ParameterError as exc:
        sys.stderr.write(f"error: {_one_line(exc)}\n")
        sys.exit(2)
    except SolverError as exc:
        sys.stderr.write(f"solver error: {_one_line(exc)}\n")
        sys.exit(1)
    except FlexbeamError as exc:
        sys.stderr.write(f"error: {_one_line(exc)}\n")
        sys.exit(2)
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        sys.exit(130)


if __name__ == "__main__":  # pragma: no cover
    main()
