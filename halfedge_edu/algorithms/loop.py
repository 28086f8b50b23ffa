"""Loop subdivision: every triangle becomes four, and the surface gets smoother.

One level does two things, and the course keeps them apart:

1. **Connectivity (the 4-to-1 split).** Every edge gets a new vertex (an *edge point*,
   "odd" vertex); every triangle ``v0 v1 v2`` with edge points ``m0`` (on ``v0 v1``),
   ``m1`` (on ``v1 v2``), ``m2`` (on ``v2 v0``) becomes the three corner triangles
   ``v0 m0 m2``, ``v1 m1 m0``, ``v2 m2 m1`` and the centre triangle ``m0 m1 m2``, all
   turning the same way as the parent. Counts: ``V' = V + E``, ``F' = 4 F``,
   ``E' = 2 E + 3 F``, so ``V' - E' + F' = V - E + F``: the Euler characteristic (and
   the genus) is kept.
2. **Positions, all computed from the old mesh** before anything moves:

   * an interior edge ``a b`` whose two triangles have the opposite corners ``c`` and
     ``d`` gets the edge point ``3/8 (a + b) + 1/8 (c + d)``: mostly the midpoint,
     pulled a little towards the two wings, which is what makes the limit smooth;
   * a boundary edge gets its midpoint ``(a + b) / 2``, so the boundary is refined as
     a curve of its own and never depends on the inside;
   * an old interior vertex ``v`` of degree ``n`` moves to
     ``(1 - n beta) v + beta * (sum of its n neighbours)``, with Warren's
     ``beta = 3/16`` for ``n = 3`` and ``3 / (8 n)`` otherwise: a weighted average of
     itself and its ring, the vertex keeping the largest share;
   * an old boundary vertex moves to ``3/4 v + 1/8 (b0 + b1)`` with ``b0``, ``b1`` its
     two neighbours along the boundary (the cubic B-spline rule for curves).

   ``weights="loop"`` uses Loop's original
   ``beta = (5/8 - (3/8 + 1/4 cos(2 pi / n))**2) / n`` instead (what trimesh uses); the
   two agree for ``n = 3`` and ``n = 6``.

Numbering (so results are predictable): the old vertices keep their indices ``0..V-1``
and the edge point of edge ``e`` is vertex ``V + e``. Face ``f`` becomes faces
``4 f + k`` (``k = 0, 1, 2``: the corner at the ``k``-th vertex of ``face_vertices()``,
listed ``[v_k, m_k, m_(k-1)]``) and ``4 f + 3`` (the centre, ``[m0, m1, m2]``). Edge
``e`` from ``a`` to ``b`` becomes edges ``2 e`` (``a - m``) and ``2 e + 1`` (``m - b``);
the centre triangle of face ``f`` adds edges ``2 E + 3 f + k``.

:func:`loop_subdivide` builds the new halfedge arrays directly from that numbering,
with array operations (no sorting, no loop over faces). The course's way of doing the
same thing with local operations (split every edge, flip the new edges that join an
old and a new vertex, then move everything) is :func:`loop_subdivide_by_operations`.
"""

from __future__ import annotations

from typing import Callable, NamedTuple

import numpy as np

from ..core import Edge, HalfedgeMesh, Vertex
from ..core.build import INDEX, HalfedgeArrays
from ._progress import progress_range
from .arguments import callback, check_mesh, choice, flag, refuse_pillows, whole_number

VERTEX_WEIGHTS = ("warren", "loop")


