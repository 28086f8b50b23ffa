"""python -m halfedge_edu.figures: one command, deterministic pictures, a --check for CI."""

from __future__ import annotations

import subprocess
import sys

from halfedge_edu import figures


def test_every_figure_has_a_caption_and_a_maker():
    assert len(figures.FIGURES) >= 10
    for name, (caption, make) in figures.FIGURES.items():
        assert caption and callable(make), name


def test_writing_a_figure_twice_gives_the_same_bytes(tmp_path):
    assert figures.main(["--only", "two_triangles", "--out", str(tmp_path)]) == 0
    first = (tmp_path / "two_triangles.png").read_bytes()
    assert first.startswith(b"\x89PNG")
    assert figures.main(["--only", "two_triangles", "--out", str(tmp_path), "--check"]) == 0
    assert figures.FIGURES["two_triangles"][1]() == first


def test_check_reports_a_stale_figure(tmp_path, capsys):
    (tmp_path / "two_triangles.png").write_bytes(b"old")
    assert figures.main(["--only", "two_triangles", "--out", str(tmp_path), "--check"]) == 1
    assert "out of date: two_triangles.png" in capsys.readouterr().out
    assert (tmp_path / "two_triangles.png").read_bytes() == b"old"


def test_the_module_runs_as_a_command():
    result = subprocess.run([sys.executable, "-m", "halfedge_edu.figures", "--list"],
                            capture_output=True, text=True, check=True)
    assert "navigation.png" in result.stdout and "collapse_refused.png" in result.stdout
