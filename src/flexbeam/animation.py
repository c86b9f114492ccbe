"""Animations of a run: the beam's deformed shape with magnified deflection, the hub, the obstacle and the
contact-force trace with a moving cursor, rendered frame by frame to a GIF (Pillow) or an MP4 (ffmpeg).

The beam's centre line at a time comes from the modal coordinates q and the hub angle phi of the result
(:func:`beam_shape`, the kinematics of ``docs/formulation.md``).  Its deflection -- micrometres to millimetres
against a beam of a metre -- is drawn magnified by a stated factor about a rigid reference line, the large
overall motion at its true scale.  The frames are placed non-uniformly in time (:func:`frame_times`): a fixed
share of them inside the contacts, the rest at a uniform rate in free flight, so the animation runs in slow
motion through each contact; every frame shows the simulated time and the slow-motion factor.

MP4 needs ``imageio-ffmpeg`` (``pip install "flexbeam[video]"``), whose wheel ships an ffmpeg binary; without it
an MP4 request writes a GIF next to it and warns (:class:`VideoFallbackWarning`).  Matplotlib is used through its
object API on the Agg canvas (no pyplot state).
"""

from __future__ import annotations

import math
import os
import sys
import time
import tomllib
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from PIL import Image

from .errors import ModelError, ParameterError

if TYPE_CHECKING:
    from .model.beam import ModalBeam
    from .model.system import BeamSystem
    from .parameters.case import Case
    from .solution import Solution

#: suffixes :func:`animate` writes
SUFFIXES = (".gif", ".mp4")
#: auto scale: the largest magnified deflection over the frames is this fraction of the beam length, less at
#: most 1/11 of it (the factor is rounded down to two significant digits): 10.9-12 % of L
TARGET_DEFLECTION = 0.12
#: rigid reference lines the deflection is measured from (see :func:`animate`)
REFERENCES = ("contact", "hub")
#: allowed frame sizes [px] per side
MIN_PIXELS, MAX_PIXELS = 32, 4096
MAX_FRAMES = 20000
#: material points drawn along the beam
BEAM_POINTS = 121


class VideoFallbackWarning(UserWarning):
    """An MP4 was asked for but ``imageio-ffmpeg`` is not installed: a GIF was written instead."""


# ------------------------------------------------------------------------------------------------ kinematics
def coupling_matrices(beam: ModalBeam, x: np.ndarray) -> np.ndarray:
    """H(x) = r_h d^T d + int_0^x Psi'^T Psi' dxi at each point of ``x``, shape (len(x), n, n).

    The coupling (foreshortening) matrix of ``docs/formulation.md``, u_x(x) = -1/2 q^T H(x) q; zero for the
    zeroth-order model.  The integral is accumulated over the intervals between the sorted points, each by an
    (8 n + 48)-point Gauss-Legendre rule, the rule :class:`~flexbeam.model.beam.ModalBeam` uses for the whole
    span (exact to round-off for products of the first n mode slopes on any sub-interval).
    """
    x = np.atleast_1d(np.asarray(x, float))
    n = beam.n
    H = np.zeros((x.size, n, n))
    if n == 0 or not beam.first_order:
        return H
    order = np.argsort(x)
    edges = np.concatenate(([0.0], x[order]))
    xi, wi = np.polynomial.legendre.leggauss(8 * n + 48)
    half = 0.5 * np.diff(edges)  # (k,)
    nodes = (0.5 * (edges[1:] + edges[:-1]))[:, None] + half[:, None] * xi[None, :]  # (k, p)
    slopes = beam.shapes(nodes.ravel(), 1).reshape(*nodes.shape, n)  # (k, p, n)
    pieces = np.einsum("kp,kpi,kpj->kij", half[:, None] * wi[None, :], slopes, slopes)
    H[order] = np.cumsum(pieces, axis=0) + beam.hub_radius * np.outer(beam.d, beam.d)
    return 0.5 * (H + H.transpose(0, 2, 1))


