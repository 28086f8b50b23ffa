"""The corner table is the halfedge mesh's halfedges with ``next`` by arithmetic.

Each test holds one of its tables against what :class:`HalfedgeMesh` says of the same
faces: twins, flips, one-rings. Mesh halfedges map to corner-table halfedges ``3f + k``
through the mesh's faces (:func:`corner_of`).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.core.corner_table import CornerTable, next_halfedge, prev_halfedge
from tests import strategies as shapes


def corner_of(mesh: hx.HalfedgeMesh) -> np.ndarray:
    """(H,) the corner-table halfedge ``3f + k`` of each halfedge of a freshly built mesh, -1 outside every face.

    A fresh mesh's face ``f`` starts at its ``face_halfedge``, whose origin is ``faces[f, 0]``;
    the next two halfedges around the face are ``3f + 1`` and ``3f + 2``.
    """
    corner = np.full(mesh.n_halfedge_slots, -1, dtype=np.int64)
    h = mesh.face_halfedge.astype(np.int64)
    for k in range(3):
        corner[h] = 3 * np.arange(mesh.n_faces) + k
        h = mesh.halfedge_next[h].astype(np.int64)
    return corner


def _sorted_csr(offsets: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The CSR's values, each row sorted, rows one after the other: equal for two CSRs with the same rows."""
    row = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    return values[np.lexsort((values, row))]


SAMPLE_SHAPES = {
    "tetrahedron": shapes.tetrahedron,
    "torus": shapes.torus,
    "icosphere": lambda: shapes.icosphere(2),
    "grid (boundary)": lambda: shapes.grid(4, 3),
    "annulus (two boundary loops)": lambda: shapes.annulus(8, 2),
    "open fan (boundary)": shapes.open_fan,
    "spot": lambda: hx.sample("spot").to_arrays(),
    "bunny (holes)": lambda: hx.sample("bunny").to_arrays(),
}


def _assert_twins_are_the_meshes(vertices: np.ndarray, faces: np.ndarray) -> None:
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    assert np.array_equal(mesh.face_vertices(), faces)              # so corner_of's numbering is the table's
    table = CornerTable(faces, len(vertices))
    corner = corner_of(mesh)
    inside = np.flatnonzero(corner >= 0)                            # (3m,) every halfedge of a face
    twin = np.arange(mesh.n_halfedge_slots) ^ 1                     # the mesh's twin: h ^ 1
    assert np.array_equal(table.twin[corner[inside]], corner[twin[inside]])    # -1 where the twin is outside
    # The same edges: both halfedges of a mesh edge are in one slot, and the slots hold the mesh's edges.
    assert len(table.keys) == mesh.n_edges
    slot_of_edge = np.where(corner >= 0, table.edge[np.maximum(corner, 0)], -1).reshape(-1, 2)
    own = corner.reshape(-1, 2) >= 0
    both = own.all(axis=1)
    assert np.array_equal(slot_of_edge[both, 0], slot_of_edge[both, 1])
    slot = np.where(own[:, 0], slot_of_edge[:, 0], slot_of_edge[:, 1])                 # (n_edges,)
    assert np.array_equal(np.sort(slot), np.arange(mesh.n_edges))
    assert np.array_equal(table.edges[slot], np.sort(mesh.edge_vertices(), axis=1))
    assert np.array_equal(table.boundary[slot], ~both)


@pytest.mark.parametrize("name", SAMPLE_SHAPES)
def test_a_built_meshs_twins_are_the_corner_tables(name):
    _assert_twins_are_the_meshes(*SAMPLE_SHAPES[name]())


@given(drawn=shapes.meshes())
def test_a_drawn_meshs_twins_are_the_corner_tables(drawn):
    _assert_twins_are_the_meshes(*drawn)


