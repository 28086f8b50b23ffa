"""Feature edges: the creases and the boundary that remeshing must keep where they are.

A **feature edge** is a boundary edge, or an interior edge whose two faces meet at a
dihedral angle above a threshold (their normals differ by more than ``feature_angle``
degrees): the sharp edges of a CAD part, the rim of a hole. A **feature vertex** lies
on at least one feature edge; a **corner** is a feature vertex with other than two
feature edges (where three creases of a cube meet, or where a crease ends), or one
where its line turns by more than the threshold (the corner of a square hole): it has
no single straight line to move along, so it stays exactly where it is.

Feature edges chain into **feature lines**, from corner to corner (or around a loop
without corners), each with a number. Remeshing (Botsch and Kobbelt 2004, as in
pmp-library's ``uniform_remeshing``) keeps them by four rules: a feature edge is never
flipped; a collapse never moves a feature vertex off its line; a split of a feature
edge makes two feature halves; feature vertices are smoothed only along their line and
projected back onto their own line of the input (by its number: not onto another line
that happens to pass nearer).

Everything here works on plain arrays, as :mod:`.remesh` does: :class:`Features` holds
the feature edges as vertex pairs (k, 2) and the corners as a mask (n,), and has one
method per change :mod:`.remesh` makes to the face array (a split pass, a round of
merges, a compaction), so the features stay the same lines while vertices come, go and
are renumbered. They are found once, on the input, and never again from the changing
geometry: a vertex's status follows from the rules, not from angles that remeshing
itself perturbs.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..core.arrays import csr, face_cross
from ..core.corner_table import EdgeTable, edge_table
from ..core.mesh import HalfedgeMesh
from .arguments import check_mesh, real_number

__all__ = ["DEFAULT_FEATURE_ANGLE", "Features", "detect_features", "feature_arrays", "number_lines"]

#: Edges whose faces meet at more than this many degrees (between the normals) are
#: creases by default. PyMeshLab's isotropic remeshing uses 30, CGAL's examples 60; 45
#: keeps the folds of a machined part and of a low-polygon model, and leaves the
#: small wrinkles of a scanned surface (the bunny's) to be smoothed.
DEFAULT_FEATURE_ANGLE = 45.0


def _keys(pairs: np.ndarray, n: int) -> np.ndarray:
    """(k,) ``low * n + high`` of each pair (the pairs may come in either order)."""
    return np.minimum(pairs[:, 0], pairs[:, 1]) * np.int64(n) + np.maximum(pairs[:, 0], pairs[:, 1])


def _sorted_unique(pairs: np.ndarray, lines: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rows ``low, high`` without repeats, sorted (the form :class:`Features` keeps), and
    the line number (k,) of each kept row."""
    if len(pairs) == 0:
        return pairs.reshape(0, 2), lines
    unique, first = np.unique(pairs, axis=0, return_index=True)
    return unique, lines[first]


