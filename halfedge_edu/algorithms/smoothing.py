"""Laplacian smoothing: move every vertex towards the average of its neighbours.

One iteration computes, for every vertex ``v`` with neighbours ``u`` and weights
``w_vu`` (summing to one over the neighbours),

    target(v) = sum_u w_vu * p_u                 (a weighted mean of the neighbours)
    p'(v)     = p_v + step * (target(v) - p_v)   (step 1: jump onto the mean)

Two rules of the course:

* **Jacobi, not Gauss-Seidel.** Every target is computed from the *old* positions, and
  all vertices move together at the end of the iteration. Updating in place, vertex
  after vertex (Gauss-Seidel), would let later vertices see some neighbours already
  moved, so the result would depend on the order the vertices happen to be numbered
  in. Jacobi is order-independent, and all the targets together are one sparse
  matrix product ``W @ P`` per iteration, which is how the fast version runs.
* **Boundary vertices stay put by default** (``boundary="fixed"``). A boundary vertex
  has neighbours on one side only, so its neighbour mean lies inside the mesh and an
  open mesh shrinks from its rim inwards, iteration after iteration, until a flat
  patch has lost its outline. Fixing the rim keeps the outline and smooths the inside
  (a membrane stretched over a fixed frame). ``boundary="along"`` instead smooths the
  rim as a curve: a boundary vertex moves towards the mean of its two neighbours
  *along its boundary loop* (a 1D Laplacian), so the outline gets smoother but also
  shrinks, like a closed polygon does.

The weights:

* ``"uniform"``: ``w_vu = 1 / degree(v)``, the plain mean of the neighbours. It moves
  vertices along the surface as well as across it, evening out triangle sizes.
* ``"cotangent"``: ``w_vu`` proportional to ``(cot alpha + cot beta) / 2``, where
  ``alpha`` and ``beta`` are the angles opposite the edge ``vu`` in its two triangles
  (one on the boundary). These weights approximate the surface's own Laplace-Beltrami
  operator, so vertices move mostly *across* the surface (along the normal) and the
  triangulation is left alone. They are recomputed from the current positions at
  every iteration. Obtuse angles make cotangents negative; a negative edge weight
  could push a vertex out of its neighbours' hull, so edge weights are clamped at
  zero. Each cotangent is also clamped to ``[-COT_LIMIT, COT_LIMIT]`` (the cotangent
  of 1 degree) and a flat triangle contributes nothing, so a nearly degenerate
  triangle cannot dominate. "Flat" means zero area up to rounding: twice the area at
  most ``FLAT_TRIANGLE`` times the longest side squared. A triangle two of whose
  corners have (nearly) met, as smoothing can make, then gives no weight at all,
  rather than a cotangent that is the ratio of two rounding errors. A vertex whose weights all clamp to zero falls back to
  uniform weights.

:func:`smooth` is the vectorized version; :func:`smooth_reference` is the loop the
course writes, vertex by vertex with handles. The tests check that they agree.
"""

from __future__ import annotations

import math

import numpy as np

from ..core import HalfedgeMesh
from ._progress import progress_range
from .arguments import check_smooth, flag

WEIGHTS = ("uniform", "cotangent")
BOUNDARY_RULES = ("fixed", "along")
#: Largest magnitude a cotangent weight may have: cot(1 degree), about 57.3.
COT_LIMIT = 1.0 / math.tan(math.radians(1.0))
#: A triangle is flat when twice its area is at most this times its longest side
#: squared (its height below 1e-12 of that side). Rounding in positions of order 1
#: leaves areas near 1e-16; a real sliver this thin would be clamped to COT_LIMIT anyway.
FLAT_TRIANGLE = 1e-12


def _check_arguments(iterations: int, weights: str, boundary: str, step: float) -> None:
    if int(iterations) != iterations or iterations < 0:
        raise ValueError(f"iterations must be a whole number >= 0, got {iterations!r}")
    if weights not in WEIGHTS:
        raise ValueError(f"weights must be one of {WEIGHTS}, got {weights!r}")
    if boundary not in BOUNDARY_RULES:
        raise ValueError(f"boundary must be one of {BOUNDARY_RULES}, got {boundary!r}")
    if not math.isfinite(step) or step == 0:
        raise ValueError(f"step must be a finite non-zero number, got {step!r}")


