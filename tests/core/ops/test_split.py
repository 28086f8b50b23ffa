"""Edge split: hand-worked results inside and on the boundary, counts, the new vertex's halfedge."""

from __future__ import annotations

import numpy as np
import pytest

from halfedge_edu.data import sample
import halfedge_edu as hx
from halfedge_edu.core.ops import can_split, collapse, split
from tests.core.ops.helpers import assert_same_mesh, assert_unchanged, counts, pillow, snapshot

STRIP_VERTICES = [[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [1.5, 1, 0], [2, 0, 0]]


def test_split_of_an_interior_edge_makes_four_triangles_around_the_midpoint():
    strip = sample("strip")  # faces (0, 1, 2), (1, 3, 2), (1, 4, 3); edge 1 is 1 - 2
    m = split(strip, 1)
    strip.validate()
    assert m.index == 5
    np.testing.assert_array_equal(m.position, [0.75, 0.5, 0])
    assert_same_mesh(
        strip,
        (STRIP_VERTICES + [[0.75, 0.5, 0]], [[1, 5, 0], [5, 2, 0], [5, 1, 3], [2, 5, 3], [1, 4, 3]]),
    )


def test_split_of_a_boundary_edge_cuts_its_one_triangle_and_keeps_the_boundary_loop():
    strip = sample("strip")  # edge 0 is the boundary edge 0 - 1 of face (0, 1, 2)
    m = split(strip, 0)
    strip.validate()
    assert_same_mesh(strip, (STRIP_VERTICES + [[0.5, 0, 0]], [[0, 5, 2], [5, 1, 2], [1, 3, 2], [1, 4, 3]]))
    assert m.is_boundary and strip.n_boundary_loops == 1
    loop = strip.boundary_loops()[0]
    assert len(loop) == 6 and m.index in strip.halfedge_vertex[loop]


@pytest.mark.parametrize(
    ("name", "edge", "delta"),
    [("octahedron", 0, (1, 3, 2)), ("strip", 1, (1, 3, 2)), ("strip", 0, (1, 2, 1)), ("lone_triangle", 2, (1, 2, 1))],
)
def test_split_adds_the_stated_elements(name, edge, delta):
    mesh = sample(name)
    before = counts(mesh)
    euler = mesh.euler_characteristic
    split(mesh, edge)
    mesh.validate()
    assert tuple(after - b for after, b in zip(counts(mesh), before)) == delta
    assert mesh.euler_characteristic == euler


@pytest.mark.parametrize(("name", "edge"), [("octahedron", 0), ("strip", 1), ("strip", 0)])
def test_the_new_vertex_halfedge_runs_along_the_original_edge(name, edge):
    mesh = sample(name)
    a, b = (v.index for v in mesh.edge(edge).vertices)
    m = split(mesh, edge)
    along = m.halfedge
    assert along.tip.index in (a, b)
    assert {along.edge.index, edge} <= {h.edge.index for h in m.outgoing()}
    halves = {e.index for e in m.edges() if {v.index for v in e.vertices} & {a, b}}
    assert along.edge.index in halves and edge in halves


def test_split_at_a_given_position():
    mesh = sample("octahedron")
    m = split(mesh, 0, position=(0.1, 0.2, 0.3))
    np.testing.assert_array_equal(m.position, [0.1, 0.2, 0.3])
    mesh.validate()


@pytest.mark.parametrize("position", [(1, 2), (np.nan, 0, 0), "abc"])
def test_a_bad_position_is_refused_before_anything_changes(position):
    mesh = sample("octahedron")
    before = snapshot(mesh)
    with pytest.raises(ValueError, match="position"):
        split(mesh, 0, position=position)
    assert_unchanged(mesh, before)


def test_every_live_edge_can_be_split():
    mesh = sample("figure8")
    assert all(can_split(mesh, e) for e in range(mesh.n_edges))


def test_a_deleted_edge_cannot_be_split():
    mesh = sample("octahedron")
    mesh.delete_edge(0)
    with pytest.raises(IndexError, match="deleted"):
        can_split(mesh, 0)


def test_the_mesh_method_is_the_same_operation():
    mesh = sample("cube")
    m = mesh.split(3, position=None)
    mesh.validate()
    assert m.index == 8 and mesh.n_faces == 14


def test_split_of_a_boundary_edge_stored_hole_side_first():
    strip = sample("strip")
    collapse(strip, 0)  # leaves edge 1 with its face on halfedge 3 and the hole on 2
    assert strip.halfedge_face[2] < 0 <= strip.halfedge_face[3]
    m = split(strip, 1)
    strip.validate()
    assert m.is_boundary and m.halfedge.is_boundary
    assert counts(strip) == (5, 7, 3)


def test_two_triangles_back_to_back_cannot_be_split():
    mesh = pillow()
    before = snapshot(mesh)
    check = can_split(mesh, 0)
    assert not check and check.rule == "back-to-back" and "two different edges" in check.reason
    with pytest.raises(hx.TopologyError):
        split(mesh, 0)
    assert_unchanged(mesh, before)
