"""The command line: `halfedge-edu info|check|subdivide|simplify|smooth|remesh|convert` (halfedge_edu/cli/).

Most tests call ``main([...])`` in-process; a few run the real ``python -m
halfedge_edu`` to check what a user sees. Bad input always means: exit status 2, one
line on stderr starting ``halfedge-edu: error:``, no traceback, and no output file (an
existing one is left as it was). Progress bars are off: stderr is not a terminal here.
"""

from __future__ import annotations

import errno
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.cli import main

ROOT = Path(__file__).resolve().parents[1]

ALL_COMMANDS = ("info", "check", "subdivide", "simplify", "smooth", "remesh", "convert")


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


def test_info_keeps_an_unreferenced_vertex_at_its_index(capsys, tmp_path):
    path = write_obj(tmp_path / "extra.obj", TETRA_V + [(5, 5, 5)], TETRA_F)
    status, out, err = run(capsys, "info", path)
    assert status == 0
    assert fields(out)["vertices"] == "5"
    assert err == ""


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


def usage_error(capsys, *argv) -> str:
    """Run a command line argparse rejects; return its stderr, checked to be one line."""
    with pytest.raises(SystemExit) as stop:
        main([str(a) for a in argv])
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and err.startswith("halfedge-edu: error: "), err
    return err


def test_no_command_is_a_one_line_usage_error(capsys):
    err = usage_error(capsys)
    assert "COMMAND" in err and "'halfedge-edu --help'" in err


def test_an_unknown_command_lists_the_commands(capsys):
    err = usage_error(capsys, "frobnicate")
    for command in ALL_COMMANDS:
        assert repr(command) in err


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
    for command in ALL_COMMANDS:
        assert f"\n    {command}" in result.stdout
    assert result.stderr == ""


@pytest.mark.parametrize("command", ["info", "subdivide"])
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


