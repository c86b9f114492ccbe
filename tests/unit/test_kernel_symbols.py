"""The compiled kernels call no elementary function of the C library whose bits depend on the machine.

glibc picks FMA/AVX2 variants of exp, sin, cos, pow, log, ... by CPU; the kernels use detmath*.c instead
(docs/reproducibility.md).  What the built extension still takes from the C library must be exact on every IEEE 754
machine: sqrt, fabs, fmin/fmax, ldexp, rounding.  The undefined symbols of the shared object say what it calls.
"""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest

from flexbeam.kernels import _core

#: C library functions whose results IEEE 754 (or their definition) fixes exactly
EXACT = {"sqrt", "fabs", "fmax", "fmin", "ldexp", "frexp", "scalbn", "lround", "lrint", "floor", "ceil", "trunc",
         "rint", "nearbyint", "round", "copysign", "fmod", "modf"}  # fmt: skip
#: elementary functions a kernel must not take from libm
FORBIDDEN = {"sin", "cos", "tan", "sincos", "exp", "exp2", "expm1", "log", "log2", "log10", "log1p", "pow", "cbrt",
             "atan", "atan2", "asin", "acos", "sinh", "cosh", "tanh", "hypot", "tgamma", "lgamma", "erf"}  # fmt: skip


@pytest.mark.skipif(sys.platform != "linux" or shutil.which("nm") is None, reason="needs nm and an ELF build")
def test_kernels_take_no_transcendental_function_from_libm():
    out = subprocess.run(["nm", "-D", "--undefined-only", _core.__file__], capture_output=True, text=True, check=True)
    names = {line.split()[-1].split("@")[0] for line in out.stdout.splitlines() if line.strip()}
    forbidden = {f + s for f in FORBIDDEN for s in ("", "f", "l")} & names
    assert not forbidden, f"the kernels call libm's {sorted(forbidden)}: use detmath.h"
    assert "sqrt" in names or names & EXACT  # the scan sees the C library calls at all
