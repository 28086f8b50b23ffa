"""The fast pass of ``validate()``: "does every rule hold?" in a few passes over memory.

You never need to read this file to learn the rules. They are in
:mod:`halfedge_edu.core.validate`, one rule at a time, each naming the element that
breaks it; this file is the engine beside that lecture. :func:`every_rule_holds`
answers one question, True or False, for a mesh whose slots are all live, and
:func:`~halfedge_edu.core.validate.validate` asks it first: a sound mesh (the common
case) is done after this pass, and only on False do the rule-by-rule checks run, to
say which rule broke and where. Its True is believed: a broken mesh it passed would
go unreported, and that is what the tests below rule out.

How it gets its speed: blocks of halfedges small enough that a block's temporaries stay
in the core's own cache while every rule reads them; an edge's two int32 values read
as one 64-bit word; rows of four values (prev, origin, face, next) side by side when
``next`` jumps about memory; one walk around every vertex for the manifold and
duplicate-edge rules instead of a sort of all edges. The measurements behind each
choice are in docs/performance.md ("validate's fast pass").

Pinned to the rules by the tests in ``tests/core/test_validate_fast.py``:

* ``test_the_fast_path_fails_exactly_when_a_rule_by_rule_check_fails`` (hypothesis):
  on random meshes with one pointer of any array overwritten (with another pointer's
  value, -1 or one past the end), this pass says "broken" exactly when the
  rule-by-rule checks name a broken rule;
* ``test_the_fast_path_agrees_with_the_rules_with_and_without_packed_rows``
  (hypothesis): the same, with the four values at ``next(h)`` read from separate
  arrays and from rows of four;
* one test for each shape the rules refuse that a random overwrite rarely makes
  (``test_parallel_edges_between_vertices_of_any_degree_are_found``,
  ``test_a_boundary_that_turns_back_along_a_second_edge_is_found``,
  ``test_a_vertex_on_two_pieces_of_boundary_is_not_manifold``,
  ``test_an_edge_between_two_boundaries_with_no_face_is_found_by_the_fast_path``,
  ``test_a_face_of_one_halfedge_on_a_loop_edge_fails_the_fast_path``,
  ``test_a_mesh_of_quads_fails_the_fast_path``) and for the edges of its blocks
  (``test_the_fast_path_checks_every_block_of_halfedges``,
  ``test_the_fan_walk_checks_every_block_of_walks``, ...), each checking that this
  pass refuses the mesh and that ``validate()`` then names the rule.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .mesh import HalfedgeMesh

__all__ = ["every_rule_holds"]


#: Halfedges checked per block in :func:`every_rule_holds`: a block's temporaries (a
#: dozen arrays of this many int32, 64 KiB each) stay in the core's own (L2) cache while
#: the rules read them; much smaller blocks lose that again to the Python overhead of
#: each block (docs/performance.md has the block sizes measured).
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
#: within the core's L2 cache.
_COPY_BLOCK = 1 << 16


def every_rule_holds(mesh: "HalfedgeMesh") -> bool:
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

    False means some rule is broken; :func:`~halfedge_edu.core.validate.validate` then
    runs the rules one by one to say which. A mesh with deleted or isolated elements
    never comes here.
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
    # method through two Python wrappers, and the loops make a few gathers per block.

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
    # with int64 would convert every value first.)
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
        # the part of vertex-manifold that the walk cannot see (validate's
        # _one_piece_of_boundary).
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
    fetched from memory and written back once per column (four times for four
    columns); block by block, a block's rows stay in the cache until all their columns
    are in.
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
    Attention: ``values`` must be contiguous in memory (:func:`every_rule_holds` makes
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
    by side (one cache line per halfedge read, see :func:`every_rule_holds`).

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
    # are stored, and walks taken vertex by vertex jump about the halfedge arrays; in
    # this order they read those arrays from start to end.
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

