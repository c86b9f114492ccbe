"""The command-line options several commands share (``--method``, ``--set``, ``--out``, ``--json``)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from ..registry import METHOD_NAMES

MethodOpt = Annotated[str, typer.Option("--method", "-m", help=f"impact method: {', '.join(METHOD_NAMES)}")]
SetOpt = Annotated[
    list[str] | None,
    typer.Option("--set", "-s", help="override a case field: KEY=VALUE (dotted key, repeatable)"),
]
OutOpt = Annotated[Path | None, typer.Option("--out", "-o", help="directory for result.nc, summary.json, plots")]
JsonOpt = Annotated[bool, typer.Option("--json", help="print the metrics as one JSON object")]
