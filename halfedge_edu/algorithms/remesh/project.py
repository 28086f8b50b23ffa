"""Phase 5 of remeshing: put every vertex back onto the input surface.

Splitting at chord midpoints and smoothing in a plane both step a little off a curved
surface; this phase takes each vertex to the nearest point of the input (boundary
vertices onto the input's boundary polyline, vertices on a feature line onto that line
of the input). A vertex that lands very near an input vertex goes onto it.

The closest-point code of the package lives here, once: :func:`closest_points_on_triangles`
(Ericson's method, all rows at once), :func:`closest_points_on_segments`, and
:class:`InputSurface`, the input ready for queries (a k-d tree of triangle centroids,
then the triangles beside the nearest).
"""

from __future__ import annotations

import numpy as np

from ...core.arrays import cross_rows, vertex_faces
from ..collapse_rounds import round_tables
from ..features import Features

#: A face counts as flat (no area) when twice its area is at most this times its
#: squared longest edge; the projection never leaves a face flat that was not.
MIN_RELATIVE_AREA = 1e-10


def project_to_surface(vertices: np.ndarray, faces: np.ndarray, surface: InputSurface,
                       features: Features | None, on_boundary: np.ndarray,
                       snap_radius: float = 0.0) -> np.ndarray:
    """Put every vertex on the nearest point of the input surface (boundary vertices on
    its boundary), except where that would flatten a face; a vertex off the lines whose
    nearest point is within ``snap_radius`` of an input vertex goes onto that vertex
    (see :meth:`InputSurface.project`).

    Why: splitting at chord midpoints and smoothing in a tangent plane both step a
    little off a curved surface, and those steps would add up over the iterations.
    Resting on the input's own vertices: they are the points where its surface was
    measured (a scan) or modelled, and a triangle resting on them follows it more
    closely than one whose corners lie between them.

    With ``features``, a vertex on a feature line (a crease or the boundary) goes onto
    its own line of the input, and corners stay exactly where they are.

    Where the input folds (a crease, a thin part), two corners of one face can land on
    the same nearest point, or three on one line, and the face would be left with no
    area. Corners of such a face are put back where they were before the projection:
    first only those off the lines, which need not be on anything exactly, and only if
    a face has none of those left to put back, its corners on lines (which smoothing
    may have moved off their line where it turns). Putting back may flatten a face next
    to them in turn, so this repeats until no face is flattened (each pass puts back at
    least one more vertex, so it ends).

    Args:
        vertices: (n, 3) float positions (not modified).
        faces: (m, 3) int triangles.
        surface: the input, ready for queries.
        features: the feature lines, the same as ``surface``'s (None: only the boundary).
        on_boundary: (n,) bool, the boundary vertices.
        snap_radius: how near an input vertex a point must land to go onto it (0: never).

    Returns:
        (n, 3) the projected positions.
    """
    result = vertices.copy()
    if features is None:
        on_line = on_boundary
        inside = np.flatnonzero(~on_boundary)
        if on_boundary.any() and surface.segment_tree is not None:
            result[on_boundary] = surface.project_to_boundary(vertices[on_boundary])
    else:
        on_line = features.counts() > 0
        inside = np.flatnonzero(~on_line)
        line_of = features.vertex_lines()                              # (n,) -1 off the lines and at corners
        moving = np.flatnonzero(line_of >= 0)
        if len(moving) and surface.line_tree is not None:
            result[moving] = surface.project_to_lines(vertices[moving], line_of[moving])
    result[inside] = surface.project(vertices[inside], snap_radius)
    while True:
        flat = np.flatnonzero(_nearly_flat(result, faces))
        flattened = flat[~_nearly_flat(vertices, faces[flat])]        # flat now, and not before (few)
        if len(flattened) == 0:
            return result
        corners = faces[flattened]                                     # (k, 3)
        moved = (result[corners] != vertices[corners]).any(axis=2)     # (k, 3) not put back yet
        loose = moved & ~on_line[corners]                              # (k, 3) and off the lines
        put_back = corners[np.where(loose.any(axis=1)[:, None], loose, moved)]
        result[put_back] = vertices[put_back]


