"""Halfedge arrows as flat triangles, built for many halfedges in one numpy pass.

A halfedge from A to B is drawn inside its own face: the segment AB is pulled toward
the face's centroid C (so a halfedge and its twin become two parallel arrows, one in
each face), shortened at both ends, and given a triangular head at B. A boundary
halfedge has no face, so it is drawn in the mirror image of its twin's face, outside
the mesh, in the hole it runs along.

Each arrow is 7 points and 3 triangles (two for the shaft, one for the head), lifted a
little off its face along the face normal so the surface does not hide it::

        3 ----------------- 6
        |                   | \\
        0                   |   5   (tip, near B)
        |                   | /
        1 ----------------- 2 - 4      shaft: (1, 2, 3), (1, 3, 0); head: (4, 5, 6)

    (A side)                      (B side)
"""

from __future__ import annotations

import numpy as np

from .palette import ROLES, rgb

POINTS_PER_ARROW = 7
TRIANGLES_PER_ARROW = 3
_ARROW_TRIANGLES = np.array([[1, 2, 3], [1, 3, 0], [4, 5, 6]])  # (3, 3) within one arrow

# Shape, as fractions (see arrow_geometry).
INSET = 0.28         # how far the arrow moves from the edge toward the centroid
GAP = 0.12           # how much is cut off each end of the moved segment
SHAFT = 0.022        # shaft half-width, times the typical edge length
HEAD = 0.065         # head half-width, times the typical edge length
LIFT = 0.004         # lift off the face, times the typical edge length


def halfedge_corners(mesh, halfedges: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Origin, tip and "third corner" positions of ``halfedges``, each (k, 3).

    The third corner is the face's corner opposite the halfedge (the origin of
    ``prev``); for a boundary halfedge it is the twin face's opposite corner mirrored
    across the edge (``A + B - c``), which puts the arrow outside the mesh.
    """
    halfedges = np.asarray(halfedges, dtype=np.int64)
    positions = mesh.positions
    origin = mesh.halfedge_vertex[halfedges]
    tip = mesh.halfedge_vertex[halfedges ^ 1]
    on_boundary = mesh.halfedge_face[halfedges] < 0
    # Inside a face the opposite corner is prev's origin; for a boundary halfedge we
    # take the twin's opposite corner (the twin is never on the boundary as well,
    # except on a broken mesh, where the arrow just lies flat on the edge).
    side = np.where(on_boundary, halfedges ^ 1, halfedges)
    opposite = mesh.halfedge_vertex[mesh.halfedge_prev[side]]
    A = positions[origin]                                         # (k, 3)
    B = positions[tip]                                            # (k, 3)
    third = positions[opposite]                                   # (k, 3)
    third = np.where(on_boundary[:, None], A + B - third, third)
    return A, B, third


def arrow_geometry(
    A: np.ndarray,
    B: np.ndarray,
    third: np.ndarray,
    *,
    scale: float,
    width: float = 1.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Flat arrows from A toward B inside the triangles (A, B, third).

    Args:
        A, B, third: (k, 3) positions.
        scale: a typical edge length; arrow widths and the lift are fractions of it.
        width: thickness multiplier (the "large" preset uses more than 1).

    Returns:
        ``points`` (7k, 3) float64 and ``triangles`` (3k, 3) int64, arrow ``i``
        owning points ``7i .. 7i+6`` and triangles ``3i .. 3i+2``.
    """
    k = len(A)
    centroid = (A + B + third) / 3.0                              # (k, 3)
    A_in = A + INSET * (centroid - A)
    B_in = B + INSET * (centroid - B)
    along = B_in - A_in
    length = np.linalg.norm(along, axis=1)                        # (k,)
    u = along / np.maximum(length, 1e-300)[:, None]               # unit, A -> B
    to_centre = centroid - A_in
    w = to_centre - (to_centre * u).sum(axis=1)[:, None] * u      # in-plane, toward C
    distance = np.linalg.norm(w, axis=1)                          # arrow line to C
    w = w / np.maximum(distance, 1e-300)[:, None]
    normal = np.cross(u, w)                                       # (k, 3) unit

    # Keep the head inside the face on thin triangles: never wider than the gap
    # between the arrow and the edge, nor than the room toward the centroid.
    room = np.minimum(distance, INSET / (1.0 - INSET) * distance)
    head = np.minimum(HEAD * scale * width, 0.8 * room)           # (k,)
    shaft = np.minimum(SHAFT * scale * width, 0.4 * head)
    tail = A_in + GAP * along
    tip = B_in - GAP * along
    head_length = np.minimum(2.4 * head, 0.45 * (1.0 - 2 * GAP) * length)
    neck = tip - head_length[:, None] * u

    s, h = shaft[:, None] * w, head[:, None] * w
    points = np.stack(
        [tail, tail - s, neck - s, neck + s, neck - h, tip, neck + h], axis=1
    ) + (LIFT * scale) * normal[:, None, :]                       # (k, 7, 3)
    triangles = _ARROW_TRIANGLES[None, :, :] + POINTS_PER_ARROW * np.arange(k)[:, None, None]
    return points.reshape(-1, 3), triangles.reshape(-1, 3)


