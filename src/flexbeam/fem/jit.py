"""Numba compilation of the finite-element kernels, cached on disk under a key of all the FE sources.

Numba's cache (``cache=True``) checks each function against its own source file only, but a kernel's compiled
code includes the kernels it calls from other modules: after an edit to ``element.py`` alone, the cached
``assembly.py`` kernels would go on running the old element (a documented limitation of Numba, numba/numba#1833).
:func:`fem_jit` compiles like ``numba.njit(cache=True)`` into a cache directory named by a hash of every
``fem/*.py`` source, so that any edit to any of them makes every kernel compile afresh.

The directory is ``<root>/flexbeam-fem-<key>``, with ``root`` numba's ``NUMBA_CACHE_DIR`` if set, else this
package's ``__pycache__`` if writable, else ``$XDG_CACHE_HOME/flexbeam`` (``~/.cache/flexbeam``).  Numba's own
setting is restored after each decoration: other Numba users in the process are not affected.  Directories of
earlier keys are left in place (a shared ``NUMBA_CACHE_DIR`` may serve other checkouts).
"""

from __future__ import annotations

import functools
import hashlib
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numba

FEM_DIR = Path(__file__).resolve().parent


@functools.cache
def source_key() -> str:
    """SHA-256 (first 16 hex digits) of the names and contents of every ``*.py`` file of this package."""
    digest = hashlib.sha256()
    for path in sorted(FEM_DIR.glob("*.py")):
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def _writable(path: Path) -> bool:
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError:
        return False
    return os.access(path, os.W_OK)


@functools.cache
def cache_dir() -> str:
    """The cache directory of the FE kernels: ``<root>/flexbeam-fem-<source_key()>`` (see the module docstring)."""
    if numba.config.CACHE_DIR:
        root = Path(numba.config.CACHE_DIR)
    elif _writable(FEM_DIR / "__pycache__"):
        root = FEM_DIR / "__pycache__"
    else:
        root = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "flexbeam"
    return str(root / f"flexbeam-fem-{source_key()}")


def fem_jit(fn: Callable[..., Any]) -> Any:
    """``numba.njit(cache=True)(fn)`` cached in :func:`cache_dir` (numba picks a function's cache directory when it
    is decorated, from ``numba.config.CACHE_DIR``)."""
    saved = numba.config.CACHE_DIR
    numba.config.CACHE_DIR = cache_dir()
    try:
        return numba.njit(cache=True)(fn)
    finally:
        numba.config.CACHE_DIR = saved
