"""Phase 3 of remeshing: flip edges toward vertex degree 6 (4 on the boundary).

Edge ``a-b`` with faces ``[a, b, c]`` and ``[b, a, d]`` becomes ``c-d`` with faces
``[c, a, d]`` and ``[d, b, c]``: a and b lose an edge, c and d gain one. A flip is made
where that brings the four degrees closer, in total, to their ideal: 6 inside, the
degree of a vertex in a regular triangle grid, and 4 on the boundary.

The flips run in passes: every interior edge's degree gain is computed at once, and a
set of improving flips that share no vertex is flipped together (:func:`_flip_pass`).
The edge list is sorted once per phase and then updated in place by each pass
(:class:`_EdgeUses`, a view of the faces' corner table: a flip changes five edges,
found through the slot each halfedge names, without a search).
"""

from __future__ import annotations

import math

import numpy as np

from ...core.arrays import cross_rows
from ...core.corner_table import EdgeTable
from ...core.corner_table import CornerTable
from ..features import Features

#: How many flip passes one iteration may take (each pass is one array operation).
MAX_FLIP_PASSES = 10
#: Flip passes stop once a pass flips at most this fraction of the faces' count; the
#: last few flips (a handful of edges each pass) are left to the next iteration.
MIN_FLIP_FRACTION = 0.001
#: An edge whose two faces meet at a sharper angle than this is a crease, never flipped.
MAX_FLIP_DIHEDRAL = 20.0


def flip_to_regular_degrees(vertices: np.ndarray, faces: np.ndarray, rng: np.random.Generator,
                            features: Features | None = None) -> tuple[np.ndarray, EdgeTable]:
    """Flip edges where that brings the degrees of the four vertices involved closer to
    6 (4 on the boundary), pass after pass until few flips are left (at most
    :data:`MAX_FLIP_PASSES` passes, stopping once a pass flips at most
    :data:`MIN_FLIP_FRACTION` of the faces' count).

    Why: in a grid of equilateral triangles every inner vertex has degree 6; a vertex of
    another degree pulls its triangles out of shape, and smoothing cannot fix that
    alone. An edge whose faces meet at more than :data:`MAX_FLIP_DIHEDRAL` degrees (a
    crease) is never flipped, nor is a feature edge; see :func:`_flip_pass` for the rest.

    Args:
        vertices: (n, 3) float positions (only read: a flip moves no vertex).
        faces: (m, 3) int triangles (not modified).
        rng: breaks ties between flips of equal gain (seeded by the caller: the same
            seed, the same flips).
        features: the feature lines to keep (None: only the boundary's edges are kept,
            which no flip can touch anyway).

    Returns:
        ``(faces, table)``: the flipped faces (m, 3), and their
        :class:`~halfedge_edu.core.corner_table.EdgeTable`, which the passes kept up to date
        (smoothing and projection use it).
    """
    max_crease_cos = math.cos(math.radians(MAX_FLIP_DIHEDRAL))
    uses = _EdgeUses.of(faces, len(vertices))
    faces = faces.copy()                                               # the passes flip in this copy
    for _ in range(MAX_FLIP_PASSES):
        faces, n_flipped, uses = _flip_pass(vertices, faces, rng, max_crease_cos, features, uses=uses,
                                            in_place=True)
        if n_flipped <= MIN_FLIP_FRACTION * len(faces):
            break
    return faces, uses.table()


def _unit(vectors: np.ndarray) -> np.ndarray:
    return vectors / np.maximum(np.linalg.norm(vectors, axis=1), 1e-300)[:, None]


