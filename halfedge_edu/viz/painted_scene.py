"""A mesh picture painted by groups: coloured edges, vertices, segments, or a heat-map on edges.

The steppers of chapters 09 and 10 need a different picture from the halfedge arrows of
:class:`~halfedge_edu.viz.scene.HalfedgeScene`: *which* edges are new, which vertices
are old, how much each edge would cost to collapse. A :class:`PaintedScene` draws a
mesh's surface and, on top, any number of :class:`Layer` s (a label, a colour, and the
edges, vertices, points or segments it paints), optionally a heat-map of one number per
edge with a colour bar::

    scene = PaintedScene(mesh)
    scene.paint(mesh, layers=[Layer("new edges", "#009E73", "edges", [3, 7, 9])],
                edge_values=costs, value_label="log10 cost")
    png = scene.screenshot()

It has what :class:`~halfedge_edu.viz.widgets.SceneWidget` and
:class:`~halfedge_edu.viz.renderer.View` need from a scene (``mesh``, ``plotter``,
``window_size``, ``render()``, ``screenshot()``, ``legend_entries()``, ``close()``), so
the same widget code runs live in JupyterLab and as a static image elsewhere.

The camera is set once, from the first mesh, and stays put while the widget steps:
that way moving vertices and shrinking meshes are seen to move and shrink.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .palette import Preset, preset as _preset
from ..algorithms.normals import face_normals
from .camera import VIEW_DIRECTION
from .pictures import plotter_png
from .renderer import prepare_plotter
from .labels import BADGE_POINT, PADDING, place, text_size
from .screen import from_screen, to_screen, unit

#: Vertex labels are drawn when the mesh has at most this many vertices.
LABEL_VERTICES = 60



@dataclass
class Layer:
    """One group of elements painted in one colour, with its legend text.

    Attributes:
        label: the legend text ("" keeps it out of the legend).
        color: ``"#RRGGBB"``.
        kind: ``"edges"`` (edge indices), ``"vertices"`` (vertex indices),
            ``"points"`` ((k, 3) positions) or ``"segments"`` ((k, 2, 3) start and end).
        items: what to paint, as the kind says.
        size: line width or point size in pixels (None: the kind's default).
    """

    label: str
    color: str
    kind: str
    items: object = field(default_factory=list)
    size: float | None = None

    def count(self) -> int:
        return len(np.asarray(self.items).reshape(-1, *self._tail()))

    def _tail(self) -> tuple:
        return {"edges": (), "vertices": (), "points": (3,), "segments": (2, 3)}[self.kind]


class PlotterScene:
    """What a scene that owns one plotter (``self.plotter``, of ``self.window_size``)
    does with it: render, give its picture, free it. Shared by :class:`PaintedScene`
    and the de Casteljau viewer's curve scene."""

    plotter: object
    window_size: tuple[int, int]

    def render(self) -> None:
        """Push the current state to the render window."""
        self.plotter.render()

    def screenshot(self, path=None) -> bytes:
        """Render and return the picture as PNG bytes; also write it to ``path`` if given."""
        return plotter_png(self.plotter, path, window_size=self.window_size)

    def close(self) -> None:
        """Free the render window."""
        self.plotter.close()


class PaintedScene(PlotterScene):
    """Draw a mesh and paint layers of edges, vertices, points and segments on it.

    Args:
        mesh: the mesh to draw first (it also fixes the camera).
        preset: ``"default"`` or ``"large"`` (a projector: thicker lines, bigger dots).
        plotter: draw into this ``pyvista.Plotter``; by default a new off-screen one.
        window_size: image size in pixels; the preset's by default.
        view_direction: (3,) from the mesh toward the camera; by default along the
            normal of a flat mesh, else an oblique view.
        vertex_labels: write vertex numbers beside the vertices ("auto": on meshes with
            at most ``LABEL_VERTICES`` vertices, only those facing the camera). They do
            not crowd: a number that would come closer than ``labels.SPACING`` pixels to
            another, or stray from its dot, is left out, except those of
            :meth:`paint`'s ``keep_labels``.
        fit_points: (k, 3) more points the first view must take in (say, control points).
        view_up: (3,) the direction that points up in the picture (y by default).
    """

    def __init__(self, mesh, *, preset: "str | Preset" = "default", plotter=None, window_size=None,
                 view_direction=None, vertex_labels="auto", fit_points=None, view_up=None):
        self.mesh = mesh
        self.preset = _preset(preset)
        self.window_size = tuple(window_size or self.preset.window_size)
        self.plotter = prepare_plotter(self.preset, self.window_size, plotter)
        self.vertex_labels = vertex_labels
        self.layers: list[Layer] = []
        self._names: set[str] = set()
        self._legend: list[tuple[str, str, str]] = []
        self._aim(mesh, view_direction, fit_points, view_up)

    # -- public ----------------------------------------------------------------------------

    def paint(self, mesh=None, *, layers=(), edge_values=None, value_label: str = "",
              value_range=None, cmap: str = "viridis", base_edges: bool = True,
              surface_opacity: float = 1.0, smooth: bool = False, surface_color: str | None = None,
              keep_labels=()) -> None:
        """Draw ``mesh`` (the scene's mesh if None) with ``layers`` on top.

        Args:
            layers: :class:`Layer` s, drawn in order (later ones on top).
            edge_values: (n_edge_slots,) one number per edge, drawn as a heat-map on
                every live edge with a colour bar titled ``value_label``; NaN values
                are drawn grey.
            value_range: ``(low, high)`` of the colour bar (by default the values' range).
            cmap: a matplotlib colour map name (the default, viridis, reads in grey too).
            base_edges: draw every edge not in a layer as a thin grey line.
            surface_opacity: below 1, the surface is see-through (to show points inside).
            smooth: shade the surface smoothly (for sampled surfaces) instead of facet by facet.
            surface_color: ``"#RRGGBB"`` of the surface (the preset's by default).
            keep_labels: vertices whose numbers are written first and always (a step's
                own vertices); the others' only where they do not crowd.
        """
        import pyvista as pv

        if mesh is not None:
            self.mesh = mesh
        mesh, look = self.mesh, self.preset
        positions = np.asarray(mesh.positions, dtype=np.float64)
        drawn: set[str] = set()

        def add(name: str, data, **style) -> None:
            self.plotter.add_mesh(data, name=name, reset_camera=False, render=False, **style)
            drawn.add(name)

        corners = mesh.face_vertices()[~mesh.face_deleted]                  # (F, 3)
        if len(corners):
            surface = pv.PolyData.from_regular_faces(positions, corners)
            add("surface", surface, color=surface_color or look.surface, ambient=0.45, diffuse=0.55, specular=0.0,
                smooth_shading=bool(smooth), show_edges=False, opacity=float(surface_opacity))
            # Push the faces back a little so lines lying on them are not hidden.
            mapper = self.plotter.actors["surface"].GetMapper()
            mapper.SetResolveCoincidentTopologyToPolygonOffset()
            mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 2.0)

        live_edges = np.flatnonzero(~mesh.edge_deleted)
        ends = mesh.edge_vertices()                                          # (E, 2)
        in_layer = np.zeros(mesh.n_edge_slots, dtype=bool)
        for layer in layers:
            if layer.kind == "edges":
                in_layer[np.asarray(layer.items, dtype=np.int64)] = True
        scale = 2.0 if look.name == "large" else 1.0
        if edge_values is not None:
            values = np.asarray(edge_values, dtype=np.float64)[live_edges]
            lines = _lines(positions, ends[live_edges])
            lines.cell_data[value_label or "value"] = values
            finite = values[np.isfinite(values)]
            low, high = value_range if value_range is not None else (
                (float(finite.min()), float(finite.max())) if len(finite) else (0.0, 1.0))
            add("edge_values", lines, scalars=value_label or "value", cmap=cmap, clim=(low, high),
                line_width=2.0 * scale, lighting=False, nan_color="#B0B0B0",
                scalar_bar_args=dict(title=value_label, vertical=False, n_labels=2, fmt="%.1f",
                                     position_x=0.05, position_y=0.02, width=0.5, height=0.08,
                                     color="#000000", title_font_size=12 * int(scale) + 2,
                                     label_font_size=11 * int(scale) + 1))
        elif base_edges:
            plain = live_edges[~in_layer[live_edges]]
            if len(plain):
                add("base_edges", _lines(positions, ends[plain]), color=look.edge,
                    line_width=look.edge_width, lighting=False)

        self._legend = []
        for k, layer in enumerate(layers):
            name = f"layer_{k}"
            if layer.count() == 0:
                continue
            if layer.kind == "edges":
                edges = np.asarray(layer.items, dtype=np.int64)
                data = _lines(positions, ends[edges])
                style = dict(line_width=(layer.size or 3.0) * scale, lighting=False)
                symbol = "edge"
            elif layer.kind == "segments":
                segments = np.asarray(layer.items, dtype=np.float64).reshape(-1, 2, 3)
                data = _lines(segments.reshape(-1, 3), np.arange(2 * len(segments)).reshape(-1, 2))
                style = dict(line_width=(layer.size or 1.5) * scale, lighting=False)
                symbol = "edge"
            else:
                where = (positions[np.asarray(layer.items, dtype=np.int64)] if layer.kind == "vertices"
                         else np.asarray(layer.items, dtype=np.float64).reshape(-1, 3))
                data = pv.PolyData(where)
                style = dict(point_size=(layer.size or look.vertex_size + 3) * scale,
                             render_points_as_spheres=True)
                symbol = "vertex"
            add(name, data, color=layer.color, **style)
            if layer.label:
                self._legend.append((layer.label, layer.color, symbol))

        labels = self._labels(mesh, positions, np.asarray(keep_labels, dtype=np.int64).reshape(-1))
        if labels is not None:
            points, words = labels
            self.plotter.add_point_labels(points, words, name="vertex_labels", show_points=False,
                                          always_visible=True, font_size=look.label_size, text_color="#000000",
                                          shape=None, bold=True, margin=0, reset_camera=False, render=False,
                                          justification_horizontal="left", justification_vertical="bottom")
            drawn.add("vertex_labels")

        for name in self._names - drawn:
            self.plotter.remove_actor(name, render=False)
        self._names = drawn
        self.layers = list(layers)

    def legend_entries(self) -> list[tuple[str, str, str]]:
        """The layers' legend as ``(text, "#RRGGBB", "edge" | "vertex")`` rows."""
        return list(self._legend)

    # -- internals -------------------------------------------------------------------------

    def _aim(self, mesh, view_direction, fit_points=None, view_up=None) -> None:
        positions = mesh.positions[~mesh.vertex_deleted]
        if fit_points is not None:
            positions = np.concatenate([positions, np.asarray(fit_points, dtype=np.float64).reshape(-1, 3)])
        normals = face_normals(mesh)[~mesh.face_deleted]
        mean_normal = normals.mean(axis=0) if len(normals) else np.zeros(3)
        if view_direction is not None:
            direction = unit(np.asarray(view_direction, dtype=np.float64))
        elif np.linalg.norm(mean_normal) > 0.9:
            direction = unit(mean_normal)
        else:
            direction = unit(VIEW_DIRECTION)
        centre = 0.5 * (positions.min(axis=0) + positions.max(axis=0))
        radius = float(np.linalg.norm(positions - centre, axis=1).max()) or 1.0
        up = np.array([0.0, 1.0, 0.0]) if view_up is None else unit(np.asarray(view_up, dtype=np.float64))
        if abs(direction @ up) > 0.95:
            up = np.array([0.0, 0.0, -1.0]) if direction[1] > 0 else np.array([0.0, 0.0, 1.0])
        up = unit(up - (up @ direction) * direction)
        width, height = self.window_size
        half_angle = np.radians(15.0) * min(1.0, width / height)
        distance = radius / np.sin(half_angle) * 1.1
        camera = self.plotter.camera
        camera.focal_point = tuple(centre)
        camera.position = tuple(centre + distance * direction)
        camera.up = tuple(up)
        camera.view_angle = 30.0
        self.plotter.camera_set = True
        self.plotter.renderer.ResetCameraClippingRange()
        self._eye = centre + distance * direction

    def _labels(self, mesh, positions, keep: np.ndarray):
        """``(points, texts)``: vertex numbers beside the vertices that face the camera, put
        with :func:`.labels.place` (``keep`` first and always, the others where they do not
        crowd), or None."""
        live = np.flatnonzero(~mesh.vertex_deleted)
        wanted = self.vertex_labels
        if wanted is False or wanted is None or (wanted == "auto" and len(live) > LABEL_VERTICES):
            return None
        corners = mesh.face_vertices()[~mesh.face_deleted]
        a, b, c = (positions[corners[:, k]] for k in range(3))
        face_normal = np.cross(b - a, c - a)
        facing = ((self._eye - a) * face_normal).sum(axis=1) > 0
        seen = np.zeros(mesh.n_vertex_slots, dtype=bool)
        seen[corners[facing].ravel()] = True
        shown = live[seen[live]]
        if len(shown) == 0:
            return None
        kept = np.isin(shown, keep)
        shown = np.concatenate([shown[kept], shown[~kept]])                 # the kept ones are placed first
        optional = np.arange(len(shown)) >= kept.sum()                      # (k,)
        texts = [str(int(v)) for v in shown]
        look = self.preset
        anchors = to_screen(self.plotter, self.window_size, positions[shown])          # (k, 3)
        sizes = np.array([text_size(text, look.label_size, PADDING["vertex"]) for text in texts])   # (k, 2)
        dots = np.column_stack([anchors[:, :2], np.full(len(shown), 0.5 * (look.vertex_size + 3))])
        keep_clear = np.full(len(shown), 0.5 * look.highlight_vertex_size + 1)
        centres = place(anchors[:, :2], sizes, keep_clear, dots, np.zeros((0, 4)), self.window_size, optional)
        # A kept number without room anywhere near is still written, up and right of its dot.
        homeless = np.isnan(centres[:, 0]) & ~optional
        centres[homeless] = anchors[homeless, :2] + keep_clear[homeless, None] + sizes[homeless] / 2
        written = ~np.isnan(centres[:, 0])
        if not written.any():
            return None
        corners = centres[written] - sizes[written] / 2 + BADGE_POINT      # the text is drawn from its point
        points = from_screen(self.plotter, self.window_size, np.column_stack([corners, anchors[written, 2]]))
        return points, [text for text, w in zip(texts, written) if w]



def _lines(points: np.ndarray, pairs: np.ndarray):
    """A PolyData of straight lines between ``points[pairs[:, 0]]`` and ``points[pairs[:, 1]]``."""
    import pyvista as pv

    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    cells = np.concatenate([np.full((len(pairs), 1), 2), pairs], axis=1).ravel()
    return pv.PolyData(np.asarray(points, dtype=np.float64), lines=cells)


def legend_html(entries, look: Preset) -> str:
    """An HTML legend for :meth:`PaintedScene.legend_entries`: a coloured line or dot, then the text."""
    import html

    size = "20px" if look.name == "large" else "14px"
    symbol = {"edge": "&#9473;&#9473;", "vertex": "&#9679;"}
    rows = "".join(
        f'<div style="white-space:nowrap"><span style="color:{color};font-size:1.3em;font-weight:bold">'
        f"{symbol[kind]}</span>&nbsp;{html.escape(text)}</div>"
        for text, color, kind in entries
    )
    return f'<div style="font-size:{size};line-height:1.45">{rows}</div>'
