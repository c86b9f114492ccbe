"""The public namespace: ``dir()`` of flexbeam and of each of its packages shows its public API (``__all__``), not
the helper names its ``__init__`` binds (``annotations``, ``Any``, ``TYPE_CHECKING``, private aliases).

Submodules are not listed (``flexbeam.results.solution``, ``flexbeam.errors``, ``flexbeam.results.metrics``,
``flexbeam.schemas``, ...): a user imports them by name.  A package without ``__all__`` (``flexbeam.model``,
``flexbeam.methods``, ...) is only a folder of submodules: its ``dir()`` may show the submodules imported so far,
and nothing else.
"""

from __future__ import annotations

import importlib
import pkgutil
import types

import pytest

import flexbeam


def is_dunder(name: str) -> bool:
    return name.startswith("__") and name.endswith("__")


PACKAGES = sorted(
    ["flexbeam"]
    + [m.name for m in pkgutil.walk_packages(flexbeam.__path__, "flexbeam.", onerror=lambda _: None) if m.ispkg]
)


def test_dir_flexbeam_is_its_public_api():
    names = {n for n in dir(flexbeam) if not is_dunder(n)}
    assert names == {n for n in flexbeam.__all__ if not is_dunder(n)}
    assert {"annotations", "Any", "TYPE_CHECKING", "_calibrate_module", "_sweep_module"}.isdisjoint(dir(flexbeam))
    assert {"simulate", "sweep", "calibrate", "load_case", "Case", "ParameterError"} <= names


def test_the_walk_finds_the_packages():
    assert {"flexbeam.sweep", "flexbeam.calibrate", "flexbeam.parameters", "flexbeam.schemas"} <= set(PACKAGES)


@pytest.mark.parametrize("name", PACKAGES)
def test_dir_of_every_package_is_its_all_or_its_submodules(name):
    package = importlib.import_module(name)
    names = {n for n in dir(package) if not is_dunder(n)}
    if hasattr(package, "__all__"):
        assert names == {n for n in package.__all__ if not is_dunder(n)}
        assert all(hasattr(package, n) for n in package.__all__), [
            n for n in package.__all__ if not hasattr(package, n)
        ]
    else:
        assert all(isinstance(getattr(package, n), types.ModuleType) for n in names), names
