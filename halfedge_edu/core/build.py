"""Building the halfedge structure from a list of triangles.

Two versions of the same construction live here:

* :func:`build_reference` is the loop from the course notes, one face and one corner
  at a time, written to be read.
* :func:`build_arrays` does exactly the same work with whole-array numpy operations,
  so that a 1.3-million-face mesh builds in about a quarter of a second.

The tests check that both give *identical* arrays, index for index. The numbering they
share is the one the course teaches:

* Faces keep their row order. Face ``f = [i, j, k]`` makes the halfedges
  ``(i, j)``, ``(j, k)``, ``(k, i)``, in that order.
* Edges are numbered in the order they are first seen. Edge ``e`` owns halfedges
  ``2e`` and ``2e + 1``, so the twin of ``h`` is ``h ^ 1`` and its edge is ``h >> 1``.
  The first time an edge is seen, as ``(a, b)``, that halfedge becomes ``2e``; the
  second time, as ``(b, a)``, it becomes the twin ``2e + 1``.
* An edge seen only once lies on the boundary: its halfedge ``2e + 1`` runs the other
  way with no face (``face == -1``), and the boundary halfedges are linked into loops.
* Each vertex's ``halfedge`` is its outgoing boundary halfedge if it has one (so a
  vertex knows it is on the boundary in O(1)), otherwise its outgoing halfedge with the
  smallest index.

Positions are not needed for any of this: topology comes from the faces alone.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .arrays import compact, face_halfedges, sort_undirected
from .errors import MeshInputError, MeshWarning, first_few
from .rings import ring_lengths

#: Integer type of every topology array. 32 bits hold 2 billion elements and halve the
#: memory of 64-bit indices, which matters at millions of faces.
INDEX = np.int32


@dataclass
class HalfedgeArrays:
    """The raw arrays of a halfedge mesh, as construction produces them.

    Shapes: ``positions`` (V, 3) float64; ``vertex_halfedge`` (V,);
    ``halfedge_next``, ``halfedge_prev``, ``halfedge_vertex``, ``halfedge_face`` (2E,);
    ``face_halfedge`` (F,). All index arrays are :data:`INDEX`; -1 means "none".
    """

    positions: np.ndarray
    vertex_halfedge: np.ndarray
    halfedge_next: np.ndarray
    halfedge_prev: np.ndarray
    halfedge_vertex: np.ndarray
    halfedge_face: np.ndarray
    face_halfedge: np.ndarray


# --------------------------------------------------------------------------------------
# Input checks shared by both builders
# --------------------------------------------------------------------------------------

def _where(face: int, face_lines: np.ndarray | None, source: str | None) -> str:
    """' (line 40 of bunny.obj)' for messages, when we know where a face came from."""
    if face_lines is None:
        return ""
    place = f"line {int(face_lines[face])}"
    return f" ({place} of {source})" if source else f" ({place})"


def _line(face: int, face_lines: np.ndarray | None) -> int | None:
    return None if face_lines is None else int(face_lines[face])


def real_array(values, what: str) -> np.ndarray:
    """``values`` as a fresh float64 array, refusing what would convert with a loss or by accident.

    Complex numbers (numpy would drop the imaginary part), booleans (True would become
    1.0) and strings (numpy would parse "1.5") raise :class:`MeshInputError` naming
    ``what``; so does anything numpy cannot turn into numbers at all.
    """
    try:
        array = np.asarray(values)
    except ValueError:
        raise MeshInputError(f"{what} must be an array of numbers, but its rows have different lengths") from None
    if array.dtype.kind in "cbUS" or (array.dtype.kind == "O" and any(
        isinstance(item, (complex, np.complexfloating, bool, np.bool_, str, bytes)) for item in array.flat
    )):
        raise MeshInputError(_not_real(array, what))
    try:
        return np.array(array, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise MeshInputError(f"{what} are not numbers: {error}") from None


def _not_real(array: np.ndarray, what: str) -> str:
    """The message for an array that :func:`real_array` refuses: what its values are instead."""
    if array.dtype.kind == "c" or any(isinstance(item, (complex, np.complexfloating)) for item in array.flat):
        return f"{what} must be real numbers, got complex numbers ({array.dtype}) whose imaginary parts would be lost"
    if array.dtype.kind == "b" or any(isinstance(item, (bool, np.bool_)) for item in array.flat):
        return f"{what} must be real numbers, got True/False values ({array.dtype})"
    return f"{what} are not numbers: got text ({array.dtype})"


def _face_index_array(faces) -> np.ndarray:
    """``faces`` as an (m, 3) array of whole numbers (any integer or float dtype), or an error."""
    try:
        face_array = np.asarray(faces)
    except ValueError:
        raise MeshInputError(
            "faces must be an (m, 3) array of vertex indices (triangles), but its rows have different lengths"
        ) from None
    if face_array.size == 0:
        return np.zeros((0, 3), dtype=INDEX)                   # no faces: the empty mesh
    if face_array.ndim != 2 or face_array.shape[1] != 3:
        if face_array.ndim == 2 and face_array.shape[1] < 3:
            raise MeshInputError(
                f"faces need at least 3 vertices each, got rows of {face_array.shape[1]}"
            )
        raise MeshInputError(
            f"faces must be an (m, 3) array of vertex indices (triangles), got shape {face_array.shape}"
        )
    if not np.issubdtype(face_array.dtype, np.integer):
        rounded = real_array(face_array, "face indices")
        if not np.all(np.isfinite(rounded)) or not np.all(rounded == np.round(rounded)):
            raise MeshInputError("face indices must be whole numbers")
    return face_array


def _check_face_lines(face_lines, n_faces: int, source) -> None:
    """Refuse ``face_lines`` that is not one whole line number per face, and a ``source`` that is not text."""
    if source is not None and not isinstance(source, str):
        raise MeshInputError(f"source must be a file name (str) or None, got {type(source).__name__}",
                             element=("argument", "source"))
    if face_lines is None:
        return
    lines = np.asarray(face_lines)
    if lines.shape != (n_faces,) or (n_faces and not np.issubdtype(lines.dtype, np.integer)):
        raise MeshInputError(
            f"face_lines must hold one whole line number per face: {n_faces} for {n_faces} faces, "
            f"got shape {lines.shape} of {lines.dtype}",
            element=("argument", "face_lines"),
        )


def check_input(
    vertices, faces, face_lines=None, source: str | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Check shapes, types, finiteness, index range and degenerate faces.

    Returns ``(positions (n, 3) float64, faces (m, 3) INDEX)`` as fresh arrays.
    Raises :class:`MeshInputError` naming the first offending vertex or face, or the
    argument (``element=("argument", name)``) when ``face_lines`` or ``source`` is unusable.

    No faces at all is allowed: it is the empty mesh, as in pmp-library, OpenMesh and
    trimesh (its vertices, if any, are then all unreferenced and dropped with a warning).
    """
    positions = real_array(vertices, "vertex positions")
    if positions.size == 0:
        positions = positions.reshape(0, 3)
    if positions.ndim != 2 or positions.shape[1] != 3:
        raise MeshInputError(
            f"vertices must be an (n, 3) array of positions, got shape {positions.shape}"
        )
    if not np.isfinite(positions).all():
        bad = int(np.flatnonzero(~np.isfinite(positions).all(axis=1))[0])
        raise MeshInputError(
            f"vertex {bad} has a coordinate that is not a finite number: {positions[bad].tolist()}",
            element=("vertex", bad),
        )

    face_array = _face_index_array(faces)
    _check_face_lines(face_lines, len(face_array), source)
    if len(face_array) == 0:
        return positions, face_array
    n_vertices = len(positions)
    if face_array.min() < 0 or face_array.max() >= n_vertices:
        out_of_range = (face_array < 0) | (face_array >= n_vertices)
        face, corner = (int(x) for x in np.argwhere(out_of_range)[0])
        raise MeshInputError(
            f"face {face}{_where(face, face_lines, source)} uses vertex index "
            f"{int(face_array[face, corner])}, but vertices are numbered 0 to {n_vertices - 1}",
            element=("face", face),
            line=_line(face, face_lines),
        )
    if n_vertices >= np.iinfo(INDEX).max // 2:
        raise MeshInputError(f"{n_vertices} vertices is more than this package's 32-bit indices hold")
    face_array = face_array.astype(INDEX)
    a, b, c = face_array.T
    repeated = (a == b) | (b == c) | (c == a)
    if repeated.any():
        face = int(np.flatnonzero(repeated)[0])
        raise MeshInputError(
            f"face {face}{_where(face, face_lines, source)} is degenerate: it repeats a vertex "
            f"{face_array[face].tolist()}",
            element=("face", face),
            line=_line(face, face_lines),
        )
    _refuse_pillows(face_array, n_vertices, face_lines, source)
    return positions, face_array


