"""Validation report: flexbeam against independent references, written to ``docs/validation.md``.

Run ``python -m flexbeam.validation [--reduced] [--out docs]``.  Every section computes a
reference (closed form, published value, independent series or solver) and flexbeam's
value of the same quantity, the error and its stated tolerance, and writes one Markdown
table per reference plus figures (``<out>/figures/*.png``).  ``--reduced`` runs smaller
versions of the expensive sections (fewer modes, shorter runs; under a minute in all) and
is what ``tests/validation/test_report.py`` runs, so that the page cannot drift from the code.

* :mod:`~flexbeam.validation.report` -- :class:`Row`, :class:`Section` and the Markdown page;
* :mod:`~flexbeam.validation.references` -- the independent references (rotating-beam
  power series, quasi-static spin-up deflection, exact restitution relations, the
  two-mass chain, published values);
* :mod:`~flexbeam.validation.sections` -- one function per section, grouped by topic;
* :mod:`~flexbeam.validation.runs` -- the preset runs the sections share;
* :mod:`~flexbeam.validation.runner` -- :func:`run_validation` and the command line.
"""

from __future__ import annotations

from .._namespace import public_dir
from .references import (
    HERTZ_DURATION_CONSTANT,
    PUBLISHED_ROOTS,
    ROTATING_DATA,
    frequency_determinant,
    hunt_crossley_restitution,
    kane_hub_rates,
    kelvin_voigt_restitution,
    law_restitution,
    published_rotating_values,
    quasi_static_tip,
    reference_flapwise,
    series_tip,
    two_mass_chain,
)
from .report import Row, Section, render
from .runner import main, run_validation
from .sections import LAW_NAMES, SECTIONS

__all__ = [
    "HERTZ_DURATION_CONSTANT",
    "LAW_NAMES",
    "PUBLISHED_ROOTS",
    "ROTATING_DATA",
    "SECTIONS",
    "Row",
    "Section",
    "frequency_determinant",
    "hunt_crossley_restitution",
    "kane_hub_rates",
    "kelvin_voigt_restitution",
    "law_restitution",
    "main",
    "published_rotating_values",
    "quasi_static_tip",
    "reference_flapwise",
    "render",
    "run_validation",
    "series_tip",
    "two_mass_chain",
]

__dir__ = public_dir(globals())
