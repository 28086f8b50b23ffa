"""Phase 2 of remeshing: collapse every edge shorter than ``4/5 L`` to its midpoint (or,
failing that, to one of its ends), unless that would make an edge longer than ``4/3 L``.

The *lines* are the boundary and, with ``features``, the feature lines: an edge along a
line collapses only along it, onto one of its ends (never removing a corner), and an
edge across from one line to another never collapses.

The collapses run in *rounds*, as ``simplify``'s do (:mod:`..collapse_rounds`): each
round checks every short edge (link condition, boundary rules, degrees, the 4/3 L rule,
no face turned over) and collapses a set of them far enough apart to be done together,
preferring shorter edges by class of length (:func:`_collapse_order`). After the first
round, a round looks only at the faces within two rings of the short edges still worth
trying (:func:`_faces_near`): nothing farther away can change its choice.
"""

from __future__ import annotations

import math

import numpy as np

from ...core.arrays import compact, expand
from ..collapse_rounds import (COST_CLASSES, choose_round, collapse_topology_ok, no_turned_faces, round_tables,
                               spread_ties_keys)
from ..features import Features
from .lengths import COLLAPSE_BELOW, SPLIT_ABOVE, edge_lengths

#: How many rounds the collapse may take within one iteration (each is one array operation).
MAX_COLLAPSE_ROUNDS = 30
#: Collapse rounds stop early once a round collapses at most this fraction of the faces'
#: count: the last few short edges are then left to the next iteration, where smoothing
#: has given them room, instead of paying a whole round each.
MIN_COLLAPSE_FRACTION = 0.0005
#: They also stop once a round collapses at most this share of the busiest round so far.
#: What is left then are chains, where one collapse makes the next possible: collapsing a
#: vertex of degree 4 into its neighbour takes an edge from the vertex opposite, which
#: then has degree 4 and short edges itself. A chain moves one edge per round (along a
#: whole ring on a torus), and could use up every round. The next iteration takes up
#: what is left, after the flips have raised those degrees.
MIN_COLLAPSE_SHARE = 0.1
#: A collapse may not swing any face normal by more than this (degrees).
MAX_COLLAPSE_NORMAL_ANGLE = 30.0


def collapse_short_edges(vertices: np.ndarray, faces: np.ndarray, target_length: float,
                         features: Features | None = None) -> tuple[np.ndarray, np.ndarray, Features | None]:
    """Collapse edges shorter than ``4/5 target_length``, round after round, until (almost)
    no short edge can go (at most :data:`MAX_COLLAPSE_ROUNDS` rounds).

    Why: splits never make an edge longer, so only collapses take away the short edges
    (and the crowded vertices at their ends). A collapse is skipped where it would make an
    edge longer than 4/3 L (the next split would undo it), break the link condition,
    turn a face over or swing its normal by more than :data:`MAX_COLLAPSE_NORMAL_ANGLE`,
    or pull a line (the boundary, a feature line) off itself; :func:`_collapse_round`
    says where the merged vertex goes.

    The rounds stop early once one collapses little: at most :data:`MIN_COLLAPSE_FRACTION`
    of the faces' count, or at most :data:`MIN_COLLAPSE_SHARE` of the busiest round's.

    Args:
        vertices: (n, 3) float positions (not modified).
        faces: (m, 3) int triangles.
        target_length: ``L``.
        features: the feature lines to keep (None: only the boundary is kept).

    Returns:
        ``(vertices, faces, features)``, compacted (unused vertices dropped): (n', 3),
        (m', 3), and the features renumbered to match.
    """
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


def _line_turning(vertices, line_edges: np.ndarray, n: int) -> np.ndarray:
    """(n,) how sharply a line of edges (the boundary, or the feature lines) turns at
    each vertex: ``|u1 + u2|`` for the unit vectors to its two neighbours on the line
    (0 where the line runs straight, up to 2)."""
    d = vertices[line_edges[:, 1]] - vertices[line_edges[:, 0]]
    d /= np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
    total = np.empty((n, 3))
    for axis in range(3):           # sums per vertex, by bincount (np.add.at would do, slowly)
        total[:, axis] = (np.bincount(line_edges[:, 0], weights=d[:, axis], minlength=n)
                          - np.bincount(line_edges[:, 1], weights=d[:, axis], minlength=n))
    return np.linalg.norm(total, axis=1)


#: How many short edges :func:`_collapse_places` measures at a time. Each edge gathers the
#: neighbours of both ends (about 13 points): in blocks, every temporary stays a few MiB
#: however large the mesh, instead of growing with its number of short edges.
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
    place, that place is taken without gathering any neighbours. The others are
    measured, :data:`PLACE_CHECK_BLOCK` at a time.
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
    bits of the shuffle), rather than a sort by two keys. Those numbers are distinct for
    keys below 2**30; a large mesh's keys are bigger, so where two numbers agree (rare)
    both keys decide.

    Why not strictly shortest first: a round takes an edge only where it comes first
    among the short edges within one ring of its ends (see
    :func:`~halfedge_edu.algorithms.collapse_rounds.choose_round`). Where lengths change
    smoothly, few edges are first in their neighbourhood: on a torus the edge lengths
    rise ring by ring across the tube, so strict order lets each round take little more
    than the shortest ring left, and the number of rounds grows with the mesh. Edges of
    about the same length are about as good to collapse first, and a shuffle among them
    makes first places as common as random ones do, so the number of rounds stays flat
    (the counts are in docs/performance.md).
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
    length = edge_lengths(vertices, edges)
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
