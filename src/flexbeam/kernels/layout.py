"""The flat buffers the compiled kernels read (``fb_model_unpack`` / ``fb_basis_unpack`` in ``src/``).

Model buffer (float64; integers stored exactly)::

    [version, n + n_a, joint kind, njp, n_a, npoints, nobstacles, npairs, nmeasure,
     kind_0 .. kind_{nobstacles-1},
     Jc, m1, g, the joint's parameters (njp: flexbeam.model.joints, Joint.parameters),
     Mc (n x n), Mqq (n x n), mtq (n), K (n x n), sf (n), G (n x n), d (n),
     with n_a > 0 (axial modes): M_aa, K_a (their diagonals), m_ta, s_a (n_a each), S (n_a x n),
     per point:    base, offset, phi (n), dphi (n), H (n x n), with n_a > 0: Phi_a (n_a),
     per obstacle: cx, cy, radius, nx, ny, m_s, k_s, c_s, u_x, u_y, ground (1: fixed to the ground, not carried by
                   a moving base),
     per pair:     point, obstacle, anywhere (0 a fixed point, 1 the capsule's nearest point, 2 flat end faces),
     hub radius, nst, surface c, first_order,
     with nst > 0 (contact anywhere): stations x (nst), Psi, Psi', Psi'' (nst x n each), H (nst x n x n),
                   max over the beam of |Psi_k| and |Psi'_k| (n each),
                   with n_a > 0 also Phi_a, Phi_a' (nst x n_a each), max over the beam of |Phi_a,k| (n_a),
     with structural damping: C (n + n_a square, flexbeam.model.damping)]

n counts the bending modes, n_a the axial ones (``model.axial_modes``), whose coordinates p follow q in the
state: the kernels' flexible coordinates are [q, p].

Points: 0 is the first pair's contact point P, 1 the beam tip (centre line), then the measuring points, then the
other pairs' contact points.  Only obstacle 0 may stand on a compliant support.

Contacts buffer (how each pair acts during a phase)::

    [npairs, alpha, beta, per pair: mode, p0, p1, p2, p3]

Control buffer of a phase (:func:`pack_controls`): ``[rtol, atol, max step, omega_rigid, event bits, contacts
buffer]``.

Basis buffer::

    [version, N, nz, diagonal, inv00, omega (N), Psi (N x N), toM (N x N), row0 (nz), with structural damping:
     each mode's 2 zeta omega (N)]
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..contact.setup import ObstacleGeometry
    from ..model.beam import ModalBeam, PointData
    from ..model.stations import StationTable

LAYOUT_VERSION = 4

#: columns of the kernels' ``outputs`` (``FB_NCOLS`` in C), in order
OUTPUT_COLUMNS = (
    "theta", "theta_rate", "gap", "normal_velocity", "contact_force", "contact_energy",
    "kinetic_energy", "elastic_energy", "gravitational_energy", "dissipated_energy", "drive_work",
    "joint_torque", "tip_deflection", "support_displacement", "sensor_force",
)  # fmt: skip
#: columns per contact pair of the kernels' ``outputs`` (``FB_PAIR_COLS`` in C)
PAIR_COLUMNS = ("gap", "normal_velocity", "contact_force", "contact_position")
#: the rules of the switches the compiled stepper takes inside a phase (``coef[0]`` of ``core.advance``,
#: ``kernels/src/switching.c``): CCFM's Coulomb switches (friction_switch.c), CCM's and IMM's contacts on one pair
#: (held_switch.c)
SWITCH_FRICTION, SWITCH_HELD, SWITCH_REBOUND = 1.0, 2.0, 3.0


def pack_model(
    beam: ModalBeam,
    joint: int,
    joint_parameters: Sequence[float],
    gravity: float,
    points: Sequence[PointData],
    obstacles: Sequence[ObstacleGeometry],
    pairs: Sequence[tuple[int, int, int]] = ((0, 0, 0),),
    nmeasure: int | None = None,
    stations: StationTable | None = None,
    damping: np.ndarray | None = None,
) -> np.ndarray:
    """The model buffer of a beam, its joint (its kind's code and parameters), points (P, tip, measuring points,
    other contact points), obstacles and contact pairs (point index, obstacle index, anywhere); ``nmeasure``
    measuring points follow P and the tip (default: every point after them); ``stations``: the shape tables of
    contact anywhere; ``damping``: the structural damping C of the flexible coordinates (appended when given)."""
    na = beam.na
    head = [
        LAYOUT_VERSION,
        beam.nq,
        joint,
        len(joint_parameters),
        na,
        len(points),
        len(obstacles),
        len(pairs),
        len(points) - 2 if nmeasure is None else nmeasure,
        *[o.kind for o in obstacles],
    ]
    scalars = [beam.Jc, beam.m1, gravity, *joint_parameters]
    parts: list[np.ndarray] = [np.asarray(head, float), np.asarray(scalars, float)]
    for arr in (beam.Mc, beam.Mqq, beam.mtq, beam.Kff, beam.sf, beam.G, beam.d):
        parts.append(np.asarray(arr, float).ravel())
    if na:
        ax = beam.axial
        parts += [np.asarray(a, float).ravel() for a in (ax.Maa, ax.Ka, ax.mta, ax.sa, ax.S)]
    for pt in points:
        parts += [np.array([pt.base, pt.offset]), pt.phi.ravel(), pt.dphi.ravel(), pt.H.ravel()]
        if na:
            parts.append(np.asarray(pt.aphi, float).ravel())
    for o in obstacles:
        parts += [
            np.asarray(o.centre, float),
            np.array([o.radius]),
            np.asarray(o.normal, float),
            np.asarray(o.support, float),
            np.array([float(o.ground)]),
        ]
    parts.append(np.asarray(pairs, float).reshape(-1, 3).ravel())
    if stations is None:
        parts.append(np.array([beam.hub_radius, 0.0, 0.0, float(beam.first_order)]))
    else:
        st = stations
        parts += [np.array([beam.hub_radius, st.x.size, st.surface, float(beam.first_order)]), st.x, st.phi.ravel(),
                  st.dphi.ravel(), st.ddphi.ravel(), st.H.ravel(), st.maxphi, st.maxdphi]  # fmt: skip
        if na:
            parts += [st.aphi.ravel(), st.daphi.ravel(), st.maxaphi]
    if damping is not None:
        parts.append(np.asarray(damping, float).ravel())
    return np.ascontiguousarray(np.concatenate(parts))


def pack_contacts(
    modes: Sequence[int], parameters: np.ndarray, alpha: float = 0.0, beta: float = 0.0, friction=None
) -> np.ndarray:
    """The contacts buffer: per pair its :class:`~flexbeam.integrate.phases.ContactMode` and law parameters
    [K, n, chi/d'_0, C] (rows of ``parameters``), and the constraints' Baumgarte alpha, beta; with ``friction``
    (pairs x 5: [sigma, stick, mu_s, v_rest, sign(v_t) of a slip] per pair, some row nonzero) each pair's row carries
    them too."""
    S = len(modes)
    fric = None if friction is None else np.asarray(friction, float).reshape(S, 5)
    width = 5 if fric is None or not np.count_nonzero(fric) else 10  # (count_nonzero: no ufunc reduction)
    out = np.empty(3 + width * S)
    out[:3] = S, alpha, beta
    rows = out[3:].reshape(S, width)
    rows[:, 0] = modes
    rows[:, 1:5] = np.asarray(parameters, float).reshape(S, 4)
    if width == 10:
        rows[:, 5:] = fric
    return out


def pack_controls(
    *, rtol: float, atol: float, max_step: float, omega_rigid: float, event_bits: int, contacts: np.ndarray
) -> np.ndarray:
    """The control buffer of a phase (``fb_ctrl`` in ``src/``): the step control's tolerances and step bound, the
    rigid rotation's frequency scale for the error norm, the events the phase ends on (bits) and the contacts
    buffer of :func:`pack_contacts`."""
    out = np.empty(5 + contacts.size)
    out[:5] = rtol, atol, max_step, omega_rigid, event_bits
    out[5:] = contacts
    return out


def pack_basis(
    omega: np.ndarray, Psi: np.ndarray, toM: np.ndarray, row0: np.ndarray, inv00: float, nz: int, diagonal: bool,
    damp: np.ndarray | None = None,
) -> np.ndarray:  # fmt: skip
    """The basis buffer of a modal basis (see :class:`flexbeam.integrate.modal_basis.ModalBasis`); ``damp``: each mode's
    damping coefficient 2 zeta omega (appended when given)."""
    N = omega.size
    head = np.array([LAYOUT_VERSION, N, nz, int(diagonal), inv00], float)
    parts = [head, omega, Psi.ravel(), toM.ravel(), np.asarray(row0, float)]
    if damp is not None:
        parts.append(np.asarray(damp, float))
    return np.ascontiguousarray(np.concatenate(parts))
