"""Loop subdivision: hand-worked positions, counts and invariants, trimesh as a reference."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial import cKDTree

import halfedge_edu as hx
from halfedge_edu.algorithms import face_normals, loop_subdivide, loop_subdivide_by_operations
from tests import strategies as shapes
from tests.strategies import build, cases, closed_meshes, meshes

CUBE_VERTICES = [[i & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)]   # vertex i at its bits
CUBE_FACES = [
    [0, 4, 2], [2, 4, 6], [7, 5, 3], [3, 5, 1], [0, 1, 4], [1, 5, 4],
    [7, 3, 6], [3, 2, 6], [0, 2, 1], [1, 2, 3], [7, 6, 5], [5, 6, 4],
]


def canonical_faces(faces) -> set[tuple[int, int, int]]:
    """Faces as a set, each rotated to start at its smallest vertex (orientation kept)."""
    result = set()
    for face in np.asarray(faces).tolist():
        k = face.index(min(face))
        result.add(tuple(face[k:] + face[:k]))
    return result


def written_out_loop(vertices, faces, edge_list):
    """One Loop step computed from a plain face list, vertex by vertex, from the rules.

    ``edge_list`` (E, 2) gives the edge numbering, so edge point ``e`` is row ``V + e``.
    """
    vertices = np.asarray(vertices, dtype=float)
    opposite: dict[tuple[int, int], list[int]] = {}
    for a, b, c in np.asarray(faces).tolist():
        for u, v, w in ((a, b, c), (b, c, a), (c, a, b)):
            opposite.setdefault((min(u, v), max(u, v)), []).append(w)
    neighbours = {v: set() for v in range(len(vertices))}
    rim_neighbours = {v: set() for v in range(len(vertices))}
    for (u, v), wings in opposite.items():
        neighbours[u].add(v)
        neighbours[v].add(u)
        if len(wings) == 1:
            rim_neighbours[u].add(v)
            rim_neighbours[v].add(u)
    new = []
    for v, p in enumerate(vertices):
        if rim_neighbours[v]:                                   # boundary: 3/4, 1/8, 1/8
            b0, b1 = sorted(rim_neighbours[v])
            new.append(3 / 4 * p + 1 / 8 * (vertices[b0] + vertices[b1]))
        else:                                                   # interior: Warren's beta
            n = len(neighbours[v])
            beta = 3 / 16 if n == 3 else 3 / (8 * n)
            new.append((1 - n * beta) * p + beta * sum(vertices[u] for u in neighbours[v]))
    for a, b in np.asarray(edge_list).tolist():
        wings = opposite[(min(a, b), max(a, b))]
        if len(wings) == 1:                                     # boundary: the midpoint
            new.append((vertices[a] + vertices[b]) / 2)
        else:                                                   # interior: 3/8, 3/8, 1/8, 1/8
            c, d = wings
            new.append(3 / 8 * (vertices[a] + vertices[b]) + 1 / 8 * (vertices[c] + vertices[d]))
    return np.array(new)


def test_two_triangle_square_by_hand(square):
    # Edges in build order: 0-1, 1-2, 2-0 (the diagonal), 2-3, 3-0; edge point e is 4 + e.
    assert square.edge_vertices().tolist() == [[0, 1], [1, 2], [2, 0], [2, 3], [3, 0]]
    fine = loop_subdivide(square)
    expected = np.array([
        # Every old vertex is on the boundary: 3/4 itself + 1/8 each boundary neighbour.
        [1 / 8, 1 / 8, 0], [7 / 8, 1 / 8, 0], [7 / 8, 7 / 8, 0], [1 / 8, 7 / 8, 0],
        [1 / 2, 0, 0], [1, 1 / 2, 0],                      # boundary edges: midpoints
        [1 / 2, 1 / 2, 0],                                 # diagonal: 3/8 (v0 + v2) + 1/8 (v1 + v3)
        [1 / 2, 1, 0], [0, 1 / 2, 0],
    ])
    assert np.allclose(fine.positions, expected, atol=1e-15)
    assert fine.face_vertices().tolist() == [
        [0, 4, 6], [1, 5, 4], [2, 6, 5], [4, 5, 6],        # face [0, 1, 2] with m = 4, 5, 6
        [0, 6, 8], [2, 7, 6], [3, 8, 7], [6, 7, 8],        # face [0, 2, 3] with m = 6, 7, 8
    ]
    fine.validate()


def test_cube_by_hand():
    cube = hx.HalfedgeMesh.from_faces(CUBE_VERTICES, CUBE_FACES)
    fine = loop_subdivide(cube)
    edge = {tuple(sorted(ends)): e for e, ends in enumerate(cube.edge_vertices().tolist())}
    # Vertex 0 has degree 3, neighbours (1,0,0), (0,1,0), (0,0,1): beta = 3/16.
    assert np.allclose(fine.positions[0], 7 / 16 * np.zeros(3) + 3 / 16 * np.ones(3))
    # Vertex 7 = (1,1,1) has degree 3, neighbours summing to (2,2,2).
    assert np.allclose(fine.positions[7], 7 / 16 * np.ones(3) + 3 / 16 * np.full(3, 2.0))
    # Vertex 1 = (1,0,0) has degree 5 (neighbours 0, 2, 3, 4, 5, summing to (2,2,2)): beta = 3/40.
    assert np.allclose(fine.positions[1], (1 - 15 / 40) * np.array([1, 0, 0]) + 3 / 40 * np.full(3, 2.0))
    # Edge 0-4 lies in faces [0,4,2] and [0,1,4]: wings 2 = (0,1,0) and 1 = (1,0,0).
    assert np.allclose(fine.positions[8 + edge[(0, 4)]], 3 / 8 * np.array([0, 0, 1]) + 1 / 8 * np.array([1, 1, 0]))
    # Diagonal 1-2 of the bottom square: wings 0 = (0,0,0) and 3 = (1,1,0).
    assert np.allclose(fine.positions[8 + edge[(1, 2)]], [1 / 2, 1 / 2, 0])
    assert np.allclose(fine.positions, written_out_loop(CUBE_VERTICES, CUBE_FACES, cube.edge_vertices()))


@given(meshes())
def test_positions_follow_the_written_out_rules(drawn):
    mesh = build(drawn)
    expected = written_out_loop(*drawn, mesh.edge_vertices())
    assert np.allclose(loop_subdivide(mesh).positions, expected, rtol=1e-12, atol=1e-12)


@given(meshes())
def test_faces_are_the_four_children_of_each_parent(drawn):
    mesh = build(drawn)
    n = mesh.n_vertices
    edge = {tuple(sorted(ends)): e for e, ends in enumerate(mesh.edge_vertices().tolist())}
    expected = []
    for face in mesh.face_vertices().tolist():
        m = [n + edge[tuple(sorted((face[k], face[(k + 1) % 3])))] for k in range(3)]
        expected += [[face[k], m[k], m[k - 1]] for k in range(3)] + [m]
    assert loop_subdivide(mesh).face_vertices().tolist() == expected


@given(cases(), st.integers(1, 2))
def test_counts_and_topology(case, levels):
    mesh = build(case)
    fine = loop_subdivide(mesh, levels)
    fine.validate()
    v, e, f = mesh.n_vertices, mesh.n_edges, mesh.n_faces
    for _ in range(levels):
        v, e, f = v + e, 2 * e + 3 * f, 4 * f
    assert (fine.n_vertices, fine.n_edges, fine.n_faces) == (v, e, f)
    assert fine.euler_characteristic == case.euler_characteristic
    assert fine.genus == case.genus
    assert fine.n_boundary_loops == case.n_boundary_loops
    assert fine.is_closed == (case.n_boundary_loops == 0)


def _with_twins_swapped(mesh, edges):
    """The same mesh with halfedges 2e and 2e + 1 of each edge in ``edges`` exchanged.

    ``from_faces`` always puts a boundary edge's missing face on ``2e + 1``; meshes
    edited by local operations need not, and this builds such a mesh directly.
    """
    from halfedge_edu.core.build import HalfedgeArrays

    swap = np.arange(mesh.n_halfedge_slots)
    for e in edges:
        swap[[2 * e, 2 * e + 1]] = [2 * e + 1, 2 * e]         # an involution: old <-> new
    arrays = HalfedgeArrays(
        positions=mesh.positions.copy(),
        vertex_halfedge=swap[mesh.vertex_halfedge],
        halfedge_next=swap[mesh.halfedge_next][swap],
        halfedge_prev=swap[mesh.halfedge_prev][swap],
        halfedge_vertex=mesh.halfedge_vertex[swap],
        halfedge_face=mesh.halfedge_face[swap],
        face_halfedge=swap[mesh.face_halfedge],
    )
    swapped = hx.HalfedgeMesh(arrays)
    swapped.validate()
    return swapped


def test_boundary_on_the_even_halfedge_of_an_edge(grid):
    boundary_edges = np.flatnonzero(grid.halfedge_face[1::2] < 0)
    swapped = _with_twins_swapped(grid, boundary_edges[::2])
    assert (swapped.halfedge_face[0::2] < 0).any()
    once = loop_subdivide(swapped)
    once.validate()
    assert np.allclose(once.positions, loop_subdivide(grid).positions)
    # The children of a swapped edge are numbered from its other end, so compare the
    # second level against the rules rather than against the unswapped mesh.
    twice = loop_subdivide(once)
    twice.validate()
    assert np.allclose(twice.positions, written_out_loop(*once.to_arrays(), once.edge_vertices()))


def test_children_face_the_same_way_as_their_parent():
    sphere = hx.HalfedgeMesh.from_faces(*shapes.icosphere(1))
    fine = loop_subdivide(sphere)
    parent = np.repeat(face_normals(sphere), 4, axis=0)          # face f -> faces 4f..4f+3
    assert (np.einsum("ij,ij->i", face_normals(fine), parent) > 0.9).all()


@given(meshes(), st.sampled_from(["warren", "loop"]))
def test_the_input_is_not_modified(drawn, weights):
    mesh = build(drawn)
    before = mesh.copy()
    fine = loop_subdivide(mesh, 2, weights=weights)
    assert fine is not mesh
    for name in ("positions", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face",
                 "vertex_halfedge", "face_halfedge"):
        assert np.array_equal(getattr(mesh, name), getattr(before, name)), name


def _match_by_position(ours, theirs):
    """Index into ``theirs`` of the point at each of ``ours`` (a bijection, checked)."""
    distance, index = cKDTree(theirs).query(ours)
    assert distance.max() < 1e-9
    assert len(np.unique(index)) == len(ours)
    return index


@given(closed_meshes(), st.integers(1, 2))
def test_matches_trimesh_on_closed_meshes(drawn, levels):
    # trimesh uses Loop's original beta; the same vertices, positions and faces,
    # up to the numbering of the new vertices.
    vertices, faces = trimesh.remesh.subdivide_loop(*drawn, iterations=levels)
    ours_vertices, ours_faces = loop_subdivide(build(drawn), levels, weights="loop").to_arrays()
    ours_to_theirs = _match_by_position(ours_vertices, vertices)
    assert canonical_faces(ours_to_theirs[ours_faces]) == canonical_faces(faces)


def test_matches_trimesh_on_an_open_fan():
    # (trimesh's boundary rule also counts boundary vertices reached by interior edges,
    # so open meshes are compared where that cannot happen: a fan around an interior vertex.)
    drawn = shapes.fan(7)
    vertices, faces = trimesh.remesh.subdivide_loop(*drawn)
    ours_vertices, ours_faces = loop_subdivide(build(drawn), weights="loop").to_arrays()
    ours_to_theirs = _match_by_position(ours_vertices, vertices)
    assert canonical_faces(ours_to_theirs[ours_faces]) == canonical_faces(faces)


def test_warren_and_loop_weights_agree_at_degree_3_and_6(tetrahedron, torus):
    # Tetrahedron: every vertex has degree 3; the regular torus grid: every vertex degree 6.
    for mesh in (tetrahedron, torus):
        assert np.allclose(loop_subdivide(mesh, 2).positions, loop_subdivide(mesh, 2, weights="loop").positions)


def test_zero_levels_return_a_copy(icosphere):
    copy = loop_subdivide(icosphere, 0)
    assert copy is not icosphere
    assert np.array_equal(copy.positions, icosphere.positions)
    assert np.array_equal(copy.face_vertices(), icosphere.face_vertices())


def test_deleted_elements_are_compacted_first():
    vertices, faces = shapes.grid(2, 2)
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    compact = mesh.copy()
    mesh.add_vertex([9.0, 9.0, 9.0])             # a spare slot, then flagged deleted
    mesh.delete_vertex(mesh.n_vertex_slots - 1)
    fine = loop_subdivide(mesh)
    assert np.array_equal(fine.positions, loop_subdivide(compact).positions)
    assert mesh.has_garbage                       # the input itself is left as it was


def test_progress_bar_gives_the_same_mesh(icosphere):
    assert np.array_equal(loop_subdivide(icosphere, 2, progress=True).positions, loop_subdivide(icosphere, 2).positions)


@given(meshes(), st.sampled_from(["warren", "loop"]))
def test_the_course_route_by_operations_gives_the_same_mesh(drawn, weights):
    # Split every edge, flip old-new cross edges, move: the same vertices (same numbers,
    # bit-identical positions) and the same triangles, only the face order differs.
    mesh = build(drawn)
    before = mesh.copy()
    by_operations = loop_subdivide_by_operations(mesh, weights=weights)
    direct = loop_subdivide(mesh, weights=weights)
    by_operations.validate()
    assert np.array_equal(by_operations.positions, direct.positions)
    assert canonical_faces(by_operations.face_vertices()) == canonical_faces(direct.face_vertices())
    assert np.array_equal(mesh.positions, before.positions)
    assert np.array_equal(mesh.halfedge_next, before.halfedge_next)


def test_the_course_route_reports_its_steps_in_order(square):
    steps = []
    loop_subdivide_by_operations(square, on_step=lambda step: steps.append((step.phase, step.number, step.element)))
    phases = [phase for phase, _, _ in steps]
    assert phases == ["split"] * 5 + ["flip"] * 2 + ["reposition"]
    # Splitting edge e (in index order) adds vertex V + e = 4 + e.
    assert [element.index for phase, _, element in steps if phase == "split"] == [4, 5, 6, 7, 8]
    assert [number for phase, number, _ in steps if phase == "flip"] == [0, 1]
    assert all(isinstance(element, hx.Edge) for phase, _, element in steps if phase == "flip")
    assert steps[-1][2] is None


@pytest.mark.parametrize("arguments", [{"levels": -1}, {"levels": 0.5}, {"weights": "catmull-clark"}])
def test_bad_arguments_are_refused(square, arguments):
    with pytest.raises(ValueError):
        loop_subdivide(square, **arguments)


@given(meshes(), st.integers(1, 4))
def test_refining_block_by_block_gives_the_same_mesh(drawn, block):
    """The faces and edges are refined in blocks (loop._FACE_BLOCK, for speed on big
    meshes); blocks of a few faces, ending anywhere, must give what one block gives."""
    from unittest import mock

    from halfedge_edu.algorithms import loop as loop_module

    mesh = build(drawn)
    whole = loop_subdivide(mesh)
    with mock.patch.object(loop_module, "_FACE_BLOCK", block):
        in_blocks = loop_subdivide(mesh)
    in_blocks.validate()
    for name in ("halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face", "vertex_halfedge",
                 "face_halfedge"):
        assert np.array_equal(getattr(in_blocks, name), getattr(whole, name)), name
    assert np.array_equal(in_blocks.positions, whole.positions)
