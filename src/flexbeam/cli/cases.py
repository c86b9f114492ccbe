"""``flexbeam cases`` (list the built-in cases), ``flexbeam cases show`` (one as TOML) and ``flexbeam
frequencies`` (a case's natural frequencies about steady spin)."""

from __future__ import annotations

import json
import math
from typing import TYPE_CHECKING, Annotated

import typer

from ..errors import ParameterError
from .options import SetOpt
from .runs import load

if TYPE_CHECKING:
    import numpy as np

cases_app = typer.Typer(add_completion=False, rich_markup_mode=None, help="List or show the built-in cases.")


@cases_app.callback(invoke_without_command=True)
def cases(ctx: typer.Context) -> None:
    """List the built-in cases."""
    if ctx.invoked_subcommand is None:
        from ..parameters.io import builtin_cases

        for name, desc in builtin_cases().items():
            typer.echo(f"{name:28s} {desc}")


@cases_app.command("show")
def cases_show(name: Annotated[str, typer.Argument(help="built-in case name")]) -> None:
    """Print a built-in case as TOML (``flexbeam run`` accepts it back unchanged)."""
    from ..parameters.io import dump_case, load_case

    typer.echo(dump_case(load_case(name)), nl=False)


def frequencies(
    case: Annotated[str, typer.Argument(help="built-in case name or TOML file")],
    spin: Annotated[float, typer.Option("--spin", help="hub spin rate Omega [rad/s]")] = 0.0,
    modes: Annotated[int | None, typer.Option("--modes", help="number of assumed modes")] = None,
    set_: SetOpt = None,
    json_: Annotated[
        bool,
        typer.Option(
            "--json",
            help="print one JSON object: spin, the first-order and zeroth-order frequencies "
            "[rad/s], stable (per model), note",
        ),
    ] = False,
) -> None:
    """Natural frequencies [rad/s] of in-plane vibration about steady spin, hub clamped."""
    from ..model.frequencies import case_frequencies

    sets = list(set_ or [])
    if modes is not None:
        sets.append(f"model.modes={modes}")
    if not math.isfinite(spin):
        raise ParameterError(f"--spin: must be a finite number (got {spin})")
    c = load(case, sets)
    freqs = case_frequencies(c, spin)
    note = _stability_note(spin, case_frequencies(c, 0.0)["first-order"])
    if json_:
        stable = {k: bool(v.size == 0 or v[0] > 0) for k, v in freqs.items()}
        payload = {
            "spin": spin,
            "first-order": [float(v) for v in freqs["first-order"]],
            "zeroth-order": [float(v) for v in freqs["zeroth-order"]],
            "stable": stable,
            "note": note,
        }
        typer.echo(json.dumps(payload, indent=2))
        return
    _print_frequencies(freqs)
    if note:
        typer.echo(note)


def _stability_note(spin: float, w1: np.ndarray) -> str:
    """The warning for a spin above the first bending frequency at rest ``w1[0]`` [rad/s]; "" below it."""
    if w1.size and abs(spin) > w1[0]:
        return (
            f"spin {abs(spin):.6g} rad/s exceeds the first bending frequency {w1[0]:.6g} rad/s: "
            "the zeroth-order model (no coupling deformation) softens and loses stability there"
        )
    return ""


def _print_frequencies(freqs: dict[str, np.ndarray]) -> None:
    """One row per mode: the first-order and the zeroth-order model's frequency [rad/s] (w^2 < 0: unstable)."""
    typer.echo(f"{'mode':>4s} {'first-order [rad/s]':>22s} {'zeroth-order [rad/s]':>22s}")
    for i, (a, b) in enumerate(zip(freqs["first-order"], freqs["zeroth-order"]), 1):
        bt = f"{b:22.6f}" if b > 0 else f"{'unstable (w^2<0)':>22s}"
        typer.echo(f"{i:4d} {a:22.6f} {bt}")
