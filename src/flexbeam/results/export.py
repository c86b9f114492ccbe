"""A run's :class:`~flexbeam.results.solution.Solution` as an :class:`xarray.Dataset` and a NetCDF-4 file.

Every variable carries its ``units`` and ``long_name`` (:data:`~flexbeam.results.records.VARIABLES`); the contact
records are variables along a ``contact`` dimension; the metrics and the provenance are attributes.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .files import atomic_path, jsonable
from .records import VARIABLES

if TYPE_CHECKING:
    from .solution import Solution


def to_xarray(sol: Solution):
    """:class:`xarray.Dataset` with dims time, mode, point, contact; units in attrs."""
    import xarray as xr

    n_modes = sol.arrays["q"].shape[1] if sol.arrays["q"].ndim == 2 else 0
    data_vars: dict[str, Any] = {}
    for name, arr in sol.arrays.items():
        units, long_name = VARIABLES[name]
        if name in ("q", "q_rate"):
            dims: tuple[str, ...] = ("time", "mode")
        elif name == "measuring_velocity":
            dims = ("time", "point")
        elif name.startswith("pair_"):
            dims = ("time", "pair")
        else:
            dims = ("time",)
        data_vars[name] = (dims, arr, {"units": units, "long_name": long_name})
    data_vars["phase"] = (("time",), sol.phase.astype(str), {"long_name": "Phase of motion"})
    c = sol.contacts
    counts = sol.contact_counts()
    episodes = [math.nan if k is None else k for k in counts.episode]
    contact_fields = {
        "contact_onset": ("s", "Contact onset time", [e.onset for e in c]),
        "contact_end": ("s", "Contact end time", [e.end for e in c]),
        "contact_velocity_before": ("m/s", "Normal velocity of P before contact", [e.velocity_before for e in c]),
        "contact_velocity_after": ("m/s", "Normal velocity of P after contact", [e.velocity_after for e in c]),
        "contact_impulse": ("N s", "Contact impulse", [e.impulse for e in c]),
        "contact_peak_force": ("N", "Peak contact force", [e.peak_force for e in c]),
        "contact_pair": ("1", "Contact pair of the contact (0: [contact] against [obstacle])", [e.pair for e in c]),
        "contact_micro_impact": ("1", "1 for a micro-impact, 0 for a contact (docs/methods.md)", counts.micro),
        "contact_chatter_episode": ("1", "Chatter episode of a micro-impact (NaN for a contact)", episodes),
    }
    for name, (units, long_name, values) in contact_fields.items():
        data_vars[name] = (("contact",), np.asarray(values, float), {"units": units, "long_name": long_name})
    coords = {
        "time": ("time", sol.time, {"units": "s", "long_name": "Time"}),
        "mode": ("mode", np.arange(1, n_modes + 1), {"long_name": "Mode number"}),
        "point": ("point", sol.measuring_points, {"units": "m", "long_name": "Measuring point x"}),
        "contact": ("contact", np.arange(len(c)), {"long_name": "Contact index"}),
    }
    if any(name.startswith("pair_") for name in sol.arrays):
        labels = sol.pair_labels
        coords["pair"] = ("pair", np.asarray(labels, str), {"long_name": "Contact pair (its obstacle)"})
    attrs = {
        "title": "flexbeam simulation",
        "status": sol.status,
        "message": sol.message,
        "metrics": json.dumps(jsonable(sol.metrics())),
        **{k: (v if isinstance(v, (str, int, float)) else json.dumps(jsonable(v))) for k, v in sol.provenance.items()},
    }
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def to_netcdf(sol: Solution, path: str | Path, time_chunk: int = 4096) -> Path:
    """Write :func:`to_xarray` to NetCDF-4 atomically (temporary file, then rename).

    Lossless compression: every non-empty variable is deflated (zlib level 4) after
    the byte shuffle, in chunks of ``time_chunk`` samples along ``time`` (whole along
    the other dimensions), so reading a time window decompresses only its chunks.
    ``phase`` is stored as a character array (variable-length strings cannot be
    compressed) and reads back as strings.  The seed experiment's result shrinks from
    11.3 MB to 7.2 MB: the float64 histories' low bits do not compress.
    """
    path = Path(path)
    ds = sol.to_xarray()
    encoding: dict[str, dict[str, Any]] = {}
    for name, var in ds.variables.items():
        if var.size == 0 or var.dtype.kind not in "fiuU":
            continue
        chunks = [min(time_chunk, n) if dim == "time" else n for dim, n in zip(var.dims, var.shape)]
        enc: dict[str, Any] = {"zlib": True, "complevel": 4, "shuffle": True}
        if var.dtype.kind == "U":
            enc["dtype"] = "S1"
            chunks.append(max(1, var.dtype.itemsize // np.dtype("U1").itemsize))
        encoding[name] = {**enc, "chunksizes": tuple(chunks)}
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", encoding=encoding)
    return path
