"""Edge collapse: merge the two ends of an edge into one vertex (chapters 07 and 08).

The names (a halfedge ``h_X_Y`` runs from vertex ``vX`` to vertex ``vY``)::

                   gL    vL
                       /    ^
              h_L_B   /  fL  \\   h_A_L
                     v        \\
                  vB ---h_BA---> vA
                     <--h_AB----
                     \\        ^
              h_B_R   \\  fR  /   h_R_A
                       v    /
                   gR    vR

    the twins, outside fL and fR: h_B_L = twin(h_L_B), h_L_A = twin(h_A_L),
                                  h_R_B = twin(h_B_R), h_A_R = twin(h_R_A)

    h_BA runs from vB, the vertex that is REMOVED, to vA, the vertex that SURVIVES
    fL = face(h_BA) = (h_BA, h_A_L, h_L_B);  fR = face(h_AB) = (h_AB, h_B_R, h_R_A)
    gL = face(h_B_L), gR = face(h_R_B): the faces on the far side of vB's edges to
    vL and vR (-1 where that far side is the boundary)

Which end goes: ``collapse(mesh, h)`` with a halfedge ``h`` removes ``h``'s origin and
keeps its tip, as pmp-library's ``collapse(h)`` and OpenMesh's do; an edge ``e`` (or
its index) means its halfedge ``2e``, so ``e.vertices[0]`` is removed. ``vA`` moves to
``position`` (the midpoint by default). The result does not depend on which end goes:
collapsing from the other end gives the same mesh up to relabelling, with the same
positions.

What it does, for an interior edge (at a boundary edge one side has no face and is
skipped):

1. ``vA`` moves to the new position.
2. Every halfedge that leaves ``vB``, except ``h_BA``, ``h_B_L`` and ``h_B_R``, now
   leaves ``vA``.
3. fL is removed. Its edges ``vA - vL`` and ``vB - vL`` become the same edge, so one
   of them goes: we keep ``vA``'s (``h_A_L``/``h_L_A``) and delete ``vB``'s.
   ``h_A_L`` takes the place of ``h_B_L`` in ``gL``: it gets ``h_B_L``'s next, prev
   and face, and ``gL`` points at it if it pointed at ``h_B_L``.
4. The same for fR: ``h_R_A`` takes the place of ``h_R_B`` in ``gR``.
5. (Boundary edge only) The collapsed edge's boundary halfedge leaves its loop.
6. Vertex halfedges that pointed at a deleted halfedge are moved: ``vL``'s
   (if it was ``h_L_B``) to ``h_L_A``, ``vR``'s (if ``h_R_B``) to ``h_R_A``, and
   ``vA``'s to its outgoing boundary halfedge if the merged vertex is on the boundary.
7. Deleted: ``vB``, the edge, the two faces and the edges ``vB - vL`` and ``vB - vR``
   (at a boundary edge: one face and one more edge). Counts: V - 1, E - 3, F - 2
   (boundary: V - 1, E - 2, F - 1), so V - E + F does not change.

The two cases the course separates:

* ``vB`` of degree > 3: ``vB`` has other faces; their halfedges move to ``vA`` in
  step 2, and ``gL`` and ``gR`` are two different faces.
* ``vB`` of degree 3: ``vB``'s only other face is ``(vB, vL, vR)``, so ``gL`` and
  ``gR`` are *the same face*, and no halfedge moves in step 2. Step 3 changes that
  face's links and step 4 changes them again; code that first copies every neighbour
  pointer and then writes them all would write stale values here. Steps 3 and 4 read
  each pointer when they need it, so the one code path covers both cases. The face
  survives as ``(vA, vL, vR)``.

Which of the merged edges is kept does not matter either: keeping ``vB``'s gives the
same mesh with other edge numbers (collapsing from the other end does exactly that,
and the tests check that both give the same mesh).

The rules (``can_collapse``), each with the name its refusal carries in ``.rule``:

* ``back-to-back``: both triangles beside the edge have the same opposite vertex
  (``vL == vR``, two triangles glued back to back); nothing would be left.
* ``lone-triangle``: a boundary edge whose triangle has its other two edges on the
  boundary too; the collapse would leave a bare edge with no face.
* ``both-ends-on-boundary``: an interior edge whose two ends are both on the boundary;
  the merged vertex would be on the boundary twice (a figure-8 pinch).
* ``link-condition``: ``vA`` and ``vB`` share a neighbour that is not opposite the
  edge (``vL`` or ``vR``); its two edges to them would become one doubled edge and
  the surface would be pinched there.
* ``tetrahedron``: both ends are interior of degree 3 with the same neighbours: the
  edge lies on a closed tetrahedron. pmp-library and OpenMesh allow this collapse and
  leave two triangles glued back to back (a 2-face "pillow", not a surface any other
  operation here accepts). We refuse it, as the full link condition does: the edge
  ``vL - vR`` lies in the links of both ``vA`` and ``vB`` but not in the link of the
  edge. Together, these four rules are the link condition of ``link.py`` with the
  boundary counted as one extra vertex: the check asks ``link_violation`` there, the
  one implementation of the condition, and names the rule from what it found.

The check walks the one-rings of ``vA`` and ``vB``, and the collapse the one-ring of
``vB``: O(degree) work, whatever the size of the mesh.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..elements import Vertex
from .check import OpCheck, edge_argument, position_argument
from .link import BOUNDARY, link_violation, outgoing
from .log import OperationLog, Writer, writer_for

if TYPE_CHECKING:
    from ..mesh import HalfedgeMesh

__all__ = ["CollapseRecord", "apply_collapse", "can_collapse", "collapse", "prepare_collapse"]


def can_collapse(mesh: "HalfedgeMesh", edge) -> OpCheck:
    """Whether ``edge`` can be collapsed: a truthy :class:`OpCheck`, or falsy with the reason.

    ``edge`` is an :class:`Edge`, an edge index or a :class:`Halfedge`. The answer does
    not depend on the direction. The mesh is not changed.
    """
    _, h_BA = edge_argument(mesh, edge, "collapse")
    return _check(mesh, h_BA)


def _listed(vertices) -> str:
    return ", ".join(str(v) for v in vertices)


def _check(mesh: "HalfedgeMesh", h_BA: int, check_link: bool = True) -> OpCheck:
    """The rules, in the module docstring's order: back to back, then the link condition.

    ``check_link=False`` (the teaching switch of :func:`collapse`) stops after back to back.

    :func:`~halfedge_edu.core.ops.link.link_violation` decides the link condition; its
    answer (what ``link(a) ∩ link(b)`` has beyond ``link(ab)``) tells which rule it is:
    the boundary vertex shared by an interior edge (both ends on the boundary), the
    edge from the boundary to the opposite vertex (a lone triangle), shared neighbours
    (the link condition proper) or, with none of those, the edge ``vL - vR`` (the
    tetrahedron).
    """
    origin_of, next_of, prev_of = mesh._halfedge_vertex.item, mesh._halfedge_next.item, mesh._halfedge_prev.item
    face_of = mesh._halfedge_face.item
    e, h_AB = h_BA >> 1, h_BA ^ 1
    a, b = origin_of(2 * e), origin_of(2 * e + 1)  # the edge's own order, for messages
    fL, fR = face_of(h_BA), face_of(h_AB)
    vL = origin_of(prev_of(h_BA)) if fL >= 0 else BOUNDARY
    vR = origin_of(prev_of(h_AB)) if fR >= 0 else BOUNDARY
    edge_words = f"edge {e} (vertices {a} and {b})"

    if fL >= 0 and fR >= 0 and vL == vR:
        return OpCheck.refuse(
            "back-to-back",
            f"both triangles beside {edge_words} have vertex {vL} opposite it: they are glued back "
            f"to back, and collapsing the edge would leave no triangle at all.",
            (("edge", e), ("vertex", vL)),
        )
    if not check_link:
        return OpCheck.ok(
            f"{edge_words} may be collapsed without the link condition (check_link=False): the "
            f"result may not be a valid mesh; mesh.validate() says why."
        )
    extra = link_violation(mesh, e)
    opposite = sorted(v for v in (vL, vR) if v != BOUNDARY)
    if BOUNDARY in extra.vertices:
        return OpCheck.refuse(
            "both-ends-on-boundary",
            f"{edge_words} is interior (it has a triangle on each side) but both its ends are on "
            f"the boundary: the merged vertex would lie on the boundary twice, pinching the "
            f"surface into a figure 8 there (a non-manifold vertex).",
            (("edge", e), ("vertex", a), ("vertex", b)),
        )
    if len(opposite) == 1 and (BOUNDARY, opposite[0]) in extra.edges:
        inside = h_BA if fL >= 0 else h_AB
        f = face_of(inside)
        corners = _listed((origin_of(inside), origin_of(next_of(inside)), origin_of(prev_of(inside))))
        return OpCheck.refuse(
            "lone-triangle",
            f"face {f} (vertices {corners}) has all three edges on the boundary: it is a lone "
            f"triangle, and collapsing its {edge_words} would leave a bare edge with no face.",
            (("edge", e), ("face", f)),
        )
    if extra.vertices:
        shared = sorted(extra.vertices.union(opposite))
        allowed = (
            f"only the vertices opposite the edge ({_listed(opposite)}) may be shared"
            if len(opposite) == 2
            else f"only the vertex opposite this boundary edge ({opposite[0]}) may be shared"
        )
        in_extra = sorted(extra.vertices)
        return OpCheck.refuse(
            "link-condition",
            f"vertices {a} and {b} share {len(shared)} neighbours ({_listed(shared)}), but {allowed}: "
            f"collapsing {edge_words} would pinch the surface at {' and '.join(map(str, in_extra))} (its "
            f"edges to {a} and to {b} would become one doubled edge).",
            (("edge", e),) + tuple(("vertex", v) for v in in_extra),
        )
    if extra.edges:
        return OpCheck.refuse(
            "tetrahedron",
            f"vertices {a} and {b} have only 3 edges each and share their other neighbours {vL} "
            f"and {vR}: together they make a closed tetrahedron. Collapsing {edge_words} would leave "
            f"two triangles glued back to back on vertices {vL}, {vR} and the merged vertex. The "
            f"link condition refuses it: edge {min(vL, vR)}-{max(vL, vR)} lies in the links of both "
            f"vertices but not in the link of the edge.",
            (("edge", e), ("vertex", vL), ("vertex", vR)),
        )
    return OpCheck.ok(f"{edge_words} can be collapsed: vertices {a} and {b} share only {_listed(opposite)}")


def _take_place(mesh: "HalfedgeMesh", write: Writer, old: int, new: int) -> None:
    """Halfedge ``new`` takes the place of ``old`` in old's face (or boundary loop).

    The neighbours are read now, not when the collapse began: in the degree-3 case an
    earlier step has just changed them.
    """
    before, after = mesh._halfedge_prev.item(old), mesh._halfedge_next.item(old)
    face = mesh._halfedge_face.item(old)
    write.link(before, new)
    write.link(new, after)
    write.set_face(new, face)
    if face >= 0 and mesh._face_halfedge.item(face) == old:
        write.set_face_halfedge(face, new)


class CollapseRecord(NamedTuple):
    """A prepared collapse: every element it names, gathered before anything changes.

    The first eighteen fields are the names of the picture in this module's docstring
    (-1 for what does not exist at a boundary edge); :func:`apply_collapse` does the
    collapse from them alone. Made by :func:`prepare_collapse`.
    """

    vA: int
    vB: int
    h_BA: int
    h_AB: int
    fL: int
    vL: int
    h_A_L: int
    h_L_B: int
    h_L_A: int
    h_B_L: int
    gL: int
    fR: int
    vR: int
    h_B_R: int
    h_R_A: int
    h_R_B: int
    h_A_R: int
    gR: int
    #: the halfedges that leave vB, apart from h_BA, h_B_L and h_B_R: they will leave vA
    moving: tuple[int, ...]
    #: vB's degree before the collapse
    degree_B: int
    #: vB's outgoing boundary halfedge, or -1 when vB is interior
    boundary_of_B: int
    #: whether vA is interior (not on the boundary) before the collapse
    interior_A: bool
    #: (3,) where vA goes
    position: np.ndarray

    @property
    def edge(self) -> int:
        """The collapsed edge."""
        return self.h_BA >> 1

    def names(self) -> dict[str, tuple[str, int]]:
        """Name -> ``(kind, index)`` of the picture's elements, in order, for ``OperationLog.name``."""
        kinds = {"v": "vertex", "h": "halfedge", "f": "face", "g": "face"}
        return {name: (kinds[name[0]], index) for name, index in zip(self._fields[:18], self)}