def beam_shape(system: BeamSystem, phi, q, x) -> tuple[np.ndarray, np.ndarray]:
    """Global coordinates (X, Y) [m] of the beam's centre line at the material points ``x`` [m].

    r(x) = A(theta) rho(x) with rho(x) = (r_h + x - 1/2 q^T H(x) q, Psi(x) q) in the body frame
    (``docs/formulation.md``), A the rotation by the body frame's angle theta = phi - d q (d = Psi'(0); zero in
    the hub frame, where theta is the hub angle phi) and H from :func:`coupling_matrices`.

    Parameters
    ----------
    system
        The case's :class:`~flexbeam.model.system.BeamSystem` (its modal beam: shapes, frame, d, r_h).
    phi
        Hub angle(s) [rad], scalar or shape (m,): the Solution's ``theta``.
    q
        Modal coordinates, shape (n,) or (m, n).
    x
        Material coordinates, shape (k,), 0 <= x <= L.

    Returns
    -------
    X, Y
        Shape (k,) for a scalar ``phi``, else (m, k).
    """
    beam = system.beam
    x = np.atleast_1d(np.asarray(x, float))
    phi = np.asarray(phi, float)
    single = phi.ndim == 0
    phi = np.atleast_1d(phi)
    q = np.asarray(q, float).reshape(phi.size, beam.n)
    theta = phi - q @ beam.d
    qHq = np.einsum("mi,kij,mj->mk", q, coupling_matrices(beam, x), q)
    rho_x = beam.hub_radius + x[None, :] - 0.5 * qHq
    rho_y = q @ beam.shapes(x, 0).T
    c, s = np.cos(theta)[:, None], np.sin(theta)[:, None]
    X, Y = c * rho_x - s * rho_y, s * rho_x + c * rho_y
    return (X[0], Y[0]) if single else (X, Y)


# ------------------------------------------------------------------------------------------------ frame plan
def frame_times(
    window: tuple[float, float],
    contacts: Sequence[tuple[float, float]],
    frames: int,
    contact_share: float = 0.5,
    pad: float = 0.25,
) -> tuple[np.ndarray, np.ndarray]:
    """Frame times [s] and the frame density [frames per simulated second] at each.

    The frame density is piecewise constant: inside the contacts (each widened by ``pad`` times its duration on
    either side, clipped to the window, overlaps merged) it puts ``contact_share`` of the frames, spread in
    proportion to the contacts' durations; in free flight the rest at one uniform rate.  When that would make
    the contacts no denser than free flight (long contacts), or nothing of a contact is in the window (an IMM
    jump has no duration), the frames are uniform.  The first frame is at ``window[0]``, the last at
    ``window[1]``: frame i is where the cumulative density reaches i.
    """
    t0, t1 = float(window[0]), float(window[1])
    if frames < 2 or not t1 > t0:
        raise ParameterError(f"frame_times: need frames >= 2 and t0 < t1 (got {frames}, {t0:g}, {t1:g})")
    spans: list[list[float]] = []
    for onset, end in sorted(contacts):
        end = end if math.isfinite(end) else t1
        if not end > onset:
            continue
        widen = pad * (end - onset)
        a, b = max(t0, onset - widen), min(t1, end + widen)
        if b <= a:
            continue
        if spans and a <= spans[-1][1]:
            spans[-1][1] = max(spans[-1][1], b)
        else:
            spans.append([a, b])
    total = t1 - t0
    slow = sum(b - a for a, b in spans)
    rho_uniform = (frames - 1) / total
    rho_c = contact_share * (frames - 1) / slow if slow > 0 else 0.0
    rho_f = (1.0 - contact_share) * (frames - 1) / (total - slow) if total > slow else math.inf
    if not spans or rho_c <= rho_f or not math.isfinite(rho_f):
        t = np.linspace(t0, t1, frames)
        return t, np.full(frames, rho_uniform)
    knots, rates = [t0], []
    for a, b in spans:
        if a > knots[-1]:
            knots.append(a)
            rates.append(rho_f)
        knots.append(b)
        rates.append(rho_c)
    if t1 > knots[-1]:
        knots.append(t1)
        rates.append(rho_f)
    knots_a, rates_a = np.asarray(knots), np.asarray(rates)
    cumulative = np.concatenate(([0.0], np.cumsum(rates_a * np.diff(knots_a))))
    cumulative *= (frames - 1) / cumulative[-1]  # exact end despite round-off
    s = np.arange(frames, dtype=float)
    t = np.interp(s, cumulative, knots_a)
    t[-1] = t1
    segment = np.clip(np.searchsorted(knots_a, t, side="right") - 1, 0, rates_a.size - 1)
    return t, rates_a[segment]


