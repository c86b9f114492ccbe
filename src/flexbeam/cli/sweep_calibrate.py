"""``flexbeam sweep`` (a case over a grid or random samples of its fields, on Dask) and ``flexbeam calibrate``
(fit case fields to measured histories or features): the commands that run a case many times."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from ..errors import ParameterError
from ..progress import StderrProgress
from .messages import Terminated, interrupt_code
from .options import MethodOpt, SetOpt, out_dir, store_dir
from .runs import load
from .tables import print_calibration


def sweep(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    out: Annotated[
        Path,
        typer.Option(
            "--out",
            "-o",
            callback=store_dir,
            help="store directory (cases/KEY.json, result.nc); a re-run computes only the missing cases",
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
    from ..sweep import parse_grid, parse_samples, summary
    from ..sweep import sweep as run_sweep

    if bool(grid) == bool(sample):
        raise ParameterError("--grid, --sample: give the fields to sweep with one of them (not both)")
    if grid and count is not None:
        raise ParameterError("-n: only with --sample")
    c = load(case, set_)
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
    except (KeyboardInterrupt, Terminated) as exc:
        progress.close()
        sys.stderr.write(f"interrupted: the finished cases are kept in {out}; the same command resumes\n")
        sys.exit(interrupt_code(exc))
    finally:
        progress.close()
    info = summary(ds)
    info["result"] = str(out / "result.nc")
    if json_:
        from ..results.files import jsonable

        typer.echo(json.dumps(jsonable(info), indent=2))
    else:
        _print_sweep(info)
    if info["missing"]:
        sys.exit(1)


def _print_sweep(info: dict[str, Any]) -> None:
    """A sweep's summary (:func:`~flexbeam.sweep.summary`): the case counts, then up to 20 failed cases."""
    typer.echo(
        f"{info['cases']} cases: {info['computed']} computed, {info['reused']} reused, "
        f"{info['failed']} failed, {info['missing']} missing -> {info['result']}"
    )
    if info["incomplete"]:
        typer.echo(f"  {info['incomplete']} ended before solver.t_end (max-contacts: the Zeno guard)")
    if info.get("repeated"):
        typer.echo(f"  {info['repeated']} repeated an earlier case (the same sampled values: computed once)")
    if info.get("warned"):
        typer.echo(f"  {info['warned']} warned (each case's warnings: the result's variable 'warning')")
    for f in info["failures"][:20]:
        where = ", ".join(f"{k}={v}" for k, v in f["parameters"].items())
        typer.echo(f"  {f['status']}: {where}: {f['error']}")


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
        typer.Option(
            "--out",
            "-o",
            callback=out_dir,
            help="directory for calibration.json, fitted.toml, overlay.png, residuals.csv (with --data)",
        ),
    ] = None,
    json_: Annotated[bool, typer.Option("--json", help="print the report as one JSON object")] = False,
) -> None:
    """Fit case fields (such as contact stiffness and restitution) to measured histories or features."""
    from ..calibrate import calibrate as run_calibrate
    from ..calibrate import parse_columns, parse_features

    c = load(case, set_)
    result = run_calibrate(
        c, fit=fit, data=data, features=parse_features(features), method=method, columns=parse_columns(columns), out=out
    )
    report = result.to_dict()
    if json_:
        typer.echo(json.dumps(report, indent=2))
    else:
        print_calibration(report, f"{c.name} [{method}]")
    if not report["success"]:
        sys.exit(1)
