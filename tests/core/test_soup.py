"""SoupTopology: a face list's topology built without breaking, and UChicago P3's two questions."""

from __future__ import annotations

import pytest

import halfedge_edu as hx
from halfedge_edu.core.soup import SoupTopology


def test_a_non_manifold_edge_builds_and_is_found():
    soup = SoupTopology(hx.sample("nonmanifold_edge").faces)
    assert soup.faces_of_edge(0, 1) == [0, 1, 2]
    assert soup.nonmanifold_edges() == [(0, 1)]
    assert soup.has_nonmanifold_edges() and not soup.has_nonmanifold_vertices()


def test_a_non_manifold_vertex_builds_and_is_found_with_its_two_fans():
    soup = SoupTopology(hx.sample("nonmanifold_vertex").faces)
    assert soup.fans(0) == [[0, 1, 2], [4, 5, 6]]
    assert soup.nonmanifold_vertices() == [0]
    assert soup.has_nonmanifold_vertices() and not soup.has_nonmanifold_edges()


@pytest.mark.parametrize("name", ["tetrahedron", "cube", "open_patch", "strip", "lone_triangle"])
def test_a_manifold_mesh_has_neither(name):
    soup = SoupTopology(hx.sample(name).to_arrays()[1])
    assert not soup.has_nonmanifold_edges() and not soup.has_nonmanifold_vertices()


def test_halfedges_go_round_their_face_and_twins_pair_only_where_two_run_opposite_ways():
    soup = SoupTopology([[0, 1, 2], [0, 2, 3]])
    assert soup.halfedge_next.tolist() == [1, 2, 0, 4, 5, 3]
    assert soup.halfedge_twin.tolist() == [-1, -1, 3, 2, -1, -1]
    book = SoupTopology(hx.sample("nonmanifold_edge").faces)
    assert all(book.halfedge_twin[h] == -1 for h in book.halfedges_of_edge(0, 1))


def test_faces_joined_only_away_from_the_vertex_are_two_fans():
    """Two triangles at vertex 0, joined through other faces that do not touch 0: two fans at 0,
    however connected the surface is elsewhere."""
    soup = SoupTopology([[0, 1, 2], [0, 3, 4], [2, 1, 5], [2, 5, 3]])
    assert soup.fans(0) == [[0], [1]] and 0 in soup.nonmanifold_vertices()
    assert soup.fans(2) == [[0, 2, 3]]
