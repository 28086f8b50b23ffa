"""Element handles: what they are (equality, hashing, int, repr) and what they measure."""

from __future__ import annotations

import operator

import numpy as np
import pytest
import trimesh
from hypothesis import given

import halfedge_edu as hx
from tests import strategies as shapes
from tests.strategies import build, meshes


# ---- identity ---------------------------------------------------------------------------

def test_handles_of_the_same_kind_mesh_and_index_are_equal(square):
    assert square.halfedge(3) == square.halfedge(3)
    assert square.halfedge(3) != square.halfedge(4)
    assert square.vertex(1) == square.halfedge(2).vertex


def test_handles_of_different_kinds_or_meshes_differ(square):
    assert square.vertex(1) != square.edge(1)
    assert square.edge(1) != square.face(1)
    assert square.face(0) != square.copy().face(0)
    assert square.vertex(0) != 0


def test_handles_hash_by_kind_and_index(square):
    seen = {square.halfedge(0), square.halfedge(0), square.halfedge(0).next.next.next}
    assert seen == {square.halfedge(0)}
    by_vertex = {square.vertex(2): "two"}
    assert by_vertex[square.halfedge(2).tip] == "two"
    assert len({square.vertex(1), square.edge(1), square.face(1), square.halfedge(1)}) == 4


def test_handles_convert_to_their_index(square):
    assert int(square.vertex(2)) == 2
    assert operator.index(square.edge(3)) == 3
    assert square.halfedge(7).index == 7
    assert np.array_equal(square.positions[square.vertex(2)], [1.0, 1.0, 0.0])
    assert [0, 10, 20, 30][square.face(1)] == 10


def test_reprs_name_the_index_and_what_it_joins(square):
    assert repr(square.halfedge(0)) == "Halfedge(0: 0 -> 1, face 0)"
    assert repr(square.halfedge(1)) == "Halfedge(1: 1 -> 0, boundary)"
    assert repr(square.vertex(2)) == "Vertex(2: (1, 1, 0))"
    assert repr(square.edge(0)) == "Edge(0: boundary 0 - 1)"
    assert repr(square.edge(2)) == "Edge(2: 2 - 0)"
    assert repr(square.face(1)) == "Face(1: [0, 2, 3])"


# ---- what elements measure ------------------------------------------------------------

@given(meshes())
def test_face_corners_normal_and_area_agree_with_trimesh(drawn):
    vertices, faces = drawn
    mesh = build(drawn)
    tm = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    for f in mesh.faces:
        assert [v.index for v in f.vertices()] == faces[f.index].tolist()
        assert [h.face for h in f.halfedges()] == [f, f, f]
        assert f.halfedges()[0] == f.halfedge
        assert np.allclose(f.normal, tm.face_normals[f.index], atol=1e-9)
        assert np.isclose(f.area, tm.area_faces[f.index])
        assert len(f.edges()) == 3


def test_face_normal_of_the_square_points_up(square):
    assert np.allclose(square.face(0).normal, [0, 0, 1])
    assert square.face(0).area == pytest.approx(0.5)
    assert np.allclose(square.face(1).centroid, [1 / 3, 2 / 3, 0])


@given(meshes())
def test_edges_know_their_ends_length_and_boundary(drawn):
    vertices, _ = drawn
    mesh = build(drawn)
    for e in mesh.edges:
        a, b = e.vertices
        assert e.halfedge.index == 2 * e.index
        assert (e.halfedge.vertex, e.halfedge.tip) == (a, b)
        assert e.length == pytest.approx(np.linalg.norm(vertices[b.index] - vertices[a.index]))
        assert e.is_boundary == (e.halfedge.is_boundary or e.halfedge.twin.is_boundary)
        assert len(e.faces()) == 2 - int(e.is_boundary)
        assert np.allclose(e.midpoint, (vertices[a.index] + vertices[b.index]) / 2)


def test_writing_a_position_moves_the_vertex(square):
    square.vertex(2).position = [2.0, 2.0, 0.0]
    assert square.positions[2].tolist() == [2.0, 2.0, 0.0]
    square.vertex(2).position[2] = 5.0
    assert square.positions[2, 2] == 5.0
    assert square.edge(1).length == pytest.approx(np.sqrt(1 + 4 + 25))


# ---- bad indices ----------------------------------------------------------------------------

@pytest.mark.parametrize(
    "kind, index",
    [("vertex", 4), ("vertex", -1), ("halfedge", 10), ("halfedge", -1), ("edge", 5), ("face", 2), ("face", -3)],
)
def test_out_of_range_indices_raise_index_error(square, kind, index):
    with pytest.raises(IndexError, match=f"no {kind} {index}"):
        getattr(square, kind)(index)


def test_deleted_elements_raise_index_error(square):
    square.delete_face(1)
    square.delete_edge(3)
    square.delete_vertex(3)
    for kind, index in [("face", 1), ("edge", 3), ("halfedge", 6), ("halfedge", 7), ("vertex", 3)]:
        with pytest.raises(IndexError, match="deleted"):
            getattr(square, kind)(index)
    assert square.halfedge(5).vertex.index == 0


def test_element_lists_hold_only_live_elements(square):
    square.delete_face(1)
    square.delete_edge(3)
    assert len(square.faces) == 1 and [f.index for f in square.faces] == [0]
    assert [e.index for e in square.edges] == [0, 1, 2, 4]
    assert [h.index for h in square.halfedges] == [0, 1, 2, 3, 4, 5, 8, 9]
    assert square.edges[3] == square.edge(4)
    assert len(square.vertices) == 4
    assert repr(square.faces) == "<1 live faces>"


def test_handles_on_a_fresh_mesh_need_no_fixture():
    mesh = hx.HalfedgeMesh.from_faces(*shapes.square())
    assert mesh.halfedge(0).next.twin.vertex.index == 2

