"""Growing the arrays (add_*), flagging elements deleted, and compacting them (garbage_collect)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

import halfedge_edu as hx
from tests import strategies as shapes
from tests.strategies import build, closed_meshes, meshes

ARRAY_NAMES = (
    "positions", "vertex_halfedge", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face",
    "face_halfedge",
)


def _snapshot(mesh: hx.HalfedgeMesh) -> dict[str, np.ndarray]:
    return {name: getattr(mesh, name).copy() for name in ARRAY_NAMES}


def _assert_same_arrays(mesh: hx.HalfedgeMesh, expected: dict[str, np.ndarray]) -> None:
    for name in ARRAY_NAMES:
        assert np.array_equal(getattr(mesh, name), expected[name]), name


def _delete_component(mesh: hx.HalfedgeMesh, vertices: np.ndarray) -> None:
    """Flag the given vertices, and every edge and face that touches them, deleted."""
    doomed = np.zeros(mesh.n_vertex_slots, dtype=bool)
    doomed[vertices] = True
    for f in np.flatnonzero(doomed[mesh.face_vertices()].any(axis=1)):
        mesh.delete_face(f)
    for e in np.flatnonzero(doomed[mesh.edge_vertices()].any(axis=1)):
        mesh.delete_edge(e)
    for v in vertices:
        mesh.delete_vertex(v)


# ---- nothing deleted ---------------------------------------------------------------------

@given(meshes())
def test_collecting_a_clean_mesh_changes_nothing_and_maps_are_identities(drawn):
    mesh = build(drawn)
    before = _snapshot(mesh)
    maps = mesh.garbage_collect()
    assert isinstance(maps, hx.GarbageCollectMaps)
    assert np.array_equal(maps.vertices, np.arange(mesh.n_vertices))
    assert np.array_equal(maps.halfedges, np.arange(mesh.n_halfedges))
    assert np.array_equal(maps.edges, np.arange(mesh.n_edges))
    assert np.array_equal(maps.faces, np.arange(mesh.n_faces))
    _assert_same_arrays(mesh, before)
    mesh.validate()


# ---- deleting a whole component -----------------------------------------------------

@given(meshes(), meshes(), st.booleans())
def test_deleting_one_component_leaves_exactly_the_other(first, second, keep_first):
    mesh = hx.HalfedgeMesh.from_faces(*shapes.disjoint_union(first, second))
    n_first = len(first[0])
    kept_arrays = first if keep_first else second
    doomed = np.arange(n_first, mesh.n_vertices) if keep_first else np.arange(n_first)
    old_faces = mesh.face_vertices()
    kept_positions = np.delete(mesh.positions, doomed, axis=0)   # shifted apart by the union
    _delete_component(mesh, doomed)
    mesh.validate()                                      # sound, with garbage
    assert mesh.has_garbage and mesh.n_components == 1
    assert (mesh.face_vertices()[mesh.face_deleted] == -1).all()
    exported_with_garbage = mesh.to_arrays()

    maps = mesh.garbage_collect()
    mesh.validate()
    assert not mesh.has_garbage
    assert (mesh.n_vertex_slots, mesh.n_edge_slots, mesh.n_face_slots) == (
        mesh.n_vertices, mesh.n_edges, mesh.n_faces,
    )
    # The piece keeps its relative order, so the arrays are those of building it alone.
    _assert_same_arrays(mesh, _snapshot(hx.HalfedgeMesh.from_faces(kept_positions, kept_arrays[1])))
    vertices, faces = mesh.to_arrays()
    assert np.array_equal(vertices, kept_positions) and np.array_equal(faces, kept_arrays[1])
    assert np.array_equal(exported_with_garbage[0], vertices) and np.array_equal(exported_with_garbage[1], faces)

    # The maps send deleted elements to -1 and live ones to their new place.
    assert (maps.vertices[doomed] == -1).all()
    live = maps.vertices >= 0
    assert np.array_equal(maps.vertices[live], np.arange(mesh.n_vertices))
    live_faces = np.flatnonzero(maps.faces >= 0)
    assert np.array_equal(mesh.face_vertices()[maps.faces[live_faces]], maps.vertices[old_faces[live_faces]])
    assert np.array_equal(maps.halfedges[0::2], np.where(maps.edges >= 0, 2 * maps.edges, -1))
    assert np.array_equal(maps.halfedges[1::2], np.where(maps.edges >= 0, 2 * maps.edges + 1, -1))


def test_derived_arrays_are_recomputed_after_collecting(two_spheres):
    stale = two_spheres.vertex_adjacency()
    assert len(stale[0]) == 11
    _delete_component(two_spheres, np.arange(6))         # the octahedron goes
    two_spheres.garbage_collect()
    offsets, neighbors = two_spheres.vertex_adjacency()
    fresh = hx.HalfedgeMesh.from_faces(*shapes.tetrahedron()).vertex_adjacency()
    assert np.array_equal(offsets, fresh[0]) and np.array_equal(neighbors, fresh[1])
    assert len(two_spheres.one_rings().vertices) == 4
    assert two_spheres.vertex(3).degree == 3


# ---- punching a hole by hand, as a local operation would ----------------------------------

@given(closed_meshes(), st.integers(min_value=0))
def test_deleting_a_face_by_hand_and_collecting_gives_the_mesh_with_a_hole(drawn, which):
    vertices, faces = drawn
    mesh = build(drawn)
    f = which % mesh.n_faces
    hole = [h.index for h in mesh.face(f).halfedges()]
    mesh.delete_face(f)
    mesh.halfedge_face[hole] = -1
    for h in hole:                       # each corner now leaves along a boundary halfedge
        mesh.vertex_halfedge[mesh.halfedge_vertex[h]] = h
    mesh.validate()
    assert mesh.n_boundary_loops == 1

    maps = mesh.garbage_collect()
    mesh.validate()
    assert maps.faces[f] == -1 and np.array_equal(maps.vertices, np.arange(len(vertices)))
    out_vertices, out_faces = mesh.to_arrays()
    assert np.array_equal(out_vertices, vertices)
    assert np.array_equal(out_faces, np.delete(faces, f, axis=0))
    assert mesh.n_boundary_loops == 1 and not mesh.is_closed


# ---- growing ---------------------------------------------------------------------------

def test_add_vertex_grows_the_arrays_and_keeps_the_old_rows(tetrahedron):
    before = _snapshot(tetrahedron)
    version = tetrahedron.topology_version
    added = [tetrahedron.add_vertex([k, -k, 2 * k]) for k in range(40)]
    assert added == list(range(4, 44))
    assert tetrahedron.n_vertices == tetrahedron.n_vertex_slots == 44
    assert np.array_equal(tetrahedron.positions[:4], before["positions"])
    assert np.array_equal(tetrahedron.vertex_halfedge[:4], before["vertex_halfedge"])
    assert np.array_equal(tetrahedron.positions[4:], [[k, -k, 2 * k] for k in range(40)])
    assert (tetrahedron.vertex_halfedge[4:] == -1).all()
    assert not tetrahedron.vertex_deleted.any()
    assert tetrahedron.topology_version > version
    tetrahedron.validate()  # isolated vertices are allowed (a file's unused vertices stay)


def test_add_edge_grows_the_arrays_and_leaves_the_links_empty(tetrahedron):
    before = _snapshot(tetrahedron)
    added = [tetrahedron.add_edge(k % 4, (k + 1) % 4) for k in range(30)]
    assert added == list(range(6, 36))
    assert tetrahedron.n_edges == tetrahedron.n_edge_slots == 36 and tetrahedron.n_halfedges == 72
    for name in ("halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face"):
        assert np.array_equal(getattr(tetrahedron, name)[:12], before[name]), name
        if name != "halfedge_vertex":
            assert (getattr(tetrahedron, name)[12:] == -1).all(), name
    e = added[5]                                          # runs from vertex 1 to vertex 2
    assert tetrahedron.halfedge_vertex[2 * e] == 1 and tetrahedron.halfedge_vertex[2 * e + 1] == 2
    assert not tetrahedron.edge_deleted.any()


def test_add_face_grows_the_arrays(tetrahedron):
    added = [tetrahedron.add_face(k) for k in range(20)]
    assert added == list(range(4, 24))
    assert tetrahedron.n_faces == tetrahedron.n_face_slots == 24
    assert tetrahedron.face_halfedge[4:].tolist() == list(range(20))
    assert not tetrahedron.face_deleted.any()


def test_a_triangle_added_element_by_element_is_a_sound_new_component(grid):
    old_vertices, old_faces = grid.to_arrays()
    a, b, c = (grid.add_vertex(p) for p in ([10, 0, 0], [11, 0, 0], [10, 1, 0]))
    ab, bc, ca = grid.add_edge(a, b), grid.add_edge(b, c), grid.add_edge(c, a)
    inside = [2 * ab, 2 * bc, 2 * ca]                     # a -> b -> c -> a
    outside = [2 * ab + 1, 2 * ca + 1, 2 * bc + 1]        # b -> a -> c -> b, the boundary loop
    f = grid.add_face(inside[0])
    for loop in (inside, outside):
        for here, after in zip(loop, loop[1:] + loop[:1]):
            grid.halfedge_next[here] = after
            grid.halfedge_prev[after] = here
    grid.halfedge_face[inside] = f
    grid.halfedge_face[outside] = -1
    grid.vertex_halfedge[[a, b, c]] = [2 * ca + 1, 2 * ab + 1, 2 * bc + 1]
    grid.validate()
    assert grid.n_components == 2 and grid.n_boundary_loops == 2
    vertices, faces = grid.to_arrays()
    assert np.array_equal(vertices[:-3], old_vertices) and np.array_equal(faces[:-1], old_faces)
    assert faces[-1].tolist() == [a, b, c]


def test_collecting_removes_added_then_deleted_slots(square):
    before = _snapshot(square)
    v = square.add_vertex([9.0, 9.0, 9.0])
    e = square.add_edge(0, v)
    f = square.add_face(2 * e)
    square.delete_face(f)
    square.delete_edge(e)
    square.delete_vertex(v)
    square.validate()
    maps = square.garbage_collect()
    assert (maps.vertices[v], maps.edges[e], maps.faces[f]) == (-1, -1, -1)
    assert maps.halfedges[2 * e] == maps.halfedges[2 * e + 1] == -1
    _assert_same_arrays(square, before)
    assert (square.n_vertex_slots, square.n_edge_slots, square.n_face_slots) == (4, 5, 2)


def test_deleting_bumps_the_topology_version(square):
    version = square.topology_version
    square.delete_face(0)
    assert square.topology_version > version
    version = square.topology_version
    square.garbage_collect()
    assert square.topology_version > version
