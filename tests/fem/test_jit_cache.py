"""Every edit to an FE source takes effect (``flexbeam.fem.jit``): Numba's on-disk cache checks a kernel against its
own file only, while the kernel's compiled code holds the kernels it calls from other files."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import flexbeam
from flexbeam.fem import jit

# d/dxi of an element's centre line at its middle (gap._centre_line): the chord dx of element.element_chord, 1 m
PROBE = (
    "import numpy as np\n"
    "from flexbeam.fem.gap import _centre_line\n"
    "print(_centre_line(np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0]), 1.0, 0.5)[1][0])\n"
)


@pytest.mark.slow
def test_an_edit_to_the_element_reaches_the_cached_kernels_that_call_it(tmp_path):
    """A copy of the package, its kernels cached in a fresh NUMBA_CACHE_DIR; then element.py alone is edited (the
    chord doubled) and gap.py's kernel, cached and unchanged, must see it.  Before the cache was keyed on all the FE
    sources the second run printed the old 1.0.  Two subprocesses each compiling three small kernels cold (6 s
    together measured); each is given 120 s."""
    pkg = tmp_path / "pkg"
    shutil.copytree(
        Path(flexbeam.__file__).parent, pkg / "flexbeam", ignore=shutil.ignore_patterns("__pycache__", "*.nb[ic]")
    )
    cache = tmp_path / "numba-cache"
    env = {**os.environ, "PYTHONPATH": str(pkg), "NUMBA_CACHE_DIR": str(cache)}

    def probe() -> float:
        out = subprocess.run(
            [sys.executable, "-c", PROBE], env=env, capture_output=True, text=True, timeout=120, check=True
        )
        return float(out.stdout)

    assert probe() == 1.0
    assert list(cache.rglob("*.nbi")), "the kernels were not cached"
    element = pkg / "flexbeam" / "fem" / "element.py"
    text, chord = element.read_text(), "    dx = xe[3] - xe[0]\n    dy = xe[4] - xe[1]\n    ell = math.sqrt("
    assert text.count(chord) == 1
    element.write_text(text.replace(chord, chord.replace("xe[3] - xe[0]", "2.0 * (xe[3] - xe[0])")))
    assert probe() == 2.0


def test_every_fe_kernel_is_compiled_through_fem_jit():
    """A kernel decorated with numba's own ``njit(cache=True)`` would be cached against its file alone."""
    for path in sorted(jit.FEM_DIR.glob("*.py")):
        if path.name != "jit.py":
            assert "njit" not in path.read_text(), f"{path.name}: use flexbeam.fem.jit.fem_jit"


def test_the_cache_directory_is_keyed_on_the_sources_and_numba_is_left_as_it_was():
    import numba

    before = numba.config.CACHE_DIR
    jit.fem_jit(lambda x: x + 1)
    assert numba.config.CACHE_DIR == before
    assert Path(jit.cache_dir()).name == f"flexbeam-fem-{jit.source_key()}"
