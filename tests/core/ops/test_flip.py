"""Edge flip: hand-worked results, every refusal rule, and the argument checks."""

from __future__ import annotations

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.data import sample
from halfedge_edu.core.ops import can_flip, flip
from tests.core.ops.helpers import assert_same_mesh, assert_unchanged, counts, pillow, snapshot, tent

STRIP_VERTICES = [[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [1.5, 1, 0], [2, 0, 0]]


def test_flip_of_the_strips_interior_edge_joins_the_opposite_vertices():
    strip = sample("strip")  # faces (0, 1, 2), (1, 3, 2), (1, 4, 3); edge 1 is 1 - 2
    assert strip.edge(1).vertices == (strip.vertex(1), strip.vertex(2))
    flipped = flip(strip, 1)
    strip.validate()
    assert {v.index for v in flipped.vertices} == {0, 3}
    assert_same_mesh(strip, (STRIP_VERTICES, [[1, 3, 0], [2, 0, 3], [1, 4, 3]]))


def test_flip_returns_the_same_edge_and_keeps_every_count():
    mesh = sample("icosphere", subdivisions=1)
    before = counts(mesh)
    result = flip(mesh, 7)
    assert result == mesh.edge(7)
    assert counts(mesh) == before
    assert not mesh.has_garbage
    mesh.validate()


def test_flipping_twice_gives_back_the_same_mesh():
    mesh = sample("octahedron")
    original = mesh.copy()
    flip(mesh, 0)
    flip(mesh, 0)
    mesh.validate()
    assert_same_mesh(mesh, original)


def test_edge_index_edge_handle_and_halfedge_handle_are_the_same_argument():
    results = []
    for argument in (lambda m: 3, lambda m: m.edge(3), lambda m: m.halfedge(7)):
        mesh = sample("octahedron")
        flip(mesh, argument(mesh))
        results.append(mesh.to_arrays()[1])
    assert all(np.array_equal(results[0], other) for other in results[1:])


def test_the_mesh_method_is_the_same_operation():
    mesh, other = sample("octahedron"), sample("octahedron")
    assert mesh.can_flip(0)
    mesh.flip(0)
    flip(other, 0)
    assert np.array_equal(mesh.halfedge_next, other.halfedge_next)


def test_flip_refreshes_cached_rings():
    mesh = sample("octahedron")
    degrees = mesh.vertex_degrees().copy()
    mesh.one_rings()
    flip(mesh, 0)  # edge 0 joins 0 and 2; the flip joins 4 and 5 instead
    walk = mesh.one_rings()
    assert np.array_equal(np.diff(walk.offsets), degrees + np.array([-1, 0, -1, 0, 1, 1]))


# ---- refusals ---------------------------------------------------------------------------

def assert_refused(mesh, edge, rule, *words):
    """``can_flip`` refuses with ``rule``; ``flip`` raises the same reason and changes nothing."""
    before = snapshot(mesh)
    check = can_flip(mesh, edge)
    assert not check and check.rule == rule
    for word in words:
        assert word in check.reason
    with pytest.raises(hx.TopologyError) as raised:
        flip(mesh, edge)
    assert raised.value.reason == check.reason and raised.value.rule == rule
    assert_unchanged(mesh, before)
    return check


def test_a_boundary_edge_of_the_strip_is_refused():
    check = assert_refused(sample("strip"), 0, "boundary-edge", "edge 0", "vertices 0 and 1", "boundary")
    assert check.elements == (("edge", 0),)


@pytest.mark.parametrize("edge", range(6))
def test_every_tetrahedron_edge_is_refused_because_the_new_edge_exists(edge):
    mesh = sample("tetrahedron")
    check = assert_refused(mesh, edge, "edge-exists", "already joins", "only 3 edges each")
    a, b = mesh.edge(edge).vertices
    assert f"Vertices {a.index} and {b.index}" in check.reason


def test_an_edge_at_the_cubes_degree_3_corner_is_refused_and_the_reason_says_why():
    # Edge 0 joins corner 0 (degree 3) to vertex 4; its opposite vertices 2 and 1 are joined.
    assert_refused(sample("cube"), 0, "edge-exists", "join vertices 2 and 1", "Vertex 0 has only 3 edges")


def test_an_existing_edge_refuses_the_flip_even_without_a_degree_3_endpoint():
    check = assert_refused(tent(), 0, "edge-exists", "would join vertices 2 and 3", "edge 8 already joins them")
    assert "only 3 edges" not in check.reason


def test_two_triangles_glued_back_to_back_cannot_be_flipped():
    assert_refused(pillow(), 0, "same-opposite-vertex", "back to back")


# ---- arguments ---------------------------------------------------------------------------

def test_an_edge_that_does_not_exist_is_an_index_error():
    mesh = sample("tetrahedron")
    with pytest.raises(IndexError, match="no edge 6"):
        can_flip(mesh, 6)
    with pytest.raises(IndexError, match="no edge -1"):
        flip(mesh, -1)


def test_a_deleted_edge_is_an_index_error():
    mesh = sample("octahedron")
    mesh.delete_edge(2)
    with pytest.raises(IndexError, match="edge 2 was deleted"):
        flip(mesh, 2)


def test_a_vertex_handle_or_a_foreign_edge_is_refused():
    mesh = sample("octahedron")
    with pytest.raises(TypeError):
        flip(mesh, mesh.vertex(0))
    with pytest.raises(TypeError):
        flip(mesh, 1.5)
    with pytest.raises(ValueError, match="another mesh"):
        flip(mesh, sample("octahedron").edge(0))
