"""Widgets for chapter 12: de Casteljau's levels under a slider for t, and a Bezier surface to bend.

    from halfedge_edu.viz.bezier_widgets import DeCasteljauViewer, BezierSurfaceEditor
    w = DeCasteljauViewer([[0, 0], [1, 2], [3, 2], [4, 0]], t=0.5)
    w.set_t(0.25); w.show_levels(2)        # the same as moving the two sliders
    w.move_control_point(1, (1.5, 3.0))     # the same as dragging P_1 in the live view
    print(w.describe())                     # every level's points, for nbval

    s = BezierSurfaceEditor(grid)           # grid: (4, 4, 3) control points
    s.select(1, 2); s.move_to([1.0, 2.0, 1.5])
    print(s.describe())

:class:`DeCasteljauViewer` draws a planar curve. Its two sliders set ``t`` and how many
levels of the construction are drawn, so the construction can be shown one level at a
time. In JupyterLab the picture is a live PyVista view of the plane seen from above,
with a ball on every control point: drag a ball and the curve and its construction
follow when the mouse is let go. Elsewhere (course CI, nbval, a static export) it is a
matplotlib PNG, the same on every run, and the control points move from code only.

:class:`BezierSurfaceEditor` draws the surface of a control grid in 3D with PyVista (a
live view in JupyterLab, a static image elsewhere, like every widget of
:mod:`halfedge_edu.viz`); sliders pick a control point and move it.

Both can be driven from code and say their state in words (``describe()``); callbacks
never print.

Attention: in a live JupyterLab, a drag's callback may arrive on another thread than
the one VTK draws on (issue 11); every callback here goes through
:func:`.main_thread.call_on_main_thread` first. The curve's drag balls (VTK sphere
widgets) are made once and only moved afterwards: deleting one inside its own callback
kills the kernel.
"""

from __future__ import annotations

import base64
import html
import io
from collections.abc import Callable

import numpy as np

from ..algorithms.bezier import bezier_curve, bezier_surface, bezier_surface_points, de_casteljau
from .main_thread import call_on_main_thread, on_main_thread
from .painted_scene import Layer, PaintedScene, PlotterScene, legend_html
from .palette import BLACK, BLUE, BLUISH_GREEN, ORANGE, REDDISH_PURPLE, SKY_BLUE, VERMILLION, panel_css
from .palette import Preset, preset as _preset
from .renderer import View, choose_mode, make_plotter, prepare_plotter
from .widgets import SceneWidget, panel_button

#: Colours of de Casteljau's levels 1, 2, 3, ... (level 0, the control polygon, is grey).
LEVEL_COLORS = (BLUE, BLUISH_GREEN, ORANGE, REDDISH_PURPLE, SKY_BLUE, "#8C6D31")
CONTROL = "#7A7A7A"
CURVE_POINT = VERMILLION
SURFACE = "#E8B96A"
#: The balls a drag in the curve's live view moves.
HANDLE = "#555555"
#: Samples of the drawn curve.
CURVE_SAMPLES = 161


def _point_text(point) -> str:
    return "(" + ", ".join(f"{float(c):.4g}" for c in np.asarray(point).ravel()) + ")"


