"""A run's :class:`~flexbeam.results.solution.Solution` as an :class:`xarray.Dataset` and a NetCDF-4 file.

Every variable carries its ``units`` and ``long_name`` (:data:`~flexbeam.results.records.VARIABLES`); the contact
records are variables along a ``contact`` dimension; the metrics and the provenance are attributes.

The file keeps what the run knows and no more (:func:`to_netcdf`): every variable is deflated (zlib after the byte
shuffle) in chunks of :data:`TIME_CHUNK` samples, one column at a time; the outputs computed from the integrated state
(:data:`QUANTIZED`) are rounded to the precision the integrator's tolerance gives them (:func:`significant_bits`,
:func:`bitround`; CF 1.11 quantization attributes), the rest -- time, the hub angle, the total energy, the contact
records -- is stored exactly.  Both stay float64, so the file opens with plain xarray as before.
"""

from __future__ import annotations

import json
import math
import numbers
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .files import atomic_path, jsonable
from .poincare import drive_phase
from .records import CENTRE_VARIABLES, VARIABLES

if TYPE_CHECKING:
    from .solution import Solution

#: samples per chunk along ``time`` in a file (256 kB of one float64 column; a longer chunk deflates a little better,
#: a shorter one reads a short time window faster: the seed experiment's file is 2.96 MB in chunks of 4096)
TIME_CHUNK = 32768
#: zlib level of every variable (zlib's default; 9 gains 0.1 % on the seed experiment's file, at twice the time)
COMPLEVEL = 6
#: the outputs stored to the integrator's precision: functions of the integrated state, whose error the step control
#: bounds relative to the state's size.  Stored exactly: ``time``; ``theta``, the rigid angle, which the error norm
#: leaves out (its value has no scale: a long spin carries it far from its error); ``total_energy``, whose drift is
#: what it shows; ``pair_contact_position`` (a nearest-point search, not a state); a free beam's ``centre_of_mass``
#: and its velocity (G's coordinates, as theta: a long flight carries them far from their error); the contact records.
QUANTIZED = frozenset(
    {
        "theta_rate", "q", "q_rate", "gap", "normal_velocity", "contact_force", "contact_energy", "kinetic_energy",
        "elastic_energy", "gravitational_energy", "dissipated_energy", "drive_work", "joint_torque",
        "tip_deflection", "measuring_velocity", "support_displacement", "sensor_force", "pair_gap",
        "pair_normal_velocity", "pair_contact_force", "pair_tangential_force", "pair_slip_velocity",
    }
)  # fmt: skip
#: a rounded value moves by at most this fraction of the integrator's relative tolerance (of its own size)
PRECISION_FRACTION = 1.0 / 16.0
#: the CF container variable that describes the rounding (CF 1.11, section 8.4)
QUANTIZATION_INFO = "quantization_info"
#: the names of the phases a ``phase`` sample may hold (their longest sets the width of its characters)
PHASE_NAMES = ("free", "contact", "constrained", "resting")


def significant_bits(rtol: float) -> int | None:
    """The mantissa bits a value keeps so that rounding moves it by at most :data:`PRECISION_FRACTION` of ``rtol``
    (relative): 2^-(nsb + 1) <= rtol / 16.  23 for the compiled integrator's default 1e-6 -- float32's precision,
    kept in a float64 -- and 33 for the reference's 1e-9; None (keep all 52) for no known tolerance."""
    try:
        rtol = float(rtol)
    except (TypeError, ValueError):
        return None
    if not (math.isfinite(rtol) and rtol > 0.0):
        return None
    nsb = max(1, math.ceil(math.log2(0.5 / (PRECISION_FRACTION * rtol))))
    return nsb if nsb < 52 else None


def bitround(x: np.ndarray, nsb: int) -> np.ndarray:
    """``x`` (float64) rounded to ``nsb`` explicit mantissa bits, to nearest with ties to even (the BitRound of
    Kloewer et al. 2021, Nat. Comput. Sci. 1, 713): the relative change is at most 2^-(nsb + 1) (below 2.2e-308, where
    doubles thin out, 2^-(nsb + 1) of 2.2e-308) and the dropped bits are zeros, which the byte shuffle and zlib then
    store in almost nothing.  NaN and +-inf are kept; so is a value that rounding would carry beyond the largest
    double."""
    x = np.ascontiguousarray(x, dtype=np.float64)
    drop = 52 - int(nsb)
    if drop <= 0:
        return x.copy()
    bits = x.view(np.uint64)
    one = np.uint64(1)
    half = np.uint64(1 << (drop - 1))
    keep = ~np.uint64((1 << drop) - 1)
    rounded = ((bits + (half - one) + ((bits >> np.uint64(drop)) & one)) & keep).view(np.float64)
    return np.where(np.isfinite(rounded) | ~np.isfinite(x), rounded, x)


