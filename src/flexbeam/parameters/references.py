"""The published reference numbers shipped beside the built-in cases, and whether a case is the experiment they
were measured on (so that only such a case is scored against them)."""

from __future__ import annotations

import tomllib
from importlib import resources
from typing import Any

from .case import Case
from .io import PRESETS_PACKAGE, builtin_cases, get_dotted, load_case


def reference_data(name: str) -> dict[str, Any]:
    """Published reference numbers shipped beside a built-in case ({} if none).

    A calibrated variant (``NAME-calibrated``) shares the numbers of its base case ``NAME``.
    """
    for base in (name, name.removesuffix("-calibrated")):
        entry = resources.files(PRESETS_PACKAGE) / f"{base}.reference.toml"
        if entry.is_file():
            return tomllib.loads(entry.read_text(encoding="utf-8"))
    return {}


#: the fields that describe the experiment a preset's reference numbers were measured on (the beam and its hub, the
#: obstacles' geometry and material and where they are struck, the start, the joint and its drive, the base,
#: gravity); the others -- the contact law and its parameters, an obstacle's support (the sensor's compliance the
#: calibrated preset fits), the modes, the solver, the outputs -- are the model's choices a comparison is about
SET_UP = ("beam", "hub", "initial", "joint", "drive", "base", "model.gravity", "contact.position", "contact.side")
OBSTACLE_SET_UP = ("kind", "centre", "radius", "normal", "youngs_modulus", "poisson_ratio", "fixed_to")


def _set_up(case: Case) -> dict[str, Any]:
    """The :data:`SET_UP` and :data:`OBSTACLE_SET_UP` fields of ``case`` (:func:`get_dotted`)."""
    view: dict[str, Any] = {key: get_dotted(case, key) for key in SET_UP}
    view["obstacle"] = [getattr(case.obstacle, k) for k in OBSTACLE_SET_UP]
    view["obstacles"] = [
        ([getattr(o, k) for k in OBSTACLE_SET_UP], o.contact.position, o.contact.side) for o in case.obstacles
    ]
    return view


def reference_for(case: Case) -> dict[str, Any]:
    """:func:`reference_data` of ``case``'s name if ``case`` is the experiment they were measured on -- its
    set-up (:func:`_set_up`) that of the built-in case of that name -- else {} (a case named like a preset but with
    another beam, obstacle or start was scored against the preset's experiment: ``--set beam.length=1.5`` gave a
    597 % "error")."""
    reference = reference_data(case.name)
    if not reference or case.name not in builtin_cases():
        return {}
    return reference if _set_up(case) == _set_up(load_case(case.name)) else {}
