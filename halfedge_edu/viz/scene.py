"""A PyVista scene of a halfedge mesh: the surface, its halfedges as arrows, highlights.

    scene = HalfedgeScene(mesh)                 # draws every halfedge of a small mesh
    scene.show_halfedge(7)                      # h, h.twin, h.next, h.prev, origin, tip, face
    scene.show_one_ring(3)                      # v, its outgoing halfedges, neighbours, faces
    scene.set_roles({"current": [7], "origin": [2]})   # any roles of palette.ROLES
    png = scene.screenshot()                    # PNG bytes (or scene.screenshot("a.png"))

How it stays fast on the bunny (69k faces, 208k halfedges): the surface is built once;
on a small mesh every arrow is built once too and a highlight only rewrites the arrows'
colour array; on a large mesh (more than ``max_arrows`` halfedges) only the halfedges
within ``rings`` rings of the highlighted elements are drawn, and those few hundred
arrows are rebuilt in one numpy pass when the highlight moves. Labels follow the same
rule: all of them on a tiny mesh, only those near the highlight otherwise.

Attention: after editing the mesh (an operation, moved vertices) call ``refresh()``;
the scene does not watch the mesh.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import numpy as np

from . import arrows as _arrows
from .palette import ROLES, Preset, preset as _preset, rgb
from .pictures import png_bytes
from .screen import beside, unit

#: Halfedge counts above this draw arrows only near the highlight.
MAX_ARROWS = 3000
#: With ``labels="auto"``: meshes with at most this many faces get every label.
TINY_FACES = 12
#: With ``labels="auto"``: meshes with at most this many vertices get every vertex label.
TINY_VERTICES = 40
#: With explicit label kinds: meshes with at most this many faces get every label of
#: those kinds; larger ones only near the highlight.
LABEL_ALL_FACES = 40
#: Default view direction (from the object toward the camera) for meshes that are not flat.
VIEW_DIRECTION = np.array([0.75, 0.85, 1.3])

_KINDS = ("vertex", "halfedge", "face")
_LABEL_PREFIX = {"vertex": "v", "halfedge": "h", "face": "f"}



def _legend_arrow():
    """A small arrow shape for legend entries of halfedge roles."""
    import pyvista as pv

    points = np.array([[0, -0.12, 0], [0.55, -0.12, 0], [0.55, 0.12, 0], [0, 0.12, 0],
                       [0.55, -0.4, 0], [1, 0, 0], [0.55, 0.4, 0]], dtype=float)
    return pv.PolyData.from_regular_faces(points, np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6]]))


class HalfedgeScene:
    """Draw ``mesh`` with its halfedges as arrows and highlight elements by role.

    Args:
        mesh: a :class:`~halfedge_edu.HalfedgeMesh`.
        preset: ``"default"`` or ``"large"`` (projector: big labels, thick arrows).
        labels: which index labels to draw: ``"auto"`` (vertices, halfedges and faces
            on a small mesh, vertices only on a larger one), ``None``/``False`` (none),
            ``True`` (all three kinds), or an iterable of ``"vertex"``, ``"halfedge"``,
            ``"face"``. Large meshes only label elements near the highlight.
        rings: on a large mesh, draw arrows this many vertex rings around the highlight.
        max_arrows: draw every halfedge when the mesh has at most this many.
        legend: show a legend of the roles on screen.
        plotter: draw into this ``pyvista.Plotter``; by default a new off-screen one.
        window_size: image size in pixels; the preset's by default.
        follow: ``"auto"`` (a large mesh's camera follows the highlight; a small mesh
            turns only when the highlight is on its far side), True or False.
        local_faces: faces an edit will touch (steppers): they are drawn apart from the
            rest of the surface and redrawn by :meth:`set_mesh`, so stepping through an
            operation never rebuilds the whole surface.

    Two hooks let a stepper draw meshes whose pointers are half rewired:
    ``scene.corners(mesh, halfedges) -> (A, B, third)`` places the arrows (default
    :func:`~halfedge_edu.viz.arrows.halfedge_corners`), and ``scene.fixed_window`` (an
    array of halfedges, or None) replaces the rings around the highlight on large meshes.
    """

    def __init__(
        self,
        mesh,
        *,
        preset: "str | Preset" = "default",
        labels="auto",
        rings: int = 2,
        max_arrows: int = MAX_ARROWS,
        legend: bool = True,
        plotter=None,
        window_size: tuple[int, int] | None = None,
        follow="auto",
        local_faces=None,
    ):
        import pyvista as pv

        self.mesh = mesh
        self.preset = _preset(preset)
        self.rings = int(rings)
        self.max_arrows = int(max_arrows)
        self.legend = bool(legend)
        self.follow = follow
        self.label_kinds = self._label_kinds(labels)
        self.corners = _arrows.halfedge_corners
        self.fixed_window: np.ndarray | None = None
        self._local_faces = np.unique(np.asarray([] if local_faces is None else local_faces, dtype=np.int64))
        self.window_size = tuple(window_size or self.preset.window_size)
        if plotter is None:
            plotter = pv.Plotter(off_screen=True, window_size=list(self.window_size))
        self.plotter = plotter
        self.plotter.set_background(self.preset.background)
        # One light at the eye: faces seen head-on show their true colour.
        self.plotter.remove_all_lights()
        self.plotter.add_light(pv.Light(light_type="headlight"))
        self._legend_actor = None
        self.roles: dict[str, np.ndarray] = {}
        self.names: dict[tuple[str, int], str] = {}
        #: Hook for faces whose loop is half rewired: ``faces -> (k, 3)`` corner vertices.
        self.face_corners = None
        self._legend_key: tuple | None = None
        self._actors: dict[str, object] = {}
        self._data: dict[str, object] = {}
        self._camera_state = None
        self._build()
        self._update()

    # ----------------------------------------------------------------------------------
    # Public interface
    # ----------------------------------------------------------------------------------

    @property
    def windowed(self) -> bool:
        """True when only the halfedges near the highlight are drawn (large meshes)."""
        return self.mesh.n_halfedges > self.max_arrows

    @property
    def drawn_halfedges(self) -> np.ndarray:
        """(k,) the halfedges that currently have an arrow."""
        return self._arrow_halfedges.copy()

    def set_roles(self, roles: Mapping[str, "int | Iterable[int]"], *, names=None) -> None:
        """Highlight elements by role: ``{"current": 7, "origin": [2], ...}``.

        Role names are those of :data:`halfedge_edu.viz.palette.ROLES`; each role has
        a kind (vertex, halfedge or face), so plain indices are enough. An element in
        two roles takes the colour of the one listed first in ``ROLES``. ``names``
        optionally maps ``(kind, index)`` to a label text (the steppers' "vA", "h_AB").
        Replaces the previous highlight.
        """
        cleaned: dict[str, np.ndarray] = {}
        for role, members in roles.items():
            if role not in ROLES:
                raise ValueError(f"unknown role {role!r}; roles are {', '.join(ROLES)}")
            indices = np.atleast_1d(np.asarray(members, dtype=np.int64))
            # Elements that do not exist (yet) are left out.
            indices = indices[(indices >= 0) & (indices < self._slots(ROLES[role].kind))]
            if len(indices):
                cleaned[role] = indices
        self.roles = cleaned
        self.names = dict(names or {})
        self._update()

    def _slots(self, kind: str) -> int:
        mesh = self.mesh
        return {"vertex": mesh.n_vertex_slots, "halfedge": mesh.n_halfedge_slots, "face": mesh.n_face_slots}[kind]

    def show_halfedge(self, h: int) -> None:
        """Highlight halfedge ``h`` with its twin, next, prev, origin, tip and face."""
        mesh, h = self.mesh, int(h)
        roles = {
            "current": [h],
            "twin": [h ^ 1],
            "next": [int(mesh.halfedge_next[h])],
            "prev": [int(mesh.halfedge_prev[h])],
            "origin": [int(mesh.halfedge_vertex[h])],
            "tip": [int(mesh.halfedge_vertex[h ^ 1])],
        }
        face = int(mesh.halfedge_face[h])
        if face >= 0:
            roles["face"] = [face]
        self.set_roles(roles)

    def show_one_ring(self, v: int, current: int | None = None) -> None:
        """Highlight vertex ``v``, its outgoing halfedges, neighbours and faces.

        ``current`` (one of the outgoing halfedges) is drawn as the current halfedge.
        """
        vertex = self.mesh.vertex(int(v))
        outgoing = [h.index for h in vertex.outgoing()]
        roles = {
            "current": [] if current is None else [int(current)],
            "center": [vertex.index],
            "outgoing": outgoing,
            "neighbor": [int(self.mesh.halfedge_vertex[h ^ 1]) for h in outgoing],
            "ring_face": [f.index for f in vertex.faces()],
        }
        self.set_roles(roles)

    def clear(self) -> None:
        """Remove every highlight."""
        self.set_roles({})

    def refresh(self) -> None:
        """Rebuild everything from the mesh (after an operation or moved vertices)."""
        self._build()
        self._update()

    def set_mesh(self, mesh, roles: Mapping | None = None, *, names=None) -> None:
        """Draw ``mesh``, an edited version of the scene's mesh, and highlight ``roles``.

        Only the arrows, the vertices and the ``local_faces`` given at construction are
        redrawn (the rest of the surface stays as built), so an edit must stay inside
        those faces; created faces count as local. ``mesh`` may be half rewired
        (a stepper's in-between state): faces whose ``next`` loop is not a triangle
        are drawn in the preset's "rewiring" colour, where :attr:`face_corners` says.
        """
        self.mesh = mesh
        self._grow_normals()
        self._geometry_dirty = True
        self.set_roles({} if roles is None else roles, names=names)

    def look_at(self, vertices, rings: int = 1) -> None:
        """Turn the camera toward ``vertices`` and fit them with ``rings`` rings around them.

        A small mesh (at most ``LABEL_ALL_FACES`` faces) is shown whole, turned toward them.
        """
        vertices = np.asarray(vertices, dtype=np.int64)
        normal = unit(self._vertex_normals[vertices].sum(axis=0))
        if self._flat or not np.linalg.norm(normal) > 0:
            direction = self._view_direction()
        else:
            direction = normal
        if self.mesh.n_faces <= LABEL_ALL_FACES:
            self._aim_whole_mesh(direction)        # a small mesh is best seen whole
            self._draw_labels(self._focus_vertices())
            return
        around = np.flatnonzero(self._ring_mark(vertices, rings)) if rings else vertices
        centre = self.mesh.positions[vertices].mean(axis=0)
        # The ring around gives context; halfway out to it is enough to show it.
        points = np.concatenate([self.mesh.positions[vertices],
                                 centre + 0.6 * (self.mesh.positions[around] - centre)])
        self._set_camera(centre, direction, self._radius, points=points)
        self._draw_labels(self._focus_vertices())

    def render(self) -> None:
        """Push the current state to the render window."""
        self.plotter.render()

    def screenshot(self, path=None) -> bytes:
        """Render and return the picture as PNG bytes; also write it to ``path`` if given."""
        from PIL import Image

        self.plotter.render()
        pixels = self.plotter.screenshot(None, return_img=True)
        return png_bytes(Image.fromarray(np.asarray(pixels)), path)

    def describe(self) -> str:
        """The mesh and the highlight in plain, deterministic text."""
        mesh = self.mesh
        lines = [
            f"mesh: {mesh.n_vertices} vertices, {mesh.n_edges} edges, {mesh.n_faces} faces, "
            f"{mesh.n_boundary_loops} boundary loop{'s' if mesh.n_boundary_loops != 1 else ''}"
        ]
        for role in ROLES.values():
            if role.name in self.roles:
                members = ", ".join(str(int(i)) for i in self.roles[role.name])
                lines.append(f"{role.legend}: {role.kind} {members}")
        return "\n".join(lines)

    def close(self) -> None:
        """Free the render window."""
        self.plotter.close()

    # ----------------------------------------------------------------------------------
    # Building (once, and again on refresh)
    # ----------------------------------------------------------------------------------

    @staticmethod
    def _label_kinds(labels) -> tuple[str, ...] | str:
        if labels is None or labels is False:
            return ()
        if labels is True:
            return _KINDS
        if labels == "auto":
            return "auto"
        kinds = tuple(labels)
        for kind in kinds:
            if kind not in _KINDS:
                raise ValueError(f"labels: unknown kind {kind!r}; use 'vertex', 'halfedge' or 'face'")
        return kinds

    def _add(self, name: str, data, **style) -> None:
        """Add (or replace) the actor ``name`` drawing ``data``."""
        self._data[name] = data
        self._actors[name] = self.plotter.add_mesh(data, name=name, reset_camera=False, **style)

    def _set_data(self, name: str, data) -> None:
        """Swap the geometry of actor ``name`` in place (hidden when ``data`` is empty)."""
        target = self._data[name]
        actor = self._actors[name]
        if data is None or data.n_points == 0:
            actor.SetVisibility(False)
            return
        target.copy_from(data, deep=False)
        actor.SetVisibility(True)

    def _build(self) -> None:
        import pyvista as pv

        mesh, look = self.mesh, self.preset
        self._scale = _arrows.typical_edge_length(mesh)
        self._live_faces = np.flatnonzero(~mesh.face_deleted)
        positions = np.array(mesh.positions)
        corners = mesh.face_vertices()[self._live_faces]                  # (F, 3)
        # Faces around each vertex, in CSR form: faces[offsets[v]:offsets[v + 1]].
        flat = corners.ravel()
        order = np.argsort(flat, kind="stable")
        offsets = np.searchsorted(flat[order], np.arange(mesh.n_vertex_slots + 1))
        self._vertex_faces = (offsets, self._live_faces[order // 3])
        self._face_first_corner = np.zeros(mesh.n_face_slots, dtype=np.int64)
        self._face_first_corner[self._live_faces] = corners[:, 0]
        static = ~np.isin(self._live_faces, self._local_faces)
        surface = pv.PolyData.from_regular_faces(positions, corners[static])
        self._face_normals = np.zeros((mesh.n_face_slots, 3))
        a, b, c = (positions[corners[:, i]] for i in range(3))
        self._face_normals[self._live_faces] = unit(np.cross(b - a, c - a))
        vertex_normals = np.zeros((mesh.n_vertex_slots, 3))
        area_normals = np.cross(b - a, c - a)
        for i in range(3):
            np.add.at(vertex_normals, corners[:, i], area_normals)
        self._vertex_normals = unit(vertex_normals)
        mean_normal = self._face_normals[self._live_faces].mean(axis=0) if len(self._live_faces) else np.zeros(3)
        self._flat = bool(np.linalg.norm(mean_normal) > 0.9)
        self._center = positions[~mesh.vertex_deleted].mean(axis=0)
        self._radius = float(np.linalg.norm(positions[~mesh.vertex_deleted] - self._center, axis=1).max()) or 1.0

        self._add(
            "surface", surface, color=look.surface, show_edges=not self.windowed,
            edge_color=look.edge, line_width=look.edge_width, ambient=0.5, diffuse=0.5,
            specular=0.0, smooth_shading=False,
        )
        placeholder = pv.PolyData(np.zeros((3, 3)), faces=[3, 0, 1, 2])
        placeholder.cell_data["rgb"] = np.zeros((1, 3), dtype=np.uint8)
        self._add("local_surface", placeholder.copy(), scalars="rgb", rgb=True, show_edges=True,
                  edge_color=look.edge, line_width=look.edge_width, ambient=0.5, diffuse=0.5,
                  specular=0.0, show_scalar_bar=False)
        self._add("highlight_faces", placeholder.copy(), scalars="rgb", rgb=True,
                  ambient=0.5, diffuse=0.5, specular=0.0, show_scalar_bar=False)
        arrows = placeholder.copy()
        self._add("arrows", arrows, scalars="rgb", rgb=True, lighting=False, show_scalar_bar=False)
        if self.windowed:
            self._add("window_edges", pv.PolyData(np.zeros((2, 3)), lines=[2, 0, 1]),
                      color=look.edge, line_width=look.edge_width, lighting=False)
        self._add("vertices", pv.PolyData(np.zeros((1, 3))), color=look.vertex,
                  point_size=look.vertex_size, render_points_as_spheres=True)
        points = pv.PolyData(np.zeros((1, 3)))
        points.point_data["rgb"] = np.zeros((1, 3), dtype=np.uint8)
        self._add("highlight_vertices", points, scalars="rgb", rgb=True,
                  point_size=look.highlight_vertex_size, render_points_as_spheres=True,
                  show_scalar_bar=False)

        self._arrow_halfedges = np.zeros(0, dtype=np.int64)
        self._local_drawn = (np.zeros(0, dtype=np.int64), np.zeros((0, 3), dtype=np.int64))
        self._label_texts = {kind: [] for kind in _KINDS}
        self._geometry_dirty = True
        self._legend_key = None

    def _grow_normals(self) -> None:
        """Make room in the normal arrays for vertices and faces an edit created."""
        mesh = self.mesh
        if len(self._vertex_normals) < mesh.n_vertex_slots:
            extra = np.zeros((mesh.n_vertex_slots - len(self._vertex_normals), 3))
            self._vertex_normals = np.concatenate([self._vertex_normals, extra])
        if len(self._face_normals) < mesh.n_face_slots:
            extra = np.zeros((mesh.n_face_slots - len(self._face_normals), 3))
            self._face_normals = np.concatenate([self._face_normals, extra])

    def _drawable(self, halfedges: np.ndarray) -> np.ndarray:
        """The live ones among ``halfedges`` whose two ends are set (not -1)."""
        mesh = self.mesh
        halfedges = halfedges[(halfedges >= 0) & (halfedges < mesh.n_halfedge_slots)]
        halfedges = halfedges[~mesh.edge_deleted[halfedges >> 1]]
        ends_set = (mesh.halfedge_vertex[halfedges] >= 0) & (mesh.halfedge_vertex[halfedges ^ 1] >= 0)
        return halfedges[ends_set]

    def _draw_local_faces(self) -> None:
        """Redraw the local faces as the mesh has them now (rewired ones stand out)."""
        import pyvista as pv

        mesh, look = self.mesh, self.preset
        faces = self._local_faces[self._local_faces < mesh.n_face_slots]
        faces = faces[~mesh.face_deleted[faces]]
        self._local_drawn = (np.zeros(0, dtype=np.int64), np.zeros((0, 3), dtype=np.int64))
        if len(faces) == 0:
            self._set_data("local_surface", None)
            return
        h0 = mesh.face_halfedge[faces]
        valid = h0 >= 0
        h0 = np.where(valid, h0, 0)
        h1 = mesh.halfedge_next[h0]
        h2 = mesh.halfedge_next[np.maximum(h1, 0)]
        loop = np.stack([h0, h1, h2], axis=1)                              # (k, 3)
        valid &= (loop >= 0).all(axis=1)
        valid &= mesh.halfedge_next[np.maximum(h2, 0)] == h0
        valid &= (mesh.halfedge_face[np.maximum(loop, 0)] == faces[:, None]).all(axis=1)
        corners = mesh.halfedge_vertex[np.maximum(loop, 0)]
        valid &= (corners >= 0).all(axis=1)
        # Each halfedge must end where the next one starts.
        tips = mesh.halfedge_vertex[np.maximum(loop, 0) ^ 1]
        valid &= (tips == np.roll(corners, -1, axis=1)).all(axis=1)
        if not valid.all() and self.face_corners is not None:
            corners[~valid] = self.face_corners(faces[~valid])
        drawn = (corners >= 0).all(axis=1)
        faces, corners, valid = faces[drawn], corners[drawn], valid[drawn]
        points = mesh.positions[corners]                                   # (k, 3, 3)
        self._face_normals[faces] = unit(np.cross(points[:, 1] - points[:, 0], points[:, 2] - points[:, 0]))
        data = pv.PolyData.from_regular_faces(points.reshape(-1, 3), np.arange(3 * len(faces)).reshape(-1, 3))
        data.cell_data["rgb"] = np.where(valid[:, None], rgb(look.surface), rgb(look.rewiring_face)).astype(np.uint8)
        self._set_data("local_surface", data)
        order = np.argsort(faces)
        self._local_drawn = (faces[order], corners[order])

    # ----------------------------------------------------------------------------------
    # Updating (every highlight change)
    # ----------------------------------------------------------------------------------

    def _members(self, kind: str) -> list[tuple[str, np.ndarray]]:
        """(role, indices) of the current highlight for one element kind, in ROLES order."""
        return [(name, self.roles[name]) for name, role in ROLES.items()
                if role.kind == kind and name in self.roles]

    def _focus_vertices(self) -> np.ndarray:
        mesh = self.mesh
        found = [np.zeros(0, dtype=np.int64)]
        for _, members in self._members("vertex"):
            found.append(members)
        for _, members in self._members("halfedge"):
            found.append(mesh.halfedge_vertex[members])
            found.append(mesh.halfedge_vertex[members ^ 1])
        for _, members in self._members("face"):
            found.append(self._corners_of(members).ravel())
        focus = np.unique(np.concatenate(found).astype(np.int64))
        return focus[(focus >= 0) & ~mesh.vertex_deleted[np.clip(focus, 0, None)]] if len(focus) else focus

    def _corners_of(self, faces: np.ndarray) -> np.ndarray:
        """(k, 3) corner vertices of ``faces``, as drawn (local faces as last drawn)."""
        mesh = self.mesh
        h0 = mesh.face_halfedge[faces]
        h1 = mesh.halfedge_next[h0]
        h2 = mesh.halfedge_next[h1]
        corners = np.stack([mesh.halfedge_vertex[h0], mesh.halfedge_vertex[h1], mesh.halfedge_vertex[h2]], axis=1)
        drawn_faces, drawn_corners = self._local_drawn
        if len(drawn_faces) and len(faces):
            slot = np.minimum(np.searchsorted(drawn_faces, faces), len(drawn_faces) - 1)
            hit = drawn_faces[slot] == faces
            corners[hit] = drawn_corners[slot[hit]]
        return corners

    def _ring_mark(self, seeds: np.ndarray, rings: int) -> np.ndarray:
        """(n_vertex_slots,) bool: the vertices within ``rings`` edges of ``seeds``."""
        offsets, neighbors = self.mesh.vertex_adjacency()
        mark = np.zeros(self.mesh.n_vertex_slots, dtype=bool)
        mark[seeds] = True
        frontier = seeds
        for _ in range(rings):
            starts, stops = offsets[frontier], offsets[frontier + 1]
            reached = neighbors[_ranges(starts, stops)]
            frontier = np.unique(reached[~mark[reached]])
            if len(frontier) == 0:
                break
            mark[frontier] = True
        return mark

    def _outgoing_of(self, vertices: np.ndarray) -> np.ndarray:
        """All outgoing halfedges of ``vertices`` (from the cached one-ring walk)."""
        offsets, _ = self.mesh.vertex_adjacency()
        walk = self.mesh.one_rings()
        return walk.halfedges[_ranges(offsets[vertices], offsets[vertices + 1])].astype(np.int64)

    def _draw_arrows(self, halfedges: np.ndarray) -> None:
        import pyvista as pv

        halfedges = np.asarray(halfedges, dtype=np.int64)
        self._arrow_halfedges = halfedges
        self._arrow_slot = {}
        if len(halfedges) == 0:
            self._set_data("arrows", None)
            return
        A, B, third = self.corners(self.mesh, halfedges)
        points, triangles = _arrows.arrow_geometry(A, B, third, scale=self._scale, width=self.preset.arrow_width)
        data = pv.PolyData.from_regular_faces(points, triangles)
        data.cell_data["rgb"] = np.zeros((len(triangles), 3), dtype=np.uint8)
        self._set_data("arrows", data)
        # Where each halfedge sits in the arrow list (-1 if it has no arrow).
        self._arrow_index = np.full(self.mesh.n_halfedge_slots, -1, dtype=np.int64)
        self._arrow_index[halfedges] = np.arange(len(halfedges))

    def _update(self) -> None:
        import pyvista as pv

        mesh, look = self.mesh, self.preset
        focus = self._focus_vertices()
        if self._geometry_dirty:
            self._draw_local_faces()
        if self.windowed:
            if self.fixed_window is not None:
                window = self._drawable(np.asarray(self.fixed_window, dtype=np.int64))
                ends = np.concatenate([mesh.halfedge_vertex[window], mesh.halfedge_vertex[window ^ 1]])
                inside = np.unique(ends)
            else:
                if len(focus) == 0:
                    focus = np.array([int(np.flatnonzero(~mesh.vertex_deleted)[0])])
                mark = self._ring_mark(focus, self.rings)
                inside = np.flatnonzero(mark)
                outgoing = self._outgoing_of(inside)
                window = np.sort(outgoing[mark[mesh.halfedge_vertex[outgoing ^ 1]]])
            self._draw_arrows(window)
            positions = mesh.positions
            ends = mesh.edge_vertices()[np.unique(window >> 1)]             # (k, 2)
            lines = pv.PolyData(positions, lines=np.hstack([np.full((len(ends), 1), 2), ends]).ravel())
            self._set_data("window_edges", lines)
            self._set_data("vertices", pv.PolyData(positions[inside]))
        elif self._geometry_dirty:
            self._draw_arrows(self._drawable(np.arange(mesh.n_halfedge_slots)))
            self._set_data("vertices", pv.PolyData(np.array(mesh.positions[~mesh.vertex_deleted])))
        self._geometry_dirty = False
        if self._camera_state is None:
            self._aim_whole_mesh()                 # first time: fit the mesh and its arrows
        self._color_arrows()
        self._draw_highlight_faces()
        self._draw_highlight_vertices()
        self._draw_legend()
        self._aim(focus)
        self._draw_labels(focus)

    def _color_arrows(self) -> None:
        mesh, look = self.mesh, self.preset
        halfedges = self._arrow_halfedges
        if len(halfedges) == 0:
            return
        colors = np.where((mesh.halfedge_face[halfedges] < 0)[:, None], rgb(look.boundary_arrow), rgb(look.plain_arrow))
        # Later roles first, so the earliest role in ROLES wins where two overlap.
        for name, members in reversed(self._members("halfedge")):
            slots = self._arrow_index[members[(members >= 0) & (members < len(self._arrow_index))]]
            colors[slots[slots >= 0]] = rgb(ROLES[name].color)
        self._data["arrows"].cell_data["rgb"] = np.repeat(colors.astype(np.uint8), _arrows.TRIANGLES_PER_ARROW, axis=0)

    def _draw_highlight_faces(self) -> None:
        import pyvista as pv

        faces, colors = [], []
        for name, members in reversed(self._members("face")):
            faces.append(members)
            colors.append(np.repeat(rgb(ROLES[name].color)[None], len(members), axis=0))
        if not faces:
            self._set_data("highlight_faces", None)
            return
        faces = np.concatenate(faces)
        faces, first = np.unique(faces[::-1], return_index=True)          # earliest role wins
        colors = np.concatenate(colors)[::-1][first]
        faces_ok = (faces >= 0) & (faces < self.mesh.n_face_slots)
        faces, colors = faces[faces_ok], colors[faces_ok]
        faces_ok = ~self.mesh.face_deleted[faces]
        faces, colors = faces[faces_ok], colors[faces_ok]
        if len(faces) == 0:
            self._set_data("highlight_faces", None)
            return
        corners = self._corners_of(faces)                                  # (k, 3)
        lift = 0.5 * _arrows.LIFT * self._scale * self._face_normals[faces]
        points = self.mesh.positions[corners] + lift[:, None, :]           # (k, 3, 3)
        data = pv.PolyData.from_regular_faces(points.reshape(-1, 3), np.arange(3 * len(faces)).reshape(-1, 3))
        data.cell_data["rgb"] = colors.astype(np.uint8)
        self._set_data("highlight_faces", data)

    def _draw_highlight_vertices(self) -> None:
        import pyvista as pv

        chosen: dict[int, np.ndarray] = {}
        for name, members in self._members("vertex"):
            for v in members:
                chosen.setdefault(int(v), rgb(ROLES[name].color))
        chosen = {v: c for v, c in chosen.items() if 0 <= v < self.mesh.n_vertex_slots and not self.mesh.vertex_deleted[v]}
        if not chosen:
            self._set_data("highlight_vertices", None)
            return
        vertices = np.array(sorted(chosen))
        data = pv.PolyData(self.mesh.positions[vertices])
        data.point_data["rgb"] = np.array([chosen[v] for v in vertices], dtype=np.uint8)
        self._set_data("highlight_vertices", data)

    # ----------------------------------------------------------------------------------
    # Camera
    # ----------------------------------------------------------------------------------

    def _view_direction(self) -> np.ndarray:
        """Toward the camera: along the normal of a flat mesh, else an oblique default."""
        normals = self._face_normals[self._live_faces]
        mean = normals.mean(axis=0) if len(normals) else np.zeros(3)
        if np.linalg.norm(mean) > 0.9:
            return unit(mean)
        return unit(VIEW_DIRECTION)

    def _legend_width(self) -> float:
        """Fraction of the image width the legend takes (0 without one)."""
        return self.preset.legend_size[0] + 0.03 if self.legend else 0.0

    def _set_camera(self, focal: np.ndarray, direction: np.ndarray, radius: float,
                    points: np.ndarray | None = None) -> None:
        """Look at ``focal`` from ``direction``, far enough to see a ball of ``radius``,
        or, when ``points`` are given, exactly those points (re-centred, small margin).

        With a legend on the right, the picture is shifted left so the two do not overlap.
        """
        direction = unit(direction)
        up = np.array([0.0, 1.0, 0.0])
        if abs(direction @ up) > 0.95:
            up = np.array([0.0, 0.0, -1.0]) if direction[1] > 0 else np.array([0.0, 0.0, 1.0])
        up = unit(up - (up @ direction) * direction)
        right = np.cross(up, direction)
        width, height = self.window_size
        free = 1.0 - self._legend_width()
        tan_vertical = np.tan(np.radians(15.0))
        tan_horizontal = tan_vertical * free * width / height
        if points is None:
            distance = radius / np.sin(np.arctan(min(tan_vertical, tan_horizontal))) * 1.02
        else:
            offset = points - focal
            x, y = offset @ right, offset @ up
            focal = focal + right * 0.5 * (x.max() + x.min()) + up * 0.5 * (y.max() + y.min())
            offset = points - focal
            x, y, z = offset @ right, offset @ up, offset @ direction
            distance = float(np.max(np.maximum(np.abs(x) / tan_horizontal, np.abs(y) / tan_vertical) * 1.15 + z))
        camera = self.plotter.camera
        camera.focal_point = tuple(focal)
        camera.position = tuple(focal + distance * direction)
        camera.up = tuple(up)
        camera.view_angle = 30.0
        camera.SetWindowCenter(1.0 - free, 0.0)
        self.plotter.camera_set = True  # else pyvista resets the camera at the first render
        self._camera_state = (np.array(focal), direction, radius)
        self.plotter.renderer.ResetCameraClippingRange()

    def _aim_whole_mesh(self, direction: np.ndarray | None = None) -> None:
        # Fit the vertices and the arrows (boundary arrows lie outside the mesh).
        points = [self.mesh.positions[~self.mesh.vertex_deleted]]
        if self._actors["arrows"].GetVisibility():
            points.append(np.asarray(self._data["arrows"].points))
        self._set_camera(self._center, self._view_direction() if direction is None else direction,
                         self._radius, points=np.concatenate(points))

    def _aim(self, focus: np.ndarray) -> None:
        if len(focus) == 0:
            return
        follow = self.follow
        _, to_camera, _ = self._camera_state
        faces = [members for _, members in self._members("face")]
        if faces:
            faces = np.concatenate(faces)
            faces = faces[(faces >= 0) & (faces < self.mesh.n_face_slots)]
            normal = unit(self._face_normals[faces].sum(axis=0))
        else:
            normal = unit(self._vertex_normals[focus].sum(axis=0))
        if not np.linalg.norm(normal) > 0:
            return
        if follow == "auto":
            follow = self.windowed
            centre = self.mesh.positions[focus].mean(axis=0) - self._center
            off_axis = np.linalg.norm(centre - (centre @ to_camera) * to_camera) / self._radius
            facing = normal @ to_camera
            if not follow and (facing < 0.3 or (facing < 0.8 and off_axis > 0.6)):
                # The highlight is seen edge-on or from behind: swing round to face it,
                # still looking at the whole mesh, a little from the side.
                self._aim_whole_mesh(unit(1.5 * normal + unit(VIEW_DIRECTION)))
                return
        if follow:
            positions = self.mesh.positions[focus]
            centre = positions.mean(axis=0)
            radius = max(float(np.linalg.norm(positions - centre, axis=1).max()), 0.5 * self._scale)
            self._set_camera(centre, normal, radius + 0.4 * self.rings * self._scale)

    # ----------------------------------------------------------------------------------
    # Labels and legend
    # ----------------------------------------------------------------------------------

    def _facing(self, points: np.ndarray, normals: np.ndarray) -> np.ndarray:
        """(k,) bool: the element's front side looks toward the camera."""
        position = np.array(self.plotter.camera.position)
        return ((position - points) * normals).sum(axis=1) > 0


    def _vertex_in_sight(self, vertices: np.ndarray) -> np.ndarray:
        """(k,) bool: one of the vertex's faces (as built) looks toward the camera, so
        silhouette corners count; vertices of the local faces always do."""
        offsets, faces = self._vertex_faces
        known = vertices < len(offsets) - 1
        seen = ~known
        inside = vertices[known]
        ring = _ranges(offsets[inside], offsets[inside + 1])                 # their faces
        owner = np.repeat(np.arange(len(inside)), offsets[inside + 1] - offsets[inside])
        around = faces[ring]
        corner = self.mesh.positions[self._face_first_corner[around]]
        front = self._facing(corner, self._face_normals[around])
        hit = np.zeros(len(inside), dtype=bool)
        hit[owner[front]] = True
        seen[known] = hit
        seen |= np.isin(vertices, self._local_drawn[1])
        return seen

    def _label_choice(self) -> dict[str, str]:
        """For each kind, which elements get a label: "all", "near" or "highlighted"."""
        mesh, kinds = self.mesh, self.label_kinds
        if kinds == "auto":
            if mesh.n_faces <= TINY_FACES:
                return {kind: "all" for kind in _KINDS}
            return {"vertex": "all" if mesh.n_vertices <= TINY_VERTICES and not self.windowed else "near",
                    "halfedge": "highlighted", "face": "highlighted"}
        reach = "all" if mesh.n_faces <= LABEL_ALL_FACES and not self.windowed else "near"
        return {kind: reach for kind in kinds}

    def _labelled(self, kind: str, choice: str | None, near: np.ndarray | None) -> np.ndarray:
        """The indices of ``kind`` that get a label (named ones always do)."""
        mesh = self.mesh
        chosen = [np.array([i for k, i in self.names if k == kind], dtype=np.int64)]
        if choice == "highlighted" or (choice == "near" and near is None):
            chosen += [members for _, members in self._members(kind)]
        elif choice is not None:
            if kind == "vertex":
                candidates = np.flatnonzero(~mesh.vertex_deleted)
            elif kind == "face":
                candidates = self._live_faces
            else:
                candidates = self._arrow_halfedges
            if choice == "near":
                if kind == "vertex":
                    candidates = candidates[near[candidates]]
                elif kind == "face":
                    candidates = candidates[near[self._corners_of(candidates)].all(axis=1)]
                else:
                    candidates = candidates[near[mesh.halfedge_vertex[candidates]] & near[mesh.halfedge_vertex[candidates ^ 1]]]
            chosen.append(candidates)
        found = np.unique(np.concatenate(chosen).astype(np.int64))
        if kind == "halfedge":
            found = found[(found >= 0) & (found < mesh.n_halfedge_slots)]
            return found[~mesh.edge_deleted[found >> 1]]
        slots = mesh.n_vertex_slots if kind == "vertex" else mesh.n_face_slots
        deleted = mesh.vertex_deleted if kind == "vertex" else mesh.face_deleted
        found = found[(found >= 0) & (found < slots)]
        return found[~deleted[found]]

    def _draw_labels(self, focus: np.ndarray) -> None:
        mesh, look = self.mesh, self.preset
        choice = self._label_choice()
        near = self._ring_mark(focus, 1) if len(focus) and "near" in choice.values() else None
        positions = mesh.positions
        texts: dict[str, tuple[np.ndarray, list[str]]] = {}

        vertices = self._labelled("vertex", choice.get("vertex"), near)
        if len(vertices):
            vertices = vertices[self._vertex_in_sight(vertices)]
            points = beside(self.plotter, self.window_size, positions[vertices], 0.45 * look.highlight_vertex_size)
            texts["vertex"] = (points, [self._label_text("vertex", v) for v in vertices])
        faces = self._labelled("face", choice.get("face"), near)
        if len(faces):
            centroids = positions[self._corners_of(faces)].mean(axis=1)
            keep = self._facing(centroids, self._face_normals[faces])
            faces, centroids = faces[keep], centroids[keep]
            centroids = centroids + _arrows.LIFT * self._scale * self._face_normals[faces]
            texts["face"] = (centroids, [self._label_text("face", f) for f in faces])
        halfedges = self._labelled("halfedge", choice.get("halfedge"), near)
        if len(halfedges):
            A, B, third = self.corners(mesh, halfedges)
            middle = 0.5 * (A + B)
            points = middle + 0.6 * ((A + B + third) / 3.0 - middle)
            keep = self._facing(points, np.cross(B - A, third - A))
            texts["halfedge"] = (points[keep], [self._label_text("halfedge", h) for h in halfedges[keep]])

        styles = {
            "vertex": dict(text_color="#FFFFFF", shape_color=look.vertex, shape="rounded_rect",
                           font_size=look.label_size, bold=True,
                           justification_horizontal="left", justification_vertical="bottom"),
            "face": dict(text_color=look.text, shape=None, font_size=look.label_size, bold=False, italic=True,
                         justification_horizontal="center", justification_vertical="center"),
            "halfedge": dict(text_color="#333333", shape=None, font_size=max(8, look.label_size - 1), bold=False,
                             justification_horizontal="center", justification_vertical="center"),
        }
        import pyvista as pv

        self._label_texts = {kind: list(texts.get(kind, ((), []))[1]) for kind in _KINDS}
        for kind in _KINDS:
            name = f"{kind}_labels"
            points, words = texts.get(kind, (np.zeros((0, 3)), []))
            if len(words) == 0:
                if name in self._actors:
                    self._actors[name].SetVisibility(False)
                continue
            data = pv.PolyData(np.asarray(points, dtype=float))
            data.point_data["labels"] = np.array(words)
            if name in self._actors:
                # The label actor reads this dataset: refill it instead of a new actor.
                self._data[name].copy_from(data)
                self._actors[name].SetVisibility(True)
                continue
            self._data[name] = data
            self._actors[name] = self.plotter.add_point_labels(
                data, "labels", name=name, show_points=False, always_visible=True,
                margin=2, reset_camera=False, render=False, **styles[kind],
            )

    def labels_shown(self) -> dict[str, list[str]]:
        """The label texts drawn now, by kind: ``{"vertex": ["v0", ...], ...}``."""
        return {kind: list(words) for kind, words in self._label_texts.items()}

    def _label_text(self, kind: str, index: int) -> str:
        plain = f"{_LABEL_PREFIX[kind]}{int(index)}"
        name = self.names.get((kind, int(index)))
        return plain if name is None else f"{name} ({int(index)})"

    def legend_entries(self) -> list[tuple[str, str, str]]:
        """What the legend shows now: ``(text, "#RRGGBB", kind)`` rows, kind being
        "halfedge", "vertex" or "face" (for drawing the legend elsewhere, e.g. HTML)."""
        entries = []
        if len(self._arrow_halfedges):
            entries.append(("halfedge", self.preset.plain_arrow, "halfedge"))
            if (self.mesh.halfedge_face[self._arrow_halfedges] < 0).any():
                entries.append(("boundary halfedge", self.preset.boundary_arrow, "halfedge"))
        seen = set()
        for name, role in ROLES.items():
            if name in self.roles and (role.legend, role.color) not in seen:
                seen.add((role.legend, role.color))
                entries.append((role.legend, role.color, role.kind))
        return entries

    def _draw_legend(self) -> None:
        if not self.legend:
            return
        entries = self.legend_entries()
        key = tuple(entries)
        if key == self._legend_key:
            return
        self._legend_key = key
        if self._legend_actor is not None:
            self.plotter.renderer.RemoveViewProp(self._legend_actor)
            self._legend_actor = None
        if entries:
            self._legend_actor = _legend_box(entries, self.preset, self.window_size)
            self.plotter.renderer.AddViewProp(self._legend_actor)


def _legend_box(entries, look: Preset, window_size):
    """A legend with black text and coloured symbols (VTK's own colours its text)."""
    import pyvista as pv
    from vtkmodules.vtkRenderingAnnotation import vtkLegendBoxActor

    symbols = {"halfedge": _legend_arrow(), "vertex": pv.Disc(inner=0, outer=0.45, c_res=24).triangulate(),
               "face": pv.PolyData(np.array([[0, -0.4, 0], [1, -0.4, 0], [1, 0.4, 0], [0, 0.4, 0.0]]),
                                   faces=[4, 0, 1, 2, 3])}
    legend = vtkLegendBoxActor()
    legend.SetNumberOfEntries(len(entries))
    for i, (text, color, kind) in enumerate(entries):
        symbol = symbols[kind].copy()
        symbol.cell_data["rgb"] = np.repeat(rgb(color)[None], symbol.n_cells, axis=0)
        legend.SetEntry(i, symbol, text, (0.0, 0.0, 0.0))
    legend.ScalarVisibilityOn()
    legend.UseBackgroundOn()
    legend.SetBackgroundColor(1.0, 1.0, 1.0)
    legend.SetBackgroundOpacity(0.9)
    legend.BorderOff()
    text = legend.GetEntryTextProperty()
    text.SetFontFamilyToArial()
    text.SetColor(0.0, 0.0, 0.0)
    width = look.legend_size[0]
    row = look.label_size * 1.9 / window_size[1]
    height = min(0.96, row * len(entries))
    legend.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    legend.GetPositionCoordinate().SetValue(1.0 - width - 0.01, 0.98 - height)
    legend.GetPosition2Coordinate().SetValue(width, height)
    return legend


def _ranges(starts: np.ndarray, stops: np.ndarray) -> np.ndarray:
    """Concatenate ``arange(s, t)`` for each pair, without a Python loop."""
    lengths = stops - starts
    total = int(lengths.sum())
    if total == 0:
        return np.zeros(0, dtype=np.int64)
    owner_start = np.repeat(starts - np.concatenate([[0], np.cumsum(lengths)[:-1]]), lengths)
    return owner_start + np.arange(total)
