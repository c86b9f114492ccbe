"""``--out`` where no output can go: one line naming ``--out``, exit 2, before anything runs.

Every command wrote its outputs after its run, and an ``--out`` that was a file (or lay under one) ended the run
in a traceback (``FileExistsError``, ``NotADirectoryError``), the computed run lost; ``sweep`` alone checked.
"""

from __future__ import annotations

import contextlib
import io
import os
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


def _unmakeable(tmp_path: Path, kind: str) -> Path:
    """An --out that passes every test of the path itself but where the system refuses to make or write a file."""
    if kind == "a broken symbolic link":
        link = tmp_path / "link"
        link.symlink_to(tmp_path / "nowhere" / "dir")
        return link
    if kind == "a name too long":
        return tmp_path / ("a" * 300)
    if not Path("/proc/self").is_dir():  # (Linux's process file system: no directory can be made in it)
        pytest.skip("no /proc")
    return Path("/proc/flexbeam-test/out")


@pytest.mark.parametrize("command", list(COMMANDS))
@pytest.mark.parametrize("kind", ["a broken symbolic link", "a name too long", "a directory under /proc"])
def test_an_out_directory_the_system_cannot_make_is_refused_first(tmp_path, command, kind):
    """A path that passed the checks of the path itself (no file in the way, a writable parent as far as access(2)
    tells) but that the system refuses -- under /proc, a broken symbolic link, a name over 255 bytes -- ended the
    command in a traceback, exit 1: ``run`` only after the whole integration, its run lost.  Now one line naming
    --out, exit 2, before the run, and nothing left behind."""
    out = _unmakeable(tmp_path, kind)
    before = sorted(p.name for p in tmp_path.iterdir())
    code, stdout, stderr = _cli([*COMMANDS[command], "--out", str(out)])
    lines = stderr.splitlines()
    assert code == 2 and stdout == "" and len(lines) == 1, (code, stderr)
    assert lines[0].startswith("error: --out: "), lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # the probe's directories removed again


def test_an_animation_file_where_none_can_be_written_is_refused(tmp_path):
    """``animate --out /proc/movie.gif``: its directory exists, but no file can be made in it."""
    if not Path("/proc/self").is_dir():
        pytest.skip("no /proc")
    code, stdout, stderr = _cli(["animate", "seed-experiment", "--frames", "3", *SHORT, "--out", "/proc/movie.gif"])
    assert code == 2 and stdout == "" and stderr.startswith("error: --out: cannot write in '/proc'"), stderr


def test_a_missing_out_directory_is_probed_and_removed_again(tmp_path):
    """The check makes the missing directories to see that they can be made, and removes them: a command refused
    for another reason after it leaves no empty directory."""
    from flexbeam.results.files import check_output_dir

    out = tmp_path / "new" / "deeper"
    assert check_output_dir(out, "--out") == out
    assert list(tmp_path.iterdir()) == []


def test_an_interrupted_probe_leaves_nothing(tmp_path, monkeypatch):
    """Ctrl-C or SIGTERM while the check's probe file exists (it raises in the main thread between two calls) left
    the probe ``.flexbeam-probe.*`` and the directories made for it: the streamed run's SIGTERM test met them under
    load.  The interrupt still propagates; nothing is left."""
    from flexbeam.results import files

    real_close = os.close

    def close(fd):  # the interrupt arrives with the probe made, before its removal
        real_close(fd)
        raise KeyboardInterrupt

    monkeypatch.setattr(files.os, "close", close)
    with pytest.raises(KeyboardInterrupt):
        files.check_output_dir(tmp_path / "new" / "deeper", "--out")
    monkeypatch.undo()
    assert list(tmp_path.iterdir()) == []


def test_a_refused_sweep_leaves_a_finished_store_as_it_was(tmp_path):
    """A sweep refused in one line (exit 2) wrote the store first: ``--workers 0`` against a finished store, or a
    scheduler that cannot be reached, replaced its sweep.json and its result.nc -- by one of "missing" cases for the
    new grid -- and a fresh --out was left holding both (an exploratory hunt).  ``-w 0`` was even taken (exit 0)
    when every case was stored already.  Now the workers and the connection come first."""

    def sweep(restitution: str, out: Path, *more: str) -> tuple[int, str, str]:
        return _cli(["sweep", "seed-experiment", "-g", f"contact.restitution={restitution}", *SHORT, "--out", str(out),
                     *more])  # fmt: skip

    def files(out: Path) -> dict[str, bytes]:
        return {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}

    out = tmp_path / "store"
    assert sweep("0.5,0.6", out, "-w", "1")[0] == 0
    before = files(out)
    unreachable = ("--scheduler", "tcp://127.0.0.1:1")  # nothing listens on port 1
    for grid, more in (("0.5,0.6", ("-w", "0")), ("0.5,0.7", ("-w", "0")), ("0.5,0.7", unreachable)):
        code, _, stderr = sweep(grid, out, *more)
        assert code == 2 and len(stderr.splitlines()) == 1, (grid, more, code, stderr)
        assert stderr.startswith(("error: --workers: must be an integer >= 1", "error: --scheduler: cannot connect"))
        assert files(out) == before, (grid, more)
    fresh = tmp_path / "fresh"  # (the same order for a scheduler that cannot be reached: 10 s of retries)
    assert sweep("0.5", fresh, "-w", "0")[0] == 2
    assert not fresh.exists()


def test_a_malformed_scheduler_address_is_refused_before_the_store_is_written(tmp_path):
    """``sweep --scheduler foo`` (no port) wrote the store's sweep.json, failed to connect, and then ended in a
    145-line traceback: the failed connection stayed Dask's default client and the store's result.nc, written after
    it, went through it.  Now the address's form is checked first: one line naming the scheduler, exit 2, nothing
    written (``bifurcation`` answered so already)."""
    out = tmp_path / "store"
    sweep = ["sweep", "seed-experiment", "-g", "contact.restitution=0.5", *SHORT]
    code, stdout, stderr = _cli([*sweep, "--out", str(out), "--scheduler", "foo"])
    lines = stderr.splitlines()
    assert code == 2 and stdout == "" and len(lines) == 1, (code, stderr)
    assert lines[0].startswith("error: --scheduler: cannot connect to 'foo'") and "port" in lines[0], lines[0]
    assert not out.exists()


@pytest.mark.parametrize("command", ["sweep", "bifurcation"])
def test_no_worker_is_refused_naming_the_option(tmp_path, command):
    """``-w 0``: one line naming ``--workers`` as every other option is named (it said ``workers:``), exit 2,
    nothing written (bifurcation made its empty store first)."""
    out = tmp_path / "store"
    code, stdout, stderr = _cli([*COMMANDS[command], "--out", str(out), "-w", "0"])  # (the last -w is taken)
    lines = stderr.splitlines()
    assert code == 2 and stdout == "" and len(lines) == 1, (code, stderr)
    assert lines[0] == "error: --workers: must be an integer >= 1 (got 0)", lines[0]
    assert not out.exists()
