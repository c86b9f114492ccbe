"""Case parameters: validated sections, built-in presets and TOML input/output."""

from .._namespace import public_dir
from .case import CONTACT_LAWS, Beam, Case, Contact, Drive, Hub, Initial, Model, Obstacle, Output, Solver, Support
from .io import builtin_cases, dump_case, load_case, parse_overrides
from .references import reference_data

__all__ = [
    "CONTACT_LAWS",
    "Beam",
    "Case",
    "Contact",
    "Drive",
    "Hub",
    "Initial",
    "Model",
    "Obstacle",
    "Output",
    "Solver",
    "Support",
    "builtin_cases",
    "dump_case",
    "load_case",
    "parse_overrides",
    "reference_data",
]

__dir__ = public_dir(globals())
