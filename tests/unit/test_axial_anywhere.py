"""Contact anywhere with the axial modes (``model.axial_modes``; ``kernels/src/nearest.c``): the nearest-point
search runs on the stretched centre line rho(x) = (b(x) + Phi_a(x) p - 1/2 q^T H(x) q, Psi(x) q).

* the pair's gap and contact point against a brute-force minimum over the deformed centre line of
  :func:`flexbeam.model.clearance.centre_line` (its own Gauss quadrature of u_x and the axial shapes written by
  :mod:`flexbeam.model.axial`), for a sphere abreast of the beam (the stretch moves the foot of the perpendicular
  along the beam) and a half-plane under an end (the stretch moves the end), on a free beam and a revolute one,
  with hemispherical and flat end caps;
* the gap's Jacobian against finite differences, its axial columns included (envelope theorem: the nearest point is
  held as a material point);
* without the stretch (p = 0) the gap is that of the beam without axial modes, to round-off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy import optimize

import flexbeam as fb
from flexbeam.model.clearance import centre_line
from flexbeam.model.system import BeamSystem

DATA = "tests/validation/data/free-bar-drop.toml"


def free(**over) -> fb.Case:
    return fb.load_case(DATA, overrides={"model.axial_modes": 3, "model.modes": 3, **over})


def revolute(**over) -> fb.Case:
    over = {"model.axial_modes": 3, "model.modes": 3, "contact.anywhere": True, "hub.radius": 0.05, **over}
    return fb.load_case("seed-experiment", overrides=over)


def _state(system: BeamSystem, frame: list[float], q: np.ndarray) -> np.ndarray:
    """y with the frame's coordinates ``frame``, [q, p] = ``q`` and a small random velocity."""
    y = np.zeros(system.size)
    nr = system.nz - system.n
    y[:nr], y[nr : system.nz] = frame, q
    y[system.nz : 2 * system.nz] = np.random.default_rng(7).normal(size=system.nz) * 0.1
    return y


