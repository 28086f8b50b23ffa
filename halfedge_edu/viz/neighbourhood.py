"""Which vertices and halfedges lie near a highlight: rings of vertices, the arrows between them.

A large mesh draws its arrows only near what is highlighted; these functions say where
"near" ends. They read the mesh's cached vertex adjacency and one-ring walk, so each is
a few numpy passes, without a Python loop per vertex.
"""

from __future__ import annotations

import numpy as np


def ranges(starts: np.ndarray, stops: np.ndarray) -> np.ndarray:
    """Concatenate ``arange(s, t)`` for each pair, without a Python loop."""
    lengths = stops - starts
    total = int(lengths.sum())
    if total == 0:
        return np.zeros(0, dtype=np.int64)
    owner_start = np.repeat(starts - np.concatenate([[0], np.cumsum(lengths)[:-1]]), lengths)
    return owner_start + np.arange(total)


def ring_mark(mesh, seeds: np.ndarray, rings: int) -> np.ndarray:
    """(n_vertex_slots,) bool: the vertices within ``rings`` edges of ``seeds``."""
    offsets, neighbors = mesh.vertex_adjacency()
    mark = np.zeros(mesh.n_vertex_slots, dtype=bool)
    mark[seeds] = True
    frontier = seeds
    for _ in range(rings):
        reached = neighbors[ranges(offsets[frontier], offsets[frontier + 1])]
        frontier = np.unique(reached[~mark[reached]])
        if len(frontier) == 0:
            break
        mark[frontier] = True
    return mark


def outgoing_of(mesh, vertices: np.ndarray) -> np.ndarray:
    """All outgoing halfedges of ``vertices`` (from the mesh's cached one-ring walk)."""
    offsets, _ = mesh.vertex_adjacency()
    walk = mesh.one_rings()
    return walk.halfedges[ranges(offsets[vertices], offsets[vertices + 1])].astype(np.int64)


def ring_window(mesh, seeds: np.ndarray, rings: int) -> tuple[np.ndarray, np.ndarray]:
    """The vertices within ``rings`` edges of ``seeds`` and the halfedges between them.

    Returns:
        ``(vertices, halfedges)``: (k,) sorted vertex indices and (m,) sorted halfedge
        indices whose two ends are both among those vertices.
    """
    mark = ring_mark(mesh, np.asarray(seeds, dtype=np.int64), rings)
    inside = np.flatnonzero(mark)
    outgoing = outgoing_of(mesh, inside)
    return inside, np.sort(outgoing[mark[mesh.halfedge_vertex[outgoing ^ 1]]])