def precision_bits(provenance: Mapping[str, Any]) -> int | None:
    """The significant bits of a run's quantized outputs: from the relative tolerance of the integrator that ran
    (``rtol`` of the provenance); None for the finite-element reference, whose fixed steps give no tolerance."""
    if provenance.get("method") == "fem" or "rtol" not in provenance:
        return None
    return significant_bits(provenance["rtol"])


def quantization_attrs(nsb: int, rtol: float) -> dict[str, Any]:
    """A quantized variable's attributes (CF 1.11 ``quantization``, ``quantization_nsb``) and the bound on its
    rounding in words."""
    bound = 2.0 ** -(nsb + 1)
    return {
        "quantization": QUANTIZATION_INFO,
        "quantization_nsb": np.int32(nsb),
        "quantization_maximum_relative_error": bound,
        "precision": (
            f"rounded to {nsb} significant bits: relative error <= {bound:.3g}, at most 1/16 of the integrator's "
            f"relative tolerance {rtol:g}"
        ),
    }


def quantization_info(version: str) -> dict[str, Any]:
    """The attributes of the container variable :data:`QUANTIZATION_INFO`."""
    return {
        "algorithm": "bitround",
        "implementation": f"flexbeam {version} (numpy)",
        "long_name": "Quantization of the outputs computed from the integrated state (docs/usage.md)",
    }


def variable_dims(name: str) -> tuple[str, ...]:
    """The dimensions of a sampled variable."""
    if name in ("q", "q_rate"):
        return ("time", "mode")
    if name == "measuring_velocity":
        return ("time", "point")
    if name.startswith("pair_"):
        return ("time", "pair")
    if name in CENTRE_VARIABLES:
        return ("time", "axis")
    return ("time",)


#: the long names of a free beam's angle and its rate (its floating frame's: docs/free-beam.md), for the revolute
#: joint's hub angle
FREE_LONG_NAMES = {
    "theta": "Angle of the free beam's mean axis",
    "theta_rate": "Angular velocity of the free beam's mean axis",
}


def variable_attrs(name: str, free: bool = False) -> dict[str, str]:
    """The units and long name of variable ``name`` (``free``: of a free beam's, :data:`FREE_LONG_NAMES`)."""
    units, long_name = VARIABLES[name]
    return {"units": units, "long_name": FREE_LONG_NAMES.get(name, long_name) if free else long_name}


PHASE_ATTRS = {"long_name": "Phase of motion"}


