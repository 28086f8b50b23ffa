"""Element handles: small objects that make ``h.next.twin.vertex`` read like the notes.

A handle is ``(mesh, index)`` plus the mesh's *generation* when it was made. Every
attribute reads the mesh's arrays at the moment you ask, so a handle follows local
operations (flip, split and collapse keep indices). ``garbage_collect()`` is different:
it renumbers elements to close the gaps deletions left, so after it index 20 may name
another edge. It therefore starts a new generation, and a handle from an earlier one
raises :class:`~halfedge_edu.core.errors.StaleHandleError` on any use (its index,
navigation, ``int(h)``, passing it to ``mesh.flip``) instead of silently naming
whatever now has its index; the error points to the maps ``garbage_collect()``
returned. (As a numpy index, ``mesh.positions[v]``, a stale handle is refused with
numpy's own ``IndexError``: numpy replaces the handle's message with its generic one.)
A collection that removes nothing renumbers nothing and keeps the generation.

Two handles are equal when they are of the same kind, on the same mesh, of the same
generation, with the same index; they hash by kind and index, so they work in sets and
as dict keys. Comparing, hashing and ``repr`` never raise, also for a stale handle.

Handles convert to their index with ``int(h)`` (and work directly as numpy indices),
so ``mesh.positions[v]`` and ``mesh.flip(e)`` accept either a handle or a number.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .errors import StaleHandleError

if TYPE_CHECKING:
    from .mesh import HalfedgeMesh


class _Handle:
    __slots__ = ("mesh", "_index", "_generation")

    #: "vertex", "halfedge", "edge" or "face": for messages.
    kind = "element"

    def __init__(self, mesh: "HalfedgeMesh", index: int):
        self.mesh = mesh
        self._index = int(index)
        self._generation = mesh._generation

    @property
    def index(self) -> int:
        """The element's index; raises ``StaleHandleError`` after a renumbering ``garbage_collect()``."""
        if self._generation != self.mesh._generation:
            raise StaleHandleError(self.kind, self._index, self._generation, self.mesh._generation)
        return self._index

    @property
    def is_stale(self) -> bool:
        """True when ``garbage_collect()`` renumbered the mesh after this handle was made."""
        return self._generation != self.mesh._generation

    def __eq__(self, other: object) -> bool:
        return (
            type(other) is type(self)
            and other.mesh is self.mesh  # type: ignore[attr-defined]
            and other._index == self._index  # type: ignore[attr-defined]
            and other._generation == self._generation  # type: ignore[attr-defined]
        )

    def __hash__(self) -> int:
        return hash((type(self).__name__, self._index))

    def __index__(self) -> int:
        return self.index

    def __int__(self) -> int:
        return self.index

    def _stale_repr(self) -> str:
        """What ``repr`` shows for a stale handle (it must not raise in a notebook)."""
        return f"{type(self).__name__}({self._index}: stale, taken before garbage_collect())"


