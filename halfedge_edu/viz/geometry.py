"""What a scene knows about the mesh it drew: normals, centre, size, faces as drawn.

The camera aims with these normals and this centre, and the labels use them to hide
what faces away; all come from one pass over the mesh when the scene is built. Faces an
edit touches (a stepper's "local" faces) may be drawn with corners the mesh's pointers
do not give yet; :meth:`SceneGeometry.corners_of` answers with the corners as drawn.
"""

from __future__ import annotations

import numpy as np

from ..algorithms.normals import face_normals, vertex_normals
from . import arrows
from .neighbourhood import ranges
from .screen import unit


def facing(eye: np.ndarray, points: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """(k,) bool: the element at ``points`` with ``normals`` shows its front to ``eye``."""
    return ((eye - points) * normals).sum(axis=1) > 0


class SceneGeometry:
    """Normals, centre, radius and faces around each vertex of ``mesh`` as built.

    Attributes:
        scale: the typical edge length (arrow widths and lifts are fractions of it).
        live_faces: (F,) the faces that were live when built.
        face_normals: (n_face_slots, 3) unit normals (zero for deleted faces).
        vertex_normals: (n_vertex_slots, 3) area-weighted unit normals.
        flat: the mesh lies in a plane (its mean face normal is nearly unit).
        center, radius: the centre of the live vertices and their largest distance to it.
    """

    def __init__(self, mesh):
        self.scale = arrows.typical_edge_length(mesh)
        self.live_faces = np.flatnonzero(~mesh.face_deleted)
        positions = np.array(mesh.positions)
        corners = mesh.face_vertices()[self.live_faces]                     # (F, 3)
        # Faces around each vertex, in CSR form: faces[offsets[v]:offsets[v + 1]].
        flat = corners.ravel()
        order = np.argsort(flat, kind="stable")
        offsets = np.searchsorted(flat[order], np.arange(mesh.n_vertex_slots + 1))
        self._vertex_faces = (offsets, self.live_faces[order // 3])
        self._face_first_corner = np.zeros(mesh.n_face_slots, dtype=np.int64)
        self._face_first_corner[self.live_faces] = corners[:, 0]
        self.face_normals = face_normals(mesh)
        self.vertex_normals = vertex_normals(mesh)
        live_normals = self.face_normals[self.live_faces]
        mean_normal = live_normals.mean(axis=0) if len(self.live_faces) else np.zeros(3)
        self.flat = bool(np.linalg.norm(mean_normal) > 0.9)
        live_positions = positions[~mesh.vertex_deleted]
        self.center = live_positions.mean(axis=0)
        self.radius = float(np.linalg.norm(live_positions - self.center, axis=1).max()) or 1.0
        self.clear_local()

    def grow(self, mesh) -> None:
        """Make room in the normal arrays for vertices and faces an edit created."""
        if len(self.vertex_normals) < mesh.n_vertex_slots:
            extra = np.zeros((mesh.n_vertex_slots - len(self.vertex_normals), 3))
            self.vertex_normals = np.concatenate([self.vertex_normals, extra])
        if len(self.face_normals) < mesh.n_face_slots:
            extra = np.zeros((mesh.n_face_slots - len(self.face_normals), 3))
            self.face_normals = np.concatenate([self.face_normals, extra])

    def clear_local(self) -> None:
        """Forget the local faces' drawn corners."""
        self.local_faces = np.zeros(0, dtype=np.int64)
        self._local_corners = np.zeros((0, 3), dtype=np.int64)

    def set_local(self, mesh, faces: np.ndarray, corners: np.ndarray) -> None:
        """Record that ``faces`` are drawn with ``corners`` (k, 3) now, and their normals."""
        points = mesh.positions[corners]                                    # (k, 3, 3)
        self.face_normals[faces] = unit(np.cross(points[:, 1] - points[:, 0], points[:, 2] - points[:, 0]))
        order = np.argsort(faces)
        self.local_faces, self._local_corners = faces[order], corners[order]

    def corners_of(self, mesh, faces: np.ndarray) -> np.ndarray:
        """(k, 3) corner vertices of ``faces``, as drawn (local faces as last drawn)."""
        h0 = mesh.face_halfedge[faces]
        h1 = mesh.halfedge_next[h0]
        h2 = mesh.halfedge_next[h1]
        corners = np.stack([mesh.halfedge_vertex[h0], mesh.halfedge_vertex[h1], mesh.halfedge_vertex[h2]], axis=1)
        if len(self.local_faces) and len(faces):
            slot = np.minimum(np.searchsorted(self.local_faces, faces), len(self.local_faces) - 1)
            hit = self.local_faces[slot] == faces
            corners[hit] = self._local_corners[slot[hit]]
        return corners

    def vertex_in_sight(self, mesh, eye: np.ndarray, vertices: np.ndarray) -> np.ndarray:
        """(k,) bool: one of the vertex's faces (as built) looks toward ``eye``, so
        silhouette corners count; vertices of the local faces always do."""
        offsets, faces = self._vertex_faces
        known = vertices < len(offsets) - 1
        seen = ~known
        inside = vertices[known]
        ring = ranges(offsets[inside], offsets[inside + 1])                 # their faces
        owner = np.repeat(np.arange(len(inside)), offsets[inside + 1] - offsets[inside])
        around = faces[ring]
        corner = mesh.positions[self._face_first_corner[around]]
        front = facing(eye, corner, self.face_normals[around])
        hit = np.zeros(len(inside), dtype=bool)
        hit[owner[front]] = True
        seen[known] = hit
        seen |= np.isin(vertices, self._local_corners)
        return seen
