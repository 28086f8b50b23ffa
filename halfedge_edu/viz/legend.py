"""A scene's legend: which colours mean what, drawn in the picture's top right corner.

The entries are the plain and boundary arrows when arrows are drawn, then one per role
in the highlight (roles with the same text and colour share one entry). VTK's legend box
draws them with coloured symbols: an arrow, a dot or a square, by the role's kind.
"""

from __future__ import annotations

import numpy as np

from .highlights import Highlight
from .palette import ROLES, Preset, rgb


def legend_entries(mesh, arrow_halfedges: np.ndarray, highlight: Highlight, look: Preset) -> list[tuple[str, str, str]]:
    """``(text, "#RRGGBB", kind)`` rows, kind being "halfedge", "vertex" or "face"."""
    entries = []
    if len(arrow_halfedges):
        entries.append(("halfedge", look.plain_arrow, "halfedge"))
        if (mesh.halfedge_face[arrow_halfedges] < 0).any():
            entries.append(("boundary halfedge", look.boundary_arrow, "halfedge"))
    seen = set()
    for name, role in ROLES.items():
        if name in highlight.roles and (role.legend, role.color) not in seen:
            seen.add((role.legend, role.color))
            entries.append((role.legend, role.color, role.kind))
    return entries


class Legend:
    """The legend box of one ``plotter``, redrawn only when its entries change."""

    def __init__(self, plotter, look: Preset, window_size: tuple[int, int]):
        self.plotter = plotter
        self.look = look
        self.window_size = window_size
        self._actor = None
        self._shown: tuple | None = None

    def show(self, entries: list[tuple[str, str, str]]) -> None:
        """Draw ``entries`` (nothing when empty)."""
        key = tuple(entries)
        if key == self._shown:
            return
        self._shown = key
        if self._actor is not None:
            self.plotter.renderer.RemoveViewProp(self._actor)
            self._actor = None
        if entries:
            self._actor = legend_box(entries, self.look, self.window_size)
            self.plotter.renderer.AddViewProp(self._actor)

    def forget(self) -> None:
        """Redraw at the next :meth:`show` even if the entries are the same (after a rebuild)."""
        self._shown = None


#: The widest a legend gets, as a share of the picture's width.
MOST_WIDTH = 0.5


def legend_arrow():
    """A small arrow shape for legend entries of halfedge roles."""
    import pyvista as pv

    points = np.array([[0, -0.12, 0], [0.55, -0.12, 0], [0.55, 0.12, 0], [0, 0.12, 0],
                       [0.55, -0.4, 0], [1, 0, 0], [0.55, 0.4, 0]], dtype=float)
    return pv.PolyData.from_regular_faces(points, np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6]]))


def legend_box(entries, look: Preset, window_size):
    """A VTK legend with black text and coloured symbols (VTK's own colours its text)."""
    import pyvista as pv
    from vtkmodules.vtkRenderingAnnotation import vtkLegendBoxActor

    symbols = {"halfedge": legend_arrow(), "vertex": pv.Disc(inner=0, outer=0.45, c_res=24).triangulate(),
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
    # Wide enough for the longest text at the labels' size (VTK shrinks the text to fit
    # its box, which made a small picture's legend unreadable), within reason.
    longest = max((len(text) for text, _, _ in entries), default=0)
    wanted = (2.5 + 0.6 * longest) * look.label_size / window_size[0]
    width = min(max(look.legend_size[0], wanted), MOST_WIDTH)
    row = look.label_size * 1.9 / window_size[1]
    height = min(0.96, row * len(entries))
    legend.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    legend.GetPositionCoordinate().SetValue(1.0 - width - 0.01, 0.98 - height)
    legend.GetPosition2Coordinate().SetValue(width, height)
    return legend