def loop_subdivide(
    mesh: HalfedgeMesh,
    levels: int = 1,
    *,
    weights: str = "warren",
    progress: bool = False,
) -> HalfedgeMesh:
    """Loop subdivision, ``levels`` times; returns a new mesh (the input is not modified).

    Args:
        mesh: a triangle mesh, closed or with boundary.
        levels: how many times to subdivide; each level multiplies the faces by 4.
        weights: ``"warren"`` (default; ``beta = 3/16`` for degree 3, ``3 / (8 n)``
            otherwise) or ``"loop"`` (Loop's original ``beta``, as trimesh uses).
        progress: show a progress bar over the levels (needs tqdm).

    Returns:
        The refined :class:`HalfedgeMesh`, numbered as the module docstring says.

    Attention: a mesh with deleted elements is compacted first (on a copy), so vertex
    ``V + e`` refers to the compacted numbering (``mesh.garbage_collect()``'s maps).
    """
    check_mesh(mesh)
    whole_number(levels, "levels", minimum=0)
    choice(weights, "weights", VERTEX_WEIGHTS)
    flag(progress, "progress")
    refuse_pillows(mesh, "Loop subdivision")
    current = mesh
    if mesh.has_garbage or levels == 0:
        current = mesh.copy()
        current.garbage_collect()
    for _ in progress_range(int(levels), progress, "loop subdivision"):
        current = HalfedgeMesh(_refined_arrays(current, weights))
    return current


def loop_positions(mesh: HalfedgeMesh, weights: str = "warren") -> tuple[np.ndarray, np.ndarray]:
    """The new positions of one Loop step, from the old mesh alone.

    Args:
        mesh: a mesh without deleted elements (``garbage_collect()`` first).
        weights: ``"warren"`` or ``"loop"`` (see :func:`loop_subdivide`).

    Returns:
        ``(vertex_points (V, 3), edge_points (E, 3))``: where each old vertex moves and
        where the new vertex on each edge goes.
    """
    check_mesh(mesh)
    choice(weights, "weights", VERTEX_WEIGHTS)
    return _positions(mesh, weights)


def _positions(mesh: HalfedgeMesh, weights: str) -> tuple[np.ndarray, np.ndarray]:
    """:func:`loop_positions` without the argument checks, for the levels after the first:
    each level shrinks a curved mesh a little, so a mesh at ``MIN_EXTENT`` would be
    refused at its second level although its input was accepted."""
    positions = mesh.positions                                      # (V, 3)
    n_vertices = len(positions)
    origin = mesh.halfedge_vertex                                   # (H,)
    face = mesh.halfedge_face                                       # (H,)
    a, b = origin[0::2], origin[1::2]                               # (E,) edge ends

    # Edge points: 3/8 of each end plus 1/8 of each opposite corner (block by block of
    # edges, for the reason given at _FACE_BLOCK); midpoints on the boundary.
    n_edges = len(a)
    edge_points = np.empty((n_edges, 3))                            # (E, 3)
    for start in range(0, n_edges, _FACE_BLOCK):
        block = slice(start, start + _FACE_BLOCK)
        c = origin[mesh.halfedge_prev[0::2][block]]                 # (k,) corner opposite 2e
        d = origin[mesh.halfedge_prev[1::2][block]]                 # (k,) corner opposite 2e+1
        edge_points[block] = 0.375 * (positions[a[block]] + positions[b[block]]) + 0.125 * (positions[c] + positions[d])
    on_boundary_edge = (face[0::2] < 0) | (face[1::2] < 0)          # (E,)
    ends = positions[a[on_boundary_edge]] + positions[b[on_boundary_edge]]
    edge_points[on_boundary_edge] = 0.5 * ends

    # Vertex points: the sum of the neighbours, by scattering each edge onto both ends.
    degree = np.bincount(a, minlength=n_vertices) + np.bincount(b, minlength=n_vertices)   # (V,)
    ring_sum = np.empty((n_vertices, 3))                            # (V, 3)
    for axis in range(3):
        ring_sum[:, axis] = np.bincount(a, weights=positions[b, axis], minlength=n_vertices)
        ring_sum[:, axis] += np.bincount(b, weights=positions[a, axis], minlength=n_vertices)
    n = np.maximum(degree, 1).astype(np.float64)
    if weights == "warren":
        beta = np.where(degree == 3, 3.0 / 16.0, 3.0 / (8.0 * n))
    else:
        beta = (5.0 / 8.0 - (3.0 / 8.0 + 0.25 * np.cos(2.0 * np.pi / n)) ** 2) / n
    vertex_points = (1.0 - n * beta)[:, None] * positions + beta[:, None] * ring_sum

    # Boundary vertices: 3/4 of themselves, 1/8 of each neighbour along the boundary.
    rim = np.flatnonzero(mesh.vertex_is_boundary())                 # (B,)
    out = mesh.vertex_halfedge[rim]                                 # (B,) outgoing boundary halfedge
    after = origin[out ^ 1]                                         # (B,) next vertex on the loop
    before = origin[mesh.halfedge_prev[out]]                        # (B,) previous vertex on the loop
    vertex_points[rim] = 0.75 * positions[rim] + 0.125 * (positions[after] + positions[before])
    return vertex_points, edge_points