class Halfedge(_Handle):
    """One side of an edge. It runs from ``vertex`` (its origin, or tail) to ``tip``."""

    __slots__ = ()
    kind = "halfedge"

    @property
    def next(self) -> "Halfedge":
        """The next halfedge around the same face (counter-clockwise), or along the boundary."""
        return Halfedge(self.mesh, self.mesh._halfedge_next[self.index])

    @property
    def prev(self) -> "Halfedge":
        return Halfedge(self.mesh, self.mesh._halfedge_prev[self.index])

    @property
    def twin(self) -> "Halfedge":
        """The halfedge running the other way along the same edge (index ``h ^ 1``)."""
        return Halfedge(self.mesh, self.index ^ 1)

    @property
    def vertex(self) -> "Vertex":
        """The vertex this halfedge leaves (its origin)."""
        return Vertex(self.mesh, self.mesh._halfedge_vertex[self.index])

    @property
    def tip(self) -> "Vertex":
        """The vertex this halfedge points to (the origin of its twin)."""
        return Vertex(self.mesh, self.mesh._halfedge_vertex[self.index ^ 1])

    @property
    def edge(self) -> "Edge":
        """The edge this halfedge belongs to (index ``h >> 1``)."""
        return Edge(self.mesh, self.index >> 1)

    @property
    def face(self) -> "Face | None":
        """The face on this halfedge's left, or None for a boundary halfedge."""
        f = int(self.mesh._halfedge_face[self.index])
        return None if f < 0 else Face(self.mesh, f)

    @property
    def is_boundary(self) -> bool:
        """True when there is no face on this halfedge's side (it runs along a hole)."""
        return bool(self.mesh._halfedge_face[self.index] < 0)

    @property
    def is_deleted(self) -> bool:
        return bool(self.mesh._edge_deleted[self.index >> 1])

    @property
    def vector(self) -> np.ndarray:
        """(3,) tip position minus origin position."""
        positions = self.mesh._positions
        return positions[self.mesh._halfedge_vertex[self.index ^ 1]] - positions[self.mesh._halfedge_vertex[self.index]]

    def __repr__(self) -> str:
        if self.is_stale:
            return self._stale_repr()
        mesh, h = self.mesh, self.index
        face = int(mesh._halfedge_face[h])
        where = "boundary" if face < 0 else f"face {face}"
        return f"Halfedge({h}: {int(mesh._halfedge_vertex[h])} -> {int(mesh._halfedge_vertex[h ^ 1])}, {where})"


class Vertex(_Handle):
    """A point of the mesh, with one outgoing ``halfedge`` to start walks from."""

    __slots__ = ()
    kind = "vertex"

    @property
    def halfedge(self) -> Halfedge | None:
        """One outgoing halfedge; for a boundary vertex, its outgoing *boundary* halfedge."""
        h = int(self.mesh._vertex_halfedge[self.index])
        return None if h < 0 else Halfedge(self.mesh, h)

    @property
    def position(self) -> np.ndarray:
        """(3,) a *view* of the vertex's position: writing into it moves the vertex."""
        return self.mesh._positions[self.index]

    @position.setter
    def position(self, value) -> None:
        self.mesh._positions[self.index] = value

    @property
    def is_boundary(self) -> bool:
        """True for a vertex on a boundary loop (checked in O(1) through its halfedge)."""
        h = int(self.mesh._vertex_halfedge[self.index])
        return h >= 0 and bool(self.mesh._halfedge_face[h] < 0)

    @property
    def is_deleted(self) -> bool:
        return bool(self.mesh._vertex_deleted[self.index])

    def outgoing(self) -> list[Halfedge]:
        """Outgoing halfedges in counter-clockwise order, starting with ``halfedge``.

        The walk is ``h -> h.prev.twin``: ``h.prev`` comes into this vertex, and its
        twin leaves it again in the next face counter-clockwise. (Walking
        ``h -> h.twin.next`` visits the same halfedges clockwise.)
        """
        mesh = self.mesh
        start = int(mesh._vertex_halfedge[self.index])
        if start < 0:
            return []
        ring = [start]
        h = int(mesh._halfedge_prev[start]) ^ 1
        while h != start:
            ring.append(h)
            if len(ring) > 2 * mesh.n_edge_slots:
                raise RuntimeError(f"the one-ring walk around vertex {self.index} does not close; run validate()")
            h = int(mesh._halfedge_prev[h]) ^ 1
        return [Halfedge(mesh, h) for h in ring]

    def neighbors(self) -> list["Vertex"]:
        """The adjacent vertices, counter-clockwise (the tips of :meth:`outgoing`)."""
        return [h.tip for h in self.outgoing()]

    def faces(self) -> list["Face"]:
        """The faces around this vertex, counter-clockwise (boundary gaps skipped)."""
        return [face for face in (h.face for h in self.outgoing()) if face is not None]

    def edges(self) -> list["Edge"]:
        return [h.edge for h in self.outgoing()]

    @property
    def degree(self) -> int:
        """How many edges meet here."""
        return len(self.outgoing())

    def __repr__(self) -> str:
        if self.is_stale:
            return self._stale_repr()
        x, y, z = (float(c) for c in self.mesh._positions[self.index])
        return f"Vertex({self.index}: ({x:.4g}, {y:.4g}, {z:.4g}))"


