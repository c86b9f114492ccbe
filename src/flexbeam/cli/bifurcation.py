"""``flexbeam bifurcation``: a bifurcation diagram of a beam on a moving base (:mod:`flexbeam.bifurcation`)."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path
from typing import Annotated

import typer

from ..errors import ParameterError
from .messages import Terminated, interrupt_code
from .options import MethodOpt, SetOpt, out_dir
from .runs import load

PARAM = re.compile(r"^base\.frequency=([^:]+):([^:]+):([^:]+)$")


def parse_param(text: str) -> tuple[float, float, int]:
    """``base.frequency=lo:hi:N`` -> (lo, hi, N); one line naming --param otherwise."""
    m = PARAM.match(text.strip())
    if not m:
        raise ParameterError(f"--param: expected base.frequency=lo:hi:N (Hz, Hz, count), got {text!r}")
    try:
        lo, hi, count = float(m.group(1)), float(m.group(2)), int(m.group(3))
    except ValueError:
        raise ParameterError(f"--param: lo and hi must be numbers and N an integer, got {text!r}") from None
    return lo, hi, count


def bifurcation(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file, with a [base] shaken by harmonics")],
    param: Annotated[str, typer.Option("--param", help="the swept drive frequency: base.frequency=lo:hi:N [Hz]")],
    periods: Annotated[int, typer.Option("--periods", help="drive periods run at each frequency")],
    discard: Annotated[int, typer.Option("--discard", help="the first periods of each, the transient, left out")],
    out: Annotated[
        Path,
        typer.Option(
            "--out", "-o", callback=out_dir, help="store directory (branch-*.json, bifurcation.nc, bifurcation.png)"
        ),
    ],
    phase: Annotated[
        float, typer.Option("--phase", help="phase of the drive of the Poincaré section, in [0, 1)")
    ] = 0.0,
    method: MethodOpt = "ccfm",
    scheduler: Annotated[
        str | None, typer.Option("--scheduler", help="Dask scheduler address (default: a local cluster)")
    ] = None,
    workers: Annotated[
        int | None, typer.Option("--workers", "-w", help="worker processes of the local cluster")
    ] = None,
    set_: SetOpt = None,
    json_: Annotated[bool, typer.Option("--json", help="print the summary as one JSON object")] = False,
) -> None:
    """Sweep the drive frequency up and down with continuation; Poincaré samples and impacts in OUT/bifurcation.nc,
    the diagram in OUT/bifurcation.png."""
    from ..bifurcation import bifurcation as run_diagram
    from ..views.bifurcation import plot_bifurcation

    lo, hi, count = parse_param(param)
    c = load(case, set_)
    try:
        ds = run_diagram(c, lo, hi, count, periods, discard, method=method, phase=phase, out=out,
                         scheduler=scheduler, workers=workers)  # fmt: skip
    except (KeyboardInterrupt, Terminated) as exc:
        sys.stderr.write(f"interrupted: the finished points are kept in {out}; the same command resumes\n")
        sys.exit(interrupt_code(exc))
    png = plot_bifurcation(ds, out / "bifurcation.png")
    status = ds["status"].values.ravel().tolist()
    info = {
        "points": len(status),
        "success": sum(s == "success" for s in status),
        "failed": sum(s not in ("success", "missing") for s in status),
        "missing": sum(s == "missing" for s in status),
        "result": str(out / "bifurcation.nc"),
        "figure": str(png),
    }
    if json_:
        typer.echo(json.dumps(info, indent=2))
    else:
        typer.echo(
            f"{info['points']} points (2 branches x {count} frequencies): {info['success']} succeeded, "
            f"{info['failed']} failed, {info['missing']} missing -> {info['result']}, {info['figure']}"
        )
    if info["missing"] or info["failed"]:
        sys.exit(1)
