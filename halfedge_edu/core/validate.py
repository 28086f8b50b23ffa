"""``validate()``: check every rule of the halfedge structure, all elements at once.

Each rule is a whole-array comparison (no Python loop per element), so validating a
100k-face mesh after every operation stays cheap. The rules run in an order where each
one can rely on the earlier ones: pointers are checked to be in range and live before
anything follows them.

| rule                      | what must hold                                              |
|---------------------------|-------------------------------------------------------------|
| deletion-count            | the deleted flags agree with the mesh's element counts      |
| deleted-reference         | live elements point only at live elements, within range     |
| next-prev-inverse         | prev(next(h)) == h and next(prev(h)) == h                   |
| twin-involution           | twin(h) = h ^ 1 runs the other way: origin(twin(h)) != origin(h) |
| next-origin               | next(h) starts where h ends: origin(next(h)) == tip(h)      |
| next-cycle                | a face's halfedges form a loop of exactly 3, all in that face; boundary halfedges continue along the boundary |
| face-halfedge             | face(halfedge(f)) == f                                      |
| edge-halfedge             | every edge has a face on at least one side                  |
| vertex-halfedge-origin    | origin(halfedge(v)) == v; only an isolated vertex has none  |
| boundary-vertex-halfedge  | a boundary vertex's halfedge is its outgoing boundary halfedge |
| vertex-manifold           | walking around a vertex meets all its edges, and at most one boundary halfedge leaves it (one fan, no hourglass) |
| duplicate-edge            | no two edges join the same pair of vertices                 |

Two sizes of check. :func:`validate` checks every element, in time proportional to the
mesh. :func:`validate_around` checks the same rules (all but deletion-count, which is
about the whole mesh's counters) on the elements one operation touched and their
one-rings, in time proportional to those rings: after a flip on a million-face mesh it
looks at a few dozen halfedges, not six million. It finds the elements to check by
following the pointers outward from the touched ones, each pointer checked before it is
followed, so a broken pointer is reported instead of followed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from .arrays import undirected_keys
from .errors import MeshInputError, MeshInvariantError
from .rings import ring_lengths

if TYPE_CHECKING:
    from .mesh import HalfedgeMesh


def _first(bad: np.ndarray, indices) -> int | None:
    """Index (from ``indices``) of the first True in ``bad``, or None."""
    if not bad.any():
        return None
    position = int(np.argmax(bad))
    return int(position if indices is None else indices[position])


def _refuse(found: int | None, rule: str, kind: str, sentence: Callable[[int], str]) -> None:
    """Raise ``rule``'s error for element ``(kind, found)`` if :func:`_first` found one.

    ``sentence(found)`` writes the message; it runs only when there is something to
    report, so it may look up whatever it names.
    """
    if found is not None:
        raise MeshInvariantError(rule, (kind, found), sentence(found))


def validate(mesh: "HalfedgeMesh") -> None:
    """Raise :class:`MeshInvariantError` for the first broken rule, else return None."""
    n_v, n_h, n_f = mesh.n_vertex_slots, mesh.n_halfedge_slots, mesh.n_face_slots
    prv, origin, vertex_he = mesh.halfedge_prev, mesh.halfedge_vertex, mesh.vertex_halfedge
    vertex_deleted, face_deleted = mesh.vertex_deleted, mesh.face_deleted
    edge_deleted = mesh.edge_deleted

    # ---- deletion-count ---------------------------------------------------------------
    # The flags themselves say what is deleted, not the counters the operations keep: a
    # flag set by hand must not hide behind counters that say "nothing deleted".
    flagged = {kind: int(np.count_nonzero(flags))            # counts bytes, no int conversion
               for kind, flags in (("vertex", vertex_deleted), ("edge", edge_deleted), ("face", face_deleted))}
    counted = {"vertex": n_v - mesh.n_vertices, "edge": n_h // 2 - mesh.n_edges, "face": n_f - mesh.n_faces}
    for kind in ("vertex", "edge", "face"):
        if flagged[kind] != counted[kind]:
            flags = {"vertex": vertex_deleted, "edge": edge_deleted, "face": face_deleted}[kind]
            first = _first(flags, None)
            raise MeshInvariantError(
                "deletion-count",
                (kind, first if first is not None else 0),
                f"{flagged[kind]} {kind} slots are flagged deleted, but the mesh counts "
                f"{counted[kind]} deleted {kind}s"
                + (f" (the first flagged is {kind} {first})" if first is not None else "")
                + "; delete elements with the mesh's operations, which keep both in step",
            )
    garbage = any(flagged.values())

    # An isolated vertex (no halfedge, and no halfedge leaves it), as a file's vertex that
    # no face uses stays when loading, is allowed, as in pmp-library and OpenMesh: the
    # vertex rules below skip it. A vertex without a halfedge that some halfedge leaves
    # is still refused (vertex-halfedge-origin).
    isolated = (vertex_he == -1) & ~vertex_deleted
    if isolated.any():
        isolated[origin[~np.repeat(edge_deleted, 2)]] = False

    # The common case, a mesh with every slot live: all rules at once, in a few passes.
    # Only if one of them fails do the rules run one by one, to name the first broken
    # rule and element.
    if not garbage and not isolated.any() and _every_rule_holds(mesh):
        return

    # Which elements to check: every slot when nothing is deleted or isolated (no gather
    # needed), otherwise the live ones, as index arrays.
    if garbage or isolated.any():
        hs = np.flatnonzero(~np.repeat(edge_deleted, 2))
        vs = np.flatnonzero(~vertex_deleted & ~isolated)
        fs = np.flatnonzero(~face_deleted)
    else:
        hs = vs = fs = None
    _element_rules(mesh, hs, vs, fs, garbage)

    # ---- vertex-manifold --------------------------------------------------------------
    # By now rotation h -> twin(prev(h)) is a permutation that keeps each halfedge's
    # origin, so the walk around every vertex comes back to its start. The vertices
    # are manifold exactly when those walks, together, meet every halfedge; only when
    # they do not do we count degrees to say which vertex is at fault.
    walked = np.arange(n_v) if vs is None else vs
    ring_length = ring_lengths(vertex_he[walked], prv)
    if int(ring_length.sum()) != (n_h if hs is None else len(hs)):
        degree = np.bincount(origin if hs is None else origin[hs], minlength=n_v)[walked]
        v = _first(ring_length != degree, walked)
        raise MeshInvariantError(
            "vertex-manifold",
            ("vertex", v),
            f"walking around vertex {v} from its halfedge (h -> twin(prev(h))) meets "
            f"{int(ring_length[np.argmax(ring_length != degree)])} of its "
            f"{int(degree[np.argmax(ring_length != degree)])} edges before coming back; "
            f"its faces form more than one fan (an hourglass)",
        )
    _one_piece_of_boundary(mesh, np.flatnonzero(mesh.halfedge_face < 0) if hs is None
                           else hs[mesh.halfedge_face[hs] < 0])

    # ---- duplicate-edge ---------------------------------------------------------------
    _no_duplicate_edges(origin, None if hs is None else np.flatnonzero(~edge_deleted), n_v)


def _one_piece_of_boundary(mesh: "HalfedgeMesh", boundary: np.ndarray) -> None:
    """vertex-manifold: each of ``boundary`` (boundary halfedges) is its origin's halfedge.

    A vertex on two pieces of boundary has two fans, even when the walk around it meets
    all its edges: the boundary's next pointers can link its fans crosswise, and the
    walk then runs through both. With boundary-vertex-halfedge holding (a boundary
    vertex's halfedge is one of its outgoing boundary halfedges), a boundary halfedge
    that is not its origin's halfedge is exactly a second one leaving that vertex.
    """
    origin, vertex_he = mesh.halfedge_vertex, mesh.vertex_halfedge
    second = boundary[vertex_he[origin[boundary]] != boundary]
    if len(second):
        h = int(second[0])
        v = int(origin[h])
        raise MeshInvariantError(
            "vertex-manifold",
            ("vertex", v),
            f"vertex {v} lies on two pieces of boundary: boundary halfedges {int(vertex_he[v])} "
            f"and {h} both leave it, so its faces form more than one fan",
        )


#: Halfedges checked per block in :func:`_every_rule_holds`: a block's temporaries (a
#: dozen arrays of this many int32, 64 KiB each) stay in the core's own (L2) cache while
#: the rules read them. Measured at 1.3M faces, the loop over blocks takes 38 ms with
#: 2**14 against 47 ms with 2**18 (whose temporaries spill out of a 2 MiB L2); smaller
#: blocks lose it again to the Python overhead of each block (45 ms with 2**12).
_BLOCK = 1 << 14

#: Vertices walked together in :func:`_fans_hold` (its temporaries: a dozen arrays of
#: this many, one per step, also kept in the L2 cache).
_VERTEX_BLOCK = 1 << 13

#: Up to this many steps round a vertex, :func:`_fans_hold` compares each neighbour met
#: with the ones met before it; the rare vertices with more edges are checked by a sort.
_PAIRWISE_STEPS = 8

#: A ``next`` pointer "jumps far" when it leads this many halfedges away or more (a
#: quarter of a MiB of int32): the value it reads is then rarely in any cache.
_FAR = 1 << 16

#: Rows written at a time by :func:`_side_by_side`: 64k rows of four int32 are 1 MiB,
#: within the core's 2 MiB L2 cache (2**14 and 2**16 measured alike, 2**12 slower).
_COPY_BLOCK = 1 << 16


def _every_rule_holds(mesh: "HalfedgeMesh") -> bool:
    """True when every rule of the table holds, on a mesh whose slots are all live.

    The same conditions as the rule-by-rule checks, in fewer passes over memory:

    * deleted-reference is a range check, made on as little as the other rules leave
      open: one reduction over the faces' and the vertices' halfedges, one per block of
      ``face`` (while the block is in the cache), two look-ups for ``next``; ``prev``
      and ``origin`` are in range because other checks pass (the proofs are where
      those checks are made).
    * The rules that look one step ahead (next-prev-inverse, next-origin, next-cycle)
      gather each value they need at ``next(h)`` once, and all of them read it while a
      block of halfedges is still in the cache, with no index array per rule; an
      edge's two halfedges are compared at once, as one 64-bit word. edge-halfedge
      reads the same block. For meshes in random order the four values come from rows
      of four (:func:`_jumps_far`): one cache miss instead of four.
    * twin-involution compares each halfedge's origin with its twin's, which sits next
      to it in memory (``h ^ 1``): no gather at all.
    * vertex-halfedge-origin is one gather over the vertices; vertex-manifold and
      duplicate-edge come from one walk around every vertex (:func:`_fans_hold`),
      without the sort of all edges, the walks taken in the order of the vertices'
      halfedges, so that they read the halfedge arrays from start to end.

    False means some rule is broken; :func:`validate` then runs the rules one by one to
    say which. A mesh with deleted or isolated elements never comes here.
    """
    n_h, n_f = mesh.n_halfedge_slots, mesh.n_face_slots
    # The loop below reads pairs of int32 as 64-bit words (_edge_words), which needs
    # contiguous memory: arrays given as strided views are copied once, here
    # (np.ascontiguousarray hands back an array that is contiguous already as it is).
    nxt, prv, origin, face = (np.ascontiguousarray(values) for values in (
        mesh.halfedge_next, mesh.halfedge_prev, mesh.halfedge_vertex, mesh.halfedge_face))
    vertex_he, face_he = mesh.vertex_halfedge, mesh.face_halfedge
    unsigned = np.dtype(f"u{face.itemsize}")                  # see _all_below
    # The loops' gathers call the arrays' own take(): np.take(a, ...) reaches the same
    # method through two Python wrappers, a microsecond a call, and the loops make about
    # 2,000 gathers at 1.3M faces.

    # ---- deleted-reference of the faces' and the vertices' halfedges ----------------------
    if not (_all_below(face_he, n_h) and _all_below(vertex_he, n_h)):
        return False

    # When next pointers jump far (faces in random order), each of the four values read
    # at next(h) is a cache miss of its own; copied side by side into rows of four, they
    # cost one miss together, which pays for the copy. Ordered meshes skip the copy.
    rows = _side_by_side(prv, origin, face, nxt) if _jumps_far(nxt) else None   # (n_h, 4) or None
    boundary = []                                             # boundary halfedges, block by block

    # ---- next-prev-inverse, twin-involution, next-origin, next-cycle, edge-halfedge -------
    # The gathers at next(h) use mode="clip": an index out of range reads the first or
    # the last value instead (numpy then skips the bounds check it would otherwise make
    # for each value), so they are safe before next is known to be in range, and the
    # look-ups after the loop show that it is (deleted-reference of next).
    for start in range(0, n_h, _BLOCK):                       # start and block length are even
        block = slice(start, start + _BLOCK)
        h_next, h_prev, h_face, h_origin = nxt[block], prv[block], face[block], origin[block]
        # deleted-reference of face, on the block while it is in the cache. Read as
        # unsigned, -1 is the largest value (_all_below), so one reduction says both
        # "every face in range" and "no boundary halfedge here"; only a block with
        # boundary halfedges needs its smallest and largest value apart.
        closed = h_face.view(unsigned).max() < n_f
        if not closed and (h_face.min() < -1 or h_face.max() >= n_f):
            return False
        at_next = h_next.astype(np.intp)                      # numpy indexes with intp: convert once, not per gather
        if rows is None:
            next_prev = prv.take(at_next, mode="clip")
            next_origin = origin.take(at_next, mode="clip")
            next_face = face.take(at_next, mode="clip")
            next_next = nxt.take(at_next, mode="clip")
        else:
            next_prev, next_origin, next_face, next_next = (
                np.ascontiguousarray(column) for column in rows.take(at_next, axis=0, mode="clip").T)
        # An edge's two halfedges 2e and 2e + 1 sit side by side, so their two int32
        # values read as one 64-bit word (_edge_words): one comparison checks both, and
        # swapping the word's halves swaps the two, giving each halfedge its twin's value.
        h = np.arange(start, start + len(h_next), dtype=h_next.dtype)
        own_origin = _edge_words(h_origin)                    # (k/2,)
        tip = (own_origin << 32) | (own_origin >> 32)         # (k/2,) the twins' origins: where each halfedge ends
        if (own_origin == tip).any():                         # twin-involution
            return False
        ok = _edge_words(next_prev) == _edge_words(h)         # next-prev-inverse
        ok &= _edge_words(next_origin) == tip                 # next-origin: next starts where h ends
        ok &= _edge_words(next_face) == _edge_words(h_face)   # next-cycle: same face (or both boundary)
        # next-cycle, a triangle: next(next(h)) == prev(h) makes the loop 3 long or 1, and
        # it is not 1: next(h) == h would start where h ends, at h's own origin, which
        # next-origin and twin-involution have ruled out.
        if closed:
            ok &= _edge_words(next_next) == _edge_words(h_prev)
        else:
            on_boundary = h_face < 0
            if not (on_boundary | (next_next == h_prev)).all():
                return False
            # edge-halfedge: an edge is faceless when both its faces are -1, that is when
            # both sign bits are set, which is the sign bit of their bitwise and.
            if ((h_face[0::2] & h_face[1::2]) < 0).any():
                return False
            if on_boundary.any():
                boundary.append(np.flatnonzero(on_boundary) + start)
        if not ok.all():
            return False

    # ---- deleted-reference of next and prev -----------------------------------------------
    # The loop has checked prev(clip(next(h))) == h for every h, with clip() moving an
    # index out of range to 0 or n_h - 1. So clip(next()) is one-to-one, a permutation
    # of the halfedges, and prev its inverse: every prev is one of 0 .. n_h - 1. A next
    # out of range would have been clipped to 0 or n_h - 1, and the one halfedge whose
    # clipped next is 0 is prev(0) (likewise for n_h - 1): two look-ups check both.
    for end in {0, n_h - 1} if n_h else ():
        if int(nxt[prv[end]]) != end:
            return False

    # ---- face-halfedge ------------------------------------------------------------------
    # (The face numbers to compare with are made in face's own type: comparing int32
    # with int64 would convert every value first, 1.3x the time of the loop.)
    for start in range(0, n_f, _BLOCK):                       # in blocks: no temporaries as long as the mesh
        f_he = face_he[start:start + _BLOCK]
        if not np.array_equal(face.take(f_he, mode="clip"), np.arange(start, start + len(f_he), dtype=face.dtype)):
            return False

    # ---- boundary-vertex-halfedge, and no boundary that turns back ------------------------
    if boundary:
        boundary_he = np.concatenate(boundary)                # (b,) every boundary halfedge
        boundary_origin = origin[boundary_he]
        # Each boundary halfedge is its origin's halfedge: boundary-vertex-halfedge, and
        # (a vertex has one halfedge) at most one boundary halfedge leaves a vertex,
        # the part of vertex-manifold that the walk cannot see (_one_piece_of_boundary).
        # (origin is shown to be in range only by the walk below: until then, clip.)
        if not np.array_equal(np.take(vertex_he, boundary_origin, mode="clip"), boundary_he):
            return False
        # A boundary that runs u -> v -> u runs along two edges between u and v (the
        # twin of a boundary halfedge has a face, so the way back is another edge): a
        # duplicate edge that the fan walk below does not look for.
        if (origin[nxt[boundary_he] ^ 1] == boundary_origin).any():
            return False

    # ---- vertex-halfedge-origin, vertex-manifold, duplicate-edge ----------------------------
    return _fans_hold(mesh, rows)


def _side_by_side(*columns: np.ndarray) -> np.ndarray:
    """(n, len(columns)) the equally long ``columns`` (n,) as the columns of one array, one row per index.

    What ``np.stack(columns, axis=1)`` returns, written a block of rows at a time:
    ``np.stack`` writes one whole column after the other, so each row's cache line is
    fetched from memory and written back once per column (four times for four columns,
    120 MiB of rows at 1.3M faces each time); block by block, a block's rows stay in
    the cache until all their columns are in. Measured on the shuffled 1.3M-face
    icosphere: 0.72x the CPU time of ``np.stack`` (medians of 15, taking turns).
    """
    n = len(columns[0])
    rows = np.empty((n, len(columns)), dtype=np.result_type(*columns))
    for start in range(0, n, _COPY_BLOCK):
        block = rows[start:start + _COPY_BLOCK]              # (b, len(columns)), a view
        for j, column in enumerate(columns):
            block[:, j] = column[start:start + _COPY_BLOCK]
    return rows


def _all_below(values: np.ndarray, size: int) -> bool:
    """True when every one of ``values`` (a signed integer array) is in ``0 .. size - 1``.

    One reduction instead of a min and a max: read as unsigned integers of the same
    width, negative values become huge (-1 is 2**32 - 1 in 32 bits), so the largest
    value is below ``size`` exactly when all of them are in range.
    """
    if len(values) == 0:
        return True
    return int(values.view(np.dtype(f"u{values.itemsize}")).max()) < size


def _edge_words(values: np.ndarray) -> np.ndarray:
    """(k/2,) the int32 ``values`` (k,) of halfedges ``2i, 2i + 1, ...`` read in pairs as 64-bit words.

    Word ``i`` holds the values of halfedges 2i and 2i + 1 (which half is which depends
    on the machine's byte order, but equal words mean equal pairs either way).
    Attention: ``values`` must be contiguous in memory (:func:`_every_rule_holds` makes
    sure of it), which a view as another type needs.
    """
    return values.view(np.uint64)


def _jumps_far(nxt: np.ndarray) -> bool:
    """True when over a quarter of the ``next`` pointers (one in 64, sampled) jump :data:`_FAR` or more."""
    sample = nxt[::64].astype(np.int64)                       # (n_h / 64,)
    sample -= np.arange(0, len(nxt), 64)
    return bool(np.count_nonzero(np.abs(sample) >= _FAR) * 4 > len(sample))


def _fans_hold(mesh: "HalfedgeMesh", rows: np.ndarray | None) -> bool:
    """vertex-halfedge-origin, then vertex-manifold and duplicate-edge in one walk round every vertex.

    Call it only once the pointer rules hold (next-prev-inverse, next-origin, next-cycle,
    twin-involution, edge-halfedge, no boundary turning back, and all pointers in range
    but ``origin``, which the walk itself shows to be in range: see the end).
    ``rows`` (n_h, 4), if given, holds prev, origin, face and next of each halfedge side
    by side (one cache line per halfedge read, see :func:`_every_rule_holds`).

    The walk goes round each vertex by h -> next(twin(h)): ``twin(h)`` comes into the
    vertex, its next leaves it again. That is the inverse of validate's h -> twin(prev(h))
    (next(twin(twin(prev(h)))) = h), so it goes round the same fans the other way, and
    it reads ``origin`` and ``next`` at one place, ``twin(h)``: the neighbour ``h`` leads
    to and the next halfedge round the vertex. All vertices of a block walk in lockstep.

    * vertex-manifold: the walks together must meet every halfedge (the rotation keeps
      each halfedge's origin, so a walk never leaves its vertex).
    * duplicate-edge: two edges between ``v`` and ``u`` are two halfedges leaving ``v``
      towards the same neighbour ``u``, so each neighbour met is compared with the ones
      met before. Not with the one just before it: two halfedges one step apart round
      ``v`` have a face between them, and a triangle's corners are distinct (next-origin
      and twin-involution), or the boundary between them, which does not turn back
      (checked before the walk). The same holds for the last and the first, which are
      compared all the same (simpler than leaving that one pair out). Vertices with
      more than :data:`_PAIRWISE_STEPS` edges finish their walks apart and sort their
      neighbours instead.
    """
    nxt, origin, vertex_he = mesh.halfedge_next, mesh.halfedge_vertex, mesh.vertex_halfedge
    n_v, n_h = mesh.n_vertex_slots, mesh.n_halfedge_slots

    def neighbour_and_following(h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """For halfedges ``h`` leaving some vertices: where each ends, and the next one round its vertex."""
        twin = h ^ 1
        if rows is None:
            return origin.take(twin, mode="clip"), nxt.take(twin, mode="clip")   # in range: see above
        row = rows.take(twin, axis=0, mode="clip")            # (k, 4) prev, origin, face, next
        return row[:, 1], row[:, 3]

    # vertex-halfedge-origin: each vertex's halfedge leaves it (so no two vertices share one).
    if not np.array_equal(np.take(origin, vertex_he, mode="clip"), np.arange(n_v, dtype=origin.dtype)):
        return False
    # The walks start at the vertices' halfedges taken in ascending order, not in the
    # order of the vertices: a vertex's number says nothing about where its halfedges
    # are stored, and walks taken vertex by vertex jump about the halfedge arrays. At
    # 1.3M faces as generated the walks take 0.91-0.92x the CPU time in this order,
    # the sort (3 ms) included (medians of 31, taking turns).
    starts = np.sort(vertex_he).astype(np.intp)               # (n_v,)

    met = 0                                                   # halfedges the walks have met so far
    for first in range(0, n_v, _VERTEX_BLOCK):
        start = starts[first:first + _VERTEX_BLOCK]           # (k,)
        current, walking, n_walking = start, np.ones(len(start), dtype=bool), len(start)
        neighbours = np.empty((_PAIRWISE_STEPS, len(start)), dtype=origin.dtype)   # row = step: the neighbour met
        for step in range(_PAIRWISE_STEPS):
            met += n_walking
            neighbours[step], following = neighbour_and_following(current)
            if step >= 2:                                     # met before, not counting the step just before?
                met_before = neighbours[:step - 1] == neighbours[step]   # (step - 1, k)
                if n_walking < len(start):
                    met_before &= walking                     # a finished walk goes round again: ignore it
                if met_before.any():
                    return False
            current = following.astype(np.intp)
            walking &= current != start                       # back at the start: that walk is done
            n_walking = int(np.count_nonzero(walking))
            if n_walking == 0:
                break
        else:
            still = np.flatnonzero(walking)
            steps = _finish_walks_by_sorting(still, start[still], current[still],
                                             list(neighbours[:, still]), neighbour_and_following, n_v)
            if steps is None:
                return False
            met += steps
    # deleted-reference of origin: every halfedge has a vertex in range. The rotation
    # keeps each halfedge's origin (next-origin and twin-involution), so a walk meets
    # only halfedges with its start's origin, which is its own vertex v (checked before
    # the walks, with v in range); two vertices' walks therefore never meet the same
    # halfedge, and walks that meet n_h halfedges between them have met every one.
    return met == n_h


def _finish_walks_by_sorting(owner: np.ndarray, start: np.ndarray, current: np.ndarray,
                             neighbours: list[np.ndarray], neighbour_and_following, n_v: int) -> int | None:
    """Finish the walks of the vertices with many edges; None if one meets a neighbour twice.

    ``owner``, ``start``, ``current`` (k,): which walk, where it began, where it is now;
    ``neighbours``: the neighbours each has met so far, one (k,) array per step. Returns
    how many more halfedges the walks met. Every neighbour of a vertex gets the key
    ``owner * n_v + neighbour``; after a sort, a repeated key is a repeated neighbour.
    """
    owners = [owner] * len(neighbours)
    steps = 0
    while len(current):
        steps += len(current)
        neighbour, following = neighbour_and_following(current)
        owners.append(owner)
        neighbours.append(neighbour)
        current = following.astype(np.intp)
        walking = current != start
        owner, start, current = owner[walking], start[walking], current[walking]
    key = np.concatenate(owners).astype(np.int64) * n_v + np.concatenate(neighbours)
    key.sort()
    if (key[1:] == key[:-1]).any():
        return None
    return steps


def _no_duplicate_edges(origin: np.ndarray, edges: np.ndarray | None, n_v: int) -> None:
    """duplicate-edge: no two of ``edges`` (edge indices, None for all) join the same two vertices."""
    ends = origin.reshape(-1, 2)
    if edges is not None:
        ends = ends[edges]
    key = np.sort(undirected_keys(ends[:, 0], ends[:, 1], n_v))
    repeated = _first(key[1:] == key[:-1], None)
    if repeated is not None:
        a, b = divmod(int(key[repeated]), n_v)
        raise MeshInvariantError(
            "duplicate-edge",
            ("edge", (a, b)),
            f"vertices {a} and {b} are joined by two different edges; a triangle mesh has "
            f"at most one edge between two vertices",
        )


def validate_around(mesh: "HalfedgeMesh", vertices=(), halfedges=(), edges=(), faces=()) -> None:
    """Check every rule of :func:`validate` (but deletion-count) near some elements only.

    Args:
        mesh: the mesh to check; it is not changed.
        vertices, halfedges, edges, faces: what an operation touched (indices or handles,
            any iterable). Deleted ones are skipped: an operation that removed them has
            nothing left there to check.

    Raises:
        MeshInvariantError: for the first broken rule found, as :func:`validate` does.
        MeshInputError: an element index that is not a slot of the mesh.

    The touched elements' corners, the one-ring of every touched vertex, and the ring of
    every vertex in those rings are checked: every halfedge that leaves or enters one of
    the touched vertices or their neighbours, with its face and edge. That is every
    element whose pointers a flip, split or collapse writes, and every element those
    pointers can reach in one step. The cost grows with the size of those rings only,
    not with the mesh: on a million-face mesh it is about a thousand times less than
    :func:`validate`. Deletion-count compares flags with counters of the whole mesh, so
    only :func:`validate` checks it.
    """
    seed_vertices = _seeds(vertices, mesh.n_vertex_slots, "vertex")
    seed_faces = _seeds(faces, mesh.n_face_slots, "face")
    seed_edges = _seeds(edges, mesh.n_edge_slots, "edge")
    seed_halfedges = np.concatenate([
        _seeds(halfedges, mesh.n_halfedge_slots, "halfedge"), 2 * seed_edges, 2 * seed_edges + 1])
    seed_vertices = seed_vertices[~mesh.vertex_deleted[seed_vertices]]
    seed_faces = seed_faces[~mesh.face_deleted[seed_faces]]
    seed_halfedges = seed_halfedges[~mesh.edge_deleted[seed_halfedges >> 1]]

    # The touched halfedges, with the faces' and vertices' own halfedges and each
    # one's next and prev: a face's three corners are then among their origins.
    edge_deleted = _EdgeFlagsAsHalfedges(mesh.edge_deleted)
    n_h = mesh.n_halfedge_slots
    face_he = mesh.face_halfedge[seed_faces]
    _check_pointer(face_he, n_h, edge_deleted, "face", seed_faces, "halfedge", "halfedge")
    vertex_he = mesh.vertex_halfedge[seed_vertices]
    _check_pointer(vertex_he, n_h, edge_deleted, "vertex", seed_vertices, "halfedge", "halfedge")
    touched = np.concatenate([seed_halfedges, face_he, vertex_he])
    touched = np.concatenate([touched, _follow(mesh, touched, "next"), _follow(mesh, touched, "prev")])
    centres = np.union1d(seed_vertices, _follow(mesh, np.concatenate([touched, touched ^ 1]), "vertex"))

    # Two rings deep: the touched vertices' rings, then the rings of their neighbours.
    ring = _walk_around(mesh, centres)
    neighbours = np.setdiff1d(_follow(mesh, ring ^ 1, "vertex"), centres)
    walked = np.concatenate([centres, neighbours])
    ring = np.concatenate([ring, _walk_around(mesh, neighbours)])

    hs = np.unique(np.concatenate([touched, ring, ring ^ 1]))
    face_of = mesh.halfedge_face[hs]
    fs = np.union1d(seed_faces, face_of[face_of >= 0])
    vs = np.union1d(walked, mesh.halfedge_vertex[hs])
    _element_rules(mesh, hs, vs, fs, check_deleted=True)

    # ---- vertex-manifold, around the walked vertices ---------------------------------
    # Every checked halfedge that leaves a walked vertex must be met by that vertex's walk.
    origin = mesh.halfedge_vertex
    leaving_walked = hs[np.isin(origin[hs], walked)]
    missed = leaving_walked[~np.isin(leaving_walked, ring)]
    if len(missed):
        h = int(missed[0])
        v = int(origin[h])
        raise MeshInvariantError(
            "vertex-manifold",
            ("vertex", v),
            f"walking around vertex {v} from its halfedge (h -> twin(prev(h))) comes back "
            f"without meeting halfedge {h}, which also leaves it; its faces form more than "
            f"one fan (an hourglass)",
        )
    _one_piece_of_boundary(mesh, hs[mesh.halfedge_face[hs] < 0])

    # ---- duplicate-edge, among the checked edges ----------------------------------------
    _no_duplicate_edges(origin, np.unique(hs >> 1), mesh.n_vertex_slots)


def _seeds(elements, n_slots: int, kind: str) -> np.ndarray:
    """The indices of ``elements`` (ints or handles) as an int64 array, each a slot of the mesh."""
    indices = np.array([int(element) for element in elements], dtype=np.int64)
    outside = (indices < 0) | (indices >= n_slots)
    if outside.any():
        index = int(indices[np.argmax(outside)])
        raise MeshInputError(f"{kind} {index} is not in the mesh (it has {n_slots} {kind} slots)",
                             element=(kind, index))
    return indices


def _follow(mesh: "HalfedgeMesh", halfedges: np.ndarray, field: str) -> np.ndarray:
    """The ``next``, ``prev`` or ``vertex`` of each of ``halfedges``, each checked before use."""
    if field == "vertex":
        values, size, deleted, kind = mesh.halfedge_vertex[halfedges], mesh.n_vertex_slots, mesh.vertex_deleted, "vertex"
    else:
        pointers = mesh.halfedge_next if field == "next" else mesh.halfedge_prev
        values, size, deleted, kind = (pointers[halfedges], mesh.n_halfedge_slots,
                                       _EdgeFlagsAsHalfedges(mesh.edge_deleted), "halfedge")
    _check_pointer(values, size, deleted, "halfedge", halfedges, field, kind)
    return values


def _walk_around(mesh: "HalfedgeMesh", vertices: np.ndarray) -> np.ndarray:
    """Walk h -> twin(prev(h)) around each vertex, checking every pointer before it is followed.

    Returns the halfedges met, all walks together. A walk stops when it is back at its start, when it reaches a halfedge that does
    not leave its vertex (the rules that follow name the broken pointer), or when it goes
    round a loop that misses its start, which is reported here.
    """
    origin = mesh.halfedge_vertex
    start = mesh.vertex_halfedge[vertices]
    _check_pointer(start, mesh.n_halfedge_slots, _EdgeFlagsAsHalfedges(mesh.edge_deleted),
                   "vertex", vertices, "halfedge", "halfedge")
    # One row per walk: (vertex, halfedge it is at, halfedge it started from), so that
    # dropping the walks that end is one indexing call, not three.
    walks = np.stack([vertices, start, start]).astype(np.int64)   # (3, k)
    owners, met = [vertices], [start]
    steps = 0
    while walks.shape[1]:
        walks[1] = _follow(mesh, walks[1], "prev") ^ 1
        walks = walks[:, walks[1] != walks[2]]                     # back at the start: that walk is done
        owners.append(walks[0])
        met.append(walks[1])                # kept even if it leaves another vertex: the rules name it
        walks = walks[:, origin[walks[1]] == walks[0]]             # a halfedge leaving another vertex ends it
        steps += 1
        if steps & (steps - 1) == 0 and steps >= 64:      # now and then: is a walk going round in a loop?
            _no_walk_in_a_loop(np.concatenate(owners), np.concatenate(met), mesh.n_halfedge_slots)
    return np.concatenate(met)


def _no_walk_in_a_loop(owner: np.ndarray, met: np.ndarray, n_h: int) -> None:
    """vertex-manifold: raise if some walk has met a halfedge twice (it goes round a loop)."""
    key = np.sort(owner * n_h + met)
    repeated = _first(key[1:] == key[:-1], None)
    if repeated is not None:
        v = int(key[repeated]) // n_h
        raise MeshInvariantError(
            "vertex-manifold",
            ("vertex", v),
            f"walking around vertex {v} from its halfedge (h -> twin(prev(h))) goes round a "
            f"loop that never comes back to the start; prev pointers around it are broken",
        )

def _check_pointer(values: np.ndarray, size: int, deleted, owner_kind: str, owner_indices,
                   field: str, target_kind: str, allow_none: bool = False) -> None:
    """deleted-reference: raise unless every pointer in ``values`` names a live element.

    ``deleted`` looks up "is it deleted?" for whole index arrays, or None when nothing
    can be deleted; ``owner_indices`` says whose pointers ``values`` are (None: slot i).
    """
    # Fast path: two reductions say "all in range" without building a mask, and one
    # gather of the deleted flags says "none deleted". Only a broken pointer takes the
    # masks below, which find the first one. validate_around calls this about 30 times
    # on a few hundred values, so the number of numpy calls is what it costs.
    if len(values) == 0:
        return
    if values.min() >= (-1 if allow_none else 0) and values.max() < size:
        if deleted is None:
            return
        pointed_at = values[values >= 0] if allow_none else values
        if not deleted[pointed_at].any():
            return
    in_range = (values >= 0) & (values < size)
    bad = ~in_range
    if allow_none:
        bad &= values != -1
    if deleted is not None:
        bad |= in_range & deleted[np.where(in_range, values, 0)]
    owner = _first(bad, owner_indices)
    if owner is not None:
        value = int(values[np.argmax(bad)])
        state = "does not exist" if not (0 <= value < size) else "was deleted"
        raise MeshInvariantError(
            "deleted-reference",
            (owner_kind, owner),
            f"{owner_kind} {owner}: its {field} is {target_kind} {value}, which {state}; "
            f"a live element may only point at live elements",
        )


def _element_rules(mesh: "HalfedgeMesh", hs: np.ndarray | None, vs: np.ndarray | None,
                   fs: np.ndarray | None, check_deleted: bool) -> None:
    """Every rule from deleted-reference to boundary-vertex-halfedge, on chosen elements.

    ``hs``, ``vs``, ``fs``: the halfedges, vertices and faces to check (sorted index
    arrays), or all three None for every slot. ``check_deleted``: whether pointers may
    lead to deleted elements (False only when the mesh has none, which saves a gather).
    Pointers of the checked elements are followed only after they are checked.
    """
    n_v, n_h, n_f = mesh.n_vertex_slots, mesh.n_halfedge_slots, mesh.n_face_slots
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    vertex_he, face_he = mesh.vertex_halfedge, mesh.face_halfedge
    vertex_deleted, face_deleted = mesh.vertex_deleted, mesh.face_deleted
    edge_deleted = mesh.edge_deleted
    if hs is None:
        h_next, h_prev, h_origin, h_face = nxt, prv, origin, face
        v_he, f_he = vertex_he, face_he
    else:
        h_next, h_prev, h_origin, h_face = nxt[hs], prv[hs], origin[hs], face[hs]
        v_he, f_he = vertex_he[vs], face_he[fs]
    h_index = np.arange(n_h) if hs is None else hs

    # ---- deleted-reference ------------------------------------------------------------
    def check_pointer(values, size, deleted, owner_kind, owner_indices, field, target_kind, allow_none=False):
        _check_pointer(values, size, deleted if check_deleted else None, owner_kind, owner_indices,
                       field, target_kind, allow_none)

    halfedge_deleted = _EdgeFlagsAsHalfedges(edge_deleted)
    check_pointer(h_next, n_h, halfedge_deleted, "halfedge", hs, "next", "halfedge")
    check_pointer(h_prev, n_h, halfedge_deleted, "halfedge", hs, "prev", "halfedge")
    check_pointer(h_origin, n_v, vertex_deleted, "halfedge", hs, "vertex", "vertex")
    check_pointer(h_face, n_f, face_deleted, "halfedge", hs, "face", "face", allow_none=True)
    check_pointer(f_he, n_h, halfedge_deleted, "face", fs, "halfedge", "halfedge")
    _refuse(_first(v_he == -1, vs), "vertex-halfedge-origin", "vertex", lambda orphan: (
        f"vertex {orphan} has no halfedge, but halfedge {int(np.argmax(origin == orphan))} leaves it; "
        f"a vertex that edges use must point at one of its outgoing halfedges"))
    check_pointer(v_he, n_h, halfedge_deleted, "vertex", vs, "halfedge", "halfedge")

    # ---- next-prev-inverse ------------------------------------------------------------
    # Checking prev(next(h)) == h for every h is enough: it makes `next` one-to-one, so a
    # permutation, and `prev` its inverse; next(prev(h)) == h then follows.
    _refuse(_first(prv[h_next] != h_index, hs), "next-prev-inverse", "halfedge", lambda h: (
        f"halfedge {h}: next is {int(nxt[h])} but that halfedge's prev is {int(prv[nxt[h]])}, "
        f"not {h}; next and prev must undo each other"))

    # ---- twin-involution --------------------------------------------------------------
    h_tip = origin[h_index ^ 1]
    _refuse(_first(h_origin == h_tip, hs), "twin-involution", "halfedge", lambda h: (
        f"halfedge {h} and its twin {h ^ 1} both start at vertex {int(origin[h])}; "
        f"twins must run in opposite directions along edge {h >> 1}"))

    # ---- next-origin ------------------------------------------------------------------
    _refuse(_first(origin[h_next] != h_tip, hs), "next-origin", "halfedge", lambda h: (
        f"halfedge {h} ends at vertex {int(origin[h ^ 1])}, but its next ({int(nxt[h])}) "
        f"starts at vertex {int(origin[nxt[h]])}; next must start where the halfedge ends"))

    # ---- next-cycle -------------------------------------------------------------------
    interior = h_face >= 0
    next_face = face[h_next]
    _refuse(_first(interior & (next_face != h_face), hs), "next-cycle", "halfedge", lambda h: (
        f"halfedge {h} is in face {int(face[h])} but its next ({int(nxt[h])}) is in "
        f"face {int(face[nxt[h]])}; a face's halfedges must all belong to it"))
    _refuse(_first(~interior & (next_face != -1), hs), "next-cycle", "halfedge", lambda h: (
        f"boundary halfedge {h}'s next ({int(nxt[h])}) is inside face {int(face[nxt[h]])}; "
        f"the next of a boundary halfedge must continue along the boundary"))
    # With prev the inverse of next, next(next(h)) == prev(h) says next^3(h) == h; with
    # next(h) != h the loop has exactly three halfedges.
    not_a_triangle = interior & ((nxt[h_next] != h_prev) | (h_next == h_index))
    _refuse(_first(not_a_triangle, hs), "next-cycle", "halfedge", lambda h: (
        f"halfedge {h}: next->next->next is {int(nxt[nxt[nxt[h]]])}, not {h}, so face "
        f"{int(face[h])} is not a loop of three halfedges (a triangle)"))

    # ---- face-halfedge ----------------------------------------------------------------
    elsewhere = face[f_he] != (np.arange(n_f) if fs is None else fs)
    _refuse(_first(elsewhere, fs), "face-halfedge", "face", lambda f: (
        f"face {f}'s halfedge is {int(face_he[f])}, which belongs to face "
        f"{int(face[face_he[f]])}; a face's halfedge must lie in that face"))

    # ---- edge-halfedge ----------------------------------------------------------------
    if hs is None:
        faceless = np.maximum(face[0::2], face[1::2]) < 0     # (n_edge_slots,)
        edge_index = None
    else:
        edge_index = np.unique(hs >> 1)
        faceless = np.maximum(face[2 * edge_index], face[2 * edge_index + 1]) < 0
    _refuse(_first(faceless, edge_index), "edge-halfedge", "edge", lambda e: (
        f"edge {e} (vertices {int(origin[2 * e])} and {int(origin[2 * e + 1])}) has no face "
        f"on either side; every edge must border at least one face"))

    # ---- vertex-halfedge-origin -------------------------------------------------------
    leaves_another = origin[v_he] != (np.arange(n_v) if vs is None else vs)
    _refuse(_first(leaves_another, vs), "vertex-halfedge-origin", "vertex", lambda v: (
        f"vertex {v}'s halfedge is {int(vertex_he[v])}, which starts at vertex "
        f"{int(origin[vertex_he[v]])}; a vertex's halfedge must leave that vertex"))

    # ---- boundary-vertex-halfedge -----------------------------------------------------
    boundary_origins = h_origin[~interior]
    v = _first(face[vertex_he[boundary_origins]] >= 0, boundary_origins)
    if v is not None:
        b = int((h_index[~interior])[np.argmax(face[vertex_he[boundary_origins]] >= 0)])
        raise MeshInvariantError(
            "boundary-vertex-halfedge",
            ("vertex", v),
            f"vertex {v} is on the boundary (boundary halfedge {b} leaves it) but its halfedge "
            f"{int(vertex_he[v])} is an interior one; a boundary vertex must point at its "
            f"outgoing boundary halfedge",
        )



class _EdgeFlagsAsHalfedges:
    """Looks up "is halfedge h deleted?" as ``edge_deleted[h >> 1]`` for whole arrays."""

    def __init__(self, edge_deleted: np.ndarray):
        self._edge_deleted = edge_deleted

    def __getitem__(self, halfedges: np.ndarray) -> np.ndarray:
        return self._edge_deleted[halfedges >> 1]
