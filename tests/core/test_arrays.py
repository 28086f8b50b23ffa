"""The array toolbox against plain Python: edge keys and tables, CSR rows, compaction, merging."""

from __future__ import annotations

import numpy as np
from hypothesis import given

from halfedge_edu.core.arrays import (
    compact, csr, expand, face_cross, face_halfedges, key_ends, merge_vertices, sort_undirected,
    undirected_keys, unique_edges, vertex_faces, vertex_neighbours,
)
from halfedge_edu.core.corner_table import edge_table
from tests import strategies as shapes


def edges_by_hand(faces: np.ndarray) -> dict[tuple[int, int], list[int]]:
    """{(low, high): [directed edge 3f + k using it, ...]} by a loop over the faces."""
    uses: dict[tuple[int, int], list[int]] = {}
    for f, face in enumerate(faces.tolist()):
        for k in range(3):
            a, b = face[k], face[(k + 1) % 3]
            uses.setdefault((min(a, b), max(a, b)), []).append(3 * f + k)
    return uses


def test_key_ends_give_back_the_low_and_high_end_of_each_key():
    # Up to 2**31 vertices: a key (below n**2) then needs nearly all of int64.
    rng = np.random.default_rng(3)
    for n in (2, 7, 1000, 2**31):
        tail, head = rng.integers(0, n, 500), rng.integers(0, n, 500)
        ends = key_ends(undirected_keys(tail, head, n), n)
        assert ends.dtype == np.int64
        assert np.array_equal(ends, np.stack([np.minimum(tail, head), np.maximum(tail, head)], axis=1))


@given(drawn=shapes.meshes())
def test_edge_table_and_unique_edges_match_a_loop_over_the_faces(drawn):
    vertices, faces = drawn
    n = len(vertices)
    uses = edges_by_hand(faces)
    table = edge_table(faces, n)
    assert [tuple(edge) for edge in table.edges.tolist()] == sorted(uses)
    assert table.count.tolist() == [len(uses[key]) for key in sorted(uses)]
    for e, key in enumerate(sorted(uses)):
        found = [int(table.first[e])] + ([int(table.second[e])] if table.second[e] >= 0 else [])
        assert sorted(found) == uses[key]
        for p in uses[key]:
            assert table.corner_edge.reshape(-1)[p] == e
    edges, count = unique_edges(faces, n)
    assert np.array_equal(edges, table.edges) and np.array_equal(count, table.count)
    assert np.array_equal(table.keys, undirected_keys(edges[:, 0], edges[:, 1], n))
    on_boundary = {v for key in uses if len(uses[key]) == 1 for v in key}
    assert set(np.flatnonzero(table.boundary_vertices(n)).tolist()) == on_boundary


@given(drawn=shapes.meshes())
def test_sort_undirected_groups_each_edge_first_use_first(drawn):
    vertices, faces = drawn
    order, sorted_key = sort_undirected(*face_halfedges(faces), len(vertices))
    uses = edges_by_hand(faces)
    assert order.tolist() == [p for key in sorted(uses) for p in uses[key]]
    assert np.all(np.diff(sorted_key) >= 0)


@given(drawn=shapes.meshes())
def test_csr_rows_hold_each_vertex_neighbours_and_faces(drawn):
    vertices, faces = drawn
    n = len(vertices)
    offsets, neighbours = vertex_neighbours(edge_table(faces, n).edges, n)
    face_offsets, around = vertex_faces(faces, n)
    for v in range(n):
        expected = {w for key in edges_by_hand(faces) for w in key if v in key and w != v}
        assert sorted(neighbours[offsets[v]:offsets[v + 1]].tolist()) == sorted(expected)
        faces_at_v = np.flatnonzero((faces == v).any(axis=1)).tolist()
        assert sorted(around[face_offsets[v]:face_offsets[v + 1]].tolist()) == faces_at_v
    rows = np.array([n - 1, 0, n - 1])
    owner, items = expand(offsets, neighbours, rows)
    for i, v in enumerate(rows):
        assert sorted(items[owner == i].tolist()) == sorted(neighbours[offsets[v]:offsets[v + 1]].tolist())


def test_csr_gives_empty_rows_for_rows_without_values():
    offsets, values = csr(np.array([2, 0, 2]), np.array([10, 11, 12]), 4)
    assert offsets.tolist() == [0, 1, 1, 3, 3]
    assert values[0] == 11 and sorted(values[1:].tolist()) == [10, 12]


def test_compact_drops_unused_vertices_and_keeps_their_order():
    vertices = np.arange(15.0).reshape(5, 3)
    faces = np.array([[4, 1, 3]])
    kept_vertices, new_faces, kept = compact(vertices, faces)
    assert kept.tolist() == [1, 3, 4]
    assert new_faces.tolist() == [[2, 0, 1]]
    assert np.array_equal(kept_vertices, vertices[[1, 3, 4]])


def test_merge_vertices_relabels_and_drops_the_faces_that_held_both_ends():
    faces = np.array([[0, 1, 2], [0, 2, 3], [2, 4, 3]])
    assert merge_vertices(faces, np.array([0]), np.array([2]), 5).tolist() == [[2, 4, 3]]
    assert merge_vertices(faces, np.array([4]), np.array([1]), 5).tolist() == [[0, 1, 2], [0, 2, 3], [2, 1, 3]]


def test_face_cross_is_twice_the_area_along_the_normal():
    corners = np.array([[[0.0, 0, 0], [2, 0, 0], [0, 3, 0]], [[0.0, 0, 0], [1, 1, 1], [2, 2, 2]]])
    assert face_cross(corners).tolist() == [[0.0, 0.0, 6.0], [0.0, 0.0, 0.0]]
