"""Command-line interface (thin: it parses, calls the library and prints).

The command and ``--json`` key names are a contract users script against: add new
ones, never rename.  Bad input prints one line on stderr and exits with code 2.
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path
from typing import Annotated, Any

import typer

try:  # typer >= 0.22 vendors click
    from typer._click import exceptions as click_exc
except ImportError:  # pragma: no cover - older typer with click as a dependency
    from click import exceptions as click_exc

from .errors import FlexbeamError, ParameterError, SolverError

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    help="flexbeam: impact dynamics of flexible beams with large overall motion.",
)
cases_app = typer.Typer(add_completion=False, help="List or show the built-in cases.")
app.add_typer(cases_app, name="cases")

MethodOpt = Annotated[str, typer.Option("--method", "-m", help="impact method: ccfm, ccm, imm or fem")]
SetOpt = Annotated[
    list[str] | None,
    typer.Option("--set", "-s", help="override a case field: KEY=VALUE (dotted key, repeatable)"),
]
OutOpt = Annotated[Path | None, typer.Option("--out", "-o", help="directory for result.nc, summary.json, plots")]
JsonOpt = Annotated[bool, typer.Option("--json", help="print the metrics as one JSON object")]


def _load(case: str, sets: list[str] | None):
    from .parameters.io import load_case, parse_overrides

    return load_case(case, parse_overrides(sets or []))


class _Progress:
    """A Rich progress bar on stderr, shown only for runs longer than ~1 s on a terminal."""

    def __init__(self, t_end: float, label: str) -> None:
        self.t_end, self.label = t_end, label
        self.start = time.perf_counter()
        self.bar: Any = None
        self.task: Any = None
        self.enabled = sys.stderr.isatty()

    def __call__(self, t: float) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            if time.perf_counter() - self.start < 1.0:
                return
            from rich.console import Console
            from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

            self.bar = Progress(
                TextColumn("{task.description}"), BarColumn(), TextColumn("t = {task.completed:.4g} s"),
                TimeElapsedColumn(), console=Console(stderr=True), transient=True,
            )  # fmt: skip
            self.bar.start()
            self.task = self.bar.add_task(self.label, total=self.t_end)
        self.bar.update(self.task, completed=t)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()


def _simulate(case, method: str):
    from .simulation import simulate

    progress = _Progress(case.solver.t_end, f"{case.name} [{method}]")
    try:
        return simulate(case, method, progress=progress)
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
    sol = _simulate(c, method)
    metrics = sol.metrics()
    if out is not None:
        from .report import write_run_outputs

        write_run_outputs(sol, c, out)
    if json_:
        from .solution import metrics_json

        typer.echo(metrics_json(metrics))
    else:
        _print_metrics(metrics, f"{c.name} [{method}]")
    if sol.status == "failed":
        raise typer.Exit(1)


def _print_metrics(metrics: dict[str, Any], title: str) -> None:
    from rich.console import Console
    from rich.table import Table

    table = Table(title=title)
    table.add_column("metric")
    table.add_column("value", justify="right")
    for key, value in metrics.items():
        if isinstance(value, float):
            text = "-" if math.isnan(value) else f"{value:.6g}"
        elif isinstance(value, list):
            text = ", ".join(f"{v:.4g}" for v in value)
        else:
            text = str(value)
        table.add_row(key, text)
    Console().print(table)


@app.command()
def compare(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    set_: SetOpt = None,
    out: OutOpt = None,
    methods: Annotated[str, typer.Option("--methods", help="comma-separated methods")] = "ccfm,ccm,fem",
    json_: JsonOpt = False,
) -> None:
    """Run CCFM, CCM and the FE reference on one case; figures and a table against the paper."""
    from .report import _markdown, compare as run_compare
    from .parameters.io import reference_data

    c = _load(case, set_)
    chosen = tuple(m.strip() for m in methods.split(",") if m.strip())
    for m in chosen:
        if m not in ("ccfm", "ccm", "imm", "fem"):
            raise ParameterError(f"--methods: unknown method '{m}'; allowed: ccfm, ccm, imm, fem")
    _, rows = run_compare(c, out, chosen, lambda m: _Progress(c.solver.t_end, f"{c.name} [{m}]"))
    if json_:
        from .solution import _jsonable

        typer.echo(json.dumps(_jsonable(rows), indent=2))
    else:
        typer.echo(_markdown(rows, reference_data(c.name)), nl=False)


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


def main(argv: list[str] | None = None) -> None:
    """Console-script entry point: one-line errors with exit code 2 for bad input."""
    try:
        app(args=argv, standalone_mode=False, prog_name="flexbeam")
    except typer.Exit as exc:
        sys.exit(exc.exit_code)
    except typer.Abort:
        sys.stderr.write("aborted\n")
        sys.exit(130)
    except click_exc.ClickException as exc:
        sys.stderr.write(f"error: {exc.format_message()}\n")
        sys.exit(exc.exit_code if exc.exit_code else 2)
    except ParameterError as exc:
        sys.stderr.write(f"error: {exc}\n")
        sys.exit(2)
    except SolverError as exc:
        sys.stderr.write(f"solver error: {exc}\n")
        sys.exit(1)
    except FlexbeamError as exc:
        sys.stderr.write(f"error: {exc}\n")
        sys.exit(2)
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        sys.exit(130)


if __name__ == "__main__":  # pragma: no cover
    main()
