"""The beam's whole body against the obstacles at one state: where it penetrates one, and how deep.

The body is the beam's section swept along its deformed centre line: at each material coordinate x in [0, L] the
segment rho(x) + s n(x), -c <= s <= c, with c the surface offset (``beam.radius``, or ``beam.half_depth``), rho(x) the
centre line of the modal model in the body frame (``docs/formulation.md``),

    rho(x) = (r_h + x + u_x(x), Psi(x) q),   u_x(x) = -1/2 q^T H(x) q = -1/2 [r_h (d q)^2 + int_0^x (Psi' q)^2 dxi]

(u_x = 0 in the zeroth-order model; a free beam's frame sits at its centre of mass, r_h = -L/2, and its H starts at
-H_bar instead of r_h d^T d), and n(x) = (-sin a, cos a) the section normal turned by the slope a = Psi'(x) q,
as the compiled point kinematics place a surface point (``kernels/src/model.c``, ``fb_point_kinematics``).  Its ends
are the flat faces at x = 0 and x = L (the tip's end face is where a ``side = "centre"`` contact point at x = L lies).
For a sphere in the plane of motion the nearest point of a circular cylinder lies in that plane, so this strip is
the beam exactly; it is sampled at :func:`stations` sections joined by straight edges, exact for a straight beam and
within h^2 kappa / 8 of a curved one (h the spacing, kappa the curvature: ~1e-10 m for the seed beam's static
deflection under gravity with h = L / 1000).

:func:`penetrations` gives, per obstacle, the depth by which the body reaches into it: a sphere's radius minus the
distance from its centre to the body (plus the centre's depth inside the body when the centre itself is covered),
a half-plane's depth as the lowest body point below its boundary line.  Negative depths are clearances.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..contact.setup import OBSTACLE_SPHERE, ObstacleGeometry
from .beam import ModalBeam

#: Gauss-Legendre points per station interval for int (Psi' q)^2 (a polynomial of degree ~2 (2 pi / 32)^-1 per
#: wavelength between stations: 6 points are exact to round-off for the station spacing below)
_GAUSS_POINTS = 6


@dataclass(frozen=True)
class Penetration:
    """How deep the body reaches into obstacle ``obstacle`` [m] (< 0: the clearance) and where: the material
    coordinate ``x`` [m] of the deepest body point and where it lies (``"lower surface"`` -- the side a ``below``
    contact point is on --, ``"upper surface"``, ``"root face"``, ``"tip face"``, a corner, or ``"the sphere's
    centre inside the beam"``)."""

    obstacle: int
    depth: float
    x: float
    surface: str


def stations(beam: ModalBeam) -> np.ndarray:
    """Material coordinates of the body's sections: at least 1001, and 32 per wavelength of the highest mode
    (~ 2 L / (n + 1/4))."""
    count = 1 + max(1000, 16 * (beam.n + 1))
    return np.linspace(0.0, beam.length, count)


def centre_line(beam: ModalBeam, q: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(rho_x, rho_y, a): the deformed centre line in the body frame and the section's slope angle at ``x``
    (sorted, starting at 0) for the modal coordinates ``q`` (with axial modes [q, p])."""
    q = np.asarray(q, float)
    base = beam.hub_radius + x
    if beam.axial is not None:  # [q, p]: the axial modes' stretch Phi_a(x) p moves the sections along e1
        q, p = q[: beam.n], q[beam.n :]
        base = base + beam.axial.shapes(x, 0) @ p
    if beam.n == 0 or not np.any(q):  # undeformed (every start from rest): the straight line, no shapes evaluated
        zero = np.zeros_like(x)
        return base, zero, zero
    w = beam.shapes(x, 0) @ q
    a = beam.shapes(x, 1) @ q
    u = np.zeros_like(x)
    if beam.first_order:
        # int_0^x (Psi' q)^2 by Gauss-Legendre per interval, accumulated
        xi, wi = np.polynomial.legendre.leggauss(_GAUSS_POINTS)
        lo, hi = x[:-1], x[1:]
        pts = (0.5 * (hi - lo)[:, None] * (xi[None, :] + 1.0) + lo[:, None]).ravel()
        slope = (beam.shapes(pts, 1) @ q).reshape(lo.size, _GAUSS_POINTS)
        parts = 0.5 * (hi - lo) * ((slope * slope) @ wi)
        integral = np.concatenate(([0.0], np.cumsum(parts)))
        if beam.H_root is None:
            u = -0.5 * (beam.hub_radius * float(beam.d @ q) ** 2 + integral)
        else:  # a free beam: H(x) = H(0) + int_0^x Psi'^T Psi', H(0) = -H_bar
            u = -0.5 * (float(q @ beam.H_root @ q) + integral)
    return base + u, w, a


def outline(
    beam: ModalBeam, surface: float, theta: float, q: np.ndarray, origin: tuple[float, float] | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(x, lower, upper): the sections' material coordinates and their lower (c below the centre line) and upper
    ends in the plane of motion (rows of points), for the frame angle ``theta`` and modal coordinates ``q``; the
    frame's ``origin`` (a free beam's centre of mass; default: O)."""
    x = stations(beam)
    rx, ry, a = centre_line(beam, q, x)
    nx, ny = -np.sin(a), np.cos(a)
    ct, st = math.cos(theta), math.sin(theta)

    def world(bx: np.ndarray, by: np.ndarray) -> np.ndarray:
        pts = np.column_stack((ct * bx - st * by, st * bx + ct * by))
        return pts if origin is None else pts + np.asarray(origin, float)[None, :]

    return x, world(rx - surface * nx, ry - surface * ny), world(rx + surface * nx, ry + surface * ny)


def penetrations(
    beam: ModalBeam,
    surface: float,
    theta: float,
    q: np.ndarray,
    obstacles: tuple[ObstacleGeometry, ...],
    origin: tuple[float, float] | None = None,
) -> list[Penetration]:
    """The deepest penetration of the body (frame angle ``theta``, modal coordinates ``q``, surface offset
    ``surface``, the frame's ``origin``: default O) into each of the ``obstacles`` at their rest positions (see the
    module docstring)."""
    x, lower, upper = outline(beam, surface, theta, q, origin)
    return [_penetration(k, ob, x, lower, upper) for k, ob in enumerate(obstacles)]


def _penetration(k: int, ob: ObstacleGeometry, x: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> Penetration:
    if ob.kind != OBSTACLE_SPHERE:  # a linear function is lowest at a vertex of the sampled body
        heights = np.concatenate(((lower - ob.centre) @ ob.normal, (upper - ob.centre) @ ob.normal))
        i = int(np.argmin(heights))
        j = i % x.size
        where = "lower" if i < x.size else "upper"
        where = f"{where} {'root corner' if j == 0 else 'tip corner' if j == x.size - 1 else 'surface'}"
        return Penetration(k, float(-heights[i]), float(x[j]), where)
    C = np.asarray(ob.centre, float)
    # the boundary: lower and upper edges, root and tip faces; x of each segment's ends
    starts = np.vstack((lower[:-1], upper[:-1], lower[:1], lower[-1:]))
    ends = np.vstack((lower[1:], upper[1:], upper[:1], upper[-1:]))
    xs = np.concatenate((x[:-1], x[:-1], x[:1], x[-1:]))
    xe = np.concatenate((x[1:], x[1:], x[:1], x[-1:]))
    names = ["lower surface"] * (x.size - 1) + ["upper surface"] * (x.size - 1) + ["root face", "tip face"]
    dist, t = _segment_distance(C, starts, ends)
    i = int(np.argmin(dist))
    xi = float(xs[i] + t[i] * (xe[i] - xs[i]))
    if _covered(C, lower, upper):  # the centre inside the beam: deeper than the radius
        return Penetration(k, float(ob.radius + dist[i]), xi, "the sphere's centre inside the beam")
    return Penetration(k, float(ob.radius - dist[i]), xi, names[i])


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Distances from point p to the segments [a_i, b_i] (rows) and the parameter in [0, 1] of the nearest point."""
    with np.errstate(over="ignore", invalid="ignore"):  # an obstacle ~1e300 m away: its distance is inf, not NaN
        ab = b - a
        ll = np.einsum("ij,ij->i", ab, ab)
        t = np.where(ll > 0.0, np.einsum("ij,ij->i", p - a, ab) / np.where(ll > 0.0, ll, 1.0), 0.0)
        t = np.clip(np.nan_to_num(t, nan=0.0), 0.0, 1.0)
        d = p - (a + t[:, None] * ab)
        dist = np.hypot(d[:, 0], d[:, 1])
    return np.where(np.isnan(dist), np.inf, dist), t


def _covered(p: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> bool:
    """Is p inside one of the quadrilaterals between consecutive sections (lower_j, lower_j+1, upper_j+1,
    upper_j)?  Each is convex (a section turns by far less than a right angle over a spacing)."""
    quad = (lower[:-1], lower[1:], upper[1:], upper[:-1])
    signs = []
    for a, b in zip(quad, quad[1:] + quad[:1]):
        e, r = b - a, p - a
        signs.append(e[:, 0] * r[:, 1] - e[:, 1] * r[:, 0])
    s = np.array(signs)
    return bool(np.any(np.all(s >= 0.0, axis=0) | np.all(s <= 0.0, axis=0)))


__all__ = ["Penetration", "centre_line", "outline", "penetrations", "stations"]
