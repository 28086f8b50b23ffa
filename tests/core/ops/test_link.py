"""Links of vertices and edges, and the link condition spelled out (chapter 08)."""

from __future__ import annotations

import pytest

from halfedge_edu.data import sample
from halfedge_edu.core.ops import link_condition, link_of_edge, link_of_vertex, link_violation
from halfedge_edu.core.ops.link import BOUNDARY, halfedge_between, one_ring, outgoing


def test_the_link_of_an_interior_vertex_is_the_polygon_around_it():
    octahedron = sample("octahedron")  # vertex 4 (+z) has the square 0, 2, 1, 3 around it
    link = link_of_vertex(octahedron, 4)
    assert link.vertices == {0, 1, 2, 3}
    assert link.edges == {(0, 2), (1, 2), (1, 3), (0, 3)}


def test_the_link_of_a_boundary_vertex_reaches_the_boundary_vertex():
    strip = sample("strip")  # vertex 0 is a corner of face (0, 1, 2) only
    link = link_of_vertex(strip, 0)
    assert link.vertices == {1, 2, BOUNDARY}
    assert link.edges == {(1, 2), (BOUNDARY, 1), (BOUNDARY, 2)}


def test_the_link_of_an_edge_is_its_opposite_vertices():
    strip = sample("strip")
    assert link_of_edge(strip, 1).vertices == {0, 3}
    assert link_of_edge(strip, 0).vertices == {2, BOUNDARY}
    assert not link_of_edge(strip, 0).edges


def test_the_link_condition_holds_for_an_ordinary_edge():
    result = link_condition(sample("single_collapse"), 0)
    assert result and result.holds
    assert result.shared == result.link_ab
    assert result.shared.vertices == {4, 8}


def test_a_shared_extra_neighbour_breaks_it():
    cube = sample("cube")
    result = link_condition(cube, cube.find_edge(2, 4))
    assert not result
    assert result.extra.vertices == {1}


def test_the_tetrahedron_breaks_it_with_an_edge():
    result = link_condition(sample("tetrahedron"), 0)  # edge 0 - 1; opposite 2 and 3
    assert not result
    assert not result.extra.vertices
    assert result.extra.edges == {(2, 3)}


def test_the_boundary_vertex_breaks_it_for_the_figure8_and_the_lone_triangle():
    assert link_condition(sample("figure8"), 0).extra.vertices == {BOUNDARY}
    lone = link_condition(sample("lone_triangle"), 0)  # edge 0 - 1, opposite 2
    assert lone.extra.edges == {(BOUNDARY, 2)}


def test_ring_walks_are_counter_clockwise_and_find_edges():
    fan = sample("single_collapse")
    assert one_ring(fan, 0) == [fan.halfedge(h).tip.index for h in outgoing(fan, 0)]
    assert [v.index for v in fan.vertex(0).neighbors()] == one_ring(fan, 0)
    assert halfedge_between(fan, 0, 1) == 0
    assert halfedge_between(fan, 0, 2) == -1


@pytest.mark.parametrize("name", ["tetrahedron", "cube", "open_patch", "figure8", "lone_triangle", "strip"])
def test_link_violation_is_the_set_difference_on_every_edge(name):
    """The ring-only answer equals link(a) ∩ link(b) - link(ab) built from the full links."""
    mesh = sample(name)
    for e in range(mesh.n_edges):
        a, b = mesh.edge(e).vertices
        full = (link_of_vertex(mesh, a.index) & link_of_vertex(mesh, b.index)) - link_of_edge(mesh, e)
        assert link_violation(mesh, e) == full, e
