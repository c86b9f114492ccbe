"""NetCDF write/read round trip of a Solution for every impact method and a compliant support.

What ``Solution.to_netcdf`` writes must read back with :func:`xarray.open_dataset` to the
dataset of ``Solution.to_xarray``: every variable and coordinate with equal values (NaN
where NaN) -- the outputs of the integrated state within their documented rounding
(:data:`~flexbeam.results.export.QUANTIZED`, ``quantization_nsb`` significant bits), the rest exactly --, its
units and long_name, the metrics (strict JSON) and the provenance, whose case TOML loads back to the case that ran.
The seed experiment's file is below 3 MB (5.96 MB before the rounding and the column chunks).
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.results.export import QUANTIZATION_INFO, QUANTIZED, bitround, precision_bits, significant_bits
from tests.conftest import seed

SHORT = {"model__modes": 2, "solver__t_end": 0.002}
COMPLIANT = {"obstacle__support__stiffness": 3e7, "obstacle__support__mass": 0.02, "obstacle__support__damping": 50.0}
PROVENANCE = ("flexbeam_version", "case_toml", "method", "integrator")
#: a NetCDF double holds a float64 exactly; 1e-12 is the tolerance rule shared with the CLI's JSON
REL = 1e-12


def strict_json(text: str) -> Any:
    def refuse(name: str) -> Any:
        raise ValueError(f"not strict JSON: {name}")

    return json.loads(text, parse_constant=refuse)


def assert_same_metrics(got: Any, expected: Any, key: str = "") -> None:
    """Parsed metrics equal Solution.metrics(): NaN as null, floats to REL, the rest (lists and the per-pair
    records item by item) exactly."""
    if isinstance(expected, dict):
        assert isinstance(got, dict) and set(got) == set(expected), key
        for k, want in expected.items():
            assert_same_metrics(got[k], want, f"{key}.{k}" if key else k)
    elif isinstance(expected, list):
        assert isinstance(got, list) and len(got) == len(expected), key
        for h, w in zip(got, expected, strict=True):
            assert_same_metrics(h, w, key)
    elif isinstance(expected, float) and math.isnan(expected):
        assert got is None, key
    elif isinstance(expected, float):
        assert math.isclose(got, expected, rel_tol=REL, abs_tol=0.0), (key, got, expected)
    else:
        assert got == expected and type(got) is type(expected), (key, got, expected)


@pytest.mark.parametrize(
    ("method", "overrides"),
    [
        ("ccfm", {}),
        ("ccm", {}),
        ("imm", {}),
        ("fem", {"fem__elements": 8}),
        ("ccfm", COMPLIANT),
        ("ccm", COMPLIANT),  # constrained phases against the moving obstacle (reference integrator)
    ],
    ids=["ccfm", "ccm", "imm", "fem", "ccfm-compliant", "ccm-compliant"],
)
def test_netcdf_round_trip(tmp_path, method, overrides):
    import xarray as xr

    case = seed(**SHORT, **overrides)
    sol = fb.simulate(case, method)
    assert sol.status == "success" and sol.contacts
    expected = sol.to_xarray()
    path = sol.to_netcdf(tmp_path / "result.nc")
    assert [p.name for p in tmp_path.iterdir()] == ["result.nc"]  # no temporary file left behind

    with xr.open_dataset(path) as ds:
        ds.load()
    nsb = precision_bits(sol.provenance)
    assert (nsb is None) == (method == "fem")  # the FE reference's fixed steps give no tolerance
    assert_read_back(ds, expected, nsb)
    assert "sensor_force" in ds if case.obstacle.support.compliant else "sensor_force" not in ds

    assert_same_metrics(strict_json(ds.attrs["metrics"]), sol.metrics())
    for key in PROVENANCE:
        assert ds.attrs[key] == expected.attrs[key] == sol.provenance[key], key
    assert ds.attrs["method"] == method
    for key, value in expected.attrs.items():  # every other attribute too (numbers as numbers)
        assert ds.attrs[key] == value, key

    toml = tmp_path / "case.toml"
    toml.write_text(ds.attrs["case_toml"], encoding="utf-8")
    assert fb.load_case(toml) == case


def assert_read_back(ds, expected, nsb: int | None) -> None:
    """``ds`` (read from a file) holds every variable of ``expected`` (``to_xarray``): the :data:`QUANTIZED` ones
    rounded to ``nsb`` significant bits (a relative change <= 2^-(nsb + 1)), the rest exactly."""
    for name in [*expected.data_vars, *expected.coords]:
        assert name in ds, name
        want, have = expected[name], ds[name]
        assert have.dims == want.dims, name
        if want.dtype.kind in "US":  # strings come back as objects
            np.testing.assert_array_equal(have.values.astype(str), want.values, err_msg=name)
        elif nsb is not None and name in QUANTIZED:
            assert have.dtype == want.dtype == np.float64, name
            assert have.attrs["quantization_nsb"] == nsb and have.attrs["quantization"] == QUANTIZATION_INFO, name
            bound = 2.0 ** -(nsb + 1)
            assert have.attrs["quantization_maximum_relative_error"] == bound
            np.testing.assert_array_equal(have.values, bitround(want.values, nsb), err_msg=name)
            finite = np.isfinite(want.values)
            np.testing.assert_array_equal(finite, np.isfinite(have.values), err_msg=name)
            assert np.all(np.abs(have.values - want.values)[finite] <= bound * np.abs(want.values)[finite]), name
        else:
            assert have.dtype == want.dtype, name
            np.testing.assert_array_equal(have.values, want.values, err_msg=name)  # NaN == NaN here
        for attr in ("units", "long_name"):
            assert have.attrs.get(attr) == want.attrs.get(attr), (name, attr)
    assert set(ds.data_vars) == set(expected.data_vars) | ({QUANTIZATION_INFO} if nsb is not None else set())
    if nsb is not None:
        assert ds[QUANTIZATION_INFO].attrs["algorithm"] == "bitround"


def test_the_seed_experiments_file_is_below_3_mb_with_the_same_content(tmp_path):
    """``flexbeam run seed-experiment --out`` writes this file: 23 571 samples of 43 floats.  Deflated in columns and
    rounded to the compiled integrator's precision (rtol = 1e-6: 23 significant bits) it is 2.7 MB (5.96 MB
    before); every name users read is there, the time, the hub angle, the total energy and the records exactly."""
    import xarray as xr

    sol = fb.simulate("seed-experiment")
    path = sol.to_netcdf(tmp_path / "result.nc")
    size = path.stat().st_size
    assert size < 3e6, size
    with xr.open_dataset(path) as ds:
        ds.load()
    assert precision_bits(sol.provenance) == 23
    assert_read_back(ds, sol.to_xarray(), 23)
    for name in ("time", "theta", "total_energy", "contact_onset", "contact_peak_force"):
        assert "quantization" not in ds[name].attrs, name
    exact = sol.to_netcdf(tmp_path / "exact.nc", quantize=False)  # lossless, on request
    assert exact.stat().st_size > 2 * size
    with xr.open_dataset(exact) as ds:
        assert_read_back(ds.load(), sol.to_xarray(), None)


@pytest.mark.parametrize(("rtol", "nsb"), [(1e-6, 23), (1e-9, 33), (1e-3, 13), (1e-15, None), (0.0, None)])
def test_significant_bits_keep_rounding_below_a_sixteenth_of_the_tolerance(rtol, nsb):
    assert significant_bits(rtol) == nsb
    if nsb is not None:
        assert 2.0 ** -(nsb + 1) <= rtol / 16 < 2.0**-nsb


def test_bitround_rounds_to_nearest_even_and_keeps_what_is_not_finite():
    rng = np.random.default_rng(1)
    x = np.concatenate([rng.normal(size=10000) * 10.0 ** rng.integers(-300, 300, 10000), [0.0, -0.0, 5e-324]])
    for nsb in (1, 10, 23, 33, 51):
        r = bitround(x, nsb)
        assert np.all(np.abs(r - x) <= 2.0 ** -(nsb + 1) * np.maximum(np.abs(x), np.finfo(float).tiny))
        assert np.all((r.view(np.uint64) & np.uint64((1 << (52 - nsb)) - 1)) == 0)  # the dropped bits are zeros
        np.testing.assert_array_equal(bitround(r, nsb), r)  # idempotent
    assert bitround(np.array([1.0 + 2.0**-24]), 23)[0] == 1.0  # a tie goes to the even neighbour
    assert bitround(np.array([1.0 + 3 * 2.0**-24]), 23)[0] == 1.0 + 2.0**-22  # and up to the even one
    special = np.array([np.nan, np.inf, -np.inf, np.finfo(float).max])
    np.testing.assert_array_equal(bitround(special, 10), special)  # the largest double would round past inf


@pytest.mark.parametrize("source", ["seed-experiment", "rod-end"])  # hub + beam modes; free-free and axial modes
def test_modal_coordinates_carry_the_unit_of_a_displacement(source):
    """The mode shapes are dimensionless -- normalised to int phi^2 dx = L, so the modal mass matrix is mu L I [kg]
    -- and w = sum phi_i q_i makes q a length [m] and q' a velocity [m/s] (the file said '1' and '1/s')."""
    from flexbeam.model.beam import build_modal_beam

    case = fb.load_case(source)
    beam = build_modal_beam(case)
    mu_l = case.beam.line_density * case.beam.length
    np.testing.assert_allclose(np.diag(beam.Mff), mu_l, rtol=1e-9)
    if beam.axial is not None:  # the rod's axial modes alike
        np.testing.assert_allclose(beam.axial.Maa, mu_l, rtol=1e-9)  # (its diagonal)
    assert beam.n + beam.na == (2 + 32 if source == "rod-end" else 12)
    ds = fb.simulate(fb.load_case(source, {"solver.t_end": 1e-5}), "ccfm").to_xarray()
    assert ds["q"].attrs["units"] == "m" and ds["q_rate"].attrs["units"] == "m/s"