def smooth(
    mesh: HalfedgeMesh,
    iterations: int = 1,
    *,
    weights: str = "uniform",
    boundary: str = "fixed",
    step: float = 1.0,
    progress: bool = False,
) -> HalfedgeMesh:
    """Laplacian smoothing; returns a new mesh with the same connectivity.

    Args:
        mesh: the mesh to smooth. It is not modified.
        iterations: how many Jacobi iterations to run (0 returns a copy).
        weights: ``"uniform"`` (the mean of the neighbours) or ``"cotangent"``.
        boundary: ``"fixed"`` (default: boundary vertices do not move, so open meshes
            do not shrink from the rim) or ``"along"`` (they move towards the mean of
            their two neighbours along the boundary loop).
        step: how far to move towards the target. ``0 < step <= 1`` keeps every new
            position a convex combination of old ones (stable); 1 jumps onto the
            mean. Other values are allowed (Taubin's smoothing alternates a positive
            and a negative step).
        progress: show a progress bar over the iterations (needs tqdm).

    Returns:
        A new :class:`HalfedgeMesh`: same indices and connectivity (deleted slots
        included), new positions.

    How: the targets of all vertices at once are the sparse matrix product
    ``W @ P``, with ``P`` the (n_vertex_slots, 3) old positions and row ``v`` of ``W``
    holding the weights ``w_vu`` at the columns of its neighbours. ``W`` has the
    layout of ``mesh.vertex_adjacency()`` (CSR: one row per vertex, its neighbours in
    ring order), so it is built without sorting, once for uniform weights. Vertices
    that stay still get their old position back after the product.
    """
    check_smooth(mesh, iterations, weights, boundary, step, WEIGHTS, BOUNDARY_RULES)
    flag(progress, "progress")
    _check_arguments(iterations, weights, boundary, step)
    from scipy.sparse import csr_matrix

    n = mesh.n_vertex_slots
    offsets, neighbours = mesh.vertex_adjacency()                       # (V+1,), (nnz,)
    degree = np.diff(offsets)                                           # (V,)
    uniform = _uniform_row_weights(mesh, offsets, neighbours, boundary)  # (nnz,)
    still = mesh.vertex_deleted | (degree == 0)                          # (V,) never move
    if boundary == "fixed":
        still = still | mesh.vertex_is_boundary()
    still = np.flatnonzero(still)

    positions = mesh.positions.copy()                                   # (V, 3)
    matrix = csr_matrix((uniform, neighbours, offsets), shape=(n, n))
    for _ in progress_range(int(iterations), progress, "smooth"):
        if weights == "cotangent":
            matrix.data = _cotangent_row_weights(mesh, positions, offsets, uniform)
        target = matrix @ positions                                      # (V, 3)
        if step != 1.0:
            target -= positions
            target *= step
            target += positions
        target[still] = positions[still]
        positions = target
    result = mesh.copy()
    result.positions[:] = positions
    return result


def _uniform_row_weights(mesh, offsets, neighbours, boundary) -> np.ndarray:
    """(nnz,) the uniform weights in adjacency (CSR) order: ``1 / degree`` per row.

    With ``boundary="along"`` a boundary vertex's row weighs only its two neighbours
    along the boundary loop, 1/2 each (the other entries of its row are 0).
    """
    degree = np.diff(offsets)
    weights = np.repeat(1.0 / np.maximum(degree, 1), degree)           # (nnz,)
    if boundary == "along":
        ring = np.flatnonzero(mesh.vertex_is_boundary())                # (B,)
        out = mesh.vertex_halfedge[ring]                                # (B,) outgoing boundary halfedges
        after = mesh.halfedge_vertex[out ^ 1]                           # (B,) next vertex on the loop
        before = mesh.halfedge_vertex[mesh.halfedge_prev[out]]          # (B,) previous vertex on the loop
        entries = _row_entries(offsets, ring)                           # (k,) CSR positions of those rows
        owner = np.repeat(np.arange(len(ring)), degree[ring])           # (k,) which boundary vertex
        on_loop = (neighbours[entries] == after[owner]) | (neighbours[entries] == before[owner])
        weights[entries] = np.where(on_loop, 0.5, 0.0)
    return weights


