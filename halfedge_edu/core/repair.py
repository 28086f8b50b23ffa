"""``repair_faces``: turn any triangle soup into faces a halfedge mesh can hold.

The repair happens in three steps, each undoing one way a face list can fail to be a
manifold surface (see ``manifold_report``):

1. drop degenerate faces (a repeated vertex) and duplicate faces (the same three
   vertices as an earlier face, in either orientation);
2. orient: walk each connected piece breadth-first across edges with exactly two
   faces, flipping faces to agree with their neighbours; each piece keeps the
   orientation most of its faces already had;
3. split: around each vertex, group the corners into fans joined through edges with
   exactly two consistently oriented faces; every fan after the first gets its own copy
   of the vertex. This cuts non-manifold edges and vertices apart, and cuts a piece
   that cannot be oriented (a Moebius strip) along the edges where orientation fails.

Why one split is enough: after it, each vertex copy has one fan, a path or a cycle of
faces joined through good edges. A bad edge (a, b) is never a joint, so at copy a' only
the two end faces of a path can have it as a side, and if both also share the copy b'
they close the fan into a cycle, around which consistent orientation makes them run
along (a, b) in opposite directions: a good edge after all. ``repair_faces`` still
checks the result with ``manifold_report``.

Attention: the output may have more vertices than the input (the copies, appended at
the end) and fewer faces; ``RepairReport.face_origin`` and ``vertex_origin`` map back.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import MeshInputError
from .arrays import face_halfedges, sort_undirected
from .manifold import check_faces_array, corner_fans, manifold_report

__all__ = ["RepairReport", "repair_faces"]


@dataclass
class RepairReport:
    """What ``repair_faces`` changed. Face numbers are rows of the input face array.

    Attributes:
        dropped_degenerate: (k,) faces dropped because they repeat a vertex.
        dropped_duplicate: (k,) faces dropped because an earlier face has the same vertices.
        flipped_faces: (k,) faces whose orientation was reversed.
        vertex_copies: (k, 2) rows ``(original vertex, new vertex)``: each copy made
            when a vertex was split into fans.
        face_origin: (m_out,) the input face of each output face.
        vertex_origin: (n_out,) the input vertex of each output vertex.

    ``bool(report)`` is True when anything changed.
    """

    dropped_degenerate: np.ndarray
    dropped_duplicate: np.ndarray
    flipped_faces: np.ndarray
    vertex_copies: np.ndarray
    face_origin: np.ndarray
    vertex_origin: np.ndarray

    def __bool__(self) -> bool:
        changes = (self.dropped_degenerate, self.dropped_duplicate, self.flipped_faces, self.vertex_copies)
        return any(len(done) for done in changes)

    @property
    def split_vertices(self) -> np.ndarray:
        """(k,) the input vertices that were split into copies."""
        return np.unique(self.vertex_copies[:, 0])

    def describe(self, max_items: int = 8) -> str:
        """A few readable lines: each kind of change and the elements it touched."""
        if not self:
            return "repair_faces changed nothing: the faces were already manifold and consistently oriented"

        def listing(items: list) -> str:
            shown = ", ".join(str(item) for item in items[:max_items])
            return shown + (f", ... and {len(items) - max_items} more" if len(items) > max_items else "")

        copies: dict[int, list[int]] = {}
        for original, copy in self.vertex_copies.tolist():
            copies.setdefault(original, []).append(copy)
        splits = [f"{v} -> {[v] + c}" for v, c in copies.items()]
        rows = [
            ("dropped degenerate faces", self.dropped_degenerate.tolist()),
            ("dropped duplicate faces", self.dropped_duplicate.tolist()),
            ("flipped faces", self.flipped_faces.tolist()),
            ("split vertices (into copies)", splits),
        ]
        lines = ["repair_faces changed the mesh:"]
        lines += [f"  {title} ({len(items)}): {listing(items)}" for title, items in rows if items]
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.describe()


def repair_faces(vertices, faces) -> tuple[np.ndarray, np.ndarray, RepairReport]:
    """Make a triangle soup loadable by ``HalfedgeMesh.from_faces``.

    Args:
        vertices: (n, 3) float positions.
        faces: (m, 3) int triangles, 0-based.

    Returns:
        ``(vertices, faces, report)``: new (n', 3) float64 and (m', 3) int64 arrays whose
        ``manifold_report`` is clean, and a ``RepairReport`` of what changed. Faces that
        were already clean come back unchanged (equal copies, and a report that is False).
        Vertex copies are appended after the input vertices; unreferenced vertices stay.

    Raises:
        MeshInputError: wrong shapes or indices out of range.
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise MeshInputError(f"vertices must have shape (n, 3), not {vertices.shape}")
    faces, n_vertices = check_faces_array(faces, len(vertices))
    empty = np.zeros(0, dtype=np.int64)

    before = manifold_report(faces, n_vertices)
    if before:
        return vertices.copy(), faces.copy(), RepairReport(
            empty, empty, empty, np.zeros((0, 2), np.int64), np.arange(len(faces)), np.arange(n_vertices)
        )

    # 1. Drop degenerate faces, then duplicates of an earlier face.
    dropped = np.zeros(len(faces), dtype=bool)
    dropped[before.degenerate_faces] = True
    dropped[before.duplicate_faces] = True
    face_origin = np.flatnonzero(~dropped)  # (m',) input row of each kept face
    kept = faces[face_origin]

    # 2. Orient each piece consistently.
    flip = _orientation_flips(kept)  # (m',) bool
    kept[flip] = kept[flip][:, [0, 2, 1]]

    # 3. Split vertices into fans.
    out_faces, copies = _split_fans(kept, n_vertices, _joining_halfedges(kept))
    if not manifold_report(out_faces, n_vertices + len(copies)):  # pragma: no cover - see the module docstring
        raise RuntimeError("repair_faces left a non-manifold mesh; this is a bug, please report it")

    out_vertices = np.concatenate([vertices, vertices[copies]])
    report = RepairReport(
        dropped_degenerate=before.degenerate_faces,
        dropped_duplicate=before.duplicate_faces,
        flipped_faces=face_origin[flip],
        vertex_copies=np.stack([copies, n_vertices + np.arange(len(copies))], axis=1),
        face_origin=face_origin,
        vertex_origin=np.concatenate([np.arange(n_vertices), copies]),
    )
    return out_vertices, out_faces, report


