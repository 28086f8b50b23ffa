"""Rounds of edge collapses on face arrays: which collapses are allowed, which go together.

``simplify`` and ``remesh`` both shrink a mesh by collapsing many edges at once. This
module holds the two questions they share, asked of plain arrays (positions (n, 3),
faces (m, 3), the edges of :func:`halfedge_edu.core.arrays.unique_edges`):

1. **May edge a-b collapse?** :func:`collapse_topology_ok` answers for many edges at
   once with the same rules as :meth:`HalfedgeMesh.can_collapse` (the tests hold the
   two equal on every edge of random meshes): the link condition (the ends share
   exactly the vertices opposite the edge: two inside, one on the boundary), no
   interior edge between two boundary vertices, and no opposite vertex left with too
   few edges. :func:`no_turned_faces` adds what the topology cannot see: no face
   around the edge may turn over when both ends move to the new point.
2. **Which allowed collapses can be done together?** :func:`choose_round` picks a set
   of cheap candidates far enough apart (no two within one ring, see
   :func:`independent_edges`) that doing them all at once is the same as doing them one
   after the other.

Checking is the expensive part, so :func:`choose_round` checks only the few candidates
it picks, pass after pass, instead of every candidate.

A round needs the same few tables of the face array every time: the edges, the face
across each edge, the faces (and their corners) and the neighbours around every vertex.
They are the face array's corner table (:class:`halfedge_edu.core.corner_table.CornerTable`,
the course's halfedges with ``next`` by arithmetic): :func:`round_tables` builds it
from two sorts, and the checks take its arrays as keyword arguments (``face_across``,
``neighbours``, ``corners_around``) where they replace a search.

Why rebuild them every round rather than patch the rows a round changed: a round's
collapses are spread over the whole mesh, one every few rings, so on the benchmark
meshes a round touches about half of the faces (43-53% on average, measured with
``benchmarks/bench_simplify.py --rounds``). Patching that half of the tables in place
(the faces that vanish, the rows of the merged and opposite vertices, the edges merged
into key order) took 1.5-1.9 times as long as the two sorts and the scatters of a
rebuild: numpy sorts integer keys with SIMD instructions, a few passes over the array.
"""

from __future__ import annotations

from typing import Callable, NamedTuple

import numpy as np

from ..core.arrays import expand, grouping_order
from ..core.corner_table import CornerTable

__all__ = [
    "FOLD_ANGLE", "RoundTables", "choose_round", "collapse_topology_ok", "drop_folding_neighbours", "independent_edges",
    "no_turned_faces", "one_collapse_per_opposite_vertex", "round_tables", "spread_ties", "spread_ties_keys",
]


