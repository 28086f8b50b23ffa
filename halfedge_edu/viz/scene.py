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

The scene assembles parts that live in their own modules: :mod:`.geometry` (normals,
centre, faces as drawn), :mod:`.arrows` (the arrow layer), :mod:`.highlights` (roles,
coloured faces and dots), :mod:`.labels`, :mod:`.legend` and :mod:`.camera`; this module
holds the surface and the vertex dots, and decides what is redrawn when.

Attention: after editing the mesh (an operation, moved vertices) call ``refresh()``;
the scene does not watch the mesh.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping

import numpy as np

from .actors import Actors
from .arrows import POINTS_PER_ARROW, ArrowLayer, drawable, halfedge_corners
from .camera import Camera
from .geometry import SceneGeometry
from .highlights import Highlight
from .labels import LABEL_ALL_FACES, Labels, label_kinds
from .legend import Legend, legend_entries
from .neighbourhood import Origins, Rings
from .palette import Preset, preset as _preset, rgb
from .pictures import plotter_png
from .renderer import prepare_plotter

#: Halfedge counts above this draw arrows only near the highlight.
MAX_ARROWS = 3000


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
        corners: ``(mesh, halfedges) -> (A, B, third)``, where the arrows go (default
            :func:`~halfedge_edu.viz.arrows.halfedge_corners`); a stepper passes its own
            to draw a mesh whose pointers are half rewired.
        face_corners: ``faces -> (k, 3)`` corner vertices for local faces whose ``next``
            loop is not a triangle (a stepper's in-between state); None draws them not.
        window: on a large mesh, draw the arrows of these halfedges (and nothing else)
            instead of the rings around the highlight.
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
        corners=halfedge_corners,
        face_corners=None,
        window=None,
    ):
        self.mesh = mesh
        self.preset = _preset(preset)
        self.rings = int(rings)
        self.max_arrows = int(max_arrows)
        self.legend = bool(legend)
        self.follow = follow
        self.window_size = tuple(window_size or self.preset.window_size)
        self.plotter = prepare_plotter(self.preset, self.window_size, plotter)
        self._local_faces = np.unique(np.asarray([] if local_faces is None else local_faces, dtype=np.int64))
        self._face_corners = face_corners
        self._window = None if window is None else np.asarray(window, dtype=np.int64)
        self._rings: Rings | None = None
        self._actors = Actors(self.plotter)
        self._arrows = ArrowLayer(self._actors, self.preset, corners)
        self._highlight = Highlight()
        self._labels = Labels(self._actors, self.preset, self.window_size, label_kinds(labels))
        self._legend = Legend(self.plotter, self.preset, self.window_size)
        legend_width = self.preset.legend_size[0] + 0.03 if self.legend else 0.0
        self._camera = Camera(self.plotter, self.window_size, legend_width)
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
        return self._arrows.halfedges.copy()

    def drawn_edges(self) -> np.ndarray:
        """(k, 2) the vertex pairs drawn as edge lines now, each pair sorted, no repeats:
        the outlines of the surface as built, the local faces' edges as their halfedges'
        ``.vertex`` pointers are now, and on a large mesh the edges near the highlight."""
        pairs = [self._local_edge_ends]
        if self.windowed:
            pairs.append(self._window_edge_ends)
        else:
            static = self._static_faces
            pairs += [static[:, [0, 1]], static[:, [1, 2]], static[:, [2, 0]]]
        pairs = np.sort(np.concatenate(pairs).astype(np.int64), axis=1)
        return np.unique(pairs, axis=0) if len(pairs) else pairs.reshape(0, 2)

    @property
    def arrow_points(self) -> np.ndarray:
        """(k, 7, 3) the points of each arrow, in the order of :attr:`drawn_halfedges`
        (see :mod:`.arrows` for the seven points of one arrow)."""
        return self._arrows.points().reshape(-1, POINTS_PER_ARROW, 3).copy()

    @property
    def arrow_colors(self) -> np.ndarray:
        """(k, 3) uint8 the colour of each arrow, in the order of :attr:`drawn_halfedges`."""
        return self._arrows.colors().copy()

    @property
    def roles(self) -> dict[str, np.ndarray]:
        """The highlight: role name -> (k,) element indices (after leaving out missing ones)."""
        return self._highlight.roles

    @property
    def names(self) -> dict[tuple[str, int], str]:
        """Label texts by ``(kind, index)``, as given to :meth:`set_roles`."""
        return self._highlight.names

    def set_roles(self, roles: Mapping[str, "int | Iterable[int]"], *, names=None) -> None:
        """Highlight elements by role: ``{"current": 7, "origin": [2], ...}``.

        Role names are those of :data:`halfedge_edu.viz.palette.ROLES`; each role has
        a kind (vertex, halfedge or face), so plain indices are enough. An element in
        two roles takes the colour of the one listed first in ``ROLES``. ``names``
        optionally maps ``(kind, index)`` to a label text (the steppers' "vA", "h_AB").
        Replaces the previous highlight.
        """
        self._highlight.set(self.mesh, roles, names)
        self._update()

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
        are drawn in the preset's "rewiring" colour, where ``face_corners`` says.
        """
        self.mesh = mesh
        self._geometry.grow(mesh)
        self._geometry_dirty = True
        self.set_roles({} if roles is None else roles, names=names)

    def look_at(self, vertices, rings: int = 1) -> None:
        """Turn the camera toward ``vertices`` and fit them with ``rings`` rings around them.

        A small mesh (at most ``LABEL_ALL_FACES`` faces) is shown whole, turned toward them.
        """
        vertices = np.asarray(vertices, dtype=np.int64)
        if self.mesh.n_faces <= LABEL_ALL_FACES:
            # A small mesh is best seen whole.
            self._camera.fit(self._geometry, self._whole_mesh_points(),
                             self._camera.direction_toward(self._geometry, vertices))
        else:
            around = np.flatnonzero(self._mesh_rings().mark(vertices, rings)) if rings else vertices
            self._camera.look_at(self.mesh, self._geometry, vertices, around)
        self._draw_labels(self._highlight.focus_vertices(self.mesh, self._geometry))

    def render(self) -> None:
        """Push the current state to the render window."""
        self.plotter.render()

    def screenshot(self, path=None) -> bytes:
        """Render and return the picture as PNG bytes; also write it to ``path`` if given."""
        return plotter_png(self.plotter, path)

    def describe(self) -> str:
        """The mesh and the highlight in plain, deterministic text."""
        mesh = self.mesh
        lines = [
            f"mesh: {mesh.n_vertices} vertices, {mesh.n_edges} edges, {mesh.n_faces} faces, "
            f"{mesh.n_boundary_loops} boundary loop{'s' if mesh.n_boundary_loops != 1 else ''}"
        ]
        return "\n".join(lines + self._highlight.describe())

    def labels_shown(self) -> dict[str, list[str]]:
        """The label texts drawn now, by kind: ``{"vertex": ["v0", ...], ...}``."""
        return {kind: list(words) for kind, words in self._labels.texts.items()}

    def legend_entries(self) -> list[tuple[str, str, str]]:
        """What the legend shows now: ``(text, "#RRGGBB", kind)`` rows, kind being
        "halfedge", "vertex" or "face" (for drawing the legend elsewhere, e.g. HTML)."""
        return legend_entries(self.mesh, self._arrows.halfedges, self._highlight, self.preset)

    def close(self) -> None:
        """Free the render window."""
        self.plotter.close()

    # ----------------------------------------------------------------------------------
    # Building (once, and again on refresh)
    # ----------------------------------------------------------------------------------

    def _build(self) -> None:
        import pyvista as pv

        mesh, look = self.mesh, self.preset
        self._geometry = SceneGeometry(mesh)
        live_faces = self._geometry.live_faces
        corners = mesh.face_vertices()[live_faces]                          # (F, 3)
        static = ~np.isin(live_faces, self._local_faces)
        self._static_faces = corners[static]                                 # (S, 3) drawn with outlines
        self._window_edge_ends = np.zeros((0, 2), dtype=np.int64)
        # Who leaves which vertex, for the edited versions set_mesh draws (see Origins).
        self._origins = Origins(mesh)
        surface = pv.PolyData.from_regular_faces(np.array(mesh.positions), corners[static])
        add = self._actors.add
        add("surface", surface, color=look.surface, show_edges=not self.windowed,
            edge_color=look.edge, line_width=look.edge_width, ambient=0.5, diffuse=0.5,
            specular=0.0, smooth_shading=False)
        placeholder = pv.PolyData(np.zeros((3, 3)), faces=[3, 0, 1, 2])
        placeholder.cell_data["rgb"] = np.zeros((1, 3), dtype=np.uint8)
        # The local faces are filled without outlines: their edges are drawn as lines from
        # the halfedges' own ends ("local_edges"), so a half rewired face never shows an
        # edge the pointers do not have yet (the flip's new diagonal before its .vertex
        # pointers change).
        add("local_surface", placeholder.copy(), scalars="rgb", rgb=True, show_edges=False,
            ambient=0.5, diffuse=0.5, specular=0.0, show_scalar_bar=False)
        add("local_edges", pv.PolyData(np.zeros((2, 3)), lines=[2, 0, 1]),
            color=look.edge, line_width=look.edge_width, lighting=False)
        add("highlight_faces", placeholder.copy(), scalars="rgb", rgb=True,
            ambient=0.5, diffuse=0.5, specular=0.0, show_scalar_bar=False)
        add("arrows", placeholder.copy(), scalars="rgb", rgb=True, lighting=False, show_scalar_bar=False)
        if self.windowed:
            add("window_edges", pv.PolyData(np.zeros((2, 3)), lines=[2, 0, 1]),
                color=look.edge, line_width=look.edge_width, lighting=False)
        add("vertices", pv.PolyData(np.zeros((1, 3))), color=look.vertex,
            point_size=look.vertex_size, render_points_as_spheres=True)
        points = pv.PolyData(np.zeros((1, 3)))
        points.point_data["rgb"] = np.zeros((1, 3), dtype=np.uint8)
        add("highlight_vertices", points, scalars="rgb", rgb=True,
            point_size=look.highlight_vertex_size, render_points_as_spheres=True, show_scalar_bar=False)
        self._geometry_dirty = True                # the next update draws the arrows again
        self._legend.forget()

    def _draw_local_faces(self) -> None:
        """Redraw the local faces as the mesh has them now (rewired ones stand out)."""
        import pyvista as pv

        mesh, look = self.mesh, self.preset
        faces = self._local_faces[self._local_faces < mesh.n_face_slots]
        faces = faces[~mesh.face_deleted[faces]]
        self._geometry.clear_local()
        if len(faces) == 0:
            self._actors.set("local_surface", None)
            self._draw_local_edges(np.zeros(0, dtype=np.int64))
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
        if not valid.all() and self._face_corners is not None:
            corners[~valid] = self._face_corners(faces[~valid])
        drawn = (corners >= 0).all(axis=1)
        faces, corners, valid = faces[drawn], corners[drawn], valid[drawn]
        points = mesh.positions[corners]                                   # (k, 3, 3)
        data = pv.PolyData.from_regular_faces(points.reshape(-1, 3), np.arange(3 * len(faces)).reshape(-1, 3))
        data.cell_data["rgb"] = np.where(valid[:, None], rgb(look.surface), rgb(look.rewiring_face)).astype(np.uint8)
        self._actors.set("local_surface", data)
        self._geometry.set_local(mesh, faces, corners)
        self._draw_local_edges(np.unique(corners))

    def _draw_local_edges(self, corners: np.ndarray) -> None:
        """Fill "local_edges" with every live edge that has an end in ``corners``, from its
        halfedges' ``.vertex`` pointers as they are now."""
        import pyvista as pv

        mesh = self.mesh
        self._local_edge_ends = np.zeros((0, 2), dtype=np.int64)
        if len(corners) == 0:
            self._actors.set("local_edges", None)
            return
        # An edge has an end in ``corners`` when one of its halfedges leaves one of them:
        # the table of origins answers that from the few halfedges that changed (Origins).
        edges = np.unique(self._origins.leaving(mesh, corners) >> 1)
        ends = mesh.edge_vertices()[edges]                                 # (k, 2)
        self._local_edge_ends = ends[(ends >= 0).all(axis=1)]
        if len(self._local_edge_ends) == 0:
            self._actors.set("local_edges", None)
            return
        cells = np.hstack([np.full((len(self._local_edge_ends), 1), 2), self._local_edge_ends]).ravel()
        self._actors.set("local_edges", pv.PolyData(np.asarray(mesh.positions, dtype=np.float64), lines=cells))

    # ----------------------------------------------------------------------------------
    # Updating (every highlight change)
    # ----------------------------------------------------------------------------------

    def _update(self) -> None:
        import pyvista as pv

        mesh = self.mesh
        if self._geometry_dirty:
            # First: the focus below reads the local faces' corners as drawn for this mesh.
            self._draw_local_faces()
        focus = self._highlight.focus_vertices(mesh, self._geometry)
        if self.windowed:
            if self._window is not None:
                window = drawable(mesh, self._window)
                inside = np.unique(np.concatenate([mesh.halfedge_vertex[window], mesh.halfedge_vertex[window ^ 1]]))
            else:
                seeds = focus if len(focus) else np.array([int(np.flatnonzero(~mesh.vertex_deleted)[0])])
                inside, window = self._mesh_rings().window(seeds, self.rings)
            self._arrows.draw(mesh, window, self._geometry.scale)
            ends = mesh.edge_vertices()[np.unique(window >> 1)]             # (k, 2)
            self._window_edge_ends = ends
            lines = pv.PolyData(mesh.positions, lines=np.hstack([np.full((len(ends), 1), 2), ends]).ravel())
            self._actors.set("window_edges", lines)
            self._actors.set("vertices", pv.PolyData(mesh.positions[inside]))
        elif self._geometry_dirty:
            self._arrows.draw(mesh, drawable(mesh, np.arange(mesh.n_halfedge_slots)), self._geometry.scale)
            self._actors.set("vertices", pv.PolyData(np.array(mesh.positions[~mesh.vertex_deleted])))
        self._geometry_dirty = False
        if self._camera.direction is None:
            self._camera.fit(self._geometry, self._whole_mesh_points())   # first time: the mesh and its arrows
        self._arrows.color(mesh, self._highlight.members("halfedge"))
        self._highlight.draw_faces(self._actors, mesh, self._geometry)
        self._highlight.draw_vertices(self._actors, mesh)
        if self.legend:
            self._legend.show(self.legend_entries())
        self._camera.follow(mesh, self._geometry, focus, self._highlight.faces(), mode=self.follow,
                            windowed=self.windowed, rings=self.rings, whole_mesh_points=self._whole_mesh_points)
        self._draw_labels(focus)

    def _mesh_rings(self) -> Rings:
        """The rings of the mesh shown now: walked again only after the mesh changed
        (a stepper's next state), so a highlight moving on one mesh reuses its degrees."""
        if self._rings is None or not self._rings.is_for(self.mesh):
            self._rings = Rings(self.mesh, self._origins.degree(self.mesh))
        return self._rings

    def _whole_mesh_points(self) -> np.ndarray:
        """What a view of the whole mesh must fit: the vertices and the arrows (boundary
        arrows lie outside the mesh)."""
        return np.concatenate([self.mesh.positions[~self.mesh.vertex_deleted], self._arrows.points()])

    def _draw_labels(self, focus: np.ndarray) -> None:
        self._labels.draw(self.mesh, self._geometry, self._highlight, focus, self._mesh_rings(),
                          windowed=self.windowed, arrow_halfedges=self._arrows.halfedges,
                          corners=self._arrows.corners)


def scene_picture(mesh, show: "Callable[[HalfedgeScene], None] | None" = None, **options) -> bytes:
    """One picture of ``mesh`` as PNG bytes: a :class:`HalfedgeScene` made with ``options``,
    ``show(scene)`` run on it (e.g. ``lambda s: s.show_halfedge(7)``), then closed."""
    scene = HalfedgeScene(mesh, **options)
    try:
        if show is not None:
            show(scene)
        return scene.screenshot()
    finally:
        scene.close()
