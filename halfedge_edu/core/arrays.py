"""The array toolbox: what whole-array code needs to know about a triangle array.

Construction (:mod:`.build`), :func:`validate`, and the fast algorithms (``simplify``,
``remesh``) all work on plain numpy arrays, not on halfedge objects: a face array
``faces`` (m, 3) of vertex indices, counter-clockwise, and positions (n, 3). They need
the same few ideas, kept here once:

* **Directed edges of faces.** Face ``f`` uses the directed edges ``faces[f, k] ->
  faces[f, k + 1]``, numbered ``3 f + k`` (:func:`face_halfedges`).
* **Edge keys.** An undirected edge ``{a, b}`` is the integer ``low * n + high`` with
  ``low < high`` (:func:`undirected_keys`). Sorting integers is what numpy does fastest,
  and after a sort the uses of one edge sit next to each other: a run of one is a
  boundary edge, a run of two an interior edge, longer runs are non-manifold.
* **Edge tables.** The distinct edges of a face array, with how many faces use each
  (:func:`unique_edges`). Which halfedges use each edge, their twins and the rings
  around each vertex are the corner table (:mod:`.corner_table`), with its per-edge view
  ``EdgeTable`` and ``edge_table``.
* **CSR adjacency.** "The neighbours of vertex v" as one flat array plus offsets
  (compressed sparse rows): row v is ``values[offsets[v]:offsets[v + 1]]``
  (:func:`vertex_neighbours`, :func:`vertex_faces`), and :func:`expand` gathers many
  rows at once without a Python loop.
* **Merging and compaction.** Collapsing edges on a face array is a relabelling: every
  removed vertex becomes the one it merges into, and the faces that held both go
  (:func:`merge_vertices`); then drop the vertices no face uses and renumber
  (:func:`compact`).
* **Face cross products.** ``(b - a) x (c - a)`` of every face: its direction is the
  face normal, its length twice the area (:func:`face_cross`).

This module imports nothing else from the package, so every layer may use it.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "compact", "cross_rows", "csr", "expand", "face_cross", "face_halfedges", "grouping_order", "key_ends",
    "merge_vertices", "sort_undirected", "undirected_keys", "unique_edges", "vertex_faces", "vertex_neighbours",
]


# ----------------------------------------------------------------------------------------
# Directed edges and edge keys
# ----------------------------------------------------------------------------------------

def face_halfedges(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The directed edges of each face, corner by corner.

    Returns ``(tail, head)``, each (3m,): directed edge ``3f + k`` runs from corner ``k``
    of face ``f`` to corner ``k + 1``, that is ``faces[f, k] -> faces[f, (k + 1) % 3]``.
    """
    tail = faces.reshape(-1)                                  # (3m,)
    head = faces[:, [1, 2, 0]].reshape(-1)                    # (3m,)
    return tail, head


def undirected_keys(tail: np.ndarray, head: np.ndarray, n_vertices: int) -> np.ndarray:
    """(k,) int64 key ``low * n_vertices + high`` of each edge ``tail[i] - head[i]``.

    Both directions of an edge get the same key, and keys sort like ``(low, high)``
    pairs, so ``key // n_vertices`` and ``key % n_vertices`` give the ends back.
    """
    # In-place arithmetic: each new int64 array costs ~30 MB at 1.3M faces.
    key = np.minimum(tail, head, dtype=np.int64)
    key *= n_vertices
    key += np.maximum(tail, head)
    return key


def key_ends(keys: np.ndarray, n_vertices: int) -> np.ndarray:
    """(k, 2) int64 the ends ``(low, high)`` of each edge key of :func:`undirected_keys`.

    Written straight into the table: ``key // n_vertices``, then ``key % n_vertices``
    as ``key - low * n_vertices`` (no second division), with no whole-array temporaries
    (on a big mesh each would be tens of MiB, handed out afresh by the system each time).
    """
    ends = np.empty((len(keys), 2), dtype=np.int64)
    low, high = ends[:, 0], ends[:, 1]                        # views into the table
    np.floor_divide(keys, n_vertices, out=low)
    np.multiply(low, n_vertices, out=high)
    np.subtract(keys, high, out=high)
    return ends


def sort_undirected(tail: np.ndarray, head: np.ndarray, n_vertices: int) -> tuple[np.ndarray, np.ndarray]:
    """Sort directed edges by their undirected key, keeping equal keys in input order.

    Returns ``(order, sorted_key)``: ``order`` (k,) lists directed-edge numbers so that
    their keys (:func:`undirected_keys`) ascend, ties in increasing directed-edge number
    (a stable order: the first use of an edge comes first).

    How: when it fits in 63 bits, the directed-edge number is packed into the low bits
    of the key and the packed numbers are sorted with ``np.sort``, which is several
    times faster than a stable ``argsort``; ties are then broken by the packed position,
    which is exactly stability. Larger meshes fall back to ``argsort(kind="stable")``.
    """
    key = undirected_keys(tail, head, n_vertices)
    n = len(key)
    position_bits = max(1, int(n - 1).bit_length())
    if (int(n_vertices) ** 2) < 2 ** (63 - position_bits):
        packed = key
        packed <<= position_bits
        packed |= np.arange(n, dtype=np.int64)
        packed.sort()
        order = packed & ((1 << position_bits) - 1)
        packed >>= position_bits
        return order, packed
    order = np.argsort(key, kind="stable")
    return order, key[order]


