"""RoundMesh: tables updated after a round of collapses equal the tables built from scratch."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.algorithms.collapse_rounds import (
    RoundMesh, choose_round, collapse_topology_ok, gather_rings, independent_edges, round_tables,
)
from halfedge_edu.algorithms.simplify import simplify
from halfedge_edu.core.arrays import expand, merge_vertices, unique_edges, vertex_faces, vertex_neighbours
from tests import strategies as shapes
from tests.algorithms.test_collapse_rounds import roughened


def _ring_sets(rings, n: int) -> list[list[int]]:
    """Each vertex's ring (CSR or padded) as a sorted list."""
    owner, items = gather_rings(rings, np.arange(n))
    rows: list[list[int]] = [[] for _ in range(n)]
    for vertex, item in zip(owner.tolist(), items.tolist()):
        rows[vertex].append(item)
    return [sorted(row) for row in rows]


def _a_round(mesh: RoundMesh, n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """An allowed round of collapses (random priorities), as ``(keep, remove)``."""
    edges = np.flatnonzero(mesh.is_edge)
    candidates = np.random.default_rng(seed).permutation(edges)
    ends = np.stack(mesh.ends(candidates), axis=1)
    boundary_edge = mesh.twin[candidates] < 0

    def check_topology(indices):
        ok, owner, vertex = collapse_topology_ok(n, ends[indices], boundary_edge[indices], mesh.boundary_vertex,
                                                 mesh.degree, mesh.neighbours)
        return ok, indices[owner], vertex

    everything = np.arange(len(candidates))
    chosen = choose_round(ends, everything, np.ones(len(candidates), dtype=bool), n, check_topology,
                          lambda indices: np.ones(len(indices), dtype=bool), neighbours=mesh.neighbours)
    return ends[chosen, 0], ends[chosen, 1]


@settings(max_examples=80, deadline=None)
@given(case=shapes.cases(), seed=st.integers(0, 2**32 - 1), n_collapses=st.integers(0, 20), rounds=st.integers(1, 3))
def test_tables_after_rounds_of_collapses_equal_fresh_ones(case, seed, n_collapses, rounds):
    vertices, faces = roughened(case, seed, n_collapses).to_arrays()
    n = len(vertices)
    mesh = RoundMesh(faces, n)
    merged = faces
    for round_number in range(rounds):
        keep, remove = _a_round(mesh, n, seed + round_number)
        if len(keep) == 0:
            break
        mesh.collapse(keep, remove)
        merged = merge_vertices(merged, remove, keep, n)

        # The faces that stay, in their order, are the merged face array.
        assert np.array_equal(mesh.live_faces(), merged) and mesh.n_faces == len(merged)
        # Rings, degrees and boundary as the array toolbox builds them from scratch.
        live = np.flatnonzero(mesh.alive)                          # RoundMesh face number of each merged face
        edges, count = unique_edges(merged, n)
        faces_around = _ring_sets(mesh.faces_around, n)
        assert [sorted(live[row].tolist()) for row in _ring_sets(vertex_faces(merged, n), n)] == faces_around
        assert _ring_sets(mesh.neighbours, n) == _ring_sets(vertex_neighbours(edges, n), n)
        assert np.array_equal(mesh.degree, np.bincount(edges.reshape(-1), minlength=n))
        on_boundary = np.zeros(n, dtype=bool)
        on_boundary[edges[count == 1].reshape(-1)] = True
        assert np.array_equal(mesh.boundary_vertex[np.unique(merged)], on_boundary[np.unique(merged)])
        # One name per edge, and the twins and faces across as round_tables finds them.
        names = np.flatnonzero(mesh.is_edge)
        named = np.sort(np.stack(mesh.ends(names), axis=1), axis=1)
        assert np.array_equal(named[np.lexsort(named.T[::-1])], edges)
        assert np.array_equal(mesh.twin[names] < 0, count[np.searchsorted(edges[:, 0] * n + edges[:, 1],
                                                                           named[:, 0] * n + named[:, 1])] == 1)
        fresh_across = round_tables(merged, n).face_across
        across = mesh.face_across[live]
        assert np.array_equal(np.where(across >= 0, np.searchsorted(live, across), -1), fresh_across)
        assert np.array_equal(mesh.face_across.reshape(-1)[live[:, None] * 3 + np.arange(3)].reshape(-1) >= 0,
                              mesh.twin.reshape(-1, 3)[live].reshape(-1) >= 0)
        # edges_at names each edge at the kept vertices once.
        at_keep = mesh.edges_at(keep)
        expected = np.flatnonzero(np.isin(edges[:, 0], keep) | np.isin(edges[:, 1], keep))
        found = np.sort(np.stack(mesh.ends(at_keep), axis=1), axis=1)
        assert len(at_keep) == len(np.unique(at_keep)) == len(expected)
        assert np.array_equal(np.sort(found[:, 0] * n + found[:, 1]), edges[expected, 0] * n + edges[expected, 1])


@settings(max_examples=60)
@given(case=shapes.cases(), seed=st.integers(0, 2**32 - 1))
def test_padded_and_csr_rings_give_the_same_rows_and_the_same_independent_edges(case, seed):
    vertices, faces = case.vertices, case.faces
    n = len(vertices)
    tables = round_tables(faces, n)
    mesh = RoundMesh(faces, n)
    rows = np.random.default_rng(seed).integers(0, n, size=2 * n)
    assert [list(x) for x in zip(*gather_rings(mesh.neighbours, rows))] == \
        [list(x) for x in zip(*expand(*tables.neighbours, rows))]
    edges = tables.edges
    priority = np.random.default_rng(seed).permutation(len(edges))
    scanned = independent_edges(edges, priority, edges, n)
    assert np.array_equal(independent_edges(edges, priority, None, n, neighbours=mesh.neighbours), scanned)
    assert np.array_equal(independent_edges(edges, priority, None, n, neighbours=tables.neighbours), scanned)


def test_simplify_gives_the_same_mesh_every_time():
    mesh = hx.sample("bunny")
    first = simplify(mesh, 2000).to_arrays()
    second = simplify(mesh, 2000).to_arrays()
    assert all(np.array_equal(a, b) for a, b in zip(first, second))