def _refuse_pillows(faces: np.ndarray, n_vertices: int, face_lines, source) -> None:
    """Raise if two faces use the same three vertices in opposite orders (a "pillow").

    Such a pair is glued along all three of its edges: a closed surface of two
    triangles that encloses nothing. It passes every halfedge rule, but it is not a
    simplicial surface (two faces on the same three vertices), and no algorithm can
    refine or simplify it: Loop subdivision would join two vertices by two edges. So it
    is refused here, naming both faces. (Two faces in the *same* order share directed
    edges, which :func:`build_arrays` reports; a pillow whose edges or corners touch
    other faces is non-manifold and reported there too.) Only faces whose three corners
    each have exactly two faces can form a lone pillow, so only those are compared, and
    only when there are three such vertices at all (most meshes have none).
    """
    two_faces = np.bincount(faces.ravel(), minlength=n_vertices) == 2    # (n,) vertices with exactly two
    if np.count_nonzero(two_faces) < 3:
        return
    candidates = np.flatnonzero(two_faces[faces].all(axis=1))           # (k,) usually none
    if len(candidates) < 2:
        return
    corners = faces[candidates]                                          # (k, 3)
    # A face's orientation is the parity of its corner order: rotations keep it, a swap flips it.
    parity = ((corners[:, 0] > corners[:, 1]).astype(int) + (corners[:, 1] > corners[:, 2])
              + (corners[:, 0] > corners[:, 2])) % 2                    # (k,)
    vertex_set = np.sort(corners, axis=1)                                # (k, 3)
    order = np.lexsort(vertex_set.T[::-1])
    same_set = (vertex_set[order][1:] == vertex_set[order][:-1]).all(axis=1)
    opposite = parity[order][1:] != parity[order][:-1]
    pairs = np.flatnonzero(same_set & opposite)
    if len(pairs) == 0:
        return
    f, g = sorted(int(candidates[order[k]]) for k in (pairs[0], pairs[0] + 1))
    raise MeshInputError(
        f"faces {f}{_where(f, face_lines, source)} and {g}{_where(g, face_lines, source)} use the same "
        f"three vertices {vertex_set[order[pairs[0]]].tolist()} in opposite orders: glued along all "
        f"three edges they form a closed two-triangle 'pillow' that encloses nothing, which no "
        f"algorithm can refine or simplify (Loop subdivision would join two vertices by two edges); "
        f"a mesh has at most one face on any three vertices, and repairing drops the second",
        element=("face", g),
        line=_line(g, face_lines),
    )


