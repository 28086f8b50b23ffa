"""Topology of any triangle list, built without breaking: the structure for chapter 04's questions.

``HalfedgeMesh.from_faces`` refuses a face list the halfedge structure cannot hold (an
edge with three faces, a vertex where two cones touch). To *ask* such a list what is
wrong with it, UChicago's assignment (P3) builds "the topology for non-manifold OBJs
without breaking" and then asks it ``hasNonManifoldVertices()`` and
``hasNonManifoldEdges()``. ``SoupTopology`` is that general structure:

    soup = SoupTopology(hx.sample("nonmanifold_edge").faces)
    soup.faces_of_edge(0, 1)          # [0, 1, 2]: three faces on one edge
    soup.has_nonmanifold_edges()      # True
    soup.fans(0)                      # the faces around vertex 0, grouped into fans

Conventions:

* Each face ``f`` makes three halfedges, ``3f``, ``3f + 1``, ``3f + 2``; halfedge ``3f + k``
  runs from ``faces[f][k]`` to ``faces[f][(k + 1) % 3]``, and its ``next`` is the following
  one in the same face. These always exist, whatever the faces are.
* An edge is an unordered vertex pair; it keeps *all* the halfedges that run along it,
  however many (a halfedge mesh has room for two). ``twin`` is only defined where an edge
  has exactly two halfedges running opposite ways; elsewhere it is -1.
* An edge is manifold when one or two faces use it. A vertex is manifold when its faces
  form one fan: each can be reached from any other by crossing edges at that vertex.

Positions are not needed: topology comes from the faces alone.
"""

from __future__ import annotations

import numpy as np

from .manifold import check_faces_array

__all__ = ["SoupTopology"]


class SoupTopology:
    """Faces, halfedges and edges of any triangle list, manifold or not.

    Args:
        faces: (m, 3) int triangles, 0-based (a polygon soup cut into triangles).
        n_vertices: the number of vertices (default: the largest index + 1).

    Attributes:
        faces: (m, 3) int64, the triangles.
        halfedge_vertex: (3m,) int64, the vertex each halfedge leaves.
        halfedge_face: (3m,) int64, the face of each halfedge (``h // 3``).
        halfedge_next: (3m,) int64, the next halfedge round the same face.
        halfedge_twin: (3m,) int64, the twin where the edge has exactly two halfedges
            running opposite ways, else -1.
    """

    def __init__(self, faces, n_vertices: int | None = None):
        self.faces, self.n_vertices = check_faces_array(faces, n_vertices)
        m = len(self.faces)
        corner = np.arange(3 * m)                                             # (3m,) halfedge ids
        self.halfedge_vertex = self.faces.reshape(-1).copy()                  # (3m,) tail of each halfedge
        self.halfedge_face = corner // 3                                      # (3m,)
        self.halfedge_next = corner - corner % 3 + (corner % 3 + 1) % 3       # (3m,)
        tips = self.halfedge_vertex[self.halfedge_next]                       # (3m,) head of each halfedge

        # 1. Every edge keeps the list of its halfedges, however many there are.
        self._edge_halfedges: dict[tuple[int, int], list[int]] = {}
        for h in range(3 * m):
            a, b = int(self.halfedge_vertex[h]), int(tips[h])
            self._edge_halfedges.setdefault((min(a, b), max(a, b)), []).append(h)

        # 2. Twins only where the edge looks like a halfedge mesh's: two halfedges, opposite ways.
        self.halfedge_twin = np.full(3 * m, -1, dtype=np.int64)
        for pair in self._edge_halfedges.values():
            if len(pair) == 2 and self.halfedge_vertex[pair[0]] == tips[pair[1]]:
                self.halfedge_twin[pair[0]], self.halfedge_twin[pair[1]] = pair[1], pair[0]

        # 3. Each vertex keeps the faces that use it.
        self._vertex_faces: dict[int, list[int]] = {}
        for f, face in enumerate(self.faces.tolist()):
            for v in face:
                self._vertex_faces.setdefault(v, []).append(f)

    # ----------------------------------------------------------------------------------
    # Questions about elements
    # ----------------------------------------------------------------------------------

    @property
    def n_faces(self) -> int:
        return len(self.faces)

    def edges(self) -> list[tuple[int, int]]:
        """Every edge as a vertex pair ``(a, b)`` with ``a < b``, in the order first used."""
        return list(self._edge_halfedges)

    def halfedges_of_edge(self, a: int, b: int) -> list[int]:
        """The halfedges running along edge ``(a, b)`` either way ([] if there is no such edge)."""
        return list(self._edge_halfedges.get((min(a, b), max(a, b)), []))

    def faces_of_edge(self, a: int, b: int) -> list[int]:
        """The faces that use edge ``(a, b)``: one on the boundary, two inside, more when non-manifold."""
        return [int(self.halfedge_face[h]) for h in self.halfedges_of_edge(a, b)]

    def faces_of_vertex(self, v: int) -> list[int]:
        """The faces that use vertex ``v`` ([] for a vertex no face uses)."""
        return list(self._vertex_faces.get(int(v), []))

    def fans(self, v: int) -> list[list[int]]:
        """The faces around ``v`` grouped into fans: two faces are in one fan when a chain of
        faces joins them, each sharing an edge at ``v`` with the one before it."""
        unvisited = set(self.faces_of_vertex(v))
        fans = []
        while unvisited:
            start = min(unvisited)
            fan, stack = [], [start]
            unvisited.discard(start)
            while stack:
                f = stack.pop()
                fan.append(f)
                for u in self.faces[f].tolist():                         # the face's two edges at v
                    if u == v:
                        continue
                    for g in self.faces_of_edge(v, u):
                        if g in unvisited:
                            unvisited.discard(g)
                            stack.append(g)
            fans.append(sorted(fan))
        return fans

    # ----------------------------------------------------------------------------------
    # UChicago P3's two questions
    # ----------------------------------------------------------------------------------

    def nonmanifold_edges(self) -> list[tuple[int, int]]:
        """The edges with more than two faces."""
        return [edge for edge, halfedges in self._edge_halfedges.items() if len(halfedges) > 2]

    def nonmanifold_vertices(self) -> list[int]:
        """The vertices whose faces form more than one fan."""
        return [v for v in sorted(self._vertex_faces) if len(self.fans(v)) > 1]

    def has_nonmanifold_edges(self) -> bool:
        """True when some edge has more than two faces (an edge is manifold with one or two)."""
        return bool(self.nonmanifold_edges())

    def has_nonmanifold_vertices(self) -> bool:
        """True when the faces around some vertex form more than one fan."""
        return bool(self.nonmanifold_vertices())

    def __repr__(self) -> str:
        return (f"SoupTopology({self.n_faces} faces, {len(self._edge_halfedges)} edges, "
                f"{len(self._vertex_faces)} vertices used)")
