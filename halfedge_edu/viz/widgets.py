"""Notebook widgets for walking a halfedge mesh: :class:`HalfedgeExplorer`, :class:`OneRingViewer`.

    from halfedge_edu.viz import HalfedgeExplorer
    w = HalfedgeExplorer(hx.sample("cube"), halfedge=0)
    w                       # the view with next / prev / twin buttons and a pointer table
    w.go("twin")            # the same as clicking "twin"
    w.go("next.twin")       # several moves, read left to right like h.next.twin
    w.press("n")            # the key n, as pressed in the Lab: the same as clicking "next"
    print(w.describe())     # "current: halfedge 3 (4 -> 0, face 1); next ...", for nbval

Every widget shows a 3D view beside a side panel of buttons and tables. The view is
live in JupyterLab and a static image everywhere else (see :mod:`.renderer`); the
code path is the same. Displayed in a notebook, a widget also carries its
``describe()`` text as ``text/plain`` and a PNG of its view, so a static export or
GitHub's preview still shows something faithful.

Every widget also answers keys in a live Lab (the explorer ``n`` / ``p`` / ``t``, the
steppers the arrows, space, Home and End) while the mouse pointer is over the panel
below its buttons; a hint line there lists them (see :mod:`.keys`).

Attention: callbacks never print (under nbval a print inside a callback lands in the
cell's output); messages go to the panel's status line.
"""

from __future__ import annotations

import html
import re
from collections.abc import Callable

from .keys import KeyArea
from .main_thread import on_main_thread
from .palette import ROLES, Preset, panel_css, preset as _preset
from .renderer import View, choose_mode, make_plotter, widget_bundle
from .scene import HalfedgeScene


def panel_button(look: Preset, label: str, tooltip: str, action: Callable[[], object], *,
                 on_error: Callable[[Exception], None] | None = None):
    """A bold panel button of the preset's size that runs ``action()`` when clicked.

    ``on_error`` receives an ``IndexError`` or ``ValueError`` the action raises (a widget
    shows it in its status line: callbacks must not print); without it the error propagates.
    A click runs the action on the kernel's main thread (see :mod:`.main_thread`), so
    its redraw cannot break the view's OpenGL context.
    """
    import ipywidgets as widgets

    css = panel_css(look)
    # At least the preset's width, wider for a longer label: a label is never cut to "st…".
    button = widgets.Button(description=label, tooltip=tooltip,
                            layout=widgets.Layout(height=css["button_height"], width="auto",
                                                  min_width=css["button_width"], flex="0 0 auto"))
    button.style.font_size = css["font"]
    button.style.font_weight = "bold"

    def clicked(_):
        if on_error is None:
            action()
            return
        try:
            action()
        except (IndexError, ValueError) as error:
            on_error(error)

    button.on_click(on_main_thread(clicked))
    return button


def legend_html(entries, look: Preset) -> str:
    """An HTML legend for ``scene.legend_entries()``: a coloured symbol, then the text."""
    symbol = {"halfedge": "&#10140;", "vertex": "&#9679;", "face": "&#9632;"}
    rows = "".join(
        f'<div style="white-space:nowrap"><span style="color:{color};font-size:1.3em">{symbol[kind]}</span>'
        f"&nbsp;{html.escape(text)}</div>"
        for text, color, kind in entries
    )
    return f'<div style="font-size:{panel_css(look)["font"]};line-height:1.45">{rows}</div>'


def table_html(rows, look: Preset, *, header=None, mark_row: int | None = None) -> str:
    """An HTML table; a row is ``(cells, role_or_None)``, the role colouring its left edge."""
    css = panel_css(look)
    cell = f"padding:{css['cell']};border-bottom:1px solid #ddd;text-align:left;white-space:nowrap"
    lines = [f'<table style="border-collapse:collapse;font-size:{css["font"]};'
             f'font-family:monospace">']
    if header:
        lines.append("<tr>" + "".join(f'<th style="{cell}">{html.escape(str(h))}</th>' for h in header) + "</tr>")
    for i, (cells, role) in enumerate(rows):
        color = ROLES[role].color if role else "transparent"
        weight = "font-weight:bold;background:#FFF3D6;" if i == mark_row else ""
        first = f"border-left:8px solid {color};"
        lines.append("<tr>" + "".join(
            f'<td style="{cell};{weight}{first if j == 0 else ""}">{html.escape(str(c))}</td>'
            for j, c in enumerate(cells)) + "</tr>")
    lines.append("</table>")
    return "".join(lines)


