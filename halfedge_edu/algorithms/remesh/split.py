"""Phase 1 of remeshing: split every edge longer than ``4/3 L`` at its midpoint.

An edge of length ``l > 4/3 L`` becomes two of ``l/2``, both nearer to ``L``
(:mod:`.lengths`). The new vertex sits on the chord, a little off a curved surface;
phase 5 (:mod:`.project`) puts it back.

All long edges are split at once. Each triangle with 1, 2 or 3 split edges is cut by a
fixed template (one 2-to-1 cut, a corner plus a quad cut along its shorter diagonal, or
4 triangles), the way "red-green" refinement does it; rotating each face first puts its
split edges in front, so one template per count covers all cases. The pass repeats until
no edge is long (a half of a very long edge may still be long).

A feature edge (:mod:`..features`) splits into two feature edges.
"""

from __future__ import annotations

import numpy as np

from ...core.corner_table import EdgeTable, edge_table
from ..features import Features
from .lengths import SPLIT_ABOVE, edge_lengths

#: How often the split may repeat within one iteration (each pass is one array operation).
MAX_SPLIT_PASSES = 10


def split_long_edges(vertices: np.ndarray, faces: np.ndarray, target_length: float,
                     features: Features | None = None,
                     table: EdgeTable | None = None) -> tuple[np.ndarray, np.ndarray, Features | None]:
    """Split every edge longer than ``4/3 target_length`` at its midpoint, pass after pass
    until none is (at most :data:`MAX_SPLIT_PASSES` passes).

    Why: an edge longer than 4/3 L is farther from L than its two halves would be.

    Args:
        vertices: (n, 3) float positions.
        faces: (m, 3) int triangles, oriented.
        target_length: ``L``.
        features: the feature edges to carry along (None: none are tracked).
        table: the :func:`~halfedge_edu.core.corner_table.edge_table` of ``faces``, if the caller
            has it (for the first pass).

    Returns:
        ``(vertices, faces, features)``: the old vertices first, then the midpoints
        (n', 3); the cut faces (m', 3), orientation kept; the features after the splits.
    """
    for _ in range(MAX_SPLIT_PASSES):
        vertices, faces, features, n_split = _split_pass(vertices, faces, SPLIT_ABOVE * target_length, features,
                                                         table)
        table = None                                                   # the faces have changed
        if n_split == 0:
            break
    return vertices, faces, features


def _split_pass(vertices: np.ndarray, faces: np.ndarray, max_length: float, features: Features | None = None,
                table: EdgeTable | None = None):
    """Split every edge longer than ``max_length`` at its midpoint, all at once.

    Returns ``(vertices, faces, features, n_split)``. Each face is cut by the template
    for its number of split edges; rotating the face first puts the split edges in
    front, so one template per count covers all cases. Orientation is kept. A split
    feature edge leaves two feature halves (``features`` None: none are tracked).
    ``table``: the :func:`~halfedge_edu.core.corner_table.edge_table` of ``faces``, if the
    caller has it already.
    """
    n = len(vertices)
    if not _has_long_side(vertices, faces, max_length):            # the usual last pass: no edge table needed
        return vertices, faces, features, 0
    if table is None:
        table = edge_table(faces, n)
    long = edge_lengths(vertices, table.edges) > max_length
    n_split = int(long.sum())
    midpoint_of = np.full(len(table.edges), -1, dtype=np.int64)
    midpoint_of[long] = n + np.arange(n_split)
    if features is not None:
        features = features.split(table, midpoint_of)
    split_edges = table.edges[long]
    vertices = np.concatenate([vertices, 0.5 * (vertices[split_edges[:, 0]] + vertices[split_edges[:, 1]])])

    corner_mid = midpoint_of[table.corner_edge]                       # (F, 3) midpoint of edge k -> k+1, or -1
    is_split = corner_mid >= 0
    n_cut = is_split.sum(axis=1)
    # Rotate each face: 1 cut -> the cut edge first; 2 cuts -> the uncut edge last.
    shift = np.where(n_cut == 1, np.argmax(is_split, axis=1), (np.argmin(is_split, axis=1) + 1) % 3)
    shift[n_cut == 3] = 0
    turn = (shift[:, None] + np.arange(3)) % 3
    v = np.take_along_axis(faces, turn, axis=1)                      # (F, 3) corners v0 v1 v2
    m = np.take_along_axis(corner_mid, turn, axis=1)                 # (F, 3) m0 on v0v1, m1 on v1v2, m2 on v2v0

    pieces = [faces[n_cut == 0]]
    one = n_cut == 1
    v0, v1, v2, m0 = v[one, 0], v[one, 1], v[one, 2], m[one, 0]
    pieces += [np.stack([v0, m0, v2], axis=1), np.stack([m0, v1, v2], axis=1)]

    two = n_cut == 2
    v0, v1, v2, m0, m1 = v[two, 0], v[two, 1], v[two, 2], m[two, 0], m[two, 1]
    pieces.append(np.stack([m0, v1, m1], axis=1))
    # The quad v0 m0 m1 v2 is cut along its shorter diagonal.
    short_first = (np.linalg.norm(vertices[v0] - vertices[m1], axis=1)
                   <= np.linalg.norm(vertices[m0] - vertices[v2], axis=1))
    pieces.append(np.where(short_first[:, None], np.stack([v0, m0, m1], axis=1), np.stack([v0, m0, v2], axis=1)))
    pieces.append(np.where(short_first[:, None], np.stack([v0, m1, v2], axis=1), np.stack([m0, m1, v2], axis=1)))

    three = n_cut == 3
    v0, v1, v2, m0, m1, m2 = (v[three, 0], v[three, 1], v[three, 2], m[three, 0], m[three, 1], m[three, 2])
    pieces += [np.stack(corner, axis=1) for corner in ((v0, m0, m2), (m0, v1, m1), (m2, m1, v2), (m0, m1, m2))]
    return vertices, np.concatenate(pieces), features, n_split


def _has_long_side(vertices: np.ndarray, faces: np.ndarray, max_length: float) -> bool:
    """Whether any face has a side longer than ``max_length``: each interior edge is
    measured twice, but no sort is needed to find the edges first."""
    corners = [np.take(vertices, faces[:, k], axis=0) for k in range(3)]     # (m, 3) each
    limit = max_length * max_length
    for k in range(3):
        side = corners[(k + 1) % 3] - corners[k]
        if (np.einsum("ij,ij->i", side, side) > limit).any():
            return True
    return False