def auto_scale(deflection: float, length: float, target: float = TARGET_DEFLECTION) -> float:
    """Deflection magnification that draws the largest ``deflection`` [m] as ``target`` x ``length``.

    Rounded down to two significant digits (so the drawn maximum is 10/11 to 1 times the target) and never
    below 1: a deflection already that large is drawn at its true size.
    """
    if not deflection > 0.0:
        return 1.0
    raw = target * length / deflection
    if raw <= 1.0:
        return 1.0
    unit = 10.0 ** (math.floor(math.log10(raw)) - 1)
    return max(1.0, math.floor(raw / unit * (1 + 1e-12)) * unit)


# --------------------------------------------------------------------------------------------- the history
@dataclass
class History:
    """What an animation needs of a result: samples of the hub angle, the modal coordinates and the contact
    force, the contact intervals, and the case."""

    time: np.ndarray
    phi: np.ndarray
    q: np.ndarray
    force: np.ndarray
    support: np.ndarray | None
    contacts: list[tuple[float, float]]
    case: Case
    label: str

    @classmethod
    def from_solution(cls, sol: Solution, case: Case | None = None) -> History:
        """The arrays and contact log of a :class:`~flexbeam.solution.Solution`."""
        case = case if case is not None else _case_from_toml(sol.provenance.get("case_toml"))
        support = sol.arrays.get("support_displacement")
        return cls(
            np.asarray(sol.time, float),
            np.asarray(sol["theta"], float),
            np.asarray(sol["q"], float),
            np.asarray(sol["contact_force"], float),
            None if support is None else np.asarray(support, float),
            [(c.onset, c.end) for c in sol.contacts],
            case,
            f"{case.name} [{sol.method}]",
        )

    @classmethod
    def from_dataset(cls, ds: Any, case: Case | None = None) -> History:
        """The variables of a result dataset (:meth:`~flexbeam.solution.Solution.to_xarray`, or ``result.nc``)."""
        for name in ("time", "theta", "q", "contact_force"):
            if name not in ds.variables:
                raise ParameterError(f"result: the dataset has no variable '{name}' (not a flexbeam result)")
        case = case if case is not None else _case_from_toml(ds.attrs.get("case_toml"))
        onset = np.asarray(ds["contact_onset"].values, float) if "contact_onset" in ds.variables else np.empty(0)
        end = (
            np.asarray(ds["contact_end"].values, float)
            if "contact_end" in ds.variables
            else np.full_like(onset, np.nan)
        )
        support = np.asarray(ds["support_displacement"].values, float) if "support_displacement" in ds else None
        method = str(ds.attrs.get("method", ""))
        return cls(
            np.asarray(ds["time"].values, float),
            np.asarray(ds["theta"].values, float),
            np.asarray(ds["q"].values, float).reshape(ds["time"].size, -1),
            np.asarray(ds["contact_force"].values, float),
            support,
            [(float(a), float(b)) for a, b in zip(onset, end)],
            case,
            f"{case.name} [{method}]",
        )

    @classmethod
    def load(cls, result: Solution | Any | str | Path, case: Case | None = None) -> History:
        """From a Solution, an :class:`xarray.Dataset` or the path of a ``result.nc``."""
        if isinstance(result, (str, Path)):
            import xarray as xr

            path = Path(result)
            if not path.is_file():
                raise ParameterError(f"result: no such file '{path}'")
            try:
                with xr.open_dataset(path) as ds:
                    data = ds.load()
            except (OSError, ValueError) as exc:
                raise ParameterError(f"result: cannot read '{path}' as NetCDF: {_one_line(exc)}") from None
            return cls.from_dataset(data, case)
        if hasattr(result, "arrays") and hasattr(result, "contacts"):
            return cls.from_solution(result, case)
        return cls.from_dataset(result, case)


def _one_line(message: object) -> str:
    return str(message).replace("\r", " ").replace("\n", " ")


def _case_from_toml(text: Any) -> Case:
    from .parameters.io import load_case

    if not isinstance(text, str) or not text:
        raise ParameterError("result: it records no case (provenance 'case_toml'); pass case=")
    return load_case(tomllib.loads(text))


# ------------------------------------------------------------------------------------------------ rendering
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