def _first_half(h: np.ndarray) -> np.ndarray:
    """The new halfedge on the first half of old halfedge ``h`` (origin -> edge point).

    Old edge ``e`` becomes new edges ``2e`` (halfedges ``4e``: a -> m, ``4e+1``: m -> a)
    and ``2e+1`` (``4e+2``: m -> b, ``4e+3``: b -> m). So for ``h = 2e`` (a -> b) the
    halves are ``4e, 4e+2``, and for ``h = 2e+1`` (b -> a) they are ``4e+3, 4e+1``.
    """
    return np.where(h & 1, 2 * h + 1, 2 * h)


def _second_half(h: np.ndarray) -> np.ndarray:
    """The new halfedge on the second half of old halfedge ``h`` (edge point -> tip)."""
    return np.where(h & 1, 2 * h - 1, 2 * h + 2)


#: Old faces refined per block in :func:`_refined_arrays`. A block's temporaries (a dozen
#: (k, 3) int64 arrays, 768 KiB each) stay in the cache and are small enough for the
#: allocator to reuse the same memory block after block. Done for the whole mesh at once,
#: each temporary of a 5M-face mesh is 360 MiB, which the allocator maps fresh from the
#: system every time (anything over 32 MiB is), and the kernel then spends as long
#: handing out and zeroing pages as the arithmetic takes.
_FACE_BLOCK = 1 << 15


def _refined_arrays(mesh: HalfedgeMesh, weights: str) -> HalfedgeArrays:
    """The halfedge arrays of one Loop level of a compact ``mesh`` (see the module docstring)."""
    n_vertices, n_edges, n_faces = mesh.n_vertex_slots, mesh.n_edge_slots, mesh.n_face_slots
    vertex_points, edge_points = _positions(mesh, weights)

    old_origin = mesh.halfedge_vertex
    old_next = mesh.halfedge_next
    old_face = mesh.halfedge_face
    new_count = 4 * n_edges + 6 * n_faces                           # H' = 2 E'
    origin = np.empty(new_count, dtype=INDEX)
    next_ = np.empty(new_count, dtype=INDEX)
    prev = np.empty(new_count, dtype=INDEX)
    face = np.empty(new_count, dtype=INDEX)

    # The two halves of every old edge e (a -> b, edge point m): new halfedges 4e (a -> m),
    # 4e+1 (m -> a), 4e+2 (m -> b) and 4e+3 (b -> m), so the origins are four columns.
    halves_origin = origin[:4 * n_edges].reshape(-1, 4)             # (E, 4) a view
    halves_origin[:, 0] = old_origin[0::2]
    halves_origin[:, 3] = old_origin[1::2]
    halves_origin[:, 1] = halves_origin[:, 2] = n_vertices + np.arange(n_edges, dtype=INDEX)

    # Boundary halves stay on the boundary loop: first -> second -> first half of the next.
    boundary = np.flatnonzero(old_face < 0)                         # (B,)
    first, second = _first_half(boundary), _second_half(boundary)   # (B,)
    after = _first_half(old_next[boundary].astype(np.int64))
    next_[first] = second
    prev[second] = first
    next_[second] = after
    prev[after] = second
    face[first] = -1
    face[second] = -1

    face_halfedge = np.empty((n_faces, 4), dtype=INDEX)             # (F, 4): new faces 4f .. 4f+3
    for start in range(0, n_faces, _FACE_BLOCK):
        faces = np.arange(start, min(start + _FACE_BLOCK, n_faces))
        _refine_faces(faces, mesh, origin, next_, prev, face, face_halfedge)

    # An old vertex keeps the first half of its halfedge (a boundary one stays boundary,
    # and the smallest index stays the smallest). An edge point leaves along the second
    # half of the edge's odd halfedge (4e+1), or of 2e (4e+2) if 2e is the boundary side.
    vertex_halfedge = np.empty(n_vertices + n_edges, dtype=INDEX)
    vertex_halfedge[:n_vertices] = _first_half(mesh.vertex_halfedge.astype(np.int64))
    vertex_halfedge[n_vertices:] = 4 * np.arange(n_edges, dtype=INDEX) + np.where(old_face[0::2] < 0, 2, 1)
    return HalfedgeArrays(
        positions=np.concatenate([vertex_points, edge_points]),
        vertex_halfedge=vertex_halfedge,
        halfedge_next=next_,
        halfedge_prev=prev,
        halfedge_vertex=origin,
        halfedge_face=face,
        face_halfedge=face_halfedge.reshape(-1),
    )


