"""Files written atomically (``flexbeam.results.files``): no temporary file left behind, whatever fails.

``Solution.to_netcdf("/tmp")`` wrote its whole file to a temporary ``/.tmp.XXXX`` beside the target, then failed to
rename it over the directory and left it there (620 kB in ``/``).
"""

from __future__ import annotations

import pytest

from flexbeam.results.files import atomic_path, write_text_atomic


def test_a_directory_is_refused_before_anything_is_written(tmp_path):
    target = tmp_path / "already-a-directory"
    target.mkdir()
    with pytest.raises(IsADirectoryError), atomic_path(target) as tmp:
        tmp.write_text("never")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["already-a-directory"]


def test_no_temporary_file_is_left_when_the_rename_fails(tmp_path):
    target = tmp_path / "out.txt"
    with pytest.raises(OSError), atomic_path(target) as tmp:
        tmp.write_text("x")
        target.mkdir()  # the target became a directory meanwhile: the rename fails
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt"]
    assert target.is_dir()


def test_no_temporary_file_is_left_when_the_writer_fails(tmp_path):
    with pytest.raises(RuntimeError), atomic_path(tmp_path / "out.txt") as tmp:
        tmp.write_text("half")
        raise RuntimeError("the writer failed")
    assert list(tmp_path.iterdir()) == []


def test_a_written_file_arrives_whole(tmp_path):
    path = write_text_atomic(tmp_path / "sub" / "a.txt", "text")
    assert path.read_text() == "text" and sorted(p.name for p in path.parent.iterdir()) == ["a.txt"]
