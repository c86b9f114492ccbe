"""The command-line contract: JSON keys, outputs, case round trip, one-line errors."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

import flexbeam as fb

CONTRACT = [
    "peak_force",
    "peak_time",
    "contact_duration",
    "force_peaks",
    "contacts",
    "post_impact_velocity",
    "energy_drift",
    "wall_time",
    "steps",
]


def flexbeam(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "flexbeam.cli", *args], capture_output=True, text=True, timeout=600)


def test_run_json_has_the_contract_keys(tmp_path):
    r = flexbeam(
        "run",
        "seed-experiment",
        "--json",
        "--set",
        "model.modes=2",
        "--set",
        "solver.t_end=0.002",
        "--out",
        str(tmp_path / "out"),
    )
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    for key in CONTRACT:
        assert key in data
    assert data["contacts"] >= 1 and data["peak_force"] > 0
    assert data["post_impact_velocity"] > 0  # away from the obstacle after the first contact
    for name in ("result.nc", "summary.json", "contact_force.png", "normal_velocity.png"):
        assert (tmp_path / "out" / name).stat().st_size > 0
    import xarray as xr

    with xr.open_dataset(tmp_path / "out" / "result.nc") as ds:
        assert ds["contact_force"].attrs["units"] == "N"
        assert float(ds["contact_force"].max()) == pytest.approx(data["peak_force"], rel=1e-3)


def test_cases_show_round_trips_through_run(tmp_path):
    r = flexbeam("cases", "show", "seed-experiment")
    assert r.returncode == 0
    path = tmp_path / "seed.toml"
    path.write_text(r.stdout)
    assert fb.load_case(path) == fb.load_case("seed-experiment")
    listing = flexbeam("cases")
    assert "seed-experiment" in listing.stdout


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["--set", "beam.lenght=1"], "beam.lenght"),
        (["--set", "beam.length=-1"], "beam.length"),
        (["--set", "contact.position=2"], "contact.position"),
        (["--set", "model.modes=-3"], "model.modes"),
        (["--set", "contact.restitution=2"], "contact.restitution"),
        (["--set", "beam.youngs_modulus=abc"], "beam.youngs_modulus"),
        (["--set", "beam.youngs_modulus=nan"], "beam.youngs_modulus"),
        (["--method", "xyz"], "method"),
    ],
)
def test_bad_input_is_one_line_exit_2(args, field):
    r = flexbeam("run", "seed-experiment", "--json", *args)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and field in lines[0]
    assert "Traceback" not in r.stderr


#: beta_k L of the clamped-free beam, Blevins, Formulas for Natural Frequency and Mode Shape (1979), Table 8-1
CLAMPED_FREE = [1.87510407, 4.69409113, 7.85475744]


def test_frequencies_json_gives_the_clamped_free_beam_and_the_zeroth_order_softening():
    """The hub is held at a steady spin Omega.  At rest both models are the cantilever, omega_k = (beta_k L)^2
    sqrt(EI / (rho A L^4)): the assumed modes are its eigenfunctions, so only quadrature and the table's eighth
    decimal (up to 5.3e-9 relative in omega_1) err; measured 1.4e-9, bound 1e-7.  Spinning at 50 rad/s the
    zeroth-order stiffness K - Omega^2 M with mass-orthonormal modes gives omega_k^2 - Omega^2 exactly (round-off:
    measured 2e-16, bound 1e-12); the first-order model's centrifugal stiffening more than offsets the softening
    (Southwell: omega^2 = omega_0^2 + (K_1 - 1) Omega^2 with K_1 > 1)."""
    b = fb.load_case("seed-experiment").beam
    exact = np.square(CLAMPED_FREE) * math.sqrt(b.bending_stiffness / (b.line_density * b.length**4))
    data = {}
    for spin in (0.0, 50.0):
        r = flexbeam("frequencies", "seed-experiment", "--spin", str(spin), "--modes", "3", "--json")
        assert r.returncode == 0, r.stderr
        data[spin] = json.loads(r.stdout)
        assert data[spin]["spin"] == spin and data[spin]["stable"] == {"first-order": True, "zeroth-order": True}
    rest, spun = data[0.0], data[50.0]
    np.testing.assert_allclose(rest["first-order"], exact, rtol=1e-7)
    np.testing.assert_allclose(rest["zeroth-order"], exact, rtol=1e-7)
    np.testing.assert_allclose(np.square(spun["zeroth-order"]), np.square(rest["zeroth-order"]) - 50.0**2, rtol=1e-12)
    assert np.all(np.array(spun["first-order"]) > np.array(rest["first-order"]))
