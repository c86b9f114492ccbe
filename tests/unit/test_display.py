"""Notebook reprs (flexbeam.views.display) and the compressed NetCDF output of a Solution."""

from __future__ import annotations

import base64
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import xarray as xr

import flexbeam as fb

#: every element the reprs may use: a fragment with anything else (a script, a stray tag) fails
HTML_TAGS = {"div", "span", "b", "table", "thead", "tbody", "tr", "th", "td", "img"}


def _fragment(html: str) -> ET.Element:
    """Parse an HTML fragment strictly (as XML: balanced tags, quoted attributes, escaped text)."""
    root = ET.fromstring(html)
    assert root.tag == "div"
    tags = {el.tag for el in root.iter()}
    assert tags <= HTML_TAGS, tags - HTML_TAGS
    for img in root.iter("img"):
        src = img.get("src", "")
        assert src.startswith("data:image/png;base64,")
        assert base64.b64decode(src.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
        assert img.get("alt")
    return root


def _text(root: ET.Element) -> str:
    return " ".join(t.strip() for t in root.itertext() if t.strip())


@pytest.fixture(scope="module")
def ccfm():
    return fb.simulate("seed-experiment", model__modes=2, solver__t_end=5e-3)


def test_solution_repr_shows_status_and_peak_force(ccfm):
    m = ccfm.metrics()
    root = _fragment(ccfm._repr_html_())
    text = _text(root)
    assert "success" in text and "seed-experiment" in text and "CCFM" in text
    assert f"{m['peak_force']:.4g}" in text and "peak_force" in text
    assert len(list(root.iter("img"))) == 1


@pytest.mark.parametrize("case, method", [("seed-experiment", "imm"), ("kane-spinup", "ccfm")])
def test_solution_repr_without_a_force_history(case, method):
    """IMM has impulses but no force; the Kane spin-up has no contact: both still render."""
    sol = fb.simulate(case, method=method, model__modes=2, solver__t_end=5e-3 if method == "imm" else 0.5)
    root = _fragment(sol._repr_html_())
    text = _text(root)
    assert sol.status in text and method.upper() in text
    assert np.isnan(sol.metrics()["peak_force"]) and "peak_force" not in text  # no NaN rows


def test_failed_status_and_markup_in_messages_are_escaped():
    sol = fb.simulate("seed-experiment", model__modes=0, solver__t_end=2e-3)
    sol.status, sol.message = "failed", "step size < 1e-12 s at t = 0 & <unknown>"
    root = _fragment(sol._repr_html_())
    assert "failed" in _text(root) and "<unknown>" in _text(root)


def test_calibration_repr_shows_fitted_values_and_peak_force():
    """A rigid-beam fit of the restitution to the peak force and duration of a known case."""
    case = fb.load_case("seed-experiment", {"model.modes": 0, "solver.t_end": 2e-3})
    m = fb.simulate(fb.load_case(case, {"contact.restitution": 0.6})).metrics()
    fit = fb.calibrate(
        case,
        fit=["contact.restitution"],
        features={"peak_force": m["peak_force"], "contact_duration": m["contact_duration"]},
    )
    root = _fragment(fit._repr_html_())
    text = _text(root)
    assert "success" in text and "contact.restitution" in text
    assert f"{fit.values[0]:.4g}" in text
    assert f"{fit.solution.metrics()['peak_force']:.4g}" in text


def test_netcdf_is_compressed_chunked_along_time_and_lossless_on_request(ccfm, tmp_path):
    """Chunks of ``time_chunk`` samples, one column each; ``quantize=False``: every value exact (by default the
    outputs of the state are rounded to the integrator's precision: tests/test_netcdf_roundtrip.py)."""
    path = ccfm.to_netcdf(tmp_path / "result.nc", time_chunk=256, quantize=False)
    raw = sum(np.asarray(a).nbytes for a in ccfm.arrays.values()) + ccfm.time.nbytes
    assert path.stat().st_size < raw  # deflated (the uncompressed file is larger than the raw arrays)
    with xr.open_dataset(path) as ds:
        enc = ds["q"].encoding
        assert enc["zlib"] and enc["shuffle"]
        assert enc["chunksizes"] == (256, 1)
        assert "quantization" not in ds["q"].attrs
        np.testing.assert_array_equal(ds["time"].values, ccfm.time)
        for name, arr in ccfm.arrays.items():
            np.testing.assert_array_equal(ds[name].values, arr)
        assert list(ds["phase"].values) == list(ccfm.phase)
        assert ds["contact_force"].attrs["units"] == "N"


def test_a_solution_prints_in_one_line_without_evaluating_its_samples():
    """``repr``/``print`` of a Solution (outside Jupyter) named an object address; now one line with the case, the
    method, the status and its records -- and no sample evaluated for it (a long run's samples cost seconds)."""
    sol = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 0.005}), "ccfm")
    text = repr(sol)
    assert text == f"<Solution 'seed-experiment' ccfm: success, {len(sol.records)} contact records>"
    assert str(sol) == text and "\n" not in text
    assert sol._samples is None  # (what the repr did not ask for)