@given(drawn=shapes.meshes())
def test_next_three_times_is_the_identity_and_prev_undoes_next(drawn):
    vertices, faces = drawn
    h = np.arange(faces.size)
    assert np.array_equal(next_halfedge(next_halfedge(next_halfedge(h))), h)
    assert np.array_equal(prev_halfedge(next_halfedge(h)), h)
    assert np.array_equal(next_halfedge(h) // 3, h // 3)                  # next stays in the face
    origin = faces.reshape(-1)
    assert np.array_equal(origin[next_halfedge(h)], faces[:, [1, 2, 0]].reshape(-1))   # next leaves the tip


@given(drawn=shapes.meshes())
def test_twin_is_an_involution_that_runs_the_other_way(drawn):
    vertices, faces = drawn
    table = CornerTable(faces, len(vertices))
    origin = faces.reshape(-1)
    tip = origin[next_halfedge(np.arange(faces.size))]
    h = np.flatnonzero(table.twin >= 0)
    twin = table.twin[h]
    assert np.array_equal(table.twin[twin], h)
    assert np.array_equal(origin[twin], tip[h]) and np.array_equal(tip[twin], origin[h])
    assert np.array_equal(table.face_across.reshape(-1)[h], twin // 3)
    assert np.all(table.face_across.reshape(-1)[table.twin < 0] == -1)
    # The boundary halfedges are exactly the ones without a twin, one per boundary edge.
    assert np.array_equal(np.sort(table.boundary_halfedge), np.flatnonzero(table.twin < 0))


@given(drawn=shapes.meshes())
def test_rings_are_the_meshs_one_rings(drawn):
    vertices, faces = drawn
    n = len(vertices)
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    table = CornerTable(faces, n)
    offsets, neighbours = mesh.vertex_adjacency()
    assert np.array_equal(table.neighbours[0], offsets)
    assert np.array_equal(_sorted_csr(*table.neighbours), _sorted_csr(offsets, neighbours))
    walk = mesh.one_rings()
    ring_faces = mesh.halfedge_face[walk.halfedges]
    owner = np.repeat(walk.vertices, np.diff(walk.offsets))[ring_faces >= 0]
    face_offsets = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(owner, minlength=n), out=face_offsets[1:])
    assert np.array_equal(table.faces_around[0], face_offsets)
    assert np.array_equal(_sorted_csr(*table.faces_around), _sorted_csr(face_offsets, ring_faces[ring_faces >= 0]))
    # corners_around: the same rows, each face named by the halfedge that leaves the vertex.
    corner_offsets, corners = table.corners_around
    assert np.array_equal(corners // 3, table.faces_around[1])
    assert np.array_equal(faces.reshape(-1)[corners], np.repeat(np.arange(n), np.diff(corner_offsets)))


def _same_faces_up_to_rotation(a: np.ndarray, b: np.ndarray) -> bool:
    def canonical(faces):
        start = np.argmin(faces, axis=1)
        return np.take_along_axis(faces, (start[:, None] + np.arange(3)) % 3, axis=1)

    return np.array_equal(canonical(a), canonical(b))


@settings(max_examples=40)
@given(drawn=shapes.meshes(), seed=st.integers(0, 2**32 - 1), n_flips=st.integers(1, 12))
def test_flips_keep_the_slots_and_give_the_meshs_faces(drawn, seed, n_flips):
    vertices, faces = drawn
    n = len(vertices)
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    table = CornerTable(faces.copy(), n)
    start_keys = table.keys.copy()
    rng = np.random.default_rng(seed)
    flipped_slots = set()
    for _ in range(n_flips):
        inner = np.flatnonzero(table.twin >= 0)
        if len(inner) == 0:
            break
        h = int(rng.choice(inner))
        a, b = (int(v) for v in table.faces.reshape(-1)[[h, next_halfedge(h)]])
        edge = mesh.find_edge(a, b)
        if not mesh.can_flip(edge):
            continue
        mesh.flip(edge)
        slot_before = int(table.edge[h])
        slot = table.flip(np.array([h]))
        assert slot.tolist() == [slot_before]                       # the flipped edge keeps its slot ...
        flipped_slots.add(slot_before)
        assert _same_faces_up_to_rotation(table.faces, mesh.face_vertices())
        # ... the other slots keep their edges, and every slot holds the edge its halfedges run along.
        kept = np.setdiff1d(np.arange(len(start_keys)), list(flipped_slots))
        assert np.array_equal(table.keys[kept], start_keys[kept])
        fresh = CornerTable(table.faces.copy(), n)
        assert np.array_equal(table.keys[table.edge], fresh.keys[fresh.edge])
        assert np.array_equal(table.twin, fresh.twin)
        assert table.contains(fresh.keys).all()
        assert not table.contains(np.setdiff1d(start_keys, fresh.keys)).any()
    # Put back in key order, the slots are a fresh table's.
    fresh, ordered = CornerTable(table.faces.copy(), n), table.in_key_order()
    assert np.array_equal(ordered.keys, fresh.keys) and np.array_equal(ordered.edge, fresh.edge)
    assert np.array_equal(np.sort([ordered.first, ordered.second], axis=0), np.sort([fresh.first, fresh.second], axis=0))
    assert np.array_equal(ordered.edges, fresh.edges) and np.array_equal(ordered.count, fresh.count)


@given(drawn=shapes.meshes())
def test_edge_table_is_a_view_of_the_corner_tables_arrays(drawn):
    vertices, faces = drawn
    table = CornerTable(faces, len(vertices))
    columns = table.edge_columns()
    assert columns.first is table.first and columns.keys is table.keys
    assert np.shares_memory(columns.corner_edge, table.edge)
    assert np.array_equal(table.boundary_vertices(), columns.boundary_vertices(len(vertices)))
