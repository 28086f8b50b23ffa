"""Construction from hostile input (issue 10): the empty mesh, the pillow, arrays of the wrong kind.

``from_faces`` either builds a valid mesh or raises ``MeshInputError`` naming the
face, vertex or argument; nothing is converted with a loss (complex to real, True to
1.0) and nothing is changed silently.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.cli import main

EDGE_CASES = Path(__file__).resolve().parents[1] / "data" / "edge_cases"
TRIANGLE = np.eye(3)
CUBE_VERTICES, CUBE_FACES = hx.sample("cube").to_arrays()


# ---- the empty mesh ---------------------------------------------------------------------------

@pytest.mark.parametrize("vertices, faces", [
    (np.zeros((0, 3)), np.zeros((0, 3), dtype=int)),
    ([], []),
    (np.zeros((0, 3)), np.zeros((0, 3))),
], ids=["arrays", "empty lists", "float faces"])
def test_the_empty_mesh_builds_and_validates(vertices, faces):
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    mesh.validate()
    assert (mesh.n_vertices, mesh.n_edges, mesh.n_faces, mesh.n_boundary_loops) == (0, 0, 0, 0)
    assert mesh.euler_characteristic == 0 and mesh.genus == 0
    vertices, faces = mesh.to_arrays()
    assert vertices.shape == (0, 3) and faces.shape == (0, 3)


def test_vertices_without_faces_stay_as_isolated_vertices():
    # Every input vertex keeps its index (as in pmp-library and OpenMesh), faces or not.
    mesh = hx.HalfedgeMesh.from_faces(TRIANGLE, np.zeros((0, 3), dtype=int))
    mesh.validate()
    assert (mesh.n_vertices, mesh.n_faces) == (3, 0)


def test_dropping_unreferenced_vertices_without_faces_gives_the_empty_mesh_with_a_warning():
    with pytest.warns(hx.MeshWarning, match="dropped 3 unreferenced vertices"):
        mesh = hx.HalfedgeMesh.from_faces(TRIANGLE, np.zeros((0, 3), dtype=int), drop_unreferenced=True)
    assert mesh.n_vertices == 0


def test_the_empty_mesh_round_trips_through_obj(tmp_path):
    hx.save(hx.HalfedgeMesh.from_faces([], []), tmp_path / "empty.obj")
    loaded = hx.load(tmp_path / "empty.obj")
    loaded.validate()
    assert (loaded.n_vertices, loaded.n_faces) == (0, 0)


@pytest.mark.parametrize("suffix", [".ply", ".off", ".stl", ".glb"])
def test_the_empty_mesh_round_trips_through_every_format(tmp_path, suffix):
    # What ``save`` writes for the empty mesh, ``load`` must read back (trimesh writes a
    # file with zero vertices and zero faces; the OBJ reader's rule applies to it).
    path = tmp_path / f"empty{suffix}"
    hx.save(hx.HalfedgeMesh.from_faces([], []), path)
    loaded = hx.load(path)
    loaded.validate()
    assert (loaded.n_vertices, loaded.n_faces) == (0, 0)


def test_a_ply_of_points_only_is_refused_as_a_point_cloud(tmp_path):
    path = tmp_path / "cloud.ply"
    path.write_text("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0\n1 0 0\n")
    with pytest.raises(hx.MeshInputError, match="2 vertices but no triangles: a point cloud"):
        hx.load(path)


def test_an_obj_of_comments_only_is_the_empty_mesh():
    assert hx.load(EDGE_CASES / "only_comments.obj").n_faces == 0


def test_an_obj_of_zero_bytes_is_refused_by_name(tmp_path):
    (tmp_path / "zero.obj").write_bytes(b"")
    with pytest.raises(hx.MeshInputError, match="the file is empty \\(0 bytes\\)"):
        hx.load(tmp_path / "zero.obj")


def test_an_obj_of_vertices_only_is_refused_as_a_point_cloud(tmp_path):
    (tmp_path / "cloud.obj").write_text("v 0 0 0\nv 1 0 0\n")
    with pytest.raises(hx.MeshInputError, match="2 vertices but no faces .*point cloud"):
        hx.load(tmp_path / "cloud.obj")


@pytest.mark.parametrize("command", [
    ["info"], ["check"], ["subdivide", "OUT", "1"], ["smooth", "OUT"], ["simplify", "OUT", "--ratio", "0.5"],
    ["remesh", "OUT"], ["convert", "OUT"],
])
def test_every_command_takes_the_empty_mesh_and_writes_it_back_empty(tmp_path, command, capsys):
    source = tmp_path / "empty.obj"
    hx.save(hx.HalfedgeMesh.from_faces([], []), source)
    output = tmp_path / "out.obj"
    arguments = [command[0], str(source)] + [str(output) if part == "OUT" else part for part in command[1:]]
    assert main(arguments) == 0, capsys.readouterr().err
    if "OUT" in command:
        assert hx.load(output).n_faces == 0


# ---- the pillow: two faces on the same three vertices ----------------------------------------

def test_a_pillow_beside_a_cube_is_refused_naming_both_faces_and_lines(tmp_path):
    vertices = np.vstack([CUBE_VERTICES, TRIANGLE + 5.0])
    faces = np.vstack([CUBE_FACES, [[8, 9, 10], [8, 10, 9]]])
    path = tmp_path / "pillow.obj"
    hx.io.write_obj(path, vertices, faces)
    with pytest.raises(hx.MeshInputError, match="faces 12 .* and 13 .*pillow") as caught:
        hx.load(path)
    assert caught.value.element == ("face", 13)
    assert f"line {caught.value.line}" in str(caught.value)


def test_repair_drops_the_second_face_of_a_pillow(tmp_path):
    path = tmp_path / "pillow.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n")
    mesh = hx.load(path, repair=True)
    mesh.validate()
    assert mesh.n_faces == 1 and mesh.repair_report.dropped_duplicate.tolist() == [1]


def test_a_duplicate_face_in_the_same_order_is_still_reported_by_its_directed_edge():
    with pytest.raises(hx.MeshInputError, match="directed edge"):
        hx.HalfedgeMesh.from_faces(TRIANGLE, [[0, 1, 2], [1, 2, 0]])


@pytest.mark.parametrize("command", [["check"], ["subdivide", "OUT", "1"], ["remesh", "OUT"], ["simplify", "OUT", "--faces", "1"]])
def test_commands_refuse_a_pillow_file_as_bad_input_and_write_nothing(tmp_path, command, capsys):
    source = tmp_path / "pillow.obj"
    source.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n")
    output = tmp_path / "out.obj"
    arguments = [command[0], str(source)] + [str(output) if part == "OUT" else part for part in command[1:]]
    assert main(arguments) == 2
    assert "pillow" in capsys.readouterr().err
    assert not output.exists()


# ---- arrays of the wrong kind -----------------------------------------------------------------

@pytest.mark.parametrize("vertices, faces, words", [
    (TRIANGLE + 1j, [[0, 1, 2]], "vertex positions must be real numbers, got complex"),
    (np.array([[1, 0, 0], [0, 1j, 0], [0, 0, 1]], dtype=object), [[0, 1, 2]], "vertex positions must be real numbers, got complex"),
    (TRIANGLE > 0, [[0, 1, 2]], "vertex positions must be real numbers, got True/False"),
    (TRIANGLE, [[True, False, True]], "face indices must be real numbers, got True/False"),
    (TRIANGLE, np.array([[0, 1, 2]]) + 0j, "face indices must be real numbers, got complex"),
    (TRIANGLE, [["0", "1", "2"]], "face indices are not numbers"),
    ([["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]], [[0, 1, 2]], "vertex positions are not numbers"),
], ids=["complex positions", "complex object positions", "boolean positions", "boolean faces", "complex faces",
        "text faces", "text positions"])
def test_values_that_would_convert_with_a_loss_are_refused(vertices, faces, words):
    with pytest.raises(hx.MeshInputError, match=words):
        hx.HalfedgeMesh.from_faces(vertices, faces)


@pytest.mark.parametrize("face_lines", [[4, 5], [], [[4]], [4.5], ["4"]], ids=["too many", "none", "2d", "fraction", "text"])
def test_face_lines_that_do_not_fit_the_faces_are_refused_by_name(face_lines):
    with pytest.raises(hx.MeshInputError, match="face_lines must hold one whole line number per face") as caught:
        hx.HalfedgeMesh.from_faces(TRIANGLE, [[0, 1, 2]], face_lines=face_lines)
    assert caught.value.element == ("argument", "face_lines")


def test_face_lines_are_still_quoted_when_they_fit():
    with pytest.raises(hx.MeshInputError, match="face 1 \\(line 9 of a.obj\\)"):
        hx.HalfedgeMesh.from_faces(TRIANGLE, [[0, 1, 2], [0, 1, 5]], face_lines=[8, 9], source="a.obj")


def test_a_source_that_is_not_text_is_refused_by_name():
    with pytest.raises(hx.MeshInputError, match="source must be a file name") as caught:
        hx.HalfedgeMesh.from_faces(TRIANGLE, [[0, 1, 2]], source=Path("a.obj"))
    assert caught.value.element == ("argument", "source")


def test_to_arrays_refuses_a_face_that_uses_a_vertex_deleted_by_hand():
    # A flag set by hand, with no earlier deletions: never a face holding -1.
    mesh = hx.sample("cube")
    mesh.vertex_deleted[0] = True
    with pytest.raises(hx.MeshInvariantError, match="uses a deleted vertex") as caught:
        mesh.to_arrays()
    assert caught.value.rule == "deleted-reference" and caught.value.element[0] == "face"


def test_counts_of_one_read_in_the_singular():
    with pytest.warns(hx.MeshWarning, match="dropped 1 unreferenced vertex \\(no face uses it\\)"):
        hx.HalfedgeMesh.from_faces(np.vstack([TRIANGLE, [[5.0, 5.0, 5.0]]]), [[0, 1, 2]], drop_unreferenced=True)
    with pytest.raises(IndexError, match="vertices are numbered 0 to 2"):
        hx.HalfedgeMesh.from_faces(TRIANGLE, [[0, 1, 2]]).vertex(7)