def collapse_topology_ok(
    n: int,
    edges: np.ndarray,
    boundary_edge: np.ndarray,
    boundary_vertex: np.ndarray,
    degree: np.ndarray,
    neighbours: tuple[np.ndarray, np.ndarray],
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Which of k edges the topology allows to collapse, and each one's opposite vertices.

    Args:
        n: the number of vertices.
        edges: (k, 2) the edges to check, as vertex pairs.
        boundary_edge: (k,) True for the edges among them that lie on the boundary.
        boundary_vertex: (n,) True for boundary vertices.
        degree: (n,) how many edges each vertex has.
        neighbours: the vertex adjacency as CSR, from
            :func:`halfedge_edu.core.arrays.vertex_neighbours`.

    Returns:
        ``(ok (k,), opposite_owner, opposite_vertex)``: edge i may collapse where
        ``ok[i]``; the vertices it shares with both ends (for an allowed edge: the
        vertices opposite it) are ``opposite_vertex[opposite_owner == i]``.

    The rules are those of :meth:`HalfedgeMesh.can_collapse`, written for arrays:

    * an interior edge whose two ends are on the boundary would pinch the surface;
    * the ends may share only the opposite vertices (two inside, one on the boundary):
      a third common neighbour would become a doubled edge. This one count also
      refuses two triangles glued back to back and the edge of a lone triangle;
    * each opposite vertex loses an edge, and must keep at least 3 (2 on the
      boundary): this refuses the edges of a tetrahedron.

    How the common neighbours are found without a loop: gather the neighbours of
    every ``a`` and every ``b`` (:func:`expand`), label each with the edge it belongs
    to as ``edge * n + vertex``, sort; a label seen twice is a vertex next to both ends.
    The geometric check (:func:`no_turned_faces`) comes later, only for chosen edges.
    """
    k = len(edges)
    a, b = edges[:, 0], edges[:, 1]

    # Interior edge whose ends are both on the boundary: would pinch the surface.
    ok = ~(~boundary_edge & boundary_vertex[a] & boundary_vertex[b])

    # Link condition: common neighbours of a and b must be exactly the opposite vertices.
    nbr_offsets, nbr = neighbours
    owner_a, around_a = expand(nbr_offsets, nbr, a)
    owner_b, around_b = expand(nbr_offsets, nbr, b)
    owner = np.concatenate([owner_a, owner_b])
    around = np.concatenate([around_a, around_b])
    key = np.sort(owner * n + around)
    shared = key[1:][key[1:] == key[:-1]]                          # keys seen twice
    shared_owner, shared_vertex = shared // n, shared % n
    n_shared = np.bincount(shared_owner, minlength=k)
    ok &= n_shared == np.where(boundary_edge, 1, 2)

    # An opposite vertex must keep enough edges: interior ones at least 3 after losing one.
    needed = np.where(boundary_vertex[shared_vertex], 3, 4)
    too_thin = degree[shared_vertex] < needed
    ok[shared_owner[too_thin]] = False

    return ok, shared_owner, shared_vertex


#: Two neighbouring faces whose normals differ by more than this many degrees are folded
#: back onto each other (a dihedral angle near 180): no collapse may make such a pair.
FOLD_ANGLE = 150.0


class _MovedFaces(NamedTuple):
    """The faces k collapses move, one row each (j rows), before and after.

    Each face is read from its moving corner: ``(moving corner, u, w)`` is the face's
    own counter-clockwise order, and ``u - w`` its far edge, the one that stays.
    Vectors are stored by coordinate, (3, j): see :func:`_columns`.
    """

    owner: np.ndarray          # (j,) which collapse moves the face
    face: np.ndarray           # (j,) the face's index
    position: np.ndarray       # (j,) 0, 1 or 2: which corner moves
    u: np.ndarray              # (j,) the corner after the moving one
    w: np.ndarray              # (j,) the corner after u
    normal_before: np.ndarray | None  # (3, j) cross products, length twice the area
    normal_after: np.ndarray | None   # (3, j)


# The checks below keep their vectors by coordinate, (3, j): three contiguous rows of j
# numbers. Gathering positions that way (np.take along axis 1 of the (3, n) transposed
# positions) costs what gathering (j, 3) rows does, but then every product and sum runs
# over contiguous rows instead of columns strided three apart, and the cross products
# need no stacking: the whole check runs about a third faster.

def _columns(rows: np.ndarray) -> np.ndarray:
    """(3, k) the coordinates of (k, 3) rows, each contiguous."""
    return np.ascontiguousarray(rows.T)


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(3, j) cross products of (3, j) vectors, as :func:`halfedge_edu.core.arrays.cross_rows` computes them."""
    return np.array([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]])