def prepare_collapse(mesh: "HalfedgeMesh", edge, position=None, *, check_link: bool = True) -> CollapseRecord | None:
    """Gather a collapse of ``edge`` without changing anything: its record, or None when refused.

    The first half of :func:`collapse` (the UChicago assignment's "prepare, then do"):
    pass the record to :func:`apply_collapse` to do it. When the collapse is refused,
    ``can_collapse(mesh, edge).reason`` says why.

    Args:
        edge, position: as for :func:`collapse`.
        check_link: False skips the link condition (see :func:`collapse`).

    Raises:
        IndexError: there is no such edge, or it was deleted.
        ValueError: ``position`` is not three finite numbers.
    """
    e, h_BA = edge_argument(mesh, edge, "collapse")
    position = position_argument(mesh, e, position, "collapse")
    if not _check(mesh, h_BA, check_link):
        return None
    return _gather(mesh, h_BA, position)


def _gather(mesh: "HalfedgeMesh", h_BA: int, position: np.ndarray) -> CollapseRecord:
    """Every named element of the collapse of ``h_BA`` (see the picture), before anything changes."""
    next_of, prev_of = mesh._halfedge_next.item, mesh._halfedge_prev.item
    origin_of, face_of = mesh._halfedge_vertex.item, mesh._halfedge_face.item
    vertex_halfedge_of = mesh._vertex_halfedge.item
    h_AB = h_BA ^ 1
    vB, vA = origin_of(h_BA), origin_of(h_AB)
    fL, fR = face_of(h_BA), face_of(h_AB)
    h_A_L = h_L_B = h_L_A = h_B_L = vL = gL = -1  # the side of fL, if it has a face
    if fL >= 0:
        h_A_L, h_L_B = next_of(h_BA), prev_of(h_BA)
        h_L_A, h_B_L = h_A_L ^ 1, h_L_B ^ 1
        vL, gL = origin_of(h_L_B), face_of(h_B_L)
    h_B_R = h_R_A = h_R_B = h_A_R = vR = gR = -1  # the side of fR, if it has a face
    if fR >= 0:
        h_B_R, h_R_A = next_of(h_AB), prev_of(h_AB)
        h_R_B, h_A_R = h_B_R ^ 1, h_R_A ^ 1
        vR, gR = origin_of(h_R_A), face_of(h_R_B)
    ring_B = outgoing(mesh, vB)
    moving = tuple(h for h in ring_B if h != h_BA and h != h_B_L and h != h_B_R)
    boundary_of_B = vertex_halfedge_of(vB) if face_of(vertex_halfedge_of(vB)) < 0 else -1
    interior_A = face_of(vertex_halfedge_of(vA)) >= 0
    return CollapseRecord(
        vA, vB, h_BA, h_AB, fL, vL, h_A_L, h_L_B, h_L_A, h_B_L, gL,
        fR, vR, h_B_R, h_R_A, h_R_B, h_A_R, gR, moving, len(ring_B), boundary_of_B, interior_A, position,
    )


