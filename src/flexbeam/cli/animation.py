"""``flexbeam animate``: a GIF or MP4 of a run, simulated first or read from a ``result.nc``."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path
from typing import Annotated, Any

import typer

from ..errors import ParameterError
from ..registry import METHOD_NAMES
from .messages import one_line
from .options import SetOpt, out_file
from .runs import exit_unless_complete, load, simulate


def animate(
    source: Annotated[str, typer.Argument(help="built-in case name, TOML file (simulated first) or a result.nc")],
    out: Annotated[
        Path,
        typer.Option("--out", "-o", callback=out_file, help="output file: .gif or .mp4 (MP4 needs flexbeam[video])"),
    ],
    scale: Annotated[str, typer.Option("--scale", help="deflection magnification: auto or a number")] = "auto",
    window: Annotated[str | None, typer.Option("--window", help="time window t0,t1 [s] (default: all)")] = None,
    frames: Annotated[int, typer.Option("--frames", help="number of frames")] = 200,
    fps: Annotated[float, typer.Option("--fps", help="frames per second of the file")] = 25.0,
    size: Annotated[str, typer.Option("--size", help="frame size WIDTHxHEIGHT [px]")] = "800x600",
    method: Annotated[
        str | None, typer.Option("--method", "-m", help=f"impact method of a case's run: {', '.join(METHOD_NAMES)}")
    ] = None,
    set_: SetOpt = None,
) -> None:
    """Animate a run: deformed beam (magnified deflection), hub, obstacle and contact force, slow motion in
    contacts.  A case's run that ends early is animated as far as it went, then reported as ``run`` reports it
    (one line, exit 1)."""
    from ..views.animation import VideoFallbackWarning, parse_scale, parse_size, parse_window
    from ..views.animation import animate as render

    options = {
        "scale": parse_scale(scale),
        "window": parse_window(window),
        "frames": frames,
        "fps": fps,
        "size": parse_size(size),
    }
    result = _result(source, set_, method)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", VideoFallbackWarning)
        path = render(result, out, **options)
    for w in caught:
        if issubclass(w.category, VideoFallbackWarning):
            sys.stderr.write(f"note: {one_line(w.message)}\n")
        else:
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    typer.echo(f"wrote {path}")
    if not isinstance(result, Path):
        exit_unless_complete([result])


def _result(source: str, sets: list[str] | None, method: str | None) -> Any:
    """What to animate: the path of a ``result.nc`` as it is (no ``--set`` nor ``--method``), or a case (name or
    TOML file) run with ``method`` (default CCFM)."""
    if source.endswith(".nc"):
        if sets:
            raise ParameterError("--set: only with a case, not with a result file")
        if method is not None:
            raise ParameterError("--method: only with a case, not with a result file (it holds its own run)")
        if not Path(source).is_file():
            raise ParameterError(f"source: no such result file '{source}'")
        return Path(source)
    return simulate(load(source, sets), method or "ccfm", outputs=True)
