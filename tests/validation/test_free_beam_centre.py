"""A free beam's centre of mass G in the outputs: ``centre_of_mass`` and ``centre_of_mass_velocity`` (time x axis).

In free flight G moves as a particle under gravity whatever the beam's spin and vibration (the free-free modes are
orthogonal to the rigid translation, and gravity acts on y_G alone: docs/free-beam.md), so it follows the parabola
r_G(t) = r_0 + v_0 t - g t^2 e_y / 2 -- a closed form the modal model and the finite-element reference (whose G is
the mass-weighted mean of its nodes' motion, flexbeam.fem.free) must both reproduce.
"""

from __future__ import annotations

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.validation.bars import STEEL_BAR

G, R0, V0 = 9.81, (0.1, 0.5), (0.3, 1.2)


def tumbling_bar(modal_velocity: list[float] | None = None, t_end: float = 0.2, lift: float = 0.0) -> fb.Case:
    """The steel bar (8 modes) thrown from G = R0 (``lift`` [m] higher) at V0, at 0.4 rad turning at 5 rad/s, high
    above a floor it never reaches by ``t_end``."""
    initial = {"kind": "state", "position": [R0[0], R0[1] + lift], "velocity": list(V0), "angle": 0.4, "rate": 5.0}
    if modal_velocity is not None:
        initial["modal_velocity"] = modal_velocity
    return fb.load_case({
        "name": "tumbling-bar", "beam": dict(STEEL_BAR), "joint": {"kind": "free"},
        "model": {"modes": 8, "gravity": G},
        "obstacle": {"kind": "half-plane", "centre": [0.0, -10.0], "normal": [0.0, 1.0]},
        "contact": {"law": "hertz", "position": 0.0, "stiffness": 1.16e10, "side": "centre", "anywhere": True},
        "initial": initial,
        "solver": {"t_end": t_end},
    })  # fmt: skip


@pytest.mark.parametrize(
    ("method", "vibrating", "t_end", "tol"),
    [("ccfm", True, 0.2, 1e-12), ("imm", False, 0.2, 1e-12), ("fem", False, 0.02, 1e-10)],
)
def test_g_follows_the_parabola_of_free_flight(method, vibrating, t_end, tol):
    """G's position and velocity at every sample against the parabola: the modal model within 1e-12 m and m/s
    (its G is the coordinates x_G, y_G, forced by the constant -m g: measured 5e-15, round-off), vibrating (three
    modes started moving) or not; the finite-element reference (a straight bar: it starts undeformed; 0.02 s) within
    1e-10 (measured 5e-13 and 7e-12 over 0.2 s, 1.7e5 samples: generalised-alpha's round-off)."""
    case = tumbling_bar([0.5, -0.3, 0.2, 0.0, 0.0, 0.0, 0.0, 0.0] if vibrating else None, t_end)
    sol = fb.simulate(case, method)
    assert sol.status == "success", sol.message
    t = sol.time
    r = np.column_stack((R0[0] + V0[0] * t, R0[1] + V0[1] * t - 0.5 * G * t**2))
    v = np.column_stack((np.full(t.size, V0[0]), V0[1] - G * t))
    assert sol["centre_of_mass"].shape == (t.size, 2)
    np.testing.assert_allclose(sol["centre_of_mass"], r, rtol=0.0, atol=tol)
    np.testing.assert_allclose(sol["centre_of_mass_velocity"], v, rtol=0.0, atol=tol)
    if vibrating:  # the beam does ring: G's motion is not that of a rigid bar by construction
        assert np.max(np.abs(sol["tip_deflection"])) > 1e-5


@pytest.mark.parametrize("lift", [1e4, 1e12, 1e300])
def test_the_tip_deflection_does_not_depend_on_where_the_beam_flies(lift):
    """The tip's deflection is measured in the beam's frame (e2(phi) . A(theta) rho, never as the difference of two
    positions in the plane), and nothing in the beam's deformation and spin depends on where G is: the same vibrating
    throw ``lift`` metres higher gives the same deflection at every sample and the same extremes, within the
    integrator's tolerance: the step control weighs G's coordinates relative to their size, so the steps differ (128
    near the origin, 112 at 1e8 m and beyond) and the deflections by up to 5.7e-6 of their size (measured; fast_rtol
    1e-6); bound 1e-4 of it.  Formed as r_tip - r_G it lost the digits of |r_G|: 41 % at 1e12 m, and at 1e300 m a
    false large-deflection warning (0.25 beam.length)."""
    modal_velocity = [0.5, -0.3, 0.2, 0.0, 0.0, 0.0, 0.0, 0.0]
    near = fb.simulate(tumbling_bar(modal_velocity, 0.05), "ccfm")
    far = fb.simulate(tumbling_bar(modal_velocity, 0.05, lift), "ccfm")
    assert near.status == far.status == "success", far.message
    scale = np.max(np.abs(near["tip_deflection"]))
    assert scale > 1e-5  # it rings
    np.testing.assert_allclose(far["tip_deflection"], near["tip_deflection"], rtol=0.0, atol=1e-4 * scale)
    for name in ("tip_deflection_min", "tip_deflection_max"):
        assert abs(far.metrics()[name] - near.metrics()[name]) <= 1e-4 * scale


def test_the_dataset_and_file_hold_g_along_axis(tmp_path):
    """``centre_of_mass`` and its velocity have dims (time, axis), axis = [x, y], units m and m/s, and read back from
    result.nc as written (stored exactly, as theta: a rigid coordinate whose value has no scale); a beam on a
    revolute joint has neither variable nor the axis; theta is named the mean axis's angle (a joint's: the hub's)."""
    sol = fb.simulate(tumbling_bar(), "ccfm")
    ds = sol.to_xarray()
    assert ds["centre_of_mass"].dims == ("time", "axis") and list(ds["axis"].values) == ["x", "y"]
    assert ds["centre_of_mass"].attrs["units"] == "m" and ds["centre_of_mass_velocity"].attrs["units"] == "m/s"
    assert ds["theta"].attrs["long_name"] == "Angle of the free beam's mean axis"
    import xarray as xr

    with xr.open_dataset(sol.to_netcdf(tmp_path / "result.nc")) as back:
        for name in ("centre_of_mass", "centre_of_mass_velocity"):
            np.testing.assert_array_equal(back[name].values, sol[name])
    seed = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 0.01}), "ccfm").to_xarray()
    assert "centre_of_mass" not in seed and "axis" not in seed.coords
    assert seed["theta"].attrs["long_name"] == "Hub angle"