def _refine_faces(faces: np.ndarray, mesh: HalfedgeMesh, origin: np.ndarray, next_: np.ndarray,
                  prev: np.ndarray, face: np.ndarray, face_halfedge: np.ndarray) -> None:
    """Write the new halfedges inside old ``faces`` (k,), and the new faces' halfedges, into the new arrays.

    Per old face: its halfedges h_k (k = 0, 1, 2), their halves, and the three new inner
    edges 2E + 3f + k. Inner halfedge "centre_k" runs m_k -> m_(k+1) inside the centre
    triangle; its twin "corner_k" runs m_(k+1) -> m_k inside a corner triangle.
    """
    n_vertices, n_edges = mesh.n_vertex_slots, mesh.n_edge_slots
    h0 = mesh.face_halfedge[faces].astype(np.int64)                 # (k,)
    h1 = mesh.halfedge_next[h0].astype(np.int64)
    h2 = mesh.halfedge_next[h1].astype(np.int64)
    corners = np.stack([h0, h1, h2], axis=1)                        # (k, 3) old halfedges
    firsts, seconds = _first_half(corners), _second_half(corners)   # (k, 3)
    edge_point = n_vertices + (corners >> 1)                        # (k, 3) m_k
    inner_edge = 2 * n_edges + 3 * faces[:, None] + np.arange(3)    # (k, 3)
    centre = 2 * inner_edge                                         # (k, 3) m_k -> m_(k+1)
    corner = centre + 1                                             # (k, 3) m_(k+1) -> m_k
    origin[centre] = edge_point
    origin[corner] = edge_point[:, [1, 2, 0]]

    # Corner triangle k sits at v_k: first half of h_k (v_k -> m_k), then the inner
    # halfedge m_k -> m_(k-1), then the second half of h_(k-1) (m_(k-1) -> v_k).
    back_inner = corner[:, [2, 0, 1]]                               # (k, 3) m_k -> m_(k-1)
    back_second = seconds[:, [2, 0, 1]]                             # (k, 3) m_(k-1) -> v_k
    next_[firsts] = back_inner
    next_[back_inner] = back_second
    next_[back_second] = firsts
    prev[back_inner] = firsts
    prev[back_second] = back_inner
    prev[firsts] = back_second
    new_face = 4 * faces[:, None] + np.arange(4)                    # (k, 4)
    face[firsts] = face[back_inner] = face[back_second] = new_face[:, :3]
    # Centre triangle: m0 -> m1 -> m2.
    next_[centre] = centre[:, [1, 2, 0]]
    prev[centre] = centre[:, [2, 0, 1]]
    face[centre] = new_face[:, 3:]
    face_halfedge[faces, :3] = firsts                               # corner triangle k: v_k -> m_k
    face_halfedge[faces, 3] = centre[:, 0]                          # centre triangle: m_0 -> m_1