class DeCasteljauViewer:
    """A planar Bezier curve with de Casteljau's construction at one ``t``, level by level.

    Args:
        control_points: (n + 1, 2) the control polygon (copied).
        t: the parameter shown first.
        levels: how many levels of the construction to draw (all by default).
        figsize: the picture's size in inches (at 100 pixels per inch).
        preset: ``"default"`` or ``"large"`` (bigger text and lines for a projector).
        mode: ``"live"`` (a PyVista view whose control points can be dragged),
            ``"static"`` (a matplotlib PNG) or None (automatic, see
            :func:`.renderer.choose_mode`).

    ``set_t(t)``, ``show_levels(k)``, ``step()`` (one more level), ``back()`` and
    ``go(k)`` move the sliders from code; ``move_control_point(i, (x, y))`` does what
    dragging ``P_i`` does, and ``reset()`` puts every control point back; ``levels`` are
    the arrays of :func:`~halfedge_edu.algorithms.bezier.de_casteljau`; ``point`` is the
    curve's point.
    """

    def __init__(self, control_points, t: float = 0.5, *, levels: int | None = None,
                 figsize=(5.6, 4.2), preset: str = "default", mode: str | None = None):
        import ipywidgets as widgets

        self.control_points = np.array(control_points, dtype=np.float64)
        if self.control_points.ndim != 2 or self.control_points.shape[1] != 2 or len(self.control_points) < 2:
            raise ValueError(f"control_points must have shape (n + 1, 2) with n >= 1, got {self.control_points.shape}")
        if not np.isfinite(self.control_points).all():
            raise ValueError(f"control points must be finite numbers, got {self.control_points.tolist()}")
        self.original = self.control_points.copy()
        self.degree = len(self.control_points) - 1
        self.figsize = tuple(figsize)
        self.look = _preset(preset)
        self.large = self.look.name == "large"
        self.mode = choose_mode(mode)
        self.curve = bezier_curve(self.control_points, CURVE_SAMPLES)     # (CURVE_SAMPLES, 2)
        self.t_slider = widgets.FloatSlider(value=float(t), min=0.0, max=1.0, step=0.01, description="t",
                                            readout_format=".2f", continuous_update=True)
        self.level_slider = widgets.IntSlider(value=self.degree if levels is None else int(levels), min=0,
                                              max=self.degree, description="levels")
        self.status = widgets.HTML()
        self.hint = widgets.HTML()
        self.legend = widgets.HTML()
        if self.mode == "live":
            size = (int(round(100 * self.figsize[0])), int(round(100 * self.figsize[1])))
            self.scene = _CurveScene(self.control_points, size, self.look,
                                     on_drag=lambda i, centre: call_on_main_thread(self._dragged, i, centre))
            self.view = View(self.scene, "live")
            picture = self.view.widget
            how = "Drag a grey ball to move its control point; the curve follows when you let go."
        else:
            self.image = widgets.Image(format="png")
            picture = self.image
            how = ("A still picture: dragging the control points needs the live view of JupyterLab. "
                   "From code, viewer.move_control_point(i, (x, y)) moves P_i.")
        self.hint.value = f'<span style="color:#555">{html.escape(how)}</span>'
        self.t_slider.observe(on_main_thread(lambda change: self._redraw()), names="value")
        self.level_slider.observe(on_main_thread(lambda change: self._redraw()), names="value")
        reset = panel_button(self.look, "reset", "every control point back where it started", self.reset)
        self.widget = widgets.VBox([widgets.HBox([self.t_slider, self.level_slider]),
                                    widgets.HBox([picture, self.legend]), widgets.HBox([reset, self.hint]),
                                    self.status])
        self._redraw()

    # -- public --------------------------------------------------------------------------

    @property
    def t(self) -> float:
        return float(self.t_slider.value)

    @property
    def shown_levels(self) -> int:
        return int(self.level_slider.value)

    @property
    def levels(self) -> list[np.ndarray]:
        """Every level of the construction at the current ``t`` (level 0 is the control polygon)."""
        return de_casteljau(self.control_points, self.t)

    @property
    def point(self) -> np.ndarray:
        """(2,) the curve's point at the current ``t``."""
        return self.levels[-1][0]

    def set_t(self, t: float) -> "DeCasteljauViewer":
        """Move the t slider (0 to 1, in steps of 0.01)."""
        if not 0.0 <= float(t) <= 1.0:
            raise ValueError(f"t must be between 0 and 1, got {t}")
        self.t_slider.value = float(t)
        return self

    def show_levels(self, k: int) -> "DeCasteljauViewer":
        """Draw levels 1 to ``k`` of the construction (0: only the control polygon)."""
        if not 0 <= int(k) <= self.degree:
            raise IndexError(f"there is no level {k}: levels run from 0 to {self.degree}")
        self.level_slider.value = int(k)
        return self

    go = show_levels

    def step(self) -> "DeCasteljauViewer":
        """One more level (stays at the last)."""
        return self.show_levels(min(self.shown_levels + 1, self.degree))

    def back(self) -> "DeCasteljauViewer":
        """One level fewer (stays at 0)."""
        return self.show_levels(max(self.shown_levels - 1, 0))

    def move_control_point(self, index: int, position) -> np.ndarray:
        """Move control point ``P_index`` to ``position`` (x, y) and redraw; returns where it is now.

        What letting go of a dragged ball does in the live view.

        Raises:
            IndexError: there is no control point ``index``.
            ValueError: ``position`` is not two finite numbers.
            In both cases nothing changes.
        """
        if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index <= self.degree:
            raise IndexError(f"there is no control point {index!r}: this curve has P_0 to P_{self.degree}")
        point = np.asarray(position, dtype=np.float64)
        if point.shape != (2,) or not np.isfinite(point).all():
            raise ValueError(f"P_{index}: a control point of a planar curve is two finite numbers (x, y), "
                             f"got {position!r}")
        self.control_points[index] = point
        self._reshaped()
        return self.control_points[index].copy()

    def reset(self) -> None:
        """Put every control point back where it started."""
        self.control_points[:] = self.original
        self._reshaped()

    def describe(self) -> str:
        """``t``, the levels drawn with their points, and the curve's point if reached."""
        levels = self.levels
        lines = [f"degree {self.degree} curve at t = {self.t:.2f}: showing {self.shown_levels} of {self.degree} levels"]
        for k in range(self.shown_levels + 1):
            points = " ".join(_point_text(p) for p in levels[k])
            name = "control points" if k == 0 else f"level {k}"
            lines.append(f"{name}: {points}")
        if self.shown_levels == self.degree:
            lines.append(f"point on the curve: C({self.t:.2f}) = {_point_text(self.point)}")
        return "\n".join(lines)

    def screenshot(self, path=None) -> bytes:
        """The current picture as PNG bytes (also written to ``path`` if given)."""
        if self.mode == "live":
            return self.scene.screenshot(path)
        data = bytes(self.image.value)
        if path is not None:
            with open(path, "wb") as file:
                file.write(data)
        return data

    def close(self) -> None:
        self.widget.close()
        if self.mode == "live":
            self.scene.close()

    def _repr_mimebundle_(self, include=None, exclude=None):
        bundle = self.widget._repr_mimebundle_(include=include, exclude=exclude) or {}
        bundle["text/plain"] = self.describe()
        # A client-side live view renders in the browser only: no picture to give here.
        if self.mode == "static" or not getattr(self.scene.plotter, "suppress_rendering", False):
            bundle["image/png"] = base64.b64encode(self.screenshot()).decode("ascii")
        return bundle

    # -- drawing -------------------------------------------------------------------------

    def figure(self):
        """A matplotlib figure of the current state (the caller closes it)."""
        from matplotlib.figure import Figure

        scale = 1.6 if self.large else 1.0
        figure = Figure(figsize=self.figsize, dpi=100)
        axes = figure.add_axes((0.02, 0.12, 0.96, 0.8))
        levels, t = self.levels, self.t
        polygon = self.control_points
        axes.plot(*polygon.T, "--", color=CONTROL, lw=1.2 * scale, zorder=1)
        axes.plot(*polygon.T, "o", color=CONTROL, ms=6 * scale, zorder=2)
        for i, p in enumerate(polygon):
            axes.annotate(f"$P_{i}$", p, textcoords="offset points", xytext=(6, 6), fontsize=11 * scale)
        axes.plot(*self.curve.T, color=BLACK, lw=1.0 * scale, alpha=0.35, zorder=1)
        done = self.curve[: int(round(t * (len(self.curve) - 1))) + 1]
        axes.plot(*done.T, color=BLACK, lw=2.4 * scale, zorder=3)
        for k in range(1, self.shown_levels + 1):
            color = LEVEL_COLORS[(k - 1) % len(LEVEL_COLORS)]
            level = levels[k]
            if len(level) > 1:
                axes.plot(*level.T, "-", color=color, lw=1.5 * scale, zorder=4)
            last = k == self.degree
            axes.plot(*level.T, "o", color=CURVE_POINT if last else color, ms=(10 if last else 6) * scale,
                      zorder=5, label="point on the curve" if last else f"level {k}")
        axes.set_aspect("equal")
        axes.axis("off")
        span = np.ptp(polygon, axis=0).max() or 1.0
        low, high = polygon.min(axis=0) - 0.08 * span, polygon.max(axis=0) + 0.08 * span
        axes.set_xlim(low[0], high[0])
        axes.set_ylim(low[1], high[1])
        figure.suptitle(f"t = {t:.2f}, levels shown: {self.shown_levels} of {self.degree}", fontsize=12 * scale)
        if self.shown_levels:
            axes.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=min(self.shown_levels, 4),
                        fontsize=9 * scale, frameon=False)
        return figure

    def _reshaped(self) -> None:
        """After a control point moved: the sampled curve, then the picture."""
        self.curve = bezier_curve(self.control_points, CURVE_SAMPLES)
        self._redraw()

    def _legend_entries(self) -> list[tuple[str, str, str]]:
        """What the live picture shows, as :func:`.painted_scene.legend_html` rows (the
        static picture has its legend inside)."""
        entries = [("control polygon", CONTROL, "edge"), (f"curve from t = 0 to {self.t:.2f}", BLACK, "edge")]
        for k in range(1, self.shown_levels + 1):
            if k == self.degree:
                entries.append(("point on the curve", CURVE_POINT, "vertex"))
            else:
                entries.append((f"level {k}", LEVEL_COLORS[(k - 1) % len(LEVEL_COLORS)], "edge"))
        return entries

    def _dragged(self, index: int, centre) -> None:
        """A ball was let go in the live view at ``centre`` (x, y, z): move its point in the plane.

        A release that did not move the ball changes nothing (VTK also reports the first
        mouse release in the view to a ball that was never grabbed).
        """
        point = np.asarray(centre, dtype=np.float64)[:2]
        if point.shape == (2,) and np.allclose(point, self.control_points[index]):
            return
        try:
            self.move_control_point(index, point)
        except (IndexError, ValueError) as error:
            self.status.value = f'<span style="color:#B00020">{html.escape(str(error))}</span>'

    def _redraw(self) -> None:
        if self.mode == "live":
            self.scene.draw(self.control_points, self.curve, self.levels, self.shown_levels, self.t)
            self.view.update()
            self.legend.value = legend_html(self._legend_entries(), self.look)
        else:
            figure = self.figure()
            buffer = io.BytesIO()
            figure.savefig(buffer, format="png", metadata={"Software": None})
            self.image.value = buffer.getvalue()
        self.status.value = "<br>".join(html.escape(line) for line in self.describe().splitlines())


