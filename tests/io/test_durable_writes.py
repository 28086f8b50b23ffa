"""Writes reach the disk before the rename; leftovers of killed writes are removed; over-long paths are named."""

from __future__ import annotations

import os
import time

import pytest

import halfedge_edu as hx
from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io.obj import remove_stale_temporaries


@pytest.mark.parametrize("suffix", [".obj", ".ply", ".stl", ".off"])
def test_save_flushes_the_file_then_renames_then_flushes_the_folder(tmp_path, monkeypatch, suffix):
    events = []
    real_fsync, real_replace = os.fsync, os.replace
    monkeypatch.setattr(os, "fsync", lambda fd: (events.append("fsync"), real_fsync(fd))[1])
    monkeypatch.setattr(os, "replace", lambda *a: (events.append("replace"), real_replace(*a))[1])
    hx.save(hx.sample("cube"), tmp_path / f"cube{suffix}")
    assert events == ["fsync", "replace", "fsync"]
    assert hx.load(tmp_path / f"cube{suffix}").n_faces == 12


def _age(path, seconds: float) -> None:
    then = time.time() - seconds
    os.utime(path, (then, then), follow_symlinks=False)


def test_only_old_temporary_files_with_the_package_prefix_are_removed(tmp_path):
    stale = tmp_path / ".halfedge_edu-0123abcd.tmp"
    fresh = tmp_path / ".halfedge_edu-89abcdef.tmp"
    not_ours = [tmp_path / name for name in (".halfedge_edu-ABCDEF01.tmp", ".halfedge_edu-0123abcd.tmp.bak",
                                              "halfedge_edu-0123abcd.tmp", "result.obj")]
    for path in [stale, fresh, *not_ours]:
        path.write_text("partial")
    for path in [stale, *not_ours]:
        _age(path, 3600)
    assert remove_stale_temporaries(tmp_path) == [stale]
    assert fresh.exists() and all(path.exists() for path in not_ours)


def test_a_link_or_folder_with_the_temporary_name_is_never_removed(tmp_path):
    target = tmp_path / "precious.obj"
    target.write_text("keep me")
    link = tmp_path / ".halfedge_edu-0123abcd.tmp"
    link.symlink_to(target)
    folder = tmp_path / ".halfedge_edu-89abcdef.tmp"
    folder.mkdir()
    _age(link, 3600)
    _age(folder, 3600)
    assert remove_stale_temporaries(tmp_path) == []
    assert link.is_symlink() and folder.is_dir() and target.read_text() == "keep me"


def test_cleaning_a_folder_that_cannot_be_listed_removes_nothing_and_raises_nothing(tmp_path):
    assert remove_stale_temporaries(tmp_path / "missing") == []


@pytest.mark.parametrize("long_path", [
    lambda folder: folder / ("n" * 300 + ".obj"),
    lambda folder: folder.joinpath(*["d" * 200] * 25, "x.ply"),
], ids=["name-over-255-bytes", "path-over-4096-bytes"])
def test_load_and_save_name_a_path_too_long_for_the_system(tmp_path, long_path):
    path = long_path(tmp_path)
    with pytest.raises(MeshInputError, match="cannot read the file: the path is too long") as loading:
        hx.load(path)
    with pytest.raises(MeshInputError, match="cannot write the file: the path is too long") as saving:
        hx.save(hx.sample("cube"), path)
    for error in (loading.value, saving.value):
        assert len(str(error)) < 600