class _EdgeUses:
    """A flip phase's corner table, with each vertex's degree counted as the flips go.

    The edges are the slots of a :class:`~halfedge_edu.core.corner_table.CornerTable`
    (``corners``), sorted once when the phase begins (``of``). A flip keeps its edge's
    slot and only changes what is in it (the new key ``c-d`` and its two halfedges), and
    ``corners.edge`` names the slot of every halfedge, so a flip finds the slots of its
    edge and of the four edges around it by looking them up there (one read each)
    instead of searching the sorted keys for them (a random walk through all E keys per
    look-up): :meth:`CornerTable.record_flips`. The slots stay in key order except the
    flipped ones; :meth:`table` puts them back in order once, at the end of the phase.

    Besides the table's ``keys``, ``first``, ``second``, ``start_keys``, :meth:`contains`
    and :meth:`key_order`, what the flip pass asks: ``inner`` the slots of interior edges
    (flips keep them interior); ``degree`` (n,) how many edges each vertex has;
    ``boundary_vertex`` (n,) the vertices on a boundary edge (flips do not change them);
    ``n`` the number of vertices. The faces are the caller's: :func:`_flip_pass` writes
    the new faces, then tells the table (:meth:`flip`).
    """

    def __init__(self, corners: CornerTable):
        self.corners = corners
        self.n = n = corners.n_vertices
        keys, second = corners.keys, corners.second
        self.inner = np.flatnonzero(second >= 0)
        self.degree = np.bincount(keys // n, minlength=n) + np.bincount(keys % n, minlength=n)
        boundary_edge = keys[second < 0]
        self.boundary_vertex = np.zeros(n, dtype=bool)
        self.boundary_vertex[boundary_edge // n] = True
        self.boundary_vertex[boundary_edge % n] = True

    @classmethod
    def of(cls, faces: np.ndarray, n: int) -> "_EdgeUses":
        return cls(CornerTable(faces, n))

    keys = property(lambda self: self.corners.keys, doc="(E,) the key of the edge in each slot.")
    first = property(lambda self: self.corners.first, doc="(E,) a halfedge using each slot's edge.")
    second = property(lambda self: self.corners.second, doc="(E,) the other one, -1 on the boundary.")
    start_keys = property(lambda self: self.corners.start_keys, doc="(E,) the keys at the start, ascending.")

    def key_order(self, slots: np.ndarray) -> np.ndarray:
        """:meth:`CornerTable.key_order <halfedge_edu.core.corner_table.CornerTable.key_order>`."""
        return self.corners.key_order(slots)

    def contains(self, keys: np.ndarray) -> np.ndarray:
        """:meth:`CornerTable.contains <halfedge_edu.core.corner_table.CornerTable.contains>`."""
        return self.corners.contains(keys)

    def table(self) -> EdgeTable:
        """The :class:`~halfedge_edu.core.corner_table.EdgeTable` of the faces these uses are
        of, edges in key order as a fresh one lists them: smoothing and projection after
        the flips ask for it (:meth:`CornerTable.in_key_order`, no sort of all edges)."""
        return self.corners.in_key_order().edge_columns()

    def flip(self, a, b, c, d, h1, h2) -> None:
        """Record flips of edges ``a-b`` (halfedge ``h1`` in face ``[a, b, c]``, ``h2`` in
        ``[b, a, d]``) into ``c-d``, the faces becoming ``[c, a, d]`` and ``[d, b, c]``
        (see :func:`_flip_pass`; the flips share no vertex, so no slot is touched twice)."""
        self.corners.record_flips(h1, h2, c, d)
        self.degree[a] -= 1                                            # the flips share no vertex: no repeats
        self.degree[b] -= 1
        self.degree[c] += 1
        self.degree[d] += 1


def _flip_pass(vertices, faces, rng, max_crease_cos, features: Features | None = None, selection_passes: int = 4,
               uses: _EdgeUses | None = None, *, in_place: bool = False):
    """Flip a vertex-disjoint set of degree-improving edges. Returns ``(faces, n_flipped,
    uses)``: ``uses`` the :class:`_EdgeUses` of the new faces (given ``uses`` of ``faces``,
    it is updated in place and the pass does not sort the edges again). ``in_place``:
    flip in ``faces`` itself instead of a copy (the flip phase copies once for all passes).

    Edge ``a-b`` with faces ``[a, b, c]`` and ``[b, a, d]`` becomes ``c-d`` with faces
    ``[c, a, d]`` and ``[d, b, c]``: a and b lose an edge, c and d gain one. With
    ``features``, a feature edge is never flipped (the lines keep their edges), and no
    flip makes an edge between two vertices on lines (c and d).

    The flips done together share no vertex, not merely no face: each gain is computed
    as if its flip were alone, and two flips at one vertex could both take an edge from
    it (leaving fewer than 3), or both create the same new edge ``c-d``.
    """
    n = len(vertices)
    if uses is None:
        uses = _EdgeUses.of(faces, n)
    inner = uses.inner                                                 # (I,) slots of interior edges
    h1, h2 = uses.first[inner], uses.second[inner]
    # Corner h of the flat face array is corner h % 3 of face h // 3; the face's next
    # corner is h + 1 and its previous h - 1, wrapping around within the face.
    flat = faces.reshape(-1)
    a, b = np.take(flat, h1), np.take(flat, h1 + np.where(h1 % 3 == 2, -2, 1))
    c, d = np.take(flat, h1 + np.where(h1 % 3 == 0, 2, -1)), np.take(flat, h2 + np.where(h2 % 3 == 0, 2, -1))

    degree, boundary_vertex = uses.degree, uses.boundary_vertex
    ideal = np.where(boundary_vertex, 4, 6)
    # What each vertex gains (in |degree - ideal|) by losing an edge, and by gaining one:
    # per vertex first, so each edge's gain is four look-ups.
    deviation = np.abs(degree - ideal)
    gain_by_losing = deviation - np.abs(degree - 1 - ideal)
    gain_by_gaining = deviation - np.abs(degree + 1 - ideal)
    gain = gain_by_losing[a] + gain_by_losing[b] + gain_by_gaining[c] + gain_by_gaining[d]
    ok = (gain > 0) & (degree[a] > 3) & (degree[b] > 3) & (c != d)
    if features is not None:
        # Never flip a line's edge, and never make an edge across from one line to
        # another: both its ends would be held on lines, where smoothing cannot even it out.
        # (Flips never make a feature edge, so the slots of the start's feature edges stay theirs.)
        on_line = features.counts() > 0
        ok &= ~features.edge_mask(uses.start_keys)[inner] & ~(on_line[c] & on_line[d])
    # The new edge c-d must not exist already (looked up only for the flips still wanted).
    wanted = np.flatnonzero(ok)
    ok[wanted[uses.contains(np.minimum(c[wanted], d[wanted]) * n + np.maximum(c[wanted], d[wanted]))]] = False

    # Geometry: no flip across a crease, and the new triangles may not fold over.
    which = np.flatnonzero(ok)
    pa, pb, pc, pd = (vertices[x[which]] for x in (a, b, c, d))
    n1, n2 = cross_rows(pb - pa, pc - pa), cross_rows(pa - pb, pd - pb)
    m1, m2 = cross_rows(pa - pc, pd - pc), cross_rows(pb - pd, pc - pd)
    u1, u2, w1, w2 = _unit(n1), _unit(n2), _unit(m1), _unit(m2)
    average = u1 + u2
    flat_enough = np.einsum("ij,ij->i", u1, u2) >= max_crease_cos
    unfolded = (np.einsum("ij,ij->i", w1, average) > 0) & (np.einsum("ij,ij->i", w2, average) > 0) \
        & (np.einsum("ij,ij->i", w1, w2) > 0)
    scale = np.einsum("ij,ij->i", n1, n1) + np.einsum("ij,ij->i", n2, n2)
    not_flat = (np.einsum("ij,ij->i", m1, m1) > 1e-16 * scale) & (np.einsum("ij,ij->i", m2, m2) > 1e-16 * scale)
    ok[which[~(flat_enough & unfolded & not_flat)]] = False

    # In the edges' key order, as a freshly sorted table lists them: the random numbers
    # below go to the same edges as they would without the slots.
    candidates = np.flatnonzero(ok)                                    # (k,) into inner
    candidates = candidates[uses.key_order(inner[candidates])]
    if len(candidates) == 0:
        return faces, 0, uses
    # Biggest gain first, ties in a random (seeded) order.
    candidates = candidates[np.lexsort((rng.random(len(candidates)), -gain[candidates]))]
    quads = np.stack([a[candidates], b[candidates], c[candidates], d[candidates]], axis=1)   # (k, 4)
    priority = np.arange(len(candidates), dtype=np.int64)
    chosen = np.zeros(len(candidates), dtype=bool)
    open_ = np.ones(len(candidates), dtype=bool)
    used = np.zeros(n, dtype=bool)
    big = np.iinfo(np.int64).max
    for _ in range(selection_passes):
        open_ &= ~used[quads].any(axis=1)
        if not open_.any():
            break
        lowest = np.full(n, big)
        np.minimum.at(lowest, quads[open_].reshape(-1), np.repeat(priority[open_], 4))
        picked = open_ & (lowest[quads] == priority[:, None]).all(axis=1)
        chosen |= picked
        open_ &= ~picked
        used[quads[picked].reshape(-1)] = True
    take = candidates[chosen]
    if not in_place:
        faces = faces.copy()
    faces[h1[take] // 3] = np.stack([c[take], a[take], d[take]], axis=1)
    faces[h2[take] // 3] = np.stack([d[take], b[take], c[take]], axis=1)
    uses.flip(a[take], b[take], c[take], d[take], h1[take], h2[take])
    return faces, len(take), uses
