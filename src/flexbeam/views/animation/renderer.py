"""Drawing the frames of an animation: :class:`FrameRenderer` draws a
:class:`~flexbeam.views.animation.scene.Scene` frame by frame on a Matplotlib Agg canvas (object API, no pyplot
state) --
the beam, the hub, the obstacles, the clock with the playback speed (:func:`speed_label`) and the contact-force
trace with a cursor (one trace per contact pair in its own colour, :func:`pair_colour`, when there are several).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Circle, Polygon
    from matplotlib.text import Text

    from ...contact.setup import ObstacleGeometry
    from .scene import Scene


def _time_unit(span: float) -> tuple[float, str]:
    return (1e3, "ms") if span < 1.0 else (1.0, "s")


#: colours of the contact pairs' force traces and contact points when there are several (pair 0's is C3, as for
#: a single pair; C0 is the beam's)
PAIR_COLOURS = ("C3", "C1", "C2", "C4", "C5", "C6", "C8", "C9")


def pair_colour(k: int) -> str:
    """The colour of contact pair ``k`` in an animation with several pairs (:data:`PAIR_COLOURS`, cycled)."""
    return PAIR_COLOURS[k % len(PAIR_COLOURS)]


def _draw_obstacle(ax, ob: ObstacleGeometry, edge: str, big: float, animated: bool = False) -> Artist:
    """Draw obstacle ``ob`` on ``ax`` and return its artist.

    Parameters
    ----------
    ax
        The Matplotlib axes of the beam.
    ob
        A sphere (a grey disc; a cross for radius 0) or a half-plane (a hatched band ``big`` [m] wide and deep
        behind its line).
    edge
        The edge (and hatch) colour.
    big
        Half-width and depth [m] of a half-plane's band, well beyond the view.
    animated
        Whether the artist moves (a compliant support: drawn frame by frame).
    """
    from matplotlib.patches import Circle, Polygon

    centre = np.asarray(ob.centre, float)
    if ob.kind == 0 and ob.radius > 0:
        return ax.add_patch(Circle(centre, ob.radius, facecolor="0.75", edgecolor=edge, zorder=1, animated=animated))
    if ob.kind == 0:
        return ax.plot([centre[0]], [centre[1]], "x", color=edge, zorder=1)[0]
    nrm = np.asarray(ob.normal, float)
    tan = np.array([-nrm[1], nrm[0]])
    corners = np.array(
        [centre - big * tan, centre + big * tan, centre + big * tan - big * nrm, centre - big * tan - big * nrm]
    )
    return ax.add_patch(Polygon(corners, closed=True, facecolor="0.85", edgecolor=edge, hatch="///", zorder=1))


def speed_label(density: float, fps: float) -> str:
    """The playback speed of a frame taken at ``density`` frames per simulated second, shown at ``fps``:
    "1,234x slow motion" (density / fps > 1) or "2.5x real time"."""
    slow = density / fps
    if slow >= 10.0:
        return f"{slow:,.0f}x slow motion"
    if slow > 1.0:
        return f"{slow:.2g}x slow motion"
    return f"{1.0 / slow:.2g}x real time"


class FrameRenderer:
    """Draws the frames of a :class:`~flexbeam.views.animation.scene.Scene` on a Matplotlib Agg canvas (object API, no
    pyplot).

    The static part (axes, ticks, labels, force traces, fixed obstacles) is drawn once; each frame restores it and
    draws only the moving artists (Matplotlib's blitting), about 8x faster than redrawing the figure.  The beam's
    axes show a fixed view of everything the frames draw; the moving artists are the beam's, the clock and the
    force's cursor, each group with its own ``update``.

    Attributes
    ----------
    obstacles : list of matplotlib.artist.Artist
        One artist per obstacle of the case, in the order of ``system.contact.obstacles``.
    obstacle : matplotlib.patches.Circle or None
        Obstacle 0's disc (None for a point or a half-plane), which moves on a compliant support.
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

    def update(self, i: int) -> None:
        """Move the moving artists to frame ``i``."""
        scene = self.scene
        self._beam.update(scene, i, self._colours)
        if self._moves and self.obstacle is not None:
            self.obstacle.set_center(self._obstacle_centre + scene.obstacle_shift[i])
        self._clock.update(scene, i)
        self._force.update(scene, i)

    def _build(self, w_in: float, h_in: float, dpi: float, fps: float, font: float) -> None:
        """Draw the figure (``w_in`` x ``h_in`` inches): the beam's axes above, the contact force below."""
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        scene = self.scene
        obstacle = scene.system.contact.obstacle
        self._colours = [pair_colour(k) for k in range(scene.pairs)] if scene.pairs > 1 else ["C3"]
        fig = self.fig = Figure(figsize=(w_in, h_in), dpi=dpi, facecolor="white")
        self.canvas = FigureCanvasAgg(fig)
        gs = fig.add_gridspec(2, 1, height_ratios=(3, 1), left=0.13, right=0.97, top=0.9, bottom=0.11, hspace=0.38)
        ax = fig.add_subplot(gs[0])
        axf = fig.add_subplot(gs[1])
        span = _fit_view(ax, scene, w_in, h_in)

        # -- the obstacles: only obstacle 0 moves, and only on a compliant support
        self._moves = bool(np.any(scene.obstacle_shift))
        self._obstacle_centre = np.asarray(obstacle.centre, float)
        self.obstacles = _draw_obstacles(ax, scene, self._colours, span, self._moves)
        self.obstacle = self.obstacles[0] if obstacle.kind == 0 and obstacle.radius > 0 else None

        self._beam = _BeamArtists.draw(ax, scene, font)
        _draw_titles(fig, ax, scene, font)
        mult, unit = _time_unit(scene.times[-1] - scene.times[0])
        self._clock = _Clock.draw(ax, font, mult, unit, _clock_decimals(scene.times, mult), fps)
        self._force = _ForceArtists.draw(axf, scene, self._colours, font, mult, unit)
        self.moving = [
            a
            for a in (
                self.obstacle if self._moves else None,
                *self._beam.artists,
                self._clock.text,
                *self._force.artists,
            )
            if a is not None
        ]


def _fit_view(ax: Axes, scene: Scene, w_in: float, h_in: float) -> float:
    """Fix the view of ``ax`` on everything the frames draw, with equal scales in x and y; return its width [m].

    The view holds the beam's band in every frame, the hub and each obstacle near the beam (a case may park one
    far away: no contact), with a 5 % margin, widened in x or y to the shape of the axes' box in a figure of
    ``w_in`` x ``h_in`` inches.
    """
    system = scene.system
    L, rh = system.beam.length, system.beam.hub_radius
    hub = np.array([[-rh, -rh], [rh, rh]]) if scene.origin is None else np.empty((0, 2))  # a free beam has none
    beam_pts = np.concatenate([scene.upper.reshape(-1, 2), scene.lower.reshape(-1, 2), hub])
    rh = abs(rh)
    lo, hi = beam_pts.min(axis=0), beam_pts.max(axis=0)
    beam_lo, beam_hi = lo, hi
    for j, ob in enumerate(system.contact.obstacles):
        r_ob = ob.radius if ob.kind == 0 else 0.0
        at = np.asarray(ob.centre, float) + (scene.obstacle_shift if j == 0 else np.zeros((1, 2)))
        ob_lo, ob_hi = np.min(at, axis=0) - r_ob, np.max(at, axis=0) + r_ob
        # an obstacle joins the view when it is near the beam (a case may park it far away: no contact)
        if np.all(ob_lo <= beam_hi + 0.5 * (rh + L)) and np.all(ob_hi >= beam_lo - 0.5 * (rh + L)):
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
    return 2.0 * float(half[0])


def _draw_obstacles(ax: Axes, scene: Scene, colours: list[str], span: float, moves: bool) -> list[Artist]:
    """Draw every obstacle of the case on ``ax`` (a view ``span`` [m] wide) and return their artists.

    With several pairs each obstacle is edged in the colour of the (first) pair touching it, else grey; obstacle
    0 is animated when it ``moves`` (a compliant support).
    """
    system = scene.system
    obstacles, pairs = system.contact.obstacles, system.contact.pairs
    edges = ["0.3"] * len(obstacles)
    if scene.pairs > 1:  # each obstacle edged in the colour of the (first) pair touching it
        for k in reversed(range(len(pairs))):
            edges[pairs[k].obstacle] = colours[k]
    big = 20.0 * (span + system.beam.length)
    return [_draw_obstacle(ax, ob, edges[j], big, animated=moves and j == 0) for j, ob in enumerate(obstacles)]


def _draw_titles(fig: Figure, ax: Axes, scene: Scene, font: float) -> None:
    """The run's label above the figure and, above the beam, the reference line and the magnification."""
    how = "line O-P" if scene.reference == "contact" else "hub's radial line"
    if scene.origin is not None:
        how = "mean axis"
    fig.text(0.5, 0.965, scene.history.label, ha="center", va="center", fontsize=font * 1.1)
    ax.set_title(f"deflection from the {how} magnified x{scene.scale:.4g}", fontsize=font * 0.9, pad=2)


def _clock_decimals(times: np.ndarray, mult: float) -> int:
    """Decimals of the clock in units ``1 / mult`` s: one more than the smallest step between frames needs."""
    steps = np.diff(times) * mult
    smallest = float(np.min(steps[steps > 0], initial=1.0))
    return int(np.clip(math.ceil(-math.log10(smallest)) + 1, 0, 9))


@dataclass
class _BeamArtists:
    """The beam's moving artists: a band of its thickness about the magnified centre line, the centre line, the
    rigid reference line, each pair's contact point and the hub with its radial line (a free beam: a mark at its
    centre of mass, no radial line)."""

    chord: Line2D
    band: Polygon
    line: Line2D
    marks: list[Line2D]
    anywhere: list[bool]  # per pair: contact anywhere (its point is marked only in contact)
    hub: Circle
    hub_line: Line2D
    reach: float  # length of the hub's radial line [m]

    @classmethod
    def draw(cls, ax: Axes, scene: Scene, font: float) -> _BeamArtists:
        """Add the (empty) artists to ``ax``."""
        from matplotlib.patches import Circle, Polygon

        system = scene.system
        pairs = system.contact.pairs
        L, rh = system.beam.length, system.beam.hub_radius
        (chord,) = ax.plot([], [], ls="--", lw=0.6, color="0.55", zorder=2, animated=True)
        band = ax.add_patch(
            Polygon(np.zeros((3, 2)), closed=True, facecolor="C0", edgecolor="C0", alpha=0.85, zorder=3, animated=True)
        )
        (line,) = ax.plot([], [], color="navy", lw=0.5, zorder=4, animated=True)
        marks = [ax.plot([], [], "o", ms=max(1.5, font * 0.45), zorder=5, animated=True)[0] for _ in range(scene.pairs)]
        anywhere = [bool(pairs[k].anywhere) if k < len(pairs) else False for k in range(scene.pairs)]
        free = scene.origin is not None
        hub_r = rh if rh > 0 and not free else 0.015 * L
        hub = ax.add_patch(
            Circle((0.0, 0.0), hub_r, facecolor="white" if rh <= 0 else "0.85", edgecolor="k", zorder=6, animated=True)
        )
        (hub_line,) = ax.plot([], [], color="k", lw=1.0, zorder=7, animated=True)
        reach = 0.0 if free else (max(hub_r, 0.04 * L) if rh > 0 else hub_r)
        return cls(chord, band, line, marks, anywhere, hub, hub_line, reach)

    @property
    def artists(self) -> list[Artist]:
        """The artists in drawing order."""
        return [self.chord, self.band, self.line, *self.marks, self.hub, self.hub_line]

    def update(self, scene: Scene, i: int, colours: list[str]) -> None:
        """Move them to frame ``i``; a pair's point in its colour while in contact, else dark grey."""
        self.band.set_xy(np.concatenate((scene.upper[i], scene.lower[i][::-1])))
        self.line.set_data(scene.centre[i, :, 0], scene.centre[i, :, 1])
        self.chord.set_data(scene.chord[i, :, 0], scene.chord[i, :, 1])
        for k, mark in enumerate(self.marks):
            on = bool(scene.pair_force[i, k] > 0.0)
            if self.anywhere[k] and not on:  # an anywhere pair's point is marked only in contact
                mark.set_data([], [])
            else:
                mark.set_data([scene.pair_points[i, k, 0]], [scene.pair_points[i, k, 1]])
            mark.set_color(colours[k] if on else "0.2")
        a = scene.hub_angle[i]
        o = (0.0, 0.0) if scene.origin is None else tuple(scene.origin[i])
        self.hub.set_center(o)
        self.hub_line.set_data([o[0], o[0] + self.reach * math.cos(a)], [o[1], o[1] + self.reach * math.sin(a)])


@dataclass
class _Clock:
    """The text in the beam's corner: the simulated time, the playback speed (:func:`speed_label`) and
    "contact" while a pair touches."""

    text: Text
    mult: float  # the time unit's factor: 1e3 for ms, 1 for s
    unit: str
    decimals: int
    fps: float

    @classmethod
    def draw(cls, ax: Axes, font: float, mult: float, unit: str, decimals: int, fps: float) -> _Clock:
        """Add the (empty) text to the top left corner of ``ax``."""
        text = ax.text(
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
        return cls(text, mult, unit, decimals, fps)

    def update(self, scene: Scene, i: int) -> None:
        """Show frame ``i``'s time, speed and contact."""
        touching = bool(np.any(scene.pair_force[i] > 0.0))
        t = scene.times[i] * self.mult
        self.text.set_text(
            f"t = {t:.{self.decimals}f} {self.unit}\n{speed_label(scene.density[i], self.fps)}"
            + ("\ncontact" if touching else "")
        )


@dataclass
class _ForceArtists:
    """The contact force against time (one trace per pair that touches, with several) and its moving cursor and
    dots."""

    cursor: Line2D
    traces: list[int]  # the pairs traced
    dots: list[Line2D]  # one per traced pair: its force at the frame
    mult: float

    @classmethod
    def draw(cls, axf: Axes, scene: Scene, colours: list[str], font: float, mult: float, unit: str) -> _ForceArtists:
        """Draw the traces on ``axf`` (times in units ``1 / mult`` s, named ``unit``) and add the cursor and
        dots."""
        h, pairs = scene.history, scene.system.contact.pairs
        multi = scene.pairs > 1
        sel = (h.time >= scene.times[0]) & (h.time <= scene.times[-1])
        if multi and h.pair_force is not None:  # each pair that touches in the window, pair 0 always
            traces = [k for k in range(scene.pairs) if k == 0 or np.any(h.pair_force[sel, k] > 0.0)]
            forces = h.pair_force[sel]
            for k in traces:
                axf.plot(h.time[sel] * mult, forces[:, k], color=colours[k], lw=0.8, label=pairs[k].label)
            axf.legend(fontsize=font * 0.75, loc="upper right", handlelength=1.2, borderaxespad=0.3)
        else:
            traces, forces = [0], h.force[sel][:, None]
            axf.plot(h.time[sel] * mult, h.force[sel], color="C3", lw=0.8)
        axf.set_xlim(scene.times[0] * mult, scene.times[-1] * mult)
        top = max(float(np.max(forces, initial=0.0)), 1.0)
        axf.set_ylim(-0.05 * top, 1.1 * top)
        axf.set_xlabel(f"Time [{unit}]", labelpad=1)
        axf.set_ylabel("Contact force [N]", labelpad=1)
        axf.tick_params(length=2, pad=1)
        cursor = axf.axvline(scene.times[0] * mult, color="k", lw=0.8, animated=True)
        dots = [
            axf.plot([], [], "o", color=colours[k] if multi else "k", ms=max(1.5, font * 0.4), animated=True)[0]
            for k in traces
        ]
        return cls(cursor, traces, dots, mult)

    @property
    def artists(self) -> list[Artist]:
        """The moving artists in drawing order."""
        return [self.cursor, *self.dots]

    def update(self, scene: Scene, i: int) -> None:
        """Move the cursor and the dots to frame ``i``."""
        t = scene.times[i] * self.mult
        self.cursor.set_xdata([t, t])
        for k, dot in zip(self.traces, self.dots):
            dot.set_data([t], [scene.pair_force[i, k]])
