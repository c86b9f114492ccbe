"""The figure of a bifurcation diagram (:func:`flexbeam.bifurcation.bifurcation`): the Poincaré samples of the tip's
deflection and the impacts' approach velocities against the drive frequency, up and down, and the frequency
response (the largest tip deflection)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..results.files import atomic_path

COLOURS = {"up": "C0", "down": "C3"}
#: each branch's marker: the swept-down branch's hollow, so that both show where they coincide (drawn 0.15 of a
#: frequency step to the right before, at frequencies it was not run at)
MARKERS = {"up": {"marker": ".", "ms": 2}, "down": {"marker": "o", "ms": 3.5, "mfc": "none", "mew": 0.6}}


def bifurcation_figure(ds: xr.Dataset):
    """Three panels against the frequency -- the Poincaré samples of the tip deflection [mm], the impacts' approach
    speeds [m/s], the largest absolute tip deflection [mm] -- the branch swept up in blue dots, down in red circles,
    every point at the frequency it was run at: the Matplotlib figure."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f = ds["frequency"].values
    fig, axes = plt.subplots(3, 1, figsize=(7.0, 8.0), sharex=True, height_ratios=(2, 2, 1), layout="constrained")
    for name in ds["branch"].values:
        b = ds.sel(branch=name)
        style = {"color": COLOURS.get(str(name), "k"), "ls": "none", **MARKERS.get(str(name), MARKERS["up"])}
        tip = b["tip"].values
        axes[0].plot(np.repeat(f, tip.shape[1]), 1e3 * tip.ravel(), label=f"swept {name}", **style)
        iv = b["impact_velocity"].values
        axes[1].plot(np.repeat(f, iv.shape[1]), -iv.ravel(), **style)
        axes[2].plot(f, 1e3 * b["amplitude"].values, **{**style, "ls": "-"})
    axes[0].set(ylabel="tip deflection at the\nPoincaré section [mm]",
                title=f"{ds.attrs.get('case', '')}: {ds.attrs.get('method', '')}, "
                      f"{ds.attrs.get('periods', '')} periods, {ds.attrs.get('discard', '')} discarded")  # fmt: skip
    axes[0].legend(markerscale=2, fontsize="small")
    axes[1].set(ylabel="impact speed [m/s]")
    axes[2].set(xlabel="drive frequency [Hz]", ylabel="max |tip|\n[mm]")
    return fig


def plot_bifurcation(ds: xr.Dataset, path: str | Path) -> Path:
    """:func:`bifurcation_figure` written as a PNG."""
    import matplotlib.pyplot as plt

    fig = bifurcation_figure(ds)
    path = Path(path)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    return path
