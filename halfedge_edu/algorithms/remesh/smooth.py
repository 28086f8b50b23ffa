"""Phase 4 of remeshing: tangential smoothing.

First the centroid of every vertex's neighbours (all of them, from the old positions:
a Jacobi step), then every vertex moves towards its centroid *only in its tangent
plane*, so the vertices spread out evenly without the surface shrinking. Boundary
vertices stay put; with features, a vertex on a feature line slides along its own two
edges (:func:`_slide_along_line`) and corners stay.
"""

from __future__ import annotations

import numpy as np

from ...core.corner_table import EdgeTable, edge_table
from ..features import Features
from ..normals import area_weighted_vertex_normals


def tangential_smoothing(vertices: np.ndarray, faces: np.ndarray, features: Features | None = None,
                         fraction: float = 1.0, *, table: EdgeTable | None = None) -> np.ndarray:
    """Move every interior vertex to its neighbours' centroid, in its tangent plane only.

    Why: after the splits, collapses and flips the edges are about the right length
    and the degrees about right, but the vertices are unevenly spaced; moving each
    towards its neighbours' centroid evens them out, and dropping the move's normal
    part keeps the surface from shrinking.

    Without ``features`` the boundary vertices stay. With them, vertices on a feature
    line (the boundary is one) move only along it: towards the midpoint of their two
    neighbours on the line, along the direction from one to the other (smoothing in 1D);
    corners stay.

    Args:
        vertices: (n, 3) float positions (not modified).
        faces: (m, 3) int triangles.
        features: the feature lines to keep (None: only the boundary stays).
        fraction: how much of each step is taken, from 0 to 1 (1: all the way).
        table: the :func:`~halfedge_edu.core.corner_table.edge_table` of ``faces``, if the
            caller has it already.

    Returns:
        (n, 3) the new positions.
    """
    n = len(vertices)
    if table is None:
        table = edge_table(faces, n)
    edges = table.edges
    degree = np.bincount(edges.reshape(-1), minlength=n)
    # All centroids first, from the old positions (Jacobi): sums over both directions of each edge.
    centroid = np.empty((n, 3))
    for axis in range(3):
        centroid[:, axis] = (np.bincount(edges[:, 0], weights=vertices[edges[:, 1], axis], minlength=n)
                             + np.bincount(edges[:, 1], weights=vertices[edges[:, 0], axis], minlength=n))
    centroid /= np.maximum(degree, 1)[:, None]
    normal = area_weighted_vertex_normals(vertices, faces)
    step = centroid - vertices
    step -= normal * np.einsum("ij,ij->i", step, normal)[:, None]     # drop the normal part
    if features is None:
        step[table.boundary_vertices(n)] = 0.0
        return vertices + fraction * step
    step[features.counts() > 0] = 0.0
    smoothed = vertices + fraction * step
    on_line, before, after = features.line_neighbours()
    moving = ~features.corners[on_line]
    smoothed[on_line[moving]] = _slide_along_line(vertices, on_line[moving], before[moving], after[moving], fraction)
    return smoothed


def _slide_along_line(vertices: np.ndarray, on_line: np.ndarray, before: np.ndarray, after: np.ndarray,
                      fraction: float) -> np.ndarray:
    """(j, 3) where smoothing moves each vertex ``on_line`` (j,) along its line, between
    its two neighbours ``before`` and ``after`` on it: towards the point halfway along
    the path ``before -> vertex -> after``, ``fraction`` of the way.

    The vertex walks along its own two edges, never along the chord from ``before`` to
    ``after``: where the line turns at the vertex (by less than the feature angle, or
    it would be a corner), the chord leaves the line, and the vertex would leave it too.
    On a straight line both are the same move (to the midpoint of the neighbours).
    """
    point = vertices[on_line]                                            # (j, 3)
    to_before, to_after = vertices[before] - point, vertices[after] - point
    length_before = np.sqrt(np.einsum("ij,ij->i", to_before, to_before))  # (j,) the vertex's two edges
    length_after = np.sqrt(np.einsum("ij,ij->i", to_after, to_after))
    # Signed distance to walk along the path: > 0 towards ``after``, < 0 towards ``before``.
    # The halfway point lies on the longer of the two edges, |walk| from the vertex.
    walk = fraction * 0.5 * (length_after - length_before)
    edge = np.where(walk[:, None] >= 0, to_after, to_before)             # (j, 3) the edge walked along
    edge_length = np.where(walk >= 0, length_after, length_before)
    share = np.abs(walk) / np.maximum(edge_length, 1e-300)               # (j,) at most 1/2 of that edge
    return point + edge * share[:, None]

