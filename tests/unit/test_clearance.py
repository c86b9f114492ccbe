"""The beam's body against the obstacles at the start (``flexbeam.model.clearance``, ``simulation.check_start``).

Truths: for a straight beam the body is the rectangle [r_h, r_h + L] x [-c, c] turned by theta, whose distance
from a point and lowest corner under a line are closed forms written out here; for a deflected beam the body's
surface points are those of the compiled point kinematics (``kernels/src/model.c``, an independent implementation
in C), and the static deflection under gravity is the Euler-Bernoulli cantilever's closed form
w(x) = q x^2 (6 L^2 - 4 L x + x^2) / (24 EI).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import flexbeam as fb
from flexbeam.contact.setup import OBSTACLE_PLANE, OBSTACLE_SPHERE, ObstacleGeometry
from flexbeam.errors import ParameterError
from flexbeam.model.clearance import outline, penetrations
from flexbeam.model.joints import JOINTS
from flexbeam.model.joints.revolute import RevoluteJoint
from flexbeam.model.system import BeamSystem
from flexbeam.simulation import START_INSIDE, initial_state


def _rotate(theta: float, p) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([c * p[0] - s * p[1], s * p[0] + c * p[1]])


def _rectangle_penetration(Cb, rh: float, L: float, c: float, r_s: float) -> float:
    """r_s minus the distance from the point Cb (beam frame) to the rectangle [rh, rh + L] x [-c, c]; plus its
    depth inside when it lies inside."""
    x, y = Cb
    dx = max(rh - x, 0.0, x - (rh + L))
    dy = max(abs(y) - c, 0.0)
    if dx == 0.0 and dy == 0.0:
        return r_s + min(x - rh, rh + L - x, c - y, c + y)
    return r_s - math.hypot(dx, dy)


def _straight_system(theta: float, hub_radius: float, frame: str):
    case = fb.load_case(
        "seed-experiment",
        {"hub.radius": hub_radius, "model.frame": frame, "model.modes": 4, "initial.kind": "state"},
    )
    system = BeamSystem.from_case(case)
    return case, system, system.state(theta, 0.0)


@settings(max_examples=60, deadline=None)
@given(
    theta=st.floats(-math.pi, math.pi),
    hub_radius=st.sampled_from([0.0, 0.05]),
    frame=st.sampled_from(["system", "hub"]),
    u=st.floats(-0.1, 1.1),
    v=st.floats(-0.06, 0.06),
    r_s=st.floats(1e-3, 0.05),
)
def test_straight_beam_against_a_sphere_is_the_rectangle_closed_form(theta, hub_radius, frame, u, v, r_s):
    """Depth = r_s - dist(C, rectangle) (+ depth of C inside); the body is sampled at sections joined by straight
    edges, exact for a straight beam: only round-off, ~1e-16 m of coordinates ~1 m (bound 1e-12 m)."""
    case, system, y = _straight_system(theta, hub_radius, frame)
    L, c = case.beam.length, case.beam.surface_offset
    Cb = np.array([hub_radius + u * L, v])
    sphere = ObstacleGeometry(OBSTACLE_SPHERE, _rotate(theta, Cb), r_s, np.zeros(2))
    th, _, q, _ = system.split(0.0, y)
    (p,) = penetrations(system.beam, c, th, q, (sphere,))
    assert p.depth == pytest.approx(_rectangle_penetration(Cb, hub_radius, L, c, r_s), abs=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    theta=st.floats(-math.pi, math.pi),
    phi=st.floats(-math.pi, math.pi),
    h=st.floats(-0.8, 0.8),
)
def test_straight_beam_against_a_half_plane_is_its_lowest_corner(theta, phi, h):
    """Depth = -min over the rectangle's four corners of n . (corner - P0) (to round-off, bound 1e-12 m)."""
    case, system, y = _straight_system(theta, 0.0, "system")
    L, c = case.beam.length, case.beam.surface_offset
    n = np.array([math.cos(phi), math.sin(phi)])
    P0 = h * n
    plane = ObstacleGeometry(OBSTACLE_PLANE, P0, 0.0, n)
    corners = [_rotate(theta, (x, yy)) for x in (0.0, L) for yy in (-c, c)]
    expected = -min(float(n @ (k - P0)) for k in corners)
    th, _, q, _ = system.split(0.0, y)
    (p,) = penetrations(system.beam, c, th, q, (plane,))
    assert p.depth == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize(
    "frame, coupling", [("system", "first-order"), ("hub", "first-order"), ("hub", "zeroth-order")]
)
def test_deflected_surface_is_where_the_compiled_kinematics_put_it(frame, coupling):
    """The body's lower surface at x_P and centre line at the tip equal the compiled kinematics' points P (side
    below) and tip at a bent state (tip displaced ~5 mm): the coupling deformation u_x = -1/2 q^T H q by this
    module's cumulative Gauss quadrature against the kernels' H(x).  Both are quadratures of smooth integrands to
    round-off (measured 3e-17 m; bound 1e-12 m)."""
    case = fb.load_case(
        "seed-experiment",
        {"model.frame": frame, "model.coupling": coupling, "model.modes": 6, "contact.position": 0.35,
         "hub.radius": 0.03, "initial.kind": "state"},
    )  # fmt: skip
    system = BeamSystem.from_case(case)
    q = 2e-3 / np.arange(1, 7) ** 2 * np.array([1, -1, 1, 1, -1, 1])
    y = system.state(0.3, 0.0, q)
    x, lower, upper = outline(system.beam, case.beam.surface_offset, 0.3, q)
    j = int(np.argmin(abs(x - 0.35)))
    assert abs(x[j] - 0.35) < 1e-15
    P = system.point_state(0.0, y, 0)[0]
    tip = system.point_state(0.0, y, 1)[0]
    np.testing.assert_allclose(lower[j], P, rtol=0, atol=1e-12)
    np.testing.assert_allclose(0.5 * (lower[-1] + upper[-1]), tip, rtol=0, atol=1e-12)
    assert np.linalg.norm(tip - _rotate(0.3, (0.03 + 0.7, 0.0))) > 3e-3  # really bent (4.8 - 4.9 mm)