def drop_unreferenced(positions: np.ndarray, faces: np.ndarray, *, warn: bool = True):
    """Remove vertices no face uses, renumbering the faces to match.

    Returns ``(positions, faces, kept)`` where ``kept`` (n_kept,) lists the original
    index of each vertex that stayed. With ``warn``, a :class:`MeshWarning` names the
    vertices it drops (``hx.load(path, drop_unreferenced=True)`` asks for this).
    """
    used = np.zeros(len(positions), dtype=bool)
    used[faces.ravel().astype(np.intp)] = True                # (intp: numpy's own conversion is slower)
    if used.all():
        return positions, faces, np.arange(len(positions))
    if warn:
        dropped = np.flatnonzero(~used)
        shown = ", ".join(str(v) for v in dropped[:8]) + (", ..." if len(dropped) > 8 else "")
        warnings.warn(
            f"dropped {len(dropped)} unreferenced {'vertex' if len(dropped) == 1 else 'vertices'} "
            f"(no face uses {'it' if len(dropped) == 1 else 'them'}): {shown}",
            MeshWarning,
            stacklevel=3,
        )
    positions, faces, kept = compact(positions, faces)
    return positions, faces.astype(INDEX), kept


def restore_unreferenced(arrays: HalfedgeArrays, positions: np.ndarray, kept: np.ndarray) -> HalfedgeArrays:
    """Put the vertices no face uses back at their input indices, as isolated vertices.

    ``arrays`` was built from the compacted input (``positions[kept]``); the result
    numbers every vertex as the input did: vertex ``i`` of the file is vertex ``i`` of
    the mesh, as in pmp-library and OpenMesh, so ids can be compared with the file. An
    isolated vertex has no halfedge (``vertex_halfedge`` -1). Halfedge, edge and face
    numbers do not change.

    Args:
        arrays: built from ``positions[kept]`` and the renumbered faces.
        positions: (n, 3) every input vertex.
        kept: (n_kept,) the input index of each vertex of ``arrays``.
    """
    if len(kept) == len(positions):
        return arrays
    vertex_halfedge = np.full(len(positions), -1, dtype=INDEX)
    vertex_halfedge[kept] = arrays.vertex_halfedge
    return HalfedgeArrays(
        positions=np.ascontiguousarray(positions, dtype=np.float64),
        vertex_halfedge=vertex_halfedge,
        halfedge_next=arrays.halfedge_next,
        halfedge_prev=arrays.halfedge_prev,
        halfedge_vertex=kept.astype(INDEX)[arrays.halfedge_vertex],
        halfedge_face=arrays.halfedge_face,
        face_halfedge=arrays.face_halfedge,
    )


