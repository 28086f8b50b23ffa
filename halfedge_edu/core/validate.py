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

Reading order: :func:`validate`, then :func:`_element_rules` (the rules from
deleted-reference to boundary-vertex-halfedge, one block each, in the table's order),
then the vertex-manifold and duplicate-edge checks, then :func:`validate_around`. A
sound mesh with no deleted or isolated element never reaches the rules one by one:
:func:`validate` first asks :mod:`~halfedge_edu.core.validate_fast` (an engine you
never need to read, pinned to these rules by tests) whether every rule holds, and
runs the rules here only to name the one that does not.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from . import validate_fast
from .arrays import undirected_keys
from .errors import MeshInputError, MeshInvariantError
from .rings import ring_lengths

if TYPE_CHECKING:
    from .mesh import HalfedgeMesh


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

    # The common case, a mesh with every slot live: all rules at once, in a few passes
    # (validate_fast, an engine the tests pin to the rules below). Only if one of them
    # fails do the rules run one by one, to name the first broken rule and element.
    if not garbage and not isolated.any() and validate_fast.every_rule_holds(mesh):
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
    not with the mesh (docs/performance.md compares it with :func:`validate`).
    Deletion-count compares flags with counters of the whole mesh, so only
    :func:`validate` checks it.
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


class _EdgeFlagsAsHalfedges:
    """Looks up "is halfedge h deleted?" as ``edge_deleted[h >> 1]`` for whole arrays."""

    def __init__(self, edge_deleted: np.ndarray):
        self._edge_deleted = edge_deleted

    def __getitem__(self, halfedges: np.ndarray) -> np.ndarray:
        return self._edge_deleted[halfedges >> 1]
