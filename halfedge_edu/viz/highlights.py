"""Elements highlighted by role: which they are, and their coloured faces and dots.

A highlight maps role names of :data:`~halfedge_edu.viz.palette.ROLES` ("current",
"twin", "origin", "face", ...) to element indices; each role has a kind (vertex,
halfedge or face) and a colour. Where an element has two roles, the one listed first in
``ROLES`` wins. Halfedge roles colour the arrows (see :mod:`.arrows`); face roles are
drawn as coloured triangles lifted a little off the surface, vertex roles as big dots.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import numpy as np

from . import arrows
from .actors import Actors
from .geometry import SceneGeometry
from .palette import ROLES, rgb


def slot_count(mesh, kind: str) -> int:
    """How many index slots ``mesh`` has for elements of ``kind`` (deleted ones included)."""
    return {"vertex": mesh.n_vertex_slots, "halfedge": mesh.n_halfedge_slots, "face": mesh.n_face_slots}[kind]


class Highlight:
    """The current highlight: ``roles`` (role name -> (k,) indices) and label ``names``."""

    def __init__(self):
        self.roles: dict[str, np.ndarray] = {}
        self.names: dict[tuple[str, int], str] = {}

    def set(self, mesh, roles: Mapping[str, "int | Iterable[int]"], names=None) -> None:
        """Replace the highlight; indices of elements that do not exist (yet) are left out.

        Raises:
            ValueError: a role name that is not in ``ROLES``.
        """
        cleaned: dict[str, np.ndarray] = {}
        for role, members in roles.items():
            if role not in ROLES:
                raise ValueError(f"unknown role {role!r}; roles are {', '.join(ROLES)}")
            indices = np.atleast_1d(np.asarray(members, dtype=np.int64))
            indices = indices[(indices >= 0) & (indices < slot_count(mesh, ROLES[role].kind))]
            if len(indices):
                cleaned[role] = indices
        self.roles = cleaned
        self.names = dict(names or {})

    def members(self, kind: str) -> list[tuple[str, np.ndarray]]:
        """(role, indices) of the highlight for one element kind, in ROLES order."""
        return [(name, self.roles[name]) for name, role in ROLES.items()
                if role.kind == kind and name in self.roles]

    def named(self, kind: str) -> np.ndarray:
        """(k,) the elements of ``kind`` that have a name of their own."""
        return np.array([i for k, i in self.names if k == kind], dtype=np.int64)

    def faces(self) -> np.ndarray | None:
        """(k,) every highlighted face, or None when no face role is set."""
        found = [members for _, members in self.members("face")]
        return np.concatenate(found) if found else None

    def focus_vertices(self, mesh, geometry: SceneGeometry) -> np.ndarray:
        """(k,) the live vertices the highlight touches: its vertices, the ends of its
        halfedges and the corners of its faces."""
        found = [np.zeros(0, dtype=np.int64)]
        for _, members in self.members("vertex"):
            found.append(members)
        for _, members in self.members("halfedge"):
            found.append(mesh.halfedge_vertex[members])
            found.append(mesh.halfedge_vertex[members ^ 1])
        for _, members in self.members("face"):
            found.append(geometry.corners_of(mesh, members).ravel())
        focus = np.unique(np.concatenate(found).astype(np.int64))
        return focus[(focus >= 0) & ~mesh.vertex_deleted[np.clip(focus, 0, None)]] if len(focus) else focus

    def draw_faces(self, actors: Actors, mesh, geometry: SceneGeometry) -> None:
        """Fill the part "highlight_faces" with the highlighted faces in their roles' colours."""
        import pyvista as pv

        faces, colors = [], []
        for name, members in reversed(self.members("face")):
            faces.append(members)
            colors.append(np.repeat(rgb(ROLES[name].color)[None], len(members), axis=0))
        if not faces:
            actors.set("highlight_faces", None)
            return
        faces = np.concatenate(faces)
        faces, first = np.unique(faces[::-1], return_index=True)          # earliest role wins
        colors = np.concatenate(colors)[::-1][first]
        keep = (faces >= 0) & (faces < mesh.n_face_slots)
        faces, colors = faces[keep], colors[keep]
        keep = ~mesh.face_deleted[faces]
        faces, colors = faces[keep], colors[keep]
        if len(faces) == 0:
            actors.set("highlight_faces", None)
            return
        corners = geometry.corners_of(mesh, faces)                         # (k, 3)
        lift = 0.5 * arrows.LIFT * geometry.scale * geometry.face_normals[faces]
        points = mesh.positions[corners] + lift[:, None, :]                # (k, 3, 3)
        data = pv.PolyData.from_regular_faces(points.reshape(-1, 3), np.arange(3 * len(faces)).reshape(-1, 3))
        data.cell_data["rgb"] = colors.astype(np.uint8)
        actors.set("highlight_faces", data)

    def draw_vertices(self, actors: Actors, mesh) -> None:
        """Fill the part "highlight_vertices" with the highlighted vertices' dots."""
        import pyvista as pv

        chosen: dict[int, np.ndarray] = {}
        for name, members in self.members("vertex"):
            for v in members:
                chosen.setdefault(int(v), rgb(ROLES[name].color))
        chosen = {v: c for v, c in chosen.items() if 0 <= v < mesh.n_vertex_slots and not mesh.vertex_deleted[v]}
        if not chosen:
            actors.set("highlight_vertices", None)
            return
        vertices = np.array(sorted(chosen))
        data = pv.PolyData(mesh.positions[vertices])
        data.point_data["rgb"] = np.array([chosen[v] for v in vertices], dtype=np.uint8)
        actors.set("highlight_vertices", data)

    def describe(self) -> list[str]:
        """One line per role set: ``"h.twin: halfedge 1"``, ``"neighbours of v: vertices
        1, 4, 5"``, in ROLES order."""
        plural = {"vertex": "vertices", "halfedge": "halfedges", "face": "faces"}
        lines = []
        for role in ROLES.values():
            if role.name in self.roles:
                members = self.roles[role.name]
                kind = role.kind if len(members) == 1 else plural[role.kind]
                lines.append(f"{role.legend}: {kind} {', '.join(str(int(i)) for i in members)}")
        return lines