# --------------------------------------------------------------------------------------
# The reference construction (the course's loop)
# --------------------------------------------------------------------------------------

def build_reference(faces, n_vertices: int | None = None) -> HalfedgeArrays:
    """Build the halfedge arrays one face at a time, the way the course notes do.

    This is the readable version of :func:`build_arrays`; both produce identical arrays.
    It checks for edges with more than two faces and for inconsistent orientation,
    but leaves the rest of input checking to :func:`check_input`.

    Args:
        faces: (m, 3) vertex indices of triangles, counter-clockwise seen from outside.
        n_vertices: how many vertices there are (default: largest index + 1).

    Returns:
        The arrays, with ``positions`` all zero (topology needs no positions).
    """
    faces = [tuple(int(v) for v in face) for face in faces]
    if n_vertices is None:
        n_vertices = 1 + max(max(face) for face in faces)

    edge_of: dict[tuple[int, int], int] = {}     # (smaller, larger) vertex -> edge index
    origin: dict[int, int] = {}                  # halfedge -> the vertex it leaves
    face_of: dict[int, int] = {}                 # halfedge -> its face
    next_of: dict[int, int] = {}
    face_halfedge: list[int] = []

    for face_index, (i, j, k) in enumerate(faces):
        corner_halfedges = []
        for a, b in ((i, j), (j, k), (k, i)):
            key = (min(a, b), max(a, b))
            if key not in edge_of:
                edge_of[key] = len(edge_of)      # first time we see this edge
                h = 2 * edge_of[key]
            else:
                h = 2 * edge_of[key] + 1         # second time: this is the twin
                if h in origin:
                    raise MeshInputError(
                        f"edge {key} has more than two faces (face {face_index} is the third)",
                        element=("edge", key),
                    )
                if origin[h ^ 1] == a:
                    raise MeshInputError(
                        f"directed edge ({a}, {b}) is used by two faces: the faces are "
                        f"inconsistently oriented (face {face_index} is the second)",
                        element=("edge", key),
                    )
            origin[h] = a
            face_of[h] = face_index
            corner_halfedges.append(h)
        for position, h in enumerate(corner_halfedges):
            next_of[h] = corner_halfedges[(position + 1) % 3]
        face_halfedge.append(corner_halfedges[0])

    n_halfedges = 2 * len(edge_of)
    # Edges seen once: their second halfedge is a boundary halfedge running the other way.
    boundary = [h for h in range(1, n_halfedges, 2) if h not in origin]
    for h in boundary:
        interior = h ^ 1                          # runs a -> b inside its face
        origin[h] = origin[next_of[interior]]     # so the boundary twin starts at b
        face_of[h] = -1
    outgoing_boundary: dict[int, int] = {}
    for h in boundary:
        if origin[h] in outgoing_boundary:
            raise MeshInputError(
                f"vertex {origin[h]} is non-manifold: its faces form more than one fan "
                f"(it lies on two separate pieces of boundary)",
                element=("vertex", origin[h]),
            )
        outgoing_boundary[origin[h]] = h
    for h in boundary:
        tip = origin[h ^ 1]                       # the interior twin starts where h ends
        next_of[h] = outgoing_boundary[tip]

    vertex_halfedge = [-1] * n_vertices
    for h in range(n_halfedges):
        v = origin[h]
        if vertex_halfedge[v] == -1 or (h < vertex_halfedge[v]):
            vertex_halfedge[v] = h
    for v, h in outgoing_boundary.items():
        vertex_halfedge[v] = h

    prev_of = {n: h for h, n in next_of.items()}

    # Every vertex's faces must form one fan: walking counter-clockwise from its
    # halfedge (h -> twin(prev(h))) must meet all of its outgoing halfedges.
    outgoing_count = [0] * n_vertices
    for h in range(n_halfedges):
        outgoing_count[origin[h]] += 1
    for v in range(n_vertices):
        if vertex_halfedge[v] == -1:
            continue
        h, steps = vertex_halfedge[v], 0
        while True:
            steps += 1
            h = prev_of[h] ^ 1
            if h == vertex_halfedge[v] or steps > outgoing_count[v]:
                break
        if steps != outgoing_count[v]:
            raise MeshInputError(
                f"vertex {v} is non-manifold: its faces form more than one fan",
                element=("vertex", v),
            )
    as_array = lambda values: np.array(values, dtype=INDEX)  # noqa: E731 (local shorthand)
    return HalfedgeArrays(
        positions=np.zeros((n_vertices, 3)),
        vertex_halfedge=as_array(vertex_halfedge),
        halfedge_next=as_array([next_of[h] for h in range(n_halfedges)]),
        halfedge_prev=as_array([prev_of[h] for h in range(n_halfedges)]),
        halfedge_vertex=as_array([origin[h] for h in range(n_halfedges)]),
        halfedge_face=as_array([face_of[h] for h in range(n_halfedges)]),
        face_halfedge=as_array(face_halfedge),
    )


