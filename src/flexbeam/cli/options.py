"""The command-line options several commands share (``--method``, ``--set``, ``--out``, ``--json``), and the check
of an output directory or file (:func:`out_dir`, :func:`out_file`) that the commands' ``--out`` options run before
anything else."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from ..errors import ParameterError
from ..registry import METHOD_NAMES
from ..results.files import check_output_dir


def out_dir(value: Path | None) -> Path | None:
    """``--out DIR``: a directory, or one that can be made (:func:`flexbeam.results.files.check_output_dir`)."""
    return None if value is None else check_output_dir(value, "--out")


def run_dir(value: Path | None) -> Path | None:
    """``--out DIR`` of a run: as :func:`out_dir`, none of the files the run writes there a directory
    (:data:`~flexbeam.views.report.RUN_FILES`; checked once, here, before the run)."""
    from ..views.report import RUN_FILES

    return None if value is None else check_output_dir(value, "--out", files=RUN_FILES)


def store_dir(value: Path) -> Path:
    """``--out DIR`` of a sweep: as :func:`out_dir`, none of the store's files a directory nor its ``cases`` a file
    (refused by the store as ``out``, the Python argument's name, before)."""
    from ..sweep.store import STORE_DIRS, STORE_FILES

    return check_output_dir(value, "--out", files=STORE_FILES, dirs=STORE_DIRS)


def out_file(value: Path) -> Path:
    """``--out FILE``: a file whose directory is one, or can be made."""
    check_output_dir(value.parent, "--out")
    if value.is_dir():
        raise ParameterError(f"--out: '{value}' is a directory; give a file name")
    return value


MethodOpt = Annotated[str, typer.Option("--method", "-m", help=f"impact method: {', '.join(METHOD_NAMES)}")]
SetOpt = Annotated[
    list[str] | None,
    typer.Option("--set", "-s", help="override a case field: KEY=VALUE (dotted key, repeatable)"),
]
OutOpt = Annotated[
    Path | None, typer.Option("--out", "-o", callback=run_dir, help="directory for result.nc, summary.json, plots")
]
JsonOpt = Annotated[bool, typer.Option("--json", help="print the metrics as one JSON object")]
