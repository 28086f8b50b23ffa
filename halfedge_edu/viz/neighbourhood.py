"""Which vertices and halfedges lie near a highlight: rings of vertices, the arrows between them.

A large mesh draws its arrows only near what is highlighted; these functions say where
"near" ends. They walk the one-rings of only the vertices a question reaches
(:class:`Rings`), a few numpy passes over a few hundred vertices, without a Python loop
per vertex and without a pass over the whole mesh per question.
"""

from __future__ import annotations

import numpy as np

from ..core.rings import walk_rings


def ranges(starts: np.ndarray, stops: np.ndarray) -> np.ndarray:
    """Concatenate ``arange(s, t)`` for each pair, without a Python loop."""
    lengths = stops - starts
    total = int(lengths.sum())
    if total == 0:
        return np.zeros(0, dtype=np.int64)
    owner_start = np.repeat(starts - np.concatenate([[0], np.cumsum(lengths)[:-1]]), lengths)
    return owner_start + np.arange(total)


class Rings:
    """The vertex rings of one state of ``mesh``, walked only around the vertices asked about.

    ``mesh.vertex_adjacency()`` walks the ring of every vertex (about 9 ms on the 69k-face
    bunny) and keeps it until the connectivity changes. A stepper shows a new mesh at
    every step, so that walk would be paid again each time for the few hundred vertices
    near the operation. Here each question walks the rings of just the vertices it
    reaches, with the same walk (:func:`~halfedge_edu.core.rings.walk_rings`) and the same
    degrees, so the answers are exactly those of the whole-mesh adjacency, even on a half
    rewired mesh whose rings do not close. Only the degrees are counted over the whole
    mesh, once (one ``bincount``).

    Attention: the answers are for the mesh as it was when this was made; make a new one
    after an edit (:meth:`is_for` says whether one still fits).
    """

    def __init__(self, mesh):
        self.mesh = mesh
        self.topology_version = mesh.topology_version
        # (n_vertex_slots,) the walk length of each vertex: its live outgoing halfedges;
        # 0 for deleted vertices, whose rings the whole-mesh adjacency leaves empty.
        self.degree = np.where(mesh.vertex_deleted, 0, mesh.vertex_degrees())

    def is_for(self, mesh) -> bool:
        """True when ``mesh`` is the mesh these rings were walked on, not edited since."""
        return mesh is self.mesh and mesh.topology_version == self.topology_version

    def outgoing(self, vertices: np.ndarray) -> np.ndarray:
        """All outgoing halfedges of ``vertices``, ring after ring, each ring counter-clockwise
        (a ring that stops early, on a broken mesh, is padded with -1 as the walk pads it)."""
        vertices = np.asarray(vertices, dtype=np.int64)
        walk = walk_rings(vertices, self.mesh.vertex_halfedge, self.mesh.halfedge_prev, self.degree[vertices])
        return walk.halfedges.astype(np.int64)

    def neighbours(self, vertices: np.ndarray) -> np.ndarray:
        """The tips of the outgoing halfedges of ``vertices`` (with repeats), as
        ``mesh.vertex_adjacency()`` lists them."""
        return self.mesh.halfedge_vertex[self.outgoing(vertices) ^ 1]

    def mark(self, seeds: np.ndarray, rings: int) -> np.ndarray:
        """(n_vertex_slots,) bool: the vertices within ``rings`` edges of ``seeds``."""
        seeds = np.asarray(seeds, dtype=np.int64)
        mark = np.zeros(self.mesh.n_vertex_slots, dtype=bool)
        mark[seeds] = True
        frontier = seeds
        for _ in range(rings):
            reached = self.neighbours(frontier)
            frontier = np.unique(reached[~mark[reached]])
            if len(frontier) == 0:
                break
            mark[frontier] = True
        return mark

    def window(self, seeds: np.ndarray, rings: int) -> tuple[np.ndarray, np.ndarray]:
        """The vertices within ``rings`` edges of ``seeds`` and the halfedges between them.

        Returns:
            ``(vertices, halfedges)``: (k,) sorted vertex indices and (m,) sorted halfedge
            indices whose two ends are both among those vertices.
        """
        mark = self.mark(seeds, rings)
        inside = np.flatnonzero(mark)
        outgoing = self.outgoing(inside)
        return inside, np.sort(outgoing[mark[self.mesh.halfedge_vertex[outgoing ^ 1]]])


def ring_mark(mesh, seeds: np.ndarray, rings: int) -> np.ndarray:
    """(n_vertex_slots,) bool: the vertices within ``rings`` edges of ``seeds`` (see :class:`Rings`)."""
    return Rings(mesh).mark(seeds, rings)


def ring_window(mesh, seeds: np.ndarray, rings: int) -> tuple[np.ndarray, np.ndarray]:
    """The vertices within ``rings`` edges of ``seeds`` and the halfedges between them
    (see :meth:`Rings.window`)."""
    return Rings(mesh).window(seeds, rings)
