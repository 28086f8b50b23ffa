"""Which vertices and halfedges lie near a highlight: rings of vertices, the arrows between them.

A large mesh draws its arrows only near what is highlighted; these functions say where
"near" ends. They walk the one-rings of only the vertices a question reaches
(:class:`Rings`), a few numpy passes over a few hundred vertices, without a Python loop
per vertex and without a pass over the whole mesh per question. :class:`Origins` says
which halfedges leave given vertices in a locally edited mesh (a stepper's states) from
a table made once and the few halfedges that changed since.
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
    mesh, once per state (one ``bincount``), unless :class:`Origins` gives them.

    Args:
        mesh: the mesh.
        degree: (n_vertex_slots,) each vertex's live outgoing halfedges, if known
            (:meth:`Origins.degree`); counted over the whole mesh otherwise.

    Attention: the answers are for the mesh as it was when this was made; make a new one
    after an edit (:meth:`is_for` says whether one still fits).
    """

    def __init__(self, mesh, degree: np.ndarray | None = None):
        self.mesh = mesh
        self.topology_version = mesh.topology_version
        if degree is None:
            degree = mesh.vertex_degrees()
        # (n_vertex_slots,) the walk length of each vertex: its live outgoing halfedges;
        # 0 for deleted vertices, whose rings the whole-mesh adjacency leaves empty.
        self.degree = np.where(mesh.vertex_deleted, 0, degree)
        # The last breadth-first walk: (seeds as bytes, marks after 0, 1, ... rings,
        # the last frontier). One update asks for one and two rings around the same focus
        # (labels near it, the window, the dots), which are levels of one walk.
        self._walk: tuple[bytes, list[np.ndarray], np.ndarray] | None = None

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
        if self._walk is None or self._walk[0] != seeds.tobytes():
            mark = np.zeros(self.mesh.n_vertex_slots, dtype=bool)
            mark[seeds] = True
            self._walk = (seeds.tobytes(), [mark], seeds)
        key, levels, frontier = self._walk
        while len(levels) <= rings and len(frontier):
            mark = levels[-1].copy()
            reached = self.neighbours(frontier)
            frontier = np.unique(reached[~mark[reached]])
            mark[frontier] = True
            levels.append(mark)
            self._walk = (key, levels, frontier)
        return levels[min(rings, len(levels) - 1)].copy()

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


class Origins:
    """Which halfedges leave each vertex, in a mesh and in its local edits (a stepper's states).

    Made once from the mesh as drawn: its live halfedges sorted by origin (one sort). An
    edited version keeps the indices and differs in a few halfedges: their origin or their
    deleted flag changed, or they were created. Those are found with one comparison of the
    origin arrays (much cheaper than a gather or a sort over the whole mesh), and every
    answer is the table's, with those few halfedges looked at again.

    Attention: for edits that keep indices (no ``garbage_collect()``); a mesh with fewer
    slots than the table is read as a new mesh.
    """

    def __init__(self, mesh):
        self._tabulate(mesh)

    def _tabulate(self, mesh) -> None:
        self.origin = mesh.halfedge_vertex.copy()                          # (H0,) as built
        self.live = ~mesh.halfedge_deleted                                 # (H0,)
        self.edge_live = ~mesh.edge_deleted                                # (H0 / 2,)
        live = np.flatnonzero(self.live)
        order = np.argsort(self.origin[live], kind="stable")
        #: Live halfedges by origin: those leaving v are by_origin[offsets[v]:offsets[v + 1]].
        self.by_origin = live[order]
        self.offsets = np.searchsorted(self.origin[self.by_origin], np.arange(mesh.n_vertex_slots + 1))
        self.built_degree = np.diff(self.offsets)                           # (V0,)
        self._state = None                                                 # (mesh, version, changed)

    def changed(self, mesh) -> np.ndarray:
        """(c,) sorted: the halfedges of ``mesh`` whose origin or deleted flag differ from
        the table's, and those created since (remembered for the last mesh asked about)."""
        state = self._state
        if state is not None and state[0] is mesh and state[1] == mesh.topology_version:
            return state[2]
        n_built = len(self.origin)
        if mesh.n_halfedge_slots < n_built or mesh.n_vertex_slots < len(self.built_degree):
            self._tabulate(mesh)
            n_built = len(self.origin)
        moved = np.flatnonzero(mesh.halfedge_vertex[:n_built] != self.origin)
        # An edge deleted or brought back changes both its halfedges.
        flagged = np.flatnonzero(~mesh.edge_deleted[: n_built // 2] != self.edge_live)
        changed = np.unique(np.concatenate([moved, 2 * flagged, 2 * flagged + 1,
                                            np.arange(n_built, mesh.n_halfedge_slots)]))
        self._state = (mesh, mesh.topology_version, changed)
        return changed

    def degree(self, mesh) -> np.ndarray:
        """(n_vertex_slots,) how many live halfedges leave each vertex of ``mesh`` now
        (``mesh.vertex_degrees()``, from the table and the changed halfedges)."""
        changed = self.changed(mesh)
        degree = np.zeros(mesh.n_vertex_slots, dtype=np.int64)
        degree[: len(self.built_degree)] = self.built_degree
        before = changed[changed < len(self.origin)]
        np.subtract.at(degree, self.origin[before[self.live[before]]], 1)
        origin_now = mesh.halfedge_vertex[changed[~mesh.edge_deleted[changed >> 1]]]
        np.add.at(degree, origin_now[origin_now >= 0], 1)
        return degree

    def leaving(self, mesh, vertices: np.ndarray) -> np.ndarray:
        """(k,) sorted: the live halfedges of ``mesh`` whose origin is one of ``vertices`` now."""
        vertices = np.asarray(vertices, dtype=np.int64)
        changed = self.changed(mesh)
        built = vertices[vertices < len(self.built_degree)]
        table = self.by_origin[ranges(self.offsets[built], self.offsets[built + 1])]
        table = table[~np.isin(table, changed)]                            # still leaving them
        changed = changed[~mesh.edge_deleted[changed >> 1]]
        moved = changed[np.isin(mesh.halfedge_vertex[changed], vertices)]
        return np.sort(np.concatenate([table, moved]))


def ring_window(mesh, seeds: np.ndarray, rings: int) -> tuple[np.ndarray, np.ndarray]:
    """The vertices within ``rings`` edges of ``seeds`` and the halfedges between them
    (see :meth:`Rings.window`)."""
    return Rings(mesh).window(seeds, rings)
