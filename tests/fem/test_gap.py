"""The FE reference's own gap geometry against closed forms, at random configurations (Hypothesis).

* sphere: the gap is the signed distance of P to the circle, checked against the explicit
  |r - c| - R and against the smallest distance to points of the circle found by a search
  over its angle (:func:`scipy.optimize.minimize_scalar`); half-plane: n . (r - c) and the
  foot of the perpendicular lying on the line;
* the Jacobian d delta/d(X, Y, psi) of the node against central differences;
* delta' and delta'' against differences of delta along a trajectory with constant
  acceleration of the node (this checks the curvature term of the sphere and the surface
  offset's velocity products);
* the obstacle read from the case touches P in the impact configuration.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.optimize import minimize_scalar

from flexbeam.fem import FemBeam
from flexbeam.fem.gap import HALF_PLANE, SPHERE, gap_at, obstacle_gap
from tests.fem.cases import seed

coord = st.floats(-2.0, 2.0)
angle = st.floats(-math.pi, math.pi)
rate = st.floats(-3.0, 3.0)
radius = st.floats(0.0, 1.0)
offset = st.floats(0.0, 0.05)


@settings(max_examples=80, deadline=None)
@given(r=st.tuples(coord, coord), c=st.tuples(coord, coord), R=radius)
def test_sphere_gap_is_the_signed_distance_to_the_circle(r, c, R):
    r, c = np.array(r), np.array(c)
    dist = float(np.linalg.norm(r - c))
    if dist < 1e-3:  # the normal is undefined at the centre
        return
    zero = np.zeros(2)
    delta, rate_, acc, nx, ny = obstacle_gap(r, zero, zero, SPHERE, c, R, zero)
    # explicit formula: round-off of a norm and a difference (measured 0); tolerance 1e-13
    assert_allclose(delta, dist - R, atol=1e-13)
    assert_allclose([nx, ny], (r - c) / dist, atol=1e-13)
    assert rate_ == 0.0 and acc == 0.0
    # geometric definition: the nearest point of the circle (bounded search around the sampled minimum, on the
    # squared distance, which is smooth there; the search on the distance itself stalls at an angle error
    # ~sqrt(eps) when P nearly touches the circle, its kink: 8.5e-12 found by Hypothesis at a 3e-5 gap).  The
    # distance is stationary at the minimum, so its error is round-off: measured <= 4e-15, tolerance 1e-12)
    phis = np.linspace(-math.pi, math.pi, 721)
    pts = c + R * np.stack((np.cos(phis), np.sin(phis)), axis=1)
    k = int(np.argmin(np.linalg.norm(pts - r, axis=1)))
    res = minimize_scalar(
        lambda p: float(np.sum((r - c - R * np.array([math.cos(p), math.sin(p)])) ** 2)),
        bounds=(phis[k] - 0.01, phis[k] + 0.01),
        method="bounded",
        options={"xatol": 1e-10},
    )
    assert_allclose(abs(delta), math.sqrt(res.fun), atol=1e-12)
    assert (delta > 0.0) == (dist > R)


@settings(max_examples=60, deadline=None)
@given(r=st.tuples(coord, coord), c=st.tuples(coord, coord), phi=angle)
def test_half_plane_gap_is_the_signed_distance_to_the_line(r, c, phi):
    r, c = np.array(r), np.array(c)
    n = np.array([math.cos(phi), math.sin(phi)])
    zero = np.zeros(2)
    delta, _, _, nx, ny = obstacle_gap(r, zero, zero, HALF_PLANE, c, 0.0, n)
    assert_allclose(delta, n @ (r - c), atol=1e-13)
    foot = r - delta * n  # lies on the line through c along t = (-n_y, n_x) (measured 1.3e-15; tolerance 1e-12)
    t = np.array([-n[1], n[0]])
    assert_allclose(foot, c + (t @ (foot - c)) * t, atol=1e-12)
    assert (nx, ny) == (n[0], n[1])


def _node_gap(kind, x, v, a, c_off, centre, R, normal):
    J = np.empty(3)
    d, dv, da = gap_at(
        np.asarray(x, float), np.asarray(v, float), np.asarray(a, float), c_off, kind, centre, R, normal, J
    )
    return d, dv, da, J


obstacle = st.one_of(
    st.tuples(st.just(SPHERE), st.tuples(coord, coord), st.floats(0.05, 1.0), st.just(0.0)),
    st.tuples(st.just(HALF_PLANE), st.tuples(coord, coord), st.just(0.0), angle),
)


@settings(max_examples=80, deadline=None)
@given(
    ob=obstacle,
    x=st.tuples(coord, coord, angle),
    v=st.tuples(rate, rate, rate),
    a=st.tuples(rate, rate, rate),
    c_off=offset,
)
def test_jacobian_and_rates_are_derivatives_of_the_gap(ob, x, v, a, c_off):
    """J by central differences (step 1e-6; measured <= 8.4e-10 over 5000 random draws, tolerance
    1e-7), and delta', delta'' by differences of delta along X(t) = X + V t + A t^2/2 (step 1e-4;
    relative to s = 1 + (|V| + |A|)^2, measured <= 1.9e-8 and 7.9e-7, tolerances 1e-6 and 1e-5 --
    margins 50 and 12; leaving out the sphere's curvature term or the offset's velocity
    products gives errors of order s)."""
    kind, centre, R, phi = ob
    centre = np.array(centre)
    normal = np.array([math.cos(phi), math.sin(phi)]) if kind == HALF_PLANE else np.zeros(2)
    x, v, a = np.array(x), np.array(v), np.array(a)
    # P: the node's point at c_off below the centre line
    p = x[:2] + c_off * np.array([math.sin(x[2]), -math.cos(x[2])])
    if kind == SPHERE and np.linalg.norm(p - centre) < 0.05:
        return  # near the centre the gap's curvature is unbounded
    d, dv, da, J = _node_gap(kind, x, v, a, c_off, centre, R, normal)
    h = 1e-6
    num = np.empty(3)
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        num[k] = (
            _node_gap(kind, x + e, v, a, c_off, centre, R, normal)[0]
            - _node_gap(kind, x - e, v, a, c_off, centre, R, normal)[0]
        ) / (2 * h)
    assert_allclose(J, num, atol=1e-7)
    assert_allclose(dv, J @ v, atol=1e-12)

    def along(t):
        return _node_gap(kind, x + v * t + 0.5 * a * t * t, v, a, c_off, centre, R, normal)[0]

    ht = 1e-4
    scale = 1.0 + float(np.abs(v).sum() + np.abs(a).sum()) ** 2
    assert_allclose(dv, (along(ht) - along(-ht)) / (2 * ht), atol=1e-6 * scale)
    assert_allclose(da, (along(ht) - 2 * d + along(-ht)) / ht**2, atol=1e-5 * scale)


@settings(max_examples=15, deadline=None)
@given(theta=st.floats(-0.5, 0.5), x_p=st.floats(0.2, 0.7), kind=st.sampled_from(["sphere", "half-plane"]))
def test_obstacle_from_the_case_touches_p_in_the_impact_configuration(theta, x_p, kind):
    """Without obstacle.centre the case puts the obstacle against P on the straight beam at the
    impact angle, with its normal along the beam normal e2 (round-off only: tolerance 1e-12 m)."""
    extra = {"contact__stiffness": 1e9} if kind == "half-plane" else {}
    beam = FemBeam.from_case(
        seed(initial__impact_angle=theta, contact__position=x_p, obstacle__kind=kind, fem__elements=6, **extra)
    )
    z, zd = beam.straight(theta, 0.0)
    delta, _, _, J = beam.gap(z, zd)
    assert abs(delta) < 1e-12
    assert_allclose(J[:2], [-math.sin(theta), math.cos(theta)], atol=1e-12)
