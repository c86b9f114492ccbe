"""Build of flexbeam's compiled kernels (everything else is in pyproject.toml).

The kernels are plain C99 (src/flexbeam/kernels/src), compiled ahead of time by pip at install: no
run-time compilation, and the same floating-point results on every x86-64 machine (no -march=native,
no FMA contraction: -ffp-contract=off).
"""

import sys
from glob import glob

from setuptools import Extension, setup

ARGS = [] if sys.platform == "win32" else ["-std=c99", "-O3", "-ffp-contract=off", "-fno-fast-math"]

setup(
    ext_modules=[
        Extension(
            "flexbeam.kernels._core",
            sources=sorted(glob("src/flexbeam/kernels/src/*.c")),
            include_dirs=["src/flexbeam/kernels/src"],
            depends=sorted(glob("src/flexbeam/kernels/src/*.h")),
            extra_compile_args=ARGS,
        )
    ]
)
