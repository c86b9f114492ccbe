"""``flexbeam run`` (one case, one method: its metrics) and ``flexbeam compare`` (several methods on one case,
against the paper's table)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

from ..errors import ParameterError
from ..interrupt import keeping_interrupted
from ..registry import METHOD_NAMES
from .options import JsonOpt, MethodOpt, OutOpt, SetOpt, out_dir
from .runs import exit_unless_complete, load, run_progress, simulate
from .tables import print_metrics


def run(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    method: MethodOpt = "ccfm",
    set_: SetOpt = None,
    out: OutOpt = None,
    json_: JsonOpt = False,
    stream: Annotated[
        bool,
        typer.Option(
            "--stream",
            help="write OUT/result.nc while the run goes on, in a memory that does not grow with the run (needs --out)",
        ),
    ] = False,
    keep_interrupted: Annotated[
        bool,
        typer.Option(
            "--keep-interrupted",
            help="Ctrl-C or SIGTERM ends the run where it is and keeps what was computed: status 'interrupted', "
            "the metrics and OUT's files, then exit 130 (143); a second one stops at once, keeping nothing",
        ),
    ] = False,
) -> None:
    """Simulate one case and print its metrics."""
    if stream and out is None:
        raise ParameterError("--stream: needs --out DIR, where the run writes DIR/result.nc as it goes")
    c = load(case, set_)
    with keeping_interrupted(keep_interrupted) as hit:
        path = out / "result.nc" if stream and out else None
        sol = simulate(c, method, outputs=out is not None, stream=path, stop=hit.cause if hit is not None else None)
    metrics = sol.metrics()
    if out is not None:
        from ..views.report import write_run_outputs

        write_run_outputs(sol, c, out)
    if json_:
        from ..results.files import metrics_json

        typer.echo(metrics_json(metrics))
    else:
        print_metrics(metrics, f"{c.name} [{method}]")
    exit_unless_complete([sol], hit.signum if hit is not None else 0)


def compare(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    set_: SetOpt = None,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", "-o", callback=out_dir, help="directory for comparison.json, comparison.md and the figures"
        ),
    ] = None,
    methods: Annotated[str, typer.Option("--methods", help="comma-separated methods")] = "ccfm,ccm,fem",
    json_: Annotated[
        bool,
        typer.Option(
            "--json",
            help="print the table's rows, one per method, as a JSON list (force_peaks: how many "
            "force maxima the first contact has)",
        ),
    ] = False,
) -> None:
    """Run CCFM, CCM and the FE reference on one case; figures and a table against the paper."""
    from ..parameters.references import reference_for
    from ..views.report import compare as run_compare
    from ..views.report import markdown_table

    c = load(case, set_)
    chosen = tuple(m.strip() for m in methods.split(",") if m.strip())
    if not chosen:
        raise ParameterError(f"--methods: give at least one method of {', '.join(METHOD_NAMES)} (got {methods!r})")
    for i, m in enumerate(chosen):
        if m not in METHOD_NAMES:
            raise ParameterError(f"--methods: unknown method '{m}'; allowed: {', '.join(METHOD_NAMES)}")
        if m in chosen[:i]:  # (it ran twice, two identical rows)
            raise ParameterError(f"--methods: {m} is given twice")
    solutions, rows = run_compare(c, out, chosen, lambda m: run_progress(c.solver.t_end, f"{c.name} [{m}]"))
    if json_:
        from ..results.files import jsonable

        typer.echo(json.dumps(jsonable(rows), indent=2))
    else:
        typer.echo(markdown_table(rows, reference_for(c)), nl=False)
    exit_unless_complete(solutions)
