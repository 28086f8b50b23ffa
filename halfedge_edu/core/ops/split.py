"""Edge split: put a new vertex on an edge and cut the triangles beside it in two (chapter 06).

An interior edge becomes four triangles around the new vertex ``m``: +1 vertex,
+3 edges, +2 faces. A boundary edge has one triangle, which becomes two: +1 vertex,
+2 edges, +1 face, and the boundary loop runs through ``m``::

            before                               after

              v2                                   v2
            /    ^                               / ^ | ^
       h3  /      \\  h2                     h3  /  | |  \\  h2
          v   f0   \\                           v f0| |f2 \\
        v0 ---h0---> v1                    v0 -h0-> m -h_m1-> v1
           <--h1----                           <-h1-   <-h_1m-
          \\   f1   ^                           \\ f1| |f3 ^
       h4  \\      /  h5                     h4  \\  | |  /  h5
            v    /                               v | v /
              v3                                   v3

    up from m: h_m2 (m -> v2), its twin h_2m comes down; down from m: h_m3 and h_3m

    h0 runs v0 -> v1 in f0; h1 is its twin, in f1 (absent at the boundary)
    h2 = next(h0), h3 = prev(h0), h4 = next(h1), h5 = prev(h1) (as for flip)
    new: vertex m; edges e_m1 (m - v1), e_m2 (m - v2), e_m3 (m - v3); faces f2, f3.
    A new halfedge h_mX runs m -> vX and h_Xm is its twin.

    after: f0 = (h0, h_m2, h3)    f2 = (h_m1, h2, h_2m)
           f1 = (h1, h4, h_3m)    f3 = (h_1m, h_m3, h5)
    at the boundary (h1 has no face): the loop runs h5 -> h_1m -> h1 -> h4.

The original edge keeps its index and its ``v0`` half (``h0`` still leaves ``v0``;
``h1`` now leaves ``m``); ``e_m1`` is its ``v1`` half. The new vertex's halfedge runs
along the original edge (``h_m1``, or ``h1`` at the boundary, which is then ``m``'s
boundary halfedge as it must be), so ``m.halfedge.edge`` is one of the two halves and
the edges to ``v2`` and ``v3`` are the new ones cutting across: the convention Loop
subdivision relies on. When the edge is a boundary edge whose halfedge ``2e`` has no
face, ``h0`` is ``2e + 1`` instead, so ``h0`` always has a face.

Almost any edge can be split. The one rule (``can_split``, its ``.rule`` name):

* ``back-to-back``: both triangles beside an interior edge have the same opposite
  vertex (two triangles glued back to back, a 3-vertex "pillow"); the new vertex would
  be joined to it by two edges.

Constant work.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..elements import Vertex
from .check import OpCheck, Quad, edge_argument, position_argument, quad_around
from .log import OperationLog, writer_for

if TYPE_CHECKING:
    from ..mesh import HalfedgeMesh

__all__ = ["can_split", "split"]


def can_split(mesh: "HalfedgeMesh", edge) -> OpCheck:
    """Whether ``edge`` can be split: a truthy :class:`OpCheck`, or falsy with the reason."""
    e, _ = edge_argument(mesh, edge, "split")
    return _check(e, _faced_quad(mesh, e))


def _check(e: int, quad: Quad) -> OpCheck:
    a, b = (quad.v0, quad.v1) if quad.h0 == 2 * e else (quad.v1, quad.v0)  # the edge's own order
    if quad.f1 < 0:
        return OpCheck.ok(f"boundary edge {e} (vertices {a} and {b}) can be split")
    if quad.v2 == quad.v3:
        v2 = quad.v2
        return OpCheck.refuse(
            "back-to-back",
            f"both triangles beside edge {e} (vertices {a} and {b}) have vertex {v2} opposite it: "
            f"they are glued back to back, and splitting the edge would join the new vertex to "
            f"vertex {v2} by two different edges.",
            (("edge", e), ("vertex", v2)),
        )
    return OpCheck.ok(f"edge {e} (vertices {a} and {b}) can be split")


def _faced_quad(mesh: "HalfedgeMesh", e: int) -> Quad:
    """The :class:`Quad` of edge ``e`` from the side that has a face: at the boundary, h1 has none."""
    return quad_around(mesh, 2 * e if mesh._halfedge_face.item(2 * e) >= 0 else 2 * e + 1)


def split(mesh: "HalfedgeMesh", edge, position=None, *, log: OperationLog | None = None) -> Vertex:
    """Split ``edge`` at ``position`` (its midpoint by default); see the module's picture.

    Args:
        edge: an :class:`Edge`, an edge index or a :class:`Halfedge` (its edge).
        position: (3,) where the new vertex goes; None for the midpoint.
        log: an :class:`OperationLog` to fill step by step; None records nothing.

    Returns:
        The new vertex ``m``. Its halfedge runs along the original edge.

    Raises:
        TopologyError: the split is not allowed (the reason says why); the mesh is unchanged.
        IndexError: there is no such edge, or it was deleted.
        ValueError: ``position`` is not three finite numbers (the mesh is unchanged).
    """
    e, _ = edge_argument(mesh, edge, "split")
    position = position_argument(mesh, e, position, "split")
    # Gather, as for flip, from the side that has a face: at the boundary h1 has none,
    # and v3, f1 do not exist.
    quad = _faced_quad(mesh, e)
    check = _check(e, quad)
    if not check:
        raise check.error()
    h0, h1, h2, h3, h4, h5, v0, v1, v2, v3, f0, f1 = quad
    interior = f1 >= 0
    if log is not None:
        log.begin("split", e, h0)
        log.name(**quad.names())
        if not interior:
            log.notes.append(f"edge {e} is on the boundary: h1 = halfedge {h1} has no face, so only f0 is cut")
    write = writer_for(mesh, log)

    write.phase("create m, the new edges and faces")
    m = write.add_vertex(position)
    h_m1 = 2 * write.add_edge(m, v1)
    h_1m = h_m1 + 1
    h_m2 = 2 * write.add_edge(m, v2)
    h_2m = h_m2 + 1
    f2 = write.add_face(h_m1)
    if interior:
        h_m3 = 2 * write.add_edge(m, v3)
        h_3m = h_m3 + 1
        f3 = write.add_face(h_1m)
    if log is not None:
        log.name(m=("vertex", m), h_m1=("halfedge", h_m1), h_1m=("halfedge", h_1m),
                 h_m2=("halfedge", h_m2), h_2m=("halfedge", h_2m), f2=("face", f2))
        if interior:
            log.name(h_m3=("halfedge", h_m3), h_3m=("halfedge", h_3m), f3=("face", f3))

    write.phase("shorten the edge: h1 now leaves m (e keeps the v0 half, e_m1 is the v1 half)")
    write.set_vertex(h1, m)

    write.phase("cut f0 in two: f0 = (h0, h_m2, h3) and f2 = (h_m1, h2, h_2m)")
    write.link(h0, h_m2)
    write.link(h_m2, h3)
    write.set_face(h_m2, f0)
    write.make_face(f2, h_m1, h2, h_2m)
    write.set_face_halfedge(f0, h0)

    if interior:
        write.phase("cut f1 in two: f1 = (h1, h4, h_3m) and f3 = (h_1m, h_m3, h5)")
        write.link(h4, h_3m)
        write.link(h_3m, h1)
        write.set_face(h_3m, f1)
        write.link(h_1m, h_m3)
        write.link(h_m3, h5)
        write.link(h5, h_1m)
        write.set_face(h_1m, f3)
        write.set_face(h_m3, f3)
        write.set_face(h5, f3)
        write.set_face_halfedge(f1, h1)
    else:
        write.phase("the boundary loop runs through m: h5 -> h_1m -> h1 -> h4")
        write.link(h5, h_1m)
        write.link(h_1m, h1)

    write.phase("vertex halfedges: m's runs along the original edge; v1's may have been h1")
    write.set_vertex_halfedge(m, h_m1 if interior else h1)
    if mesh._vertex_halfedge.item(v1) == h1:
        write.set_vertex_halfedge(v1, h_1m)
    write.touch()
    return Vertex(mesh, m)
