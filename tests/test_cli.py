"""The command line: `halfedge-edu info|check FILE` (halfedge_edu/cli.py).

Most tests call ``main([...])`` in-process; a few run the real ``python -m
halfedge_edu`` to check what a user sees. Bad input always means: exit status 2, one
line on stderr starting ``halfedge-edu: error:``, no traceback.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import pytest

import halfedge_edu as hx
from halfedge_edu.cli import main

ROOT = Path(__file__).resolve().parents[1]


# ---------------------------------------------------------------- small OBJ files

def write_obj(path: Path, vertices, faces, extra: str = "") -> Path:
    """Write an OBJ with 0-based ``faces`` (written 1-based) and return its path."""
    lines = [f"v {x} {y} {z}" for x, y, z in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in faces]
    path.write_text("\n".join(lines) + "\n" + extra)
    return path


TETRA_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TETRA_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def torus(n: int = 4, m: int = 5):
    """An n x m grid wrapped both ways: genus 1, every vertex of degree 6."""
    vertices = []
    for i in range(n):
        for j in range(m):
            u, v = 2 * math.pi * i / n, 2 * math.pi * j / m
            vertices.append(((2 + math.cos(v)) * math.cos(u), (2 + math.cos(v)) * math.sin(u), math.sin(v)))
    faces = []
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, ((i + 1) % n) * m + j
            c, d = ((i + 1) % n) * m + (j + 1) % m, i * m + (j + 1) % m
            faces += [(a, b, c), (a, c, d)]
    return vertices, faces


@pytest.fixture
def tetra(tmp_path):
    return write_obj(tmp_path / "tetra.obj", TETRA_V, TETRA_F)


def run(capsys, *argv):
    """Run the CLI in-process; return (exit status, stdout, stderr)."""
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def fields(out: str) -> dict[str, str]:
    """The ``key: value`` lines of ``info``'s output."""
    return dict(line.split(": ", 1) for line in out.splitlines() if ": " in line and not line.startswith(" "))


def degree_histogram(out: str) -> dict[int, int]:
    """The indented ``degree: count`` lines under ``vertex degrees:``."""
    block = out.split("vertex degrees:\n", 1)[1]
    return {int(d): int(c) for d, c in (line.split(":") for line in block.splitlines() if line.startswith(" "))}


def assert_one_line_error(status: int, err: str, *, internal: bool = False) -> None:
    assert status == 2
    assert "Traceback" not in err
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("halfedge-edu: error: ")
    assert ("internal error" in lines[0]) == internal, "input problems and bugs are told apart"


# ---------------------------------------------------------------- info

def test_info_counts_a_closed_tetrahedron(capsys, tetra):
    status, out, err = run(capsys, "info", tetra)
    assert status == 0 and err == ""
    info = fields(out)
    assert info["vertices"] == "4"
    assert info["edges"] == "6"
    assert info["faces"] == "4"
    assert info["halfedges"] == "12"
    assert info["euler characteristic"] == "2"
    assert info["genus"] == "0"
    assert info["boundary loops"] == "0"
    assert info["manifold"] == "yes"
    assert degree_histogram(out) == {3: 4}


def test_info_finds_genus_one_on_a_torus(capsys, tmp_path):
    path = write_obj(tmp_path / "torus.obj", *torus(4, 5))
    status, out, _ = run(capsys, "info", path)
    assert status == 0
    info = fields(out)
    assert (info["vertices"], info["edges"], info["faces"]) == ("20", "60", "40")
    assert info["euler characteristic"] == "0"
    assert info["genus"] == "1"
    assert degree_histogram(out) == {6: 20}


def test_info_counts_the_boundary_loop_of_an_open_square(capsys, tmp_path):
    path = write_obj(tmp_path / "square.obj", [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 1, 2), (0, 2, 3)])
    status, out, _ = run(capsys, "info", path)
    assert status == 0
    info = fields(out)
    assert info["edges"] == "5"
    assert info["halfedges"] == "10"  # boundary halfedges included
    assert info["euler characteristic"] == "1"
    assert info["boundary loops"] == "1"
    assert degree_histogram(out) == {2: 2, 3: 2}


def test_info_reports_a_non_manifold_edge_instead_of_failing(capsys, tmp_path):
    # Three triangles on the edge 0-1: edge-non-manifold.
    vertices = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)]
    path = write_obj(tmp_path / "fin.obj", vertices, [(0, 1, 2), (1, 0, 3), (0, 1, 4)])
    status, out, err = run(capsys, "info", path)
    assert status == 0, err
    info = fields(out)
    assert info["manifold"] == "no"
    assert info["faces"] == "3"
    assert info["edges"] == "7"
    assert "non-manifold edges (more than two faces): 1 (0-1)" in out
    assert "loading said: " in out


def test_info_reports_a_non_manifold_vertex(capsys, tmp_path):
    # Two triangles touching only at vertex 0 (a bow tie): vertex-non-manifold.
    vertices = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (-1, 0, 0), (-1, -1, 0)]
    path = write_obj(tmp_path / "bowtie.obj", vertices, [(0, 1, 2), (0, 3, 4)])
    status, out, _ = run(capsys, "info", path)
    assert status == 0
    assert fields(out)["manifold"] == "no"
    assert "non-manifold vertices (more than one fan): 1 (0)" in out


def test_info_reports_inconsistent_orientation(capsys, tmp_path):
    # Both triangles run 0->1: manifold, but cannot be oriented as given.
    vertices = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0)]
    path = write_obj(tmp_path / "flipped.obj", vertices, [(0, 1, 2), (0, 1, 3)])
    status, out, _ = run(capsys, "info", path)
    assert status == 0
    assert fields(out)["manifold"] == "yes"
    assert "edges used twice in the same direction: 1 (0->1)" in out


