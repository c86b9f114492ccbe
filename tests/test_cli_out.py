"""``--out`` where no output can go: one line naming ``--out``, exit 2, before anything runs.

Every command wrote its outputs after its run, and an ``--out`` that was a file (or lay under one) ended the run
in a traceback (``FileExistsError``, ``NotADirectoryError``), the computed run lost; ``sweep`` alone checked.
"""

from __future__ import annotations

import contextlib
import io
from pathlib import Path

import pytest

from flexbeam.cli import main

SHAKER = str(Path(__file__).resolve().parent / "validation" / "data" / "shaker-stop.toml")
SHORT = ["-s", "solver.t_end=0.001"]


def _cli(args: list[str]) -> tuple[int, str, str]:
    """(exit code, stdout, stderr) of ``flexbeam ARGS`` in-process."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            main(args)
            code = 0
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 1
    return code, out.getvalue(), err.getvalue()


COMMANDS = {
    "run": ["run", "seed-experiment", *SHORT],
    "run --stream": ["run", "seed-experiment", "--stream", *SHORT],
    "compare": ["compare", "seed-experiment", "--methods", "ccfm", *SHORT],
    "sweep": ["sweep", "seed-experiment", "-g", "contact.restitution=0.5", "-w", "1", *SHORT],
    "calibrate": ["calibrate", "seed-experiment", "--fit", "contact.stiffness", "--features", "peak_force=584", *SHORT],
    "bifurcation": ["bifurcation", SHAKER, "--param", "base.frequency=10:12:2", "--periods", "3", "--discard", "1"],
}


@pytest.mark.parametrize("command", list(COMMANDS))
@pytest.mark.parametrize("where", ["a file", "under a file"])
def test_an_out_directory_that_cannot_be_one_is_refused_first(tmp_path, command, where):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    out = blocker if where == "a file" else blocker / "sub" / "dir"
    code, stdout, stderr = _cli([*COMMANDS[command], "--out", str(out)])
    lines = stderr.splitlines()
    assert code == 2 and stdout == "" and len(lines) == 1, (code, stderr)
    assert lines[0].startswith("error: --out: "), lines[0]
    assert ("exists and is not a directory" if where == "a file" else "which is a file, not a directory") in lines[0]
    assert blocker.read_text() == "not a directory"


def test_an_animation_file_is_refused_under_a_file_or_as_a_directory(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    for out, says in ((blocker / "movie.gif", "exists and is not a directory"), (tmp_path, "is a directory")):
        code, stdout, stderr = _cli(["animate", "seed-experiment", "--frames", "3", *SHORT, "--out", str(out)])
        assert code == 2 and stdout == "" and stderr.startswith("error: --out: ") and says in stderr, stderr


def test_an_out_directory_that_does_not_exist_yet_is_made(tmp_path):
    out = tmp_path / "new" / "deeper"
    code, _, stderr = _cli(["run", "seed-experiment", *SHORT, "--out", str(out)])
    assert code == 0, stderr
    assert (out / "result.nc").is_file() and (out / "summary.json").is_file()


@pytest.mark.parametrize(
    ("command", "blocked", "says"),
    [
        ("run", "result.nc", "is a directory, where the file result.nc is written"),
        ("run", "summary.json", "is a directory, where the file summary.json is written"),
        ("run --stream", "result.nc", "is a directory, where the file result.nc is written"),
        ("sweep", "sweep.json", "is a directory, where the file sweep.json is written"),
        ("sweep", "cases", "is a file, where the directory cases/ is written"),
    ],
)
def test_an_output_in_the_way_inside_out_is_refused_first(tmp_path, command, blocked, says):
    """A directory where a file is written (or a file where the sweep's cases/ goes) inside --out ended the command
    in a 48-line traceback, exit 1 -- for a run held in memory after the whole integration, with result.nc already
    written beside the failure."""
    out = tmp_path / "out"
    out.mkdir()
    if blocked == "cases":
        (out / blocked).write_text("x")
    else:
        (out / blocked).mkdir()
    code, stdout, stderr = _cli([*COMMANDS[command], "--out", str(out)])
    lines = stderr.splitlines()
    assert code == 2 and stdout == "" and len(lines) == 1, (code, stderr)
    # naming the option (a sweep's store named 'out', the Python argument, before)
    assert lines[0].startswith("error: --out: ") and says in lines[0], lines[0]
    assert sorted(p.name for p in out.iterdir()) == [blocked]  # nothing written
