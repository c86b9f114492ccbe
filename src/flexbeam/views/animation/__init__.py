"""Animations of a run: the beam's deformed shape with magnified deflection, the hub, the obstacles and the
contact-force trace (one per contact pair, with several) with a moving cursor, rendered frame by frame to a GIF
(Pillow) or an MP4 (ffmpeg).

The beam's centre line at a time comes from the modal coordinates q and the hub angle phi of the result
(:func:`~flexbeam.views.animation.geometry.beam_shape`, the kinematics of ``docs/formulation.md``).  Its deflection --
micrometres to millimetres against a beam of a metre -- is drawn magnified by a stated factor about a rigid
reference line, the large overall motion at its true scale.  The frames are placed non-uniformly in time
(:func:`~flexbeam.views.animation.geometry.frame_times`): a fixed share of them inside the contacts, the rest at a
uniform rate in free flight, so the animation runs in slow motion through each contact; every frame shows the
simulated time and the slow-motion factor.

MP4 needs ``imageio-ffmpeg`` (``pip install "flexbeam[video]"``), whose wheel ships an ffmpeg binary; without it
an MP4 request writes a GIF next to it and warns (:class:`~flexbeam.views.animation.writers.VideoFallbackWarning`).
Matplotlib is used through its object API on the Agg canvas (no pyplot state).

The entry point is :func:`animate` (also :meth:`flexbeam.results.solution.Solution.animate` and ``flexbeam animate``),
with the command line's parsers :func:`parse_window`, :func:`parse_size` and :func:`parse_scale`.  The work is
done in the submodules, whose public names are importable from here too:

- :mod:`~flexbeam.views.animation.geometry` -- what a frame shows and when: the beam's shape, the deflection's
  reference line and magnification, the frame times;
- :mod:`~flexbeam.views.animation.history` -- reading a result (a Solution, a dataset or a ``result.nc``);
- :mod:`~flexbeam.views.animation.scene` -- the numbers each frame draws;
- :mod:`~flexbeam.views.animation.renderer` -- drawing them with Matplotlib;
- :mod:`~flexbeam.views.animation.writers` -- writing the frames to a GIF or an MP4.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..._namespace import public_dir
from ...errors import ParameterError
from .geometry import REFERENCES, auto_scale, beam_shape, coupling_matrices, frame_times
from .geometry import TARGET_DEFLECTION as TARGET_DEFLECTION
from .history import History
from .renderer import FrameRenderer, speed_label
from .scene import BEAM_POINTS as BEAM_POINTS
from .scene import Scene
from .writers import FrameProgress, GifSink, Mp4Sink, VideoFallbackWarning, write_animation

if TYPE_CHECKING:
    from ...parameters.case import Case
    from ...results.solution import Solution

#: suffixes :func:`animate` writes
SUFFIXES = (".gif", ".mp4")
#: allowed frame sizes [px] per side
MIN_PIXELS, MAX_PIXELS = 32, 4096
MAX_FRAMES = 20000


def parse_window(text: str | None) -> tuple[float, float] | None:
    """``"t0,t1"`` [s] -> (t0, t1); None stays None."""
    if text is None:
        return None
    parts = text.split(",")
    try:
        t0, t1 = (float(p) for p in parts)
    except ValueError:
        raise ParameterError(f"--window: expected two times t0,t1 in s, e.g. 0,2e-3 (got '{text}')") from None
    return t0, t1


def parse_size(text: str) -> tuple[int, int]:
    """``"WIDTHxHEIGHT"`` [px] -> (width, height)."""
    try:
        w, h = (int(p) for p in text.lower().split("x"))
    except ValueError:
        raise ParameterError(f"--size: expected WIDTHxHEIGHT in pixels, e.g. 800x600 (got '{text}')") from None
    return w, h


def parse_scale(text: str) -> float | str:
    """``"auto"`` or a positive number."""
    if text.strip().lower() == "auto":
        return "auto"
    try:
        return float(text)
    except ValueError:
        raise ParameterError(f"--scale: expected 'auto' or a number > 0 (got '{text}')") from None


def animate(
    result: Solution | Any | str | Path,
    out: str | Path,
    *,
    scale: float | str = "auto",
    window: tuple[float, float] | None = None,
    frames: int = 200,
    fps: float = 25.0,
    size: tuple[int, int] = (800, 600),
    contact_share: float = 0.5,
    reference: str = "contact",
    case: Case | None = None,
    progress: bool | Callable[[int, int], None] = True,
) -> Path:
    """Render an animation of a run to ``out`` (``.gif`` or ``.mp4``) and return the path written.

    Each frame shows the beam's deformed centre line (a band of the beam's thickness) with its deflection
    magnified by ``scale`` (stated on the frame), the hub, the obstacles and, below, the contact force against
    time with a cursor at the frame's time; the simulated time and the slow-motion factor are printed on it.
    With several contact pairs each pair's force is traced in its own colour (pairs that never touch in the
    window are left out), labelled by its obstacle ("obstacle", "obstacles[0]", ...), each obstacle edged in its
    pair's colour and each pair's contact point marked on the beam.  A contact-anywhere pair's point moves along
    the beam and is marked only while in contact.

    Parameters
    ----------
    result
        A :class:`~flexbeam.results.solution.Solution`, its
        :meth:`~flexbeam.results.solution.Solution.to_xarray` dataset, or the path of a saved ``result.nc``
        (any method but ``fem``, whose result has no modal coordinates).
    out
        Output file; its suffix picks the format: ``.gif`` (Pillow) or ``.mp4`` (H.264 by the ffmpeg of
        ``imageio-ffmpeg``; without it a ``.gif`` of the same name is written and a
        :class:`~flexbeam.views.animation.writers.VideoFallbackWarning` issued).  Written atomically.
    scale
        Deflection magnification, or ``"auto"``: the largest deflection over the frames is drawn as 11-12 % of
        the beam length (:func:`~flexbeam.views.animation.geometry.auto_scale`).  The deflection is the centre line's
        displacement from the rigid reference line; only it is magnified, the rigid motion is drawn at its true
        size.
    window
        (t0, t1) [s] to animate, within the simulated time (default: all of it).
    frames, fps
        Number of frames and their rate in the file [1/s].
    size
        (width, height) of a frame [px] (even for MP4).
    contact_share
        Fraction of the frames spent in the contacts (:func:`~flexbeam.views.animation.geometry.frame_times`),
        0 <= share < 1; 0 gives uniform frames.
    reference
        The rigid reference line the deflection is measured from
        (:func:`~flexbeam.views.animation.geometry.reference_angle`): ``"contact"`` (default), the line from O through
        the contact point's centre line, so that the magnified beam touches the obstacle where the true one does;
        ``"hub"``, the hub's radial line at angle phi (the contact point then appears displaced from the obstacle
        by the magnified deflection there).  The hub is drawn turned by the same magnification relative to the
        reference line, so the magnified beam stays clamped to it.
    case
        The case, when the result does not record it (every flexbeam result does).
    progress
        True: a progress bar on stderr when it is a terminal; or a callable ``(done, total)``; False: none.

    Returns
    -------
    pathlib.Path
        The file written (``.gif`` instead of ``.mp4`` on the fallback).
    """
    out = Path(out)
    frames, width, height = _checked_options(out, frames, fps, size, contact_share, reference, scale)
    out, ffmpeg = _video_encoder(out, width, height)
    history = History.load(result, case)
    scene = Scene.build(history, window, frames, contact_share, reference, scale)
    _render(scene, out, width, height, fps, ffmpeg, progress)
    return out


def _checked_options(
    out: Path,
    frames: int,
    fps: float,
    size: tuple[int, int],
    contact_share: float,
    reference: str,
    scale: float | str,
) -> tuple[int, int, int]:
    """:func:`animate`'s options checked (a :class:`~flexbeam.errors.ParameterError` on the first bad one):
    returns (frames, width, height) as ints."""
    if out.suffix.lower() not in SUFFIXES:
        raise ParameterError(f"out: unsupported file type '{out.suffix or out.name}'; allowed: .gif, .mp4")
    frames = _check_int("frames", frames, 2, MAX_FRAMES)
    width = _check_int("size (width)", size[0], MIN_PIXELS, MAX_PIXELS)
    height = _check_int("size (height)", size[1], MIN_PIXELS, MAX_PIXELS)
    if not (math.isfinite(fps) and 0.0 < fps <= 100.0):
        raise ParameterError(f"fps: must be in (0, 100] frames per second (got {fps:g})")
    if not 0.0 <= contact_share < 1.0:
        raise ParameterError(f"contact_share: must be in [0, 1) (got {contact_share:g})")
    if reference not in REFERENCES:
        raise ParameterError(f"reference: unknown reference '{reference}'; allowed: {', '.join(REFERENCES)}")
    if scale != "auto" and not (isinstance(scale, (int, float)) and math.isfinite(scale) and scale > 0):
        raise ParameterError(f"scale: must be 'auto' or a number > 0 (got {scale!r})")
    return frames, width, height


def _video_encoder(out: Path, width: int, height: int) -> tuple[Path, Any]:
    """The file to write and, for an MP4, the ``imageio_ffmpeg`` module that encodes it (None: a GIF).

    An MP4 without ``imageio-ffmpeg`` becomes a GIF of the same name, with a
    :class:`~flexbeam.views.animation.writers.VideoFallbackWarning` pointing at :func:`animate`'s caller; an MP4
    (H.264) needs an even width and height.
    """
    if out.suffix.lower() != ".mp4":
        return out, None
    try:
        import imageio_ffmpeg
    except ImportError:
        gif = out.with_suffix(".gif")
        warnings.warn(
            f"imageio-ffmpeg is not installed (pip install 'flexbeam[video]'): writing {gif} instead of {out}",
            VideoFallbackWarning,
            stacklevel=3,
        )
        return gif, None
    if width % 2 or height % 2:
        raise ParameterError(f"size: an MP4 (H.264) needs an even width and height (got {width}x{height})")
    return out, imageio_ffmpeg


def _render(
    scene: Scene,
    out: Path,
    width: int,
    height: int,
    fps: float,
    ffmpeg: Any,
    progress: bool | Callable[[int, int], None],
) -> None:
    """Every frame of ``scene`` drawn and written to ``out`` (an MP4 by ``ffmpeg``, the ``imageio_ffmpeg``
    module; None: a GIF), reporting to ``progress`` (True: a bar on stderr, closed at the end)."""
    bar = FrameProgress(f"rendering {out.name}") if progress is True else None
    report = progress if callable(progress) else bar
    try:
        write_animation(scene, out, width, height, fps, "gif" if ffmpeg is None else "mp4", report, ffmpeg)
    finally:
        if bar is not None:
            bar.close()


def _check_int(name: str, value: Any, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not lo <= value <= hi:
        raise ParameterError(f"{name}: must be an integer in [{lo}, {hi}] (got {value!r})")
    return int(value)


__all__ = [
    "FrameRenderer",
    "GifSink",
    "History",
    "Mp4Sink",
    "Scene",
    "VideoFallbackWarning",
    "animate",
    "auto_scale",
    "beam_shape",
    "coupling_matrices",
    "frame_times",
    "parse_scale",
    "parse_size",
    "parse_window",
    "speed_label",
]

__dir__ = public_dir(globals())