def _row_entries(offsets: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """The CSR positions of all entries in ``rows``, row after row."""
    counts = offsets[rows + 1] - offsets[rows]
    starts = np.repeat(offsets[rows] - np.cumsum(counts) + counts, counts)
    return starts + np.arange(int(counts.sum()))


def _halfedge_cotangents(mesh: HalfedgeMesh, positions: np.ndarray) -> np.ndarray:
    """(n_halfedge_slots,) clamped cotangent of the angle opposite each halfedge in its face.

    Halfedge ``h`` runs from ``a`` to ``b``; the opposite corner ``c`` is the origin of
    ``prev(h)``. Boundary halfedges (no face) and flat faces (see ``FLAT_TRIANGLE``) give 0.
    """
    a = mesh.halfedge_vertex                                            # (H,)
    b = mesh.halfedge_tip()                                             # (H,)
    c = mesh.halfedge_vertex[mesh.halfedge_prev]                        # (H,)
    u = positions[a] - positions[c]                                     # (H, 3)
    w = positions[b] - positions[c]
    area2 = np.linalg.norm(np.cross(u, w), axis=1)                      # (H,) twice the area
    dot = np.einsum("ij,ij->i", u, w)
    side = positions[b] - positions[a]
    longest2 = np.maximum(np.maximum(np.einsum("ij,ij->i", u, u), np.einsum("ij,ij->i", w, w)),
                          np.einsum("ij,ij->i", side, side))            # (H,) longest side squared
    flat = area2 <= FLAT_TRIANGLE * longest2
    has_face = (mesh.halfedge_face >= 0) & ~flat & ~mesh.halfedge_deleted
    cot = np.divide(dot, area2, out=np.zeros_like(dot), where=has_face)
    return np.clip(cot, -COT_LIMIT, COT_LIMIT)


def _cotangent_row_weights(mesh, positions, offsets, uniform) -> np.ndarray:
    """(nnz,) normalized cotangent weights in adjacency (CSR) order.

    Each entry belongs to one outgoing halfedge ``h`` of the row's vertex (the ring
    walk), and its edge weight is ``max(0, (cot(h) + cot(twin h)) / 2)``. Rows whose
    weights all clamp to zero, and the boundary rows of ``boundary="along"``, keep
    their uniform weights.
    """
    n = mesh.n_vertex_slots
    cot = _halfedge_cotangents(mesh, positions)                         # (H,)
    ring = mesh.one_rings()                                             # rows of live vertices
    h = np.empty(int(offsets[-1]), dtype=np.int64)
    h[:] = ring.halfedges                                               # live vertices, in order
    w = np.maximum(0.5 * (cot[h] + cot[h ^ 1]), 0.0)                    # (nnz,)
    rows = np.repeat(np.arange(n), np.diff(offsets))                    # (nnz,)
    along_loop = mesh.vertex_is_boundary()[rows]
    w[along_loop] = 0.0
    total = np.bincount(rows, weights=w, minlength=n)                   # (V,)
    falls_back = (total <= 0)[rows]
    return np.where(falls_back, uniform, w / np.where(falls_back, 1.0, total[rows]))


# --------------------------------------------------------------------------------------
# The reference version: one vertex at a time, with handles
# --------------------------------------------------------------------------------------

def _cotangent_opposite(mesh: HalfedgeMesh, positions: np.ndarray, h) -> float:
    """Clamped cotangent of the angle opposite halfedge ``h`` in its face (0 if none, or
    if the face is flat: see ``FLAT_TRIANGLE``)."""
    if h.face is None:
        return 0.0
    corner = positions[h.prev.vertex.index]
    u = positions[h.vertex.index] - corner
    w = positions[h.tip.index] - corner
    area2 = float(np.linalg.norm(np.cross(u, w)))
    side = positions[h.tip.index] - positions[h.vertex.index]
    longest2 = max(float(np.dot(u, u)), float(np.dot(w, w)), float(np.dot(side, side)))
    if area2 <= FLAT_TRIANGLE * longest2:      # flat up to rounding: no weight
        return 0.0
    return min(max(float(np.dot(u, w)) / area2, -COT_LIMIT), COT_LIMIT)


def smooth_reference(
    mesh: HalfedgeMesh,
    iterations: int = 1,
    *,
    weights: str = "uniform",
    boundary: str = "fixed",
    step: float = 1.0,
) -> HalfedgeMesh:
    """Laplacian smoothing written as the course's loop over vertices (slow, readable).

    Same arguments and result as :func:`smooth`, which the tests check it equals.
    """
    check_smooth(mesh, iterations, weights, boundary, step, WEIGHTS, BOUNDARY_RULES)
    _check_arguments(iterations, weights, boundary, step)
    result = mesh.copy()
    for _ in range(int(iterations)):
        old = result.positions.copy()          # Jacobi: read only the old positions
        for v in result.vertices:
            if v.halfedge is None or (v.is_boundary and boundary == "fixed"):
                continue
            if v.is_boundary:                  # boundary="along": the two loop neighbours
                neighbours = [v.halfedge.tip, v.halfedge.prev.vertex]
                w = [1.0, 1.0]
            else:
                outgoing = v.outgoing()
                neighbours = [h.tip for h in outgoing]
                w = [1.0] * len(outgoing)
                if weights == "cotangent":
                    cotangent = [
                        0.5 * (_cotangent_opposite(result, old, h) + _cotangent_opposite(result, old, h.twin))
                        for h in outgoing
                    ]
                    cotangent = [max(c, 0.0) for c in cotangent]
                    if sum(cotangent) > 0:
                        w = cotangent
            total = sum(w)
            target = sum(wi / total * old[u.index] for wi, u in zip(w, neighbours))
            result.positions[v.index] = old[v.index] + step * (target - old[v.index])
    return result