def test_python_m_subdivide_in_the_loop_assignments_form(tmp_path):
    source = tmp_path / "in.obj"
    hx.save(hx.sample("spot"), source)
    result = python_m("subdivide", "in.obj", "out.obj", "2", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""  # no progress bar: stderr is not a terminal
    faces_in = len(hx.read_obj(source).faces)
    assert len(hx.read_obj(tmp_path / "out.obj").faces) == 16 * faces_in
    assert result.stdout == f"subdivide: {faces_in} -> {16 * faces_in} faces, wrote out.obj\n"


# ---------------------------------------------------------------- what the command line loads

#: What a subcommand's own module imports and nothing before it may: numpy, the mesh, the
#: files and the algorithms.
LIBRARY = ("numpy", "halfedge_edu.core", "halfedge_edu.io", "halfedge_edu.algorithms")
SUBCOMMAND_MODULES = ("inspect", "transform", "course", "grade", "files")


def loaded_by(*argv, cwd=ROOT) -> tuple[subprocess.CompletedProcess, set[str]]:
    """Run ``python -m halfedge_edu ARGV`` in a fresh interpreter; return the run and every
    module loaded when it exits (written as the last line of stderr, after the command's own)."""
    code = ("import atexit, runpy, sys\n"
            "atexit.register(lambda: print(' '.join(sorted(sys.modules)), file=sys.stderr))\n"
            "sys.argv = ['halfedge-edu', *sys.argv[1:]]\n"
            "runpy.run_module('halfedge_edu', run_name='__main__', alter_sys=True)\n")
    result = subprocess.run([sys.executable, "-c", code, *map(str, argv)],
                            capture_output=True, text=True, cwd=cwd, timeout=120)
    *said, modules = result.stderr.splitlines() or [""]
    return subprocess.CompletedProcess(result.args, result.returncode, result.stdout, "\n".join(said)), set(modules.split())


def library_in(modules: set[str]) -> list[str]:
    return sorted(name for name in modules if name.startswith(LIBRARY))


def test_importing_the_command_line_loads_neither_numpy_nor_the_algorithms():
    code = ("import sys, halfedge_edu.cli\n"
            "print(' '.join(sorted(m for m in sys.modules if m.startswith(('numpy', 'halfedge_edu')))))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert result.returncode == 0, result.stderr
    loaded = set(result.stdout.split())
    assert "numpy" not in loaded and "halfedge_edu.algorithms" not in loaded
    assert library_in(loaded) == []
    assert not loaded & {f"halfedge_edu.cli.{name}" for name in SUBCOMMAND_MODULES}


@pytest.mark.parametrize(("argv", "status"), [
    (["--help"], 0),
    (["--version"], 0),
    (["subdivide", "--help"], 0),
    (["grade", "--help"], 0),
    (["bogus"], 2),
    (["simplify", "in.obj", "out.obj"], 2),  # --faces or --ratio missing: a usage error
])
def test_help_and_usage_errors_load_neither_numpy_nor_the_library(argv, status):
    result, modules = loaded_by(*argv)
    assert result.returncode == status, result.stderr
    assert "halfedge_edu.cli.parser" in modules
    assert library_in(modules) == []
    assert not modules & {f"halfedge_edu.cli.{name}" for name in SUBCOMMAND_MODULES}


def test_a_subcommand_loads_its_own_module_and_no_other(tetra):
    result, modules = loaded_by("info", tetra)
    assert result.returncode == 0, result.stderr
    assert {"numpy", "halfedge_edu.cli.inspect", "halfedge_edu.cli.files"} <= modules
    assert not modules & {"halfedge_edu.cli.transform", "halfedge_edu.cli.grade", "halfedge_edu.cli.course"}


# ---------------------------------------------------------------- commands that write a file

WRITERS = {  # each command's arguments after IN OUT, for tests that run them all
    "subdivide": ["1"],
    "simplify": ["--faces", "4"],
    "smooth": ["--iterations", "2"],
    "remesh": ["--iterations", "1"],
    "convert": [],
}


def sample_file(directory: Path, name: str, suffix: str = ".obj") -> Path:
    path = directory / f"{name}{suffix}"
    hx.save(hx.sample(name), path)
    return path


def faces_in(path: Path) -> int:
    return hx.load(path).n_faces


@pytest.fixture
def cube(tmp_path):
    return sample_file(tmp_path, "cube")


@pytest.mark.parametrize("command", WRITERS)
def test_every_writer_prints_one_summary_line_and_writes_a_valid_mesh(capsys, tmp_path, cube, command):
    out = tmp_path / "out.obj"
    status, stdout, err = run(capsys, command, cube, out, *WRITERS[command])
    assert status == 0 and err == ""
    written = hx.load(out)
    written.validate()
    assert stdout == f"{command}: 12 -> {written.n_faces} faces, wrote {out}\n"


@pytest.mark.parametrize("command", ALL_COMMANDS)
def test_every_command_has_help(capsys, command):
    with pytest.raises(SystemExit) as stop:
        main([command, "--help"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.startswith(f"usage: halfedge-edu {command}")


# ---------------------------------------------------------------- subdivide

def test_subdivide_n_levels_multiplies_the_faces_by_4_to_the_n(capsys, tmp_path, cube):
    out = tmp_path / "out.obj"
    status, stdout, _ = run(capsys, "subdivide", cube, out, 2)
    assert status == 0
    assert faces_in(out) == 12 * 16
    assert stdout == f"subdivide: 12 -> 192 faces, wrote {out}\n"


@pytest.mark.parametrize("levels", [[], ["--levels", "1"], ["1", "--levels", "1"]])
def test_subdivide_levels_by_option_or_default_one(capsys, tmp_path, cube, levels):
    out = tmp_path / "out.obj"
    status, _, _ = run(capsys, "subdivide", cube, out, *levels)
    assert status == 0
    assert faces_in(out) == 48


def test_subdivide_writes_what_loop_subdivide_returns(capsys, tmp_path):
    from halfedge_edu.algorithms.loop import loop_subdivide

    source = sample_file(tmp_path, "open_patch")
    out = tmp_path / "out.obj"
    run(capsys, "subdivide", source, out, 1)
    expected_vertices, expected_faces = loop_subdivide(hx.load(source)).to_arrays()
    written = hx.read_obj(out)
    assert (written.vertices == expected_vertices).all()  # OBJ keeps float64 exactly
    assert (written.faces == expected_faces).all()


def test_subdivide_weights_loop_uses_loops_original_beta(capsys, tmp_path):
    from halfedge_edu.algorithms.loop import loop_subdivide

    source = sample_file(tmp_path, "octahedron")
    out = tmp_path / "out.obj"
    status, _, _ = run(capsys, "subdivide", source, out, 1, "--weights", "loop")
    assert status == 0
    expected_vertices, _ = loop_subdivide(hx.load(source), weights="loop").to_arrays()
    warren_vertices, _ = loop_subdivide(hx.load(source)).to_arrays()
    written = hx.read_obj(out)
    assert (written.vertices == expected_vertices).all()
    assert not np.allclose(written.vertices, warren_vertices)  # degree 4: the two betas differ


def test_subdivide_help_names_both_weights(capsys):
    with pytest.raises(SystemExit):
        main(["subdivide", "--help"])
    out = capsys.readouterr().out
    assert "Warren's weights" in out and "--weights" in out and "Loop's original beta" in out


def test_subdivide_n_and_levels_that_disagree(capsys, tmp_path, cube):
    status, _, err = run(capsys, "subdivide", cube, tmp_path / "out.obj", 2, "--levels", 3)
    assert_one_line_error(status, err)
    assert not (tmp_path / "out.obj").exists()


@pytest.mark.parametrize("levels", ["-1", "1.5", "two"])
def test_subdivide_rejects_a_bad_n(capsys, tmp_path, cube, levels):
    err = usage_error(capsys, "subdivide", cube, tmp_path / "out.obj", levels)
    assert "argument N" in err
    assert not (tmp_path / "out.obj").exists()


def test_progress_bar_when_asked(capsys, tmp_path, cube):
    status, _, err = run(capsys, "subdivide", cube, tmp_path / "out.obj", 2, "--progress")
    assert status == 0
    assert "loop subdivision" in err and "2/2" in err


# ---------------------------------------------------------------- simplify

@pytest.fixture
def sphere(tmp_path):
    path = tmp_path / "sphere.obj"
    hx.save(hx.sample("icosphere", subdivisions=2), path)  # 320 faces
    return path


def test_simplify_to_a_face_count(capsys, tmp_path, sphere):
    out = tmp_path / "out.obj"
    status, stdout, err = run(capsys, "simplify", sphere, out, "--faces", 100)
    assert status == 0 and err == ""
    assert faces_in(out) in (99, 100)  # an interior collapse removes two faces
    assert stdout.startswith("simplify: 320 -> ")


def test_simplify_to_a_ratio(capsys, tmp_path, sphere):
    out = tmp_path / "out.obj"
    status, _, _ = run(capsys, "simplify", sphere, out, "--ratio", 0.25)
    assert status == 0
    assert faces_in(out) in (79, 80)


@pytest.mark.parametrize("ratio", ["0", "1.5", "-0.2", "nan", "half"])
def test_simplify_rejects_a_ratio_outside_0_to_1(capsys, tmp_path, sphere, ratio):
    err = usage_error(capsys, "simplify", sphere, tmp_path / "out.obj", "--ratio", ratio)
    assert "--ratio" in err
    assert not (tmp_path / "out.obj").exists()


@pytest.mark.parametrize("target", [[], ["--faces", "10", "--ratio", "0.5"], ["--faces", "0"]])
def test_simplify_needs_exactly_one_valid_target(capsys, tmp_path, sphere, target):
    usage_error(capsys, "simplify", sphere, tmp_path / "out.obj", *target)
    assert not (tmp_path / "out.obj").exists()


def test_simplify_to_more_faces_than_the_input_warns_and_copies(capsys, tmp_path, sphere):
    out = tmp_path / "out.obj"
    status, stdout, err = run(capsys, "simplify", sphere, out, "--faces", 1000)
    assert status == 0
    assert err.startswith("halfedge-edu: warning: ") and len(err.splitlines()) == 1
    assert stdout == f"simplify: 320 -> 320 faces, wrote {out}\n"


def test_simplify_says_in_one_line_when_it_stops_short(capsys, tmp_path):
    source = sample_file(tmp_path, "tetrahedron")
    status, stdout, err = run(capsys, "simplify", source, tmp_path / "out.obj", "--faces", 2)
    assert status == 0
    assert err.splitlines() == [
        "halfedge-edu: warning: simplify stopped at 4 faces: no allowed collapse is left (target was 2)"
    ]
    assert "4 -> 4 faces" in stdout


# ---------------------------------------------------------------- smooth

@pytest.mark.parametrize("weights", ["uniform", "cotangent"])
@pytest.mark.parametrize("boundary", ["fixed", "along"])
def test_smooth_writes_what_smooth_returns(capsys, tmp_path, weights, boundary):
    from halfedge_edu.algorithms.smoothing import smooth

    source = sample_file(tmp_path, "open_patch")
    out = tmp_path / "out.obj"
    status, _, _ = run(
        capsys, "smooth", source, out, "--iterations", 3, "--weights", weights, "--boundary", boundary
    )
    assert status == 0
    expected, _ = smooth(hx.load(source), 3, weights=weights, boundary=boundary).to_arrays()
    assert (hx.read_obj(out).vertices == expected).all()


def test_smooth_rejects_unknown_weights(capsys, tmp_path, cube):
    err = usage_error(capsys, "smooth", cube, tmp_path / "out.obj", "--weights", "mean")
    assert "'uniform', 'cotangent'" in err


# ---------------------------------------------------------------- remesh

def test_remesh_writes_what_remesh_returns(capsys, tmp_path, sphere):
    from halfedge_edu.algorithms.remesh import remesh

    out = tmp_path / "out.obj"
    status, stdout, err = run(capsys, "remesh", sphere, out, "--length", 0.15, "--iterations", 2)
    assert status == 0 and err == ""
    expected_vertices, expected_faces = remesh(hx.load(sphere), 0.15, 2).to_arrays()
    written = hx.read_obj(out)
    assert len(expected_faces) > 320  # shorter edges than the input's: more faces
    assert (written.vertices == expected_vertices).all() and (written.faces == expected_faces).all()
    assert stdout == f"remesh: 320 -> {len(expected_faces)} faces, wrote {out}\n"


def test_remesh_default_length_and_iterations(capsys, tmp_path):
    from halfedge_edu.algorithms.remesh import remesh

    source = sample_file(tmp_path, "open_patch")
    out = tmp_path / "out.obj"
    status, _, _ = run(capsys, "remesh", source, out)
    assert status == 0
    expected_vertices, _ = remesh(hx.load(source)).to_arrays()
    assert (hx.read_obj(out).vertices == expected_vertices).all()


@pytest.mark.parametrize("length", ["0", "-1", "inf", "nan", "long"])
def test_remesh_rejects_a_length_that_is_not_positive(capsys, tmp_path, cube, length):
    err = usage_error(capsys, "remesh", cube, tmp_path / "out.obj", "--length", length)
    assert "--length" in err
    assert not (tmp_path / "out.obj").exists()


# ---------------------------------------------------------------- convert

@pytest.mark.parametrize("suffix", [".ply", ".stl", ".off", ".glb", ".obj"])
def test_convert_by_suffix_keeps_the_mesh(capsys, tmp_path, cube, suffix):
    out = tmp_path / f"out{suffix}"
    status, stdout, _ = run(capsys, "convert", cube, out)
    assert status == 0
    assert stdout == f"convert: 12 -> 12 faces, wrote {out}\n"
    back = hx.load(out)
    assert (back.n_vertices, back.n_faces) == (8, 12)


def test_convert_reads_other_formats_too(capsys, tmp_path, cube):
    run(capsys, "convert", cube, tmp_path / "cube.off")
    status, _, _ = run(capsys, "convert", tmp_path / "cube.off", tmp_path / "back.obj")
    assert status == 0
    assert faces_in(tmp_path / "back.obj") == 12


# ---------------------------------------------------------------- bad input for the writers

def assert_only(directory: Path, *names: str) -> None:
    """The folder holds exactly these files: no output, no temporary file left behind."""
    assert sorted(p.name for p in directory.iterdir()) == sorted(names)


@pytest.mark.parametrize("command", WRITERS)
def test_writer_with_a_missing_input(capsys, tmp_path, command):
    status, out, err = run(capsys, command, tmp_path / "nothere.obj", tmp_path / "out.obj", *WRITERS[command])
    assert_one_line_error(status, err)
    assert "nothere.obj: no such file" in err and out == ""
    assert_only(tmp_path)


@pytest.mark.parametrize("command", WRITERS)
def test_writer_with_a_malformed_obj(capsys, tmp_path, command):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n")
    status, _, err = run(capsys, command, bad, tmp_path / "out.obj", *WRITERS[command])
    assert_one_line_error(status, err)
    assert "bad.obj" in err and "line 4" in err
    assert "--repair" not in err  # repairing cannot fix a file that does not parse
    assert_only(tmp_path, "bad.obj")


FIN_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)]
FIN_F = [(0, 1, 2), (1, 0, 3), (0, 1, 4)]  # three triangles on the edge 0-1


@pytest.mark.parametrize("command", WRITERS)
def test_writer_on_a_non_manifold_mesh_suggests_repair(capsys, tmp_path, command):
    fin = write_obj(tmp_path / "fin.obj", FIN_V, FIN_F)
    status, _, err = run(capsys, command, fin, tmp_path / "out.obj", *WRITERS[command])
    assert_one_line_error(status, err)
    assert "has 3 faces" in err and "run again with --repair" in err
    assert_only(tmp_path, "fin.obj")


def test_repair_loads_a_non_manifold_mesh(capsys, tmp_path):
    fin = write_obj(tmp_path / "fin.obj", FIN_V, FIN_F)
    out = tmp_path / "out.obj"
    status, stdout, err = run(capsys, "subdivide", "--repair", fin, out, 1)
    assert status == 0
    assert err.startswith("halfedge-edu: warning: fin.obj: repair_faces changed the mesh")
    assert stdout == f"subdivide: 3 -> 12 faces, wrote {out}\n"


def test_check_with_repair(capsys, tmp_path):
    fin = write_obj(tmp_path / "fin.obj", FIN_V, FIN_F)
    status, out, _ = run(capsys, "check", "--repair", fin)
    assert status == 0
    assert "valid halfedge mesh" in out


@pytest.mark.parametrize(
    "output, expected",
    [
        ("out.xyz", "unknown file type '.xyz'"),
        ("out", "unknown file type '(no suffix)'"),
        ("missing/out.obj", "missing: no such folder"),
        ("cube.obj/out.obj", "cube.obj: is not a folder"),
        ("folder.obj", "folder.obj: is a folder"),
    ],
)
def test_writer_with_an_output_it_cannot_write(capsys, tmp_path, cube, output, expected):
    (tmp_path / "folder.obj").mkdir()
    status, _, err = run(capsys, "convert", cube, tmp_path / output)
    assert_one_line_error(status, err)
    assert expected in err
    assert_only(tmp_path, "cube.obj", "folder.obj")
    assert_only(tmp_path / "folder.obj")


def test_writer_into_a_read_only_folder(capsys, tmp_path, cube, monkeypatch):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o555)
    # Root (as in CI) may write into read-only folders, so the permission check is also
    # told what it would tell an ordinary user; the CLI must refuse before writing.
    real_access = os.access
    monkeypatch.setattr(
        os, "access", lambda path, mode, **kw: False if Path(path) == locked else real_access(path, mode, **kw)
    )
    try:
        status, _, err = run(capsys, "convert", cube, locked / "out.obj")
    finally:
        locked.chmod(0o755)
    assert_one_line_error(status, err)
    assert "permission denied" in err
    assert_only(locked)


# ---------------------------------------------------------------- no partial output, ever

@pytest.fixture
def old_output(tmp_path):
    """An output file from an earlier run, which a failed run must leave as it was."""
    path = tmp_path / "out.obj"
    path.write_text("# an earlier result\n")
    return path


def test_algorithm_failing_half_way_writes_nothing(capsys, tmp_path, cube, old_output, monkeypatch):
    import halfedge_edu.algorithms.loop as loop

    real_loop_subdivide = loop.loop_subdivide

    def one_level_then_fail(mesh, levels, **options):
        real_loop_subdivide(mesh, 1)
        raise RuntimeError("failed after one level")

    monkeypatch.setattr(loop, "loop_subdivide", one_level_then_fail)
    status, out, err = run(capsys, "subdivide", cube, old_output, 2)
    assert_one_line_error(status, err, internal=True)
    assert "failed after one level" in err and out == ""
    assert old_output.read_text() == "# an earlier result\n"
    assert_only(tmp_path, "cube.obj", "out.obj")
    old_output.unlink()
    run(capsys, "subdivide", cube, old_output, 2)
    assert_only(tmp_path, "cube.obj")


class InterruptedWrite:
    """The temporary file: half of what is written arrives, then ``interrupt()`` is called."""

    def __init__(self, file, interrupt):
        self.file, self.interrupt = file, interrupt

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.file.close()

    def write(self, text):
        self.file.write(text[: len(text) // 2])
        self.file.flush()
        self.interrupt()


def interrupt_writes(monkeypatch, interrupt) -> None:
    """Make every file that ``hx.save`` opens an ``InterruptedWrite``."""
    real_fdopen = os.fdopen
    monkeypatch.setattr(os, "fdopen", lambda *args, **kwargs: InterruptedWrite(real_fdopen(*args, **kwargs), interrupt))


def test_disk_full_half_way_through_writing_leaves_no_partial_file(capsys, tmp_path, cube, old_output, monkeypatch):
    def disk_full():
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    interrupt_writes(monkeypatch, disk_full)
    status, out, err = run(capsys, "subdivide", cube, old_output, 1)
    monkeypatch.undo()
    assert_one_line_error(status, err)
    assert f"{old_output}: {os.strerror(errno.ENOSPC)}" in err and out == ""
    assert old_output.read_text() == "# an earlier result\n"
    assert_only(tmp_path, "cube.obj", "out.obj")


def test_a_broken_result_is_an_internal_error_with_status_1(capsys, tmp_path, cube, old_output, monkeypatch):
    import halfedge_edu.algorithms.smoothing as smoothing

    def smooth_and_break(mesh, *args, **options):
        nxt = mesh.halfedge_next
        nxt[0] = nxt[nxt[0]]  # face loop of halfedge 0 now has two steps
        return mesh

    monkeypatch.setattr(smoothing, "smooth", smooth_and_break)
    status, out, err = run(capsys, "smooth", cube, old_output)
    assert status == 1 and out == ""
    assert len(err.splitlines()) == 1
    assert err.startswith("halfedge-edu: error: internal error: smooth made a mesh that is not a valid halfedge mesh (")
    assert "nothing was written" in err
    assert old_output.read_text() == "# an earlier result\n"


def test_running_out_of_memory_is_one_line(capsys, tmp_path, cube, monkeypatch):
    import halfedge_edu.algorithms.loop as loop

    def too_big(mesh, levels, **options):
        raise MemoryError

    monkeypatch.setattr(loop, "loop_subdivide", too_big)
    status, _, err = run(capsys, "subdivide", cube, tmp_path / "out.obj", 12, "--max-faces", 10**9)
    assert_one_line_error(status, err)
    assert "out of memory" in err
    assert_only(tmp_path, "cube.obj")


# ---------------------------------------------------------------- formats that cannot hold the mesh

FIN_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)]
FIN_F = [(0, 1, 2), (1, 0, 3), (0, 1, 4)]  # three triangles on the edge 0-1


@pytest.mark.parametrize("suffix", [".stl", ".ply", ".off"])
def test_info_reports_a_non_manifold_file_alike_in_every_format(capsys, tmp_path, suffix):
    import trimesh

    as_obj = write_obj(tmp_path / "fin.obj", FIN_V, FIN_F)
    other = tmp_path / f"fin{suffix}"
    trimesh.Trimesh(np.array(FIN_V, dtype=float), np.array(FIN_F), process=False).export(other)
    _, obj_out, _ = run(capsys, "info", as_obj)
    status, out, err = run(capsys, "info", other)
    assert status == 0, err
    assert "non-manifold edges (more than two faces): 1 (0-1)" in out
    for key in ("vertices", "edges", "faces", "manifold"):
        assert fields(out)[key] == fields(obj_out)[key], key


def test_convert_repair_to_stl_is_refused_naming_the_output(capsys, tmp_path):
    path = write_obj(tmp_path / "fin.obj", FIN_V, FIN_F)
    status, out, err = run(capsys, "convert", path, tmp_path / "out.stl", "--repair")
    lines = err.splitlines()
    assert status == 2 and out == ""
    assert lines[0].startswith("halfedge-edu: warning: ") and "split vertices" in lines[0]
    assert lines[1].startswith(f"halfedge-edu: error: {tmp_path / 'out.stl'}: vertices 0 and ")
    assert ".stl stores no shared vertices" in lines[1]
    assert_only(tmp_path, "fin.obj")


def test_convert_repair_to_an_indexed_format_loads_back_as_written(capsys, tmp_path):
    path = write_obj(tmp_path / "fin.obj", FIN_V, FIN_F)
    status, _, _ = run(capsys, "convert", path, tmp_path / "out.ply", "--repair")
    assert status == 0
    status, out, err = run(capsys, "check", tmp_path / "out.ply")
    assert status == 0, err


def test_convert_to_ply_refuses_coordinates_beyond_float32(capsys, tmp_path):
    path = write_obj(tmp_path / "far.obj", [(0, 0, 0), (1e39, 0, 0), (0, 1, 0), (0, 0, 1)], TETRA_F)
    status, _, err = run(capsys, "convert", path, tmp_path / "out.ply")
    assert_one_line_error(status, err)
    assert f"{tmp_path / 'out.ply'}: vertex 1 has a coordinate beyond float32's range" in err
    assert_only(tmp_path, "far.obj")


# ---------------------------------------------------------------- huge coordinates

@pytest.mark.parametrize("command", ["subdivide", "simplify", "smooth", "remesh"])
@pytest.mark.parametrize("largest", [1e308, 1e200, -1.5e41])
def test_coordinates_too_large_to_compute_with_are_one_line(capsys, tmp_path, command, largest):
    vertices = [(0, 0, 0), (largest, 0, 0), (0, largest, 0), (0, 0, largest)]
    path = write_obj(tmp_path / "huge.obj", vertices, TETRA_F)
    status, out, err = run(capsys, command, path, tmp_path / "out.obj", *WRITERS[command])
    assert_one_line_error(status, err)
    assert f"coordinates up to {abs(largest):.3g} are too large for the computation" in err
    assert_only(tmp_path, "huge.obj")


@pytest.mark.parametrize("command", ["subdivide", "simplify", "smooth", "remesh"])
def test_coordinates_just_below_the_limit_are_computed_with(capsys, tmp_path, command):
    scaled = [(1e40 * x, 1e40 * y, 1e40 * z) for x, y, z in hx.sample("cube").to_arrays()[0]]
    path = write_obj(tmp_path / "big.obj", scaled, hx.sample("cube").to_arrays()[1])
    status, _, err = run(capsys, command, path, tmp_path / "out.obj", *WRITERS[command])
    assert status == 0 and err == ""


@pytest.mark.parametrize("command", ["subdivide", "simplify", "smooth", "remesh"])
@pytest.mark.parametrize("extent", [1e-200, 0.0])
def test_a_mesh_too_small_to_compute_with_is_one_line(capsys, tmp_path, command, extent):
    vertices = [(0, 0, 0), (extent, 0, 0), (0, extent, 0), (0, 0, extent)]
    path = write_obj(tmp_path / "tiny.obj", vertices, TETRA_F)
    status, out, err = run(capsys, command, path, tmp_path / "out.obj", *WRITERS[command])
    assert_one_line_error(status, err)
    assert f"the mesh is {extent:.3g} across, too small for the computation" in err
    assert_only(tmp_path, "tiny.obj")


def test_info_and_check_read_huge_coordinates_as_they_are(capsys, tmp_path):
    path = write_obj(tmp_path / "huge.obj", [(0, 0, 0), (1e308, 0, 0), (0, 1e308, 0), (0, 0, 1e308)], TETRA_F)
    assert run(capsys, "info", path)[0] == 0
    assert run(capsys, "check", path)[0] == 0


# ---------------------------------------------------------------- output size, estimated first

def test_subdivide_refuses_a_result_above_max_faces_naming_estimate_and_limit(capsys, tmp_path, cube):
    status, _, err = run(capsys, "subdivide", cube, tmp_path / "out.obj", 20)
    assert_one_line_error(status, err)
    assert f"20 levels of subdivision would make about {12 * 4.0**20:.3g} faces" in err
    assert "more than the limit of 10,000,000; raise it with --max-faces" in err
    assert_only(tmp_path, "cube.obj")


def test_subdivide_estimate_of_thousands_of_levels_is_refused_too(capsys, tmp_path, cube):
    status, _, err = run(capsys, "subdivide", cube, tmp_path / "out.obj", 100000)
    assert_one_line_error(status, err)
    assert "would make more than 1e308 faces" in err


def test_max_faces_moves_the_limit_both_ways(capsys, tmp_path, cube):
    status, _, err = run(capsys, "subdivide", cube, tmp_path / "out.obj", 2, "--max-faces", 191)
    assert_one_line_error(status, err)
    assert "about 192 faces, more than the limit of 191" in err
    status, _, _ = run(capsys, "subdivide", cube, tmp_path / "out.obj", 2, "--max-faces", 192)
    assert status == 0 and faces_in(tmp_path / "out.obj") == 192


@pytest.mark.parametrize("length", ["1e-9", "1e-300"])
def test_remesh_refuses_a_length_that_would_make_too_many_faces(capsys, tmp_path, cube, length):
    status, _, err = run(capsys, "remesh", cube, tmp_path / "out.obj", "--length", length)
    assert_one_line_error(status, err)
    assert f"remeshing to edge length {float(length):g} would make " in err
    assert "more than the limit of 10,000,000" in err
    assert_only(tmp_path, "cube.obj")


def test_remesh_estimate_is_close_to_what_remesh_makes(capsys, tmp_path, sphere):
    # The unit sphere's area is about 4 pi; edges of 0.2 give about 4 pi / (sqrt(3)/4 0.04) = 725 faces.
    status, out, _ = run(capsys, "remesh", sphere, tmp_path / "out.obj", "--length", "0.2", "--max-faces", 2000)
    assert status == 0
    made = faces_in(tmp_path / "out.obj")
    assert 0.5 * 725 < made < 1.5 * 725
    status, _, err = run(capsys, "remesh", sphere, tmp_path / "out.obj", "--length", "0.2", "--max-faces", 300)
    assert_one_line_error(status, err)


# ---------------------------------------------------------------- special files and names

@pytest.mark.parametrize("command", ["info", "check", "convert"])
def test_a_fifo_or_a_link_to_dev_zero_is_refused_at_once(capsys, tmp_path, command):
    os.mkfifo(tmp_path / "pipe.obj")
    (tmp_path / "zero.obj").symlink_to("/dev/zero")
    for name in ("pipe.obj", "zero.obj"):
        extra = [tmp_path / "out.obj"] if command == "convert" else []
        status, _, err = run(capsys, command, tmp_path / name, *extra)
        assert_one_line_error(status, err)
        assert f"{name}: is not a regular file" in err
    assert not (tmp_path / "out.obj").exists()


def test_an_output_name_of_255_bytes_is_written(capsys, tmp_path, cube):
    out = tmp_path / ("c" * 251 + ".obj")
    status, _, err = run(capsys, "convert", cube, out)
    assert status == 0, err
    assert_only(tmp_path, "cube.obj", out.name)


def test_a_permission_error_names_the_output_not_the_temporary_file(capsys, tmp_path, cube, monkeypatch):
    import halfedge_edu.io.obj as obj

    def refused(path, *args, **kwargs):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(path))

    monkeypatch.setattr(obj.os, "open", refused)
    status, _, err = run(capsys, "convert", cube, tmp_path / "out.obj")
    assert_one_line_error(status, err)
    assert f"{tmp_path / 'out.obj'}: {os.strerror(errno.EACCES)}" in err
    assert ".tmp" not in err


