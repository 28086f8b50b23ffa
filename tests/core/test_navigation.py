"""Walking the mesh: navigation identities, counter-clockwise rings, boundaries, finding edges."""

from __future__ import annotations

import numpy as np
from hypothesis import given

from tests.strategies import build, meshes


# ---- halfedges ------------------------------------------------------------------------------

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


# ---- around a vertex ---------------------------------------------------------------------------

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


def test_an_isolated_vertex_is_not_on_the_boundary_in_either_view(square):
    # add_vertex leaves vertex_halfedge at -1; the array view must not read halfedge -1.
    v = square.add_vertex([5.0, 5.0, 5.0])
    assert not square.vertex(v).is_boundary
    assert square.vertex_is_boundary().tolist() == [True, True, True, True, False]


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
def test_one_rings_of_all_vertices_at_once_equal_the_one_by_one_walk(drawn):
    mesh = build(drawn)
    walk = mesh.one_rings()
    assert walk.vertices.tolist() == list(range(mesh.n_vertices))
    assert walk.closed.all()
    for row, v in enumerate(mesh.vertices):
        ring = walk.halfedges[walk.offsets[row]: walk.offsets[row + 1]]
        assert ring.tolist() == [h.index for h in v.outgoing()]


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
