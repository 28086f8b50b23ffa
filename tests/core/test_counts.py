"""Counts and topology: V, E, F, Euler characteristic, genus, boundary loops, components."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given

import halfedge_edu as hx
from tests import strategies as shapes
from tests.strategies import build, cases


def _mesh(arrays) -> hx.HalfedgeMesh:
    return hx.HalfedgeMesh.from_faces(*arrays)


# (name, arrays, V, E, F, Euler characteristic, genus, boundary loops, components)
KNOWN = [
    ("tetrahedron", shapes.tetrahedron(), 4, 6, 4, 2, 0, 0, 1),
    ("octahedron", shapes.octahedron(), 6, 12, 8, 2, 0, 0, 1),
    ("icosphere", shapes.icosphere(1), 42, 120, 80, 2, 0, 0, 1),
    ("torus", shapes.torus(6, 4), 24, 72, 48, 0, 1, 0, 1),
    ("square", shapes.square(), 4, 5, 2, 1, 0, 1, 1),
    ("grid", shapes.grid(3, 2), 12, 23, 12, 1, 0, 1, 1),
    ("wheel", shapes.fan(6), 7, 12, 6, 1, 0, 1, 1),
    ("annulus", shapes.annulus(8, 2), 24, 56, 32, 0, 0, 2, 1),
    ("torus with a hole", shapes.remove_faces(*shapes.torus(6, 4), [0]), 24, 72, 47, -1, 1, 1, 1),
    ("two spheres", shapes.disjoint_union(shapes.octahedron(), shapes.tetrahedron()), 10, 18, 12, 4, 0, 0, 2),
    ("torus and disc", shapes.disjoint_union(shapes.torus(6, 4), shapes.square()), 28, 77, 50, 1, 1, 1, 2),
]


@pytest.mark.parametrize(
    "arrays, n_v, n_e, n_f, chi, genus, loops, components",
    [case[1:] for case in KNOWN],
    ids=[case[0] for case in KNOWN],
)
def test_counts_of_known_shapes(arrays, n_v, n_e, n_f, chi, genus, loops, components):
    mesh = _mesh(arrays)
    assert (mesh.n_vertices, mesh.n_edges, mesh.n_faces) == (n_v, n_e, n_f)
    assert mesh.n_halfedges == 2 * n_e
    assert mesh.euler_characteristic == chi
    assert mesh.genus == genus
    assert mesh.n_boundary_loops == loops
    assert mesh.n_components == components
    assert mesh.is_closed == (loops == 0)


@given(cases())
def test_counts_of_drawn_meshes_match_their_construction(case):
    mesh = build(case)
    vertices, faces = case.arrays
    edges = np.unique(np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1), axis=0)
    assert (mesh.n_vertices, mesh.n_edges, mesh.n_faces) == (len(vertices), len(edges), len(faces))
    assert mesh.euler_characteristic == case.euler_characteristic
    assert mesh.genus == case.genus
    assert mesh.n_boundary_loops == case.n_boundary_loops
    assert mesh.n_components == 1
    assert mesh.is_closed == (case.n_boundary_loops == 0)


@given(cases(), cases())
def test_components_add_up(first, second):
    mesh = _mesh(shapes.disjoint_union(first.arrays, second.arrays))
    assert mesh.n_components == 2
    assert mesh.genus == first.genus + second.genus
    assert mesh.n_boundary_loops == first.n_boundary_loops + second.n_boundary_loops
    assert mesh.euler_characteristic == first.euler_characteristic + second.euler_characteristic


@given(cases())
def test_boundary_loops_are_cycles_of_boundary_halfedges_under_next(case):
    mesh = build(case)
    loops = mesh.boundary_loops()
    assert len(loops) == case.n_boundary_loops
    for loop in loops:
        assert (mesh.halfedge_face[loop] == -1).all()
        assert np.array_equal(mesh.halfedge_next[loop], np.roll(loop, -1))
        assert len(np.unique(loop)) == len(loop)
    everything = np.sort(np.concatenate(loops)) if loops else np.zeros(0, dtype=int)
    assert np.array_equal(everything, np.flatnonzero(mesh.halfedge_face == -1))


def test_the_annulus_has_an_inner_and_an_outer_loop(annulus):
    loops = annulus.boundary_loops()
    assert sorted(len(loop) for loop in loops) == [8, 8]
    radii = sorted(np.linalg.norm(annulus.positions[annulus.halfedge_vertex[loop]], axis=1).mean() for loop in loops)
    assert radii == pytest.approx([1.0, 3.0])


def test_boundary_loop_runs_clockwise_around_a_disc(grid):
    # Faces are CCW seen from +z; the boundary loop walks the other way round the hole.
    (loop,) = grid.boundary_loops()
    corners = grid.positions[grid.halfedge_vertex[loop], :2]
    signed_area = 0.5 * np.sum(corners[:, 0] * np.roll(corners[:, 1], -1) - np.roll(corners[:, 0], -1) * corners[:, 1])
    assert signed_area == pytest.approx(-6.0)


def test_a_closed_mesh_has_no_boundary(tetrahedron):
    assert tetrahedron.is_closed
    assert tetrahedron.boundary_loops() == []
    assert not tetrahedron.vertex_is_boundary().any()


def test_counts_leave_out_deleted_elements(two_spheres):
    # The tetrahedron is the second piece: vertices 6..9, edges 12..17, faces 8..11.
    for f in range(8, 12):
        two_spheres.delete_face(f)
    for e in range(12, 18):
        two_spheres.delete_edge(e)
    for v in range(6, 10):
        two_spheres.delete_vertex(v)
    assert (two_spheres.n_vertices, two_spheres.n_edges, two_spheres.n_faces) == (6, 12, 8)
    assert (two_spheres.n_vertex_slots, two_spheres.n_edge_slots, two_spheres.n_face_slots) == (10, 18, 12)
    assert two_spheres.n_halfedge_slots == 36 and two_spheres.n_halfedges == 24
    assert two_spheres.euler_characteristic == 2
    assert two_spheres.n_components == 1
    assert two_spheres.genus == 0
    assert two_spheres.has_garbage


def test_deleting_twice_counts_once(square):
    square.delete_face(0)
    square.delete_face(0)
    assert square.n_faces == 1


def test_repr_gives_the_counts(annulus):
    assert repr(annulus) == "HalfedgeMesh(vertices=24, edges=56, faces=32, boundary_loops=2)"