# --------------------------------------------------------------------------------------
# The course's route: split every edge, flip, then move (local operations, slow)
# --------------------------------------------------------------------------------------

class LoopStep(NamedTuple):
    """One step of :func:`loop_subdivide_by_operations`, as passed to ``on_step``.

    Attributes:
        phase: ``"split"``, ``"flip"`` or ``"reposition"``.
        number: 0, 1, 2, ... counting the steps of this phase.
        element: the new :class:`Vertex` (split), the flipped :class:`Edge` (flip), or
            None (reposition, which is one step for all vertices).
        mesh: the mesh being worked on, right after the step. It keeps changing;
            take ``step.mesh.copy()`` to keep a picture of it.
    """

    phase: str
    number: int
    element: Vertex | Edge | None
    mesh: HalfedgeMesh


def loop_subdivide_by_operations(
    mesh: HalfedgeMesh,
    *,
    weights: str = "warren",
    on_step: Callable[[LoopStep], None] | None = None,
) -> HalfedgeMesh:
    """One level of Loop subdivision the way the course builds it, with local operations.

    1. Compute every new position from the old mesh (:func:`loop_positions`), before
       any connectivity changes.
    2. Split every original edge (``ops.split``) at its midpoint. Splitting edge ``e``
       adds vertex ``V + e``, because the edges are split in index order and a split
       appends its vertex; the split also adds one or two edges cutting *across* the
       neighbouring triangles, and those are remembered.
    3. Flip every remembered edge that joins an old vertex and a new one
       (``ops.flip``). Cross edges joining two new vertices stay: they are the sides
       of the centre triangles. Now every old triangle is four.
    4. Move every vertex to the position computed in step 1.

    Args:
        mesh: the mesh to subdivide (not modified).
        weights: ``"warren"`` or ``"loop"``, as for :func:`loop_subdivide`.
        on_step: called with a :class:`LoopStep` after every split, every flip and
            the final repositioning, for a stepper that shows the work.

    Returns:
        A new mesh with the same vertices, positions and faces as
        ``loop_subdivide(mesh, weights=weights)``: old vertices keep their indices and
        the edge point of edge ``e`` is vertex ``V + e`` (of the compacted mesh). The
        faces are the same triangles, in a different order, and the edge numbering
        differs.

    Attention: one Python step per edge; use :func:`loop_subdivide` on big meshes.
    """
    from ..core.ops import flip, split

    check_mesh(mesh)
    choice(weights, "weights", VERTEX_WEIGHTS)
    callback(on_step, "on_step")
    refuse_pillows(mesh, "Loop subdivision")
    work = mesh.copy()
    if work.has_garbage:
        work.garbage_collect()
    n_old_vertices, n_old_edges = work.n_vertex_slots, work.n_edge_slots
    report = on_step if on_step is not None else (lambda step: None)

    vertex_points, edge_points = loop_positions(work, weights)     # 1. from the old mesh

    across = []                                                    # 2. split every old edge
    for e in range(n_old_edges):
        ends = {int(v) for v in work.edge(e).vertices}
        m = split(work, e)
        across += [h.edge.index for h in m.outgoing() if h.tip.index not in ends]
        report(LoopStep("split", e, m, work))

    flips = 0                                                      # 3. flip old-new cross edges
    for e in across:
        a, b = (int(v) for v in work.edge(e).vertices)
        if (a < n_old_vertices) != (b < n_old_vertices):
            report(LoopStep("flip", flips, flip(work, e), work))
            flips += 1

    work.positions[:n_old_vertices] = vertex_points                # 4. move everything
    work.positions[n_old_vertices:] = edge_points
    report(LoopStep("reposition", 0, None, work))
    return work