#: The width the side panel asks for beside the view: with the default 600-pixel view it
#: fits a 1366-pixel laptop screen with JupyterLab's file browser open (946 pixels of
#: output), so the pointer table and the view are seen together there.
PANEL_BASIS = "300px"


class IndexBox:
    """A box to type an element's index in: ``box.widget`` goes into the panel,
    ``box.value`` is the index typed (an int; setting it shows that index).

    A text box, not an ``ipywidgets.IntText``: the browser reads what is typed into an
    IntText as far as it is a whole number, so "1e3" went to index 1 without a word.
    Here the kernel reads the whole text, and anything but a whole number is refused in
    words when the index is asked for.
    """

    def __init__(self, value: int, label: str, look: Preset):
        import ipywidgets as widgets

        css = panel_css(look)
        self.label = label
        self.widget = widgets.Text(value=str(int(value)), description=label,
                                   layout=widgets.Layout(width=f"calc({css['button_width']} * 1.6)",
                                                         height=css["button_height"]))
        self.widget.style.description_width = "auto"

    @property
    def value(self) -> int:
        """The index typed. Raises ValueError (in words) for anything but a whole number."""
        text = self.widget.value.strip()
        if not re.fullmatch(r"[+-]?\d+", text):
            raise ValueError(f"{text!r} is not an index: type a whole number, such as 12")
        return int(text)

    @value.setter
    def value(self, index: int) -> None:
        self.widget.value = str(int(index))


class SceneWidget:
    """What every widget shares: a scene, its view, a side panel, text and PNG output.

    Subclasses build their controls in ``_controls()``, put their state into the scene
    in ``_show()``, fill the panel in ``_panel_html()`` and say it in ``describe()``.
    ``KEYS`` binds keys to their buttons (key -> button label, see :mod:`.keys`): in a
    live Lab, with the mouse pointer over the panel below the buttons, a key does what
    its button does; ``w.press(key)`` does the same from code.
    """

    title = ""
    KEYS: dict[str, str] = {}

    def __init__(self, mesh, *, mode: str | None = None, preset="default", labels="auto",
                 rings: int = 2, window_size=None):
        import ipywidgets as widgets

        self.mode = choose_mode(mode)
        self.look = _preset(preset)
        size = tuple(window_size or self.look.window_size)
        self.scene = self._make_scene(mesh, labels=labels, rings=rings, legend=False,
                                      plotter=make_plotter(self.mode, size), window_size=size)
        css = panel_css(self.look)
        self._status = widgets.HTML(layout=widgets.Layout(min_height="1.5em"))
        self._info = widgets.HTML()
        self._legend = widgets.HTML()
        heading = widgets.HTML(f'<b style="font-size:calc({css["font"]} * 1.25)">{html.escape(self.title)}</b>')
        self._show()
        self.view = View(self.scene, self.mode)
        controls = self._controls()
        # Below the buttons: the part of the panel that answers the widget's KEYS.
        self.key_area = KeyArea([self._status, self._info, self._legend], getattr(self, "buttons", {}),
                                self.KEYS, self.look)
        side = widgets.VBox([heading, *controls, self.key_area.widget],
                            layout=widgets.Layout(padding="0 0 0 16px", flex=f"1 1 {PANEL_BASIS}",
                                                  min_width=PANEL_BASIS))
        # The panel asks for PANEL_BASIS beside the view and takes what is left; its rows
        # wrap. Only where even that is not left does it go below the view (rather than
        # being cut off on the right).
        self.widget = widgets.HBox([self.view.widget, side],
                                   layout=widgets.Layout(align_items="flex-start", flex_flow="row wrap"))
        self._refresh_panel()

    @property
    def mesh(self):
        return self.scene.mesh

    # -- for subclasses ------------------------------------------------------------------

    def _make_scene(self, mesh, **options) -> HalfedgeScene:
        return HalfedgeScene(mesh, preset=self.look, **options)

    def _controls(self) -> list:
        return []

    def _show(self) -> None:
        raise NotImplementedError

    def _panel_html(self) -> str:
        return ""

    def describe(self) -> str:
        """The widget's state in plain text (deterministic, for nbval and for reading)."""
        raise NotImplementedError

    # -- shared --------------------------------------------------------------------------

    def _button(self, label: str, tooltip: str, action):
        """A button that runs ``action()``; an error shows in the status line instead."""
        return panel_button(self.look, label, tooltip, action, on_error=lambda error: self._say(str(error), error=True))

    def _button_row(self, buttons: list[tuple[str, str, Callable[[], object]]]) -> list:
        """One row of ``(label, tooltip, action)`` buttons, kept by label in ``self.buttons``;
        returns the row as a list of controls."""
        import ipywidgets as widgets

        row = widgets.HBox([self._button(label, tooltip, action) for label, tooltip, action in buttons],
                           layout=widgets.Layout(flex_flow="row wrap"))
        self.buttons = {button.description: button for button in row.children}
        return [row]

    def _number_box(self, value: int, label: str) -> "IndexBox":
        return IndexBox(value, label, self.look)

    def press(self, key: str) -> str | None:
        """What pressing ``key`` does in the Lab: click the button it is bound to (see
        ``KEYS``). Returns that button's label, or None for a key the widget does not use."""
        return self.key_area.press(key)

    def _say(self, text: str, *, error: bool = False, color: str | None = None) -> None:
        """Put ``text`` in the status line: red for an error, else ``color`` (dark grey)."""
        color = "#B00020" if error else (color or "#333333")
        size = panel_css(self.look)["font"]
        self._status.value = f'<span style="color:{color};font-size:{size}">{html.escape(text)}</span>'

    def _refresh_panel(self) -> None:
        self._info.value = self._panel_html()
        self._legend.value = legend_html(self.scene.legend_entries(), self.look)

    def _changed(self) -> None:
        """After a state change: scene, panel and picture."""
        self._show()
        self._refresh_panel()
        self.view.update()

    def screenshot(self, path=None) -> bytes:
        """The view as PNG bytes (also written to ``path`` if given)."""
        if self.mode == "static" and path is None:
            return self.view.picture()
        return self.scene.screenshot(path)

    def close(self) -> None:
        """Close the widgets and free the render window."""
        self.key_area.close()
        self.widget.close()
        self.scene.close()

    def _repr_mimebundle_(self, include=None, exclude=None):
        self.view.shown()
        return widget_bundle(self.widget, self.describe(), [self.scene.plotter], self.screenshot, include, exclude)


