"""Bifurcation diagrams of a beam on a moving base: the drive frequency swept up and down with continuation, the
Poincaré samples and impacts of each frequency, on the sweep's Dask runner (:func:`bifurcation`)."""

from __future__ import annotations

from .._namespace import public_dir
from .continuation import Point, branch, run_point
from .runner import bifurcation, build_dataset

__all__ = ["Point", "bifurcation", "branch", "build_dataset", "run_point"]

__dir__ = public_dir(globals())
