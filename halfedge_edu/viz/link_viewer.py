"""Chapter 08's pictures of the link condition, and its viewer: any sample, any edge.

    from halfedge_edu.viz import LinkViewer, link_png
    link_png(hx.sample("cube"), 1)        # PNG bytes: the links of edge 1's two ends
    w = LinkViewer("cube", 1)             # a mesh dropdown, an edge slider, the picture
    w.edge_choice.value = 3               # the same as moving the slider
    print(w.describe())                   # the sets of the link condition, in words

:func:`draw_link` draws into any plotter: the surface, the edge ``a - b`` (black),
link(a) and link(b) in the palette's ``link_a`` and ``link_b`` colours, and what the two
links share: ``link_shared`` where it belongs to link(ab) (the two opposite vertices),
``link_extra`` where it does not. A boundary counts as the extra vertex "∂": when the
links share it, the boundary loops are drawn in ``link_extra``.

The viewer's picture is a live view in JupyterLab and a static image elsewhere, chosen
by :func:`~halfedge_edu.viz.renderer.choose_mode` as for every widget.
"""

from __future__ import annotations

import html

import numpy as np

from .main_thread import on_main_thread
from .palette import ROLES
from .renderer import View, choose_mode, make_plotter, widget_bundle
from .screen import beside

#: Where to look from, per sample (None: along the normal of the edge's faces).
LINK_VIEWS = {"cube": (-1.0, -1.3, -0.8), "tetrahedron": (-1.0, -0.35, 0.25), "octahedron": (1.0, 0.6, 0.8)}
#: The samples the viewer offers.
LINK_SAMPLES = ("single_collapse", "cube", "tetrahedron", "octahedron", "open_patch", "figure8", "lone_triangle",
                "icosphere")
SURFACE, SURFACE_EDGES = "#EEEBE4", "#5F5B54"


def link_sets(vertices) -> str:
    """A set of link vertices as text, sorted, the boundary written ∂: ``{2, 3, ∂}``."""
    from ..core.ops.link import BOUNDARY

    return "{" + ", ".join("∂" if v == BOUNDARY else str(v) for v in sorted(vertices)) + "}"


def link_edge_sets(edges) -> str:
    """A set of link edges as text: ``{∂-2, 3-4}``."""
    from ..core.ops.link import BOUNDARY

    return "{" + ", ".join(("∂" if i == BOUNDARY else str(i)) + "-" + str(j) for i, j in sorted(edges)) + "}"


def draw_link(plotter, mesh, e: int, view=None):
    """Draw edge ``e``'s link condition into ``plotter`` and aim its camera.

    link(a) and link(b) in the ``link_a`` and ``link_b`` role colours, what they share in
    ``link_shared`` if it belongs to link(ab) and ``link_extra`` if it does not; the edge
    and its ends in ``link_edge``. ``view``: (3,) from the mesh toward the camera (by
    default along the mean normal of the edge's faces). Returns the
    :class:`~halfedge_edu.core.ops.link.LinkCondition`.
    """
    import pyvista as pv

    from ..algorithms.normals import vertex_normals
    from ..core.ops import link_condition
    from ..core.ops.link import BOUNDARY

    lc = link_condition(mesh, e)
    P = mesh.positions
    scale = float(np.median([edge.length for edge in mesh.edges]))
    lifted = P + 0.02 * scale * vertex_normals(mesh)                 # lines just above the surface
    plotter.add_mesh(mesh.to_pyvista(), color=SURFACE, show_edges=True, edge_color=SURFACE_EDGES, line_width=1.2,
                     opacity=0.55 if mesh.is_closed else 1.0)

    def lines(pairs, role, width):
        pairs = [(i, j) for i, j in pairs if BOUNDARY not in (i, j)]   # the boundary is not a point to draw
        if pairs:
            cells = np.hstack([[2, i, j] for i, j in sorted(pairs)])
            plotter.add_mesh(pv.PolyData(lifted, lines=cells), color=ROLES[role].color, line_width=width,
                             render_lines_as_tubes=True)

    def points(vertices, role, size):
        vertices = sorted(v for v in vertices if v != BOUNDARY)
        if vertices:
            plotter.add_mesh(pv.PolyData(lifted[vertices]), color=ROLES[role].color, point_size=size,
                             render_points_as_spheres=True)

    if BOUNDARY in lc.extra.vertices:                       # draw the boundary loop instead
        loop = [(int(mesh.halfedge_vertex[h]), int(mesh.halfedge_vertex[h ^ 1]))
                for boundary in mesh.boundary_loops() for h in boundary]
        lines(loop, "link_extra", 5)
    lines(lc.link_a.edges - lc.shared.edges, "link_a", 7)
    lines(lc.link_b.edges - lc.shared.edges, "link_b", 7)
    lines(lc.extra.edges, "link_extra", 10)
    lines([(lc.a, lc.b)], "link_edge", 9)
    points([lc.a, lc.b], "link_edge", 18)
    points(lc.shared.vertices & lc.link_ab.vertices, "link_shared", 22)
    points(lc.extra.vertices, "link_extra", 26)
    centre = P[~mesh.vertex_deleted].mean(axis=0)
    radius = float(np.linalg.norm(P[~mesh.vertex_deleted] - centre, axis=1).max())
    if view is None:
        view = np.mean([f.normal for f in mesh.edge(e).faces()], axis=0)
    direction = np.asarray(view, dtype=float) / np.linalg.norm(view)
    up = (0.0, 0.0, 1.0) if abs(direction[2]) < 0.9 else (0.0, 1.0, 0.0)
    plotter.camera_position = [tuple(centre + 4.6 * radius * direction), tuple(centre), up]
    # Labels a few pixels up and right of their dots on screen (the camera is set), so
    # that no dot covers its own label.
    labelled = [lc.a, lc.b] + sorted(v for v in lc.shared.vertices if v != BOUNDARY)
    words = ["a" if v == lc.a else "b" if v == lc.b else str(v) for v in labelled]
    plotter.add_point_labels(beside(plotter, plotter.window_size, lifted[labelled], 14), words, font_size=13,
                             text_color="black", shape_color="white", shape_opacity=0.8,
                             justification_horizontal="left", justification_vertical="bottom",
                             show_points=False, always_visible=True)
    return lc


