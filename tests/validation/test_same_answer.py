"""The same answer on every machine: the modal model's runs do not depend on the BLAS kernel, numpy's SIMD level or
the C library's variant of the elementary functions.

numpy picks the OpenBLAS kernel behind ``@`` and ``linalg`` (``OPENBLAS_CORETYPE`` forces one) and its own SIMD
loops (``NPY_DISABLE_CPU_FEATURES`` limits them) by CPU, and glibc its FMA/AVX2 variants of exp, sin, cos and pow
(``GLIBC_TUNABLES`` masks them): on this machine each of these environments stands in for another machine.  Each
child process prints the digests of :data:`tests.validation.fingerprints.RUNS` (contact records, steps, final state,
metrics); every environment must print the same bits as the default one.  The expected values are not pinned: the
test compares environments of the same build with each other.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _cpu_flags() -> set[str]:
    try:
        text = Path("/proc/cpuinfo").read_text()
    except OSError:
        return set()
    for line in text.splitlines():
        if line.startswith("flags"):
            return set(line.split(":", 1)[1].split())
    return set()


def _numpy_dispatch() -> str:
    """numpy's dispatched (not baseline) SIMD features this CPU has: disabling them leaves the baseline loops."""
    try:
        from numpy._core import _multiarray_umath as mu
    except ImportError:  # numpy < 2
        from numpy.core import _multiarray_umath as mu
    return " ".join(f for f in mu.__cpu_dispatch__ if mu.__cpu_features__.get(f))


def environments() -> dict[str, dict[str, str]]:
    """Environments a CPU of this machine can run: OpenBLAS's Prescott kernel (SSE3, every x86-64), Haswell's
    (AVX2 + FMA, where the CPU has them), numpy's baseline loops only, glibc's libm without FMA/AVX2, one BLAS
    thread."""
    flags = _cpu_flags()
    envs = {"OPENBLAS_CORETYPE=Prescott": {"OPENBLAS_CORETYPE": "Prescott"}}
    if {"avx2", "fma"} <= flags:
        envs["OPENBLAS_CORETYPE=Haswell"] = {"OPENBLAS_CORETYPE": "Haswell"}
    disabled = _numpy_dispatch()
    if disabled:
        envs["NPY_DISABLE_CPU_FEATURES"] = {"NPY_DISABLE_CPU_FEATURES": disabled}
    envs["GLIBC_TUNABLES=-AVX2,-FMA"] = {"GLIBC_TUNABLES": "glibc.cpu.hwcaps=-AVX2,-FMA"}
    envs["OPENBLAS_NUM_THREADS=1"] = {"OPENBLAS_NUM_THREADS": "1"}
    return envs


def _fingerprints(extra: dict[str, str]) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES",
                                                            "GLIBC_TUNABLES", "OPENBLAS_NUM_THREADS")}  # fmt: skip
    env.update(extra)
    out = subprocess.run(
        [sys.executable, "-m", "tests.validation.fingerprints"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=True,
    )
    return json.loads(out.stdout)


@pytest.fixture(scope="module")
def reference() -> dict[str, str]:
    return _fingerprints({})


@pytest.mark.skipif(sys.platform != "linux", reason="the environment switches are those of Linux, glibc and OpenBLAS")
@pytest.mark.parametrize("name", list(environments()))
def test_every_run_gives_the_same_bits(name, reference):
    got = _fingerprints(environments()[name])
    assert set(got) == set(reference)
    differ = sorted(k for k in reference if got[k] != reference[k])
    assert not differ, f"under {name} these runs differ from the default environment: {differ}"
