"""Edge flip: turn an edge inside the quadrilateral its two triangles make (chapter 06).

The two triangles beside edge ``v0 - v1`` form a quadrilateral ``v0 v3 v1 v2``; the
flip replaces the diagonal ``v0 - v1`` by the other diagonal ``v2 - v3``. Element counts
do not change: the same edge, its two halfedges and the two faces are reused::

            before                            after

              v2                                v2
            /    ^                            / ^ | ^
       h3  /      \\  h2                 h3  /  | |  \\  h2
          v   f0   \\                       v   | |   \\
        v0 ---h0---> v1                  v0  f0 h0 h1 f1  v1
           <--h1----                        \\   | |   ^
          \\   f1   ^                    h4  \\  | |  /  h5
       h4  \\      /  h5                      v | v /
            v    /                              v3
              v3

    h0 = 2e runs v0 -> v1, h1 = 2e + 1 is its twin; f0 = face(h0), f1 = face(h1)
    h2 = next(h0), h3 = prev(h0), h4 = next(h1), h5 = prev(h1)
    after: h0 runs v3 -> v2 in f0 = (h0, h3, h4); h1 runs v2 -> v3 in f1 = (h1, h5, h2)

The rules (``can_flip``), each with the name its refusal carries in ``.rule``:

* ``boundary-edge``: an edge with a face on one side only has no quadrilateral.
* ``same-opposite-vertex``: both triangles have the same vertex opposite the edge
  (two triangles glued back to back); the new edge would join a vertex to itself.
* ``edge-exists``: ``v2`` and ``v3`` are already joined (every edge of a tetrahedron);
  the flip would make a second edge between them. This covers the endpoint of
  degree 3: an interior vertex with only 3 edges would drop to 2, and its three
  neighbours are always joined to each other, so it is this rule that refuses it, and
  its reason says so.

A boundary endpoint may drop to degree 2: that is an ordinary corner of one triangle.
The flip is constant work: a few pointers, and one walk around ``v2`` for the check.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..elements import Edge
from .check import OpCheck, Quad, edge_argument, quad_around
from .link import halfedge_between, outgoing
from .log import OperationLog, writer_for

if TYPE_CHECKING:
    from ..mesh import HalfedgeMesh

__all__ = ["can_flip", "flip"]


def can_flip(mesh: "HalfedgeMesh", edge) -> OpCheck:
    """Whether ``edge`` can be flipped: a truthy :class:`OpCheck`, or falsy with the reason.

    ``edge`` is an :class:`Edge`, an edge index or a :class:`Halfedge` (its edge).
    The mesh is not changed.
    """
    e, _ = edge_argument(mesh, edge, "flip")
    return _check(mesh, quad_around(mesh, 2 * e))


def _check(mesh: "HalfedgeMesh", quad: Quad) -> OpCheck:
    e, v0, v1, v2, v3 = quad.h0 >> 1, quad.v0, quad.v1, quad.v2, quad.v3
    if quad.f0 < 0 or quad.f1 < 0:
        return OpCheck.refuse(
            "boundary-edge",
            f"edge {e} (vertices {v0} and {v1}) is on the boundary: it has a triangle on one side "
            f"only, so there is no quadrilateral to turn it in. Only interior edges can be flipped.",
            (("edge", e),),
        )
    if v2 == v3:
        return OpCheck.refuse(
            "same-opposite-vertex",
            f"both triangles beside edge {e} (vertices {v0} and {v1}) have vertex {v2} opposite it: "
            f"they are glued back to back, and the flipped edge would join vertex {v2} to itself.",
            (("edge", e), ("vertex", v2)),
        )
    existing = halfedge_between(mesh, v2, v3)
    if existing >= 0:
        reason = (
            f"flipping edge {e} (vertices {v0} and {v1}) would join vertices {v2} and {v3}, but "
            f"edge {existing >> 1} already joins them: the mesh would have two edges between the "
            f"same two vertices."
        )
        low = [v for v in (v0, v1) if _is_interior_of_degree_3(mesh, v)]
        if len(low) == 1:
            reason += f" Vertex {low[0]} has only 3 edges, so the flip would also leave it with 2."
        elif low:
            reason += f" Vertices {v0} and {v1} have only 3 edges each, so the flip would also leave them with 2."
        return OpCheck.refuse("edge-exists", reason, (("edge", e), ("edge", existing >> 1)))
    return OpCheck.ok(f"edge {e} (vertices {v0} and {v1}) can be flipped to join vertices {v2} and {v3}")


def _is_interior_of_degree_3(mesh: "HalfedgeMesh", v: int) -> bool:
    ring = outgoing(mesh, v)  # an interior vertex's halfedge has a face; a boundary one's does not
    return len(ring) == 3 and mesh._halfedge_face.item(ring[0]) >= 0


def flip(mesh: "HalfedgeMesh", edge, *, log: OperationLog | None = None) -> Edge:
    """Flip ``edge`` in place (see the picture in this module's docstring).

    Args:
        edge: an :class:`Edge`, an edge index or a :class:`Halfedge` (its edge).
        log: an :class:`OperationLog` to fill with the named elements and every
            pointer change, for stepping through the flip; None (the default) records
            nothing.

    Returns:
        The same edge, now joining the two vertices that were opposite it.

    Raises:
        TopologyError: the flip is not allowed (the reason says why); the mesh is unchanged.
        IndexError: there is no such edge, or it was deleted.
    """
    e, _ = edge_argument(mesh, edge, "flip")
    # Gather: the two triangles (h0, h2, h3) and (h1, h4, h5) around the edge.
    quad = quad_around(mesh, 2 * e)
    check = _check(mesh, quad)
    if not check:
        raise check.error()
    h0, h1, h2, h3, h4, h5, v0, v1, v2, v3, f0, f1 = quad
    if log is not None:
        log.begin("flip", e, h0)
        log.name(**quad.names())
    write = writer_for(mesh, log)

    write.phase("turn the edge: h0 now leaves v3, h1 now leaves v2")
    write.set_vertex(h0, v3)
    write.set_vertex(h1, v2)

    write.phase("relink the two triangles: f0 = (h0, h3, h4), f1 = (h1, h5, h2)")
    write.cycle(h0, h3, h4)
    write.cycle(h1, h5, h2)

    write.phase("h4 moves into f0 and h2 into f1; each face points at its edge halfedge")
    write.set_face(h4, f0)
    write.set_face(h2, f1)
    write.set_face_halfedge(f0, h0)
    write.set_face_halfedge(f1, h1)

    write.phase("v0 and v1 no longer have the flipped edge: move their halfedge if it was it")
    if mesh._vertex_halfedge.item(v0) == h0:
        write.set_vertex_halfedge(v0, h4)
    if mesh._vertex_halfedge.item(v1) == h1:
        write.set_vertex_halfedge(v1, h2)
    write.touch()
    return Edge(mesh, e)