@pytest.mark.parametrize("command", ["info", "check"])
def test_a_file_name_that_is_not_utf8_is_printed_not_an_internal_error(tmp_path, command):
    name = os.fsencode(tmp_path) + b"/caf\xe9.obj"  # Latin-1, not UTF-8
    with open(name, "w") as file:
        file.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    env = {**os.environ, "PYTHONIOENCODING": "utf-8", "PYTHONPATH": str(ROOT)}
    result = subprocess.run(
        [sys.executable, "-m", "halfedge_edu", command, name], capture_output=True, text=True, env=env, timeout=60
    )
    assert result.returncode == 0, result.stderr
    assert "caf\\xe9.obj" in result.stdout
    assert result.stderr == ""


def test_a_file_name_that_is_not_utf8_in_an_error_is_one_line(tmp_path):
    name = os.fsencode(tmp_path) + b"/caf\xe9.obj"
    with open(name, "w") as file:
        file.write("v 0 0 0\nf 1 2 3\n")
    env = {**os.environ, "PYTHONIOENCODING": "utf-8", "PYTHONPATH": str(ROOT)}
    result = subprocess.run(
        [sys.executable, "-m", "halfedge_edu", "check", name], capture_output=True, text=True, env=env, timeout=60
    )
    assert result.returncode == 2
    assert_one_line_error(2, result.stderr)
    assert "caf\\xe9.obj" in result.stderr