def typical_edge_length(mesh, halfedges: np.ndarray | None = None) -> float:
    """The median length of the given halfedges' edges (all live edges by default)."""
    if halfedges is None:
        halfedges = 2 * np.flatnonzero(~mesh.edge_deleted)
    if len(halfedges) == 0:
        return 1.0
    ends = mesh.positions[mesh.halfedge_vertex[halfedges]] - mesh.positions[mesh.halfedge_vertex[np.asarray(halfedges) ^ 1]]
    return float(np.median(np.linalg.norm(ends, axis=1))) or 1.0


def drawable(mesh, halfedges: np.ndarray) -> np.ndarray:
    """The live ones among ``halfedges`` whose two ends are set (not -1)."""
    halfedges = halfedges[(halfedges >= 0) & (halfedges < mesh.n_halfedge_slots)]
    halfedges = halfedges[~mesh.edge_deleted[halfedges >> 1]]
    ends_set = (mesh.halfedge_vertex[halfedges] >= 0) & (mesh.halfedge_vertex[halfedges ^ 1] >= 0)
    return halfedges[ends_set]


class ArrowLayer:
    """The arrows of one scene: the part "arrows" of ``actors``, one arrow per halfedge.

    Args:
        actors: the scene's :class:`~halfedge_edu.viz.actors.Actors` holding the part.
        preset: the scene's look (arrow width and plain colours).
        corners: ``(mesh, halfedges) -> (A, B, third)``, where each arrow goes; by
            default :func:`halfedge_corners`. A stepper passes its own to place the
            arrows of a mesh whose pointers are half rewired.
    """

    def __init__(self, actors, preset, corners=halfedge_corners):
        self.actors = actors
        self.preset = preset
        self.corners = corners
        #: (k,) the halfedges that have an arrow, in arrow order.
        self.halfedges = np.zeros(0, dtype=np.int64)
        # The drawn halfedges sorted (stable), and where each sorted one sits in the arrow
        # list: a lookup that costs the k drawn halfedges, not a table of the mesh's size.
        self._sorted = np.zeros(0, dtype=np.int64)
        self._slot_of_sorted = np.zeros(0, dtype=np.int64)

    def draw(self, mesh, halfedges: np.ndarray, scale: float) -> None:
        """Build the arrows of ``halfedges`` (in one numpy pass), uncoloured."""
        import pyvista as pv

        halfedges = np.asarray(halfedges, dtype=np.int64)
        self.halfedges = halfedges
        if len(halfedges) == 0:
            self.actors.set("arrows", None)
            return
        A, B, third = self.corners(mesh, halfedges)
        points, triangles = arrow_geometry(A, B, third, scale=scale, width=self.preset.arrow_width)
        data = pv.PolyData.from_regular_faces(points, triangles)
        data.cell_data["rgb"] = np.zeros((len(triangles), 3), dtype=np.uint8)
        self.actors.set("arrows", data)
        self._slot_of_sorted = np.argsort(halfedges, kind="stable")
        self._sorted = halfedges[self._slot_of_sorted]

    def color(self, mesh, members: list[tuple[str, np.ndarray]]) -> None:
        """Colour the arrows: plain or boundary, then each role's halfedges ``members``
        (``(role, indices)`` in ROLES order; the earliest role wins)."""
        halfedges = self.halfedges
        if len(halfedges) == 0:
            return
        look = self.preset
        colors = np.where((mesh.halfedge_face[halfedges] < 0)[:, None], rgb(look.boundary_arrow), rgb(look.plain_arrow))
        for name, indices in reversed(members):
            colors[self.slots(indices)] = rgb(ROLES[name].color)
        self.actors.data("arrows").cell_data["rgb"] = np.repeat(colors.astype(np.uint8), TRIANGLES_PER_ARROW, axis=0)

    def slots(self, indices: np.ndarray) -> np.ndarray:
        """Where the arrows of the drawn ones among halfedges ``indices`` sit in the arrow
        list (a halfedge drawn twice, on a broken mesh: its last arrow)."""
        # The last equal one in the stable sort is the last in the arrow list.
        place = np.searchsorted(self._sorted, indices, side="right") - 1
        drawn = place >= 0
        drawn[drawn] = self._sorted[place[drawn]] == indices[drawn]
        return self._slot_of_sorted[place[drawn]]

    def colors(self) -> np.ndarray:
        """(k, 3) uint8 the colour of each arrow, in the order of :attr:`halfedges`."""
        return np.asarray(self.actors.data("arrows").cell_data["rgb"])[::TRIANGLES_PER_ARROW][: len(self.halfedges)]

    def points(self) -> np.ndarray:
        """(7k, 3) the arrows' points when any are drawn, else (0, 3)."""
        if not self.actors.visible("arrows"):
            return np.zeros((0, 3))
        return np.asarray(self.actors.data("arrows").points)