def test_the_drive_work_names_the_moving_base():
    """On the shaker (a joint prescribed at zero rate: no torque does work) drive_work is the moving base's work,
    which the energy balance books in W (docs/formulation.md, "The base's work"); its long name said "Work of the
    joint torque".  total_energy = T + V_e + V_g + U_c + E_d - W with W = drive_work, to round-off."""
    from pathlib import Path

    shaker = Path(__file__).resolve().parent / "validation" / "data" / "shaker-stop.toml"
    ds = fb.simulate(fb.load_case(shaker, {"solver.t_end": 0.05}), "ccfm").to_xarray()
    assert "moving base" in ds["drive_work"].attrs["long_name"]
    assert float(np.max(np.abs(ds["drive_work"]))) > 1e-6  # the base works on the beam (J)
    terms = sum(ds[k] for k in ("kinetic_energy", "elastic_energy", "gravitational_energy", "contact_energy",
                                "dissipated_energy")) - ds["drive_work"]  # fmt: skip
    scale = float(np.max(np.abs(ds["kinetic_energy"]))) + float(np.max(np.abs(ds["drive_work"])))
    assert float(np.max(np.abs(terms - ds["total_energy"]))) <= 1e-6 * scale
    # and it is the base's work: with it the balance holds (measured 7.8e-10 J of drift against |W| up to 3.4e-4 J,
    # 2.3e-6 of it; bound 1e-4 of it, 40x), without it the energies change by all of W
    drift = float(np.max(np.abs(ds["total_energy"] - ds["total_energy"][0])))
    assert drift <= 1e-4 * float(np.max(np.abs(ds["drive_work"])))


@pytest.mark.parametrize("chunk", [0, -1, 100.5, True])
def test_a_time_chunk_that_is_no_whole_number_of_samples_is_refused(tmp_path, chunk):
    """``to_netcdf(time_chunk=0)`` (or -1, 100.5) was accepted and wrote chunks of one sample: an 18x larger file
    (found by exploratory testing).  Nothing is written."""
    sol = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 1e-3}))
    with pytest.raises(ValueError, match=r"^time_chunk: must be a whole number of samples >= 1"):
        sol.to_netcdf(tmp_path / "r.nc", time_chunk=chunk)
    assert list(tmp_path.iterdir()) == []