def _edge_pairs(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The halfedges of edges that have exactly two faces, as pairs.

    Returns ``(first, second, opposite)``, each (k,): two halfedges (numbered ``3f + k``)
    of the same edge, and whether they run in opposite directions (consistent).
    """
    tail, head = face_halfedges(faces)
    base = max(int(faces.max()) + 1, 1) if faces.size else 1
    order, sorted_key = sort_undirected(tail, head, base)  # (3m,) uses of each edge together
    _, starts, counts = np.unique(sorted_key, return_index=True, return_counts=True)
    pairs = starts[counts == 2]
    first, second = order[pairs], order[pairs + 1]
    return first, second, tail[first] != tail[second]


def _orientation_flips(faces: np.ndarray) -> np.ndarray:
    """Which faces to flip so that each connected piece is consistently oriented.

    Faces are joined across edges with exactly two faces. A breadth-first walk from the
    first face of each piece decides each face's orientation from its parent's: keep it
    if they run along the shared edge in opposite directions, flip it otherwise. Each
    piece then keeps the orientation most of its faces had (the walk may have started
    from the odd one out). Where orientation fails (a non-orientable piece), the split
    step cuts the surface.

    Returns:
        (m,) bool, True for the faces to flip.
    """
    from scipy.sparse import coo_matrix  # imported on use: `import halfedge_edu` loads numpy only
    from scipy.sparse.csgraph import breadth_first_order, connected_components

    m = len(faces)
    if m == 0:
        return np.zeros(0, dtype=bool)
    first, second, opposite = _edge_pairs(faces)
    f, g = first // 3, second // 3
    # Weight 1: keep the neighbour's orientation; 2: flip relative to it (0 would vanish).
    weight = np.where(opposite, 1, 2)
    n_pieces, piece = connected_components(coo_matrix((weight, (f, g)), shape=(m, m)), directed=False)

    # One walk from a virtual root (node m) joined to the first face of every piece.
    _, seeds = np.unique(piece, return_index=True)
    rows = np.concatenate([f, np.full(n_pieces, m)])
    cols = np.concatenate([g, seeds])
    weights = np.concatenate([weight, np.ones(n_pieces, dtype=weight.dtype)])
    graph = coo_matrix((weights, (rows, cols)), shape=(m + 1, m + 1)).tocsr()
    graph = graph.maximum(graph.T)  # undirected, so the walk can cross either way
    _, parent = breadth_first_order(graph, m, directed=True, return_predecessors=True)
    parent = np.append(parent[:m], m)  # (m+1,); the root is its own parent
    flip_vs_parent = np.append(np.asarray(graph[np.arange(m), parent[:m]]).ravel() == 2, False)

    # Flip relative to the root = XOR along the path up the tree; pointer jumping
    # does all faces at once in log2(depth) rounds.
    flip = flip_vs_parent.copy()
    while (parent != m).any():
        flip ^= flip[parent]
        parent = parent[parent]
    flip = flip[:m]

    # Keep each piece's majority orientation (ties keep the first face's).
    flipped_per_piece = np.bincount(piece, weights=flip, minlength=n_pieces)
    size_per_piece = np.bincount(piece, minlength=n_pieces)
    return flip ^ (2 * flipped_per_piece > size_per_piece)[piece]


def _joining_halfedges(faces: np.ndarray) -> np.ndarray:
    """(3m,) bool: halfedges whose edge has exactly two consistently oriented faces.
    Only these join corners into fans."""
    first, second, opposite = _edge_pairs(faces)
    joins = np.zeros(faces.size, dtype=bool)
    joins[first[opposite]] = True
    joins[second[opposite]] = True
    return joins


def _split_fans(faces: np.ndarray, n_vertices: int, joins: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Give every fan of corners around a vertex its own vertex.

    The fan holding the vertex's lowest-numbered corner keeps the vertex; each other fan
    gets a new vertex numbered from ``n_vertices`` on.

    Returns:
        ``(faces, copies)``: the renumbered (m, 3) faces, and (k,) the original vertex
        of each new vertex ``n_vertices + i``.
    """
    labels = corner_fans(faces, joins)  # (3m,) one label per fan
    _, fan_first_corner = np.unique(labels, return_index=True)  # (n_fans,) lowest corner of each fan
    fan_vertex = faces.reshape(-1)[fan_first_corner]
    order = np.lexsort((fan_first_corner, fan_vertex))  # fans by vertex, then by first corner
    is_primary = np.ones(len(order), dtype=bool)
    is_primary[1:] = fan_vertex[order][1:] != fan_vertex[order][:-1]
    new_vertex = np.empty(len(order), dtype=np.int64)
    new_vertex[order[is_primary]] = fan_vertex[order[is_primary]]
    new_vertex[order[~is_primary]] = n_vertices + np.arange((~is_primary).sum())
    return new_vertex[labels].reshape(-1, 3), fan_vertex[order[~is_primary]]