def _world(system: BeamSystem, y: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The deformed centre line at ``x`` (sorted, from 0) in the plane (rows of points)."""
    nr = system.nz - system.n
    origin, theta = (y[:2], y[2]) if nr == 3 else (np.zeros(2), y[0])
    rx, ry, _ = centre_line(system.beam, y[nr : system.nz], x)
    c, s = math.cos(theta), math.sin(theta)
    return np.column_stack((c * rx - s * ry, s * rx + c * ry)) + origin


def brute_force(system: BeamSystem, y: np.ndarray) -> tuple[float, float]:
    """(gap, x) of the capsule (hemispherical caps) nearest the case's obstacle: a grid, then a bounded scalar
    minimisation of the centre line's distance (sphere) or height (half-plane) around the best grid point."""
    ob, c, L = system.contact.obstacles[0], system.case.beam.surface_offset, system.beam.length
    C, sphere = np.asarray(ob.centre, float), system.case.obstacle.kind == "sphere"

    def objective(x: np.ndarray) -> np.ndarray:
        r = _world(system, y, x)
        return np.hypot(*(r - C).T) - ob.radius - c if sphere else (r - C) @ ob.normal - c

    def at(x: float) -> float:
        return float(objective(np.linspace(0.0, x, 801))[-1]) if x > 0.0 else float(objective(np.zeros(1))[0])

    grid = np.linspace(0.0, L, 4001)
    k = int(np.argmin(objective(grid)))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    res = optimize.minimize_scalar(at, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
    ends = [(at(x), x) for x in (lo, hi)]
    return min([(float(res.fun), float(res.x)), *ends])


#: (case, obstacle overrides, frame coordinates): a sphere abreast of the beam's inner part and the floor under an
#: end, for a free bar (G, theta) and a beam on a revolute joint (theta)
SETUPS = {
    "free-sphere": (free, {"obstacle.kind": "sphere", "obstacle.centre": [0.02, -0.02], "obstacle.radius": 0.01},
                    [0.0, 0.0, 0.15]),
    "free-floor": (free, {}, [0.0, 0.03, 0.3]),
    "free-floor-flat": (free, {"beam.end_caps": "flat"}, [0.0, 0.03, 0.3]),
    "revolute-sphere": (revolute, {}, [0.0]),
}  # fmt: skip


def _system(name: str, axial: bool = True) -> tuple[BeamSystem, np.ndarray]:
    make, over, frame = SETUPS[name]
    system = BeamSystem.from_case(make(**{**over, "model.axial_modes": 3 if axial else 0}))
    L = system.beam.length
    q = np.array([2e-4, -1e-4, 5e-5]) * L
    if axial:  # a stretch of the order of 1e-3 L: p_1 Phi_a,1 alone moves an end by 1.4e-3 L
        q = np.concatenate((q, np.array([1e-3, -4e-4, 2.5e-4]) * L))
    return system, _state(system, frame, q)


@pytest.mark.parametrize(("name", "moves"), [("free-sphere", "x"), ("free-floor", "gap"), ("revolute-sphere", "x")])
def test_the_gap_is_the_stretched_capsules_brute_force_minimum(name, moves):
    """The pair's gap and contact point are the brute-force minimum's over the stretched centre line (measured: the
    gap to 5e-12 m, the point to 3e-11 m); without the stretch the search would be off by ~1e-4 m: along the beam
    for a sphere abreast of it (its gap changes at second order only), in the gap for the floor under an end."""
    system, y = _system(name)
    gap, x = brute_force(system, y)
    assert_allclose(system.gap(0.0, y)[0], gap, rtol=0, atol=1e-10)
    assert_allclose(system.contact_coordinate(0.0, y), x, rtol=0, atol=1e-9)
    y0 = y.copy()
    y0[system.nz - 3 : system.nz] = 0.0
    off = system.contact_coordinate(0.0, y0) - x if moves == "x" else system.gap(0.0, y0)[0] - gap
    assert abs(off) > 5e-5


def test_flat_end_faces_strike_with_the_stretched_ends_corner():
    """beam.end_caps = "flat": the bar's lower corner at its stretched end x = 0 is the point nearest the floor: the
    gap is the corner's height, rho(0) turned by theta less c n(0), the end displaced by Phi_a(0) p along the axis."""
    system, y = _system("free-floor-flat")
    b, c = system.beam, system.case.beam.surface_offset
    rx, ry, a = centre_line(b, y[3 : system.nz], np.zeros(1))
    theta = y[2]
    corner = np.array([rx[0] + c * math.sin(a[0]), ry[0] - c * math.cos(a[0])])  # below the centre line
    other = np.array([rx[0] - c * math.sin(a[0]), ry[0] + c * math.cos(a[0])])
    height = min(y[1] + math.sin(theta) * p[0] + math.cos(theta) * p[1] for p in (corner, other))
    assert system.contact_coordinate(0.0, y) == 0.0
    assert_allclose(system.gap(0.0, y)[0], height, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", list(SETUPS))
def test_the_gaps_jacobian_matches_finite_differences(name):
    """J = d delta / dz, every column (the axial ones n . A(theta) (Phi_a,k(x*), 0)), against central differences of
    the gap, the nearest point searched anew at each."""
    system, y = _system(name)
    J = system.gap(0.0, y)[3]
    h = 1e-7
    for i in range(system.nz):
        dy = np.zeros_like(y)
        dy[i] = h
        fd = (system.gap(0.0, y + dy)[0] - system.gap(0.0, y - dy)[0]) / (2 * h)
        assert_allclose(J[i], fd, rtol=1e-6, atol=1e-8)
    if "floor" in name:  # the end pushed at 0.3 rad to its axis: Phi_a,k(0) sin(0.3) = 0.42
        assert np.abs(J[system.nz - 3 : system.nz]).max() > 0.4


@pytest.mark.parametrize("name", list(SETUPS))
def test_without_stretch_the_gap_is_the_inextensible_beams(name):
    """p = 0: the gap, its rate's bending part and the contact point are those of the same beam without axial modes
    (the stations differ in number only with more axial than bending modes)."""
    system, y = _system(name)
    plain, y0 = _system(name, axial=False)
    nz, nz0 = system.nz, plain.nz
    y[nz - 3 : nz] = 0.0
    y[2 * nz - 3 : 2 * nz] = 0.0
    y0[:nz0], y0[nz0 : 2 * nz0] = y[: nz - 3], y[nz : 2 * nz - 3]
    assert_allclose(system.gap(0.0, y)[:2], plain.gap(0.0, y0)[:2], rtol=1e-14, atol=1e-17)
    assert_allclose(system.contact_coordinate(0.0, y), plain.contact_coordinate(0.0, y0), rtol=0, atol=1e-15)