# ---------------------------------------------------------------- SIGTERM while writing

def test_sigterm_while_writing_removes_the_temporary_file(capsys, tmp_path, cube, old_output, monkeypatch):
    import signal

    interrupt_writes(monkeypatch, lambda: os.kill(os.getpid(), signal.SIGTERM))
    before = signal.getsignal(signal.SIGTERM)
    status, out, err = run(capsys, "subdivide", cube, old_output, 1)
    monkeypatch.undo()
    assert status == 128 + signal.SIGTERM and out == ""
    assert old_output.read_text() == "# an earlier result\n"
    assert_only(tmp_path, "cube.obj", "out.obj")
    assert signal.getsignal(signal.SIGTERM) is before, "the handler is put back"


def test_sigterm_to_a_real_process_leaves_no_temporary_file(tmp_path):
    import signal

    big = tmp_path / "big.obj"
    hx.save(hx.sample("icosphere", subdivisions=5), big)  # 20480 faces: subdividing takes a moment
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen(
        [sys.executable, "-m", "halfedge_edu", "subdivide", big, tmp_path / "out.obj", "2"],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )
    # Wait until the output's temporary file exists, then terminate during the write.
    deadline, sent = time.monotonic() + 120, False
    while not sent and time.monotonic() < deadline and process.poll() is None:
        if any(p.name.startswith(".halfedge_edu-") for p in tmp_path.iterdir()):
            process.send_signal(signal.SIGTERM)
            sent = True
        time.sleep(0.001)
    process.wait(timeout=60)
    assert sent, "the temporary file was never seen"
    assert process.returncode == 128 + signal.SIGTERM
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.obj"]