def _unit_rows(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(unit rows, nonzero)``: each row scaled to length 1, and which rows had a length."""
    length = np.sqrt(np.einsum("ij,ij->i", rows, rows))
    nonzero = length > 0.0
    return rows / np.where(nonzero, length, 1.0)[:, None], nonzero


class Features(NamedTuple):
    """The feature edges of a face array, the corners among their vertices, and which
    line each edge belongs to.

    ``edges`` (k, 2): each feature edge as ``low, high`` vertex indices, rows sorted.
    ``corners`` (n,): True for the vertices that must not move at all: those with other
    than two feature edges, and those where their line turns by more than the feature
    angle (the corner of a square hole has two boundary edges, at 90 degrees). Corners
    are found once, on the input, and carried along: a vertex made later (a midpoint)
    is never a corner, and no collapse removes one.
    ``lines`` (k,): the number of the line each edge lies on (:func:`number_lines`): the
    edges of one chain between corners share it. Halves of a split edge keep their
    edge's number, so a vertex that is not a corner always has two edges of one line.
    """

    edges: np.ndarray
    corners: np.ndarray
    lines: np.ndarray

    def counts(self) -> np.ndarray:
        """(n,) how many feature edges each vertex has (0: not a feature vertex)."""
        return np.bincount(self.edges.reshape(-1), minlength=len(self.corners))

    def mask(self, table: EdgeTable) -> np.ndarray:
        """(E,) True for the edges of ``table`` (of the same vertices) that are feature edges."""
        return self.edge_mask(table.keys)

    def edge_mask(self, keys: np.ndarray) -> np.ndarray:
        """(E,) True for the edges with sorted keys ``keys`` (``low * n + high``, n the
        number of vertices) that are feature edges. ``keys`` may be the edges of part of
        the mesh: feature edges not among them are left out."""
        mask = np.zeros(len(keys), dtype=bool)
        if len(self.edges) and len(keys):
            feature_keys = _keys(self.edges, len(self.corners))
            at = np.minimum(np.searchsorted(keys, feature_keys), len(keys) - 1)
            mask[at[keys[at] == feature_keys]] = True
        return mask

    def vertex_lines(self) -> np.ndarray:
        """(n,) the number of the line through each vertex, -1 where there is none or
        more than one (off the lines, and at corners where lines meet)."""
        line_of = np.full(len(self.corners), -1, dtype=np.int64)
        line_of[self.edges[:, 0]] = self.lines
        line_of[self.edges[:, 1]] = self.lines
        line_of[self.corners] = -1
        return line_of

    def line_neighbours(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The two neighbours along its line of every vertex with exactly two feature edges.

        Returns ``(on_line, before, after)``, each (j,): those vertices, and their two
        feature neighbours (in no particular order).
        """
        n = len(self.corners)
        offsets, neighbours = csr(self.edges.reshape(-1), self.edges[:, ::-1].reshape(-1), n)
        on_line = np.flatnonzero(np.diff(offsets) == 2)
        return on_line, neighbours[offsets[on_line]], neighbours[offsets[on_line] + 1]

    def split(self, table: EdgeTable, midpoint_of: np.ndarray) -> "Features":
        """After a split pass: a feature edge split at midpoint m becomes ``a-m`` and ``m-b``.

        ``table`` is the edge table the pass used, ``midpoint_of`` (E,) the new vertex on
        each of its edges (-1 where the edge was not split); new vertices are numbered
        after the old ones, and none is a corner.
        """
        n = len(self.corners)
        corners = np.concatenate([self.corners, np.zeros(int((midpoint_of >= 0).sum()), dtype=bool)])
        if len(self.edges) == 0:
            return Features(self.edges, corners, self.lines)
        mid = midpoint_of[np.searchsorted(table.keys, _keys(self.edges, n))]
        cut = mid >= 0
        halves = np.concatenate([np.stack([self.edges[cut, 0], mid[cut]], axis=1),
                                 np.stack([mid[cut], self.edges[cut, 1]], axis=1)])
        halves.sort(axis=1)
        lines = np.concatenate([self.lines[~cut], self.lines[cut], self.lines[cut]])
        edges, lines = _sorted_unique(np.concatenate([self.edges[~cut], halves]), lines)
        return Features(edges, corners, lines)

    def merge(self, remove: np.ndarray, keep: np.ndarray) -> "Features":
        """After merging vertex ``remove[i]`` into ``keep[i]`` (collapses): a collapsed
        feature edge vanishes and the next one along its line now ends at the kept
        vertex, so the line stays one chain. Corners are never removed, so they stay."""
        relabel = np.arange(len(self.corners))
        relabel[remove] = keep
        edges = relabel[self.edges]
        kept = edges[:, 0] != edges[:, 1]
        edges = np.sort(edges[kept], axis=1)
        edges, lines = _sorted_unique(edges, self.lines[kept])
        return Features(edges, self.corners, lines)

    def renumber(self, kept: np.ndarray) -> "Features":
        """After :func:`halfedge_edu.core.arrays.compact` kept the vertices ``kept`` (old
        indices, ascending): the same features in the new numbering."""
        new_index = np.full(len(self.corners), -1, dtype=np.int64)
        new_index[kept] = np.arange(len(kept))
        return Features(new_index[self.edges], self.corners[kept], self.lines)


def feature_arrays(vertices: np.ndarray, faces: np.ndarray, feature_angle: float, *,
                   table: EdgeTable | None = None) -> Features:
    """The :class:`Features` of a face array (positions (n, 3), faces (m, 3)).

    Feature edges: every boundary edge, and every interior edge whose two face normals
    differ by more than ``feature_angle`` degrees. An edge beside a face of no area is
    not a crease (such a face has no normal to compare); it can still be a boundary edge.
    ``table``: the :func:`~halfedge_edu.core.corner_table.edge_table` of ``faces``, if the
    caller has it already.
    """
    n = len(vertices)
    if table is None:
        table = edge_table(faces, n)
    unit, has_normal = _unit_rows(face_cross(vertices[faces]))            # (m, 3)
    inner = table.count == 2
    f1, f2 = table.first[inner] // 3, table.second[inner] // 3
    limit = math.cos(math.radians(feature_angle))
    sharp = np.zeros(len(table.edges), dtype=bool)
    sharp[inner] = has_normal[f1] & has_normal[f2] & (np.einsum("ij,ij->i", unit[f1], unit[f2]) < limit)
    edges = table.edges[sharp | (table.count == 1)]
    # Corners: other than two feature edges, or a line that turns more than the angle.
    corners = np.zeros(n, dtype=bool)
    count = np.bincount(edges.reshape(-1), minlength=n)
    corners[(count > 0) & (count != 2)] = True
    unnumbered = np.zeros(len(edges), dtype=np.int64)                   # line_neighbours needs no numbers
    on_line, before, after = Features(edges, corners, unnumbered).line_neighbours()
    incoming, _ = _unit_rows(vertices[on_line] - vertices[before])
    outgoing, _ = _unit_rows(vertices[after] - vertices[on_line])
    corners[on_line[np.einsum("ij,ij->i", incoming, outgoing) < limit]] = True
    return Features(edges, corners, number_lines(edges, corners))


def number_lines(edges: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """(k,) a number for each feature edge (k, 2), the same along one line: two edges
    are on one line when they meet at a vertex that is not a corner.

    The lines are the connected pieces of a graph whose nodes are the edges, linked
    at every vertex that is not a corner (such a vertex has exactly two edges: a corner
    is any vertex with other than two). scipy finds the pieces.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n, k = len(corners), len(edges)
    if k == 0:
        return np.zeros(0, dtype=np.int64)
    offsets, edge_at = csr(edges.reshape(-1), np.repeat(np.arange(k), 2), n)   # each vertex's edges
    through = np.flatnonzero((np.diff(offsets) == 2) & ~corners)               # (j,) vertices inside a line
    first, second = edge_at[offsets[through]], edge_at[offsets[through] + 1]   # (j,) its two edges
    links = coo_matrix((np.ones(len(through)), (first, second)), shape=(k, k))
    return connected_components(links, directed=False)[1].astype(np.int64)


def detect_features(mesh: HalfedgeMesh, feature_angle: float = DEFAULT_FEATURE_ANGLE) -> Features:
    """The feature edges and corners of ``mesh`` that :func:`~halfedge_edu.algorithms.remesh.remesh` keeps.

    Indices refer to ``mesh.to_arrays()[0]`` (the live vertices, in order). Feature
    edges are the boundary edges and the creases sharper than ``feature_angle`` degrees
    (the angle between the two face normals, 0 for a flat pair); see :class:`Features`
    for the corners.

    Raises:
        MeshInputError: ``feature_angle`` is not a number from 0 to 180.
    """
    check_mesh(mesh)
    feature_angle = real_number(feature_angle, "feature_angle", minimum=0.0, maximum=180.0)
    vertices, faces = mesh.to_arrays()
    return feature_arrays(vertices, faces, feature_angle)