def contact_fields(sol: Solution) -> dict[str, tuple[str, str, np.ndarray]]:
    """The contact records as variables along ``contact``: name -> (units, long name, values)."""
    c = sol.contacts
    counts = sol.contact_counts()
    episodes = [math.nan if k is None else k for k in counts.episode]
    fields = {
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
    tangential = [e.tangential_impulse for e in c]
    if any(math.isfinite(v) for v in tangential):  # a run with frictional impacts (IMM with contact.friction)
        fields["contact_tangential_impulse"] = ("N s", "Frictional impulse along the contact's tangent", tangential)
    f = sol.drive_frequency
    if math.isfinite(f):  # a base shaken periodically: the phase of the drive at each onset
        fields["contact_drive_phase"] = (
            "1",
            "Phase of the base drive at the onset, frac(f t)",
            [drive_phase(e.onset, f) for e in c],
        )
    return {k: (u, n, np.asarray(v, float)) for k, (u, n, v) in fields.items()}


def coordinate_specs(
    n_modes: int, points: np.ndarray, contacts: int, pair_labels: list[str] | None, axes: bool = False
) -> dict[str, tuple[np.ndarray, dict[str, str]]]:
    """The coordinates besides ``time``: name -> (values, attributes); ``axis`` (x, y) with ``axes`` (a free beam's
    :data:`~flexbeam.results.records.CENTRE_VARIABLES`)."""
    coords = {
        "mode": (np.arange(1, n_modes + 1), {"long_name": "Mode number"}),
        "point": (np.asarray(points, float), {"units": "m", "long_name": "Measuring point x"}),
        "contact": (np.arange(contacts), {"long_name": "Contact index"}),
    }
    if pair_labels is not None:
        coords["pair"] = (np.asarray(pair_labels, str), {"long_name": "Contact pair (its obstacle)"})
    if axes:
        coords["axis"] = (np.array(["x", "y"]), {"long_name": "Inertial axis"})
    return coords


TIME_ATTRS = {"units": "s", "long_name": "Time"}


def global_attrs(sol: Solution) -> dict[str, Any]:
    """Title, status, message, the metrics (JSON) and the provenance."""
    return {
        "title": "flexbeam simulation",
        "status": sol.status,
        "message": sol.message,
        "metrics": json.dumps(jsonable(sol.metrics())),
        **{k: (v if isinstance(v, (str, int, float)) else json.dumps(jsonable(v))) for k, v in sol.provenance.items()},
    }


def to_xarray(sol: Solution):
    """:class:`xarray.Dataset` with dims time, mode, point, contact; units in attrs (full precision)."""
    import xarray as xr

    n_modes = sol.arrays["q"].shape[1] if sol.arrays["q"].ndim == 2 else 0
    data_vars: dict[str, Any] = {}
    free = CENTRE_VARIABLES[0] in sol.arrays  # a free beam: its angle's names, G's axis
    for name, arr in sol.arrays.items():
        data_vars[name] = (variable_dims(name), arr, variable_attrs(name, free))
    data_vars["phase"] = (("time",), sol.phase.astype(str), dict(PHASE_ATTRS))
    for name, (units, long_name, values) in contact_fields(sol).items():
        data_vars[name] = (("contact",), values, {"units": units, "long_name": long_name})
    pairs = sol.pair_labels if any(name.startswith("pair_") for name in sol.arrays) else None
    coords: dict[str, Any] = {"time": ("time", sol.time, dict(TIME_ATTRS))}
    specs = coordinate_specs(n_modes, sol.measuring_points, len(sol.contacts), pairs, free)
    for name, (values, attrs) in specs.items():
        coords[name] = (name, values, attrs)
    return xr.Dataset(data_vars, coords=coords, attrs=global_attrs(sol))


def chunk_shape(dims: Iterable[str], shape: tuple[int, ...], time_chunk: int) -> tuple[int, ...]:
    """A variable's chunks: ``time_chunk`` samples along ``time`` (fewer when it has fewer), one column of the other
    dimensions (a column of samples deflates better than rows that interleave modes); one chunk without ``time``."""
    dims = tuple(dims)
    if "time" not in dims:
        return tuple(max(1, n) for n in shape)
    return tuple(max(1, min(time_chunk, n)) if d == "time" else 1 for d, n in zip(dims, shape))


def to_netcdf(sol: Solution, path: str | Path, time_chunk: int = TIME_CHUNK, quantize: bool = True) -> Path:
    """Write :func:`to_xarray` to NetCDF-4 atomically (temporary file, then rename).

    Every non-empty variable is deflated (zlib level :data:`COMPLEVEL`) after the byte shuffle, in chunks of
    ``time_chunk`` samples along ``time``, one column at a time, so reading a time window decompresses only its
    chunks.  With ``quantize`` (the default) the :data:`QUANTIZED` outputs are rounded to the precision of the run's
    integrator (:func:`precision_bits`, :func:`bitround`: 23 significant bits for the compiled integrator's rtol =
    1e-6, a relative change <= 6e-8) and carry the CF attributes ``quantization``, ``quantization_nsb`` and a
    ``precision`` in words; everything else is stored exactly (``quantize=False``: everything, but for a run
    streamed to its file, rounded as it was written: a ValueError).  ``phase`` is stored
    as characters (variable-length strings cannot be compressed) and reads back as strings.  The seed experiment's
    result: 11.3 MB uncompressed, 5.6 MB deflated, 2.7 MB rounded to the integrator's precision.
    """
    path = Path(path)
    if isinstance(time_chunk, bool) or not isinstance(time_chunk, numbers.Integral) or time_chunk < 1:
        raise ValueError(f"time_chunk: must be a whole number of samples >= 1 (got {time_chunk!r})")
    if getattr(sol, "file", None) is not None:  # streamed: the file is written already (its chunks as written)
        if not quantize and _quantized(sol.stored_file()):
            raise ValueError(
                "quantize=False: this run was streamed to its file, whose samples were rounded as they were written; "
                "the exact samples need the run held in memory (simulate without stream=)"
            )
        return _copy_stored(sol, path)
    return write_dataset(result_dataset(sol, quantize), path, time_chunk)


def result_dataset(sol: Solution, quantize: bool = True):
    """:func:`to_xarray` as :func:`to_netcdf` stores it: with ``quantize`` the :data:`QUANTIZED` outputs rounded to the
    run's precision (:func:`precision_bits`, :func:`bitround`) with their CF attributes and the
    :data:`QUANTIZATION_INFO` variable (a sweep's histories are these, :mod:`flexbeam.sweep.store`)."""
    ds = sol.to_xarray()
    nsb = precision_bits(sol.provenance) if quantize else None
    if nsb is not None:
        rtol = float(sol.provenance["rtol"])
        for name in QUANTIZED & set(ds.data_vars):
            var = ds[name]
            ds[name] = var.copy(data=bitround(var.values, nsb))
            ds[name].attrs.update(quantization_attrs(nsb, rtol))
        ds[QUANTIZATION_INFO] = ((), np.int32(0), quantization_info(str(sol.provenance.get("flexbeam_version"))))
    return ds


def write_dataset(ds, path: str | Path, time_chunk: int = TIME_CHUNK) -> Path:
    """Write a result Dataset to NetCDF-4 at ``path`` atomically, every variable deflated in its chunks
    (:func:`variable_encoding`)."""
    path = Path(path)
    encoding = {name: variable_encoding(var, time_chunk) for name, var in ds.variables.items()}
    encoding = {k: v for k, v in encoding.items() if v}
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", encoding=encoding)
    return path


def variable_encoding(var, time_chunk: int) -> dict[str, Any]:
    """The xarray encoding of one variable: zlib after the shuffle, in :func:`chunk_shape` chunks; strings as
    characters."""
    if var.size == 0 or var.ndim == 0 or var.dtype.kind not in "fiuU":
        return {}
    chunks = list(chunk_shape(var.dims, var.shape, time_chunk))
    enc: dict[str, Any] = {"zlib": True, "complevel": COMPLEVEL, "shuffle": True}
    if var.dtype.kind == "U":
        enc["dtype"] = "S1"
        chunks.append(max(1, var.dtype.itemsize // np.dtype("U1").itemsize))
    return {**enc, "chunksizes": tuple(chunks)}


def _quantized(path: Path) -> bool:
    """Does the result file at ``path`` hold samples rounded to the integrator's precision (its
    :data:`QUANTIZATION_INFO` variable)?"""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        return QUANTIZATION_INFO in ds.variables


def _copy_stored(sol: Solution, path: Path) -> Path:
    """A streamed run's file at ``path`` (itself when it is there already)."""
    import shutil

    src = sol.stored_file()
    if path.resolve() == src.resolve():
        return path
    with atomic_path(path) as tmp:
        shutil.copyfile(src, tmp)
    return path


def read_samples(
    path: str | Path, checked: Callable[[], Path] | None = None
) -> tuple[np.ndarray, np.ndarray, LazyArrays]:
    """(time, phase, arrays) of a result file; each array read when first asked for (``checked``: as
    :class:`LazyArrays`)."""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        time = ds["time"].values
        phase = ds["phase"].values.astype(object)
        names = sampled_names(ds)
    return time, phase, LazyArrays(Path(path), names, checked)


def sampled_names(ds) -> list[str]:
    """The names of a result Dataset's sampled variables (along ``time``; ``phase`` apart)."""
    return [n for n in ds.data_vars if "time" in ds[n].dims and n != "phase"]


class LazyArrays(Mapping):
    """The sampled variables of a result file by name, each read on first access (a long run's file may hold more
    than the memory: read what is needed)."""

    def __init__(self, path: Path, names: list[str], checked: Callable[[], Path] | None = None) -> None:
        self.path, self.names, self._read = path, list(names), {}
        self.checked = checked  #: the path again, checked to be the same file (a streamed run's, before each read)

    def __getitem__(self, name: str) -> np.ndarray:
        if name not in self.names:
            raise KeyError(name)
        if name not in self._read:
            import xarray as xr

            with xr.open_dataset(self.path if self.checked is None else self.checked()) as ds:
                self._read[name] = ds[name].values
        return self._read[name]

    def __contains__(self, name: object) -> bool:  # (by name, without reading the variable)
        return name in self.names

    def __iter__(self):
        return iter(self.names)

    def __len__(self) -> int:
        return len(self.names)


__all__ = [
    "QUANTIZED", "TIME_CHUNK", "LazyArrays", "bitround", "precision_bits", "read_samples", "sampled_names",
    "result_dataset", "significant_bits", "to_netcdf", "to_xarray", "write_dataset",
]  # fmt: skip
