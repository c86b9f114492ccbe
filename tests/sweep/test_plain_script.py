"""``flexbeam.sweep`` on its local cluster from a plain script: no ``if __name__ == "__main__":`` needed.

Dask starts its local workers by "spawn", which runs the parent's main module again in each new process; a script
that sweeps at module level used to start a sweep inside every worker, and the cluster failed with ~200 lines
of tracebacks ending in "RuntimeError: Nanny failed to start.".  The workers now start without the script
(:func:`flexbeam.sweep.cluster.workers_skip_main`).
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent(
    """
    import sys
    print("script runs as", __name__, flush=True)
    import flexbeam as fb

    ds = fb.sweep(
        "seed-experiment",
        grid={"contact.restitution": [0.6, 0.8]},
        overrides={"model.modes": 2, "solver.t_end": 0.002},
        workers=1,
    )
    print("status", *[str(s) for s in ds["status"].values])
    print("file restored", __file__ == sys.argv[0], flush=True)
    """
)


@pytest.mark.parametrize("as_module", [False, True], ids=["python script.py", "python -m script"])
def test_sweep_at_module_level_of_a_plain_script_runs(tmp_path, as_module):
    (tmp_path / "plain_sweep.py").write_text(SCRIPT)
    target = ["-m", "plain_sweep"] if as_module else [str(tmp_path / "plain_sweep.py")]
    # a 2-case sweep on one local worker takes ~3 s (cluster start-up included); 300 s only bounds a hang
    r = subprocess.run(
        [sys.executable, *target], cwd=tmp_path, capture_output=True, text=True, timeout=300, check=False
    )
    assert r.returncode == 0, r.stderr[-3000:]
    lines = r.stdout.splitlines()
    assert lines.count("script runs as __main__") == 1 and not any("__mp_main__" in ln for ln in lines), lines
    assert "status success success" in lines
    assert "file restored True" in lines
    assert "Traceback" not in r.stderr and "Nanny failed" not in r.stderr, r.stderr[-3000:]
