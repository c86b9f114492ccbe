"""flexbeam: impact dynamics of flexible beams with large overall motion.

Five lines to a result::

    import flexbeam as fb
    case = fb.load_case("seed-experiment")
    sol = fb.simulate(case, method="ccfm")
    print(sol.metrics())
    sol.to_xarray().to_netcdf("result.nc")

Heavy libraries (xarray, matplotlib, dask) are imported only when used.

Sweeps and calibration::

    ds = fb.sweep(case, grid={"contact.restitution": [0.6, 0.8]}, out="store")
    fit = fb.calibrate(case, fit=["contact.stiffness"], features={"peak_force": 584.0})
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

# ``sweep`` and ``calibrate`` are both submodules and functions of the package.  The
# submodules are imported here (they are light: Dask, xarray and scipy.optimize are
# imported when used) so that the functions defined below are what ``fb.sweep`` and
# ``fb.calibrate`` stay bound to: importing a submodule later would otherwise rebind
# the package attribute to the module.
from . import calibrate as _calibrate_module
from . import sweep as _sweep_module
from ._namespace import public_dir
from .errors import FlexbeamError, ModelError, ParameterError, SolverError
from .parameters import Case, builtin_cases, dump_case, load_case
from .version import __version__
from .views import accessor as _views  # noqa: F401 - registers Solution.plot, .animate and the notebook display

if TYPE_CHECKING:
    from pathlib import Path

    import xarray as xr

    from .calibrate import Calibration
    from .results.solution import Solution


def simulate(
    case: Case | str,
    method: str = "ccfm",
    stream: str | Path | None = None,
    keep_interrupted: bool = False,
    **overrides: Any,
) -> Solution:
    """Simulate a case with an impact method (``"ccfm"``, ``"ccm"``, ``"imm"``).

    Keyword overrides use double underscores for dots:
    ``simulate("seed-experiment", model__modes=4)``.  ``stream``: a result file the run writes as it goes, in a
    memory that does not grow with the run (:func:`flexbeam.simulation.simulate`).  ``keep_interrupted``: Ctrl-C
    (in the main thread) ends the run where it is and returns what was computed, ``status = "interrupted"``,
    instead of raising KeyboardInterrupt; a second Ctrl-C raises at once (:func:`flexbeam.interrupt.ctrl_c_flag`).
    """
    from .simulation import simulate as _simulate

    if not isinstance(keep_interrupted, bool):
        raise ParameterError(f"keep_interrupted: True or False (got {keep_interrupted!r})")
    if overrides:
        case = load_case(case, {k.replace("__", "."): v for k, v in overrides.items()})
    elif not isinstance(case, Case):
        case = load_case(case)
    from .interrupt import keeping_interrupted

    with keeping_interrupted(keep_interrupted) as hit:
        return _simulate(case, method, stream=stream, stop=hit.cause if hit is not None else None)


def sweep(case: Case | str, **kwargs: Any) -> xr.Dataset:
    """Parameter sweep on Dask; see :func:`flexbeam.sweep.sweep`.

    ``fb.sweep("seed-experiment", grid={"contact.restitution": [0.6, 0.8]}, out="store")``
    """
    return _sweep_module.sweep(case, **kwargs)


def calibrate(case: Case | str, **kwargs: Any) -> Calibration:
    """Least-squares fit of case parameters to measurements; see :func:`flexbeam.calibrate.calibrate`.

    ``fb.calibrate("seed-experiment", fit=["contact.stiffness"], features={"peak_force": 584})``
    """
    return _calibrate_module.calibrate(case, **kwargs)


__all__ = [
    "Case",
    "FlexbeamError",
    "ModelError",
    "ParameterError",
    "SolverError",
    "builtin_cases",
    "calibrate",
    "dump_case",
    "load_case",
    "simulate",
    "sweep",
    "__version__",
]

__dir__ = public_dir(globals())
