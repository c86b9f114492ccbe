"""What each frame of an animation draws, as numbers: :class:`Scene` holds, per frame, the beam's band with its
deflection magnified about the rigid reference line, the contact point, the reference line, the drawn hub angle,
the obstacle's displacement and the contact force -- and, for a case with several contact pairs, each pair's
contact point and force -- built from a :class:`~flexbeam.views.animation.history.History` by
the geometry of :mod:`flexbeam.views.animation.geometry`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ...contact.setup import OBSTACLE_SPHERE
from ...errors import ModelError, ParameterError
from .geometry import auto_scale, beam_shape, frame_times, reference_angle
from .history import History

if TYPE_CHECKING:
    from ...contact.setup import ObstacleGeometry
    from ...model.system import BeamSystem

#: material points drawn along the beam
BEAM_POINTS = 121


@dataclass
class Scene:
    """Everything drawn, frame by frame: magnified beam outlines, hub angles, obstacle positions, force.

    The obstacles are ``system.contact.obstacles`` (only obstacle 0 may move, by ``obstacle_shift``); pair k of
    ``system.contact.pairs`` touches obstacle ``pairs[k].obstacle`` at ``pair_points[:, k]`` with force
    ``pair_force[:, k]`` (for a single fixed pair, ``contact_point`` and ``force``).
    """

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
    obstacle_shift: np.ndarray  # (m, 2) compliant support's displacement (and -r_O of a ground obstacle)
    force: np.ndarray  # (m,) contact force at the frames (the first pair's)
    system: BeamSystem
    pair_points: np.ndarray | None = None  # (m, p, 2) each pair's contact point on the magnified band
    pair_force: np.ndarray | None = None  # (m, p) each pair's contact force at the frames
    origin: np.ndarray | None = None  # (m, 2) a free beam's frame origin (its centre of mass); None: O, a joint

    def __post_init__(self) -> None:
        if self.pair_points is None:
            self.pair_points = self.contact_point[:, None, :]
        if self.pair_force is None:
            self.pair_force = self.force[:, None]

    @property
    def pairs(self) -> int:
        """Number of contact pairs."""
        return int(self.pair_force.shape[1])

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
        """The scene of ``frames`` frames of ``history`` over ``window`` (default: all of it).

        Frame times by :func:`~flexbeam.views.animation.geometry.frame_times`; hub angle, modal coordinates, support
        displacement and force interpolated linearly between the samples; the centre line by
        :func:`~flexbeam.views.animation.geometry.beam_shape` at :data:`BEAM_POINTS` points and the contact point;
        its deviation from the rigid line at :func:`~flexbeam.views.animation.geometry.reference_angle` magnified by
        ``scale`` (``"auto"``: :func:`~flexbeam.views.animation.geometry.auto_scale` of its largest norm over the
        frames); the band's edges offset by the contact offset c along the magnified line's normal.  Each pair's
        contact point is offset by its own c from the magnified centre line at its material coordinate: fixed
        pairs' coordinates are points of the drawn line; an anywhere pair's moves (the result's
        ``pair_contact_position``), is interpolated linearly between them and lies on the side facing its
        obstacle.
        """
        from ...model.system import BeamSystem

        t = history.time
        if t.size < 2:
            raise ParameterError("result: fewer than two samples, nothing to animate")
        free = history.case.joint.kind == "free"
        if free and history.centre is None:
            raise ParameterError(
                "result: a free beam's result without centre_of_mass (written before flexbeam had it); run it again"
            )
        system = BeamSystem.from_case(history.case)
        beam = system.beam
        if history.q.shape[1] != beam.nq:
            raise ModelError(
                f"animate: the result has {history.q.shape[1]} modal coordinates, its case "
                f"{beam.nq} (a finite-element result has none: animate a modal run)"
            )
        times, density = frame_times(_window(t, window), history.contacts, frames, contact_share)
        phi = np.interp(times, t, history.phi)
        # the bending modes only: the drawing leaves out the axial modes' stretch (of the order of the strain)
        bending = history.q[:, : beam.n]
        q = np.column_stack([np.interp(times, t, col) for col in bending.T]) if beam.n else np.zeros((frames, 0))
        x = np.union1d(np.linspace(0.0, beam.length, BEAM_POINTS), [p.position for p in system.contact.pairs])
        iP = int(np.searchsorted(x, system.contact.position))
        origin = np.column_stack([np.interp(times, t, col) for col in history.centre.T]) if free else None
        band = _Band.magnified(system, phi, q, x, iP, reference, scale, origin)
        shift = _support_shift(history, system, times, frames)
        force = np.interp(times, t, history.force)
        pair_points, pair_force = _pairs_at_frames(history, system, times, x, band, shift)
        return cls(
            history,
            times,
            density,
            band.scale,
            reference,
            band.centre,
            band.upper,
            band.lower,
            band.lower[:, iP],
            band.chord,
            band.hub_angle,
            shift,
            force,
            system,
            pair_points,
            pair_force,
            origin,
        )


def _window(t: np.ndarray, window: tuple[float, float] | None) -> tuple[float, float]:
    """The animated interval (t0, t1) [s]: ``window`` (default: all of ``t``), checked to lie within the simulated
    time up to a relative 1e-9 and clipped to it."""
    ta, tb = float(t[0]), float(t[-1])
    try:  # (a string "0,1e-4" is the CLI's --window: here two numbers)
        t0, t1 = (ta, tb) if window is None else (float(window[0]), float(window[1]))
        if window is not None and (isinstance(window, (str, bytes)) or len(window) != 2):
            raise ValueError
    except (TypeError, ValueError, IndexError):
        raise ParameterError(f"window: two times (t0, t1) in s, e.g. (0.0, 2e-3) (got {window!r})") from None
    slack = 1e-9 * max(abs(ta), abs(tb), tb - ta)
    if not (math.isfinite(t0) and math.isfinite(t1) and ta - slack <= t0 < t1 <= tb + slack):
        raise ParameterError(
            f"window: must satisfy {ta:g} <= t0 < t1 <= {tb:g} s, the simulated time (got {t0:g},{t1:g})"
        )
    return max(t0, ta), min(t1, tb)


class _Band(NamedTuple):
    """The beam drawn with its deflection magnified, per frame (m frames, k points)."""

    scale: float  # the magnification
    centre: np.ndarray  # (m, k, 2) magnified centre line
    normal: np.ndarray  # (m, k, 2) its unit normal (e2 of the magnified line)
    upper: np.ndarray  # (m, k, 2) band edges, half-thickness c either side
    lower: np.ndarray
    chord: np.ndarray  # (m, 2, 2) the rigid reference line from O to r_h + L (a free beam's: end to end)
    hub_angle: np.ndarray  # (m,) drawn hub angle

    @classmethod
    def magnified(
        cls,
        system: BeamSystem,
        phi: np.ndarray,
        q: np.ndarray,
        x: np.ndarray,
        iP: int,
        reference: str,
        scale: float | str,
        origin: np.ndarray | None = None,
    ) -> _Band:
        """The centre line by :func:`~flexbeam.views.animation.geometry.beam_shape` at the points ``x`` (``x[iP]``:
        the contact point) for hub angles ``phi`` and modal coordinates ``q``, its deviation from the rigid line at
        :func:`~flexbeam.views.animation.geometry.reference_angle` magnified by ``scale`` (``"auto"``:
        :func:`~flexbeam.views.animation.geometry.auto_scale` of its largest norm), the band's edges offset by the
        contact offset c along the magnified line's normal, the hub turned by the same magnification.  A free beam
        (its frame's ``origin`` per frame) is drawn about its frame's axis through the origin, whatever
        ``reference``: its mean axis (docs/free-beam.md), from which its deflection is measured; its band is the
        section's true thickness (its contact is often found anywhere on the centre line's capsule)."""
        beam = system.beam
        xP, c, L, rh = system.contact.position, system.contact.offset, beam.length, beam.hub_radius
        if origin is not None:  # a free beam's pairs are often on its centre line (a capsule): its true thickness
            c = abs(system.case.beam.surface_offset)
        X, Y = beam_shape(system, phi, q, x, origin)
        r = np.stack((X, Y), axis=-1)  # (m, k, 2)
        R = np.zeros((phi.size, 2)) if origin is None else origin
        alpha = reference_angle(reference, phi, r[:, iP] - R, rh + xP, rh + L) if origin is None else phi.copy()
        e1 = np.stack((np.cos(alpha), np.sin(alpha)), axis=-1)
        rigid = R[:, None, :] + (rh + x)[None, :, None] * e1[:, None, :]
        deviation = r - rigid
        k = auto_scale(float(np.max(np.linalg.norm(deviation, axis=-1))), L) if scale == "auto" else float(scale)
        centre = rigid + k * deviation
        tangent = np.gradient(centre, x, axis=1)
        tangent /= np.maximum(np.linalg.norm(tangent, axis=-1, keepdims=True), 1e-300)
        normal = np.stack((-tangent[..., 1], tangent[..., 0]), axis=-1)  # e2 of the magnified line
        upper, lower = centre + c * normal, centre - c * normal
        chord = np.stack((R if origin is None else R + rh * e1, R + (rh + L) * e1), axis=1)
        hub_angle = alpha + k * (phi - alpha)
        return cls(k, centre, normal, upper, lower, chord, hub_angle)


def _support_shift(history: History, system: BeamSystem, times: np.ndarray, frames: int) -> np.ndarray:
    """(frames, 2): obstacle 0's displacement [m] on a compliant support at the frame ``times`` (else zero), and
    for an obstacle fixed to the ground on a moving base -r_O(t) (the base frame's view of it)."""
    shift = np.zeros((frames, 2))
    obstacle = system.contact.obstacle
    if history.support is not None and obstacle.compliant:
        shift = np.interp(times, history.time, history.support)[:, None] * np.asarray(obstacle.support[3:5])[None, :]
    if obstacle.ground:
        shift = shift - np.array([system.case.base.motion(float(t))[0] for t in times])
    return shift


def _pairs_at_frames(
    history: History, system: BeamSystem, times: np.ndarray, x: np.ndarray, band: _Band, shift: np.ndarray
) -> tuple[np.ndarray | None, np.ndarray | None]:
    """Each pair's contact point on the magnified ``band`` (at the points ``x``) and its force, (m, p, 2) and
    (m, p), at the frame ``times``; (None, None) when the result has no per-pair forces.

    A pair's point is offset by its own c from the magnified centre line at its material coordinate: a fixed
    pair's is a point of ``x``; an anywhere pair's moves (the result's ``pair_contact_position``, interpolated
    linearly) and lies on the side facing its obstacle (obstacle 0 displaced by ``shift``).
    """
    pairs, L, t = system.contact.pairs, system.beam.length, history.time
    if history.pair_force is None or history.pair_force.shape[1] != len(pairs):
        return None, None
    frames = times.size
    pair_force = np.column_stack([np.interp(times, t, col) for col in history.pair_force.T])
    moving = history.pair_position
    where = np.empty((frames, len(pairs)))
    for j, pair in enumerate(pairs):
        if pair.anywhere and moving is not None:
            where[:, j] = np.clip(np.interp(times, t, moving[:, j]), 0.0, L)
        else:
            where[:, j] = pair.position
    mid, nrm = _on_line(band.centre, x, where), _on_line(band.normal, x, where)  # fixed pairs: the line's points
    pair_points = mid - np.array([p.offset for p in pairs])[None, :, None] * nrm
    for j, pair in enumerate(pairs):
        if pair.anywhere:
            ob = system.contact.obstacles[pair.obstacle]
            moved = shift if pair.obstacle == 0 else np.zeros_like(shift)
            pair_points[:, j] = _facing(mid[:, j], nrm[:, j], pair.offset, ob, moved)
    return pair_points, pair_force


def _on_line(values: np.ndarray, x: np.ndarray, where: np.ndarray) -> np.ndarray:
    """``values`` given at the points ``x`` of a line, interpolated linearly to material coordinates ``where``.

    Parameters
    ----------
    values
        Shape (m, k, 2): per frame, a vector at each of the k points.
    x
        Increasing material coordinates [m] of the points, shape (k,).
    where
        Material coordinates [m] per frame and pair, shape (m, p), within [x[0], x[-1]].

    Returns
    -------
    numpy.ndarray
        Shape (m, p, 2); at a point of ``x`` exactly its value.
    """
    j = np.clip(np.searchsorted(x, where, side="right") - 1, 0, x.size - 2)  # (m, p)
    w = ((where - x[j]) / (x[j + 1] - x[j]))[..., None]
    rows = np.arange(values.shape[0])[:, None]
    return (1.0 - w) * values[rows, j] + w * values[rows, j + 1]


def _facing(
    mid: np.ndarray, nrm: np.ndarray, offset: float, obstacle: ObstacleGeometry, shift: np.ndarray
) -> np.ndarray:
    """The surface point, ``|offset|`` either side of the centre-line points ``mid`` along ``nrm`` (both (m, 2)),
    nearer obstacle ``obstacle`` (displaced by ``shift``, (m, 2)): an anywhere pair touches on either side."""
    at = np.asarray(obstacle.centre, float)[None, :] + shift
    a, b = mid + abs(offset) * nrm, mid - abs(offset) * nrm
    if obstacle.kind == OBSTACLE_SPHERE:
        da, db = np.linalg.norm(a - at, axis=-1), np.linalg.norm(b - at, axis=-1)
    else:
        n = np.asarray(obstacle.normal, float)
        da, db = (a - at) @ n, (b - at) @ n
    return np.where((da <= db)[:, None], a, b)