def link_png(mesh, e: int, view=None, size=(320, 300)) -> bytes:
    """PNG bytes of :func:`draw_link` for edge ``e`` of ``mesh``, in an off-screen plotter."""
    import pyvista as pv

    from .pictures import plotter_png

    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    try:
        draw_link(plotter, mesh, e, view)
        return plotter_png(plotter)
    finally:
        plotter.close()


class _LinkScene:
    """What :class:`~halfedge_edu.viz.renderer.View` needs of a scene: a plotter drawn by
    :func:`draw_link`, its size, render and screenshot."""

    def __init__(self, mode: str, window_size):
        self.window_size = tuple(window_size)
        self.plotter = make_plotter(mode, self.window_size)

    def draw(self, mesh, e: int, view=None):
        self.plotter.clear_actors()
        return draw_link(self.plotter, mesh, e, view)

    def render(self) -> None:
        self.plotter.render()

    def screenshot(self, path=None) -> bytes:
        from .pictures import plotter_png

        return plotter_png(self.plotter, path)

    def close(self) -> None:
        self.plotter.close()


class LinkViewer:
    """A mesh and an edge: the link picture and the sets of the link condition.

    Args:
        name: the sample to start with (one of :data:`LINK_SAMPLES`; "icosphere" is
            subdivided once).
        edge: the edge to start with.
        mode: ``"live"``, ``"static"`` or None (automatic, as for every widget).
        window_size: the picture's size in pixels.

    ``mesh_choice`` (a dropdown) and ``edge_choice`` (a slider) are the controls; setting
    their ``value`` from code does what the learner's click does. ``describe()`` says the
    sets in words; ``condition`` is the edge's
    :class:`~halfedge_edu.core.ops.link.LinkCondition`; ``close()`` frees the picture.
    """

    def __init__(self, name: str = "single_collapse", edge: int = 0, *, mode: str | None = None,
                 window_size=(420, 360)):
        import ipywidgets as widgets

        self.mode = choose_mode(mode)
        self.scene = _LinkScene(self.mode, window_size)
        self.mesh_choice = widgets.Dropdown(options=list(LINK_SAMPLES), value=name, description="mesh")
        self.edge_choice = widgets.IntSlider(value=edge, min=0, max=edge, description="edge")
        self.text = widgets.HTML()
        self._new_mesh()
        self.view = View(self.scene, self.mode)
        # Changes from the browser arrive on another thread; redraws run on the main one
        # (a render from another thread breaks the plotter's OpenGL context).
        self.mesh_choice.observe(on_main_thread(self._mesh_changed), names="value")
        self.edge_choice.observe(on_main_thread(self._edge_changed), names="value")
        self.widget = widgets.HBox([self.view.widget, widgets.VBox([self.mesh_choice, self.edge_choice, self.text])])

    @property
    def panel(self):
        """The whole widget (the view, the controls and the text)."""
        return self.widget

    def _new_mesh(self) -> None:
        from ..data import sample

        name = self.mesh_choice.value
        self.mesh = sample(name, subdivisions=1) if name == "icosphere" else sample(name)
        edge = min(self.edge_choice.value, self.mesh.n_edges - 1)
        with self.edge_choice.hold_trait_notifications():
            self.edge_choice.max = self.mesh.n_edges - 1
            self.edge_choice.value = edge
        self._draw()

    def _draw(self) -> None:
        self.condition = self.scene.draw(self.mesh, self.edge_choice.value, LINK_VIEWS.get(self.mesh_choice.value))
        self.text.value = "<pre>" + html.escape(self.describe()) + "</pre>"

    def _mesh_changed(self, change=None) -> None:
        self._new_mesh()
        self.view.update()

    def _edge_changed(self, change=None) -> None:
        self._draw()
        self.view.update()

    def describe(self) -> str:
        """The edge, its ends, the sets of the link condition and the verdict."""
        from ..core.ops import can_collapse

        lc, check = self.condition, can_collapse(self.mesh, self.edge_choice.value)
        return "\n".join([
            f"{self.mesh_choice.value}, edge {self.edge_choice.value} (a = {lc.a}, b = {lc.b})",
            f"link(a) ∩ link(b): {link_sets(lc.shared.vertices)} {link_edge_sets(lc.shared.edges)}",
            f"link(ab):          {link_sets(lc.link_ab.vertices)}",
            f"extra:             {link_sets(lc.extra.vertices)} {link_edge_sets(lc.extra.edges)}",
            "collapse allowed" if check else f"collapse refused ({check.rule})",
        ])

    def screenshot(self, path=None) -> bytes:
        """The picture as PNG bytes (also written to ``path`` if given)."""
        if self.mode == "static" and path is None:
            return self.view.picture()
        return self.scene.screenshot(path)

    def close(self) -> None:
        """Close the widgets and free the render window."""
        self.widget.close()
        self.scene.close()

    def _repr_mimebundle_(self, include=None, exclude=None):
        self.view.shown()
        return widget_bundle(self.widget, self.describe(), [self.scene.plotter], self.screenshot, include, exclude)
