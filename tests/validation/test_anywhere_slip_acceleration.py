"""The slip velocity's rate gamma_t of a contact found anywhere: the contact point's, which moves along the beam.

For a pair with ``contact.anywhere`` the slip velocity is that of the surface's material point at the nearest point:
v_t(q, q') = T(x*(q), off*(q); q, q'), T = t . w (w the point's velocity relative to the obstacle, t its gap's tangent),
off* the point's offsets from the centre line across the section.  So v_t' = J_t z'' + [the material point's rate]
+ T_x x*' + T_off off*'; ``kernels/src/anywhere_gamma.c`` adds the last two (derivation in its header): the contact
point moves along the beam, and over the section where the centre line's tangent is not the section's, or around
an end cap.  A sticking pair is held at v_t(q, q') = 0 -- the bodies' coincident points at the current contact
point do not slide (Pfeiffer & Glocker 1996, Ch. 4-5) -- the function the collocation holds at its nodes; its
acceleration-level row in the RHS (rhs.c: the sampled forces of CCM's held pairs, the check that a held pair
leaves) needs the whole rate.

**gamma_t against the true slip velocity's difference.**  Along the path z(t) = z0 + t z0' (z'' = 0) the slip
velocity's rate is gamma_t itself; the central difference (v_t(h) - v_t(-h)) / (2 h) of the kernel's slip velocity
at the nearest point (found anew at each state) is independent of gamma_t.  Its truncation error h^2 v_t''' / 6 is
estimated from the steps 2h and h (their difference is 3 times it), its round-off by eps |v| / h; the tolerance is
10 times their sum (h = 1e-4 s as in ``test_anywhere_gap_acceleration.py``).  The free bar of ``free-bar-drop.toml``
bent by its first mode, spinning, sliding and falling, with and without axial modes, over its half-plane and over a
sphere, the nearest point inside the beam and on an end cap.  The terms are 0.2-2.8 m/s^2 here (the former build,
the material point's rate, was off by as much); measured errors: the truncation's size on the half-plane, 1.6e-6 of a
tolerance of 3e-5 over the sphere (1.2e-6 m/s^2 remain as h -> 0: the stencils along the beam, 1e-6 relative).

**The stick row keeps the true slip at zero.**  The same bent bar, its contact point brought onto the half-plane
with zero relative velocity and held there sticking (CCM's CONSTRAINT with a stick row, Baumgarte's terms off): the
RHS's accelerations z'' make v_t' = J_t z'' + gamma_t(code) = 0, so the slip velocity along the path
z0 + t z0' + t^2 z0'' / 2 must have a zero rate -- checked by the central difference as above, with a step of 1e-9 s
(the stiff modes' accelerations; measured 9e-5 m/s^2 against a tolerance of 9e-4; the former build's rate, the
material point's, leaves -0.227 m/s^2).

Not covered: a flat end face (``beam.end_caps = "flat"``: its corner's motion) keeps the material point's rate.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.kernels import pack_contacts
from flexbeam.model.system import BeamSystem

sys.path.insert(0, str(Path(__file__).parent))
from test_anywhere_gap_acceleration import DATA, SPHERE, bent_spinning_state  # noqa: E402

H = 1e-4  # [s] the difference's step along z'' = 0
#: [s] the step along the stick's z'': the bent bar's stiff modes accelerate at ~1e6 m/s^2 out of equilibrium, so the
#: slip velocity's third derivative is ~1e14 m/s^4 and only a step this short keeps the truncation below 1e-4 m/s^2
H_STICK = 1e-9


def bar(axial: int, sag: float, obstacle: dict | None = None, inside: bool = True
        ) -> tuple[BeamSystem, np.ndarray, int]:  # fmt: skip
    """The free bar over its half-plane (or ``obstacle``) with ``axial`` axial modes, in the bent, spinning, sliding
    state, its nearest point ``inside`` the beam or on an end cap."""
    case = fb.load_case(DATA, {"model.axial_modes": axial, **(obstacle or {})})
    system = BeamSystem.from_case(case)
    nz = system.nfull  # the free joint gives no coordinate
    y0 = bent_spinning_state(nz, 2 * nz + 2, sag)
    if not axial:
        y0[11] = 0.0
    x = system.contact_coordinate(0.0, y0)
    assert (0.0 < x < case.beam.length) if inside else x in (0.0, case.beam.length)  # the case is the one named
    return system, y0, nz


def path(y0: np.ndarray, nz: int, acc: np.ndarray, t: float) -> np.ndarray:
    """The state at time t on the path z = z0 + t z0' + t^2 acc / 2, z' = z0' + t acc."""
    y = y0.copy()
    y[:nz] = y0[:nz] + t * y0[nz : 2 * nz] + 0.5 * t * t * acc
    y[nz : 2 * nz] = y0[nz : 2 * nz] + t * acc
    return y


