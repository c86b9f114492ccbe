"""Writing an animation to a file: :func:`write_animation` renders every frame of a
:class:`~flexbeam.views.animation.scene.Scene` and encodes them atomically, to a GIF by Pillow (:class:`GifSink`) or an
H.264 MP4 by the ffmpeg of ``imageio-ffmpeg`` (:class:`Mp4Sink`); :class:`FrameProgress` shows the rendered frames
on a terminal; :class:`VideoFallbackWarning` says a GIF was written because an MP4 could not be.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from PIL import Image

from ...progress import StderrProgress
from .renderer import FrameRenderer

if TYPE_CHECKING:
    from .scene import Scene


class VideoFallbackWarning(UserWarning):
    """An MP4 was asked for but ``imageio-ffmpeg`` is not installed: a GIF was written instead."""


class FrameProgress(StderrProgress):
    """A Rich progress bar of the rendered frames on stderr, shown on a terminal once rendering takes > 1 s."""

    def __init__(self, label: str) -> None:
        super().__init__(label, "frames")


def write_animation(
    scene: Scene,
    out: Path,
    width: int,
    height: int,
    fps: float,
    kind: str,
    progress: Callable[[int, int], None] | None,
    ffmpeg: Any = None,
) -> None:
    """Render every frame of ``scene`` and encode them to ``out`` atomically.

    Parameters
    ----------
    scene
        What the frames draw.
    out
        The file to write; replaced only once every frame is encoded.
    width, height
        Frame size [px].
    fps
        Frame rate in the file [1/s].
    kind
        ``"gif"`` (:class:`GifSink`) or ``"mp4"`` (:class:`Mp4Sink`, needs ``ffmpeg``).
    progress
        Called as ``progress(done, total)`` after each frame, or None.
    ffmpeg
        The ``imageio_ffmpeg`` module, for ``kind="mp4"``.
    """
    from ...results.files import atomic_path

    renderer = FrameRenderer(scene, width, height, fps)
    n = scene.times.size
    with atomic_path(out) as tmp:
        # the encoder picks the container by the suffix: write to a suffixed name, moved onto tmp when done
        work = tmp.with_name(tmp.name + out.suffix)
        try:
            if kind == "mp4":
                sink: Any = Mp4Sink(work, (width, height), fps, ffmpeg)
            else:
                # one palette for all frames, from a few of them (ffmpeg's palettegen does the same)
                picks = sorted({0, n // 3, (2 * n) // 3, n - 1, int(np.argmax(scene.force))})
                sink = GifSink(work, fps, [renderer.render(i) for i in picks])
            try:
                for i in range(n):
                    sink.write(renderer.render(i))
                    if progress is not None:
                        progress(i + 1, n)
            except BaseException:
                sink.abort()
                raise
            sink.close()
            os.replace(work, tmp)
        finally:
            work.unlink(missing_ok=True)


class GifSink:
    """Frames to an animated GIF by Pillow, with one 256-colour palette for all of them.

    The palette holds the 256 most frequent colours of a few sample frames (the popularity algorithm, Heckbert
    1982): a line drawing's flat colours -- white, the beam, the text -- stay exact, and the rare anti-aliasing
    shades outside it go to their nearest entry (Euclidean in RGB; no dithering).  Frames are mapped as they
    arrive, so those held until the file is written take one byte per pixel.
    """

    def __init__(self, path: Path, fps: float, samples: Sequence[np.ndarray]) -> None:
        self.path, self.fps = path, fps
        values, counts = np.unique(np.concatenate([_packed(f) for f in samples]), return_counts=True)
        top = values[np.argsort(-counts, kind="stable")[:256]]
        self.colours = np.stack(((top >> 16) & 255, (top >> 8) & 255, top & 255), axis=1).astype(np.int32)
        # palette index of every 24-bit colour met so far (-1: not yet): one gather per frame
        self.lookup = np.full(1 << 24, -1, np.int16)
        self.lookup[top] = np.arange(top.size)
        self.frames: list[Image.Image] = []

    def write(self, rgba: np.ndarray) -> None:
        packed = _packed(rgba)
        index = self.lookup[packed]
        if np.any(index < 0):
            new = np.unique(packed[index < 0])
            rgb = np.stack(((new >> 16) & 255, (new >> 8) & 255, new & 255), axis=1).astype(np.int32)
            self.lookup[new] = np.argmin(((rgb[:, None, :] - self.colours[None, :, :]) ** 2).sum(axis=-1), axis=1)
            index = self.lookup[packed]
        frame = Image.frombytes("P", (rgba.shape[1], rgba.shape[0]), index.astype(np.uint8).tobytes())
        frame.putpalette(self.colours.astype(np.uint8).ravel().tolist())
        self.frames.append(frame)

    def close(self) -> None:
        self.frames[0].save(
            self.path,
            format="GIF",
            save_all=True,
            append_images=self.frames[1:],
            duration=round(1000.0 / self.fps),
            loop=0,
        )
        self.frames = []

    def abort(self) -> None:
        self.frames = []


def _packed(rgba: np.ndarray) -> np.ndarray:
    """Pixels of an (h, w, 3 or 4) uint8 image as 0xRRGGBB integers, flattened."""
    rgb = rgba[..., :3].reshape(-1, 3).astype(np.uint32)
    return (rgb[:, 0] << 16) | (rgb[:, 1] << 8) | rgb[:, 2]


class Mp4Sink:
    """Frames to an H.264 MP4 through ``imageio_ffmpeg.write_frames`` (its bundled ffmpeg binary)."""

    def __init__(self, path: Path, size: tuple[int, int], fps: float, imageio_ffmpeg: Any) -> None:
        self.writer = imageio_ffmpeg.write_frames(
            str(path), size, pix_fmt_in="rgba", fps=fps, codec="libx264", quality=7, macro_block_size=2
        )
        self.writer.send(None)

    def write(self, rgba: np.ndarray) -> None:
        self.writer.send(np.ascontiguousarray(rgba))

    def close(self) -> None:
        self.writer.close()

    def abort(self) -> None:
        self.writer.close()
