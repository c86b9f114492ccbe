"""The FE reference is independent of the modal model's equations: what it may import from it.

FE-vs-modal agreement can only catch an error in the modal contact force, gap or equations
if the finite-element package does not run them.  It may take from the modal side only the
case's inputs, interpreted alike on purpose: the contact set-up (where P is, where the obstacle stands, which
law with which stiffness: ``ContactSetup.from_case``), the contact law objects and their chi(e)
(``make_law``, ``ContactLaw``), the Hertz stiffness of the materials and the rigid Hertz
impact duration (used to size the contact step, not in the equations), and the joint's description: its kind
and its prescribed drive profile (``joint_of``, ``JointDrive``).  This test reads the import statements of every module.
"""

from __future__ import annotations

import ast
from pathlib import Path

import flexbeam.fem

FEM = Path(flexbeam.fem.__file__).resolve().parent
#: the modal model's packages and modules
MODAL = ("model", "contact", "integrate", "methods", "simulation")
ALLOWED = {
    "contact.setup": {"ContactSetup"},
    "contact.laws": {"ContactLaw", "make_law"},
    "contact.hertz": {"effective_modulus", "sphere_on_cylinder_stiffness", "rigid_hertz_impact"},
    "model.joints.drive": {"JointDrive"},
    "model.joints": {"joint_of"},
}


def _imports(path: Path) -> list[tuple[str, str]]:
    """(module relative to flexbeam, name) of every import in ``path``."""
    out = []
    for node in ast.walk(ast.parse(path.read_text("utf-8"))):
        if isinstance(node, ast.ImportFrom):
            if node.level == 2:  # from ..x import y
                module = node.module or ""
            elif node.level == 0 and (node.module or "").startswith("flexbeam."):
                module = node.module.removeprefix("flexbeam.")
            else:
                continue
            out += [(module, alias.name) for alias in node.names]
        elif isinstance(node, ast.Import):
            out += [(a.name.removeprefix("flexbeam."), "*") for a in node.names if a.name.startswith("flexbeam.")]
    return out


def test_fem_imports_from_the_modal_model_only_the_case_inputs():
    found = []
    for path in sorted(FEM.glob("*.py")):
        for module, name in _imports(path):
            if module.split(".")[0] in MODAL and name not in ALLOWED.get(module, set()):
                found.append(f"{path.name}: from {module} import {name}")
    assert not found, found


def test_the_check_sees_the_imports_it_guards(tmp_path):
    """The reader finds a forbidden import written in either style (the test can fail)."""
    probe = tmp_path / "probe.py"
    probe.write_text("from ..contact.laws import law_force\nimport flexbeam.model.kernels\n", "utf-8")
    assert _imports(probe) == [("contact.laws", "law_force"), ("model.kernels", "*")]
