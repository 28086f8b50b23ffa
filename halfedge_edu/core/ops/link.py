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

The one decision: :func:`link_violation` says what breaks the condition,
``link(a) ∩ link(b)`` minus ``link(ab)``, from the two one-rings alone (only a vertex in
both links can end an edge in both, so the full links are never built);
:func:`link_condition` adds every set for a notebook to draw, and ``can_collapse``
names the rule from the same answer.

Everything here walks one or two one-rings: O(degree) work, whatever the mesh size.
"""

from __future__ import annotations

from itertools import combinations
from typing import TYPE_CHECKING, NamedTuple

from .check import edge_argument

if TYPE_CHECKING:
    from ..mesh import HalfedgeMesh

__all__ = [
    "BOUNDARY", "Link", "LinkCondition", "halfedge_between", "link_condition", "link_of_edge",
    "link_of_vertex", "link_violation", "one_ring", "outgoing",
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


def _link_edges(tips: list[int], on_boundary: bool) -> set[tuple[int, int]]:
    """The edges of a vertex's link as ordered pairs, from the tips of its ``outgoing`` ring.

    Consecutive outgoing halfedges ``ring[k]``, ``ring[k + 1]`` bound the face
    ``(v, tips[k], tips[k + 1])``, whose edge opposite ``v`` is ``(tips[k], tips[k + 1])``.
    On the boundary, ``ring[0]`` (the vertex's boundary halfedge) has no face: that pair
    is the hole, and the two boundary neighbours join :data:`BOUNDARY` instead (the cone
    over the hole). A pair may come in either order; :func:`_pair` sorts it.
    """
    edges = set(zip(tips, tips[1:] + tips[:1]))
    if on_boundary:
        edges.discard((tips[0], tips[1]))
        edges.update(((tips[0], BOUNDARY), (BOUNDARY, tips[1])))
    return edges


def _in_link(tips: list[int], on_boundary: bool, i: int, j: int) -> bool:
    """Whether ``i - j`` is an edge of the link whose ring tips are ``tips`` (as :func:`_link_edges` makes them).

    ``i`` and ``j`` are vertices of that link. The cone edges to :data:`BOUNDARY` end at
    ``tips[0]`` and ``tips[1]``; a face edge joins neighbouring tips, but not the hole's
    pair ``tips[0], tips[1]`` of a boundary vertex.
    """
    if BOUNDARY in (i, j):
        return on_boundary and i + j - BOUNDARY in (tips[0], tips[1])
    k = tips.index(i)
    after, before = tips[k + 1 - len(tips)], tips[k - 1]
    return (j == after and not (on_boundary and k == 0)) or (j == before and not (on_boundary and k == 1))


def link_of_vertex(mesh: "HalfedgeMesh", v: int) -> Link:
    """The link of vertex ``v``: its neighbours and the edges opposite it in its faces.

    A boundary vertex's link also has :data:`BOUNDARY`, joined to the two neighbours
    along the boundary.
    """
    origin_of, face_of = mesh._halfedge_vertex.item, mesh._halfedge_face.item
    ring = outgoing(mesh, int(v))
    tips = [origin_of(h ^ 1) for h in ring]
    on_boundary = face_of(ring[0]) < 0  # a boundary vertex's halfedge is its boundary one
    vertices = set(tips) | ({BOUNDARY} if on_boundary else set())
    return Link(frozenset(vertices), frozenset(_pair(i, j) for i, j in _link_edges(tips, on_boundary)))


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


def link_violation(mesh: "HalfedgeMesh", edge) -> Link:
    """What breaks the link condition at ``edge``: ``link(a) ∩ link(b)`` minus ``link(ab)``.

    Empty (falsy) exactly when the condition holds. The one implementation of the
    condition: :func:`link_condition` and ``can_collapse`` both ask it. It walks the
    one-rings of ``a`` and ``b`` once and makes only the link edges whose two ends lie
    in both links, since no other edge can be in both.
    """
    e, _ = edge_argument(mesh, edge, "link_violation")
    origin_of, prev_of, face_of = mesh._halfedge_vertex.item, mesh._halfedge_prev.item, mesh._halfedge_face.item
    ring_a, ring_b = outgoing(mesh, origin_of(2 * e)), outgoing(mesh, origin_of(2 * e + 1))
    tips_a, tips_b = [origin_of(h ^ 1) for h in ring_a], [origin_of(h ^ 1) for h in ring_b]
    boundary_a, boundary_b = face_of(ring_a[0]) < 0, face_of(ring_b[0]) < 0
    shared = set(tips_a).intersection(tips_b)
    if boundary_a and boundary_b:
        shared.add(BOUNDARY)
    left = origin_of(prev_of(2 * e)) if face_of(2 * e) >= 0 else BOUNDARY
    right = origin_of(prev_of(2 * e + 1)) if face_of(2 * e + 1) >= 0 else BOUNDARY
    # An edge in both links has both its ends in both links: only pairs of shared vertices can be.
    both = frozenset(
        (i, j) for i, j in combinations(sorted(shared), 2)
        if _in_link(tips_a, boundary_a, i, j) and _in_link(tips_b, boundary_b, i, j)
    ) if len(shared) > 1 else frozenset()
    return Link(frozenset(shared.difference((left, right))), both)


def link_condition(mesh: "HalfedgeMesh", edge) -> LinkCondition:
    """Compute the link condition of ``edge`` with every set spelled out.

    ``extra`` is :func:`link_violation`'s answer, which equals ``shared - link_ab``
    (the tests hold the two equal on random meshes).

    Attention: this is the textbook condition. It is not the whole of
    ``can_collapse``: two triangles glued back to back (a 3-vertex "pillow") pass it,
    and ``can_collapse`` refuses them separately.
    """
    e, _ = edge_argument(mesh, edge, "link_condition")
    a, b = mesh._halfedge_vertex.item(2 * e), mesh._halfedge_vertex.item(2 * e + 1)
    link_a, link_b = link_of_vertex(mesh, a), link_of_vertex(mesh, b)
    link_ab = link_of_edge(mesh, e)
    return LinkCondition(a, b, link_a, link_b, link_ab, link_a & link_b, link_violation(mesh, e))
