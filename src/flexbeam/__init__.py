"""flexbeam: impact dynamics of flexible beams with large overall motion.

Five lines to a result::

    import flexbeam as fb
    case = fb.load_case("seed-experiment")
    sol = fb.simulate(case, method="ccfm")
    print(sol.metrics())
    sol.to_xarray().to_netcdf("result.nc")

Heavy libraries (xarray, matplotlib, dask) are imported only when used.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .errors import FlexbeamError, ModelError, ParameterError, SolverError
from .parameters import Case, builtin_cases, dump_case, load_case

__version__ = "0.1.0"

if TYPE_CHECKING:
    from .solution import Solution


def simulate(case: Case | str, method: str = "ccfm", **overrides: Any) -> Solution:
    """Simulate a case with an impact method (``"ccfm"``, ``"ccm"``, ``"imm"``).

    Keyword overrides use double underscores for dots:
    ``simulate("seed-experiment", model__modes=4)``.
    """
    from .simulation import simulate as _simulate

    if overrides:
        case = load_case(case, {k.replace("__", "."): v for k, v in overrides.items()})
    elif not isinstance(case, Case):
        case = load_case(case)
    return _simulate(case, method)


__all__ = [
    "Case",
    "FlexbeamError",
    "ModelError",
    "ParameterError",
    "SolverError",
    "builtin_cases",
    "dump_case",
    "load_case",
    "simulate",
    "__version__",
]
