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


# ---- navigation ---------------------------------------------------------------------------

@given(meshes())
def test_navigation_identities_hold_for_every_halfedge(drawn):
    mesh = build(drawn)
    for h in mesh.halfedges:
        assert h.twin.twin == h
        assert h.twin != h
        assert h.next.prev == h and h.prev.next == h
        assert h.tip == h.twin.vertex == h.next.vertex
        assert h.edge == h.twin.edge and h.edge.index == h.index >> 1
        if h.face is not None:
            assert h.next.next.next == h
            assert h.next.face == h.face
            assert not h.is_boundary
        else:
            assert h.is_boundary and h.next.is_boundary
            assert h.twin.face is not None


@given(meshes())
def test_outgoing_halfedges_leave_the_vertex_in_ccw_order(drawn):
    mesh = build(drawn)
    degrees = mesh.vertex_degrees()
    for v in mesh.vertices:
        ring = v.outgoing()
        assert ring[0] == v.halfedge
        assert all(h.vertex == v for h in ring)
        assert len(ring) == len(set(ring)) == v.degree == degrees[v.index]
        # Each next one is reached by h -> h.prev.twin, and the ring closes.
        for h, after in zip(ring, ring[1:] + ring[:1]):
            assert after == h.prev.twin
        assert [int(h.edge) for h in ring] == [int(e) for e in v.edges()]


def test_outgoing_turns_counter_clockwise_around_a_flat_fan(vertex_onering):
    center = vertex_onering.vertex(0)
    tips = np.array([h.tip.position[:2] for h in center.outgoing()])
    angles = np.arctan2(tips[:, 1], tips[:, 0])
    turns = np.diff(np.append(angles, angles[0])) % (2 * np.pi)
    assert np.allclose(turns, 2 * np.pi / 6)
    # Rim vertex 1 + k sits at angle 2 pi k / 6, so counter-clockwise means counting up.
    rim = [v.index for v in center.neighbors()]
    assert all(after == here % 6 + 1 for here, after in zip(rim, rim[1:] + rim[:1]))


def test_outgoing_turns_counter_clockwise_seen_from_outside_a_sphere(icosphere):
    for v in icosphere.vertices:
        tips = [h.tip.position for h in v.outgoing()]
        for a, b in zip(tips, tips[1:] + tips[:1]):
            # Consecutive tips and the vertex make a CCW triangle, whose normal points out.
            assert np.dot(np.cross(a - v.position, b - v.position), v.position) > 0


def test_ring_of_a_boundary_vertex_starts_on_the_boundary_and_skips_the_gap(open_fan):
    # Vertex 0 with rim 1, 2, 3, 4 on a half circle; faces [0, 1, 2], [0, 2, 3], [0, 3, 4].
    apex = open_fan.vertex(0)
    assert apex.is_boundary and apex.halfedge.is_boundary
    assert [v.index for v in apex.neighbors()] == [4, 1, 2, 3]
    assert [h.face for h in apex.outgoing()] == [None, open_fan.face(0), open_fan.face(1), open_fan.face(2)]
    assert apex.faces() == [open_fan.face(0), open_fan.face(1), open_fan.face(2)]
    assert apex.degree == 4


@given(meshes())
def test_boundary_vertices_point_at_their_outgoing_boundary_halfedge(drawn):
    mesh = build(drawn)
    flags = mesh.vertex_is_boundary()
    for v in mesh.vertices:
        on_boundary = any(h.is_boundary for h in v.outgoing())
        assert v.is_boundary == on_boundary == flags[v.index]
        assert v.halfedge.is_boundary == on_boundary
        assert sum(h.is_boundary for h in v.outgoing()) == int(on_boundary)


@given(meshes())
def test_neighbors_are_the_rows_of_vertex_adjacency(drawn):
    mesh = build(drawn)
    offsets, neighbors = mesh.vertex_adjacency()
    assert offsets[-1] == mesh.n_halfedges
    for v in mesh.vertices:
        assert [u.index for u in v.neighbors()] == neighbors[offsets[v.index]: offsets[v.index + 1]].tolist()


@given(meshes())
def test_vertex_faces_skip_the_boundary_gap(drawn):
    mesh = build(drawn)
    vertices, faces = drawn
    for v in mesh.vertices:
        around = v.faces()
        assert len(around) == v.degree - int(v.is_boundary)
        assert sorted(f.index for f in around) == np.flatnonzero((faces == v.index).any(axis=1)).tolist()


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


# ---- finding edges --------------------------------------------------------------------

@given(meshes())
def test_find_halfedge_finds_each_halfedge_by_its_ends(drawn):
    mesh = build(drawn)
    for h in mesh.halfedges:
        i, j = h.vertex.index, h.tip.index
        assert mesh.find_halfedge(i, j) == h
        assert mesh.find_halfedge(j, i) == h.twin
        assert mesh.find_edge(i, j) == mesh.find_edge(j, i) == h.edge


def test_find_returns_none_for_vertices_that_are_not_joined(octahedron, grid):
    # Octahedron vertices 0 (+x) and 1 (-x) are opposite; so are grid corners 0 and 11.
    assert octahedron.find_halfedge(0, 1) is None
    assert octahedron.find_edge(1, 0) is None
    assert grid.find_halfedge(0, 11) is None
    assert grid.find_halfedge(0, 0) is None


def test_find_halfedge_gives_the_direction_asked_for(square):
    assert square.find_halfedge(0, 2).index == 5
    assert square.find_halfedge(2, 0).index == 4
    assert square.find_edge(0, 2).index == square.find_edge(2, 0).index == 2


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
