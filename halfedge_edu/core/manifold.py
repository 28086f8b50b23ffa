"""Is a triangle list manifold? ``manifold_report`` answers on the raw face array.

A halfedge mesh can only hold a surface where
  * every edge has one face (boundary) or two faces (interior), and those two faces run
    along it in opposite directions (consistent orientation), and
  * the faces around each vertex form a single fan: you can walk from any of them to
    any other by crossing edges that touch the vertex.

``manifold_report`` finds every place where a face list breaks these rules, without
building anything, so it works on meshes the halfedge structure cannot hold (chapter 04).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .arrays import face_halfedges, sort_undirected
from .errors import MeshInputError, first_few

__all__ = ["ManifoldReport", "manifold_report", "check_faces_array", "corner_fans"]


@dataclass
class ManifoldReport:
    """What is not manifold about a face list.

    Attributes:
        nonmanifold_edges: (k, 2) int, vertex pairs ``(a, b)`` with ``a < b`` that have
            more than two faces.
        nonmanifold_edge_faces: list of k int arrays, the faces on each of those edges.
        inconsistent_edges: (k, 2) int, directed edges ``(a, b)`` that more than one face
            runs along in the same direction (a flipped face, or a duplicated face).
        nonmanifold_vertices: (k,) int, vertices whose faces form more than one fan.
        degenerate_faces: (k,) int, faces that repeat a vertex.
        duplicate_faces: (k,) int, faces with the same three vertices as an earlier face
            (in either orientation).
        unreferenced_vertices: (k,) int, vertices that no face uses.
        n_faces, n_vertices: the sizes of the input.

    ``bool(report)`` is True when the faces are manifold and consistently oriented:
    no non-manifold edges or vertices, no inconsistent edges, no degenerate or
    duplicate faces. Unreferenced vertices do not count: building a mesh drops them.
    """

    nonmanifold_edges: np.ndarray
    nonmanifold_edge_faces: list
    inconsistent_edges: np.ndarray
    nonmanifold_vertices: np.ndarray
    degenerate_faces: np.ndarray
    duplicate_faces: np.ndarray
    unreferenced_vertices: np.ndarray
    n_faces: int = 0
    n_vertices: int = 0

    def __bool__(self) -> bool:
        problems = (self.nonmanifold_edges, self.inconsistent_edges, self.nonmanifold_vertices,
                    self.degenerate_faces, self.duplicate_faces)
        return not any(len(found) for found in problems)

    @property
    def is_manifold(self) -> bool:
        """Same as ``bool(report)``."""
        return bool(self)

    def describe(self, max_items: int = 8) -> str:
        """A few lines a student can read: what is wrong and where (long lists cut short)."""
        verdict = "manifold and consistently oriented" if self else "NOT manifold"
        lines = [f"{self.n_faces} faces, {self.n_vertices} vertices: {verdict}"]

        def listing(items: list[str]) -> str:
            shown = ", ".join(items[:max_items])
            return shown + (f", ... and {len(items) - max_items} more" if len(items) > max_items else "")

        edge_items = [
            f"({a}, {b}) with faces [{first_few(faces.tolist())}]"
            for (a, b), faces in zip(self.nonmanifold_edges.tolist(), self.nonmanifold_edge_faces)
        ]
        rows = [
            ("edges with more than two faces", edge_items),
            ("edges used twice in the same direction", [f"{a}->{b}" for a, b in self.inconsistent_edges.tolist()]),
            ("vertices whose faces form more than one fan", [str(v) for v in self.nonmanifold_vertices.tolist()]),
            ("degenerate faces (a repeated vertex)", [str(f) for f in self.degenerate_faces.tolist()]),
            ("duplicate faces", [str(f) for f in self.duplicate_faces.tolist()]),
            ("unreferenced vertices (dropped when building)", [str(v) for v in self.unreferenced_vertices.tolist()]),
        ]
        for title, items in rows:
            if items:
                lines.append(f"  {title} ({len(items)}): {listing(items)}")
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.describe()


def check_faces_array(faces, n_vertices: int | None = None) -> tuple[np.ndarray, int]:
    """Return ``faces`` as an (m, 3) int64 array and the vertex count, or raise MeshInputError."""
    faces = np.asarray(faces)
    if faces.size == 0:
        faces = faces.reshape(0, 3)
    if faces.ndim != 2 or faces.shape[1] != 3:
        raise MeshInputError(f"faces must have shape (m, 3), not {faces.shape}")
    if faces.size and not np.issubdtype(faces.dtype, np.integer):
        raise MeshInputError(f"faces must be integers, not {faces.dtype}")
    faces = faces.astype(np.int64)
    largest = int(faces.max()) + 1 if faces.size else 0
    n_vertices = largest if n_vertices is None else int(n_vertices)
    bad = np.flatnonzero(((faces < 0) | (faces >= n_vertices)).any(axis=1))
    if len(bad):
        f = int(bad[0])
        raise MeshInputError(
            f"face {f} {faces[f].tolist()} uses an index outside 0..{n_vertices - 1}", element=("face", f)
        )
    return faces, n_vertices


def corner_fans(faces: np.ndarray, joins: np.ndarray | None = None) -> np.ndarray:
    """Label each corner (``3f + k``) with the fan it belongs to.

    Two corners at the same vertex are in the same fan when their faces share an edge
    at that vertex, directly or through other faces. ``joins`` (3m,) bool says which
    halfedges may join faces (default: all); ``repair_faces`` uses it to join only
    across edges with two consistently oriented faces.

    Returns:
        (3m,) int labels; corners with the same label are in one fan.
    """
    from scipy.sparse import coo_matrix  # imported on use: `import halfedge_edu` loads numpy only
    from scipy.sparse.csgraph import connected_components

    n_corners = faces.size
    tail, head = face_halfedges(faces)
    corner = np.arange(n_corners)  # halfedge 3f+k starts at corner 3f+k
    next_corner = corner - corner % 3 + (corner % 3 + 1) % 3  # ... and ends at corner 3f+(k+1)%3
    if joins is not None:
        tail, head, corner, next_corner = tail[joins], head[joins], corner[joins], next_corner[joins]

    # Sort the halfedges by undirected edge; neighbours in that order share the edge.
    order, sorted_key = sort_undirected(tail, head, int(faces.max()) + 1 if faces.size else 1)
    same_edge = sorted_key[1:] == sorted_key[:-1]
    first, second = order[:-1][same_edge], order[1:][same_edge]
    # The corner at the edge's lower vertex, and at its higher vertex, for each halfedge.
    low_corner = np.where(tail < head, corner, next_corner)
    high_corner = np.where(tail < head, next_corner, corner)
    rows = np.concatenate([low_corner[first], high_corner[first]])
    cols = np.concatenate([low_corner[second], high_corner[second]])
    graph = coo_matrix((np.ones(len(rows), dtype=np.int8), (rows, cols)), shape=(n_corners, n_corners))
    _, labels = connected_components(graph, directed=False)
    return labels


def manifold_report(faces, n_vertices: int | None = None) -> ManifoldReport:
    """Find the non-manifold edges and vertices, orientation conflicts and bad faces.

    Args:
        faces: (m, 3) int array of 0-based vertex indices (any triangle soup).
        n_vertices: the number of vertices (default: the largest index + 1); needed
            only to report unreferenced vertices past the last used one.

    Returns:
        A ``ManifoldReport``; ``bool(report)`` is True when the halfedge structure can
        hold the faces. Degenerate faces are reported and left out of the edge and
        vertex checks.

    Raises:
        MeshInputError: ``faces`` is not an (m, 3) integer array of indices in range.
    """
    faces, n_vertices = check_faces_array(faces, n_vertices)
    m = len(faces)

    degenerate = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
    good = np.flatnonzero(~degenerate)  # indices of the faces checked below
    clean = faces[good]  # (g, 3)

    referenced = np.zeros(n_vertices, dtype=bool)
    referenced[faces.reshape(-1)] = True

    # Duplicate faces: the same sorted vertex triple as an earlier face.
    triples = np.sort(clean, axis=1)  # (g, 3)
    order = np.lexsort(triples.T[::-1])  # sort rows; lexsort is stable, so earlier faces come first
    repeats = (triples[order][1:] == triples[order][:-1]).all(axis=1)
    duplicates = np.sort(good[order[1:][repeats]])

    # Edges: undirected edges with more than two faces, directed edges used twice.
    # An edge (a, b) gets the integer key a * base + b, so numpy sorts plain integers.
    base = max(n_vertices, 1)
    tail, head = face_halfedges(clean)
    halfedge_face = good[np.arange(clean.size) // 3]  # (3g,) face of each halfedge, input numbering
    by_edge, sorted_key = sort_undirected(tail, head, base)  # (3g,) uses of each edge together
    keys, starts, counts = np.unique(sorted_key, return_index=True, return_counts=True)
    crowded = np.flatnonzero(counts > 2)
    edge_faces = [np.sort(halfedge_face[by_edge[starts[e]:starts[e] + counts[e]]]) for e in crowded]
    nonmanifold_edges = np.stack(np.divmod(keys[crowded], base), axis=1)  # (k, 2)

    directed_keys, directed_counts = np.unique(tail * base + head, return_counts=True)
    repeated = directed_keys[directed_counts > 1]
    inconsistent = np.stack(np.divmod(repeated, base), axis=1)  # (k, 2)

    # Vertices: more than one fan of corners around the vertex.
    labels = corner_fans(clean)
    corner_vertex = clean.reshape(-1)
    fans = np.unique(corner_vertex * max(clean.size, 1) + labels)  # one key per (vertex, fan)
    fan_vertices, fan_counts = np.unique(fans // max(clean.size, 1), return_counts=True)

    return ManifoldReport(
        nonmanifold_edges=nonmanifold_edges.reshape(-1, 2),
        nonmanifold_edge_faces=edge_faces,
        inconsistent_edges=inconsistent.reshape(-1, 2),
        nonmanifold_vertices=fan_vertices[fan_counts > 1],
        degenerate_faces=np.flatnonzero(degenerate),
        duplicate_faces=duplicates,
        unreferenced_vertices=np.flatnonzero(~referenced),
        n_faces=m,
        n_vertices=n_vertices,
    )
