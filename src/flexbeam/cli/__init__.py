"""Command-line interface (thin: it parses, calls the library and prints).

The command and ``--json`` key names are a contract users script against: add new
ones, never rename.  Exit codes: 0 for a complete run; 2 for bad input (one line on
stderr naming the field); 1 when a run ends before ``solver.t_end`` (status "failed" or
"max-contacts": the metrics are still printed, one line on stderr says why), a
calibration does not converge, or a sweep leaves cases missing; 130 when interrupted (SIGINT, Ctrl-C), 143 when
terminated (SIGTERM), either after cleaning up as for an error (no file half-written).

This module holds the Typer :data:`app` and :func:`main`, which turns errors and flexbeam's warnings into one
line on stderr and an exit code.  The commands are in the submodules:

- :mod:`~flexbeam.cli.run_compare` -- ``run`` and ``compare``;
- :mod:`~flexbeam.cli.cases` -- ``cases``, ``cases show`` and ``frequencies``;
- :mod:`~flexbeam.cli.sweep_calibrate` -- ``sweep`` and ``calibrate``;
- :mod:`~flexbeam.cli.animation` -- ``animate``;
- :mod:`~flexbeam.cli.bifurcation` -- ``bifurcation``;

with what they share: :mod:`~flexbeam.cli.options` (the common options), :mod:`~flexbeam.cli.runs` (loading and
running a case, the exit code of early-stopped runs), :mod:`~flexbeam.cli.tables` (the printed tables) and
:mod:`~flexbeam.cli.messages` (one-line messages).
"""

from __future__ import annotations

import sys
import warnings

import typer

try:  # typer >= 0.22 vendors click
    from typer._click import exceptions as click_exc
except ImportError:  # pragma: no cover - older typer with click as a dependency
    from click import exceptions as click_exc

from .._namespace import public_dir
from ..errors import FlexbeamError, FlexbeamWarning, ParameterError, SolverError
from .animation import animate
from .bifurcation import bifurcation
from .cases import cases_app, frequencies
from .messages import Terminated, interrupt_code, one_line, sigterm_as_interrupt
from .run_compare import compare, run
from .sweep_calibrate import calibrate, sweep

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    rich_markup_mode=None,  # help as written: Rich markup took "[s]", "[px]", "[base]" for style tags and dropped them
    pretty_exceptions_enable=False,
    help="flexbeam: impact dynamics of flexible beams with large overall motion.",
)
app.add_typer(cases_app, name="cases")
for _command in (run, compare, frequencies, sweep, calibrate, animate, bifurcation):
    app.command()(_command)


def main(argv: list[str] | None = None) -> None:
    """Console-script entry point: one-line errors with exit code 2 for bad input; flexbeam's warnings
    (:class:`~flexbeam.errors.FlexbeamWarning`) as one line ``warning: ...`` on stderr, each once."""
    with warnings.catch_warnings():
        shown = warnings.showwarning

        def show(message, category, filename, lineno, file=None, line=None) -> None:
            if issubclass(category, FlexbeamWarning):
                sys.stderr.write(f"warning: {one_line(message)}\n")
            else:
                shown(message, category, filename, lineno, file, line)

        warnings.simplefilter("default", FlexbeamWarning)  # whatever filters the caller set
        warnings.showwarning = show
        with sigterm_as_interrupt():
            _main(argv)


def _main(argv: list[str] | None) -> None:
    """Run the app on ``argv``; each error as one line on stderr and its exit code (2 bad input, 1 a solver
    error, 130 interrupted, 143 terminated)."""
    try:
        rc = app(args=argv, standalone_mode=False, prog_name="flexbeam")
        if rc == 130:  # (Typer's return for a KeyboardInterrupt inside a command: no line said so)
            sys.stderr.write("interrupted\n")
        if isinstance(rc, int) and rc != 0:
            sys.exit(rc)
    except typer.Exit as exc:
        sys.exit(exc.exit_code)
    except typer.Abort:
        sys.stderr.write("aborted\n")
        sys.exit(130)
    except click_exc.ClickException as exc:
        sys.stderr.write(f"error: {one_line(exc.format_message())}\n")
        sys.exit(exc.exit_code if exc.exit_code else 2)
    except ParameterError as exc:
        sys.stderr.write(f"error: {one_line(exc)}\n")
        sys.exit(2)
    except SolverError as exc:
        sys.stderr.write(f"solver error: {one_line(exc)}\n")
        sys.exit(1)
    except FlexbeamError as exc:
        sys.stderr.write(f"error: {one_line(exc)}\n")
        sys.exit(2)
    except Terminated as exc:
        sys.stderr.write("terminated\n")
        sys.exit(interrupt_code(exc))
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        sys.exit(130)


__all__ = ["app", "main"]

__dir__ = public_dir(globals())