def apply_collapse(mesh: "HalfedgeMesh", record: CollapseRecord, *, log: OperationLog | None = None) -> Vertex:
    """Do a collapse that :func:`prepare_collapse` gathered: the second half of :func:`collapse`.

    ``mesh`` must be as it was when the record was prepared.

    Returns:
        The surviving vertex ``vA``.

    Raises:
        ValueError: the record does not fit the mesh any more (its edge was deleted or
            its ends changed since it was prepared); the mesh is unchanged.
    """
    e, origin_of = record.edge, mesh._halfedge_vertex.item
    if mesh._edge_deleted.item(e) or origin_of(record.h_BA) != record.vB or origin_of(record.h_AB) != record.vA:
        raise ValueError(f"apply_collapse: the mesh changed since the collapse of edge {e} was prepared; prepare it again")
    return _apply(mesh, record, log)


def _apply(mesh: "HalfedgeMesh", record: CollapseRecord, log: OperationLog | None) -> Vertex:
    """The collapse itself, from a record gathered on the mesh as it is (see the picture)."""
    (vA, vB, h_BA, h_AB, fL, vL, h_A_L, h_L_B, h_L_A, h_B_L, gL,
     fR, vR, h_B_R, h_R_A, h_R_B, h_A_R, gR, moving, degree_B, boundary_of_B, interior_A, position) = record
    e = h_BA >> 1
    next_of, prev_of = mesh._halfedge_next.item, mesh._halfedge_prev.item
    vertex_halfedge_of = mesh._vertex_halfedge.item
    if log is not None:
        log.begin("collapse", e, h_BA)
        log.name(**record.names())
        log.notes.append(f"vB = vertex {vB} is removed; vA = vertex {vA} survives")
        if degree_B == 3 and boundary_of_B < 0:
            log.notes.append(
                f"vB has degree 3: gL and gR are the same face {gL}, which survives as (vA, vL, vR); "
                f"no other halfedge leaves vB"
            )
        else:
            log.notes.append(f"vB has degree {degree_B}: {len(moving)} more halfedges leave it and move to vA")
        if fL < 0 or fR < 0:
            log.notes.append(f"edge {e} is on the boundary: only {'fR' if fL < 0 else 'fL'} is removed")
    write = writer_for(mesh, log)

    write.phase("vA moves to the new position")
    write.set_position(vA, position)

    write.phase("vB's other halfedges now leave vA")
    for h in moving:
        write.set_vertex(h, vA)

    if fL >= 0:
        write.phase("fL goes: h_A_L takes the place of h_B_L (in gL); edge vB - vL will be deleted")
        _take_place(mesh, write, h_B_L, h_A_L)
        if vertex_halfedge_of(vL) == h_L_B:
            write.set_vertex_halfedge(vL, h_L_A)
    if fR >= 0:
        write.phase("fR goes: h_R_A takes the place of h_R_B (in gR); edge vB - vR will be deleted")
        _take_place(mesh, write, h_R_B, h_R_A)
        if vertex_halfedge_of(vR) == h_R_B:
            write.set_vertex_halfedge(vR, h_R_A)
    if fL < 0 or fR < 0:
        write.phase("the collapsed edge leaves the boundary loop")
        on_boundary = h_BA if fL < 0 else h_AB
        write.link(prev_of(on_boundary), next_of(on_boundary))

    write.phase("vA's halfedge: its boundary halfedge if the merged vertex is on the boundary")
    if boundary_of_B >= 0 and (interior_A or fR < 0):
        write.set_vertex_halfedge(vA, h_A_L if boundary_of_B == h_B_L else boundary_of_B)
    elif vertex_halfedge_of(vA) == h_AB:
        write.set_vertex_halfedge(vA, h_A_R)

    write.phase("delete vB, the faces fL and fR, the edge and vB's edges to vL and vR")
    for f in (fL, fR):
        if f >= 0:
            write.delete_face(f)
    write.delete_edge(e)
    for h in (h_L_B, h_B_R):
        if h >= 0:
            write.delete_edge(h >> 1)
    write.delete_vertex(vB)
    write.touch()
    return Vertex(mesh, vA)