# ---------------------------------------------------------------- issue 25: files that lie, leftovers, long paths

def _binary_stl_with_count(path: Path, mesh: hx.HalfedgeMesh, count: int) -> Path:
    """``mesh`` as a binary STL whose header declares ``count`` triangles."""
    data = mesh.to_trimesh().export(file_type="stl")
    path.write_bytes(data[:80] + count.to_bytes(4, "little") + data[84:])
    return path


@pytest.mark.parametrize("count", [11, 13, 0])
def test_check_refuses_a_binary_stl_whose_count_is_wrong(capsys, tmp_path, count):
    damaged = _binary_stl_with_count(tmp_path / "damaged.stl", hx.sample("cube"), count)
    status, out, err = run(capsys, "check", damaged)
    assert_one_line_error(status, err)
    assert f"declares {count} triangles" in err and "room for 12 triangles" in err and out == ""


def test_check_refuses_a_truncated_ascii_stl(capsys, tmp_path):
    text = hx.sample("cube").to_trimesh().export(file_type="stl_ascii")
    damaged = tmp_path / "cut.stl"
    damaged.write_text(text[: len(text) // 2])
    status, _, err = run(capsys, "check", damaged)
    assert_one_line_error(status, err)
    assert "cut.stl" in err and "truncated" in err


@pytest.mark.parametrize("name, content, expected", [
    ("issue.off", "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
     "vertex 4 should have 3 values"),
    ("hole.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
     "declares 4 vertices and 3 faces"),
    ("underscore.obj", "v 1_000 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", "'1_000' is not a number"),
])
def test_convert_refuses_a_lying_file_and_leaves_the_output_as_it_was(capsys, tmp_path, old_output,
                                                                      name, content, expected):
    (tmp_path / name).write_text(content)
    status, _, err = run(capsys, "convert", tmp_path / name, old_output)
    assert_one_line_error(status, err)
    assert expected in err
    assert old_output.read_text() == "# an earlier result\n"
    assert_only(tmp_path, name, old_output.name)


def test_convert_of_a_damaged_stl_leaves_the_output_as_it_was(capsys, tmp_path, old_output):
    damaged = _binary_stl_with_count(tmp_path / "damaged.stl", hx.sample("cube"), 13)
    status, _, err = run(capsys, "convert", damaged, old_output)
    assert_one_line_error(status, err)
    assert old_output.read_text() == "# an earlier result\n"


def test_a_later_run_removes_temporary_files_a_killed_run_left(capsys, tmp_path, cube):
    stale = tmp_path / ".halfedge_edu-0123abcd.tmp"  # what kill -9 during a write leaves
    fresh = tmp_path / ".halfedge_edu-89abcdef.tmp"  # perhaps another run writing right now
    others = [tmp_path / name for name in (".halfedge_edu-notmine.tmp", "notes.tmp", ".halfedge_edu-0123abcd.tmp.bak")]
    for path in [stale, fresh, *others]:
        path.write_text("partial")
    an_hour_ago = time.time() - 3600
    for path in [stale, *others]:
        os.utime(path, (an_hour_ago, an_hour_ago))
    status, _, err = run(capsys, "convert", cube, tmp_path / "out.obj")
    assert status == 0, err
    assert not stale.exists()
    assert fresh.exists() and all(path.exists() for path in others)


def test_a_cli_write_is_flushed_to_the_disk_before_the_rename(capsys, tmp_path, cube, monkeypatch):
    events = []
    real_fsync, real_replace = os.fsync, os.replace
    monkeypatch.setattr(os, "fsync", lambda fd: (events.append("fsync"), real_fsync(fd))[1])
    monkeypatch.setattr(os, "replace", lambda *a: (events.append("replace"), real_replace(*a))[1])
    status, _, err = run(capsys, "convert", cube, tmp_path / "out.ply")
    assert status == 0, err
    assert events[:2] == ["fsync", "replace"]


@pytest.mark.parametrize("where", ["input", "output"])
@pytest.mark.parametrize("long_path", [
    lambda folder: folder / ("n" * 300 + ".obj"),
    lambda folder: folder.joinpath(*["d" * 200] * 25, "x.obj"),
], ids=["name-over-255-bytes", "path-over-4096-bytes"])
def test_a_path_too_long_for_the_system_is_an_input_problem(capsys, tmp_path, cube, where, long_path):
    path = long_path(tmp_path)
    argv = ("check", path) if where == "input" else ("convert", cube, path)
    status, _, err = run(capsys, *argv)
    assert_one_line_error(status, err)
    assert "the path is too long for this system" in err and len(err) < 600


def test_an_error_listing_a_million_faces_stays_short(capsys, tmp_path):
    many = tmp_path / "copies.obj"
    many.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n" + "f 1 2 3\n" * 100_000)
    status, _, err = run(capsys, "check", many)
    assert_one_line_error(status, err)
    assert "has 100000 faces" in err and "and 99992 more" in err and len(err) < 1000


def test_the_temporary_file_of_a_write_killed_with_sigkill_is_removed_by_a_later_run(capsys, tmp_path, cube):
    killed = subprocess.run(
        [sys.executable, "-c",
         "import os, signal, sys\n"
         "from halfedge_edu.io.obj import atomic_output\n"
         "with atomic_output(sys.argv[1], 'wb') as file:\n"
         "    file.write(b'half a mesh'); file.flush()\n"
         "    os.kill(os.getpid(), signal.SIGKILL)\n",
         str(tmp_path / "out.obj")],
        cwd=ROOT,
    )
    assert killed.returncode == -9
    (left,) = tmp_path.glob(".halfedge_edu-*.tmp")  # nothing in a killed process can remove it
    an_hour_ago = time.time() - 3600
    os.utime(left, (an_hour_ago, an_hour_ago))
    status, _, err = run(capsys, "convert", cube, tmp_path / "out.obj")
    assert status == 0, err
    assert_only(tmp_path, "cube.obj", "out.obj")


def test_ctrl_c_interrupts_a_run_even_when_the_parent_ignored_it():
    """A grader started by a parent that ignores SIGINT (a CI runner, a test worker,
    ``nohup``) must still stop on Ctrl-C with status 130: Python only installs its
    handler when SIGINT was not ignored at start, so the command line installs it."""
    import signal

    from halfedge_edu.cli import _sigterm_unwinds

    before = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        with _sigterm_unwinds():
            assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
            with pytest.raises(KeyboardInterrupt):
                signal.raise_signal(signal.SIGINT)
        assert signal.getsignal(signal.SIGINT) == signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, before)