def slip_rate_by_difference(system: BeamSystem, y0: np.ndarray, nz: int, acc: np.ndarray, h: float = H
                            ) -> tuple[float, float]:  # fmt: skip
    """The slip velocity's rate along the path by the central difference with step h, and its tolerance: 10 x
    (truncation, from the steps 2h and h, + round-off eps |v| / h, |v| the largest rate)."""

    def diff(h: float) -> float:
        vm, vp = (system.tangent(t, path(y0, nz, acc, t))[2] for t in (-h, h))
        return (vp - vm) / (2.0 * h)

    fd, fd2 = diff(h), diff(2.0 * h)
    speed = float(np.max(np.abs(y0[nz : 2 * nz])))
    return fd, 10.0 * (abs(fd2 - fd) / 3.0 + np.finfo(float).eps * speed / h)


#: (axial modes, sag, obstacle, nearest point inside): the half-plane's and the sphere's, inside and on a cap
CASES = {
    "half-plane": (4, 2e-3, None, True),
    "half-plane-bent": (4, 5e-3, None, True),
    "half-plane-no-axial": (0, 2e-3, None, True),
    "sphere": (4, 2e-3, SPHERE, True),
    "sphere-off-centre": (4, 2e-3, {**SPHERE, "obstacle.centre": [0.05, -0.03]}, True),
    "sphere-no-axial": (0, 2e-3, {**SPHERE, "obstacle.centre": [0.05, -0.03]}, True),
    "sphere-end-cap": (4, -2e-3, SPHERE, False),
}


@pytest.mark.parametrize("name", list(CASES))
def test_gamma_t_is_the_true_slip_velocitys_rate_at_zero_acceleration(name):
    """gamma_t = v_t' along z'' = 0 (the difference of the kernel's slip velocity at the nearest point)."""
    system, y0, nz = bar(*CASES[name])
    gamma_t = system.slip_acceleration(0.0, y0)
    fd, tol = slip_rate_by_difference(system, y0, nz, np.zeros(nz))
    assert abs(fd - gamma_t) <= tol, (fd, gamma_t, tol)


def test_the_stick_rows_accelerations_keep_the_contact_points_slip_at_zero():
    """The bent bar sticking on its half-plane: the RHS's z'' gives the slip velocity a zero rate (as above)."""
    system, y0, nz = bar(4, 2e-3)
    delta, rate, vt, J, Jt = system.tangent(0.0, y0)
    n, t = J[:2], Jt[:2]  # the free joint's first coordinates are G's: d delta / d r_G = n, d v_t / d v_G = t
    y0[:2] -= delta * n  # onto the half-plane,
    y0[nz : nz + 2] -= rate * n + vt * t  # its contact point at rest relative to it
    delta, rate, vt, _, _ = system.tangent(0.0, y0)
    assert abs(delta) < 1e-12 and abs(rate) < 1e-12 and abs(vt) < 1e-12
    held = pack_contacts([2], np.zeros((1, 4)), 0.0, 0.0, friction=np.array([[0.0, 1.0, 1.0, 0.0, 0.0]]))
    acc = system.rhs(0.0, y0, held)[0][nz : 2 * nz]
    fd, tol = slip_rate_by_difference(system, y0, nz, acc, H_STICK)
    assert abs(fd) <= tol, (fd, tol)
