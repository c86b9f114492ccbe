"""NetCDF write/read round trip of a Solution for every impact method and a compliant support.

What ``Solution.to_netcdf`` writes must read back with :func:`xarray.open_dataset` to the
dataset of ``Solution.to_xarray``: every variable and coordinate with equal values (NaN
where NaN), its units and long_name, the metrics (strict JSON) and the provenance, whose
case TOML loads back to the case that ran.
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np
import pytest

import flexbeam as fb
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
    for name in [*expected.data_vars, *expected.coords]:
        assert name in ds, name
        want, have = expected[name], ds[name]
        assert have.dims == want.dims, name
        if want.dtype.kind in "US":  # strings come back as objects
            np.testing.assert_array_equal(have.values.astype(str), want.values, err_msg=name)
        else:
            assert have.dtype == want.dtype, name
            np.testing.assert_array_equal(have.values, want.values, err_msg=name)  # NaN == NaN here
        for attr in ("units", "long_name"):
            assert have.attrs.get(attr) == want.attrs.get(attr), (name, attr)
    assert set(ds.data_vars) == set(expected.data_vars)
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