class HalfedgeExplorer(SceneWidget):
    """Walk a mesh one pointer at a time: next, prev, twin, or jump to a halfedge.

    Args:
        mesh: the mesh to explore.
        halfedge: where to start.
        mode: ``"live"``, ``"static"`` or None (automatic, see :func:`.renderer.choose_mode`).
        preset: ``"default"`` or ``"large"`` (for a projector).
        labels, rings: passed to :class:`~halfedge_edu.viz.scene.HalfedgeScene`.

    ``w.go("next")`` (or "prev", "twin", a chain like "next.twin", or an index),
    ``w.step()`` (the same as next), ``w.back()``; ``w.halfedge`` is the current
    halfedge, ``w.trail`` the visited ones.

    Keys, as in the CMU MeshEdit viewer (N next, T twin), with the mouse pointer over
    the panel below the buttons: ``n`` next, ``p`` prev, ``t`` twin, → or space next
    (``step()``), ← back (``back()``: undo the last move). ``w.press("t")`` does the
    same from code.

    The explorer holds its own copy of the mesh (``w.mesh``): a later cell that edits
    the mesh passed in does not change what the explorer shows (make a new explorer to
    walk the edited mesh).
    """

    title = "Halfedge explorer"
    MOVES = ("next", "prev", "twin")
    KEYS = {"n": "next", "ArrowRight": "next", "Space": "next", "p": "prev", "t": "twin", "ArrowLeft": "back"}

    def __init__(self, mesh, halfedge: int = 0, *, mode: str | None = None, preset="default",
                 labels="auto", rings: int = 2, window_size=None):
        start = mesh.halfedge(int(halfedge)).index
        self._trail: list[tuple[str, int]] = [("start", start)]
        super().__init__(mesh.copy(), mode=mode, preset=preset, labels=labels, rings=rings, window_size=window_size)

    @property
    def halfedge(self):
        """The current halfedge (a handle: ``w.halfedge.next.twin`` works)."""
        return self.mesh.halfedge(self._trail[-1][1])

    @property
    def trail(self) -> list[int]:
        """The halfedges visited so far, oldest first."""
        return [h for _, h in self._trail]

    def go(self, move) -> "object":
        """Move along one pointer ("next", "prev", "twin"), a chain of them
        ("next.twin"), or jump to a halfedge index. Returns the new current halfedge.

        Raises:
            ValueError: an unknown move name.
            IndexError: a halfedge index that does not exist (or was deleted).
        """
        if isinstance(move, str) and not move.strip().lstrip("-").isdigit():
            steps = [part.strip() for part in move.split(".") if part.strip()]
            for part in steps:
                if part not in self.MOVES:
                    raise ValueError(f"unknown move {part!r}: use 'next', 'prev', 'twin' or a halfedge index")
            h = self.halfedge
            for part in steps:
                h = getattr(h, part)
                self._trail.append((part, h.index))
        else:
            h = self.mesh.halfedge(int(move))
            self._trail.append(("jump", h.index))
        self._say("")
        self._changed()
        return self.halfedge

    def step(self):
        """One step along ``next`` (around the current face, or along the boundary)."""
        return self.go("next")

    def pick(self, index: int):
        """Jump to halfedge ``index``."""
        return self.go(int(index))

    def back(self):
        """Undo the last move (nothing happens at the start of the trail)."""
        if len(self._trail) > 1:
            self._trail.pop()
            self._say("")
            self._changed()
        else:
            self._say(f"back: halfedge {self.halfedge.index} is where the walk started; nothing to go back to")
        return self.halfedge

    def _controls(self) -> list:
        import ipywidgets as widgets

        self._index_box = self._number_box(self._trail[-1][1], "halfedge")
        moves = widgets.HBox([
            self._button("prev", "h = h.prev", lambda: self.go("prev")),
            self._button("next", "h = h.next", lambda: self.go("next")),
            self._button("twin", "h = h.twin", lambda: self.go("twin")),
        ], layout=widgets.Layout(flex_flow="row wrap"))
        jump = widgets.HBox([
            self._index_box.widget,
            self._button("go to", "jump to this halfedge index", lambda: self.pick(self._index_box.value)),
            self._button("back", "undo the last move", self.back),
        ], layout=widgets.Layout(flex_flow="row wrap"))
        self.buttons = {b.description: b for row in (moves, jump) for b in row.children
                        if isinstance(b, widgets.Button)}
        return [moves, jump]

    def _show(self) -> None:
        self.scene.show_halfedge(self._trail[-1][1])

    def _pointer_rows(self) -> list[tuple[list, str | None]]:
        h = self.halfedge
        face = h.face
        return [
            (["h", h.index], "current"),
            (["h.vertex", h.vertex.index], "origin"),
            (["h.tip", h.tip.index], "tip"),
            (["h.twin", h.twin.index], "twin"),
            (["h.next", h.next.index], "next"),
            (["h.prev", h.prev.index], "prev"),
            (["h.edge", h.edge.index], None),
            (["h.face", "None (boundary)" if face is None else face.index], "face" if face is not None else None),
        ]

    def _trail_text(self, limit: int | None = None) -> str:
        parts = [f"h{self._trail[0][1]}"]
        for move, h in self._trail[1:]:
            parts.append(f"-{move}-> h{h}")
        if limit is not None and len(parts) > limit:
            parts = ["..."] + parts[-limit:]
        return " ".join(parts)

    def _panel_html(self) -> str:
        if hasattr(self, "_index_box"):
            self._index_box.value = self._trail[-1][1]
        size = panel_css(self.look)["font"]
        return (table_html(self._pointer_rows(), self.look, header=("pointer", "value"))
                + f'<div style="font-size:{size};margin-top:8px"><b>trail</b>: '
                f'{html.escape(self._trail_text(limit=12))}</div>')

    def describe(self) -> str:
        h = self.halfedge
        where = "boundary" if h.face is None else f"face {h.face.index}"
        return (f"current: halfedge {h.index} ({h.vertex.index} -> {h.tip.index}, {where}); "
                f"next {h.next.index}; prev {h.prev.index}; twin {h.twin.index}; edge {h.edge.index}\n"
                f"trail: {self._trail_text()}")


