"""One-rings and links: what an edge collapse must check (chapter 08).

The *link* of a vertex ``v`` is what you see standing on ``v``: its neighbours, and
the edges opposite ``v`` in its faces (for an interior vertex, a closed polygon around
it). The link of an edge ``ab`` is the vertices opposite it in its faces.

The **link condition**: collapsing ``ab`` keeps the surface a surface exactly when

    link(a) ∩ link(b) = link(ab)

For an interior edge with its triangles ``(a, b, l)`` and ``(b, a, r)``: the one-rings
of ``a`` and ``b`` must share exactly the two opposite vertices ``l`` and ``r``, and no
edge (a tetrahedron breaks that second part: ``l - r`` lies in both links).

Boundaries join in through one convention: the boundary counts as one extra vertex,
:data:`BOUNDARY` (= -1), joined to every boundary vertex, as if each hole were closed
by a cone. Then the same condition also refuses an interior edge between two boundary
vertices (both links contain -1, the edge's does not) and a lone triangle (the edge
``-1 - l`` lies in both links).

Everything here walks one or two one-rings: O(degree) work, whatever the mesh size.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

from .check import edge_argument

if TYPE_CHECKING:
    from ..mesh import HalfedgeMesh

__all__ = [
    "BOUNDARY", "Link", "LinkCondition", "halfedge_between", "link_condition", "link_of_edge",
    "link_of_vertex", "one_ring", "outgoing",
]

#: The extra vertex the boundary counts as, in links (see the module docstring).
BOUNDARY = -1


def outgoing(mesh: "HalfedgeMesh", v: int) -> list[int]:
    """The halfedges leaving vertex ``v``, counter-clockwise from ``v``'s halfedge.

    The walk is ``h -> twin(prev(h))``: ``prev(h)`` comes into ``v`` and its twin
    leaves ``v`` again in the next face counter-clockwise. O(degree).
    """
    prev_of = mesh._halfedge_prev.item
    start = mesh._vertex_halfedge.item(v)
    ring = [start]
    h = prev_of(start) ^ 1
    while h != start:
        ring.append(h)
        h = prev_of(h) ^ 1
    return ring


def one_ring(mesh: "HalfedgeMesh", v: int) -> list[int]:
    """The neighbours of vertex ``v``, counter-clockwise (tips of :func:`outgoing`)."""
    origin_of = mesh._halfedge_vertex.item
    return [origin_of(h ^ 1) for h in outgoing(mesh, v)]


def halfedge_between(mesh: "HalfedgeMesh", a: int, b: int) -> int:
    """The halfedge from vertex ``a`` to vertex ``b``, or -1 if they are not joined."""
    origin_of = mesh._halfedge_vertex.item
    for h in outgoing(mesh, a):
        if origin_of(h ^ 1) == b:
            return h
    return -1


class Link(NamedTuple):
    """A link: a set of vertices and a set of edges ``(i, j)`` with ``i < j``.

    :data:`BOUNDARY` (-1) stands for the boundary, as explained in the module docstring.
    """

    vertices: frozenset
    edges: frozenset

    def __and__(self, other: "Link") -> "Link":
        return Link(self.vertices & other.vertices, self.edges & other.edges)

    def __sub__(self, other: "Link") -> "Link":
        return Link(self.vertices - other.vertices, self.edges - other.edges)

    def __bool__(self) -> bool:
        return bool(self.vertices or self.edges)


def _pair(i: int, j: int) -> tuple[int, int]:
    return (i, j) if i < j else (j, i)


def link_of_vertex(mesh: "HalfedgeMesh", v: int) -> Link:
    """The link of vertex ``v``: its neighbours and the edges opposite it in its faces.

    A boundary vertex's link also has :data:`BOUNDARY`, joined to the two neighbours
    along the boundary.
    """
    v = int(v)
    origin_of, next_of, face_of = mesh._halfedge_vertex.item, mesh._halfedge_next.item, mesh._halfedge_face.item
    vertices, edges = set(), set()
    for h in outgoing(mesh, v):
        tip = origin_of(h ^ 1)
        vertices.add(tip)
        if face_of(h) >= 0:  # the face (v, tip, far): its edge opposite v is tip - far
            edges.add(_pair(tip, origin_of(next_of(h) ^ 1)))
        if face_of(h) < 0 or face_of(h ^ 1) < 0:  # a boundary edge v - tip: cone triangle (v, tip, -1)
            vertices.add(BOUNDARY)
            edges.add(_pair(tip, BOUNDARY))
    return Link(frozenset(vertices), frozenset(edges))


def link_of_edge(mesh: "HalfedgeMesh", edge) -> Link:
    """The link of an edge: the vertex opposite it in each of its faces.

    A boundary edge has one face, so its link is that opposite vertex and
    :data:`BOUNDARY`. An edge's link has no edges.
    """
    e, h = edge_argument(mesh, edge, "link_of_edge")
    origin_of, prev_of, face_of = mesh._halfedge_vertex.item, mesh._halfedge_prev.item, mesh._halfedge_face.item
    opposite = {origin_of(prev_of(side)) if face_of(side) >= 0 else BOUNDARY for side in (2 * e, 2 * e + 1)}
    return Link(frozenset(opposite), frozenset())


class LinkCondition(NamedTuple):
    """``link(a) ∩ link(b)`` against ``link(ab)``, all the sets a notebook draws.

    ``holds`` (also ``bool(result)``) is True when ``shared == link_ab``, i.e. when
    ``extra`` is empty.
    """

    a: int
    b: int
    link_a: Link
    link_b: Link
    link_ab: Link
    shared: Link  # link(a) ∩ link(b)
    extra: Link  # shared, minus link(ab): what makes the condition fail

    @property
    def holds(self) -> bool:
        return not self.extra

    def __bool__(self) -> bool:
        return self.holds


def link_condition(mesh: "HalfedgeMesh", edge) -> LinkCondition:
    """Compute the link condition of ``edge`` with every set spelled out.

    Attention: this is the textbook condition. It is not the whole of
    ``can_collapse``: two triangles glued back to back (a 3-vertex "pillow") pass it,
    and ``can_collapse`` refuses them separately.
    """
    e, _ = edge_argument(mesh, edge, "link_condition")
    a, b = mesh._halfedge_vertex.item(2 * e), mesh._halfedge_vertex.item(2 * e + 1)
    link_a, link_b = link_of_vertex(mesh, a), link_of_vertex(mesh, b)
    link_ab = link_of_edge(mesh, e)
    shared = link_a & link_b
    return LinkCondition(a, b, link_a, link_b, link_ab, shared, shared - link_ab)