# --------------------------------------------------------------------------------------
# The vectorized construction
# --------------------------------------------------------------------------------------

def build_arrays(
    positions: np.ndarray,
    faces: np.ndarray,
    face_lines: np.ndarray | None = None,
    source: str | None = None,
    vertex_ids: np.ndarray | None = None,
) -> HalfedgeArrays:
    """Build the halfedge arrays with whole-array operations (no Python loop per face).

    ``positions`` (n, 3) and ``faces`` (m, 3) must already have passed
    :func:`check_input`, and every vertex must be used by a face. The numbering is the
    one described in the module docstring, identical to :func:`build_reference`.
    ``vertex_ids`` (n,), if given, is the caller's number of each vertex (the ``kept``
    of :func:`drop_unreferenced`); error messages use it, so that they name vertices
    the way the input numbered them.

    Raises:
        MeshInputError: an edge with more than two faces, a directed edge used twice
            (inconsistent orientation or a duplicated face), or a vertex whose faces form
            more than one fan. The message names the edge or vertex, the faces, and
            their file lines when ``face_lines`` is given.
    """
    n_vertices = len(positions)
    n_faces = len(faces)
    n_corners = 3 * n_faces
    name = _vertex_namer(vertex_ids)

    # Pass 1, the sort. Directed edge p = 3 * face + corner runs from tail[p] to head[p];
    # sorting by undirected key puts the uses of one edge next to each other, in the
    # order the faces used them. A run of two is an interior edge, a run of one a
    # boundary edge, a longer run is an error.
    corners = np.asarray(faces, dtype=INDEX)                  # (m, 3)
    tail, head = face_halfedges(corners)                      # (3m,) each
    order, sorted_key = sort_undirected(tail, head, n_vertices)
    same_as_next = sorted_key[1:] == sorted_key[:-1]          # (3m - 1,)
    del sorted_key
    if (same_as_next[1:] & same_as_next[:-1]).any():
        _raise_crowded_edge(order, same_as_next, tail, head, face_lines, source, name)
    pair_start = np.flatnonzero(same_as_next)                 # (P,) where each shared edge's run begins
    del same_as_next
    first_p = order[pair_start]                               # (P,) first use of each shared edge
    second_p = order[1:][pair_start]                          # (P,) second use (first_p < second_p)
    del order, pair_start

    # Pass 2, the numbering. Edges are numbered in order of first appearance: the
    # directed edges that are not a second use, taken in order, are exactly the first
    # sightings of each edge. A second use gets the twin of its first sighting.
    is_second = np.zeros(n_corners, dtype=bool)
    is_second[second_p] = True
    first_sighting = np.flatnonzero(~is_second)               # (E,) ascending
    del is_second
    n_edges = len(first_sighting)
    n_halfedges = 2 * n_edges
    halfedge = np.empty(n_corners, dtype=INDEX)               # (3m,) halfedge of each directed edge
    halfedge[first_sighting] = np.arange(0, n_halfedges, 2, dtype=INDEX)
    del first_sighting
    halfedge[second_p] = halfedge[first_p] + 1
    del first_p, second_p

    # Pass 3, the faces: each directed edge writes its halfedge's origin, face, next and
    # prev. Halfedges no face wrote keep face -1: they are the boundary.
    # (numpy indexes with intp: converting the halfedges once saves a conversion per write.
    # Every write below is one flat index array and one contiguous value array, numpy's
    # fast path: a column-permuted copy such as ``by_corner[:, [1, 2, 0]]`` comes out in
    # Fortran order, and scattering from it took twice as long at 1.3M faces.)
    write_at = halfedge.astype(np.intp)                       # (3m,) the halfedges, as indices
    halfedge_vertex = np.empty(n_halfedges, dtype=INDEX)
    halfedge_vertex[write_at] = tail                          # a directed edge leaves its tail
    del corners, tail, head
    halfedge_face = np.full(n_halfedges, -1, dtype=INDEX)
    halfedge_face[write_at] = np.repeat(np.arange(n_faces, dtype=INDEX), 3)   # (3m,) face of each
    # Around a face, the next of corner k is corner k + 1, and that of corner 2 is corner 0:
    # shift the halfedges by one, then put each face's first one after its last.
    neighbour = np.empty(n_corners, dtype=INDEX)              # (3m,) next, then prev, per corner
    neighbour[:-1] = halfedge[1:]
    neighbour[2::3] = halfedge[0::3]
    halfedge_next = np.empty(n_halfedges, dtype=INDEX)
    halfedge_next[write_at] = neighbour
    neighbour[1:] = halfedge[:-1]                             # the prev of corner k is corner k - 1,
    neighbour[0::3] = halfedge[2::3]                          # and that of corner 0 is corner 2
    face_halfedge = halfedge[0::3].copy()                     # (m,) the halfedge of corner 0
    del halfedge
    halfedge_prev = np.empty(n_halfedges, dtype=INDEX)
    halfedge_prev[write_at] = neighbour
    del neighbour, write_at

    # Pass 4, the boundary. An edge sighted once has no face on its halfedge 2e + 1,
    # which runs the other way: it starts where its interior twin ends.
    boundary = (2 * np.flatnonzero(halfedge_face[1::2] < 0) + 1).astype(INDEX)   # (B,) ascending
    interior_twin = boundary ^ 1
    halfedge_vertex[boundary] = halfedge_vertex[halfedge_next[interior_twin]]

    # Two faces on one edge must use it in opposite directions: the edge's two
    # halfedges must start at different vertices (one sequential pass over the pairs).
    edge_ends = halfedge_vertex.reshape(n_edges, 2)          # (E, 2) origin of 2e and 2e + 1
    if (edge_ends[:, 0] == edge_ends[:, 1]).any():
        _raise_same_direction(halfedge_vertex, halfedge_face, halfedge_next, n_vertices, face_lines, source, name)

    # Each boundary vertex must have exactly one outgoing boundary halfedge.
    boundary_origin = halfedge_vertex[boundary]
    count = np.bincount(boundary_origin, minlength=n_vertices)
    if (count > 1).any():
        vertex = int(np.flatnonzero(count > 1)[0])
        raise MeshInputError(
            f"vertex {name(vertex)} is non-manifold: its faces form more than one fan "
            f"(it lies on {int(count[vertex])} separate pieces of boundary)",
            element=("vertex", name(vertex)),
        )
    outgoing_boundary = np.full(n_vertices, -1, dtype=INDEX)
    outgoing_boundary[boundary_origin] = boundary
    # A boundary halfedge ends where its interior twin starts; the loop continues with
    # the boundary halfedge that leaves that vertex.
    halfedge_next[boundary] = outgoing_boundary[halfedge_vertex[interior_twin]]
    # Each boundary vertex has as many boundary halfedges coming in as going out (one),
    # so these loops are closed, and each boundary halfedge is the prev of its next.
    halfedge_prev[halfedge_next[boundary]] = boundary

    # Pass 5, the vertices. A vertex's halfedge is its smallest outgoing index,
    # overridden by its boundary halfedge.
    every_halfedge = np.arange(n_halfedges, dtype=INDEX)      # (2E,)
    vertex_halfedge = np.full(n_vertices, np.iinfo(INDEX).max, dtype=INDEX)
    np.minimum.at(vertex_halfedge, halfedge_vertex, every_halfedge)
    vertex_halfedge[boundary_origin] = boundary

    arrays = HalfedgeArrays(
        positions=positions,
        vertex_halfedge=vertex_halfedge,
        halfedge_next=halfedge_next,
        halfedge_prev=halfedge_prev,
        halfedge_vertex=halfedge_vertex,
        halfedge_face=halfedge_face,
        face_halfedge=face_halfedge,
    )
    _check_single_fans(arrays, name)
    return arrays


