"""Isotropic remeshing (Botsch and Kobbelt, 2004): make every edge about ``L`` long.

Each iteration runs four phases, then puts the vertices back on the input surface:

1. **Split** every edge longer than ``4/3 L`` at its midpoint.
2. **Collapse** every edge shorter than ``4/5 L`` to its midpoint (or, failing that,
   to one of its ends), unless that would create an edge longer than ``4/3 L``.
3. **Flip** edges where that brings the degrees of the four vertices involved closer
   to 6 (4 on the boundary), the degree of a vertex in a regular triangle grid.
4. **Smooth tangentially**: compute the centroid of every vertex's neighbours first
   (all of them, from the old positions), then move each vertex towards its centroid
   *only in its tangent plane*, so the vertices spread out evenly without the surface
   shrinking. Boundary vertices stay put.
5. **Project** every vertex back onto the input surface (boundary vertices onto the
   input's boundary polyline): splitting at chord midpoints and smoothing in a plane
   both step a little off a curved surface. A vertex that lands within
   ``SNAP_TO_INPUT_VERTEX * L`` of an input vertex goes onto it: the input's vertices
   are the points where its surface was measured (a scan) or modelled, and a triangle
   resting on them follows it more closely than one whose corners lie between them.

**Features** (``feature_angle``, :mod:`.features`): creases sharper than the angle, and
the boundary, are feature lines, found once on the input and carried through every
phase. A feature edge is split into two feature edges, collapses only along its line
(never across from one line to another, never removing a corner), and is never
flipped; in phase 4 a vertex on a line moves only along it, on its own two edges
(corners not at all), and in phase 5 it goes back onto its own line of the input.
With ``feature_angle=None`` only the boundary is kept, as described above.

Why 4/3 and 4/5: splitting an edge of length ``l`` leaves two of ``l/2``, which are
nearer to L than ``l`` was exactly when ``l > 4/3 L``; 4/5 is Botsch and Kobbelt's
matching bound below L. The "no new edge longer than 4/3 L" rule keeps a collapse from
making work for the next split, so the two phases never undo each other.

The course's version does each phase one edge at a time. This version does every phase
on whole face arrays, with numpy:

* the split handles all long edges at once: each triangle with 1, 2 or 3 split edges
  is cut by a fixed template (one 2-to-1 cut, a corner plus a quad, or 4 triangles),
  the way "red-green" refinement does it, and the pass repeats until nothing is long;
* the collapses run in *rounds*, as ``simplify``'s do (:mod:`.collapse_rounds`): each
  round checks every short edge (link condition, boundary rules, degrees, the 4/3 L
  rule, no face turned over) and collapses a set of them far enough apart to be done
  together, preferring shorter edges by class of length (a fixed shuffle inside a
  class, so that a round finds many edges to take where lengths change smoothly).
  After the first round, a round looks only at the faces within two rings of the
  short edges still worth trying: nothing farther away can change its choice;
* the flips run in passes: every interior edge's degree gain is computed at once, and
  a set of improving flips that share no vertex is flipped together. The edge list is
  sorted once per phase and then updated in place by each pass (a flip changes five
  edges, found through the slot each directed edge names, without a search).

:func:`remesh` returns the result; :func:`remesh_step_by_step` yields the mesh after each
phase, for a stepper, and :func:`remesh_history` lists them all; :func:`quality_report` measures what remeshing is for (edge
lengths, degrees, angles).
"""

from __future__ import annotations

import inspect
import math
from dataclasses import dataclass
from typing import Iterator, NamedTuple

import numpy as np

from ..core.errors import MeshInputError
from ..core.mesh import HalfedgeMesh
from ._progress import progress_range
from ..core.arrays import EdgeTable, compact, cross_rows, edge_table, expand, key_ends, vertex_faces
from .arguments import check_mesh, check_remesh, real_number, whole_number
from .collapse_rounds import (COST_CLASSES, choose_round, collapse_topology_ok, no_turned_faces, round_tables,
                              spread_ties_keys)
from .features import DEFAULT_FEATURE_ANGLE, Features, feature_arrays
from .normals import area_weighted_vertex_normals

#: Split edges longer than this times L; collapse edges shorter than ``COLLAPSE_BELOW * L``.
SPLIT_ABOVE = 4.0 / 3.0
COLLAPSE_BELOW = 4.0 / 5.0
#: How often each phase may repeat within one iteration (each pass is one array operation).
MAX_SPLIT_PASSES = 10
MAX_COLLAPSE_ROUNDS = 30
MAX_FLIP_PASSES = 10
#: Flip passes stop once a pass flips at most this fraction of the faces' count: the
#: last few flips (a handful of edges each pass) are left to the next iteration.
MIN_FLIP_FRACTION = 0.001
#: Collapse rounds stop early once a round collapses at most this fraction of the faces'
#: count: the last few short edges are then left to the next iteration, where smoothing
#: has given them room, instead of paying a whole round each.
MIN_COLLAPSE_FRACTION = 0.0005
#: They also stop once a round collapses at most this share of the busiest round so far.
#: What is left then are chains, where one collapse makes the next possible: collapsing a
#: vertex of degree 4 into its neighbour takes an edge from the vertex opposite, which
#: then has degree 4 and short edges itself. A chain moves one edge per round, along a
#: whole ring on a torus: on a 10k-face torus 6-8 chains ran until the cap of 30 rounds.
#: The next iteration takes up what is left, after the flips have raised those degrees.
MIN_COLLAPSE_SHARE = 0.1
#: A collapse may not swing any face normal by more than this (degrees).
MAX_COLLAPSE_NORMAL_ANGLE = 30.0
#: An edge whose two faces meet at a sharper angle than this is a crease: never flipped.
MAX_FLIP_DIHEDRAL = 20.0
#: A face counts as flat (no area) when twice its area is at most this times its
#: squared longest edge; the projection never leaves a face flat that was not.
MIN_RELATIVE_AREA = 1e-10
#: The projection puts a vertex (off the lines) onto an input vertex within this times
#: L of the point it found (0 turns it off). On the bunny, a scan, at L = its mean edge
#: length, the mean distance to the input (at the vertices of both) falls from 0.0088 L
#: to 0.0081 L with the full smoothing step and from 0.0073 L to 0.0054 L with half of it,
#: while the edge-length spread grows from 0.136 to 0.140 and from 0.150 to 0.165.
SNAP_TO_INPUT_VERTEX = 0.1

PHASES = ("split", "collapse", "flip", "smooth", "project")


class RemeshStep(NamedTuple):
    """One snapshot of :func:`remesh_step_by_step`: the mesh after ``phase`` of ``iteration``."""

    iteration: int
    phase: str
    mesh: HalfedgeMesh


# ----------------------------------------------------------------------------------------
# Edge lengths (the edge tables themselves come from core.arrays)
# ----------------------------------------------------------------------------------------

