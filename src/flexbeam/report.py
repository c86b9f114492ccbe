"""Files written for a run: result.nc, summary.json and the two figures (all atomically)."""

from __future__ import annotations

import json
from pathlib import Path

from .parameters.case import Case
from .parameters.io import reference_data
from .solution import Solution, _jsonable, write_text_atomic


def write_run_outputs(sol: Solution, case: Case, out: str | Path) -> dict[str, Path]:
    """Write ``result.nc``, ``summary.json``, ``contact_force.png`` and ``normal_velocity.png``."""
    from .plotting import plot_contact_force, plot_normal_velocity

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    reference = reference_data(case.name)
    summary = {"metrics": sol.metrics(), "provenance": sol.provenance, "reference": reference,
               "contacts": [vars(ev) for ev in sol.contacts]}
    files = {
        "result": sol.to_netcdf(out / "result.nc"),
        "summary": write_text_atomic(out / "summary.json", json.dumps(_jsonable(summary), indent=2)),
        "contact_force": plot_contact_force([sol], out / "contact_force.png", reference,
                                            f"{case.name}: contact force ({sol.method.upper()})"),
        "normal_velocity": plot_normal_velocity([sol], out / "normal_velocity.png", reference,
                                                f"{case.name}: normal velocity of P ({sol.method.upper()})"),
    }
    return files