def collapse(mesh: "HalfedgeMesh", edge, position=None, *, log: OperationLog | None = None,
             check_link: bool = True) -> Vertex:
    """Collapse ``edge``: its two ends become one vertex at ``position`` (midpoint by default).

    It checks (as :func:`can_collapse`), gathers (the record :func:`prepare_collapse`
    makes) and applies it (as :func:`apply_collapse`, without re-checking a record it
    has just made).

    Args:
        edge: an :class:`Edge` or edge index (its halfedge ``2e``'s origin is removed),
            or a :class:`Halfedge` ``h`` (``h``'s origin is removed, its tip survives).
        position: (3,) where the merged vertex goes; None for the edge's midpoint.
        log: an :class:`OperationLog` to fill with the named elements (see the
            picture in this module's docstring) and every pointer change; None records
            nothing.
        check_link: a teaching switch. False skips the link condition (the rules
            ``link-condition``, ``tetrahedron``, ``both-ends-on-boundary`` and
            ``lone-triangle``) and collapses anyway, to see what goes wrong: the result
            may then not be a valid mesh, and ``mesh.validate()`` says why (for example
            ``duplicate-edge``). Only ``back-to-back`` is still refused.

    Returns:
        The surviving vertex ``vA``.

    Raises:
        TopologyError: the collapse is not allowed (the reason says why); the mesh is unchanged.
        IndexError: there is no such edge, or it was deleted.
        ValueError: ``position`` is not three finite numbers (the mesh is unchanged).

    Attention: the removed vertex, faces and edges are only flagged deleted; indices are
    compacted by ``garbage_collect()``.
    """
    e, h_BA = edge_argument(mesh, edge, "collapse")
    position = position_argument(mesh, e, position, "collapse")
    check = _check(mesh, h_BA, check_link)
    if not check:
        raise check.error()
    return _apply(mesh, _gather(mesh, h_BA, position), log)