class _CurveScene(PlotterScene):
    """The live picture of a :class:`DeCasteljauViewer`: its construction in the plane
    z = 0, seen from straight above, with a ball on every control point to drag.

    Args:
        control_points: (n + 1, 2) the first control points (they fix the camera and the
            balls' size).
        window_size: the picture's (width, height) in pixels.
        look: the preset (line widths and text sizes).
        on_drag: ``on_drag(i, centre)`` when the ball of ``P_i`` is let go at ``centre``.

    It has what :class:`~halfedge_edu.viz.renderer.View` needs from a scene
    (``plotter``, ``window_size``, ``render()``, ``screenshot()``, ``close()``).
    """

    def __init__(self, control_points: np.ndarray, window_size: tuple[int, int], look: Preset,
                 on_drag: Callable[[int, tuple[float, float, float]], None]):
        self.window_size = tuple(window_size)
        self.look = look
        self.plotter = prepare_plotter(look, self.window_size, make_plotter("live", self.window_size))
        # Left-drag pans and the wheel zooms: a planar curve is never turned edge-on.
        self.plotter.enable_2d_style()
        low, high = control_points.min(axis=0), control_points.max(axis=0)
        self.span = float((high - low).max()) or 1.0
        centre = np.append(0.5 * (low + high), 0.0)
        camera = self.plotter.camera
        camera.focal_point = tuple(centre)
        camera.position = tuple(centre + (0.0, 0.0, 10.0 * self.span))
        camera.up = (0.0, 1.0, 0.0)
        self.plotter.enable_parallel_projection()
        # Room around the polygon, so that a point dragged a little outside stays in view.
        width, height = self.window_size
        camera.parallel_scale = 0.75 * max(float(high[1] - low[1]), float(high[0] - low[0]) * height / width, 1e-6)
        self.plotter.camera_set = True
        self.handles = [
            self.plotter.add_sphere_widget(lambda centre, i=i: on_drag(i, centre), center=(*point, 0.0),
                                           radius=self.span / 45, color=HANDLE, selected_color=CURVE_POINT,
                                           test_callback=False, interaction_event="end")
            for i, point in enumerate(control_points)
        ]

    def draw(self, control_points: np.ndarray, curve: np.ndarray, levels: list[np.ndarray],
             shown_levels: int, t: float) -> None:
        """Draw the construction at ``t``, levels 1 to ``shown_levels``, and put the balls on the points."""
        import pyvista as pv

        scale = 1.6 if self.look.name == "large" else 1.0
        degree = len(control_points) - 1
        lift = self.span / 1000           # later layers a little nearer the camera, so they are drawn on top

        def flat(points: np.ndarray, layer: int) -> np.ndarray:                    # (k, 2) -> (k, 3)
            points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
            return np.column_stack([points, np.full(len(points), layer * lift)])

        def line(name: str, points: np.ndarray, layer: int, color: str, width: float) -> None:
            self.plotter.add_mesh(pv.lines_from_points(flat(points, layer)), name=name, color=color,
                                  line_width=width * scale, lighting=False, reset_camera=False, render=False)

        def dots(name: str, points: np.ndarray, layer: int, color: str, size: float) -> None:
            self.plotter.add_mesh(pv.PolyData(flat(points, layer)), name=name, color=color,
                                  point_size=size * scale, render_points_as_spheres=True,
                                  reset_camera=False, render=False)

        line("control polygon", control_points, 0, CONTROL, 1.5)
        line("curve", curve, 1, "#B0B0B0", 1.5)
        done = curve[: int(round(t * (len(curve) - 1))) + 1]
        if len(done) > 1:
            line("curve so far", done, 2, BLACK, 3.0)
        else:
            self.plotter.remove_actor("curve so far", render=False)
        for k in range(1, degree + 1):
            names = (f"level {k} lines", f"level {k} points")
            if k > shown_levels:
                self.plotter.remove_actor(list(names), render=False)
                continue
            color = LEVEL_COLORS[(k - 1) % len(LEVEL_COLORS)]
            if len(levels[k]) > 1:
                line(names[0], levels[k], 3 + k, color, 2.0)
            last = k == degree
            dots(names[1], levels[k], 4 + degree + k, CURVE_POINT if last else color, 14.0 if last else 9.0)
        beside = control_points + self.span / 30                                # up and right of each ball
        self.plotter.add_point_labels(flat(beside, 5 + 2 * degree), [f"P{i}" for i in range(degree + 1)],
                                      name="labels", show_points=False, always_visible=True, shape=None,
                                      font_size=int(14 * scale), text_color=BLACK, bold=True,
                                      reset_camera=False, render=False)
        for handle, point in zip(self.handles, control_points):
            handle.SetCenter(float(point[0]), float(point[1]), 0.0)