class FrameProgress:
    """A Rich progress bar of the rendered frames on stderr, shown on a terminal once rendering takes > 1 s."""

    def __init__(self, label: str) -> None:
        self.label = label
        self.start = time.perf_counter()
        self.bar: Any = None
        self.task: Any = None
        self.enabled = sys.stderr.isatty()

    def __call__(self, done: int, total: int) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            if time.perf_counter() - self.start < 1.0:
                return
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

            self.bar = Progress(
                TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TextColumn("frames"),
                TimeElapsedColumn(), console=Console(stderr=True), transient=True,
            )  # fmt: skip
            self.bar.start()
            self.task = self.bar.add_task(self.label, total=total)
        self.bar.update(self.task, completed=done)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()


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
    magnified by ``scale`` (stated on the frame), the hub, the obstacle and, below, the contact force against
    time with a cursor at the frame's time; the simulated time and the slow-motion factor are printed on it.

    Parameters
    ----------
    result
        A :class:`~flexbeam.solution.Solution`, its :meth:`~flexbeam.solution.Solution.to_xarray` dataset, or
        the path of a saved ``result.nc`` (any method but ``fem``, whose result has no modal coordinates).
    out
        Output file; its suffix picks the format: ``.gif`` (Pillow) or ``.mp4`` (H.264 by the ffmpeg of
        ``imageio-ffmpeg``; without it a ``.gif`` of the same name is written and a
        :class:`VideoFallbackWarning` issued).  Written atomically.
    scale
        Deflection magnification, or ``"auto"``: the largest deflection over the frames is drawn as 11-12 % of
        the beam length (:func:`auto_scale`).  The deflection is the centre line's displacement from the rigid
        reference line; only it is magnified, the rigid motion is drawn at its true size.
    window
        (t0, t1) [s] to animate, within the simulated time (default: all of it).
    frames, fps
        Number of frames and their rate in the file [1/s].
    size
        (width, height) of a frame [px] (even for MP4).
    contact_share
        Fraction of the frames spent in the contacts (:func:`frame_times`), 0 <= share < 1; 0 gives uniform
        frames.
    reference
        The rigid reference line the deflection is measured from: ``"contact"`` (default), the line from O
        through the contact point's centre line, so that the magnified beam touches the obstacle where the true
        one does; ``"hub"``, the hub's radial line at angle phi (the contact point then appears displaced from
        the obstacle by the magnified deflection there).  The hub is drawn turned by the same magnification
        relative to the reference line, so the magnified beam stays clamped to it.
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
    suffix = out.suffix.lower()
    if suffix not in SUFFIXES:
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

    writer_kind = "gif"
    if suffix == ".mp4":
        try:
            import imageio_ffmpeg
        except ImportError:
            gif = out.with_suffix(".gif")
            warnings.warn(
                f"imageio-ffmpeg is not installed (pip install 'flexbeam[video]'): writing {gif} instead of {out}",
                VideoFallbackWarning,
                stacklevel=2,
            )
            out = gif
        else:
            if width % 2 or height % 2:
                raise ParameterError(f"size: an MP4 (H.264) needs an even width and height (got {width}x{height})")
            writer_kind = "mp4"

    history = History.load(result, case)
    scene = Scene.build(history, window, frames, contact_share, reference, scale)
    bar = FrameProgress(f"rendering {out.name}") if progress is True else None
    report = progress if callable(progress) else bar
    try:
        _render(scene, out, width, height, fps, writer_kind, report, imageio_ffmpeg if writer_kind == "mp4" else None)
    finally:
        if bar is not None:
            bar.close()
    return out


