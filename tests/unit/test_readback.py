"""A whole run's line reduced for a small figure (flexbeam.results.envelope): each bin's extremes, checked against a
bin-by-bin loop, and read from a result file in slices to the same numbers as from the variable read whole."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import flexbeam as fb
from flexbeam.results.envelope import envelope
from flexbeam.results.readback import read_envelope, read_span

values = hnp.arrays(
    np.float64,
    st.integers(1, 400),
    elements=st.one_of(st.floats(-1e3, 1e3), st.just(math.nan)),
)


@settings(max_examples=200, deadline=None)
@given(values=values, bins=st.integers(1, 60))
def test_each_bin_keeps_its_smallest_and_largest_sample_in_time_order(values, bins):
    n = values.size
    time = np.cumsum(np.full(n, 1e-3))
    t, v = envelope(time, values, bins)
    if n <= 2 * bins:
        assert t is time and v is values
        return
    size = math.ceil(n / bins)
    starts = range(0, n, size)
    assert t.size == v.size == 2 * len(starts) and len(starts) <= bins
    for j, a in enumerate(starts):
        chunk, times = values[a : a + size], time[a : a + size]
        (ta, tb), (va, vb) = t[2 * j : 2 * j + 2], v[2 * j : 2 * j + 2]
        assert times[0] <= ta <= tb <= times[-1]
        if np.all(np.isnan(chunk)):
            assert np.isnan(va) and np.isnan(vb)
            continue
        assert sorted([va, vb]) == [np.nanmin(chunk), np.nanmax(chunk)]
        for tk, vk in ((ta, va), (tb, vb)):  # a sample of the bin, at its own time
            assert vk in chunk[times == tk]


def test_a_bin_count_below_one_is_refused():
    with pytest.raises(ValueError, match="bins must be at least 1"):
        envelope(np.arange(5.0), np.arange(5.0), 0)


@pytest.mark.parametrize("bins, read", [(10, 7), (10, 100), (40, 1), (5000, 64)])
def test_the_envelope_read_from_a_file_in_slices_is_the_envelope_of_the_whole_variable(tmp_path, bins, read):
    """Slices of one bin (``read`` shorter than a bin), of several, and a line short enough to be kept whole."""
    sol = fb.simulate("seed-experiment", model__modes=2, solver__t_end=5e-3)
    path = sol.to_netcdf(tmp_path / "r.nc")
    with xr.open_dataset(path) as ds:
        time, force = ds["time"].values, ds["contact_force"].values
    assert time.size > 2 * 40 and np.nanmax(force) > 0.0
    t, v = read_envelope(path, "contact_force", bins=bins, read=read)
    te, ve = envelope(time, force, bins)
    np.testing.assert_array_equal(t, te)
    np.testing.assert_array_equal(v, ve)
    assert np.nanmax(v) == np.nanmax(force) and np.nanmin(v) == np.nanmin(force)
    assert read_span(path) == (time[0], time[-1], time.size)


def test_a_window_reads_its_own_samples_and_a_bisection_of_the_time(tmp_path, monkeypatch):
    """read_window read the file's time whole to find its ends (8 bytes a sample: 780 MB for 20 s of the seed case
    streamed at its default sampling); it reads the window's times and one time a bisection probe."""
    from contextlib import contextmanager

    from flexbeam.results import readback

    sol = fb.simulate("seed-experiment", model__modes=2, solver__t_end=5e-3)
    path = sol.to_netcdf(tmp_path / "r.nc")
    read: list[int] = []

    class Counted:  # the time variable, counting the samples read from it
        def __init__(self, var):
            self.var, self.shape = var, var.shape

        def __len__(self):
            return len(self.var)

        def __getitem__(self, key):
            out = np.asarray(self.var[key])
            read.append(out.size)
            return out

    opened = readback._opened

    @contextmanager
    def counted(p):
        with opened(p) as (time, ds):
            yield Counted(time), ds

    monkeypatch.setattr(readback, "_opened", counted)
    n = sol.time.size
    a, b = sol.contacts[0].onset, sol.contacts[0].onset + 0.2 * sol.contacts[0].duration
    time, _, arrays = readback.read_window(path, a, b)
    np.testing.assert_array_equal(time, sol.time[(sol.time >= a) & (sol.time <= b)])
    assert 0 < time.size < n / 4
    assert sum(read) <= time.size + 2 * math.ceil(math.log2(n + 1))
    np.testing.assert_allclose(arrays["contact_force"], sol["contact_force"][(sol.time >= a) & (sol.time <= b)],
                               rtol=2**-24, atol=0.0)  # fmt: skip