def _dot(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(j,) dot products of (3, j) vectors.

    Summed in the order ``np.einsum("ij,ij->i", ...)`` sums three products on this
    machine's numpy (first plus last, then the middle), which these checks used on (j, 3)
    rows before: rounding is then the same to the last bit, and so is every verdict.
    """
    return (u[0] * v[0] + u[2] * v[2]) + u[1] * v[1]


def _unit(vectors: np.ndarray) -> np.ndarray:
    """(3, j) vectors scaled to length 1 (zero vectors stay zero)."""
    return vectors / np.maximum(np.sqrt(_dot(vectors, vectors)), 1e-300)


def _holds_any(columns: tuple[np.ndarray, np.ndarray, np.ndarray], *vertices: np.ndarray) -> np.ndarray:
    """(j,) True where the face with corner columns ``columns`` (three (j,)) holds any of ``vertices`` (each (j,)).

    Comparisons of columns: ``(corners == vertex[:, None]).any(axis=1)`` on a (j, 3)
    array says the same, but numpy reduces along a row of three several times slower.
    """
    found = np.zeros(len(columns[0]), dtype=bool)
    for vertex in vertices:
        for column in columns:
            found |= column == vertex
    return found


def _keep_where(mask: np.ndarray, *arrays: np.ndarray) -> tuple[np.ndarray, ...]:
    """``arrays``, each cut to the rows where ``mask`` (j,) holds."""
    rows = np.flatnonzero(mask)
    return tuple(np.take(array, rows, axis=0) for array in arrays)


#: The corner after corner k of a face, and the one after that: ``(k + 1) % 3`` and ``(k + 2) % 3``.
_NEXT_CORNER = np.array([1, 2, 0])
_NEXT_BUT_ONE_CORNER = np.array([2, 0, 1])


def _moved_faces(positions, faces, faces_around, points, keep, remove, *, before: bool = True,
                 after: bool = True, corners_around=None) -> _MovedFaces:
    """Every face around ``keep[i]`` or ``remove[i]`` that survives collapse i, moved to ``points[i]``.

    ``positions`` (3, n) are the vertex positions by coordinate (:func:`_columns`),
    ``points`` (k, 3) the new points. The two faces holding both ends vanish and are
    left out. Rows come in the order of ``keep``'s faces, then ``remove``'s. With
    ``before=False`` the normals before the move are not computed (``None``), with
    ``after=False`` neither are those after (:func:`_normals_after` gives them for chosen rows).
    ``corners_around`` (from :func:`round_tables`), if given, is read instead of
    ``faces_around``: see :func:`no_turned_faces`.
    """
    k = len(keep)
    end = np.concatenate([keep, remove])                                # (2k,) the moving ends
    other = np.concatenate([remove, keep])
    flat = faces.reshape(-1)
    if corners_around is None:
        row, face = expand(*faces_around, end)                          # faces_around from vertex_faces()
        # One column of corners at a time, gathered with np.take from the flat face array:
        # several times faster than fancy indexing rows of a 2-D array.
        first_corner = 3 * face
        c0, c1, c2 = (np.take(flat, first_corner + i) for i in range(3))   # (j,) each
        gone = np.take(other, row)
        survives = np.flatnonzero((c0 != gone) & (c1 != gone) & (c2 != gone))   # faces holding both vanish
        row, face, c0, c1, c2 = (np.take(array, survives) for array in (row, face, c0, c1, c2))
        mover = np.take(end, row)
        position = np.where(c0 == mover, 0, np.where(c1 == mover, 1, 2))
        # The two corners after the mover, picked from the columns already gathered.
        u = np.where(position == 0, c1, np.where(position == 1, c2, c0))
        w = np.where(position == 0, c2, np.where(position == 1, c0, c1))
    else:
        # Each row names the mover's own corner 3 f + k, so the two corners after it are
        # read straight from the flat face array: no search for the mover among three.
        row, corner = expand(*corners_around, end)
        face = corner // 3
        position = corner - 3 * face
        first_corner = corner - position
        u = np.take(flat, first_corner + np.take(_NEXT_CORNER, position))
        w = np.take(flat, first_corner + np.take(_NEXT_BUT_ONE_CORNER, position))
        gone = np.take(other, row)
        survives = np.flatnonzero((u != gone) & (w != gone))          # faces holding both vanish
        row, face, position, u, w = (np.take(array, survives) for array in (row, face, position, u, w))
        mover = np.take(end, row)
    owner = np.where(row < k, row, row - k)
    if not after:
        return _MovedFaces(owner, face, position, u, w, None, None)
    # (mover, u, w) is a rotation of the face's corners, so (u - x) x (w - x) is its
    # cross product for x at the mover's old place and at the new point.
    at_u, at_w = np.take(positions, u, axis=1), np.take(positions, w, axis=1)        # (3, j)
    after = np.take(_columns(points), owner, axis=1)
    normal_before = None
    if before:
        at_mover = np.take(positions, mover, axis=1)
        normal_before = _cross(at_u - at_mover, at_w - at_mover)
    return _MovedFaces(owner, face, position, u, w, normal_before, _cross(at_u - after, at_w - after))


#: How many collapses :func:`no_turned_faces` and :func:`drop_folding_neighbours` work out
#: at a time. A collapse moves about ten faces, and the checks make some forty temporary
#: arrays of one number per moved face: in blocks of 1024 collapses each is about 80 KiB
#: and stays in the processor's cache; the verdicts are the same for any block size.
TURN_CHECK_BLOCK = 1024


def _moved_faces_in_blocks(positions, faces, faces_around, points, keep, remove, corners_around=None) -> _MovedFaces:
    """:func:`_moved_faces` without any normals, worked out :data:`TURN_CHECK_BLOCK` collapses at a time.

    A collapse's rows depend only on that collapse, so the blocks' rows, one after the
    other (owners renumbered back), are the rows of all of them, in another order. Each
    block's temporaries stay in the processor's cache (see :data:`TURN_CHECK_BLOCK`).
    """
    starts = range(0, len(keep), TURN_CHECK_BLOCK)
    if len(starts) <= 1:
        return _moved_faces(positions, faces, faces_around, points, keep, remove, before=False, after=False,
                            corners_around=corners_around)
    blocks = [_moved_faces(positions, faces, faces_around, points[start:start + TURN_CHECK_BLOCK],
                           keep[start:start + TURN_CHECK_BLOCK], remove[start:start + TURN_CHECK_BLOCK], before=False,
                           after=False, corners_around=corners_around)
              for start in starts]
    joined = {field: np.concatenate([getattr(block, field) for block in blocks], axis=-1)
              for field in ("face", "position", "u", "w")}
    owner = np.concatenate([block.owner + start for block, start in zip(blocks, starts)])
    return _MovedFaces(owner=owner, normal_before=None, normal_after=None, **joined)


def _normals_after(positions: np.ndarray, points: np.ndarray, moved: _MovedFaces, rows: np.ndarray) -> np.ndarray:
    """(3, r) the normals after the move of the moved faces ``rows`` (r,): :func:`_moved_faces`' ``normal_after``.

    The same numbers, computed the same way, for only the rows asked for.
    """
    u, w, owner = np.take(moved.u, rows), np.take(moved.w, rows), np.take(moved.owner, rows)
    at_u, at_w = np.take(positions, u, axis=1), np.take(positions, w, axis=1)        # (3, r)
    after = np.take(_columns(points), owner, axis=1)
    return _cross(at_u - after, at_w - after)


def no_turned_faces(
    vertices: np.ndarray,
    faces: np.ndarray,
    faces_around: tuple[np.ndarray, np.ndarray],
    points: np.ndarray,
    keep: np.ndarray,
    remove: np.ndarray,
    max_normal_cos: float,
    *,
    face_across: np.ndarray | None = None,
    positions: np.ndarray | None = None,
    corners_around: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """(k,) True where moving both ends of edge ``keep[i] - remove[i]`` to ``points[i]``
    turns no face over and folds no pair of neighbouring faces.

    ``faces_around`` is each vertex's faces as CSR, from
    :func:`halfedge_edu.core.arrays.vertex_faces`; ``max_normal_cos`` the cosine of the
    largest allowed swing of a face normal. The faces around ``keep`` and around
    ``remove`` get a corner moved to the new point; the two faces holding both ends
    vanish and are skipped. Three tests, each on every moved face:

    * **turn**: its normal swings by more than the allowed angle. A face that had no
      normal before (zero area) has nothing to swing from, so only the next two judge it;
    * **collapse**: its area drops to (almost) nothing;
    * **fold**: it and a neighbour (another moved face across an edge at the new vertex,
      or an unmoved face across its far edge) end up with normals more than
      :data:`FOLD_ANGLE` apart. The turn
      test alone misses this: two neighbours may each swing by less than the allowed
      angle, in opposite directions, and between them fold shut.

    ``face_across`` (m, 3), if the caller has it (from :func:`round_tables`): the face
    across each face's edge ``faces[f, k] -> faces[f, k + 1]``, -1 on the boundary. It
    names the unmoved neighbour of each moved face directly; without it the neighbour
    is searched for among the faces around the far edge's end, several times the work.

    ``positions`` (3, n), if the caller has them: ``vertices`` by coordinate
    (:func:`_columns`), so that several checks of one round share one copy.

    ``corners_around``, if the caller has it (from :func:`round_tables`): each vertex's
    corners ``3 f + k`` as CSR, the rows of ``faces_around`` before the division by 3.
    A corner names where the moving vertex sits in its face, so the corners after it
    are read directly instead of searched for among the face's three (same verdicts,
    less work for every moved face).
    """
    if positions is None:
        positions = _columns(vertices)                                  # (3, n)
    if len(keep) > TURN_CHECK_BLOCK:              # one block at a time: see TURN_CHECK_BLOCK
        return np.concatenate([
            no_turned_faces(vertices, faces, faces_around, points[start:start + TURN_CHECK_BLOCK],
                            keep[start:start + TURN_CHECK_BLOCK], remove[start:start + TURN_CHECK_BLOCK],
                            max_normal_cos, face_across=face_across, positions=positions,
                            corners_around=corners_around)
            for start in range(0, len(keep), TURN_CHECK_BLOCK)])
    moved = _moved_faces(positions, faces, faces_around, points, keep, remove, corners_around=corners_around)
    owner, position, u, w = moved.owner, moved.position, moved.u, moved.w
    n_before, n_after = moved.normal_before, moved.normal_after         # (3, j) each
    length_before = np.sqrt(_dot(n_before, n_before))
    length_after = np.sqrt(_dot(n_after, n_after))
    had_normal = length_before > 1e-12 * length_after
    cosine = _dot(n_before, n_after) / np.maximum(length_before * length_after, 1e-300)
    turned = had_normal & (cosine < max_normal_cos)
    turned |= length_after <= 1e-12 * np.maximum(length_before, 1e-300)
    unit_after = n_after / np.maximum(length_after, 1e-300)            # _unit, with the length at hand
    fold_cos = float(np.cos(np.radians(FOLD_ANGLE)))

    # Moved faces that share an edge at the new vertex: after the collapse both faces
    # hold the kept vertex (the removed one renamed) and one more common vertex y; the
    # face on one side of that edge holds y as its u, the face on the other side as its w.
    key_u = owner * len(vertices) + u                                   # (j,) owner and far end
    key_w = owner * len(vertices) + w
    by_w = grouping_order(key_w, len(keep) * len(vertices))
    sorted_w = key_w[by_w]
    at = np.minimum(np.searchsorted(sorted_w, key_u), max(len(sorted_w) - 1, 0))
    first = np.flatnonzero(np.take(sorted_w, at) == key_u) if len(sorted_w) else at
    second = np.take(by_w, np.take(at, first))
    folded = _dot(np.take(unit_after, first, axis=1), np.take(unit_after, second, axis=1)) < fold_cos
    turned[first[folded]] = True

    # A moved face and the unmoved face across its far edge (u, w), the face holding
    # u and w but neither end of the collapse.
    flat = faces.reshape(-1)
    if face_across is None:
        row, neighbour = expand(*faces_around, w)
        row, neighbour = _keep_where(_holds_any(tuple(faces[neighbour].T), u[row]), row, neighbour)
    else:
        neighbour = np.take(face_across.reshape(-1), 3 * moved.face + np.take(_NEXT_CORNER, position))   # across u -> w
        row, neighbour = _keep_where(neighbour >= 0, np.arange(len(owner)), neighbour)
    b0, b1, b2 = (np.take(flat, 3 * neighbour + i) for i in range(3))
    row_owner = np.take(owner, row)
    row, b0, b1, b2 = _keep_where(~_holds_any((b0, b1, b2), np.take(keep, row_owner), np.take(remove, row_owner)),
                                  row, b0, b1, b2)
    at_b0 = np.take(positions, b0, axis=1)
    n_beyond = _unit(_cross(np.take(positions, b1, axis=1) - at_b0, np.take(positions, b2, axis=1) - at_b0))
    folded = _dot(np.take(unit_after, row, axis=1), n_beyond) < fold_cos
    turned[row[folded]] = True

    ok = np.ones(len(keep), dtype=bool)
    ok[owner[turned]] = False
    return ok


#: What a round of collapses asks about a face array: its :class:`CornerTable`. The
#: checks read ``edges``, ``boundary``, ``boundary_halfedge``, ``face_across`` and the
#: rings ``faces_around``, ``neighbours`` and ``corners_around`` (the name is the one
#: rounds used before the corner table had its own).
RoundTables = CornerTable


def round_tables(faces: np.ndarray, n: int) -> CornerTable:
    """The :class:`~halfedge_edu.core.corner_table.CornerTable` of ``faces`` (m, 3),
    vertex indices below ``n``: what a round reads, from two sorts.

    The halfedges sorted by their undirected key give the edges and the face across
    each halfedge; the corners sorted by vertex give the faces and the neighbours
    around every vertex (worked out when first asked for).
    """
    return CornerTable(faces, n)


def drop_folding_neighbours(vertices: np.ndarray, faces: np.ndarray, faces_around: tuple[np.ndarray, np.ndarray],
                            points: np.ndarray, keep: np.ndarray, remove: np.ndarray, *,
                            face_across: np.ndarray | None = None, positions: np.ndarray | None = None,
                            corners_around: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """(k,) False for collapses of one round that would fold a face of another's shut.

    :func:`no_turned_faces` judges each collapse against the faces around it as they
    were. Two collapses of one round are never neighbours, but they can be two edges
    apart: a face moved by one then borders, across its far edge, a face moved by the
    other, and each was checked against the other's face unmoved. Here all of a
    round's collapses are applied at once and every such pair is measured; where a pair
    folds (normals more than :data:`FOLD_ANGLE` apart), both collapses are dropped,
    which puts each back to a state its own check accepted.

    The pairs are moved faces with the same far edge, found by sorting the far edges;
    or, given ``face_across`` (from :func:`round_tables`), as moved faces whose
    neighbour across the far edge is moved too, without a sort. ``positions`` (3, n) and
    ``corners_around``, if the caller has them: as for :func:`no_turned_faces`.
    """
    if positions is None:
        positions = _columns(vertices)                                  # (3, n)
    moved = _moved_faces_in_blocks(positions, faces, faces_around, points, keep, remove, corners_around)
    if face_across is None:
        u, w = moved.u, moved.w
        key = np.minimum(u, w) * len(vertices) + np.maximum(u, w)      # each face's far edge
        order = np.argsort(key, kind="stable")
        same = key[order][1:] == key[order][:-1]
        first, second = order[:-1][same], order[1:][same]
    else:
        row_of_face = np.full(len(faces), -1, dtype=np.int64)
        row_of_face[moved.face] = np.arange(len(moved.face))            # a face is moved by one collapse at most
        neighbour = np.take(face_across.reshape(-1), 3 * moved.face + (moved.position + 1) % 3)   # across u -> w
        other = np.where(neighbour >= 0, row_of_face[neighbour], -1)
        first = np.flatnonzero(other > np.arange(len(other)))          # each pair once
        second = other[first]
    apart = moved.owner[first] != moved.owner[second]
    first, second = first[apart], second[apart]
    # Normals only for the faces in a pair: about a quarter of the moved faces.
    folded = (_dot(_unit(_normals_after(positions, points, moved, first)),
                   _unit(_normals_after(positions, points, moved, second)))
              < float(np.cos(np.radians(FOLD_ANGLE))))
    ok = np.ones(len(keep), dtype=bool)
    ok[moved.owner[first[folded]]] = False
    ok[moved.owner[second[folded]]] = False
    return ok


def one_collapse_per_opposite_vertex(chosen: np.ndarray, opposite_owner: np.ndarray,
                                      opposite_vertex: np.ndarray) -> np.ndarray:
    """Drop chosen candidates that share an opposite vertex with a cheaper chosen one.

    Each collapse takes one edge from each opposite vertex; two collapses in one round
    could take two from the same vertex and leave it with too few. ``chosen`` (k,) is a
    mask over candidates, which are sorted cheapest first.
    """
    mine = chosen[opposite_owner]
    owner, vertex = opposite_owner[mine], opposite_vertex[mine]
    if len(owner) == 0:
        return chosen.copy()
    # The cheapest chosen owner at each vertex (candidates are cheapest first, so the
    # lowest index); every other owner there drops out. A scatter-minimum into a table
    # over the vertices, instead of sorting the (owner, vertex) pairs: about a fifth of
    # the time for the few thousand pairs of a pass.
    cheapest = np.full(int(vertex.max()) + 1, len(chosen), dtype=np.int64)
    np.minimum.at(cheapest, vertex, owner)
    result = chosen.copy()
    result[owner[np.take(cheapest, vertex) != owner]] = False
    return result


def independent_edges(edges: np.ndarray, priority: np.ndarray, all_edges: np.ndarray, n: int) -> np.ndarray:
    """(k,) True for the ``edges`` (k, 2) that are the cheapest within one ring of both their ends.

    ``priority`` (k,) distinct, lowest first; ``all_edges`` (E, 2) every edge of the
    mesh (the rings run along them); ``n`` the number of vertices.

    ``m1[x]`` is the lowest priority among candidate edges at vertex x; ``m2[y]`` the
    lowest ``m1`` over y and its neighbours. An edge taken only where it equals ``m2`` at
    both ends is at least two edges away from every other taken edge, so the collapses
    of one round touch disjoint neighbourhoods and can be applied together.
    """
    return _independent_edges(edges, priority, np.ascontiguousarray(all_edges.T), n)[0]


def _independent_edges(edges: np.ndarray, priority: np.ndarray, ring: np.ndarray,
                       n: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`independent_edges` with the mesh edges ``ring`` by column, (2, R); also the ring edges it used.

    ``m2`` is read only at the ends of the given edges, and only neighbours with an
    ``m1`` can lower it: so only the mesh edges between two such vertices take part.
    Those are returned, (2, R'), for the caller to pass back next time when its edges
    are a subset of these (as in :func:`choose_round`'s passes, where the open candidates
    only get fewer): the next call then scans R' edges instead of R.
    """
    big = np.iinfo(np.int64).max
    m1 = np.full(n, big)
    np.minimum.at(m1, edges[:, 0], priority)
    np.minimum.at(m1, edges[:, 1], priority)
    has = m1 < big
    x, y = ring
    near = np.flatnonzero(np.take(has, x) & np.take(has, y))     # indices and np.take: a 2-D boolean mask is slower
    ring = np.take(ring, near, axis=1)                            # (2, R') contiguous rows again
    x, y = ring
    m2 = m1.copy()
    np.minimum.at(m2, x, np.take(m1, y))
    np.minimum.at(m2, y, np.take(m1, x))
    return (m2[edges[:, 0]] == priority) & (m2[edges[:, 1]] == priority), ring