class Edge(_Handle):
    """An undirected edge. It owns halfedges ``2e`` and ``2e + 1``."""

    __slots__ = ()
    kind = "edge"

    @property
    def halfedge(self) -> Halfedge:
        """Halfedge ``2e``; its twin is ``2e + 1``."""
        return Halfedge(self.mesh, 2 * self.index)

    @property
    def vertices(self) -> tuple[Vertex, Vertex]:
        """The two endpoints: origin and tip of :attr:`halfedge`."""
        h = 2 * self.index
        return Vertex(self.mesh, self.mesh._halfedge_vertex[h]), Vertex(self.mesh, self.mesh._halfedge_vertex[h + 1])

    @property
    def is_boundary(self) -> bool:
        """True when one side of the edge has no face."""
        h = 2 * self.index
        face = self.mesh._halfedge_face
        return bool(face[h] < 0 or face[h + 1] < 0)

    @property
    def is_deleted(self) -> bool:
        return bool(self.mesh._edge_deleted[self.index])

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.halfedge.vector))

    @property
    def midpoint(self) -> np.ndarray:
        a, b = self.vertices
        return 0.5 * (a.position + b.position)

    def faces(self) -> list["Face"]:
        """The one or two faces beside this edge."""
        return [f for f in (self.halfedge.face, self.halfedge.twin.face) if f is not None]

    def __repr__(self) -> str:
        if self.is_stale:
            return self._stale_repr()
        h = 2 * self.index
        side = " boundary" if self.is_boundary else ""
        return f"Edge({self.index}:{side} {int(self.mesh._halfedge_vertex[h])} - {int(self.mesh._halfedge_vertex[h + 1])})"


class Face(_Handle):
    """A triangle, walked counter-clockwise by ``halfedge.next``."""

    __slots__ = ()
    kind = "face"

    @property
    def halfedge(self) -> Halfedge:
        return Halfedge(self.mesh, self.mesh._face_halfedge[self.index])

    def halfedges(self) -> list[Halfedge]:
        """The face's halfedges in CCW order, starting at :attr:`halfedge`."""
        first = self.halfedge
        loop = [first]
        h = first.next
        while h != first:
            loop.append(h)
            if len(loop) > 3:
                raise RuntimeError(f"face {self.index}'s next-loop is longer than 3; run validate()")
            h = h.next
        return loop

    def vertices(self) -> list[Vertex]:
        return [h.vertex for h in self.halfedges()]

    def edges(self) -> list[Edge]:
        return [h.edge for h in self.halfedges()]

    def _corners(self) -> np.ndarray:
        """(3, 3) positions of the corners."""
        return self.mesh._positions[[v.index for v in self.vertices()]]

    @property
    def normal(self) -> np.ndarray:
        """(3,) unit normal by the right-hand rule (zeros for a zero-area face)."""
        a, b, c = self._corners()
        n = np.cross(b - a, c - a)
        length = np.linalg.norm(n)
        return n / length if length > 0 else n

    @property
    def area(self) -> float:
        a, b, c = self._corners()
        return 0.5 * float(np.linalg.norm(np.cross(b - a, c - a)))

    @property
    def centroid(self) -> np.ndarray:
        return self._corners().mean(axis=0)

    @property
    def is_deleted(self) -> bool:
        return bool(self.mesh._face_deleted[self.index])

    def __repr__(self) -> str:
        if self.is_stale:
            return self._stale_repr()
        try:
            corners = [v.index for v in self.vertices()]
        except (IndexError, RuntimeError):
            corners = "?"
        return f"Face({self.index}: {corners})"
