"""What ``dir()`` shows of flexbeam's packages: their public names, ``__all__``, and nothing else."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


def public_dir(namespace: dict[str, Any]) -> Callable[[], list[str]]:
    """A module ``__dir__`` (PEP 562) for the package whose globals are ``namespace``: its ``__all__`` and its
    dunders, not the helper names its ``__init__`` binds (``annotations``, ``Any``, ``TYPE_CHECKING``, private
    aliases) nor its submodules, which stay importable by name (``import flexbeam.results.solution``).

    Use as the last line of an ``__init__``: ``__dir__ = public_dir(globals())``.
    """

    def __dir__() -> list[str]:
        return sorted({*namespace["__all__"], *(k for k in namespace if k.startswith("__") and k.endswith("__"))})

    return __dir__