def test_released_beam_is_checked_in_its_statically_deflected_shape():
    """Released from rest at 0.1 rad, the beam sags under gravity; a sphere touching the *straight* beam's lower
    surface at x = 0.5 m is then penetrated by the static deflection there, w(0.5) = mu g cos(0.1) x^2 (6 L^2 - 4 L x
    + x^2) / (24 EI) = 1.39e-4 m.  In the hub frame (clamped-free modes: 12 of them give a uniform load's deflection
    to ~1e-6); the axial load's change of the bending stiffness (mu g L^3 sin(0.1) / EI ~ 3e-5) and the turned
    section's second-order geometry (~1e-9 m) remain: measured 3.2e-5 relative, bound 1e-3.  (The system frame's
    pinned-free modes, with the hub held by the constraint theta + d q = angle, converge slowly to a clamped static
    shape: 7 % short at 12 modes, 3 % at 32.)"""
    angle, xs = 0.1, 0.5
    base = fb.load_case(
        "seed-experiment", {"initial.kind": "release", "initial.release_angle": angle, "model.frame": "hub"}
    )
    b, g = base.beam, base.model.gravity
    c, r_s, L = b.surface_offset, 0.01, b.length
    centre = _rotate(angle, (xs, -c - r_s))
    data = base.model_dump(mode="json", exclude_none=True)
    data["obstacles"] = [{"kind": "sphere", "radius": r_s, "centre": centre.tolist()}]
    case = fb.load_case(data)
    system = BeamSystem.from_case(case)
    y = RevoluteJoint.release_state(system, angle)
    th, _, q, _ = system.split(0.0, y)
    p = penetrations(system.beam, c, th, q, system.contact.obstacles)[1]
    w = b.line_density * g * math.cos(angle) * xs**2 * (6 * L**2 - 4 * L * xs + xs**2) / (24 * b.bending_stiffness)
    assert p.depth == pytest.approx(w, rel=1e-3)
    assert p.x == pytest.approx(xs, abs=2e-3) and p.surface == "lower surface"
    with pytest.raises(ParameterError, match=r"^obstacles\[0\]\.centre: the beam starts 0\.000139 m inside"):
        initial_state(system, case)


def test_a_contact_that_starts_exactly_closed_passes():
    """The impact kind places the seed's sphere touching P (gap 0); a second sphere touching the upper surface at
    the same x (gap 0) passes too; 1e-6 m deeper it is refused with that depth (the contact point's own check)."""
    base = fb.load_case("seed-experiment")
    c, r_s = base.beam.surface_offset, 0.01
    data = base.model_dump(mode="json", exclude_none=True)
    for dy, ok in ((0.0, True), (-1e-6, False)):
        data["obstacles"] = [
            {"kind": "sphere", "radius": r_s, "centre": [0.585, c + r_s + dy], "contact": {"side": "above"}}
        ]
        case = fb.load_case(data)
        system = BeamSystem.from_case(case)
        if ok:
            y, _ = initial_state(system, case)
            th, _, q, _ = system.split(0.0, y)
            depths = [p.depth for p in penetrations(system.beam, c, th, q, system.contact.obstacles)]
            assert max(depths) <= START_INSIDE
        else:
            with pytest.raises(ParameterError, match=r"obstacles\[0\]\.centre: the beam starts 1e-06 m inside"):
                initial_state(system, case)


def test_a_sphere_inside_the_beam_is_refused_whatever_its_contact_point():
    """The issue's case: the upper stop of two-stops moved onto the centre line (its contact point, on the upper
    surface, is outside it): depth r_s + c = 0.0245 m, for a fixed contact point and for contact anywhere, and by
    the FE reference too (refused before it starts)."""
    for anywhere in (False, True):
        case = fb.load_case("two-stops", {"obstacles[0].centre": [0.585, 0.0], "contact.anywhere": anywhere})
        with pytest.raises(ParameterError, match=r"^obstacles\[0\]\.centre: the beam starts 0\.0245 m inside"):
            fb.simulate(case)
    with pytest.raises(ParameterError, match=r"^obstacle\.centre: the beam starts 0\.0245 m inside"):
        fb.simulate(fb.load_case("seed-experiment", {"obstacle.centre": [0.585, 0.0]}), "fem")


@pytest.mark.parametrize("name", list(fb.parameters.builtin_cases()))
def test_every_preset_starts_clear_and_runs(name):
    """Each built-in case passes the start checks and runs (1 ms) to completion with every method of the modal
    model."""
    case = fb.load_case(name, {"solver.t_end": 1e-3})
    for method in ("ccfm", "ccm", "imm"):
        # a method the joint kind refuses; IMM on rod-end's rod accumulates impacts (Zeno: docs/formulation.md)
        if method in JOINTS[case.joint.kind].unsupported_methods or (name, method) == ("rod-end", "imm"):
            continue
        sol = fb.simulate(case, method)
        assert sol.status == "success", (name, method, sol.message)
