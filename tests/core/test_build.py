"""Building a halfedge mesh from faces: numbering, agreement with the reference loop, input errors, export."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.core.manifold import manifold_report
from tests import strategies as shapes
from tests.strategies import build, disjoint_union, meshes, square, tetrahedron

ARRAY_NAMES = (
    "vertex_halfedge", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face", "face_halfedge",
)


# ---- the vectorized build is the course's loop ---------------------------------------

@given(meshes())
def test_strategies_draw_manifold_meshes(drawn):
    vertices, faces = drawn
    assert vertices.dtype == np.float64 and vertices.shape[1] == 3
    assert faces.dtype == np.int64 and faces.shape[1] == 3
    assert manifold_report(faces, len(vertices))
    assert np.array_equal(np.unique(faces), np.arange(len(vertices)))


def _canonical_rows(faces: np.ndarray) -> set[tuple[int, int, int]]:
    """Each face rotated to start at its smallest vertex (rotation keeps orientation)."""
    return {tuple(np.roll(row, -int(np.argmin(row))).tolist()) for row in faces}


@given(st.integers(0, 2**32 - 1))
def test_relabel_shuffles_numbering_but_keeps_the_oriented_surface(seed):
    vertices, faces = shapes.torus(5, 4)
    new_vertices, new_faces = shapes.relabel(vertices, faces, np.random.default_rng(seed))
    # Positions are distinct, so each new vertex can be traced back to its old number.
    old_number = {tuple(p): k for k, p in enumerate(vertices.tolist())}
    traced = np.array([old_number[tuple(p)] for p in new_vertices.tolist()])[new_faces]
    assert _canonical_rows(traced) == _canonical_rows(faces)


@given(meshes())
def test_vectorized_build_equals_reference_loop(drawn):
    vertices, faces = drawn
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    reference = hx.build_reference(faces, n_vertices=len(vertices))
    for name in ARRAY_NAMES:
        assert np.array_equal(getattr(mesh, name), getattr(reference, name)), name


@given(meshes())
def test_both_sorting_paths_order_directed_edges_alike(drawn):
    # Small meshes pack the position into the key; huge vertex counts fall back to a
    # stable argsort. Both must list directed edges by (low, high) vertex, ties in order.
    from halfedge_edu.core.arrays import sort_undirected

    _, faces = drawn
    tail = faces.reshape(-1).astype(np.int32)
    head = faces[:, [1, 2, 0]].reshape(-1).astype(np.int32)
    expected = np.lexsort((np.arange(len(tail)), np.maximum(tail, head), np.minimum(tail, head)))
    packed_order, _ = sort_undirected(tail, head, int(faces.max()) + 1)
    fallback_order, _ = sort_undirected(tail, head, 2**31 - 1)
    assert np.array_equal(packed_order, expected)
    assert np.array_equal(fallback_order, expected)


def test_two_triangle_square_is_numbered_as_in_the_course():
    # 3 --- 2      face 0 = [0, 1, 2], face 1 = [0, 2, 3]
    # |   / |
    # | /   |
    # 0 --- 1
    mesh = hx.HalfedgeMesh.from_faces(*square())
    # Face 0 is read first, corner by corner:
    #   (0, 1) is new: edge 0, halfedge 0 runs 0 -> 1
    #   (1, 2) is new: edge 1, halfedge 2 runs 1 -> 2
    #   (2, 0) is new: edge 2, halfedge 4 runs 2 -> 0
    # Face 1:
    #   (0, 2) is edge 2 seen the second time: its twin, halfedge 5, runs 0 -> 2
    #   (2, 3) is new: edge 3, halfedge 6 runs 2 -> 3
    #   (3, 0) is new: edge 4, halfedge 8 runs 3 -> 0
    # Edges 0, 1, 3, 4 were seen once: their odd halfedges 1, 3, 7, 9 are the boundary,
    # running the other way: 1 = 1 -> 0, 3 = 2 -> 1, 7 = 3 -> 2, 9 = 0 -> 3.
    assert mesh.n_edges == 5 and mesh.n_halfedges == 10
    assert mesh.halfedge_vertex.tolist() == [0, 1, 1, 2, 2, 0, 2, 3, 3, 0]
    assert mesh.halfedge_face.tolist() == [0, -1, 0, -1, 0, 1, 1, -1, 1, -1]
    # Inside the faces next follows the corners: 0 -> 2 -> 4 -> 0 and 5 -> 6 -> 8 -> 5.
    # The boundary loop runs clockwise seen from above, 1 -> 0 -> 3 -> 2 -> 1:
    # halfedge 1 (1 -> 0) continues with 9 (0 -> 3), then 7 (3 -> 2), then 3 (2 -> 1).
    assert mesh.halfedge_next.tolist() == [2, 9, 4, 1, 0, 6, 8, 3, 5, 7]
    # prev is next read backwards: next[4] = 0 so prev[0] = 4, next[3] = 1 so prev[1] = 3, ...
    assert mesh.halfedge_prev.tolist() == [4, 3, 0, 7, 2, 8, 5, 9, 6, 1]
    # Every vertex is on the boundary, so each points at its outgoing boundary halfedge.
    assert mesh.vertex_halfedge.tolist() == [9, 1, 3, 7]
    # A face's halfedge is the one made by its first corner.
    assert mesh.face_halfedge.tolist() == [0, 5]


def test_interior_vertex_points_at_its_smallest_outgoing_halfedge():
    # The tetrahedron has no boundary: vertex 0 leaves along halfedges 0 (0 -> 1) and more.
    mesh = hx.HalfedgeMesh.from_faces(*tetrahedron())
    origins = mesh.halfedge_vertex
    expected = [int(np.flatnonzero(origins == v)[0]) for v in range(4)]
    assert mesh.vertex_halfedge.tolist() == expected


# ---- counts against trimesh -----------------------------------------------------------

@given(meshes())
def test_counts_and_degrees_agree_with_trimesh(drawn):
    vertices, faces = drawn
    mesh = build(drawn)
    tm = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    assert mesh.n_vertices == len(tm.vertices)
    assert mesh.n_faces == len(tm.faces)
    assert mesh.n_edges == len(tm.edges_unique)
    assert mesh.n_halfedges == 2 * len(tm.edges_unique)
    assert mesh.vertex_degrees().tolist() == [len(ring) for ring in tm.vertex_neighbors]
    boundary_edges = trimesh.grouping.group_rows(tm.edges_sorted, require_count=1)
    assert int((mesh.halfedge_face == -1).sum()) == len(boundary_edges)
    assert mesh.euler_characteristic == tm.euler_number


@given(meshes())
def test_face_rows_round_trip(drawn):
    vertices, faces = drawn
    mesh = build(drawn)
    assert np.array_equal(mesh.face_vertices(), faces)
    out_vertices, out_faces = mesh.to_arrays()
    assert np.array_equal(out_vertices, vertices)
    assert np.array_equal(out_faces, faces)


def test_topology_needs_no_positions_from_the_reference():
    reference = hx.build_reference(square()[1])
    assert reference.positions.shape == (4, 3)
    assert not reference.positions.any()


def test_input_is_copied_not_referenced():
    vertices, faces = square()
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    vertices[0] = 99.0
    faces[0] = [3, 2, 1]
    assert mesh.positions[0].tolist() == [0.0, 0.0, 0.0]
    assert mesh.face_vertices()[0].tolist() == [0, 1, 2]


def test_lists_and_whole_float_indices_are_accepted():
    vertices, faces = square()
    mesh = hx.HalfedgeMesh.from_faces(vertices.tolist(), faces.astype(float).tolist())
    assert mesh.face_vertices().tolist() == faces.tolist()


# ---- rejected input --------------------------------------------------------------------

def _two_tetrahedra_sharing_vertex_0():
    vertices, faces = tetrahedron()
    other = faces.copy() + 3
    other[other == 3] = 0                     # the second tetrahedron's vertex 0 is vertex 0
    return np.vstack([vertices, vertices[1:] + 3.0]), np.vstack([faces, other])


BOWTIE = (np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [-1, 0, 0], [-1, -1, 0]], dtype=float), [[0, 1, 2], [0, 3, 4]])
FIVE = np.arange(15, dtype=float).reshape(5, 3)

# (name, vertices, faces, element, texts the message must contain)
BAD_TOPOLOGY = [
    ("index out of range", FIVE, [[0, 1, 2], [0, 2, 7]], ("face", 1), ["face 1", "7", "0 to 4"]),
    ("negative index", FIVE, [[0, 1, 2], [0, -1, 2]], ("face", 1), ["face 1", "-1"]),
    ("degenerate face", FIVE, [[0, 1, 2], [3, 3, 4]], ("face", 1), ["face 1", "degenerate"]),
    ("flipped face", *square()[:1], [[0, 1, 2], [0, 3, 2]], ("edge", (2, 0)), ["(2, 0)", "face 0", "face 1"]),
    ("duplicate face", FIVE[:3], [[0, 1, 2], [0, 1, 2]], ("edge", (0, 1)), ["(0, 1)", "face 0", "face 1"]),
    ("rotated duplicate", FIVE[:3], [[0, 1, 2], [1, 2, 0]], ("edge", (0, 1)), ["(0, 1)", "face 0", "face 1"]),
    ("edge with three faces", FIVE, [[0, 1, 2], [1, 0, 3], [1, 0, 4]], ("edge", (0, 1)), ["(0, 1)", "3 faces"]),
    ("two closed fans", *_two_tetrahedra_sharing_vertex_0(), ("vertex", 0), ["vertex 0", "non-manifold"]),
    ("bowtie", *BOWTIE, ("vertex", 0), ["vertex 0", "non-manifold"]),
]


@pytest.mark.parametrize(
    "vertices, faces, element, texts", [case[1:] for case in BAD_TOPOLOGY], ids=[case[0] for case in BAD_TOPOLOGY]
)
def test_bad_faces_are_rejected_naming_the_element(vertices, faces, element, texts):
    with pytest.raises(hx.MeshInputError) as caught:
        hx.HalfedgeMesh.from_faces(vertices, faces)
    assert caught.value.element == element
    for text in texts:
        assert text in str(caught.value)
    assert isinstance(caught.value, ValueError)


@pytest.mark.parametrize(
    "vertices, faces, element",
    [case[1:4] for case in BAD_TOPOLOGY[3:]],
    ids=[case[0] for case in BAD_TOPOLOGY[3:]],
)
def test_reference_loop_rejects_the_same_topology(vertices, faces, element):
    with pytest.raises(hx.MeshInputError) as caught:
        hx.build_reference(faces, n_vertices=len(vertices))
    kind, index = element
    assert caught.value.element[0] == kind
    if kind == "vertex":
        assert caught.value.element[1] == index
    else:
        # The loop meets the edges in face order, so it may name another edge of the faces.
        assert set(caught.value.element[1]) <= set(np.ravel(faces).tolist())


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_coordinate_is_rejected_naming_the_vertex(bad):
    vertices, faces = square()
    vertices[2, 1] = bad
    with pytest.raises(hx.MeshInputError, match="vertex 2") as caught:
        hx.HalfedgeMesh.from_faces(vertices, faces)
    assert caught.value.element == ("vertex", 2)


@pytest.mark.parametrize(
    "vertices, faces, text",
    [
        (np.zeros((4, 2)), [[0, 1, 2]], "(n, 3)"),
        (np.zeros(12), [[0, 1, 2]], "(n, 3)"),
        (np.zeros((4, 3)), [[0, 1, 2, 3]], "triangles"),
        (np.zeros((4, 3)), [[0, 1], [1, 2]], "at least 3"),
        (np.zeros((4, 3)), [0, 1, 2], "(m, 3)"),
        (np.zeros((4, 3)), [[0, 1, 2], [0, 2]], "(m, 3)"),
        (np.zeros((4, 3)), [[0, 1.5, 2]], "whole numbers"),
        ([["a", "b", "c"]], [[0, 1, 2]], "not numbers"),
    ],
    ids=[
        "2d vertices", "flat vertices", "quads", "edges", "flat faces", "ragged faces", "fractional index",
        "text",
    ],
)
def test_wrong_shapes_and_types_are_rejected(vertices, faces, text):
    with pytest.raises(hx.MeshInputError) as caught:
        hx.HalfedgeMesh.from_faces(vertices, faces)
    assert text in str(caught.value)


FILE_CASES = [case for case in BAD_TOPOLOGY if case[3][0] != "vertex"]


@pytest.mark.parametrize(
    "vertices, faces", [case[1:3] for case in FILE_CASES], ids=[case[0] for case in FILE_CASES]
)
def test_message_names_the_file_line_of_the_offending_face(vertices, faces):
    face_lines = np.arange(len(faces)) + 10           # face k came from line 10 + k
    with pytest.raises(hx.MeshInputError) as caught:
        hx.HalfedgeMesh.from_faces(vertices, faces, face_lines=face_lines, source="shape.obj")
    last_face = len(faces) - 1                        # every case is found at its last face
    assert caught.value.line == 10 + last_face
    assert f"line {10 + last_face} of shape.obj" in str(caught.value)


def test_unreferenced_vertices_are_dropped_with_a_warning_keeping_the_order():
    vertices = np.arange(18, dtype=float).reshape(6, 3)
    faces = np.array([[0, 2, 3], [0, 3, 5]])
    with pytest.warns(hx.MeshWarning, match="dropped 2 unreferenced vertices.*1, 4"):
        mesh = hx.HalfedgeMesh.from_faces(vertices, faces, drop_unreferenced=True)
    assert mesh.n_vertices == 4
    assert np.array_equal(mesh.positions, vertices[[0, 2, 3, 5]])
    assert mesh.face_vertices().tolist() == [[0, 1, 2], [0, 2, 3]]
    mesh.validate()


@pytest.mark.parametrize(
    "faces, element",
    [
        ([[1, 2, 3], [1, 4, 5]], ("vertex", 1)),
        ([[1, 2, 3], [2, 1, 4], [2, 1, 5]], ("edge", (1, 2))),
        ([[1, 2, 3], [1, 2, 4]], ("edge", (1, 2))),
        ((_two_tetrahedra_sharing_vertex_0()[1] + 1).tolist(), ("vertex", 1)),
    ],
    ids=["bowtie", "edge with three faces", "flipped face", "two closed fans"],
)
def test_errors_name_vertices_as_numbered_in_the_input_even_when_some_are_dropped(faces, element):
    # Vertex 0 is used by no face and is dropped before the halfedges are built; the
    # error must still name the vertices the way the caller (or the file) numbers them.
    vertices = np.arange(3.0 * (1 + np.max(faces))).reshape(-1, 3)
    with pytest.warns(hx.MeshWarning), pytest.raises(hx.MeshInputError) as caught:
        hx.HalfedgeMesh.from_faces(vertices, faces, drop_unreferenced=True)
    assert caught.value.element == element
    name = f"vertex {element[1]}" if element[0] == "vertex" else str(element[1])
    assert name in str(caught.value)


def test_unreferenced_vertices_stay_at_their_input_index_as_isolated_vertices():
    vertices = np.arange(18, dtype=float).reshape(6, 3)
    faces = np.array([[0, 2, 3], [0, 3, 5]])
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    assert mesh.n_vertices == 6 and np.array_equal(mesh.positions, vertices)
    assert mesh.face_vertices().tolist() == faces.tolist()
    assert mesh.vertex_halfedge[[1, 4]].tolist() == [-1, -1]
    mesh.validate()
    kept_vertices, kept_faces = mesh.to_arrays()
    assert np.array_equal(kept_vertices, vertices) and kept_faces.tolist() == faces.tolist()
    compact_vertices, compact_faces = mesh.to_arrays(compact=True)
    assert np.array_equal(compact_vertices, vertices[[0, 2, 3, 5]])
    assert compact_faces.tolist() == [[0, 1, 2], [0, 2, 3]]


def test_errors_name_input_vertices_when_unreferenced_ones_are_kept():
    vertices = np.arange(18.0).reshape(6, 3)
    with pytest.raises(hx.MeshInputError) as caught:
        hx.HalfedgeMesh.from_faces(vertices, [[1, 2, 3], [1, 4, 5]])
    assert caught.value.element == ("vertex", 1)


def test_a_pillow_of_two_triangles_is_refused_naming_both_faces():
    # Two faces on the same three vertices: manifold_report calls it a duplicate face,
    # repair_faces drops it, and no algorithm can refine or simplify it.
    with pytest.raises(hx.MeshInputError, match="faces 0 and 1 .*pillow") as caught:
        hx.HalfedgeMesh.from_faces(np.eye(3), [[0, 1, 2], [0, 2, 1]])
    assert caught.value.element == ("face", 1)


# ---- export and interop ----------------------------------------------------------------

@given(meshes())
def test_to_arrays_gives_compact_float64_and_int64_copies(drawn):
    mesh = build(drawn)
    vertices, faces = mesh.to_arrays()
    assert vertices.shape == (mesh.n_vertices, 3) and vertices.dtype == np.float64
    assert faces.shape == (mesh.n_faces, 3) and faces.dtype == np.int64
    vertices[0] = 123.0
    assert not np.array_equal(mesh.positions[0], vertices[0])


@given(meshes())
def test_trimesh_round_trip(drawn):
    vertices, faces = drawn
    mesh = build(drawn)
    tm = mesh.to_trimesh()
    assert isinstance(tm, trimesh.Trimesh)
    assert np.array_equal(tm.vertices, vertices)
    assert np.array_equal(tm.faces, faces)
    again = hx.HalfedgeMesh.from_trimesh(tm)
    for name in ARRAY_NAMES + ("positions",):
        assert np.array_equal(getattr(again, name), getattr(mesh, name)), name


def test_from_trimesh_keeps_trimesh_numbering():
    tm = trimesh.creation.icosphere(subdivisions=1)
    mesh = hx.HalfedgeMesh.from_trimesh(tm)
    assert np.array_equal(mesh.positions, tm.vertices)
    assert np.array_equal(mesh.face_vertices(), tm.faces)
    assert mesh.is_closed and mesh.genus == 0


def test_to_pyvista_has_the_same_points_and_triangles():
    mesh = hx.HalfedgeMesh.from_faces(*disjoint_union(square(), tetrahedron()))
    polydata = mesh.to_pyvista()
    assert polydata.n_points == mesh.n_vertices
    assert polydata.n_cells == mesh.n_faces
    assert np.array_equal(np.asarray(polydata.points, dtype=float), mesh.positions)
    assert np.array_equal(polydata.regular_faces, mesh.face_vertices())