def test_info_prints_dropped_vertices_as_a_one_line_warning(capsys, tmp_path):
    path = write_obj(tmp_path / "extra.obj", TETRA_V + [(5, 5, 5)], TETRA_F)
    status, out, err = run(capsys, "info", path)
    assert status == 0
    assert fields(out)["vertices"] == "4"
    warnings = err.splitlines()
    assert len(warnings) == 1 and warnings[0].startswith("halfedge-edu: warning: ")


# ---------------------------------------------------------------- check

def test_check_accepts_a_valid_mesh(capsys, tetra):
    status, out, _ = run(capsys, "check", tetra)
    assert status == 0
    assert out.strip() == f"{tetra}: valid halfedge mesh (4 vertices, 4 faces)"


def test_check_exits_1_naming_the_broken_rule(capsys, tetra, monkeypatch):
    real_load = hx.load

    def load_then_break(path, **kwargs):
        mesh = real_load(path, **kwargs)
        nxt = mesh.halfedge_next
        nxt[0] = nxt[nxt[0]]  # face loop of halfedge 0 now has two steps
        return mesh

    monkeypatch.setattr(hx, "load", load_then_break)
    status, out, err = run(capsys, "check", tetra)
    assert status == 1
    assert err == ""
    assert len(out.splitlines()) == 1
    assert out.startswith(f"{tetra}: not a valid halfedge mesh: [")


def test_check_rejects_a_non_manifold_file_with_status_2(capsys, tmp_path):
    vertices = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)]
    path = write_obj(tmp_path / "fin.obj", vertices, [(0, 1, 2), (1, 0, 3), (0, 1, 4)])
    status, _, err = run(capsys, "check", path)
    assert_one_line_error(status, err)
    assert err.startswith(f"halfedge-edu: error: {path}: ")
    assert "line 6" in err  # the library names the first face on the edge


# ---------------------------------------------------------------- bad input

@pytest.mark.parametrize("command", ["info", "check"])
def test_missing_file(capsys, tmp_path, command):
    status, out, err = run(capsys, command, tmp_path / "nothere.obj")
    assert_one_line_error(status, err)
    assert "nothere.obj: no such file" in err
    assert out == ""


@pytest.mark.parametrize("command", ["info", "check"])
def test_a_folder_is_not_a_mesh(capsys, tmp_path, command):
    status, _, err = run(capsys, command, tmp_path)
    assert_one_line_error(status, err)


@pytest.mark.parametrize(
    "body, expected",
    [
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "line 4"),  # not an index
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "line 4"),  # index out of range
        ("v 0 0 0\nv 1 0 zero\nv 0 1 0\nf 1 2 3\n", "line 2"),  # not a number
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4"),  # two corners
    ],
)
@pytest.mark.parametrize("command", ["info", "check"])
def test_malformed_obj_names_the_line(capsys, tmp_path, command, body, expected):
    path = tmp_path / "bad.obj"
    path.write_text(body)
    status, out, err = run(capsys, command, path)
    assert_one_line_error(status, err)
    assert "bad.obj" in err and expected in err
    assert out == ""


def test_binary_file_named_obj(capsys, tmp_path):
    path = tmp_path / "noise.obj"
    path.write_bytes(bytes(range(256)) * 4)
    status, _, err = run(capsys, "info", path)
    assert_one_line_error(status, err)


def test_file_with_no_faces(capsys, tmp_path):
    path = tmp_path / "points.obj"
    path.write_text("v 0 0 0\nv 1 0 0\n")
    status, _, err = run(capsys, "info", path)
    assert_one_line_error(status, err)


def test_unknown_file_type(capsys, tmp_path):
    path = tmp_path / "mesh.xyz"
    path.write_text("1 2 3\n")
    status, _, err = run(capsys, "info", path)
    assert_one_line_error(status, err)
    assert ".xyz" in err


def test_internal_error_is_one_line_unless_debug(capsys, tetra, monkeypatch):
    def broken(path, **kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(hx, "load", broken)
    status, _, err = run(capsys, "info", tetra)
    assert_one_line_error(status, err, internal=True)
    assert "internal error (RuntimeError: boom)" in err and "--debug" in err
    with pytest.raises(RuntimeError, match="boom"):
        main(["--debug", "info", str(tetra)])


def test_no_command_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as stop:
        main([])
    assert stop.value.code == 2
    assert "usage: halfedge-edu" in capsys.readouterr().err


# ---------------------------------------------------------------- as a real process

def python_m(*argv, cwd=ROOT):
    return subprocess.run(
        [sys.executable, "-m", "halfedge_edu", *map(str, argv)],
        capture_output=True, text=True, cwd=cwd, timeout=120,
    )


def test_python_m_help_lists_the_commands():
    result = python_m("--help")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("usage: halfedge-edu")
    for command in ("info", "check"):
        assert command in result.stdout
    assert result.stderr == ""


@pytest.mark.parametrize("command", ["info", "check"])
def test_python_m_subcommand_help(command):
    result = python_m(command, "--help")
    assert result.returncode == 0
    assert f"usage: halfedge-edu {command}" in result.stdout


def test_python_m_bad_input_is_one_line_without_traceback(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nf 1 2 3\n")
    for target in (tmp_path / "nothere.obj", bad):
        result = python_m("info", target)
        assert result.returncode == 2
        assert "Traceback" not in result.stderr
        assert len(result.stderr.splitlines()) == 1
        assert result.stderr.startswith("halfedge-edu: error: ")
        assert result.stdout == ""


def test_python_m_info_on_a_file(tmp_path, tetra):
    result = python_m("info", tetra)
    assert result.returncode == 0, result.stderr
    assert fields(result.stdout)["euler characteristic"] == "2"