class OneRingViewer(SceneWidget):
    """Turn around a vertex: its outgoing halfedges, neighbours and faces in CCW order.

    ``w.go("ccw")`` moves the current outgoing halfedge counter-clockwise
    (``h = h.prev.twin``), ``w.go("cw")`` clockwise (``h = h.twin.next``),
    ``w.go("tip")`` moves to the neighbour the current halfedge points at, and
    ``w.pick(v)`` to any vertex; ``w.step()`` is one CCW turn.

    Keys, with the mouse pointer over the panel below the buttons: → or space one CCW
    turn (``step()``), ← one CW turn, ``t`` to the tip; ``w.press(key)`` from code.

    The viewer holds its own copy of the mesh (``w.mesh``): a later cell that edits the
    mesh passed in (a collapse, say) does not change what the viewer shows (make a new
    viewer to look at the edited mesh).
    """

    title = "One-ring viewer"
    MOVES = ("ccw", "cw", "tip")
    KEYS = {"ArrowRight": "ccw", "Space": "ccw", "ArrowLeft": "cw", "t": "to tip"}

    def __init__(self, mesh, vertex: int = 0, *, mode: str | None = None, preset="default",
                 labels="auto", rings: int = 2, window_size=None):
        v = mesh.vertex(int(vertex))
        self._vertex = v.index
        self._current = v.halfedge.index
        super().__init__(mesh.copy(), mode=mode, preset=preset, labels=labels, rings=rings, window_size=window_size)

    @property
    def vertex(self):
        """The centre vertex (a handle)."""
        return self.mesh.vertex(self._vertex)

    @property
    def current(self):
        """The current outgoing halfedge."""
        return self.mesh.halfedge(self._current)

    @property
    def outgoing(self) -> list:
        """The outgoing halfedges in CCW order, starting with ``vertex.halfedge``."""
        return self.vertex.outgoing()

    def go(self, move):
        """"ccw", "cw", "tip", or a vertex index to move the centre there."""
        if isinstance(move, str) and not move.strip().lstrip("-").isdigit():
            move = move.strip()
            if move not in self.MOVES:
                raise ValueError(f"unknown move {move!r}: use 'ccw', 'cw', 'tip' or a vertex index")
            h = self.current
            if move == "ccw":
                self._current = h.prev.twin.index
            elif move == "cw":
                self._current = h.twin.next.index
            else:
                self._vertex = h.tip.index
                self._current = self.vertex.halfedge.index
        else:
            v = self.mesh.vertex(int(move))
            self._vertex, self._current = v.index, v.halfedge.index
        self._say("")
        self._changed()
        return self.current

    def step(self):
        """One counter-clockwise turn: ``h = h.prev.twin``."""
        return self.go("ccw")

    def pick(self, vertex: int):
        """Centre the view on vertex ``vertex``."""
        return self.go(int(vertex))

    def _controls(self) -> list:
        import ipywidgets as widgets

        self._index_box = self._number_box(self._vertex, "vertex")
        turns = widgets.HBox([
            self._button("cw", "h = h.twin.next (clockwise)", lambda: self.go("cw")),
            self._button("ccw", "h = h.prev.twin (counter-clockwise)", lambda: self.go("ccw")),
            self._button("to tip", "move the centre to h.tip", lambda: self.go("tip")),
        ], layout=widgets.Layout(flex_flow="row wrap"))
        jump = widgets.HBox([
            self._index_box.widget,
            self._button("go to", "centre on this vertex", lambda: self.pick(self._index_box.value)),
        ], layout=widgets.Layout(flex_flow="row wrap"))
        self.buttons = {b.description: b for row in (turns, jump) for b in row.children
                        if isinstance(b, widgets.Button)}
        return [turns, jump]

    def _show(self) -> None:
        self.scene.show_one_ring(self._vertex, current=self._current)

    def _panel_html(self) -> str:
        if hasattr(self, "_index_box"):
            self._index_box.value = self._vertex
        rows, mark = [], None
        for k, h in enumerate(self.outgoing):
            face = h.face
            rows.append(([k, h.index, h.tip.index, "boundary" if face is None else face.index],
                         "current" if h.index == self._current else "outgoing"))
            if h.index == self._current:
                mark = k
        v = self.vertex
        kind = "boundary" if v.is_boundary else "interior"
        size = panel_css(self.look)["font"]
        return (f'<div style="font-size:{size};margin-bottom:6px">vertex <b>{v.index}</b> ({kind}, degree {v.degree})'
                f"<br>CCW: <code>h = h.prev.twin</code></div>"
                + table_html(rows, self.look, header=("#", "outgoing h", "h.tip", "h.face"), mark_row=mark))

    def describe(self) -> str:
        v = self.vertex
        outgoing = self.outgoing
        order = [h.index for h in outgoing]
        k = order.index(self._current) if self._current in order else -1
        faces = [f.index for f in v.faces()]
        kind = "boundary" if v.is_boundary else "interior"
        return (f"vertex {v.index} ({kind}, degree {v.degree})\n"
                f"outgoing (CCW): {', '.join(map(str, order))}\n"
                f"neighbours (CCW): {', '.join(str(h.tip.index) for h in outgoing)}\n"
                f"faces (CCW): {', '.join(map(str, faces))}\n"
                f"current: halfedge {self._current} ({k + 1} of {len(order)}) -> vertex {self.current.tip.index}")