#: How many classes of about equal cost ``simplify`` cuts a round's candidates into
#: before :func:`spread_ties` shuffles within each (``remesh`` keeps strict length order).
COST_CLASSES = 16


def spread_ties(cost_class: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """(k,) priorities for :func:`choose_round`: cost order between classes, a shuffle within.

    ``cost_class`` (k,) small integers, lower is cheaper; ``ids`` (k,) a number that
    names each candidate for good (an edge key, an edge index). A candidate of a cheaper
    class always comes first; inside a class the order is a hash of ``ids``, the same on
    every run, so results stay deterministic. Returns each candidate's rank in that order.

    Why: :func:`independent_edges` takes an edge only where it is the first of its
    neighbourhood. In strict cost order, a smooth cost field (or a symmetric mesh, where
    many costs are equal and ties fall to the edge numbering) has few such local
    minima: on a 1M-face torus the first pass of ``simplify`` took 898 of 375,144
    candidates, so the rounds grew with the mesh (19 at 10k faces, 53 at 1M). Within a
    class of nearly equal costs, a hashed order makes local minima as dense as random
    priorities do (Luby's algorithm): 24,141 in that first pass, and 17 rounds at 1M.
    """
    # A multiplicative hash (Knuth's, 64-bit; the product wraps around): neighbouring
    # numbers land far apart.
    shuffle = ids.astype(np.uint64) * _KNUTH
    priority = np.empty(len(ids), dtype=np.int64)
    priority[np.lexsort((shuffle, cost_class))] = np.arange(len(ids))
    return priority


_KNUTH = np.uint64(0x9E3779B97F4A7C15)     # 2**64 / golden ratio, odd: multiplying by it permutes 64-bit numbers

#: The largest ids :func:`spread_ties_keys` takes (see there why).
SPREAD_KEY_IDS = 2 ** 30


def spread_ties_keys(cost_class: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """(k,) priorities in exactly :func:`spread_ties`' order, computed without a sort.

    :func:`choose_round` only compares priorities, so it needs their order, not their
    ranks: each key here is the class in the top 4 bits and the top 59 bits of the
    64-bit hash below, ``class << 59 | hash >> 5``, which sorts as ``(class, hash)``,
    the order :func:`spread_ties` ranks by, as long as no two hashes share their top 59
    bits. They do not: two hashes differ by ``(i - j) * _KNUTH`` (mod 2**64), and for
    every ``0 < |i - j| < 2**30`` that is at least ``2**33`` away from 0 (checked by
    brute force; the golden ratio is the number worst approximated by fractions), so
    the top 59 bits differ. ``cost_class`` must lie in 0-15 and ``ids`` in
    ``[0, SPREAD_KEY_IDS)``; :func:`spread_ties` takes any.
    """
    shuffle = ids.astype(np.uint64) * _KNUTH
    return (cost_class.astype(np.int64) << 59) | (shuffle >> np.uint64(5)).astype(np.int64)


def choose_round(
    edges: np.ndarray,
    candidates: np.ndarray,
    open_: np.ndarray,
    n: int,
    check_topology: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]],
    check_turned_faces: Callable[[np.ndarray], np.ndarray],
    known_opposites: tuple[np.ndarray, np.ndarray] | None = None,
    passes: int = 5,
    *,
    neighbours: tuple[np.ndarray, np.ndarray] | None = None,
    priority: np.ndarray | None = None,
) -> np.ndarray:
    """(k,) mask over candidates: a set of allowed collapses that can all be done at once.

    ``edges`` (E, 2) every edge; ``candidates`` (k,) index ``edges``, cheapest first;
    ``open_`` (k,) marks the ones worth trying. The two checks are the caller's, so
    each algorithm decides where a collapse puts its vertex: they take candidate
    indices (into ``candidates``) and return answers for those. Each pass picks the
    open candidates that are cheapest in their neighbourhood (see
    :func:`independent_edges`) and checks only those: first
    ``check_topology(indices) -> (ok, opposite_owner, opposite_vertex)`` (usually
    :func:`collapse_topology_ok`; ``opposite_owner`` holds candidate indices), then
    ``check_turned_faces(indices) -> ok`` (usually :func:`no_turned_faces`). Checking the picked few
    instead of every candidate is what keeps a round cheap: a pass picks a few
    candidates in a hundred. What passes is accepted; then every vertex within one
    ring of an accepted edge is blocked, and so is every vertex that just lost an edge
    as an opposite vertex, and the next pass picks among what is left. A few passes
    come close to a maximal set, so fewer rounds are needed.

    ``known_opposites``: ``(owner, vertex)`` arrays of opposite vertices the caller has
    already found (candidate indices and vertices), so that candidates whose opposite
    vertex has lost an edge drop out before a pass picks, not after.

    ``neighbours``: the vertex adjacency as CSR (from
    :func:`halfedge_edu.core.arrays.vertex_neighbours`), if the caller has it: then
    the ring around the accepted edges is gathered from their ends' rows instead of
    found by a scan of every edge.

    ``priority`` (k,) distinct, lowest first: the order in which a pass prefers
    candidates (default: their order, cheapest first; :func:`spread_ties` gives one
    that picks many more per pass on smooth or symmetric meshes).
    """
    chosen = np.zeros(len(candidates), dtype=bool)
    open_ = open_.copy()
    blocked = np.zeros(n, dtype=bool)            # within one ring of a chosen edge
    opposite_used = np.zeros(n, dtype=bool)      # already lost an edge this round
    empty = np.zeros(0, dtype=np.int64)
    known_owner, known_vertex = known_opposites if known_opposites is not None else (empty, empty)
    if priority is None:
        priority = np.arange(len(candidates), dtype=np.int64)   # candidates are cheapest first
    cand_edges = np.take(edges, candidates, axis=0)                    # (k, 2)
    # independent_edges looks only at mesh edges between two ends of open candidates,
    # and the open candidates only get fewer from pass to pass: so cut the mesh's edges
    # to those once, instead of scanning all of them in every pass.
    open_end = np.zeros(n, dtype=bool)
    open_end[cand_edges[open_].reshape(-1)] = True
    ring = np.take(edges, np.flatnonzero(open_end[edges[:, 0]] & open_end[edges[:, 1]]), axis=0).T.copy()  # (2, R)
    # The open candidates' indices, kept from pass to pass: each pass only shortens the
    # list, instead of sweeping every candidate's flags again.
    still_open = np.flatnonzero(open_)
    for _ in range(passes):
        open_[known_owner[opposite_used[known_vertex]]] = False
        ends = np.take(cand_edges, still_open, axis=0)                  # (s, 2)
        still_open = still_open[open_[still_open] & ~blocked[ends[:, 0]] & ~blocked[ends[:, 1]]]
        if len(still_open) == 0:
            break
        # Each pass hands back the ring edges it still needed: the next pass's open
        # candidates are fewer, so it needs at most those.
        independent, ring = _independent_edges(np.take(cand_edges, still_open, axis=0), priority[still_open], ring, n)
        picked = still_open[independent]
        ok, opposite_owner, opposite_vertex = check_topology(picked)
        known_owner = np.concatenate([known_owner, opposite_owner])     # repeats do no harm
        known_vertex = np.concatenate([known_vertex, opposite_vertex])
        open_[picked[~ok]] = False                        # refused for the whole round
        passed = np.zeros(len(candidates), dtype=bool)
        passed[picked[ok]] = True
        passed = one_collapse_per_opposite_vertex(passed, opposite_owner, opposite_vertex)
        which = np.flatnonzero(passed)
        open_[which] = False
        # The geometric check last, for the fewest; a refused one just drops out.
        passed[which[~check_turned_faces(which)]] = False
        accepted = which[passed[which]]
        chosen[accepted] = True
        ends = np.take(cand_edges, accepted, axis=0).reshape(-1)
        blocked[ends] = True
        if neighbours is None:
            at_end = np.zeros(n, dtype=bool)
            at_end[ends] = True
            blocked[edges[at_end[edges[:, 0]], 1]] = True
            blocked[edges[at_end[edges[:, 1]], 0]] = True
        else:
            blocked[expand(*neighbours, ends)[1]] = True
        opposite_used[opposite_vertex[passed[opposite_owner]]] = True
    return chosen