def _check_int(name: str, value: Any, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not lo <= value <= hi:
        raise ParameterError(f"{name}: must be an integer in [{lo}, {hi}] (got {value!r})")
    return int(value)


@dataclass
class Scene:
    """Everything drawn, frame by frame: magnified beam outlines, hub angles, obstacle positions, force."""

    history: History
    times: np.ndarray
    density: np.ndarray
    scale: float
    reference: str
    centre: np.ndarray  # (m, k, 2) magnified centre line
    upper: np.ndarray  # (m, k, 2) band edges (half-thickness c on either side)
    lower: np.ndarray
    contact_point: np.ndarray  # (m, 2) the contact point on the lower surface
    chord: np.ndarray  # (m, 2, 2) the rigid reference line from O to r_h + L
    hub_angle: np.ndarray  # (m,) drawn hub angle
    obstacle_shift: np.ndarray  # (m, 2) compliant support's displacement
    force: np.ndarray  # (m,) contact force at the frames
    system: BeamSystem

    @classmethod
    def build(
        cls,
        history: History,
        window: tuple[float, float] | None,
        frames: int,
        contact_share: float,
        reference: str,
        scale: float | str,
    ) -> Scene:
        from .model.system import BeamSystem

        t = history.time
        if t.size < 2:
            raise ParameterError("result: fewer than two samples, nothing to animate")
        system = BeamSystem.from_case(history.case)
        beam = system.beam
        if history.q.shape[1] != beam.n:
            raise ModelError(
                f"animate: the result has {history.q.shape[1]} modal coordinates, its case "
                f"{beam.n} (a finite-element result has none: animate a modal run)"
            )
        ta, tb = float(t[0]), float(t[-1])
        t0, t1 = (ta, tb) if window is None else (float(window[0]), float(window[1]))
        slack = 1e-9 * max(abs(ta), abs(tb), tb - ta)
        if not (math.isfinite(t0) and math.isfinite(t1) and ta - slack <= t0 < t1 <= tb + slack):
            raise ParameterError(
                f"window: must satisfy {ta:g} <= t0 < t1 <= {tb:g} s, the simulated time (got {t0:g},{t1:g})"
            )
        t0, t1 = max(t0, ta), min(t1, tb)
        times, density = frame_times((t0, t1), history.contacts, frames, contact_share)

        phi = np.interp(times, t, history.phi)
        q = np.column_stack([np.interp(times, t, col) for col in history.q.T]) if beam.n else np.zeros((frames, 0))
        xP, c, L, rh = system.contact.position, system.contact.offset, beam.length, beam.hub_radius
        x = np.union1d(np.linspace(0.0, L, BEAM_POINTS), [xP])
        iP = int(np.searchsorted(x, xP))
        X, Y = beam_shape(system, phi, q, x)
        r = np.stack((X, Y), axis=-1)  # (m, k, 2)
        alpha = phi.copy()
        if reference == "contact" and rh + xP > 0.05 * (rh + L):
            alpha = phi + _wrap(np.arctan2(Y[:, iP], X[:, iP]) - phi)
        e1 = np.stack((np.cos(alpha), np.sin(alpha)), axis=-1)
        rigid = (rh + x)[None, :, None] * e1[:, None, :]
        deviation = r - rigid
        k = auto_scale(float(np.max(np.linalg.norm(deviation, axis=-1))), L) if scale == "auto" else float(scale)
        centre = rigid + k * deviation
        tangent = np.gradient(centre, x, axis=1)
        tangent /= np.maximum(np.linalg.norm(tangent, axis=-1, keepdims=True), 1e-300)
        normal = np.stack((-tangent[..., 1], tangent[..., 0]), axis=-1)  # e2 of the magnified line
        upper, lower = centre + c * normal, centre - c * normal
        chord = np.stack((np.zeros_like(e1), (rh + L) * e1), axis=1)
        hub_angle = alpha + k * (phi - alpha)
        shift = np.zeros((frames, 2))
        obstacle = system.contact.obstacle
        if history.support is not None and obstacle.compliant:
            shift = np.interp(times, t, history.support)[:, None] * np.asarray(obstacle.support[3:5])[None, :]
        force = np.interp(times, t, history.force)
        return cls(
            history,
            times,
            density,
            k,
            reference,
            centre,
            upper,
            lower,
            lower[:, iP],
            chord,
            hub_angle,
            shift,
            force,
            system,
        )


def _wrap(a: np.ndarray) -> np.ndarray:
    """Angle(s) wrapped to (-pi, pi]."""
    return np.pi - np.mod(np.pi - a, 2.0 * np.pi)


def _time_unit(span: float) -> tuple[float, str]:
    return (1e3, "ms") if span < 1.0 else (1.0, "s")


def speed_label(density: float, fps: float) -> str:
    """The playback speed of a frame taken at ``density`` frames per simulated second, shown at ``fps``:
    "1,234x slow motion" (density / fps > 1) or "2.5x real time"."""
    slow = density / fps
    if slow >= 10.0:
        return f"{slow:,.0f}x slow motion"
    if slow > 1.0:
        return f"{slow:.2g}x slow motion"
    return f"{1.0 / slow:.2g}x real time"


def _render(
    scene: Scene,
    out: Path,
    width: int,
    height: int,
    fps: float,
    kind: str,
    progress: Callable[[int, int], None] | None,
    ffmpeg: Any = None,
) -> None:
    """Render every frame of ``scene`` and encode them to ``out`` atomically."""
    from .solution import atomic_path

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


class FrameRenderer:
    """Draws the frames of a :class:`Scene` on a Matplotlib Agg canvas (object API, no pyplot).

    The static part (axes, ticks, labels, force trace, fixed obstacle) is drawn once; each frame restores it and
    draws only the moving artists (Matplotlib's blitting), about 8x faster than redrawing the figure.
    """

    def __init__(self, scene: Scene, width: int, height: int, fps: float, dpi: float = 100.0) -> None:
        import matplotlib as mpl

        self.scene, self.size = scene, (width, height)
        font = float(np.clip(height / 55.0, 3.0, 11.0))
        rc = {
            "font.size": font,
            "axes.linewidth": 0.6,
            "lines.linewidth": max(0.6, height / 600.0),
            "xtick.labelsize": font * 0.9,
            "ytick.labelsize": font * 0.9,
        }
        with mpl.rc_context(rc):
            self._build(width / dpi, height / dpi, dpi, fps, font)
            self.canvas.draw()
        self.background = self.canvas.copy_from_bbox(self.fig.bbox)

    def render(self, i: int) -> np.ndarray:
        """Frame ``i`` as an (height, width, 4) RGBA array (a copy)."""
        self.update(i)
        self.canvas.restore_region(self.background)
        for artist in self.moving:
            self.fig.draw_artist(artist)
        frame = np.asarray(self.canvas.buffer_rgba())
        if frame.shape[:2] != (self.size[1], self.size[0]):  # pragma: no cover - the Agg canvas rounds down
            raise RuntimeError(f"frame of {frame.shape[1]}x{frame.shape[0]} px, asked {self.size}")
        return frame.copy()

    def _build(self, w_in: float, h_in: float, dpi: float, fps: float, font: float) -> None:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
        from matplotlib.patches import Circle, Polygon

        scene = self.scene
        h, system = scene.history, scene.system
        obstacle = system.contact.obstacle
        L, rh = system.beam.length, system.beam.hub_radius
        fig = self.fig = Figure(figsize=(w_in, h_in), dpi=dpi, facecolor="white")
        self.canvas = FigureCanvasAgg(fig)
        gs = fig.add_gridspec(2, 1, height_ratios=(3, 1), left=0.13, right=0.97, top=0.9, bottom=0.11, hspace=0.38)
        ax = fig.add_subplot(gs[0])
        axf = fig.add_subplot(gs[1])

        # -- a fixed view of everything the frames draw, equal scales in x and y
        centre = np.asarray(obstacle.centre, float)
        beam_pts = np.concatenate(
            [scene.upper.reshape(-1, 2), scene.lower.reshape(-1, 2), np.array([[-rh, -rh], [rh, rh]])]
        )
        lo, hi = beam_pts.min(axis=0), beam_pts.max(axis=0)
        r_ob = obstacle.radius if obstacle.kind == 0 else 0.0
        ob_lo = np.min(centre + scene.obstacle_shift, axis=0) - r_ob
        ob_hi = np.max(centre + scene.obstacle_shift, axis=0) + r_ob
        # the obstacle joins the view when it is near the beam (a case may park it far away: no contact)
        if np.all(ob_lo <= hi + 0.5 * (rh + L)) and np.all(ob_hi >= lo - 0.5 * (rh + L)):
            lo, hi = np.minimum(lo, ob_lo), np.maximum(hi, ob_hi)
        mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo) + 0.05 * float(np.max(hi - lo))
        box = ax.get_position()
        aspect = (box.height * h_in) / (box.width * w_in)  # height / width of the axes box
        half = np.array([max(half[0], half[1] / aspect), max(half[1], half[0] * aspect)])
        ax.set_xlim(mid[0] - half[0], mid[0] + half[0])
        ax.set_ylim(mid[1] - half[1], mid[1] + half[1])
        ax.set_xlabel("x [m]", labelpad=1)
        ax.set_ylabel("y [m]", labelpad=1)
        ax.tick_params(length=2, pad=1)
        span = 2.0 * float(half[0])

        # -- obstacle: it moves only on a compliant support
        moves = bool(np.any(scene.obstacle_shift))
        self.obstacle = None
        if obstacle.kind == 0 and obstacle.radius > 0:
            self.obstacle = ax.add_patch(
                Circle(centre, obstacle.radius, facecolor="0.75", edgecolor="0.3", zorder=1, animated=moves)
            )
        elif obstacle.kind == 0:
            ax.plot([centre[0]], [centre[1]], "x", color="0.3", zorder=1)
        else:
            nrm = np.asarray(obstacle.normal, float)
            tan = np.array([-nrm[1], nrm[0]])
            big = 20.0 * (span + L)
            corners = np.array(
                [centre - big * tan, centre + big * tan, centre + big * tan - big * nrm, centre - big * tan - big * nrm]
            )
            ax.add_patch(Polygon(corners, closed=True, facecolor="0.85", edgecolor="0.3", hatch="///", zorder=1))

        # -- the beam (a band of its thickness about the magnified centre line), the reference line, P, the hub
        (chord,) = ax.plot([], [], ls="--", lw=0.6, color="0.55", zorder=2, animated=True)
        band = ax.add_patch(
            Polygon(np.zeros((3, 2)), closed=True, facecolor="C0", edgecolor="C0", alpha=0.85, zorder=3, animated=True)
        )
        (line,) = ax.plot([], [], color="navy", lw=0.5, zorder=4, animated=True)
        (pmark,) = ax.plot([], [], "o", ms=max(1.5, font * 0.45), zorder=5, animated=True)
        hub_r = rh if rh > 0 else 0.015 * L
        hub = ax.add_patch(
            Circle((0.0, 0.0), hub_r, facecolor="white" if rh == 0 else "0.85", edgecolor="k", zorder=6, animated=True)
        )
        (hub_line,) = ax.plot([], [], color="k", lw=1.0, zorder=7, animated=True)
        how = "line O-P" if scene.reference == "contact" else "hub's radial line"
        fig.text(0.5, 0.965, h.label, ha="center", va="center", fontsize=font * 1.1)
        ax.set_title(f"deflection from the {how} magnified x{scene.scale:.4g}", fontsize=font * 0.9, pad=2)
        clock = ax.text(
            0.01,
            0.97,
            "",
            transform=ax.transAxes,
            ha="left",
            va="top",
            fontsize=font,
            zorder=8,
            family="monospace",
            animated=True,
        )

        # -- the contact force with a cursor
        mult, unit = _time_unit(scene.times[-1] - scene.times[0])
        sel = (h.time >= scene.times[0]) & (h.time <= scene.times[-1])
        axf.plot(h.time[sel] * mult, h.force[sel], color="C3", lw=0.8)
        axf.set_xlim(scene.times[0] * mult, scene.times[-1] * mult)
        top = max(float(np.max(h.force[sel], initial=0.0)), 1.0)
        axf.set_ylim(-0.05 * top, 1.1 * top)
        axf.set_xlabel(f"Time [{unit}]", labelpad=1)
        axf.set_ylabel("Contact force [N]", labelpad=1)
        axf.tick_params(length=2, pad=1)
        cursor = axf.axvline(scene.times[0] * mult, color="k", lw=0.8, animated=True)
        (fdot,) = axf.plot([], [], "o", color="k", ms=max(1.5, font * 0.4), animated=True)

        steps = np.diff(scene.times) * mult
        smallest = float(np.min(steps[steps > 0], initial=1.0))
        decimals = int(np.clip(math.ceil(-math.log10(smallest)) + 1, 0, 9))
        reach = max(hub_r, 0.04 * L) if rh > 0 else hub_r

        def update(i: int) -> None:
            band.set_xy(np.concatenate((scene.upper[i], scene.lower[i][::-1])))
            line.set_data(scene.centre[i, :, 0], scene.centre[i, :, 1])
            chord.set_data(scene.chord[i, :, 0], scene.chord[i, :, 1])
            touching = bool(scene.force[i] > 0.0)
            pmark.set_data([scene.contact_point[i, 0]], [scene.contact_point[i, 1]])
            pmark.set_color("C3" if touching else "0.2")
            a = scene.hub_angle[i]
            hub_line.set_data([0.0, reach * math.cos(a)], [0.0, reach * math.sin(a)])
            if moves and self.obstacle is not None:
                self.obstacle.set_center(centre + scene.obstacle_shift[i])
            t = scene.times[i] * mult
            clock.set_text(
                f"t = {t:.{decimals}f} {unit}\n{speed_label(scene.density[i], fps)}" + ("\ncontact" if touching else "")
            )
            cursor.set_xdata([t, t])
            fdot.set_data([t], [scene.force[i]])

        self.update = update
        self.moving = [
            a
            for a in (self.obstacle if moves else None, chord, band, line, pmark, hub, hub_line, clock, cursor, fdot)
            if a is not None
        ]


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
