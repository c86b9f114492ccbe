"""A result file written while the run goes on: output samples appended in chunks, the records and metrics at the end.

:class:`SampleFile` holds at most two chunks of samples (:data:`~flexbeam.results.export.TIME_CHUNK` each) in memory:
a full chunk is rounded (:func:`~flexbeam.results.export.bitround`, as :func:`~flexbeam.results.export.to_netcdf`
rounds), deflated and appended along the unlimited ``time`` dimension.  The file has the variables, attributes,
chunks and compression of :func:`~flexbeam.results.export.to_netcdf` and reads back with plain xarray to the same
values; it is written under a temporary name and renamed when the run ends
(:class:`~flexbeam.results.files.atomic_path`).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from . import export
from .files import atomic_path

if TYPE_CHECKING:
    from .solution import Solution

#: the width of a ``phase`` sample's characters: its longest name
PHASE_WIDTH = max(len(name) for name in export.PHASE_NAMES)


class SampleFile:
    """Appends output samples to a NetCDF-4 file (see the module docstring).

    Parameters
    ----------
    path
        The result file (written as a temporary file beside it until :meth:`close`).
    n_modes, points, pair_labels
        The coordinates besides time (``pair_labels`` None without per-pair variables).
    nsb, rtol
        The significant bits of the :data:`~flexbeam.results.export.QUANTIZED` outputs (None: all exact) and the
        tolerance they come from.
    version
        flexbeam's version, for the quantization's description.
    """

    def __init__(
        self,
        path: str | Path,
        n_modes: int,
        points: np.ndarray,
        pair_labels: list[str] | None,
        nsb: int | None,
        rtol: float,
        version: str,
        time_chunk: int = export.TIME_CHUNK,
    ) -> None:
        self.path = Path(path)
        self.n_modes, self.points, self.pair_labels = n_modes, np.asarray(points, float), pair_labels
        self.nsb, self.rtol, self.version, self.chunk = nsb, rtol, version, int(time_chunk)
        import netCDF4  # noqa: F401 - imported now, not in the middle of a run (their ~100 MB come first)
        import xarray  # noqa: F401

        self._atomic = atomic_path(self.path)
        self.tmp = self._atomic.__enter__()
        self.nc: Any = None
        self.written = 0
        self._parts: list[tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]] = []
        self._held = 0

    # ----------------------------------------------------------------- samples
    def append(self, time: np.ndarray, phase: str, arrays: dict[str, np.ndarray]) -> None:
        """Samples at ``time`` of one phase (name ``phase``): each full chunk goes to the file."""
        if not time.size:
            return
        self._parts.append((np.asarray(time, float), np.full(time.size, phase, dtype=f"U{PHASE_WIDTH}"), arrays))
        self._held += time.size
        if self._held >= self.chunk:
            self._flush(whole_chunks=True)

    def _flush(self, whole_chunks: bool) -> None:
        if not self._parts:
            return
        t = np.concatenate([p[0] for p in self._parts])
        ph = np.concatenate([p[1] for p in self._parts])
        arrays = {name: np.concatenate([p[2][name] for p in self._parts]) for name in self._parts[0][2]}
        n = (t.size // self.chunk) * self.chunk if whole_chunks else t.size
        self._parts = [(t[n:], ph[n:], {k: v[n:] for k, v in arrays.items()})] if n < t.size else []
        self._held = t.size - n
        if n:
            self._write(t[:n], ph[:n], {k: v[:n] for k, v in arrays.items()})

    def _rounded(self, name: str, values: np.ndarray) -> np.ndarray:
        if self.nsb is not None and name in export.QUANTIZED:
            return export.bitround(values, self.nsb)
        return values

    def _write(self, t: np.ndarray, ph: np.ndarray, arrays: dict[str, np.ndarray]) -> None:
        if self.nc is None:
            self._create(t, ph, arrays)
            return
        n0, n1 = self.written, self.written + t.size
        self.nc["time"][n0:n1] = t
        for name, values in arrays.items():
            self.nc[name][n0:n1] = self._rounded(name, values)
        self.nc["phase"][n0:n1] = _chars(ph)
        self.written = n1

    def _create(self, t: np.ndarray, ph: np.ndarray, arrays: dict[str, np.ndarray]) -> None:
        """The file with its first samples (xarray writes the variables and their encoding), ``phase`` added as
        characters of a fixed width (a later phase may have a longer name)."""
        import netCDF4
        import xarray as xr

        data_vars: dict[str, Any] = {}
        free = export.CENTRE_VARIABLES[0] in arrays  # a free beam: its angle's names, G's axis
        for name, values in arrays.items():
            attrs = export.variable_attrs(name, free)
            if self.nsb is not None and name in export.QUANTIZED:
                attrs.update(export.quantization_attrs(self.nsb, self.rtol))
            data_vars[name] = (export.variable_dims(name), self._rounded(name, values), attrs)
        coords: dict[str, Any] = {"time": ("time", t, dict(export.TIME_ATTRS))}
        specs = export.coordinate_specs(self.n_modes, self.points, 0, self.pair_labels, free)
        for name, (values, attrs) in specs.items():
            if name != "contact":  # its size is known at the end
                coords[name] = (name, values, attrs)
        ds = xr.Dataset(data_vars, coords=coords)
        if self.nsb is not None:
            ds[export.QUANTIZATION_INFO] = ((), np.int32(0), export.quantization_info(self.version))
        encoding = {name: export.variable_encoding(var, self.chunk) for name, var in ds.variables.items()}
        ds.to_netcdf(
            self.tmp,
            engine="netcdf4",
            format="NETCDF4",
            unlimited_dims=["time"],
            encoding={k: v for k, v in encoding.items() if v},
        )
        self.nc = netCDF4.Dataset(self.tmp, "a")
        for var in self.nc.variables.values():  # whole chunks are written once: no cache (it would grow to 16 MB each)
            var.set_var_chunk_cache(size=0)
        self.nc.createDimension(f"string{PHASE_WIDTH}", PHASE_WIDTH)
        var = self.nc.createVariable(
            "phase",
            "S1",
            ("time", f"string{PHASE_WIDTH}"),
            zlib=True,
            complevel=export.COMPLEVEL,
            shuffle=True,
            chunksizes=(max(1, min(self.chunk, t.size)), PHASE_WIDTH),
        )
        var.set_auto_chartostring(False)
        var.set_var_chunk_cache(size=0)
        var.setncatts({"_Encoding": "utf-8", **export.PHASE_ATTRS})
        var[0 : t.size] = _chars(ph)
        self.written = t.size

    # ----------------------------------------------------------------- the end
    def close(self, sol: Solution) -> Path:
        """Write the last samples, the contact records (along ``contact``) and the attributes (metrics, provenance);
        rename the file to its path."""
        self._flush(whole_chunks=False)
        if self.nc is None:  # no sample at all (a run refused at its start): the variables, empty
            self._write(np.empty(0), np.empty(0, dtype=f"U{PHASE_WIDTH}"), {})
        nc = self.nc
        fields = export.contact_fields(sol)
        nc.createDimension("contact", len(sol.contacts))
        var = nc.createVariable("contact", "i8", ("contact",))
        var[:] = np.arange(len(sol.contacts))
        var.setncatts({"long_name": "Contact index"})
        for name, (units, long_name, values) in fields.items():
            var = nc.createVariable(name, "f8", ("contact",), fill_value=np.nan)
            var[:] = values
            var.setncatts({"units": units, "long_name": long_name})
        nc.setncatts(export.global_attrs(sol))
        nc.close()
        self.nc = None
        self._atomic.__exit__(None, None, None)
        return self.path

    def abort(self) -> None:
        """Remove the temporary file (the run did not finish)."""
        if self.nc is not None:
            self.nc.close()
            self.nc = None
        self._atomic.__exit__(RuntimeError, None, None)


def _chars(names: np.ndarray) -> np.ndarray:
    import netCDF4

    return netCDF4.stringtochar(np.asarray(names).astype(f"S{PHASE_WIDTH}"))


__all__ = ["PHASE_WIDTH", "SampleFile"]
