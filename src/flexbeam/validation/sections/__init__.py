"""The sections of the validation report, in the order of the page.

Each section is a function ``(reduced, figdir) -> Section`` that runs flexbeam and its
reference and fills the rows (``reduced``: the fast form; ``figdir``: where to write
figures, or None for none).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..._namespace import public_dir
from ..report import Section
from .frames import section_frames
from .frequencies import section_roots, section_rotating
from .methods import section_ccm, section_imm, section_support
from .models import section_energy, section_fem, section_kane
from .obstacles import section_obstacles
from .rigid import LAW_NAMES, section_hertz, section_pendulum, section_restitution

SECTIONS: dict[str, Callable[[bool, Path | None], Section]] = {
    "roots": section_roots,
    "rotating": section_rotating,
    "pendulum": section_pendulum,
    "hertz": section_hertz,
    "restitution": section_restitution,
    "imm": section_imm,
    "ccm": section_ccm,
    "support": section_support,
    "obstacles": section_obstacles,
    "fem": section_fem,
    "frames": section_frames,
    "kane": section_kane,
    "energy": section_energy,
}

__all__ = [
    "LAW_NAMES",
    "SECTIONS",
    "section_ccm",
    "section_energy",
    "section_fem",
    "section_obstacles",
    "section_frames",
    "section_hertz",
    "section_imm",
    "section_kane",
    "section_pendulum",
    "section_restitution",
    "section_roots",
    "section_rotating",
    "section_support",
]

__dir__ = public_dir(globals())