def _edge_lengths(vertices: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """(E,) the length of each edge (E, 2). ``np.take`` gathers the rows: the same
    numbers as ``vertices[edges[:, 0]]``, without fancy indexing's general machinery."""
    d = np.take(vertices, edges[:, 0], axis=0) - np.take(vertices, edges[:, 1], axis=0)
    return np.sqrt(np.einsum("ij,ij->i", d, d))


# ----------------------------------------------------------------------------------------
# Phase 1: split
# ----------------------------------------------------------------------------------------

def _split_pass(vertices: np.ndarray, faces: np.ndarray, max_length: float, features: Features | None = None,
                table: EdgeTable | None = None):
    """Split every edge longer than ``max_length`` at its midpoint, all at once.

    Returns ``(vertices, faces, features, n_split)``. Each face is cut by the template
    for its number of split edges; rotating the face first puts the split edges in
    front, so one template per count covers all cases. Orientation is kept. A split
    feature edge leaves two feature halves (``features`` None: none are tracked).
    ``table``: the :func:`~halfedge_edu.core.arrays.edge_table` of ``faces``, if the
    caller has it already.
    """
    n = len(vertices)
    if not _has_long_side(vertices, faces, max_length):            # the usual last pass: no edge table needed
        return vertices, faces, features, 0
    if table is None:
        table = edge_table(faces, n)
    long = _edge_lengths(vertices, table.edges) > max_length
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


def _split_long_edges(vertices, faces, target_length, features: Features | None, table: EdgeTable | None = None):
    """Split passes until no edge is longer than 4/3 L (at most ``MAX_SPLIT_PASSES``).
    ``table``: the edge table of ``faces``, if the caller has it (for the first pass)."""
    for _ in range(MAX_SPLIT_PASSES):
        vertices, faces, features, n_split = _split_pass(vertices, faces, SPLIT_ABOVE * target_length, features,
                                                         table)
        table = None                                                   # the faces have changed
        if n_split == 0:
            break
    return vertices, faces, features


# ----------------------------------------------------------------------------------------
# Phase 2: collapse
# ----------------------------------------------------------------------------------------

def _line_turning(vertices, line_edges: np.ndarray, n: int) -> np.ndarray:
    """(n,) how sharply a line of edges (the boundary, or the feature lines) turns at
    each vertex: ``|u1 + u2|`` for the unit vectors to its two neighbours on the line
    (0 where the line runs straight, up to 2)."""
    d = vertices[line_edges[:, 1]] - vertices[line_edges[:, 0]]
    d /= np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
    total = np.empty((n, 3))
    for axis in range(3):           # sums per vertex: bincount is many times faster than np.add.at
        total[:, axis] = (np.bincount(line_edges[:, 0], weights=d[:, axis], minlength=n)
                          - np.bincount(line_edges[:, 1], weights=d[:, axis], minlength=n))
    return np.linalg.norm(total, axis=1)


#: How many short edges :func:`_collapse_places` measures at a time. Each edge gathers the
#: neighbours of both ends (about 13 points); in blocks of 8192 edges every temporary is a
#: few MiB, where one block for the million short edges of a first round on a 1M-face
#: torus makes hundreds of MiB, which the system maps afresh for every array.
PLACE_CHECK_BLOCK = 8192


def _farthest_from_places(vertices: np.ndarray, neighbours: tuple[np.ndarray, np.ndarray], a: np.ndarray,
                          b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For k edges ``a-b`` (k,): (k,) each, the largest distance to a neighbour of ``a`` or
    ``b`` from the edge's midpoint; to a neighbour of ``b`` from ``a``; to a neighbour of
    ``a`` from ``b``.

    A collapse to that place makes those edges, so this is how long its longest new
    edge would be (from ``a``, the neighbours of ``a`` itself are its own edges, known
    already). Each end's neighbours are gathered once (:func:`expand`, one row after the
    other) for all the places, and the largest per row is one ``np.maximum.reduceat``
    at the rows' starts (every end of an edge has a neighbour, so no row is empty).
    """
    offsets, _ = neighbours
    midpoint = 0.5 * (np.take(vertices, a, axis=0) + np.take(vertices, b, axis=0))   # (k, 3)
    measured = []
    for end, other in ((a, b), (b, a)):
        counts = offsets[end + 1] - offsets[end]
        starts = np.cumsum(counts) - counts
        owner, around = expand(*neighbours, end)
        at = np.take(vertices, around, axis=0)                          # (r, 3) the neighbours of every end

        def farthest_from(places: np.ndarray) -> np.ndarray:
            """(k,) the largest distance from ``places[i]`` (k, 3) to a neighbour of ``end[i]``."""
            gap = at - np.take(places, owner, axis=0)
            return np.sqrt(np.maximum.reduceat(np.einsum("ij,ij->i", gap, gap), starts))

        measured.append((farthest_from(midpoint), farthest_from(np.take(vertices, other, axis=0))))
    (a_from_midpoint, a_from_b), (b_from_midpoint, b_from_a) = measured
    return np.maximum(a_from_midpoint, b_from_midpoint), b_from_a, a_from_b


def _collapse_places(vertices: np.ndarray, neighbours: tuple[np.ndarray, np.ndarray], reach: np.ndarray,
                     a: np.ndarray, b: np.ndarray, first: np.ndarray, span: np.ndarray, allowed: np.ndarray,
                     limit: float) -> np.ndarray:
    """(k,) where each of k edges ``a-b`` may collapse: 0 to its midpoint, 1 to its end
    ``first`` (``a`` or ``b``), 2 to its other end, -1 nowhere. Each edge takes the first
    place ``allowed`` (k, 3 in that order) that makes no edge longer than ``limit``.

    ``reach`` (n,) is the longest edge at each vertex, ``span`` (k,) each edge's length.
    A neighbour q of an end x is at most ``reach[x] + |x - place|`` from a place
    (triangle inequality): where that bound already fits for an edge's first allowed
    place, that place is taken without gathering any neighbours (about half the short
    edges of the first round on subdivided Spot). The others are measured,
    :data:`PLACE_CHECK_BLOCK` at a time.
    """
    second_reach = np.where(first == a, reach[b], reach[a])
    bound = np.stack([np.maximum(reach[a], reach[b]) + 0.5 * span,          # (k, 3) midpoint, first, second
                      np.maximum(reach[first], second_reach + span),
                      np.maximum(second_reach, reach[first] + span)], axis=1)
    # The bound is computed with rounding too: a margin of 1e-9 keeps "surely fits" true
    # of the exact measure, so the choice is the same as measuring every edge.
    fits = bound <= limit * (1.0 - 1e-9)
    preferred = np.argmax(allowed, axis=1)                                   # (k,) the first allowed place
    rows = np.arange(len(a))
    unsure = np.flatnonzero(allowed[rows, preferred] & ~fits[rows, preferred])
    for start in range(0, len(unsure), PLACE_CHECK_BLOCK):
        block = unsure[start:start + PLACE_CHECK_BLOCK]
        ea, eb = a[block], b[block]
        from_midpoint, from_a, from_b = _farthest_from_places(vertices, neighbours, ea, eb)
        # Kept at one end, the longest edge is that end's own longest or one from it to
        # a neighbour of the other end.
        at_a, at_b = np.maximum(reach[ea], from_a), np.maximum(reach[eb], from_b)
        a_first = first[block] == ea
        fits[block] = np.stack([from_midpoint, np.where(a_first, at_a, at_b), np.where(a_first, at_b, at_a)],
                               axis=1) <= limit
    possible = allowed & fits
    return np.where(possible.any(axis=1), np.argmax(possible, axis=1), -1)


def _longest_edge_at(n: int, edges: np.ndarray, length: np.ndarray) -> np.ndarray:
    """(n,) the length of the longest of the ``edges`` (E, 2) at each vertex (0 if none),
    given their ``length`` (E,)."""
    reach = np.zeros(n)
    np.maximum.at(reach, edges[:, 0], length)
    np.maximum.at(reach, edges[:, 1], length)
    return reach


class _Refused:
    """Short edges refused in earlier rounds, so later rounds can skip them.

    Whether an edge ``a-b`` may collapse depends only on ``a``, ``b``, their neighbours
    and the faces around them. A round changes that only for ``dirty`` vertices: the
    merged ones and their neighbours. So an edge refused before, with neither end dirty
    since, would be refused again. ``keys`` are ``low * n + high``, sorted.
    """

    def __init__(self, n: int):
        self.keys = np.empty(0, dtype=np.int64)
        self.dirty = np.zeros(n, dtype=bool)
        self.gone = np.zeros(n, dtype=bool)            # merged into another vertex

    def still_refused(self, keys: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        if len(self.keys) == 0:
            return np.zeros(len(keys), dtype=bool)
        at = np.minimum(np.searchsorted(self.keys, keys), len(self.keys) - 1)
        return (self.keys[at] == keys) & ~self.dirty[a] & ~self.dirty[b]

    def update(self, keys: np.ndarray, region_keys: np.ndarray | None, merged: np.ndarray,
               neighbours: tuple[np.ndarray, np.ndarray]) -> None:
        """Remember ``keys`` (distinct) as refused; mark the ``merged`` vertices (both ends
        of every collapse) and their neighbours before the merge (``neighbours``, CSR) dirty.

        ``region_keys`` (sorted): the edges the round looked at (None: all of them). A
        refused edge outside them was not looked at again, so it stays refused, unless
        an earlier round's merge removed one of its ends (the edge is gone).
        """
        if region_keys is not None and len(self.keys) and len(region_keys):
            at = np.minimum(np.searchsorted(region_keys, self.keys), len(region_keys) - 1)
            n = len(self.dirty)
            outside = (region_keys[at] != self.keys) & ~self.gone[self.keys // n] & ~self.gone[self.keys % n]
            keys = np.concatenate([self.keys[outside], keys])
        self.keys = np.sort(keys)
        self.dirty[:] = False
        self.dirty[merged] = True
        self.dirty[expand(*neighbours, merged)[1]] = True


#: A round ranks its short edges by length only between this many classes of equal width
#: over [0, 4/5 L), shortest class first; inside a class, in a fixed shuffle (see
#: :func:`_collapse_order`), as ``simplify`` ranks by cost.
COLLAPSE_LENGTH_CLASSES = COST_CLASSES


def _collapse_order(length: np.ndarray, keys: np.ndarray, target_length: float) -> np.ndarray:
    """(k,) the order in which a round prefers its k short edges, given their ``length``
    (k,) and ``keys`` (k,) ``low * n + high``: by class of length (:data:`COLLAPSE_LENGTH_CLASSES`
    classes over [0, 4/5 L)), shortest first, and inside a class in a shuffle fixed by the
    keys (:func:`~halfedge_edu.algorithms.collapse_rounds.spread_ties`), the same on
    every run and in a round on part of the mesh as on all of it.

    The order is one sort of one number per edge,
    :func:`~halfedge_edu.algorithms.collapse_rounds.spread_ties_keys` (class, then the top
    bits of the shuffle): a ninth of the time of sorting by two keys (0.04 s against
    0.36 s for a million edges). Those numbers are distinct for keys below 2**30; a
    large mesh's keys are bigger, so where two numbers agree (rare) both keys decide.

    Why not strictly shortest first: a round takes an edge only where it comes first
    among the short edges within one ring of its ends (see
    :func:`~halfedge_edu.algorithms.collapse_rounds.choose_round`). Where lengths change
    smoothly, few edges are first in their neighbourhood: on a torus the edge lengths
    rise ring by ring across the tube, so strict order let each round take little more
    than the shortest ring left, and the rounds grew with the mesh (7 at 10k faces, 16
    at 100k, 24 at 1M, the cap of 30 at 5M). Edges of about the same length are about
    as good to collapse first, and a shuffle among them makes first places as common as
    random ones do: 8, 7 and 8 rounds at 100k, 1M and 5M faces.
    """
    width = COLLAPSE_BELOW * target_length / COLLAPSE_LENGTH_CLASSES
    # Clipped: a length just under 4/5 L may round up to the class past the last.
    length_class = np.minimum((length / width).astype(np.int64), COLLAPSE_LENGTH_CLASSES - 1)
    priority = spread_ties_keys(length_class, keys)                    # (k,) int64, lowest first
    order = np.argsort(priority)
    in_order = priority[order]
    if (in_order[1:] == in_order[:-1]).any():
        order = np.lexsort((keys, priority))
    return order


def _collapse_round(vertices, faces, region: np.ndarray | None, target_length, max_normal_cos, refused: _Refused,
                    features: Features | None):
    """One round of collapses of short edges among ``faces[region]`` (None: all faces).

    Returns ``(faces, features, n_collapsed, live)``; ``vertices`` (n, 3) is moved in
    place. ``live`` (n,) marks the ends of the short edges that the next round will try
    (:func:`_short_edge_ends`). The region must hold every face within two rings of the
    ends of the short edges that are not refused (:func:`_faces_near`): the checks of an
    edge read its ends' faces and neighbours, and their neighbours' faces; a round on
    that region chooses exactly what a round on the whole mesh would.

    The *lines* are the boundary, and with ``features`` the feature lines too (the
    boundary is one of them). Where a collapse may put the merged vertex, in order of
    preference:

    * an edge between two vertices off the lines: its midpoint, else either end;
    * an edge with one end on a line: that end (the line stays where it is);
    * an edge along a line: the end where the line turns more (a corner stays), else
      the other end; never removing a corner of ``features``.

    An edge that is not on a line but joins two vertices on lines is never collapsed:
    it would pull a line across the surface. The first place that leaves no edge
    longer than 4/3 L is taken; an edge with none is not collapsed this time.
    """
    n = len(vertices)
    whole = faces
    if region is not None:
        faces = faces[region]
    tables = round_tables(faces, n)
    edges, boundary_edge, neighbours = tables.edges, tables.boundary, tables.neighbours
    keys = edges[:, 0] * np.int64(n) + edges[:, 1]                     # (E,) ascending
    boundary_vertex = np.zeros(n, dtype=bool)
    boundary_vertex[edges[boundary_edge].reshape(-1)] = True
    if features is None:
        line_edge, on_line, corner = boundary_edge, boundary_vertex, np.zeros(n, dtype=bool)
    else:
        line_edge, on_line, corner = features.edge_mask(keys), features.counts() > 0, features.corners
    length = _edge_lengths(vertices, edges)
    short = np.flatnonzero(length < COLLAPSE_BELOW * target_length)
    stale = refused.still_refused(keys[short], edges[short, 0], edges[short, 1])
    candidates = short[~stale]
    if len(candidates) == 0:
        return whole, features, 0, np.zeros(n, dtype=bool)
    candidates = candidates[_collapse_order(length[candidates], keys[candidates], target_length)]
    a, b = edges[candidates, 0], edges[candidates, 1]
    along = line_edge[candidates]
    free = ~on_line[a] & ~on_line[b]
    # Name the ends so that ``first`` is the preferred end to keep: the one on a line,
    # along a line a corner, else the one where the line turns more.
    swap = on_line[b] & ~on_line[a]
    if along.any():
        turning = _line_turning(vertices, edges[line_edge], n)
        swap |= along & ((corner[b] & ~corner[a]) | ((corner[b] == corner[a]) & (turning[b] > turning[a])))
    first, second = np.where(swap, b, a), np.where(swap, a, b)

    # Never across from one line to another (or to the same one further on), nor between two corners.
    valid = ~(on_line[a] & on_line[b] & ~along) & ~(corner[a] & corner[b])

    # The places in order of preference: the midpoint (between two vertices off the
    # lines), the end ``first`` (always allowed), the end ``second``. The first allowed
    # one that makes no edge longer than 4/3 L wins.
    allowed = np.stack([free, np.ones(len(candidates), dtype=bool), free | (along & ~corner[first])], axis=1)
    choice = _collapse_places(vertices, neighbours, _longest_edge_at(n, edges, length), a, b, first,
                              length[candidates], allowed & valid[:, None], SPLIT_ABOVE * target_length)
    valid &= choice >= 0
    keep, remove = np.where(choice == 2, second, first), np.where(choice == 2, first, second)
    points = np.where((choice == 0)[:, None], 0.5 * (vertices[a] + vertices[b]), vertices[keep])   # (k, 3)
    # The topology last: its sort costs more per edge than the places, and most short
    # edges have no place that fits.
    placed = np.flatnonzero(valid)
    degree = np.diff(neighbours[0])                                    # (n,) each row lists every neighbour once
    ok, opposite_owner, opposite_vertex = collapse_topology_ok(
        n, edges[candidates[placed]], boundary_edge[candidates[placed]], boundary_vertex, degree, neighbours
    )
    valid[placed[~ok]] = False
    opposite_owner = placed[opposite_owner]                            # into candidates
    turned = np.zeros(len(candidates), dtype=bool)

    def check_turned_faces(indices: np.ndarray) -> np.ndarray:
        ok = no_turned_faces(vertices, faces, tables.faces_around, points[indices], keep[indices],
                             remove[indices], max_normal_cos, face_across=tables.face_across)
        turned[indices[~ok]] = True
        return ok

    def check_topology(indices: np.ndarray):
        # Checked above for every candidate (the placement needed it); hand back the picked.
        picked = np.zeros(len(candidates), dtype=bool)
        picked[indices] = True
        mine = picked[opposite_owner]
        return valid[indices], opposite_owner[mine], opposite_vertex[mine]

    if valid.any():
        chosen = choose_round(edges, candidates, valid, n, check_topology, check_turned_faces,
                              known_opposites=(opposite_owner, opposite_vertex), neighbours=neighbours)
    else:
        chosen = np.zeros(len(candidates), dtype=bool)
    refused_keys = np.concatenate([keys[short[stale]], keys[candidates[~valid | turned]]])
    refused.update(refused_keys, None if region is None else keys, np.concatenate([keep[chosen], remove[chosen]]),
                   neighbours)
    relabel = np.arange(n)
    if chosen.any():
        vertices[keep[chosen]] = points[chosen]
        refused.gone[remove[chosen]] = True
        relabel[remove[chosen]] = keep[chosen]
        faces = relabel[faces]                          # only faces of the region hold a removed vertex
        degenerate = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
        if region is None:
            whole = faces[~degenerate]
        else:
            whole = whole.copy()
            whole[region] = faces
            whole = np.delete(whole, region[degenerate], axis=0)     # the other faces keep their order
        if features is not None:
            features = features.merge(remove[chosen], keep[chosen])
    live = _short_edge_ends(vertices, relabel[edges], target_length, refused)
    return whole, features, int(chosen.sum()), live


def _short_edge_ends(vertices, edges: np.ndarray, target_length, refused: _Refused) -> np.ndarray:
    """(n,) True at the ends of the ``edges`` (E, 2) (a round's region, after its
    collapses: collapsed edges have two equal ends, merged ones come twice) that are
    short and not refused: the next round's candidates.

    None lie outside the region: a short edge elsewhere was either refused and kept
    its ends (still refused) or was a candidate, whose ends lie in the region.
    """
    a, b = edges[:, 0], edges[:, 1]
    side = np.take(vertices, a, axis=0) - np.take(vertices, b, axis=0)
    limit = COLLAPSE_BELOW * target_length
    short = np.flatnonzero((np.einsum("ij,ij->i", side, side) < limit * limit) & (a != b))
    a, b = a[short], b[short]
    trying = ~refused.still_refused(np.minimum(a, b) * np.int64(len(vertices)) + np.maximum(a, b), a, b)
    live = np.zeros(len(vertices), dtype=bool)
    live[a[trying]] = True
    live[b[trying]] = True
    return live


def _faces_near(faces: np.ndarray, marked: np.ndarray) -> np.ndarray:
    """Indices of the faces within two rings of the ``marked`` (n,) vertices: those
    with a corner at a marked vertex or at a neighbour of one."""
    columns = [faces[:, k] for k in range(3)]
    at_marked = marked[columns[0]] | marked[columns[1]] | marked[columns[2]]
    near = marked.copy()
    near[faces[at_marked].reshape(-1)] = True                          # the marked vertices and their neighbours
    return np.flatnonzero(near[columns[0]] | near[columns[1]] | near[columns[2]])


def _collapse_short_edges(vertices, faces, target_length, features: Features | None = None):
    """Collapse rounds until (almost) no short edge can go (at most ``MAX_COLLAPSE_ROUNDS``).

    The rounds stop early once one collapses little: at most :data:`MIN_COLLAPSE_FRACTION`
    of the faces' count, or at most :data:`MIN_COLLAPSE_SHARE` of the busiest round's.

    Returns ``(vertices, faces, features)``, compacted (unused vertices dropped)."""
    max_normal_cos = math.cos(math.radians(MAX_COLLAPSE_NORMAL_ANGLE))
    refused = _Refused(len(vertices))
    vertices = vertices.copy()                      # the rounds move vertices in place
    region = None                                   # the first round looks at every face
    busiest = 0                                     # the most collapses one round has made
    for _ in range(MAX_COLLAPSE_ROUNDS):
        faces, features, n_collapsed, live = _collapse_round(
            vertices, faces, region, target_length, max_normal_cos, refused, features)
        busiest = max(busiest, n_collapsed)
        if (n_collapsed <= MIN_COLLAPSE_FRACTION * len(faces) or n_collapsed <= MIN_COLLAPSE_SHARE * busiest
                or not live.any()):
            break
        region = _faces_near(faces, live)
    vertices, faces, kept = compact(vertices, faces)
    if features is not None:
        features = features.renumber(kept)
    return vertices, faces, features


# ----------------------------------------------------------------------------------------
# Phase 3: flip
# ----------------------------------------------------------------------------------------

def _unit(vectors: np.ndarray) -> np.ndarray:
    return vectors / np.maximum(np.linalg.norm(vectors, axis=1), 1e-300)[:, None]


class _EdgeUses:
    """The edges of a face array, each with the directed edges that use it, kept up to
    date through a flip phase without sorting or searching the whole edge list again.

    Each edge has a *slot*, its place in key order when the phase began (``of``). A flip
    keeps its edge's slot and only changes what is in it (the new key ``c-d`` and its two
    directed edges), and ``corner_edge`` names the slot of every directed edge, so a
    flip finds the slots of its edge and of the four edges around it by looking them up
    there (one read each) instead of searching the sorted keys for them (a random walk
    through all E keys per look-up: at 5M faces that grew faster than the mesh). The
    slots stay in key order except the flipped ones; :meth:`table` puts them back in
    order once, at the end of the phase, by merging the few flipped edges in.

    ``keys`` (E,) ``low * n + high`` of the edge in each slot (ascending at the start,
    flipped slots changed since); ``first``/``second`` (E,) the directed edges ``3 f + k``
    using it (``second`` -1 on the boundary); ``corner_edge`` (3m,) the slot of each
    directed edge; ``start_keys`` (E,) the keys at the start, ascending; ``flipped``
    (E,) the slots flipped since; ``inner`` the slots of interior edges (flips keep
    them interior); ``degree`` (n,) how many edges each vertex has; ``boundary_vertex``
    (n,) the vertices on a boundary edge (flips do not change them); ``n`` the number
    of vertices.
    """

    def __init__(self, keys: np.ndarray, first: np.ndarray, second: np.ndarray, corner_edge: np.ndarray, n: int):
        """From an :class:`~halfedge_edu.core.arrays.EdgeTable`'s arrays, which it takes
        over: ``first``, ``second`` and ``corner_edge`` change in place from now on
        (``keys`` is copied: the sorted keys of the start are kept for look-ups)."""
        self.n = n
        self.keys, self.first, self.second = keys.copy(), first, second
        self.corner_edge = corner_edge.reshape(-1)                     # (3m,)
        self.start_keys = keys
        self.flipped = np.zeros(len(keys), dtype=bool)
        self.inner = np.flatnonzero(second >= 0)
        self.degree = np.bincount(keys // n, minlength=n) + np.bincount(keys % n, minlength=n)
        boundary_edge = keys[second < 0]
        self.boundary_vertex = np.zeros(n, dtype=bool)
        self.boundary_vertex[boundary_edge // n] = True
        self.boundary_vertex[boundary_edge % n] = True

    @classmethod
    def of(cls, faces: np.ndarray, n: int) -> "_EdgeUses":
        table = edge_table(faces, n)
        return cls(table.keys, table.first, table.second, table.corner_edge, n)

    def key_order(self, slots: np.ndarray) -> np.ndarray:
        """(k,) the order that lists the ``slots`` (k,), ascending, by key: the order a
        fresh sorted table would list them in (only flipped slots can be out of order)."""
        if not self.flipped.any():
            return np.arange(len(slots))
        return np.argsort(self.keys[slots])

    def contains(self, keys: np.ndarray) -> np.ndarray:
        """(k,) whether each of ``keys`` is an edge now: a key of the start not flipped
        away, or the key a flip put into a slot."""
        at = np.minimum(np.searchsorted(self.start_keys, keys), len(self.start_keys) - 1)
        found = (self.start_keys[at] == keys) & ~self.flipped[at]
        moved = np.sort(self.keys[self.flipped])                       # (j,) the keys flips made
        if len(moved):
            at = np.minimum(np.searchsorted(moved, keys), len(moved) - 1)
            found |= moved[at] == keys
        return found

    def table(self) -> EdgeTable:
        """The :class:`~halfedge_edu.core.arrays.EdgeTable` of the faces these uses are of,
        edges in key order as :func:`~halfedge_edu.core.arrays.edge_table` lists them:
        smoothing and projection after the flips ask for it.

        The slots never flipped are still in key order; the flipped ones (sorted among
        themselves) are merged in where ``searchsorted`` puts them, in one pass over E.
        """
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
        keys, first, second = self.keys[order], self.first[order], self.second[order]
        count = np.where(second >= 0, 2, 1)
        corner_edge = place[self.corner_edge].reshape(-1, 3)
        return EdgeTable(key_ends(keys, self.n), corner_edge, count, first, second, keys)

    def flip(self, a, b, c, d, h1, h2) -> None:
        """Record flips of edges ``a-b`` (directed edge ``h1`` in face ``[a, b, c]``, ``h2``
        in ``[b, a, d]``) into ``c-d``, the faces becoming ``[c, a, d]`` and ``[d, b, c]``
        (see :func:`_flip_pass`; the flips share no vertex, so no slot is touched twice).

        The four edges around each flipped one keep their slot and key but are used by
        other directed edges: the ones of the new faces at the same place.
        """
        f1, f2 = 3 * (h1 // 3), 3 * (h2 // 3)                          # each face's first directed edge
        after = lambda h: h + np.where(h % 3 == 2, -2, 1)              # noqa: E731  next in the face
        before = lambda h: h + np.where(h % 3 == 0, 2, -1)             # noqa: E731  previous in the face
        slot = self.corner_edge[h1]                                    # (k,) the flipped edges
        # The edges c-a, a-d, d-b and b-c: their directed edge before the flip, and after.
        around = [(before(h1), f1), (after(h2), f1 + 1), (before(h2), f2), (after(h1), f2 + 1)]
        slots = [self.corner_edge[old] for old, _ in around]           # read all before writing any
        for (old, new), at in zip(around, slots):
            was_first = self.first[at] == old
            self.first[at[was_first]] = new[was_first]
            self.second[at[~was_first]] = new[~was_first]
            self.corner_edge[new] = at
        self.keys[slot] = np.minimum(c, d) * self.n + np.maximum(c, d)
        self.first[slot], self.second[slot] = f1 + 2, f2 + 2           # d -> c in [c, a, d], c -> d in [d, b, c]
        self.corner_edge[f1 + 2] = slot
        self.corner_edge[f2 + 2] = slot
        self.flipped[slot] = True
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


def _flip_to_regular_degrees(vertices, faces, rng, features: Features | None) -> tuple[np.ndarray, EdgeTable]:
    """Flip passes until few flips are left (at most ``MAX_FLIP_PASSES``). Returns ``(faces,
    their edge table)``: the table comes from the uses the passes kept up to date."""
    max_crease_cos = math.cos(math.radians(MAX_FLIP_DIHEDRAL))
    uses = _EdgeUses.of(faces, len(vertices))
    faces = faces.copy()                                               # the passes flip in this copy
    for _ in range(MAX_FLIP_PASSES):
        faces, n_flipped, uses = _flip_pass(vertices, faces, rng, max_crease_cos, features, uses=uses,
                                            in_place=True)
        if n_flipped <= MIN_FLIP_FRACTION * len(faces):
            break
    return faces, uses.table()


# ----------------------------------------------------------------------------------------
# Phase 4: tangential smoothing
# ----------------------------------------------------------------------------------------

def tangential_smoothing(vertices: np.ndarray, faces: np.ndarray, features: Features | None = None,
                         fraction: float = 1.0, *, table: EdgeTable | None = None) -> np.ndarray:
    """Move every interior vertex to its neighbours' centroid, in its tangent plane only.

    Without ``features`` the boundary vertices stay. With them, vertices on a feature
    line (the boundary is one) move only along it: towards the midpoint of their two
    neighbours on the line, along the direction from one to the other (smoothing in 1D);
    corners stay. ``fraction``: how much of each step is taken (1: all the way).
    ``table``: the :func:`~halfedge_edu.core.arrays.edge_table` of ``faces``, if the
    caller has it already.
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


