"""Runs shared by the report sections: preset cases with overrides, a simulation, the rigid rod."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..parameters.case import Case
    from ..results.solution import Solution


def preset(name: str, **overrides: Any) -> Case:
    """Built-in case ``name`` with overrides given as ``a__b=value`` for the dotted key ``a.b``."""
    from ..parameters import load_case

    return load_case(name, {k.replace("__", "."): v for k, v in overrides.items()})


def seed(**overrides: Any) -> Case:
    """The seed experiment with overrides (see :func:`preset`)."""
    return preset("seed-experiment", **overrides)


def simulate(case: Case, method: str = "ccfm") -> Solution:
    """Run ``case`` with an impact method (``"fem"`` too)."""
    from ..simulation import simulate as run

    return run(case, method)


def rod_mass_and_inertia(case: Case) -> tuple[float, float]:
    """(mass, J_O) of the uniform rod about O (textbook m L^2 / 3, no hub)."""
    m = case.beam.line_density * case.beam.length
    return m, m * case.beam.length**2 / 3.0 + case.hub.inertia


def modes_label(n: int) -> str:
    """'1 mode', '2 modes', ..."""
    return f"{n} mode" if n == 1 else f"{n} modes"