class BezierSurfaceEditor(SceneWidget):
    """A tensor-product Bezier surface with its control net; sliders pick and move one control point.

    Args:
        control_grid: (m + 1, n + 1, 3) control points (a 4 x 4 grid is bicubic); copied.
        selected: ``(i, j)`` of the control point selected first.
        resolution: samples of the surface along u and along v.
        mode: ``"live"``, ``"static"`` or None (automatic).
        preset, window_size: as for the other widgets.
        view_direction, view_up: from the surface toward the camera, and the direction
            shown as up (by default z is up and the camera looks from the front left).

    ``select(i, j)``, ``move_to(position)`` (the selected point), ``move(i, j, position)``
    and ``reset()`` drive it from code; ``grid`` is the control grid now, ``surface`` the
    sampled surface (a HalfedgeMesh), ``describe()`` says it in words.
    """

    title = "Bezier surface: move a control point"

    def __init__(self, control_grid, *, selected=(1, 1), resolution: int = 24, mode: str | None = None,
                 preset="default", window_size=None, view_direction=(1.0, -1.8, 2.2), view_up=(0.0, 0.0, 1.0)):
        grid = np.array(control_grid, dtype=np.float64)
        if grid.ndim != 3 or grid.shape[2] != 3 or min(grid.shape[:2]) < 2:
            raise ValueError(f"control_grid must have shape (m + 1, n + 1, 3), got {grid.shape}")
        self.original = grid.copy()
        self.grid = grid
        self.resolution = int(resolution)
        self.selected = self._checked(*selected)
        self._view_direction = view_direction
        self._view_up = view_up
        self._syncing = False
        span = np.ptp(grid.reshape(-1, 3), axis=0).max() or 1.0
        self._slider_low = grid.reshape(-1, 3).min(axis=0) - 0.75 * span
        self._slider_high = grid.reshape(-1, 3).max(axis=0) + 0.75 * span
        super().__init__(bezier_surface(grid, self.resolution), mode=mode, preset=preset, labels=None, rings=0,
                         window_size=window_size)

    # -- public --------------------------------------------------------------------------

    @property
    def surface(self):
        """The sampled surface now (a HalfedgeMesh, ``resolution x resolution`` vertices)."""
        return self.scene.mesh

    def select(self, i: int, j: int) -> tuple[int, int]:
        """Select control point ``(i, j)`` (row i along u, column j along v)."""
        self.selected = self._checked(i, j)
        self._sync_sliders()
        self._changed()
        return self.selected

    def move_to(self, position) -> np.ndarray:
        """Move the selected control point to ``position`` (3 numbers); returns it."""
        i, j = self.selected
        return self.move(i, j, position)

    def move(self, i: int, j: int, position) -> np.ndarray:
        """Select control point ``(i, j)`` and move it to ``position``."""
        i, j = self._checked(i, j)
        position = np.asarray(position, dtype=np.float64).reshape(3)
        if not np.isfinite(position).all():
            raise ValueError(f"a control point needs three finite numbers, got {position}")
        self.selected = (i, j)
        self.grid[i, j] = position
        self._sync_sliders()
        self._changed()
        return self.grid[i, j].copy()

    def reset(self) -> None:
        """Put every control point back where it started."""
        self.grid[:] = self.original
        self._sync_sliders()
        self._changed()

    def surface_point(self, u: float, v: float) -> np.ndarray:
        """(3,) the surface's point at ``(u, v)``, by de Casteljau (rows first, then the column)."""
        rows = np.array([de_casteljau(self.grid[:, j], u)[-1][0] for j in range(self.grid.shape[1])])
        return de_casteljau(rows, v)[-1][0]

    def describe(self) -> str:
        i, j = self.selected
        moved = [(a, b) for a in range(self.grid.shape[0]) for b in range(self.grid.shape[1])
                 if not np.allclose(self.grid[a, b], self.original[a, b])]
        m, n = self.grid.shape[0] - 1, self.grid.shape[1] - 1
        lines = [f"degree {m} x {n} Bezier surface ({m + 1} x {n + 1} control points), "
                 f"sampled {self.resolution} x {self.resolution}",
                 f"selected: P[{i}][{j}] at {_point_text(self.grid[i, j])}"
                 + ("" if (i, j) not in moved else f" (was {_point_text(self.original[i, j])})"),
                 "moved: " + (", ".join(f"P[{a}][{b}]" for a, b in moved) if moved else "none"),
                 f"S(0.5, 0.5) = {_point_text(self.surface_point(0.5, 0.5))}"]
        return "\n".join(lines)

    # -- internals -----------------------------------------------------------------------

    def _checked(self, i: int, j: int) -> tuple[int, int]:
        rows, columns = self.grid.shape[:2]
        if not (0 <= int(i) < rows and 0 <= int(j) < columns):
            raise IndexError(f"there is no control point ({i}, {j}): rows 0..{rows - 1}, columns 0..{columns - 1}")
        return int(i), int(j)

    def _make_scene(self, mesh, **options) -> PaintedScene:
        return PaintedScene(mesh, preset=self.look, plotter=options["plotter"], window_size=options["window_size"],
                            view_direction=self._view_direction, vertex_labels=False,
                            fit_points=self._room(), view_up=self._view_up)

    def _room(self) -> np.ndarray:
        """Points the view must take in: the control points, raised and lowered a little
        along "up", so a point moved by the sliders stays in the picture."""
        points = self.grid.reshape(-1, 3)
        up = np.asarray(self._view_up if self._view_up is not None else (0.0, 1.0, 0.0), dtype=np.float64)
        lift = 0.3 * (np.ptp(points, axis=0).max() or 1.0) * up / np.linalg.norm(up)
        return np.concatenate([points, points + lift, points - lift])

    def _show(self) -> None:
        points = bezier_surface_points(self.grid, self.resolution)               # (r, r, 3)
        surface = self.scene.mesh
        surface.positions[:] = points.reshape(-1, 3)                             # same triangles, new places
        rows, columns = self.grid.shape[:2]
        net = [np.stack([self.grid[a, b], self.grid[a + 1, b]]) for a in range(rows - 1) for b in range(columns)]
        net += [np.stack([self.grid[a, b], self.grid[a, b + 1]]) for a in range(rows) for b in range(columns - 1)]
        i, j = self.selected
        layers = [
            Layer("control net", CONTROL, "segments", np.array(net), 2.0),
            Layer("control point", BLACK, "points", self.grid.reshape(-1, 3), 9.0),
            Layer(f"selected: P[{i}][{j}]", CURVE_POINT, "points", self.grid[i, j][None], 16.0),
        ]
        # A little see-through, so the parts of the net below the surface still show.
        self.scene.paint(surface, layers=layers, base_edges=False, smooth=True, surface_opacity=0.8,
                         surface_color=SURFACE)

    def _controls(self) -> list:
        import ipywidgets as widgets

        rows, columns = self.grid.shape[:2]
        # continuous_update=False: a slider tells the kernel only when the mouse lets go of it.
        # With True, the browser's slider also reports every value it is *shown*, so a slider
        # view that missed a move made from code sends its old value back and moves the
        # point there (seen in a live Lab: P[0][1] jumped to x = 1 after chapter 12's cells).
        self.row_slider = widgets.IntSlider(value=self.selected[0], min=0, max=rows - 1, description="row i",
                                            continuous_update=False)
        self.column_slider = widgets.IntSlider(value=self.selected[1], min=0, max=columns - 1,
                                               description="column j", continuous_update=False)
        self.position_sliders = [
            widgets.FloatSlider(value=float(self.grid[self.selected][axis]), min=float(self._slider_low[axis]),
                                max=float(self._slider_high[axis]), step=0.05, description=name,
                                readout_format=".2f", continuous_update=False)
            for axis, name in enumerate("xyz")
        ]
        self.row_slider.observe(on_main_thread(lambda change: self._picked()), names="value")
        self.column_slider.observe(on_main_thread(lambda change: self._picked()), names="value")
        for slider in self.position_sliders:
            slider.observe(on_main_thread(lambda change: self._slid()), names="value")
        reset = self._button("reset", "every control point back where it started", self.reset)
        return [self.row_slider, self.column_slider, *self.position_sliders, reset]

    def _picked(self) -> None:
        if not self._syncing:
            self.select(self.row_slider.value, self.column_slider.value)

    def _slid(self) -> None:
        if not self._syncing:
            i, j = self.selected
            self.grid[i, j] = [slider.value for slider in self.position_sliders]
            self._changed()

    def _sync_sliders(self) -> None:
        """Make the sliders show the selection and its position (without moving anything)."""
        if not hasattr(self, "row_slider"):
            return
        self._syncing = True
        try:
            self.row_slider.value, self.column_slider.value = self.selected
            for axis, slider in enumerate(self.position_sliders):
                value = float(self.grid[self.selected][axis])
                slider.min = min(slider.min, value)
                slider.max = max(slider.max, value)
                slider.value = value
        finally:
            self._syncing = False

    def _panel_html(self) -> str:
        size = panel_css(self.look)["font"]
        return f'<div style="font-size:{size};max-width:30em">' + "<br>".join(
            html.escape(line) for line in self.describe().splitlines()) + "</div>"

    def _refresh_panel(self) -> None:
        self._info.value = self._panel_html()
        self._legend.value = legend_html(self.scene.legend_entries(), self.look)