# ----------------------------------------------------------------------------------------
# Phase 5: projection onto the input
# ----------------------------------------------------------------------------------------

def _triangle_coordinates(d1: np.ndarray, d2: np.ndarray, ab_ab: np.ndarray, ab_ac: np.ndarray,
                          ac_ac: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(s, t)``, each like ``d1``: the point of triangle ``a, b, c`` nearest to a point
    ``p`` is ``a + s (b - a) + t (c - a)``.

    Ericson's method (Real-Time Collision Detection, 5.1.5): find which of the seven
    regions (3 corners, 3 edges, the inside) ``p`` projects into, from six dot products.
    All six follow from two, ``d1 = (b - a).(p - a)`` and ``d2 = (c - a).(p - a)``, and
    the triangle's own three (``ab_ab = (b - a).(b - a)``, ``ab_ac``, ``ac_ac``), which a
    caller asking about the same triangles again and again computes once.
    """
    d3, d4, d5, d6 = d1 - ab_ab, d2 - ab_ac, d1 - ab_ac, d2 - ac_ac    # (b-a).(p-b), (c-a).(p-b), ... (p-c)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    safe = lambda x: np.where(np.abs(x) > 1e-300, x, 1e-300)  # noqa: E731
    with np.errstate(over="ignore", invalid="ignore"):      # formulas of the regions a row is not in
        on_bc = (d4 - d3) / safe((d4 - d3) + (d5 - d6))
        inside = safe(va + vb + vc)
        # Where several region tests hold, the one Ericson makes first wins: np.select
        # takes the first true condition, so they come in his order.
        regions = [(d1 <= 0) & (d2 <= 0), (d3 >= 0) & (d4 <= d3), (vc <= 0) & (d1 >= 0) & (d3 <= 0),
                   (d6 >= 0) & (d5 <= d6), (vb <= 0) & (d2 >= 0) & (d6 <= 0),
                   (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)]
        #            corner a, corner b, edge ab,              corner c, edge ac,            edge bc
        s = np.select(regions, [0.0, 1.0, d1 / safe(d1 - d3), 0.0, 0.0, 1.0 - on_bc], vb / inside)
        t = np.select(regions, [0.0, 0.0, 0.0, 1.0, d2 / safe(d2 - d6), on_bc], vc / inside)
    return s, t


def closest_points_on_triangles(points: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """(k, 3) the point of triangle ``(a[i], b[i], c[i])`` nearest to ``points[i]``.

    Ericson's method (Real-Time Collision Detection, 5.1.5), all rows at once: see
    :func:`_triangle_coordinates`.
    """
    dot = lambda u, v: np.einsum("ij,ij->i", u, v)  # noqa: E731
    ab, ac, ap = b - a, c - a, points - a
    s, t = _triangle_coordinates(dot(ab, ap), dot(ac, ap), dot(ab, ab), dot(ab, ac), dot(ac, ac))
    return a + ab * s[:, None] + ac * t[:, None]


def closest_points_on_segments(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(k, 3) the point of segment ``a[i] b[i]`` nearest to ``points[i]``."""
    ab = b - a
    t = np.einsum("ij,ij->i", points - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    return a + ab * np.clip(t, 0.0, 1.0)[:, None]


class _Surface:
    """The input surface, ready for "nearest point" queries (a k-d tree of centroids, the
    triangles across each triangle's edges and around each vertex), with its boundary
    polyline and, given ``features``, its feature lines (the boundary among them), each
    line apart."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray, features: Features | None = None):
        from scipy.spatial import cKDTree

        corners = vertices[faces]                                      # (F, 3, 3)
        self.tree = cKDTree(corners.mean(axis=1))
        # Each triangle as a corner and two sides, with the sides' dot products: what
        # every query of the triangle asks again (see _triangle_coordinates).
        self.origin = corners[:, 0]                                    # (F, 3)
        self.sides = corners[:, 1:] - corners[:, :1]                   # (F, 2, 3) b - a, c - a
        ab, ac = self.sides[:, 0], self.sides[:, 1]
        self.gram = np.stack([np.einsum("ij,ij->i", ab, ab), np.einsum("ij,ij->i", ab, ac),
                              np.einsum("ij,ij->i", ac, ac)], axis=1)  # (F, 3)
        # The same twelve numbers per triangle in one row (a, b - a, c - a, gram): a query
        # gathers one contiguous row per candidate instead of three scattered pieces.
        self.rows = np.concatenate([self.origin, self.sides.reshape(-1, 6), self.gram], axis=1)   # (F, 12)
        self.face_corners = faces
        self.fan_offsets, self.fans = vertex_faces(faces, len(vertices))   # each vertex's triangles, CSR
        self.degree = np.diff(self.fan_offsets)
        # Each triangle and the (up to) three across its edges: the first candidates of a query.
        tables = round_tables(faces, len(vertices))
        across = tables.face_across                                    # (F, 3), -1 on the boundary
        self.around = np.concatenate([np.arange(len(faces))[:, None], across], axis=1)   # (F, 4)
        self.around = np.where(self.around >= 0, self.around, np.arange(len(faces))[:, None])
        segments = tables.edges[tables.boundary]
        self.segments = vertices[segments]                             # (S, 2, 3)
        self.segment_tree = cKDTree(self.segments.mean(axis=1)) if len(segments) else None
        # The input's vertices off its lines (off its boundary, without features): where
        # the projection may put a vertex exactly (see project's snap_radius).
        self.vertices = vertices
        self.rests = np.ones(len(vertices), dtype=bool)                # (n,)
        self.rests[segments.reshape(-1)] = False
        if features is not None:
            self.rests &= features.counts() == 0
        self.line_tree = None
        if features is not None and len(features.edges):
            self.line_segments = vertices[features.edges]              # (C, 2, 3)
            self.line_numbers = features.lines                         # (C,)
            # One tree for all lines, with the line's number as a fourth coordinate, far
            # apart: a query carrying its own line's number finds that line's segments
            # first (any other line is farther than the whole input is wide).
            self.line_spacing = 4.0 * float(np.ptp(vertices, axis=0).max()) + 1.0
            self.line_tree = cKDTree(self._with_line(self.line_segments.mean(axis=1), self.line_numbers))

    def project(self, points: np.ndarray, snap_radius: float = 0.0) -> np.ndarray:
        """Nearest points on the input triangles; with ``snap_radius``, a point found
        within that distance of a corner of its triangle off the lines goes onto that
        corner (:meth:`_rest_on_corners`).

        First among the triangle whose centroid is nearest and the three across its
        edges. Where the point found lies on the rim of its triangle (an edge or a
        corner: about one point in eight), the nearest point may be on a triangle that
        only shares a corner with it, so those points look again among all triangles
        around the corner nearest to the point found. Against a search of every
        triangle, for 2,000 points 0.1 L off Spot and off the bunny: the same point for
        99.4% and 99.7% of them (the first look alone: 91% and 92%), the others within
        0.02 L of it. The point found is on the input surface either way.
        """
        _, nearest = self.tree.query(points)
        found, face, s, t = self._nearest_of(points, self.around[nearest])
        on_rim = (s <= 0.0) | (t <= 0.0) | (s + t >= 1.0)
        rows = np.flatnonzero(on_rim)
        if len(rows):
            weights = np.stack([1.0 - s[rows] - t[rows], s[rows], t[rows]], axis=1)   # (r, 3) of the corners
            corner = self.face_corners[face[rows], np.argmax(weights, axis=1)]
            fan = self.degree[corner]                                  # (r,)
            slot = self.fan_offsets[corner][:, None] + np.arange(int(fan.max())) % fan[:, None]
            found[rows], face[rows] = self._nearest_of(points[rows], self.fans[slot])[:2]
        if snap_radius > 0.0:
            found = self._rest_on_corners(found, face, snap_radius)
        return found

    def _rest_on_corners(self, found: np.ndarray, face: np.ndarray, radius: float) -> np.ndarray:
        """The points ``found`` (P, 3) on the triangles ``face`` (P,), each moved onto the
        nearest corner of its triangle if that corner is off the lines and within
        ``radius``. Where several points are near one corner, only the nearest of them
        goes onto it: two vertices on one point would make a face flat, or make the
        surface touch itself.

        The corners of the point's own triangle stand in for all input vertices: a point
        that near a vertex lies on one of its triangles (no k-d tree query needed).
        """
        corners = self.face_corners[face]                              # (P, 3)
        gap = np.take(self.vertices, corners, axis=0) - found[:, None, :]
        distance = np.einsum("pkj,pkj->pk", gap, gap)                  # (P, 3) squared
        which = np.argmin(distance, axis=1)
        rows = np.arange(len(found))
        corner, distance = corners[rows, which], distance[rows, which]
        close = np.flatnonzero((distance <= radius * radius) & self.rests[corner])
        order = close[np.lexsort((distance[close], corner[close]))]    # by corner, nearest first
        claims = corner[order]
        first = np.ones(len(order), dtype=bool)
        first[1:] = claims[1:] != claims[:-1]
        snapped = found.copy()
        snapped[order[first]] = self.vertices[claims[first]]
        return snapped

    def _nearest_of(self, points: np.ndarray, near: np.ndarray) -> tuple[np.ndarray, ...]:
        """The nearest point to each point on its candidate triangles ``near`` (P, k):
        ``(points (P, 3), their triangles (P,), s (P,), t (P,))``, the point being
        ``a + s ab + t ac`` on its triangle.

        Only two dot products per point and candidate: the squared distance to the
        nearest point is ``|ap|^2 - 2 s d1 - 2 t d2 + s^2 ab.ab + 2 s t ab.ac + t^2
        ac.ac``, all numbers already at hand, so the point itself is built only for the
        winning candidate.
        """
        rows = np.take(self.rows, near, axis=0)                        # (P, k, 12)
        ap = points[:, None, :] - rows[:, :, 0:3]                      # (P, k, 3)
        d1 = np.einsum("pkj,pkj->pk", rows[:, :, 3:6], ap)             # (b - a).(p - a)
        d2 = np.einsum("pkj,pkj->pk", rows[:, :, 6:9], ap)             # (c - a).(p - a)
        ab_ab, ab_ac, ac_ac = rows[:, :, 9], rows[:, :, 10], rows[:, :, 11]   # (P, k) each
        s, t = _triangle_coordinates(d1, d2, ab_ab, ab_ac, ac_ac)
        gap = np.einsum("pkj,pkj->pk", ap, ap) - 2 * (s * d1 + t * d2) + s * s * ab_ab + 2 * s * t * ab_ac + t * t * ac_ac
        best = np.argmin(gap, axis=1)                                  # (P,)
        rows = np.arange(len(points))
        face, s, t = near[rows, best], s[rows, best], t[rows, best]
        return self.origin[face] + self.sides[face, 0] * s[:, None] + self.sides[face, 1] * t[:, None], face, s, t

    def project_to_boundary(self, points: np.ndarray) -> np.ndarray:
        """Nearest points on the input's boundary polyline."""
        found, gap, _ = self._nearest_on_segments(points, self.segments, self.segment_tree)
        return found[np.arange(len(points)), np.argmin(gap, axis=1)]

    def _with_line(self, points: np.ndarray, line_numbers: np.ndarray) -> np.ndarray:
        """(P, 4) the points with their line's number, times ``line_spacing``, as a fourth coordinate."""
        return np.column_stack([points, self.line_spacing * line_numbers])

    def project_to_lines(self, points: np.ndarray, line_numbers: np.ndarray) -> np.ndarray:
        """Nearest points on the input's feature lines, each point (P, 3) on its own line
        ``line_numbers`` (P,): a vertex goes back onto the line it was on, never onto
        another one nearby (which would pull an edge of its line across the surface)."""
        found, gap, near = self._nearest_on_segments(points, self.line_segments, self.line_tree,
                                                     self._with_line(points, line_numbers))
        # Of the 4 segments nearest, only those of the point's own line count (the
        # nearest one always is: other lines are line_spacing away in the tree).
        gap[self.line_numbers[near] != line_numbers[:, None]] = np.inf
        return found[np.arange(len(points)), np.argmin(gap, axis=1)]

    @staticmethod
    def _nearest_on_segments(points, segments, tree, keys=None):
        """The nearest point on each of the (up to) 4 segments whose midpoints are nearest
        (to ``keys``, the points' tree coordinates, if given): ``(points (P, k, 3),
        squared distances (P, k), the segments (P, k))``."""
        k = min(4, tree.n)
        _, near = tree.query(points if keys is None else keys, k=k)
        near = near.reshape(len(points), k)                            # (P, k)
        repeated = np.repeat(points, k, axis=0)
        flat = near.reshape(-1)
        found = closest_points_on_segments(repeated, segments[flat, 0], segments[flat, 1]).reshape(len(points), k, 3)
        return found, np.einsum("ikj,ikj->ik", found - points[:, None], found - points[:, None]), near


def _nearly_flat(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(m,) True for faces of (almost) no area: twice the area at most
    ``MIN_RELATIVE_AREA`` times the squared longest edge (two corners on one point, or
    three on a line). Measured against the face's own size, so it does not depend on
    the mesh's scale."""
    p0, p1, p2 = (np.take(vertices, faces[:, k], axis=0) for k in range(3))   # (m, 3) each
    sides = (p1 - p0, p2 - p1, p0 - p2)
    cross = cross_rows(sides[0], p2 - p0)                               # length: twice the area
    longest = np.maximum.reduce([np.einsum("ij,ij->i", side, side) for side in sides])   # (m,) squared
    # Compared squared: (twice the area)^2 <= (MIN_RELATIVE_AREA * longest^2)^2.
    return np.einsum("ij,ij->i", cross, cross) <= (MIN_RELATIVE_AREA * longest) ** 2


def _project(vertices, faces, surface: _Surface, features: Features | None, on_boundary: np.ndarray,
             snap_radius: float = 0.0) -> np.ndarray:
    """Put every vertex on the nearest point of the input surface (boundary vertices on
    its boundary), except where that would flatten a face; a vertex off the lines whose
    nearest point is within ``snap_radius`` of an input vertex goes onto that vertex
    (see :meth:`_Surface.project`).

    With ``features``, a vertex on a feature line (a crease or the boundary) goes onto
    its own line of the input, and corners stay exactly where they are.

    Where the input folds (a crease, a thin part), two corners of one face can land on
    the same nearest point, or three on one line, and the face would be left with no
    area. Corners of such a face are put back where they were before the projection:
    first only those off the lines, which need not be on anything exactly, and only if
    a face has none of those left to put back, its corners on lines (which smoothing
    may have moved off their line where it turns). Putting back may flatten a face next
    to them in turn, so this repeats until no face is flattened (each pass puts back at
    least one more vertex, so it ends). ``on_boundary`` (n,): the boundary vertices.
    """
    result = vertices.copy()
    if features is None:
        on_line = on_boundary
        inside = np.flatnonzero(~on_boundary)
        if on_boundary.any() and surface.segment_tree is not None:
            result[on_boundary] = surface.project_to_boundary(vertices[on_boundary])
    else:
        on_line = features.counts() > 0
        inside = np.flatnonzero(~on_line)
        line_of = features.vertex_lines()                              # (n,) -1 off the lines and at corners
        moving = np.flatnonzero(line_of >= 0)
        if len(moving) and surface.line_tree is not None:
            result[moving] = surface.project_to_lines(vertices[moving], line_of[moving])
    result[inside] = surface.project(vertices[inside], snap_radius)
    while True:
        flat = np.flatnonzero(_nearly_flat(result, faces))
        flattened = flat[~_nearly_flat(vertices, faces[flat])]        # flat now, and not before (few)
        if len(flattened) == 0:
            return result
        corners = faces[flattened]                                     # (k, 3)
        moved = (result[corners] != vertices[corners]).any(axis=2)     # (k, 3) not put back yet
        loose = moved & ~on_line[corners]                              # (k, 3) and off the lines
        put_back = corners[np.where(loose.any(axis=1)[:, None], loose, moved)]
        result[put_back] = vertices[put_back]


# ----------------------------------------------------------------------------------------
# The algorithm
# ----------------------------------------------------------------------------------------

def _check_arguments(target_length, iterations) -> tuple[float | None, int]:
    if int(iterations) != iterations or iterations < 0:
        raise ValueError(f"iterations must be a whole number >= 0, got {iterations!r}")
    if target_length is not None:
        target_length = float(target_length)
        if not math.isfinite(target_length) or target_length <= 0:
            raise ValueError(f"target_length must be a positive number, got {target_length!r}")
    return target_length, int(iterations)


def _check_feature_options(feature_angle, smoothing_step) -> tuple[float | None, float]:
    """``feature_angle`` as a float from 0 to 180 degrees or None (no creases), and
    ``smoothing_step`` as a float from 0 to 1."""
    if feature_angle is not None:
        feature_angle = real_number(feature_angle, "feature_angle", minimum=0.0, maximum=180.0)
    return feature_angle, real_number(smoothing_step, "smoothing_step", minimum=0.0, maximum=1.0)


def _phases(mesh: HalfedgeMesh, target_length, iterations, project, progress,
            feature_angle: float | None, smoothing_step: float = 1.0) -> Iterator[tuple[int, str, np.ndarray, np.ndarray, Features | None]]:
    """Yield ``(iteration, phase, vertices, faces, features)`` after every phase (arrays,
    not meshes; ``features`` None without ``feature_angle``)."""
    vertices, faces = mesh.to_arrays()
    table = edge_table(faces, len(vertices))           # the input's edges, sorted once for the next three uses
    if target_length is None:
        target_length = float(_edge_lengths(vertices, table.edges).mean())
    features = feature_arrays(vertices, faces, feature_angle, table=table) if feature_angle is not None else None
    surface = _Surface(vertices, faces, features) if project else None
    rng = np.random.default_rng(0)
    for iteration in progress_range(iterations, progress, "remesh"):
        vertices, faces, features = _split_long_edges(vertices, faces, target_length, features,
                                                      table if iteration == 0 else None)
        yield iteration + 1, "split", vertices, faces, features
        vertices, faces, features = _collapse_short_edges(vertices, faces, target_length, features)
        yield iteration + 1, "collapse", vertices, faces, features
        faces, table = _flip_to_regular_degrees(vertices, faces, rng, features)   # table: for smoothing and projection
        yield iteration + 1, "flip", vertices, faces, features
        vertices = tangential_smoothing(vertices, faces, features, smoothing_step, table=table)
        yield iteration + 1, "smooth", vertices, faces, features
        if surface is not None:
            vertices = _project(vertices, faces, surface, features, table.boundary_vertices(len(vertices)),
                                SNAP_TO_INPUT_VERTEX * target_length)
            yield iteration + 1, "project", vertices, faces, features


def remesh(
    mesh: HalfedgeMesh,
    target_length: float | None = None,
    iterations: int = 5,
    *,
    project: bool = True,
    progress: bool = False,
    feature_angle: float | None = DEFAULT_FEATURE_ANGLE,
    smoothing_step: float = 1.0,
) -> HalfedgeMesh:
    """Isotropic remeshing: edges of about ``target_length``, vertex degrees near 6.

    Args:
        mesh: the input; it is not modified.
        target_length: the edge length ``L`` to aim for; default: the input's mean edge length.
        iterations: how many rounds of split / collapse / flip / smooth / project.
        project: put the vertices back on the input surface after each smoothing (the
            boundary ones on the input's boundary polyline, the ones on a feature line
            on that line of the input). Each vertex goes to the nearest point of a few
            input triangles near it (a k-d tree of centroids, then the triangles beside
            the nearest; of the four segments of its line nearest, on a line), which is
            the true nearest point almost always; one that lands within
            ``SNAP_TO_INPUT_VERTEX * L`` (0.1 L) of an input vertex off the lines goes
            onto that vertex. Without it, midpoints of splits and tangential moves drift
            slightly inside curved regions.
        progress: show a progress bar (tqdm) over the iterations.
        feature_angle: keep the creases: edges whose two faces' normals differ by more
            than this many degrees (default :data:`~halfedge_edu.algorithms.features.DEFAULT_FEATURE_ANGLE`),
            together with the boundary, are feature edges (see
            :func:`~halfedge_edu.algorithms.features.detect_features`). None: no
            creases, only the boundary is kept (and its vertices do not move at all).
        smoothing_step: how much of the tangential step to its neighbours' centroid each
            vertex takes per smoothing phase, from 0 to 1. 1 (Botsch and Kobbelt) makes
            the most even triangles; smaller values leave the vertices nearer where
            splits and collapses put them, and nearer the input's vertices (where the
            projection puts those within ``SNAP_TO_INPUT_VERTEX * L``), which follows a
            noisy input (a scan) more closely at the price of less even triangles (0.5:
            PyMeshLab's mean distance to the bunny, with more even triangles than
            PyMeshLab's).

    Returns:
        A new :class:`HalfedgeMesh`. For the mesh after every phase, call
        :func:`remesh_history` (all at once) or :func:`remesh_step_by_step` (one by one).

    What is kept: the genus, the number of boundary loops and components, orientation;
    boundary vertices only move along the input's boundary (boundary edges are split at
    their midpoints and collapse only along the boundary, onto one of their ends).
    With ``feature_angle``, every feature line likewise: a feature edge is never
    flipped, is split into two feature edges and collapses only along its line, its
    vertices move only along the line and go back onto the input's feature lines, and
    corners (where lines meet, end or turn by more than ``feature_angle``) stay exactly
    where they are.
    Right after each split phase and each collapse phase no edge is longer than 4/3 L.
    What is aimed for, not guaranteed: edges between 4/5 L and 4/3 L at the end (a
    collapse that would make a long edge, fold a face or break the link condition is
    skipped, and smoothing moves vertices afterwards), degree 6 inside and 4 on the
    boundary.

    Attention: with ``feature_angle=None`` creases are not kept. An edge whose faces meet
    at more than 20 degrees is still never flipped, and no collapse may swing a face by
    more than 30 degrees, but smoothing may move vertices across a crease and round it off.
    """
    check_remesh(mesh, target_length, iterations, project, progress)
    feature_angle, smoothing_step = _check_feature_options(feature_angle, smoothing_step)
    if mesh.n_faces == 0:
        return _to_mesh(*mesh.to_arrays())
    target_length, iterations = _check_arguments(target_length, iterations)
    vertices, faces = mesh.to_arrays()
    for _, _, vertices, faces, _ in _phases(mesh, target_length, iterations, project, progress, feature_angle,
                                            smoothing_step):
        pass
    return _to_mesh(vertices, faces)


def remesh_history(mesh: HalfedgeMesh, target_length: float | None = None, **options) -> list[RemeshStep]:
    """Every :class:`RemeshStep` of :func:`remesh_step_by_step`, as one list.

    Takes exactly the arguments of :func:`remesh` (``options`` are its other keyword
    arguments, with its defaults); the last step's mesh is what :func:`remesh` returns
    for them. A separate function rather than a flag on :func:`remesh`, so that each
    function always returns one type.
    """
    # Bind to remesh's own signature: one place holds the options and their defaults,
    # and a misspelt option is a TypeError naming it.
    arguments = inspect.signature(remesh).bind(mesh, target_length, **options)
    arguments.apply_defaults()
    given = dict(arguments.arguments)
    feature_angle, smoothing_step = _check_feature_options(given.pop("feature_angle"), given.pop("smoothing_step"))
    check_remesh(**given)
    if mesh.n_faces == 0:
        return [RemeshStep(0, "input", mesh.copy())]
    target_length, iterations = _check_arguments(given["target_length"], given["iterations"])
    return list(_steps(mesh, target_length, iterations, given["project"], given["progress"], feature_angle,
                       smoothing_step))


def remesh_step_by_step(
    mesh: HalfedgeMesh,
    target_length: float | None = None,
    iterations: int = 5,
    *,
    project: bool = True,
    feature_angle: float | None = DEFAULT_FEATURE_ANGLE,
    smoothing_step: float = 1.0,
) -> Iterator[RemeshStep]:
    """Yield a :class:`RemeshStep` ``(iteration, phase, mesh)`` after every phase.

    First ``(0, "input", a copy of mesh)``; then, for each iteration from 1, the phases
    ``"split"``, ``"collapse"``, ``"flip"``, ``"smooth"`` and (with ``project=True``)
    ``"project"``. Each mesh is new. The work happens as you ask for the next step, so a
    stepper can stop whenever it likes. The arguments are those of :func:`remesh`.
    """
    check_remesh(mesh, target_length, iterations, project)
    feature_angle, smoothing_step = _check_feature_options(feature_angle, smoothing_step)
    if mesh.n_faces == 0:
        return iter([RemeshStep(0, "input", mesh.copy())])
    target_length, iterations = _check_arguments(target_length, iterations)
    return _steps(mesh, target_length, iterations, project, False, feature_angle, smoothing_step)


def _steps(mesh, target_length, iterations, project, progress, feature_angle, smoothing_step) -> Iterator[RemeshStep]:
    yield RemeshStep(0, "input", mesh.copy())
    for iteration, phase, vertices, faces, _ in _phases(mesh, target_length, iterations, project, progress,
                                                        feature_angle, smoothing_step):
        yield RemeshStep(iteration, phase, _to_mesh(vertices, faces))


def _to_mesh(vertices: np.ndarray, faces: np.ndarray) -> HalfedgeMesh:
    vertices, faces, _ = compact(vertices, faces)
    return HalfedgeMesh.from_faces(vertices, faces)


# ----------------------------------------------------------------------------------------
# Quality
# ----------------------------------------------------------------------------------------

@dataclass
class MeshQuality:
    """What isotropic remeshing improves, measured on one mesh.

    ``degree_histogram[d]`` counts the vertices of degree ``d``; ``min_angle_histogram``
    is ``(counts, bin_edges)`` of each face's smallest angle in degrees (``np.histogram``);
    ``edge_length_histogram`` likewise for the edge lengths. ``degree_deviation`` is
    the mean of ``|degree - 6|`` over interior vertices and ``|degree - 4|`` over boundary
    ones (on a closed mesh: the mean of ``|degree - 6|``).
    """

    n_vertices: int
    n_faces: int
    edge_length_mean: float
    edge_length_std: float
    edge_length_histogram: tuple[np.ndarray, np.ndarray]
    degree_histogram: np.ndarray
    degree_deviation: float
    min_angle_mean: float
    min_angle_histogram: tuple[np.ndarray, np.ndarray]

    @property
    def edge_length_spread(self) -> float:
        """``std / mean`` of the edge lengths: 0 when all edges are equally long."""
        return self.edge_length_std / self.edge_length_mean

    def __str__(self) -> str:
        return (
            f"{self.n_faces} faces, edge length {self.edge_length_mean:.4g} +- {self.edge_length_std:.2g} "
            f"(spread {self.edge_length_spread:.3f}), mean |degree - ideal| {self.degree_deviation:.3f}, "
            f"mean smallest angle {self.min_angle_mean:.1f} deg"
        )


def quality_report(mesh: HalfedgeMesh, bins: int = 30) -> MeshQuality:
    """Edge lengths, vertex degrees and smallest face angles of ``mesh``, with histograms.

    Args:
        mesh: the mesh (only read).
        bins: how many bins the edge-length histogram (from 0 to the longest edge) and the
            smallest-angle histogram (0 to 60 degrees) have.

    Raises:
        MeshInputError: the mesh has no faces (there is nothing to measure).
    """
    check_mesh(mesh)
    whole_number(bins, "bins", minimum=1)
    if mesh.n_faces == 0:
        raise MeshInputError("quality_report: the mesh has no faces, so there are no edges or angles to measure")
    vertices, faces = mesh.to_arrays()
    table = edge_table(faces, len(vertices))
    lengths = _edge_lengths(vertices, table.edges)
    degree = np.bincount(table.edges.reshape(-1), minlength=len(vertices))
    ideal = np.where(table.boundary_vertices(len(vertices)), 4, 6)
    p = vertices[faces]                                                 # (F, 3, 3)
    along, back = np.roll(p, -1, axis=1) - p, np.roll(p, 1, axis=1) - p
    angles = np.degrees(np.arctan2(np.linalg.norm(np.cross(along, back), axis=2),
                                   np.einsum("fkd,fkd->fk", along, back)))
    smallest = angles.min(axis=1)
    return MeshQuality(
        n_vertices=len(vertices),
        n_faces=len(faces),
        edge_length_mean=float(lengths.mean()),
        edge_length_std=float(lengths.std()),
        edge_length_histogram=np.histogram(lengths, bins=bins, range=(0.0, max(float(lengths.max()), 1e-300))),
        degree_histogram=np.bincount(degree),
        degree_deviation=float(np.abs(degree - ideal).mean()),
        min_angle_mean=float(smallest.mean()),
        # A smallest angle is at most 60 degrees; rounding can put an equilateral one a hair above.
        min_angle_histogram=np.histogram(np.minimum(smallest, 60.0), bins=bins, range=(0.0, 60.0)),
    )
