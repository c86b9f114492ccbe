"""The geometry of an animation: what a frame shows and when.

The beam's centre line at a time from the modal coordinates q and the hub angle phi (:func:`beam_shape`, with the
coupling matrices H(x) of :func:`coupling_matrices`, the kinematics of ``docs/formulation.md``); the rigid
reference line its deflection is measured from (:func:`reference_angle`) and the magnification that deflection is
drawn with (:func:`auto_scale`); and the times of the frames, denser inside the contacts (:func:`frame_times`).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ...errors import ParameterError

if TYPE_CHECKING:
    from ...model.beam import ModalBeam
    from ...model.system import BeamSystem

#: auto scale: the largest magnified deflection over the frames is this fraction of the beam length, less at
#: most 1/11 of it (the factor is rounded down to two significant digits): 10.9-12 % of L
TARGET_DEFLECTION = 0.12
#: a deflection below this share of the beam's length is round-off, not drawn magnified (:func:`auto_scale`): the
#: deflection is a difference of positions of order L, so its round-off is a few eps L; 1e3 eps is 1000x over that
#: and 6000x under a deflection of 1 nm on a 0.7 m beam
DEFLECTION_ROUNDOFF = 1e3 * sys.float_info.epsilon
#: rigid reference lines the deflection is measured from (see :func:`reference_angle`)
REFERENCES = ("contact", "hub")


# ------------------------------------------------------------------------------------------------ kinematics
def coupling_matrices(beam: ModalBeam, x: np.ndarray) -> np.ndarray:
    """H(x) = H(0) + int_0^x Psi'^T Psi' dxi at each point of ``x``, shape (len(x), n, n), H(0) = r_h d^T d on a
    joint, -H_bar for a free beam (``beam.H_root``: its foreshortening has zero mean, docs/free-beam.md).

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
    root = beam.hub_radius * np.outer(beam.d, beam.d) if beam.H_root is None else beam.H_root
    H[order] = np.cumsum(pieces, axis=0) + root
    return 0.5 * (H + H.transpose(0, 2, 1))


def beam_shape(system: BeamSystem, phi, q, x, origin=None) -> tuple[np.ndarray, np.ndarray]:
    """Global coordinates (X, Y) [m] of the beam's centre line at the material points ``x`` [m].

    r(x) = R + A(theta) rho(x) with rho(x) = (r_h + x - 1/2 q^T H(x) q, Psi(x) q) in the body frame
    (``docs/formulation.md``), A the rotation by the body frame's angle theta = phi - d q (d = Psi'(0); zero in
    the hub frame, where theta is the hub angle phi) and H from :func:`coupling_matrices`; R = O = 0 on a joint, a
    free beam's frame origin (its centre of mass: r_h = -L/2, docs/free-beam.md) given by ``origin``.

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
    origin
        The frame's origin R [m], shape (2,) or (m, 2) (default: O).

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
    if origin is not None:
        R = np.broadcast_to(np.asarray(origin, float).reshape(-1, 2), (phi.size, 2))
        X, Y = X + R[:, 0:1], Y + R[:, 1:2]
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
    below 1: a deflection already that large is drawn at its true size.  A deflection within
    :data:`DEFLECTION_ROUNDOFF` x ``length`` is round-off (a difference of positions of order ``length``), not a
    shape: drawn unmagnified (the rod of ``rod-end``, which does not bend, read 2e-19 m and was drawn bent and tilted
    into the plane at x1.2e17).
    """
    if not deflection > DEFLECTION_ROUNDOFF * length:
        return 1.0
    raw = target * length / deflection
    if raw <= 1.0:
        return 1.0
    unit = 10.0 ** (math.floor(math.log10(raw)) - 1)
    return max(1.0, math.floor(raw / unit * (1 + 1e-12)) * unit)


# -------------------------------------------------------------------------------------- deflection reference
def reference_angle(reference: str, phi: np.ndarray, point: np.ndarray, radius: float, reach: float) -> np.ndarray:
    """Angle alpha [rad] of the rigid reference line from O that the deflection is measured from, per frame.

    ``"hub"``: the hub's radial line, alpha = phi.  ``"contact"``: the line from O through the contact point's
    centre line, alpha = phi + wrap(atan2(Y_P, X_P) - phi) (wrapped to (-pi, pi] about phi, so alpha follows phi
    continuously), so that the magnified beam touches the obstacle where the true one does; the hub's radial line
    when P is within 5 % of the beam's reach of O, where the direction of P is ill-defined.

    Parameters
    ----------
    reference
        One of :data:`REFERENCES`.
    phi
        Hub angles [rad], shape (m,).
    point
        Global coordinates (X, Y) [m] of the centre line at the contact point, shape (m, 2) (:func:`beam_shape`).
    radius
        Undeformed distance of that point from O, r_h + x_P [m].
    reach
        Undeformed distance of the tip from O, r_h + L [m].

    Returns
    -------
    numpy.ndarray
        alpha, shape (m,) (a new array).
    """
    phi = np.asarray(phi, float)
    if reference == "contact" and radius > 0.05 * reach:
        return phi + _wrap(np.arctan2(point[..., 1], point[..., 0]) - phi)
    return phi.copy()


def _wrap(a: np.ndarray) -> np.ndarray:
    """Angle(s) wrapped to (-pi, pi]."""
    return np.pi - np.mod(np.pi - a, 2.0 * np.pi)
