"""Reading a result for an animation: :class:`History`, the samples of the hub angle, the modal coordinates and the
contact force (and, with several contact pairs or a contact anywhere, each pair's force and contact point), the
contact intervals and the case, from a :class:`~flexbeam.results.solution.Solution`, its
:meth:`~flexbeam.results.solution.Solution.to_xarray` dataset or a saved ``result.nc``.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ...errors import ParameterError

if TYPE_CHECKING:
    from ...parameters.case import Case
    from ...results.solution import Solution


@dataclass
class History:
    """What an animation needs of a result: samples of the hub angle, the modal coordinates and the contact
    force, the contact intervals, and the case.

    ``pair_force`` and ``pair_position`` (time x pair: each pair's contact force [N] and the material coordinate
    of its contact point [m]) are there when the result has per-pair arrays (several contact pairs or a contact
    anywhere), else None; ``force`` is the first pair's force.  ``centre`` (time x 2) is a free beam's frame origin
    (the result's ``centre_of_mass``), else None.
    """

    time: np.ndarray
    phi: np.ndarray
    q: np.ndarray
    force: np.ndarray
    support: np.ndarray | None
    contacts: list[tuple[float, float]]
    case: Case
    label: str
    pair_force: np.ndarray | None = None
    pair_position: np.ndarray | None = None
    centre: np.ndarray | None = None

    @classmethod
    def from_solution(cls, sol: Solution, case: Case | None = None) -> History:
        """The arrays and contact log of a :class:`~flexbeam.results.solution.Solution`."""
        case = case if case is not None else _case_from_toml(sol.provenance.get("case_toml"))
        support = sol.arrays.get("support_displacement")
        pair_force, pair_position = (sol.arrays.get(name) for name in ("pair_contact_force", "pair_contact_position"))
        return cls(
            np.asarray(sol.time, float),
            np.asarray(sol["theta"], float),
            np.asarray(sol["q"], float),
            np.asarray(sol["contact_force"], float),
            None if support is None else np.asarray(support, float),
            [(c.onset, c.end) for c in sol.contacts],
            case,
            f"{case.name} [{sol.method}]",
            _pair_array(pair_force, sol.time.size),
            _pair_array(pair_position, sol.time.size),
            _pair_array(sol.arrays.get("centre_of_mass"), sol.time.size),
        )

    @classmethod
    def from_dataset(cls, ds: Any, case: Case | None = None) -> History:
        """The variables of a result dataset (:meth:`~flexbeam.results.solution.Solution.to_xarray`, or
        ``result.nc``)."""
        for name in ("time", "theta", "q", "contact_force"):
            if name not in ds.variables:
                raise ParameterError(f"result: the dataset has no variable '{name}' (not a flexbeam result)")
        case = case if case is not None else _case_from_toml(ds.attrs.get("case_toml"))
        onset = np.asarray(ds["contact_onset"].values, float) if "contact_onset" in ds.variables else np.empty(0)
        end = (
            np.asarray(ds["contact_end"].values, float)
            if "contact_end" in ds.variables
            else np.full_like(onset, np.nan)
        )
        support = np.asarray(ds["support_displacement"].values, float) if "support_displacement" in ds else None
        method = str(ds.attrs.get("method", ""))
        n = ds["time"].size
        pair_arrays = [
            _pair_array(np.asarray(ds[name].values, float) if name in ds.variables else None, n)
            for name in ("pair_contact_force", "pair_contact_position", "centre_of_mass")
        ]
        return cls(
            np.asarray(ds["time"].values, float),
            np.asarray(ds["theta"].values, float),
            np.asarray(ds["q"].values, float).reshape(ds["time"].size, -1),
            np.asarray(ds["contact_force"].values, float),
            support,
            [(float(a), float(b)) for a, b in zip(onset, end)],
            case,
            f"{case.name} [{method}]",
            *pair_arrays,
        )

    @classmethod
    def load(cls, result: Solution | Any | str | Path, case: Case | None = None) -> History:
        """From a Solution, an :class:`xarray.Dataset` or the path of a ``result.nc``."""
        if isinstance(result, (str, Path)):
            import xarray as xr

            path = Path(result)
            if not path.is_file():
                raise ParameterError(f"result: no such file '{path}'")
            try:
                with xr.open_dataset(path) as ds:
                    data = ds.load()
            except (OSError, ValueError) as exc:
                raise ParameterError(f"result: cannot read '{path}' as NetCDF: {_one_line(exc)}") from None
            return cls.from_dataset(data, case)
        if hasattr(result, "arrays") and hasattr(result, "contacts"):
            return cls.from_solution(result, case)
        return cls.from_dataset(result, case)


def _pair_array(values: Any, samples: int) -> np.ndarray | None:
    """A per-pair (or per-axis) array as (time, pair) floats, or None when the result has none."""
    if values is None:
        return None
    return np.asarray(values, float).reshape(samples, -1)


def _one_line(message: object) -> str:
    return str(message).replace("\r", " ").replace("\n", " ")


def _case_from_toml(text: Any) -> Case:
    from ...parameters.io import load_case

    if not isinstance(text, str) or not text:
        raise ParameterError("result: it records no case (provenance 'case_toml'); pass case=")
    return load_case(tomllib.loads(text))