def grouping_order(rows: np.ndarray, n: int) -> np.ndarray:
    """The stable order that sorts ``rows`` (k,) (values below ``n``), as ``np.argsort(rows, kind="stable")``.

    The position is packed into the low bits of each row value and the packed numbers
    are sorted with ``np.sort``, about twice as fast as an argsort (the trick of
    :func:`sort_undirected`); values too large to pack fall back.
    """
    bits = max(1, int(len(rows) - 1).bit_length())
    if int(n) >= 2 ** (62 - bits):
        return np.argsort(rows, kind="stable")
    packed = rows.astype(np.int64)                 # a copy, shifted and sorted in place
    packed <<= bits
    packed |= np.arange(len(rows), dtype=np.int64)
    packed.sort()
    packed &= (1 << bits) - 1
    return packed


# ----------------------------------------------------------------------------------------
# Edge tables
# ----------------------------------------------------------------------------------------

def unique_edges(faces: np.ndarray, n_vertices: int) -> tuple[np.ndarray, np.ndarray]:
    """The distinct edges of a face array: ``(edges (E, 2) low/high, face_count (E,))``.

    Edges come in key order (by low end, then high end); ``face_count`` is 1 on the
    boundary and 2 inside. One plain sort of the keys: the cheapest table, for code that
    does not need to know which faces use an edge (for that, :class:`.corner_table.CornerTable`).
    """
    key = undirected_keys(*face_halfedges(faces), n_vertices)
    unique_key, count = np.unique(key, return_counts=True)
    return np.stack([unique_key // n_vertices, unique_key % n_vertices], axis=1), count


# ----------------------------------------------------------------------------------------
# CSR adjacency
# ----------------------------------------------------------------------------------------

def csr(rows: np.ndarray, values: np.ndarray, n_rows: int) -> tuple[np.ndarray, np.ndarray]:
    """Group ``values`` by ``rows`` into CSR ``(offsets (n_rows + 1,), values sorted by row)``.

    The values within a row come in no particular order: numpy's quicksort groups them
    about five times faster than its stable sort, and no caller needs the order.
    """
    order = np.argsort(rows)
    offsets = np.zeros(n_rows + 1, dtype=np.int64)
    np.cumsum(np.bincount(rows, minlength=n_rows), out=offsets[1:])
    return offsets, values[order]


def vertex_neighbours(edges: np.ndarray, n_vertices: int) -> tuple[np.ndarray, np.ndarray]:
    """Each vertex's neighbours as CSR ``(offsets (n + 1,), neighbours (2E,))``, from (E, 2) edges."""
    both = np.concatenate([edges, edges[:, ::-1]])                  # every edge, both ways
    return csr(both[:, 0], both[:, 1], n_vertices)


def vertex_faces(faces: np.ndarray, n_vertices: int) -> tuple[np.ndarray, np.ndarray]:
    """Each vertex's faces as CSR ``(offsets (n + 1,), face indices (3m,))``, from (m, 3) faces."""
    return csr(faces.reshape(-1), np.repeat(np.arange(len(faces)), 3), n_vertices)


def expand(offsets: np.ndarray, values: np.ndarray, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gather the CSR rows ``rows[0], rows[1], ...`` at once: ``(owner, items)``.

    ``items`` is every row's values, one row after the other; ``owner[j]`` is the
    position ``i`` in ``rows`` whose row ``items[j]`` came from. So a loop "for each
    ``i``, for each neighbour of ``rows[i]``" becomes one array pass over ``items``.
    """
    counts = offsets[rows + 1] - offsets[rows]
    owner = np.repeat(np.arange(len(rows)), counts)
    start = np.repeat(offsets[rows] - np.cumsum(counts) + counts, counts)
    return owner, values[start + np.arange(counts.sum())]


# ----------------------------------------------------------------------------------------
# Compaction and face geometry
# ----------------------------------------------------------------------------------------

def compact(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Drop vertices no face uses: ``(vertices, faces renumbered, kept)``.

    Vertices keep their relative order; ``kept`` (n_kept,) is the old index of each
    vertex that stayed, so ``new vertices == vertices[kept]``.
    """
    used = np.zeros(len(vertices), dtype=bool)
    used[faces.reshape(-1)] = True
    kept = np.flatnonzero(used)
    new_index = np.cumsum(used) - 1                          # old index -> new index where used
    return vertices[kept], new_index[faces], kept


def merge_vertices(faces: np.ndarray, remove: np.ndarray, keep: np.ndarray, n_vertices: int) -> np.ndarray:
    """Faces after merging vertex ``remove[i]`` into ``keep[i]`` for every i, all at once.

    Every corner at ``remove[i]`` becomes ``keep[i]``; a face that then repeats a vertex
    (it held both ends of a collapsed edge) is dropped. The order of the other faces is
    kept. The vertices themselves stay (unused ones go with :func:`compact`).
    """
    relabel = np.arange(n_vertices)
    relabel[remove] = keep
    faces = relabel[faces]
    degenerate = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
    return faces[~degenerate]


def cross_rows(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Row-wise cross product of (k, 3) arrays (faster than np.cross for many short rows)."""
    return np.stack(
        [u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1],
         u[:, 2] * v[:, 0] - u[:, 0] * v[:, 2],
         u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]],
        axis=1,
    )


def face_cross(corners: np.ndarray) -> np.ndarray:
    """(k, 3) ``(b - a) x (c - a)`` for the corner positions ``corners`` (k, 3, 3) of k triangles.

    It points along the face normal (right-hand rule over counter-clockwise corners)
    and its length is twice the triangle's area; zero for a degenerate triangle.
    ``corners`` is ``vertices[faces]`` for a whole face array.
    """
    return cross_rows(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