def _vertex_namer(vertex_ids: np.ndarray | None):
    """``name(v)``: the number the caller gave vertex ``v`` (for messages)."""
    if vertex_ids is None:
        return int
    return lambda v: int(vertex_ids[v])


def _raise_crowded_edge(order, same_as_next, tail, head, face_lines, source, name=int):
    """Raise the error for the first edge that has more than two faces."""
    start = int(np.flatnonzero(same_as_next[1:] & same_as_next[:-1])[0])
    end = start + 1
    while end < len(same_as_next) and same_as_next[end]:
        end += 1
    members = order[start: end + 1]
    a, b = name(tail[members[0]]), name(head[members[0]])
    faces = [int(p) // 3 for p in members]
    listed = first_few((f"{f}{_where(f, face_lines, source)}" for f in faces), total=len(faces))
    raise MeshInputError(
        f"edge ({min(a, b)}, {max(a, b)}) has {len(faces)} faces ({listed}); "
        f"in a manifold mesh every edge has one or two faces",
        element=("edge", (min(a, b), max(a, b))),
        line=_line(faces[-1], face_lines),
    )


def _raise_same_direction(halfedge_vertex, halfedge_face, halfedge_next, n_vertices: int,
                          face_lines, source, name=int):
    """Raise the error for the edge whose two faces run along it the same way.

    If several edges do, the one with the smallest ``(low, high)`` vertex pair is named.
    Its halfedge ``2e`` is the first sighting (the earlier face), ``2e + 1`` the second.
    """
    edge_ends = halfedge_vertex.reshape(-1, 2)                         # (E, 2)
    bad = np.flatnonzero(edge_ends[:, 0] == edge_ends[:, 1])           # (k,) edges
    tail = halfedge_vertex[2 * bad]
    head = halfedge_vertex[halfedge_next[2 * bad]]
    key = np.minimum(tail, head).astype(np.int64) * n_vertices + np.maximum(tail, head)
    edge = int(bad[np.argmin(key)])
    f, g = int(halfedge_face[2 * edge]), int(halfedge_face[2 * edge + 1])
    a, b = name(halfedge_vertex[2 * edge]), name(halfedge_vertex[halfedge_next[2 * edge]])
    raise MeshInputError(
        f"directed edge ({a}, {b}) is used by two faces, "
        f"face {f}{_where(f, face_lines, source)} and face {g}{_where(g, face_lines, source)}: "
        f"neighbouring faces must run along a shared edge in opposite directions "
        f"(the faces are inconsistently oriented, or one is a duplicate)",
        element=("edge", (a, b)),
        line=_line(g, face_lines),
    )


def _check_single_fans(arrays: HalfedgeArrays, name=int) -> None:
    """Raise if some vertex's faces form more than one fan (an 'hourglass' vertex).

    Walking counter-clockwise from a vertex's halfedge must meet every one of its
    outgoing halfedges before coming back; if it comes back early, the others belong to
    another fan that the vertex's single ``halfedge`` pointer cannot reach. So: all
    vertices are fine exactly when the walks, together, visit every halfedge.
    """
    if ring_steps_total(arrays.vertex_halfedge, arrays.halfedge_prev) == len(arrays.halfedge_prev):
        return
    n_vertices = len(arrays.vertex_halfedge)
    ring_length = ring_lengths(arrays.vertex_halfedge, arrays.halfedge_prev)
    degree = np.bincount(arrays.halfedge_vertex, minlength=n_vertices)
    vertex = name(np.flatnonzero(ring_length != degree)[0])
    raise MeshInputError(
        f"vertex {vertex} is non-manifold: its faces form more than one fan "
        f"(like two cones touching at their tips), so one halfedge pointer cannot "
        f"reach all of them",
        element=("vertex", vertex),
    )


def ring_steps_total(start: np.ndarray, halfedge_prev: np.ndarray) -> int:
    """How many halfedges the walks h -> twin(prev(h)) from all of ``start`` meet, together.

    The sum of :func:`~halfedge_edu.core.rings.ring_lengths`, without keeping a length
    per walk: every vertex walks in lockstep, and each step adds how many walks are
    still going. That is all the fan checks need (the walks together must meet every
    halfedge), and it saves a scattered write per step. Finished walks are dropped only
    once a quarter of them have finished, since dropping copies the arrays.

    Attention: as for ``ring_lengths``, only call it when the rotation is known to be a
    permutation that keeps each halfedge's origin; otherwise a walk might never come back.
    """
    current = start.astype(np.intp)                           # (k,) where each walk is
    start = current.copy()
    going = np.ones(len(start), dtype=bool)
    # Each step writes into these instead of new arrays, and take() with mode="clip" writes
    # straight into ``out`` (mode="raise" would buffer it); every index is a halfedge here.
    stepped = np.empty(len(start), dtype=halfedge_prev.dtype)  # (k,) prev(h) of each walk
    differs = np.empty(len(start), dtype=bool)                 # (k,) not back at the start
    n_going = len(start)
    total = 0
    while n_going:
        total += n_going                                      # each walk still going meets one halfedge
        k = len(current)
        np.take(halfedge_prev, current, out=stepped[:k], mode="clip")
        np.bitwise_xor(stepped[:k], 1, out=current)           # twin(prev(h)): the next one round the vertex
        np.not_equal(current, start, out=differs[:k])
        going &= differs[:k]
        n_going = int(np.count_nonzero(going))
        if n_going < 0.75 * len(going):
            current, start = current[going], start[going]
            going = np.ones(n_going, dtype=bool)
    return total
