"""The corner table: the halfedges of the course, with ``next`` by arithmetic.

:class:`HalfedgeMesh` stores ``next`` for every halfedge and gets ``twin`` by arithmetic
(edge ``e`` owns halfedges ``2e`` and ``2e + 1``, so ``twin(h) = h ^ 1``). The fast
algorithms (``simplify``, ``remesh``) work on a plain face array ``faces`` (m, 3)
instead, and use the same halfedges the other way round: ``next`` by arithmetic,
``twin`` stored. Number the three halfedges of face ``f`` as ``3f + k``, halfedge
``3f + k`` leaving corner ``k``::

                        faces[f, 2]
                          /    ^
                         /      \\
              3f + 2    /   f    \\    3f + 1
                       v          \\
             faces[f, 0] ---------> faces[f, 1]
                           3f + 0

    halfedge h = 3f + k runs from faces[f, k] to faces[f, (k + 1) % 3]
    face(h)   = h // 3                          origin(h) = faces.flat[h]
    next(h)   = 3 * (h // 3) + (h + 1) % 3      tip(h)    = origin(next(h))
    prev(h)   = 3 * (h // 3) + (h + 2) % 3

These are chapter 02's halfedges (``h.next``, ``h.face``, ``h.vertex``), with nothing
stored for ``next``: a face's three halfedges sit side by side, so the next one is the
one after it, wrapping around. A face is its three corners; a halfedge is the corner it
leaves (hence "corner table"). Two things differ from :class:`HalfedgeMesh`:

* **No boundary halfedges.** The mesh keeps a halfedge with face -1 outside every
  boundary edge; here only faces have halfedges, and a boundary halfedge's twin is -1.
* **The twin is looked up, once, for all halfedges.** Arithmetic cannot give it: it
  lives in another face. Give both directions of an edge ``{a, b}`` the same integer
  key ``low * n + high`` and sort all 3m keys: the uses of one edge land next to each
  other, a run of one on the boundary, of two inside (longer runs: not a manifold).
  That one sort gives each edge (its slot in key order), the halfedges using it
  (``first``, ``second``), each halfedge's edge and its twin.

And from one sort of the corners by vertex, the rings (compressed sparse rows: row v is
``values[offsets[v]:offsets[v + 1]]``): each vertex's outgoing halfedges, faces and
neighbours, what a walk around ``v`` with ``h.twin.next`` visits, in another order.

:meth:`CornerTable.flip` turns edges in place, as :func:`halfedge_edu.core.ops.flip`
does on the mesh: the same two faces and the same edge slot, with new contents.

``tests/core/test_corner_table.py`` holds the table to the mesh: a built
:class:`HalfedgeMesh`'s twins are the table's, its flips give the same faces, its
one-rings the same rows.
"""

from __future__ import annotations

from functools import cached_property
from typing import NamedTuple

import numpy as np

from .arrays import grouping_order, key_ends, sort_undirected

__all__ = ["CornerTable", "EdgeTable", "edge_table", "next_halfedge", "prev_halfedge"]


