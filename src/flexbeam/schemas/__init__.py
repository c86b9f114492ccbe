"""JSON Schemas (draft 2020-12) of flexbeam's machine-readable output, shipped as package data.

* ``run.schema.json`` -- the object that ``flexbeam run --json`` prints:
  :meth:`flexbeam.results.solution.Solution.metrics` as strict JSON (null where a value is not defined), with its
  ``pairs`` and ``events`` records (docs/usage.md, *The --json output*).

A program in any language can read the file from the installed package (``flexbeam/schemas/run.schema.json``);
from Python, :func:`run_schema` returns it as a dict, e.g. for ``jsonschema.validate(output, run_schema())``.
"""

from __future__ import annotations

import json
from importlib import resources
from typing import Any

from .._namespace import public_dir

__all__ = ["run_schema"]


def run_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the ``flexbeam run --json`` output."""
    return json.loads(resources.files(__name__).joinpath("run.schema.json").read_text(encoding="utf-8"))


__dir__ = public_dir(globals())
