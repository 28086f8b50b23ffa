"""Face and vertex normals: which way the surface faces, per triangle and per vertex.

A face normal comes from the right-hand rule: for a triangle ``a, b, c`` listed
counter-clockwise seen from outside, ``(b - a) x (c - a)`` points outwards and its
length is twice the triangle's area. Dividing by the length gives the unit normal.

A vertex has no normal of its own; we *average* the normals of the faces around it.
Which average is a choice, and it shows when shading (flat shading uses face normals,
smooth shading interpolates vertex normals):

* ``"area"``: each face counts in proportion to its area. Big faces dominate, which is
  what you want when the mesh is fine in some places and coarse in others. It is also
  the cheapest: the cross product already has length ``2 * area``, so summing the
  *unnormalized* cross products is the area-weighted sum.
* ``"angle"``: each face counts in proportion to its corner angle at the vertex
  (Thürrner and Wüthrich, 1998). Splitting a face into two does not change the result,
  so the normal depends on the surface rather than on how it was triangulated.
  This is what ``trimesh.Trimesh.vertex_normals`` computes.
* ``"uniform"``: every face counts the same. Simple, but a vertex with many thin faces
  on one side leans that way.

Both functions work over *slots* (see ``HalfedgeMesh``): row ``i`` belongs to face or
vertex ``i`` even when the mesh has deleted elements, and the rows of deleted elements
are zero. Zero-area faces have a zero normal and add nothing to their vertices.
"""

from __future__ import annotations

import numpy as np

from ..core import HalfedgeMesh
from ..core.arrays import face_cross
from .arguments import check_mesh, choice

VERTEX_WEIGHTINGS = ("area", "angle", "uniform")


def face_corners(mesh: HalfedgeMesh) -> np.ndarray:
    """(n_face_slots, 3, 3) corner positions of every face; deleted faces' rows are zero."""
    corners = mesh.face_vertices()                                 # (F, 3) int, -1 if deleted
    points = mesh.positions[np.maximum(corners, 0)]                # (F, 3, 3)
    points[mesh.face_deleted] = 0.0
    return points


def _unit_rows(vectors: np.ndarray) -> np.ndarray:
    """Each row divided by its length; rows of length zero stay zero (no NaN)."""
    length = np.linalg.norm(vectors, axis=1)                       # (n,)
    safe = np.where(length > 0, length, 1.0)
    return vectors / safe[:, None]


def face_normals(mesh: HalfedgeMesh) -> np.ndarray:
    """Unit normal of every face, by the right-hand rule over its CCW corners.

    Returns:
        (n_face_slots, 3) float64. Rows of deleted faces and of zero-area faces are
        zero (never NaN). For a mesh without deleted faces, row ``f`` is face ``f``,
        in the same order as the faces of ``mesh.to_arrays()``.
    """
    check_mesh(mesh)
    return _unit_rows(face_cross(face_corners(mesh)))


def face_areas(mesh: HalfedgeMesh) -> np.ndarray:
    """(n_face_slots,) area of every face (zero for deleted faces)."""
    check_mesh(mesh)
    cross = face_cross(face_corners(mesh))
    return 0.5 * np.sqrt(np.einsum("ij,ij->i", cross, cross))


def corner_angles(mesh: HalfedgeMesh) -> np.ndarray:
    """(n_face_slots, 3) the interior angle at each corner of each face, in radians.

    Corner ``k`` of face ``f`` is at vertex ``mesh.face_vertices()[f, k]``. Computed as
    ``atan2(|u x w|, u . w)``, which stays accurate for angles near 0 and pi (where
    ``arccos`` of a dot product loses digits). Deleted faces get zeros.
    """
    check_mesh(mesh)
    points = face_corners(mesh)                                    # (F, 3, 3)
    along = np.roll(points, -1, axis=1) - points                   # (F, 3, 3) to the next corner
    back = np.roll(points, 1, axis=1) - points                     # (F, 3, 3) to the previous one
    sine = np.linalg.norm(np.cross(along, back), axis=2)           # (F, 3) |u x w|
    cosine = np.einsum("fkd,fkd->fk", along, back)                 # (F, 3) u . w
    return np.arctan2(sine, cosine)


def area_weighted_vertex_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(n, 3) unit vertex normals of a face array, each face counting by its area.

    The array form of ``vertex_normals(mesh, "area")``, for code that works on
    ``(vertices (n, 3), faces (m, 3))`` without building a mesh (``remesh`` does, every
    iteration). The sum of the *unnormalized* face cross products around a vertex is
    the area-weighted sum, so no face normal is normalized on the way. Vertices no
    face uses get a zero row.
    """
    cross = face_cross(vertices[faces])                            # (m, 3), length 2 * area
    corner_vertex = faces.reshape(-1)                              # (3m,) vertex of each corner
    summed = np.empty((len(vertices), 3))
    for axis in range(3):
        summed[:, axis] = np.bincount(corner_vertex, weights=np.repeat(cross[:, axis], 3),
                                      minlength=len(vertices))
    return _unit_rows(summed)


def vertex_normals(mesh: HalfedgeMesh, weighting: str = "area") -> np.ndarray:
    """Unit normal of every vertex: a weighted average of the normals of its faces.

    Args:
        mesh: the mesh (it is only read).
        weighting: ``"area"`` (default; faces count by their area), ``"angle"``
            (by their corner angle at the vertex, as trimesh does) or ``"uniform"``
            (every face the same). See the module docstring for why each exists.

    Returns:
        (n_vertex_slots, 3) float64 unit vectors. Rows of deleted vertices are zero, and
        so is the row of a vertex whose weighted normals cancel out exactly.

    How: every face adds its weighted normal to its three corners at once. The sum
    over "all corners that belong to vertex v" is a ``np.bincount`` with weights, once
    per coordinate, which runs in C over all corners; no loop over vertices.
    """
    check_mesh(mesh)
    choice(weighting, "weighting", VERTEX_WEIGHTINGS)
    corners = mesh.face_vertices()                                 # (F, 3) int
    live = ~mesh.face_deleted
    if weighting == "area":
        return area_weighted_vertex_normals(mesh.positions, corners[live])
    cross = face_cross(face_corners(mesh))                         # (F, 3), length 2 * area
    if weighting == "angle":
        contribution = corner_angles(mesh)[:, :, None] * _unit_rows(cross)[:, None, :]
    else:
        contribution = np.repeat(_unit_rows(cross)[:, None, :], 3, axis=1)
    owner = corners[live].ravel()                                  # (3 F_live,) vertex of each corner
    summed = np.empty((mesh.n_vertex_slots, 3))
    for axis in range(3):
        summed[:, axis] = np.bincount(
            owner, weights=contribution[live][:, :, axis].ravel(), minlength=mesh.n_vertex_slots
        )
    return _unit_rows(summed)