def next_halfedge(h):
    """The next halfedge in the same face, ``3 * (h // 3) + (h + 1) % 3`` (an int or an array)."""
    return 3 * (h // 3) + (h + 1) % 3


def prev_halfedge(h):
    """The previous halfedge in the same face, ``3 * (h // 3) + (h + 2) % 3`` (an int or an array)."""
    return 3 * (h // 3) + (h + 2) % 3


class EdgeTable(NamedTuple):
    """The edge columns of a :class:`CornerTable`, under the names older callers read.

    A view: the same arrays, no copies (:meth:`CornerTable.edge_columns`, or
    :func:`edge_table` from a face array). ``edges`` (E, 2) low/high in key order;
    ``corner_edge`` (m, 3) the edge of halfedge ``3f + k`` (``faces[f, k] -> faces[f, k
    + 1]``); ``count`` (E,) 1 on the boundary, 2 inside; ``first``/``second`` (E,) the
    halfedges using the edge (``second`` -1 on the boundary); ``keys`` (E,) the sorted
    keys, for :func:`numpy.searchsorted` look-ups of an edge by its ends.
    """

    edges: np.ndarray
    corner_edge: np.ndarray
    count: np.ndarray
    first: np.ndarray
    second: np.ndarray
    keys: np.ndarray

    def boundary_vertices(self, n_vertices: int) -> np.ndarray:
        """(n,) True for vertices on a boundary edge."""
        on_boundary = np.zeros(n_vertices, dtype=bool)
        on_boundary[self.edges[self.count == 1].reshape(-1)] = True
        return on_boundary


def edge_table(faces: np.ndarray, n_vertices: int) -> EdgeTable:
    """The :class:`EdgeTable` of ``faces`` (m, 3), vertex indices below ``n_vertices``:
    ``CornerTable(faces, n_vertices).edge_columns()``."""
    return CornerTable(faces, n_vertices).edge_columns()


#: What a flip (:meth:`CornerTable.record_flips`) makes stale: the tables worked out from
#: the slots' contents (``edge``, ``first``, ``second`` and ``keys`` it keeps up to date itself).
_DERIVED = ("edges", "boundary_halfedge", "twin", "face_across", "_rings")


class CornerTable:
    """The halfedges ``3f + k`` of a triangle array, with their edges, twins and rings.

    ``CornerTable(faces, n_vertices)``: ``faces`` (m, 3) vertex indices below
    ``n_vertices``, counter-clockwise. Attention: ``faces`` is kept, not copied, and
    :meth:`flip` writes into it.

    Navigation (any halfedge ``h``, by arithmetic): :func:`next_halfedge`,
    :func:`prev_halfedge`, ``h // 3`` its face, ``faces.flat[h]`` its origin.

    Edges, one slot each, in key order (by low end, then high end; :meth:`flip` changes
    a slot's contents in place, see there):

    * ``keys`` (E,) ``low * n + high``; ``edges`` (E, 2) low/high;
    * ``first``, ``second`` (E,) the halfedges using the edge, ``second`` -1 on the
      boundary; ``count`` (E,) how many use it (1 on the boundary, 2 inside);
      ``boundary`` (E,) ``count == 1``; ``boundary_halfedge`` (b,) ``first`` of each
      boundary edge, in slot order. Before any flip, ``first`` is the lower-numbered
      of an interior edge's two halfedges (the sort is stable);
    * ``start_keys`` (E,) the keys before any flip, ascending; ``flipped`` (E,) the
      slots flips have changed (None before the first flip).

    Per halfedge: ``edge`` (3m,) its edge's slot; ``twin`` (3m,) the halfedge the other
    way along its edge, -1 on the boundary. Per face: ``face_across`` (m, 3) the face
    across halfedge ``3f + k``, -1 on the boundary.

    Rings, each a CSR pair ``(offsets (n + 1,), values)``, rows in no particular
    order: ``corners_around`` the halfedges leaving each vertex (its corners),
    ``faces_around`` the same rows as faces (``corner // 3``), ``neighbours`` its
    neighbouring vertices (one more than faces on the boundary).

    All but the per-edge arrays are worked out on first use and kept.
    """

    def __init__(self, faces: np.ndarray, n_vertices: int):
        self.faces = faces
        self.n_vertices = n_vertices
        origin = faces.reshape(-1)                                     # (3m,) origin of halfedge 3f + k
        self._tip = _tips(faces)                                       # (3m,) its tip, faces[f, k + 1]
        n_halfedges = len(origin)
        # The one sort: every halfedge by its edge's key, the uses of an edge side by side.
        order, sorted_key = sort_undirected(origin, self._tip, n_vertices)   # (3m,) each
        self._order = order
        self._closed = _used_twice_each(sorted_key)
        if self._closed:
            # Every edge used twice: the sorted uses pair up, (0, 1), (2, 3), ..., no search for the runs.
            self.keys, self.first, self.second = sorted_key[0::2], order[0::2], order[1::2]
            self.count = np.full(len(self.keys), 2, dtype=np.int64)
        else:
            new_run = np.ones(n_halfedges, dtype=bool)
            new_run[1:] = sorted_key[1:] != sorted_key[:-1]
            starts = np.flatnonzero(new_run)                           # (E,) where each edge's run starts
            self.count = np.diff(np.append(starts, n_halfedges))
            self.keys, self.first = sorted_key[starts], order[starts]
            inner = self.count == 2
            self.second = np.full(len(starts), -1, dtype=np.int64)
            self.second[inner] = order[starts[inner] + 1]
        self.flipped: np.ndarray | None = None      # (E,) the slots flip() changed, once it has
        self.start_keys = self.keys                 # (E,) the keys before any flip, ascending

    # -- per edge and per halfedge ---------------------------------------------------------

    @cached_property
    def edges(self) -> np.ndarray:
        """(E, 2) int64 the ends (low, high) of the edge in each slot."""
        return key_ends(self.keys, self.n_vertices)

    @cached_property
    def boundary(self) -> np.ndarray:
        """(E,) True for the slots of boundary edges (used by one face)."""
        return self.count == 1

    @cached_property
    def boundary_halfedge(self) -> np.ndarray:
        """(b,) the halfedge of each boundary edge, in slot order."""
        return self.first[self.boundary]

    @cached_property
    def edge(self) -> np.ndarray:
        """(3m,) the slot of each halfedge's edge."""
        edge = np.empty(len(self._order), dtype=np.int64)
        edge[self._order] = np.repeat(np.arange(len(self.keys)), self.count)
        return edge

    @property
    def corner_edge(self) -> np.ndarray:
        """(m, 3) ``edge`` face by face: the slot of halfedge ``faces[f, k] -> faces[f, k + 1]``."""
        return self.edge.reshape(-1, 3)

    @cached_property
    def twin(self) -> np.ndarray:
        """(3m,) the halfedge running the other way along each halfedge's edge, -1 on the boundary."""
        first, second = self._inner_uses()
        twin = np.empty(len(self.edge), dtype=np.int64) if self._closed else np.full(len(self.edge), -1, np.int64)
        twin[first] = second
        twin[second] = first
        return twin

    @cached_property
    def face_across(self) -> np.ndarray:
        """(m, 3) the face across halfedge ``3f + k``, -1 on the boundary: ``twin // 3``."""
        first, second = self._inner_uses()
        n_halfedges = 3 * len(self.faces)
        across = np.empty(n_halfedges, dtype=np.int64) if self._closed else np.full(n_halfedges, -1, np.int64)
        across[first] = second // 3
        across[second] = first // 3
        return across.reshape(-1, 3)

    def _inner_uses(self) -> tuple[np.ndarray, np.ndarray]:
        """``(first, second)`` of the interior edges' slots."""
        if self._closed:
            return self.first, self.second
        inner = self.count == 2
        return self.first[inner], self.second[inner]

    def boundary_vertices(self) -> np.ndarray:
        """(n,) True for vertices on a boundary edge."""
        return self.edge_columns().boundary_vertices(self.n_vertices)

    def edge_columns(self) -> EdgeTable:
        """The per-edge arrays as an :class:`EdgeTable` (the same arrays, no copies)."""
        return EdgeTable(self.edges, self.corner_edge, self.count, self.first, self.second, self.keys)

    # -- rings ---------------------------------------------------------------------------

    @cached_property
    def _rings(self) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
        tip = self._tip if self._tip is not None else _tips(self.faces)
        return _vertex_rings(self.faces.reshape(-1), tip, self.boundary_halfedge, self.n_vertices)

    @property
    def faces_around(self) -> tuple[np.ndarray, np.ndarray]:
        """Each vertex's faces as CSR ``(offsets (n + 1,), faces (3m,))``; a face once per corner at the vertex."""
        return self._rings[0]

    @property
    def neighbours(self) -> tuple[np.ndarray, np.ndarray]:
        """Each vertex's neighbours as CSR ``(offsets (n + 1,), vertices (2E,))``, each neighbour once."""
        return self._rings[1]

    @property
    def corners_around(self) -> tuple[np.ndarray, np.ndarray]:
        """Each vertex's corners (the halfedges leaving it) as CSR: the rows of ``faces_around``, ``3f + k`` for ``f``."""
        return self._rings[2]

    # -- flips ---------------------------------------------------------------------------

    def flip(self, h: np.ndarray) -> np.ndarray:
        """Flip the edges of halfedges ``h`` (k,) in place; returns their slots (k,).

        The halfedge ``h = a -> b`` in face ``[a, b, c]`` and its twin in ``[b, a, d]``
        become faces ``[c, a, d]`` and ``[d, b, c]``, in the same two face rows: the
        edge ``a-b`` turns into ``c-d``, as ``HalfedgeMesh.flip`` turns it (see
        :mod:`halfedge_edu.core.ops.flip`'s picture, ``v0 v1 v2 v3 = a b c d``)::

                  before                            after

                    c                                 c
                  /   ^                             / | ^
                 v  f1 \\                           v  |  \\
                a --h--> b                        a f1|f2 b
                 \\ <---- ^                         \\  |  ^
                  v f2  /                           v | /
                    d                                 d

            f1 = [a, b, c], f2 = [b, a, d]      f1 = [c, a, d], f2 = [d, b, c]

        The edge keeps its slot (``keys``, ``first``, ``second`` change in it) and so
        do the four edges around it (their halfedges change: the new faces' at the same
        place), so ``edge`` stays right with a few writes and no sort.

        Attention: the caller checks what ``can_flip`` checks (interior edge, ``c !=
        d``, no edge ``c-d`` yet: :meth:`contains`), and no two of the edges may share
        a face. The slots are then out of key order: :meth:`in_key_order`.
        """
        slot = self.edge[h]
        twin = np.where(self.first[slot] == h, self.second[slot], self.first[slot])
        flat = self.faces.reshape(-1)
        a, b = flat[h], flat[next_halfedge(h)]
        c, d = flat[prev_halfedge(h)], flat[prev_halfedge(twin)]
        self.faces[h // 3] = np.stack([c, a, d], axis=1)
        self.faces[twin // 3] = np.stack([d, b, c], axis=1)
        return self.record_flips(h, twin, c, d)

    def record_flips(self, h: np.ndarray, twin: np.ndarray, c: np.ndarray, d: np.ndarray) -> np.ndarray:
        """The slots' half of :meth:`flip`, for a caller that wrote the new faces itself.

        ``h`` (k,) the flipped halfedges, ``twin`` (k,) theirs, ``c`` and ``d`` (k,) the
        vertices opposite them (the new edge's ends). Returns the flipped slots (k,).
        """
        if self.flipped is None:
            self.flipped = np.zeros(len(self.keys), dtype=bool)
            self.keys = self.keys.copy()                               # start_keys stays sorted, for look-ups
        edge = self.edge                                               # kept up to date below
        slot = edge[h]
        f1, f2 = 3 * (h // 3), 3 * (twin // 3)                         # each face's first halfedge
        # The edges c-a, a-d, d-b and b-c: their halfedge before the flip, and after.
        around = [(prev_halfedge(h), f1), (next_halfedge(twin), f1 + 1),
                  (prev_halfedge(twin), f2), (next_halfedge(h), f2 + 1)]
        slots = [edge[old] for old, _ in around]                       # read all before writing any
        for (old, new), at in zip(around, slots):
            was_first = self.first[at] == old
            self.first[at[was_first]] = new[was_first]
            self.second[at[~was_first]] = new[~was_first]
            edge[new] = at
        self.keys[slot] = np.minimum(c, d) * self.n_vertices + np.maximum(c, d)
        self.first[slot], self.second[slot] = f1 + 2, f2 + 2           # d -> c in [c, a, d], c -> d in [d, b, c]
        edge[f1 + 2] = slot
        edge[f2 + 2] = slot
        self.flipped[slot] = True
        self._tip = None                                               # worked out again if the rings are asked for
        for name in _DERIVED:
            self.__dict__.pop(name, None)
        return slot

    def key_order(self, slots: np.ndarray) -> np.ndarray:
        """(k,) the order that lists ``slots`` (k, ascending) by key: the order a fresh
        table would list them in (only flipped slots can be out of order)."""
        if self.flipped is None or not self.flipped.any():
            return np.arange(len(slots))
        return np.argsort(self.keys[slots])

    def contains(self, keys: np.ndarray) -> np.ndarray:
        """(k,) whether each of ``keys`` is an edge now: a key of the start not flipped
        away, or the key a flip put into a slot."""
        at = np.minimum(np.searchsorted(self.start_keys, keys), len(self.start_keys) - 1)
        found = self.start_keys[at] == keys
        if self.flipped is not None:
            found &= ~self.flipped[at]
            moved = np.sort(self.keys[self.flipped])                   # (j,) the keys flips made
            if len(moved):
                at = np.minimum(np.searchsorted(moved, keys), len(moved) - 1)
                found |= moved[at] == keys
        return found

    def in_key_order(self) -> "CornerTable":
        """A table of the same faces with the slots back in key order, as a fresh one
        lists them, without a sort of all edges.

        The slots never flipped are still in key order; the flipped ones (sorted among
        themselves) are merged in where ``searchsorted`` puts them, in one pass over E.
        """
        if self.flipped is None:
            return self
        stay = np.flatnonzero(~self.flipped)                           # (E - j,) ascending keys already
        moved = np.flatnonzero(self.flipped)                           # (j,)
        moved = moved[self.key_order(moved)]
        moved_at = np.searchsorted(self.keys[stay], self.keys[moved]) + np.arange(len(moved))   # final places
        order = np.empty(len(self.keys), dtype=np.int64)               # (E,) the slot at each final place
        is_moved = np.zeros(len(self.keys), dtype=bool)
        is_moved[moved_at] = True
        order[moved_at] = moved
        order[~is_moved] = stay
        place = np.empty_like(order)                                   # (E,) the final place of each slot
        place[order] = np.arange(len(order))
        table = CornerTable.__new__(CornerTable)
        table.faces, table.n_vertices, table._tip = self.faces, self.n_vertices, self._tip
        table._order, table._closed = None, self._closed
        table.keys, table.first, table.second = self.keys[order], self.first[order], self.second[order]
        table.count = self.count[order]
        table.flipped, table.start_keys = None, table.keys
        table.edge = place[self.edge]
        return table


def _tips(faces: np.ndarray) -> np.ndarray:
    """(3m,) the tip of each halfedge ``3f + k``: ``faces[f, (k + 1) % 3]``."""
    tip = np.empty(faces.size, dtype=faces.dtype)
    tip.reshape(-1, 3)[:, :2] = faces[:, 1:]
    tip.reshape(-1, 3)[:, 2] = faces[:, 0]
    return tip


def _used_twice_each(sorted_key: np.ndarray) -> bool:
    """True if every key in ``sorted_key`` (ascending) occurs exactly twice: each pair (2i, 2i + 1) equal, and
    each pair different from the next."""
    if len(sorted_key) % 2:
        return False
    return bool(np.array_equal(sorted_key[0::2], sorted_key[1::2])
                and not (sorted_key[1:-1:2] == sorted_key[2::2]).any())


def _vertex_rings(origin: np.ndarray, tip: np.ndarray, boundary_halfedge: np.ndarray,
                  n: int) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
    """Each vertex's faces, neighbours and corners, as three CSRs from one sort of the corners.

    ``origin`` and ``tip`` (3m,) are the ends of each halfedge ``3f + k``;
    ``boundary_halfedge`` (b,) the ones on the boundary.

    The neighbours come from the corners: corner ``(f, k)`` at vertex v names the next
    corner's vertex, ``faces[f, k + 1]``. Around an inner vertex that lists every
    neighbour once. The faces of a boundary vertex form one open fan (the mesh has no
    vertex with two fans), and the neighbour at its clockwise end is missing; it is the
    origin of the boundary halfedge whose tip is v, so each boundary edge adds one row.
    """
    rows, values = origin, tip
    if len(boundary_halfedge):
        rows = np.concatenate([rows, tip[boundary_halfedge]])          # (3m + b,) the tip for the extra rows
        values = np.concatenate([values, origin[boundary_halfedge]])   # ... and the origin as its neighbour
    order = grouping_order(rows, n)
    face_offsets = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(origin, minlength=n), out=face_offsets[1:])
    # A vertex has as many neighbours as faces, plus one on the boundary: count only the extra rows.
    neighbour_offsets = face_offsets.copy()
    neighbour_offsets[1:] += np.cumsum(np.bincount(tip[boundary_halfedge], minlength=n))
    # The sort, without the extra rows (a closed mesh has none).
    corners = order[order < len(origin)] if len(boundary_halfedge) else order
    return (face_offsets, corners // 3), (neighbour_offsets, values[order]), (face_offsets, corners)
