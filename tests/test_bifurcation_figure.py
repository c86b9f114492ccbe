"""The bifurcation diagram's figure (:mod:`flexbeam.views.bifurcation`) draws each branch at the frequencies it was
run at: the swept-down branch was drawn 0.15 of a frequency step to the right in the Poincaré and impact panels
(9.6, 20.6, 31.6 Hz for 8, 19, 30 Hz), where the amplitude panel had it at its true frequencies."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from flexbeam.views.bifurcation import bifurcation_figure, plot_bifurcation  # noqa: E402

FREQ = np.array([8.0, 19.0, 30.0])


def diagram() -> xr.Dataset:
    """Two branches, three frequencies, four Poincaré samples and two impacts each (distinct values per branch)."""
    rng = np.random.default_rng(1)
    return xr.Dataset(
        {
            "tip": (("branch", "frequency", "section"), rng.normal(size=(2, 3, 4)) * 1e-3),
            "impact_velocity": (("branch", "frequency", "impact"), -rng.random((2, 3, 2))),
            "amplitude": (("branch", "frequency"), rng.random((2, 3)) * 1e-3),
        },
        coords={"branch": ["up", "down"], "frequency": FREQ},
    )


def test_every_branch_is_drawn_at_the_frequencies_it_was_run_at(tmp_path):
    ds = diagram()
    fig = bifurcation_figure(ds)
    try:
        for ax in fig.axes:
            lines = [ln for ln in ax.get_lines() if len(ln.get_xdata())]
            assert len(lines) == 2  # one per branch
            for ln in lines:
                assert set(np.asarray(ln.get_xdata(), float)) == set(FREQ), ax.get_ylabel()
        # the drawn values are the branch's own (the Poincaré panel: up's samples, then down's)
        up, down = fig.axes[0].get_lines()[:2]
        np.testing.assert_array_equal(up.get_ydata(), 1e3 * ds["tip"].sel(branch="up").values.ravel())
        np.testing.assert_array_equal(down.get_ydata(), 1e3 * ds["tip"].sel(branch="down").values.ravel())
        assert up.get_marker() != down.get_marker()  # told apart by their markers, not by a shift
    finally:
        plt.close(fig)
    assert plot_bifurcation(ds, tmp_path / "b.png").stat().st_size > 10_000