def _triangle_coordinates(d1: np.ndarray, d2: np.ndarray, ab_ab: np.ndarray, ab_ac: np.ndarray,
                          ac_ac: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(s, t)``, each like ``d1``: the point of triangle ``a, b, c`` nearest to a point
    ``p`` is ``a + s (b - a) + t (c - a)``.

    Ericson's method (Real-Time Collision Detection, 5.1.5): find which of the seven
    regions (3 corners, 3 edges, the inside) ``p`` projects into, from six dot products.
    All six follow from two, ``d1 = (b - a).(p - a)`` and ``d2 = (c - a).(p - a)``, and
    the triangle's own three (``ab_ab = (b - a).(b - a)``, ``ab_ac``, ``ac_ac``), which a
    caller asking about the same triangles again and again computes once.
    """
    d3, d4, d5, d6 = d1 - ab_ab, d2 - ab_ac, d1 - ab_ac, d2 - ac_ac    # (b-a).(p-b), (c-a).(p-b), ... (p-c)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    safe = lambda x: np.where(np.abs(x) > 1e-300, x, 1e-300)  # noqa: E731
    with np.errstate(over="ignore", invalid="ignore"):      # formulas of the regions a row is not in
        on_bc = (d4 - d3) / safe((d4 - d3) + (d5 - d6))
        inside = safe(va + vb + vc)
        # Where several region tests hold, the one Ericson makes first wins: np.select
        # takes the first true condition, so they come in his order.
        regions = [(d1 <= 0) & (d2 <= 0), (d3 >= 0) & (d4 <= d3), (vc <= 0) & (d1 >= 0) & (d3 <= 0),
                   (d6 >= 0) & (d5 <= d6), (vb <= 0) & (d2 >= 0) & (d6 <= 0),
                   (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)]
        #            corner a, corner b, edge ab,              corner c, edge ac,            edge bc
        s = np.select(regions, [0.0, 1.0, d1 / safe(d1 - d3), 0.0, 0.0, 1.0 - on_bc], vb / inside)
        t = np.select(regions, [0.0, 0.0, 0.0, 1.0, d2 / safe(d2 - d6), on_bc], vc / inside)
    return s, t


def closest_points_on_triangles(points: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """(k, 3) the point of triangle ``(a[i], b[i], c[i])`` nearest to ``points[i]``.

    Ericson's method (Real-Time Collision Detection, 5.1.5), all rows at once: see
    :func:`_triangle_coordinates`.
    """
    dot = lambda u, v: np.einsum("ij,ij->i", u, v)  # noqa: E731
    ab, ac, ap = b - a, c - a, points - a
    s, t = _triangle_coordinates(dot(ab, ap), dot(ac, ap), dot(ab, ab), dot(ab, ac), dot(ac, ac))
    return a + ab * s[:, None] + ac * t[:, None]


def closest_points_on_segments(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(k, 3) the point of segment ``a[i] b[i]`` nearest to ``points[i]``."""
    ab = b - a
    t = np.einsum("ij,ij->i", points - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    return a + ab * np.clip(t, 0.0, 1.0)[:, None]


class InputSurface:
    """The input surface, ready for "nearest point" queries (a k-d tree of centroids, the
    triangles across each triangle's edges and around each vertex), with its boundary
    polyline and, given ``features``, its feature lines (the boundary among them), each
    line apart."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray, features: Features | None = None):
        from scipy.spatial import cKDTree

        corners = vertices[faces]                                      # (F, 3, 3)
        self.tree = cKDTree(corners.mean(axis=1))
        # Each triangle as a corner and two sides, with the sides' dot products: what
        # every query of the triangle asks again (see _triangle_coordinates).
        self.origin = corners[:, 0]                                    # (F, 3)
        self.sides = corners[:, 1:] - corners[:, :1]                   # (F, 2, 3) b - a, c - a
        ab, ac = self.sides[:, 0], self.sides[:, 1]
        self.gram = np.stack([np.einsum("ij,ij->i", ab, ab), np.einsum("ij,ij->i", ab, ac),
                              np.einsum("ij,ij->i", ac, ac)], axis=1)  # (F, 3)
        # The same twelve numbers per triangle in one row (a, b - a, c - a, gram): a query
        # gathers one contiguous row per candidate instead of three scattered pieces.
        self.rows = np.concatenate([self.origin, self.sides.reshape(-1, 6), self.gram], axis=1)   # (F, 12)
        self.face_corners = faces
        self.fan_offsets, self.fans = vertex_faces(faces, len(vertices))   # each vertex's triangles, CSR
        self.degree = np.diff(self.fan_offsets)
        # Each triangle and the (up to) three across its edges: the first candidates of a query.
        tables = round_tables(faces, len(vertices))
        across = tables.face_across                                    # (F, 3), -1 on the boundary
        self.around = np.concatenate([np.arange(len(faces))[:, None], across], axis=1)   # (F, 4)
        self.around = np.where(self.around >= 0, self.around, np.arange(len(faces))[:, None])
        segments = tables.edges[tables.boundary]
        self.segments = vertices[segments]                             # (S, 2, 3)
        self.segment_tree = cKDTree(self.segments.mean(axis=1)) if len(segments) else None
        # The input's vertices off its lines (off its boundary, without features): where
        # the projection may put a vertex exactly (see project's snap_radius).
        self.vertices = vertices
        self.rests = np.ones(len(vertices), dtype=bool)                # (n,)
        self.rests[segments.reshape(-1)] = False
        if features is not None:
            self.rests &= features.counts() == 0
        self.line_tree = None
        if features is not None and len(features.edges):
            self.line_segments = vertices[features.edges]              # (C, 2, 3)
            self.line_numbers = features.lines                         # (C,)
            # One tree for all lines, with the line's number as a fourth coordinate, far
            # apart: a query carrying its own line's number finds that line's segments
            # first (any other line is farther than the whole input is wide).
            self.line_spacing = 4.0 * float(np.ptp(vertices, axis=0).max()) + 1.0
            self.line_tree = cKDTree(self._with_line(self.line_segments.mean(axis=1), self.line_numbers))

    def project(self, points: np.ndarray, snap_radius: float = 0.0) -> np.ndarray:
        """Nearest points on the input triangles; with ``snap_radius``, a point found
        within that distance of a corner of its triangle off the lines goes onto that
        corner (:meth:`_rest_on_corners`).

        First among the triangle whose centroid is nearest and the three across its
        edges. Where the point found lies on the rim of its triangle (an edge or a
        corner: about one point in eight), the nearest point may be on a triangle that
        only shares a corner with it, so those points look again among all triangles
        around the corner nearest to the point found. That finds the true nearest point
        almost always, and a point very near it otherwise (how often and how near: in
        docs/performance.md); the point found is on the input surface either way.
        """
        _, nearest = self.tree.query(points)
        found, face, s, t = self._nearest_of(points, self.around[nearest])
        on_rim = (s <= 0.0) | (t <= 0.0) | (s + t >= 1.0)
        rows = np.flatnonzero(on_rim)
        if len(rows):
            weights = np.stack([1.0 - s[rows] - t[rows], s[rows], t[rows]], axis=1)   # (r, 3) of the corners
            corner = self.face_corners[face[rows], np.argmax(weights, axis=1)]
            fan = self.degree[corner]                                  # (r,)
            slot = self.fan_offsets[corner][:, None] + np.arange(int(fan.max())) % fan[:, None]
            found[rows], face[rows] = self._nearest_of(points[rows], self.fans[slot])[:2]
        if snap_radius > 0.0:
            found = self._rest_on_corners(found, face, snap_radius)
        return found

    def _rest_on_corners(self, found: np.ndarray, face: np.ndarray, radius: float) -> np.ndarray:
        """The points ``found`` (P, 3) on the triangles ``face`` (P,), each moved onto the
        nearest corner of its triangle if that corner is off the lines and within
        ``radius``. Where several points are near one corner, only the nearest of them
        goes onto it: two vertices on one point would make a face flat, or make the
        surface touch itself.

        The corners of the point's own triangle stand in for all input vertices: a point
        that near a vertex lies on one of its triangles (no k-d tree query needed).
        """
        corners = self.face_corners[face]                              # (P, 3)
        gap = np.take(self.vertices, corners, axis=0) - found[:, None, :]
        distance = np.einsum("pkj,pkj->pk", gap, gap)                  # (P, 3) squared
        which = np.argmin(distance, axis=1)
        rows = np.arange(len(found))
        corner, distance = corners[rows, which], distance[rows, which]
        close = np.flatnonzero((distance <= radius * radius) & self.rests[corner])
        order = close[np.lexsort((distance[close], corner[close]))]    # by corner, nearest first
        claims = corner[order]
        first = np.ones(len(order), dtype=bool)
        first[1:] = claims[1:] != claims[:-1]
        snapped = found.copy()
        snapped[order[first]] = self.vertices[claims[first]]
        return snapped

    def _nearest_of(self, points: np.ndarray, near: np.ndarray) -> tuple[np.ndarray, ...]:
        """The nearest point to each point on its candidate triangles ``near`` (P, k):
        ``(points (P, 3), their triangles (P,), s (P,), t (P,))``, the point being
        ``a + s ab + t ac`` on its triangle.

        Only two dot products per point and candidate: the squared distance to the
        nearest point is ``|ap|^2 - 2 s d1 - 2 t d2 + s^2 ab.ab + 2 s t ab.ac + t^2
        ac.ac``, all numbers already at hand, so the point itself is built only for the
        winning candidate.
        """
        rows = np.take(self.rows, near, axis=0)                        # (P, k, 12)
        ap = points[:, None, :] - rows[:, :, 0:3]                      # (P, k, 3)
        d1 = np.einsum("pkj,pkj->pk", rows[:, :, 3:6], ap)             # (b - a).(p - a)
        d2 = np.einsum("pkj,pkj->pk", rows[:, :, 6:9], ap)             # (c - a).(p - a)
        ab_ab, ab_ac, ac_ac = rows[:, :, 9], rows[:, :, 10], rows[:, :, 11]   # (P, k) each
        s, t = _triangle_coordinates(d1, d2, ab_ab, ab_ac, ac_ac)
        gap = np.einsum("pkj,pkj->pk", ap, ap) - 2 * (s * d1 + t * d2) + s * s * ab_ab + 2 * s * t * ab_ac + t * t * ac_ac
        best = np.argmin(gap, axis=1)                                  # (P,)
        rows = np.arange(len(points))
        face, s, t = near[rows, best], s[rows, best], t[rows, best]
        return self.origin[face] + self.sides[face, 0] * s[:, None] + self.sides[face, 1] * t[:, None], face, s, t

    def project_to_boundary(self, points: np.ndarray) -> np.ndarray:
        """Nearest points on the input's boundary polyline."""
        found, gap, _ = self._nearest_on_segments(points, self.segments, self.segment_tree)
        return found[np.arange(len(points)), np.argmin(gap, axis=1)]

    def _with_line(self, points: np.ndarray, line_numbers: np.ndarray) -> np.ndarray:
        """(P, 4) the points with their line's number, times ``line_spacing``, as a fourth coordinate."""
        return np.column_stack([points, self.line_spacing * line_numbers])

    def project_to_lines(self, points: np.ndarray, line_numbers: np.ndarray) -> np.ndarray:
        """Nearest points on the input's feature lines, each point (P, 3) on its own line
        ``line_numbers`` (P,): a vertex goes back onto the line it was on, never onto
        another one nearby (which would pull an edge of its line across the surface)."""
        found, gap, near = self._nearest_on_segments(points, self.line_segments, self.line_tree,
                                                     self._with_line(points, line_numbers))
        # Of the 4 segments nearest, only those of the point's own line count (the
        # nearest one always is: other lines are line_spacing away in the tree).
        gap[self.line_numbers[near] != line_numbers[:, None]] = np.inf
        return found[np.arange(len(points)), np.argmin(gap, axis=1)]

    @staticmethod
    def _nearest_on_segments(points, segments, tree, keys=None):
        """The nearest point on each of the (up to) 4 segments whose midpoints are nearest
        (to ``keys``, the points' tree coordinates, if given): ``(points (P, k, 3),
        squared distances (P, k), the segments (P, k))``."""
        k = min(4, tree.n)
        _, near = tree.query(points if keys is None else keys, k=k)
        near = near.reshape(len(points), k)                            # (P, k)
        repeated = np.repeat(points, k, axis=0)
        flat = near.reshape(-1)
        found = closest_points_on_segments(repeated, segments[flat, 0], segments[flat, 1]).reshape(len(points), k, 3)
        return found, np.einsum("ikj,ikj->ik", found - points[:, None], found - points[:, None]), near


def _nearly_flat(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(m,) True for faces of (almost) no area: twice the area at most
    ``MIN_RELATIVE_AREA`` times the squared longest edge (two corners on one point, or
    three on a line). Measured against the face's own size, so it does not depend on
    the mesh's scale."""
    p0, p1, p2 = (np.take(vertices, faces[:, k], axis=0) for k in range(3))   # (m, 3) each
    sides = (p1 - p0, p2 - p1, p0 - p2)
    cross = cross_rows(sides[0], p2 - p0)                               # length: twice the area
    longest = np.maximum.reduce([np.einsum("ij,ij->i", side, side) for side in sides])   # (m,) squared
    # Compared squared: (twice the area)^2 <= (MIN_RELATIVE_AREA * longest^2)^2.
    return np.einsum("ij,ij->i", cross, cross) <= (MIN_RELATIVE_AREA * longest) ** 2
