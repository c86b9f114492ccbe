"""Files written atomically, output directories checked before a run, and numbers made strict JSON."""

from __future__ import annotations

import contextlib
import errno
import json
import math
import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError


class atomic_path:
    """Context manager giving a temporary path next to ``path``, renamed on success.  A ``path`` that is a directory
    is refused before anything is written (IsADirectoryError, as ``open`` would); the temporary file is removed
    whenever the file does not arrive, the rename's own failure included (it was left beside the target), and so are
    the directories made for it that are still empty (an interrupted streamed run left its empty --out)."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)

    def __enter__(self) -> Path:
        if self.path.is_dir():
            raise IsADirectoryError(errno.EISDIR, "is a directory, not a file to write", str(self.path))
        self.made = [p for p in (self.path.parent, *self.path.parent.parents) if not os.path.lexists(p)]
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd, name = tempfile.mkstemp(prefix=f".{self.path.name}.", dir=self.path.parent)
        os.close(fd)
        self.tmp = Path(name)
        return self.tmp

    def __exit__(self, exc_type, exc, tb) -> None:
        if exc_type is not None:
            self._undo()
            return
        try:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(self.tmp, 0o666 & ~umask)
            os.replace(self.tmp, self.path)
        except BaseException:
            self._undo()
            raise

    def _undo(self) -> None:
        self.tmp.unlink(missing_ok=True)
        for d in self.made:  # (innermost first; one that holds anything stays)
            with contextlib.suppress(OSError):
                d.rmdir()


def check_output_dir(path: str | Path, field: str, files: tuple[str, ...] = (), dirs: tuple[str, ...] = ()) -> Path:
    """``path`` as a directory outputs can be written to: one already, or one that can be made (the nearest of its
    ancestors that exists a directory this process may write in), in which none of the ``files`` to be written is a
    directory and none of the ``dirs`` a file.  Otherwise a one-line :class:`~flexbeam.errors.ParameterError` naming
    ``field``, before anything runs (a run's outputs were written after it, and a file in the way ended the run in a
    traceback: ``FileExistsError``, ``IsADirectoryError``)."""
    path = Path(path)
    try:
        _check_dir(path, field, files, dirs)
    except OSError as exc:  # the path itself cannot be examined (a name over the file system's length, ...)
        raise ParameterError(f"{field}: '{path}' cannot be used ({exc.strerror or exc})") from None
    return path


def _check_dir(path: Path, field: str, files: tuple[str, ...], dirs: tuple[str, ...]) -> None:
    """The checks of :func:`check_output_dir` (raising OSError where the system cannot examine the path)."""
    if path.is_symlink() and not path.exists():
        raise ParameterError(f"{field}: '{path}' is a symbolic link to '{os.readlink(path)}', which does not exist")
    if path.exists() and not path.is_dir():
        raise ParameterError(f"{field}: '{path}' exists and is not a directory")
    for name in files:
        if (path / name).is_dir():
            raise ParameterError(f"{field}: '{path / name}' is a directory, where the file {name} is written")
    for name in dirs:
        if (path / name).exists() and not (path / name).is_dir():
            raise ParameterError(f"{field}: '{path / name}' is a file, where the directory {name}/ is written")
    nearest = path if path.exists() else next((p for p in path.absolute().parents if p.exists()), Path("/"))
    if not nearest.is_dir():
        raise ParameterError(f"{field}: '{path}' lies under '{nearest}', which is a file, not a directory")
    if not os.access(nearest, os.W_OK | os.X_OK):
        raise ParameterError(f"{field}: cannot write in '{nearest}' (permission denied)")
    _probe_write(path, field)


def _probe_write(path: Path, field: str) -> None:
    """Make the directories of ``path`` that do not exist and a file in it, then remove them again: whether the
    system lets outputs be written there, which no test of the path itself tells (a directory under ``/proc``, a name
    over the file system's length, a broken symbolic link among its parents: each ended a finished run in a
    traceback when its outputs were written).  Nothing is left behind, so a command refused later leaves no empty
    directory."""
    missing = []
    p = path.absolute()
    while not os.path.lexists(p):
        missing.append(p)
        p = p.parent
    made: list[Path] = []
    name = None
    try:
        for d in reversed(missing):
            d.mkdir()
            made.append(d)
        fd, name = tempfile.mkstemp(prefix=".flexbeam-probe.", dir=path)
        os.close(fd)
    except OSError as exc:
        what = "make the directory" if len(made) < len(missing) else "write in"
        raise ParameterError(f"{field}: cannot {what} '{path}' ({exc.strerror or exc})") from None
    finally:  # (also when interrupted: Ctrl-C or SIGTERM here left the probe and its directories)
        with contextlib.suppress(OSError):
            if name is not None:
                os.unlink(name)
        for d in reversed(made):
            with contextlib.suppress(OSError):
                d.rmdir()


def file_stamp(path: str | Path) -> tuple[int, int, int]:
    """(inode, size, modification time [ns]) of the file at ``path``: what changes when another file is written over
    it (an atomic write renames a new file onto the path: a new inode)."""
    st = os.stat(path)
    return st.st_ino, st.st_size, st.st_mtime_ns


def write_text_atomic(path: str | Path, text: str) -> Path:
    """Write text to ``path`` atomically."""
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path


def jsonable(obj: Any) -> Any:
    """``obj`` with numpy scalars as Python numbers and non-finite floats as None (strict JSON)."""
    if isinstance(obj, dict):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def metrics_json(metrics: dict[str, Any]) -> str:
    """JSON text of metrics (NaN -> null)."""
    return json.dumps(jsonable(metrics), indent=2)
