"""Edit a mesh by hand, as in the CMU and CS184 MeshEdit viewers: :class:`MeshEditor`.

    from halfedge_edu.viz import MeshEditor
    editor = MeshEditor(hx.sample("cube"))
    editor                          # the view, index controls, buttons, keys, the last diff
    editor.select("edge", 4)        # what a click in the view or the index boxes does
    editor.apply("flip")            # the same as the "flip" button or the key f
    editor.apply("upsample")        # the whole mesh: the key u, as in CMU's MeshEdit
    editor.move_vertex(3, (0, 0, 1.5))
    editor.undo()
    print(editor.describe())        # mesh counts, "valid", selection, the pointer diff

Selecting: choose a kind (vertex, edge, halfedge, face) and an index, or, in the live
view, **right-click** the mesh: the element of the chosen kind nearest to the clicked
point is selected (:meth:`MeshEditor.pick_at`; left-drag turns the view as usual). The
static picture has nothing to click, so there the index boxes are the way.

Editing, by button, by key or from code (:meth:`MeshEditor.apply`). The keys are those
of CMU 15-462's MeshEdit viewer (f, s, c on the selection; u, d, r on the whole mesh;
i for information), with l for a Laplacian step and z for undo:

====  ==========  ==============================================================
key   operation   what it does
====  ==========  ==============================================================
f     flip        flips the selected edge (or the edge of the selected halfedge)
s     split       splits it at its midpoint; the new vertex is selected
c     collapse    collapses it at its midpoint (a halfedge: its origin goes); the
                  surviving vertex is selected
l     smooth      one uniform Laplacian step (``hx.smooth``) for the selection's
                  vertices and their neighbours; boundary vertices stay put
u     upsample    Loop subdivision of the whole mesh (``hx.loop_subdivide``)
d     downsample  quadric simplification to a quarter of the faces (``hx.simplify``)
r     remesh      isotropic remeshing at the mean edge length (``hx.remesh``)
i     info        says the selected element's pointers; changes nothing
z     undo        back to the mesh before the last edit
====  ==========  ==============================================================

A whole-mesh edit numbers the mesh anew, so its pointer diff is not shown; the selection
keeps its kind and index if the new mesh has that element, else goes to element 0.

Keys are typed into the panel's "keys" box (a notebook page keeps the keyboard for
itself, so the box is where the editor listens). Each key typed there is one edit,
however fast the keys come: the kernel never writes the box, and each time its text
arrives the characters added after what it had seen are the keys (deleting does
nothing). A vertex is moved by dragging the
ball on the selected vertex in the live view (a VTK sphere widget; the vertex moves
when the mouse is let go), with the x, y, z sliders, or :meth:`MeshEditor.move_vertex`.
Many edits from code draw once inside ``with editor.held(): ...``.

After every edit the editor runs ``mesh.validate()`` and says "valid" or the broken
rule, and shows the pointer diff of the edit: every pointer and position it wrote,
old -> new (the operation's :class:`~halfedge_edu.core.ops.log.OperationLog`). A refused
operation (``can_flip`` and friends say no) shows its reason in vermillion (the colour
of the refused edge; red is for errors), highlights the edge and the elements the
reason names, and changes nothing. Undo keeps a copy of the mesh
before each edit (at most ``undo_limit``), so undoing back to the start gives the very
same arrays.

The mesh passed in is copied, never changed; ``editor.mesh`` is the edited mesh (save
it with ``hx.save(editor.mesh, "p7.custom.obj")``).

Attention: in a live JupyterLab, widget callbacks arrive on a kernel subshell thread,
while VTK may only be touched on the kernel's main thread (issue 11). Every callback
here goes through :func:`.main_thread.call_on_main_thread` first.
"""

from __future__ import annotations

import html
import warnings
from collections.abc import Callable
from contextlib import contextmanager

import numpy as np

from .main_thread import call_on_main_thread
from ..algorithms.loop import loop_subdivide
from ..algorithms.remesh import remesh
from ..algorithms.simplify import simplify
from ..algorithms.smoothing import smooth
from ..core.errors import MeshInvariantError
from ..core.ops import OpCheck, OperationLog, PointerChange, collapse, flip, split
from .palette import VERMILLION, panel_css
from .widgets import SceneWidget, table_html

KINDS = ("vertex", "edge", "halfedge", "face")
#: Edits of the selection, then edits of the whole mesh (each makes a new mesh).
OPERATIONS = ("flip", "split", "collapse", "smooth", "upsample", "downsample", "remesh")
WHOLE_MESH = ("upsample", "downsample", "remesh")
#: Key -> what it does: CMU MeshEdit's f, s, c, u, d, r, i; l for Laplacian smoothing; z for undo.
KEYS = {"f": "flip", "s": "split", "c": "collapse", "l": "smooth",
        "u": "upsample", "d": "downsample", "r": "remesh", "i": "info", "z": "undo"}
#: The ball on the selected vertex that a drag in the live view moves (reddish purple).
HANDLE_COLOUR = "#CC79A7"
#: The most faces an upsample may make: each u multiplies them by 4, and a student who
#: keeps pressing it would otherwise wait minutes for a mesh the view cannot turn.
MAX_UPSAMPLED_FACES = 20_000
#: Diff rows shown in the panel (``describe()`` lists them all).
PANEL_DIFF_ROWS = 40

_CHANGED_ROLE = {"halfedge": "changed", "vertex": "changed_vertex", "face": "changed_face"}


class MeshEditor(SceneWidget):
    """Select elements, flip / split / collapse / smooth them, move vertices, undo.

    Args:
        mesh: the mesh to edit; it is copied (``editor.mesh`` is the edited copy).
        select: the first selection, ``(kind, index)``; edge 0 by default.
        mode: ``"live"``, ``"static"`` or None (automatic, see :func:`.renderer.choose_mode`).
        preset: ``"default"`` or ``"large"`` (for a projector).
        labels, rings, window_size: as for every widget.
        undo_limit: how many edits can be undone (a mesh copy is kept for each).

    See the module's docstring for the controls and keys.
    """

    title = "Mesh editor"

    def __init__(self, mesh, *, select: tuple[str, int] = ("edge", 0), mode: str | None = None,
                 preset="default", labels="auto", rings: int = 2, window_size=None, undo_limit: int = 200):
        if int(undo_limit) < 1:
            raise ValueError(f"undo_limit must be at least 1, got {undo_limit!r}")
        working = mesh.copy()
        self._selection = self._checked_selection(working, *select)
        self._history: list[tuple[object, tuple[str, int]]] = []
        self._undo_limit = int(undo_limit)
        self._last_log: OperationLog | None = None
        self._last_check: OpCheck | None = None
        self._last_text = ""
        self._validity = self._validity_of(working)
        self._syncing = False
        self._mesh = working
        self._handle = None                       # (vertex, VTK sphere widget) in the live view
        self._held = 0
        self._stale = False
        # The scene draws a copy taken at each redraw, so edits made while held
        # (see held()) never leave the scene's mesh and its drawing apart.
        super().__init__(working.copy(), mode=mode, preset=preset, labels=labels, rings=rings, window_size=window_size)
        if self.mode == "live":
            self.scene.plotter.enable_surface_point_picking(
                callback=lambda point: call_on_main_thread(self._picked, point),
                show_message=False, show_point=False, left_clicking=False, picker="cell")

    # -- public ----------------------------------------------------------------------------

    @property
    def mesh(self):
        """The edited mesh (the picture shows a copy of it, taken at the last redraw)."""
        return self._mesh

    @contextmanager
    def held(self):
        """Edit without redrawing until the ``with`` block ends, then draw once.

        For a script of many edits: ``with editor.held(): for e in edges: ...``.
        Every edit is still validated and can be undone.
        """
        self._held += 1
        try:
            yield self
        finally:
            self._held -= 1
            self._draw()

    @property
    def selection(self) -> tuple[str, int]:
        """``(kind, index)`` of the selected element."""
        return self._selection

    @property
    def last_log(self) -> OperationLog | None:
        """The pointer diff of the last edit (None before the first, or after undo)."""
        return self._last_log

    @property
    def can_undo(self) -> int:
        """How many edits can be undone."""
        return len(self._history)

    @property
    def valid(self) -> bool:
        """True when ``mesh.validate()`` passed after the last edit."""
        return self._validity == "valid"

    def select(self, kind: str, index: int) -> tuple[str, int]:
        """Select element ``index`` of ``kind`` ("vertex", "edge", "halfedge" or "face").

        Raises:
            ValueError: an unknown kind.
            IndexError: no such element, or it was deleted.
        """
        self._selection = self._checked_selection(self.mesh, kind, index)
        self._last_check = None
        self._say("")
        self._draw()
        return self._selection

    def pick_at(self, point, kind: str | None = None) -> tuple[str, int]:
        """Select the element of ``kind`` (the chosen kind by default) nearest to ``point``.

        What a right-click in the live view does, with the point it hit on the surface.
        """
        kind = self._selection[0] if kind is None else kind
        if kind not in KINDS:
            raise ValueError(f"unknown kind {kind!r}: use one of {', '.join(KINDS)}")
        point = np.asarray(point, dtype=float).reshape(3)
        return self.select(kind, _nearest(self.mesh, kind, point))

    def apply(self, operation: str) -> OpCheck:
        """Apply ``"flip"``, ``"split"``, ``"collapse"`` or ``"smooth"`` to the selection,
        or ``"upsample"``, ``"downsample"`` or ``"remesh"`` to the whole mesh.

        Returns the check: truthy when the edit was made, falsy (with ``.reason``) when it
        was refused, in which case nothing changed.

        Raises:
            ValueError: an unknown operation.
        """
        if operation not in OPERATIONS:
            raise ValueError(f"unknown operation {operation!r}: use one of {', '.join(OPERATIONS)}")
        if operation == "smooth":
            return self._smooth()
        if operation in WHOLE_MESH:
            return self._whole_mesh(operation)
        return self._edge_operation(operation)

    def move_vertex(self, vertex: int, position) -> OpCheck:
        """Move ``vertex`` to ``position`` (three numbers); it becomes the selection.

        Raises:
            IndexError: no such vertex, or it was deleted.
            ValueError: ``position`` is not three finite numbers.
        """
        v = self.mesh.vertex(int(vertex)).index
        new = np.asarray(position, dtype=float)
        if new.shape != (3,) or not np.isfinite(new).all():
            raise ValueError(f"vertex {v}: a position is three finite numbers, got {position!r}")
        log = OperationLog(operation="move")
        log.changes.append(PointerChange("vertex", v, "position", _as_tuple(self.mesh.positions[v]), _as_tuple(new)))
        log.notes.append(f"vertex {v} moved")

        def edit(mesh) -> tuple[str, int]:
            log.replay(mesh)
            return "vertex", v

        return self._commit(log, edit)

    def key(self, key: str) -> OpCheck | None:
        """What pressing ``key`` does (see :data:`KEYS`); returns the check, None for
        undo and info.

        Raises:
            ValueError: a key the editor does not use.
        """
        name = str(key).strip().lower()
        if name not in KEYS:
            raise ValueError(f"unknown key {key!r}: keys are " + ", ".join(f"{k} ({v})" for k, v in KEYS.items()))
        if KEYS[name] == "undo":
            self.undo()
            return None
        if KEYS[name] == "info":
            self.info()
            return None
        return self.apply(KEYS[name])

    def info(self) -> str:
        """The selected element and its pointers in one line (also shown in the panel)."""
        text = _pointers_text(self.mesh, *self._selection)
        self._say(text)
        return text

    def undo(self) -> bool:
        """Go back to the mesh and selection before the last edit; False if there is none."""
        if not self._history:
            self._say("nothing to undo")
            return False
        mesh, self._selection = self._history.pop()
        self._mesh = mesh
        self._last_log, self._last_check = None, None
        self._last_text = "undone"
        self._validity = self._validity_of(mesh)
        self._say("undone")
        self._draw(rebuild=True)
        return True

    def describe(self) -> str:
        mesh = self.mesh
        kind, index = self._selection
        lines = [f"mesh: {mesh.n_vertices} vertices, {mesh.n_edges} edges, {mesh.n_faces} faces; {self._validity}",
                 f"selected: {self._selection_text()}"]
        if self._last_check is not None and not self._last_check:
            lines.append(f"refused: {self._last_text}: {self._last_check.reason}")
        elif self._last_log is not None:
            lines.append(f"last edit: {self._last_text} ({len(self._last_log.changes)} changes)")
            lines += [f"  {change.describe()}" for change in self._last_log.changes]
        elif self._last_text:
            lines.append(f"last edit: {self._last_text}")
        lines.append(f"undo: {len(self._history)} edit{'s' if len(self._history) != 1 else ''}")
        return "\n".join(lines)

    # -- edits -----------------------------------------------------------------------------

    def _edge_operation(self, operation: str) -> OpCheck:
        kind, index = self._selection
        if kind not in ("edge", "halfedge"):
            return self._refuse(operation, OpCheck.refuse(
                "selection", f"{operation} needs an edge or a halfedge; {kind} {index} is selected",
                ((kind, index),)))
        argument = self.mesh.halfedge(index) if kind == "halfedge" else self.mesh.edge(index)
        check = getattr(self.mesh, f"can_{operation}")(argument)
        if not check:
            return self._refuse(operation, check)
        log = OperationLog()
        run = {"flip": flip, "split": split, "collapse": collapse}[operation]

        def edit(mesh) -> tuple[str, int] | None:
            result = run(mesh, mesh.halfedge(index) if kind == "halfedge" else mesh.edge(index), log=log)
            # flip keeps its edge selected; split and collapse return the vertex to select
            return None if operation == "flip" else ("vertex", result.index)

        return self._commit(log, edit, check)

    def _smooth(self) -> OpCheck:
        mesh = self.mesh
        region = _with_neighbours(mesh, _selection_vertices(mesh, *self._selection))
        smoothed = smooth(mesh, iterations=1).positions                   # (n_vertex_slots, 3)
        log = OperationLog(operation="smooth")
        for v in region:
            old, new = _as_tuple(mesh.positions[v]), _as_tuple(smoothed[v])
            if old != new:
                log.changes.append(PointerChange("vertex", int(v), "position", old, new))
        log.notes.append(f"one uniform Laplacian step for vertices {', '.join(map(str, region))}")
        return self._commit(log, log.replay, OpCheck.ok(f"smoothed {len(log.changes)} of {len(region)} vertices"))

    def _whole_mesh(self, operation: str) -> OpCheck:
        """Upsample, downsample or remesh: a new mesh, kept whole for undo."""
        mesh = self.mesh
        if operation == "upsample" and 4 * mesh.n_faces > MAX_UPSAMPLED_FACES:
            return self._refuse(operation, OpCheck.refuse(
                "size", f"it would make {4 * mesh.n_faces} faces, more than the editor's {MAX_UPSAMPLED_FACES}"))
        run = {"upsample": lambda: loop_subdivide(mesh),
               "downsample": lambda: simplify(mesh, max(mesh.n_faces // 4, 4)),
               "remesh": lambda: remesh(mesh)}[operation]
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                new = run()
        except ValueError as error:
            return self._refuse(operation, OpCheck.refuse("mesh", str(error)))
        self._history.append((mesh, self._selection))
        del self._history[:-self._undo_limit]
        kind, index = self._selection
        self._mesh = new
        self._selection = (kind, index if _is_live(new, kind, index) else _first_live(new, kind))
        self._last_log, self._last_check = None, None
        self._last_text = f"{operation}: {mesh.n_faces} -> {new.n_faces} faces"
        self._validity = self._validity_of(new)
        notes = "".join(f"; {w.message}" for w in caught)
        self._say(f"{self._last_text}; {self._validity}{notes}", error=self._validity != "valid")
        self._draw(rebuild=True)
        return OpCheck.ok(self._last_text)

    def _commit(self, log: OperationLog, edit: Callable, check: OpCheck | None = None) -> OpCheck:
        """Keep a copy for undo, run ``edit(mesh)`` (which fills ``log`` and may return the
        new selection), validate, redraw."""
        mesh = self.mesh
        self._history.append((mesh.copy(), self._selection))
        del self._history[:-self._undo_limit]
        selection = edit(mesh)
        if selection is not None:
            self._selection = selection
        self._last_log, self._last_check = log, check
        self._last_text = self._edit_text(log)
        self._validity = self._validity_of(mesh)
        self._say(f"{self._last_text}: {len(log.changes)} changes; {self._validity}",
                  error=self._validity != "valid")
        self._draw(rebuild=True)
        return check if check is not None else OpCheck.ok(self._last_text)

    def _refuse(self, operation: str, check: OpCheck) -> OpCheck:
        self._last_check, self._last_text = check, f"{operation} of {self._selection_text()}"
        self._say(f"{operation} refused: {check.reason}", color=VERMILLION)
        self._draw()
        return check

    def _draw(self, rebuild: bool = False) -> None:
        """Show the current state (after ``held()`` ends, if held); ``rebuild``: the mesh changed."""
        self._stale |= rebuild
        if self._held:
            return
        if self._stale:
            self.scene.clear()            # the old highlight may name elements the new mesh lacks
            self.scene.mesh = self._mesh.copy()
            self.scene.refresh()
            self._stale = False
        self._changed()

    # -- state in words --------------------------------------------------------------------

    def _edit_text(self, log: OperationLog) -> str:
        if log.operation in ("flip", "split", "collapse"):
            return f"{log.operation} of edge {log.edge} (from halfedge {log.halfedge})"
        if log.operation == "move":
            return log.notes[0]
        return "smooth of " + self._selection_text()

    def _selection_text(self) -> str:
        kind, index = self._selection
        mesh = self.mesh
        if kind == "edge":
            a, b = mesh.edge(index).vertices
            return f"edge {index} (vertices {a.index} - {b.index})"
        if kind == "halfedge":
            h = mesh.halfedge(index)
            return f"halfedge {index} ({h.vertex.index} -> {h.tip.index})"
        if kind == "face":
            return f"face {index} (vertices {', '.join(str(v.index) for v in mesh.face(index).vertices())})"
        position = ", ".join(f"{c:.4g}" for c in mesh.positions[index])
        return f"vertex {index} at ({position})"

    @staticmethod
    def _validity_of(mesh) -> str:
        try:
            mesh.validate()
        except MeshInvariantError as error:
            return f"NOT valid: {error}"
        return "valid"

    @staticmethod
    def _checked_selection(mesh, kind: str, index: int) -> tuple[str, int]:
        if kind not in KINDS:
            raise ValueError(f"unknown kind {kind!r}: use one of {', '.join(KINDS)}")
        return kind, getattr(mesh, kind)(int(index)).index

    # -- the widget ------------------------------------------------------------------------

    def _show(self) -> None:
        mesh = self.mesh
        kind, index = self._selection
        roles: dict[str, list[int]] = {}
        if kind == "vertex":
            vertex = mesh.vertex(index)
            roles = {"center": [index], "neighbor": [v.index for v in vertex.neighbors()],
                     "ring_face": [f.index for f in vertex.faces()]}
        elif kind in ("edge", "halfedge"):
            h = 2 * index if kind == "edge" else index
            faces = [int(f) for f in mesh.halfedge_face[[h, h ^ 1]] if f >= 0]
            roles = {"current": [h], "twin": [h ^ 1], "origin": [int(mesh.halfedge_vertex[h])],
                     "tip": [int(mesh.halfedge_vertex[h ^ 1])], "face": faces}
        else:
            roles = {"face": [index], "next": [h.index for h in mesh.face(index).halfedges()]}
        if self._last_check is not None and not self._last_check:
            roles["refused_vertex"] = [i for k, i in self._last_check.elements if k == "vertex"]
            roles["refused"] = [2 * i for k, i in self._last_check.elements if k == "edge"]
        elif self._last_log is not None:
            for change in self._last_log.changes:
                if change.kind in _CHANGED_ROLE and _is_live(mesh, change.kind, change.index):
                    roles.setdefault(_CHANGED_ROLE[change.kind], []).append(change.index)
        self.scene.set_roles(roles)
        if self.mode == "live":
            self._place_handle()

    def _place_handle(self) -> None:
        """Live view: a ball on the selected vertex; dragging it moves the vertex.

        The ball of the same vertex is moved, not made anew: a drag's callback redraws,
        and deleting the VTK widget inside its own callback kills the kernel.
        """
        plotter = self.scene.plotter
        kind, index = self._selection
        if self._handle is not None and (kind, index) == ("vertex", self._handle[0]):
            self._handle[1].SetCenter(*(float(c) for c in self.mesh.positions[index]))
            return
        plotter.clear_sphere_widgets()
        self._handle = None
        if kind != "vertex":
            return
        low, high = _slider_range(self.mesh)
        ball = plotter.add_sphere_widget(lambda centre: call_on_main_thread(self._dragged, index, centre),
                                         center=tuple(self.mesh.positions[index]),
                                         radius=float((high - low).max()) / 40, color=HANDLE_COLOUR,
                                         selected_color=HANDLE_COLOUR, test_callback=False,
                                         interaction_event="end")
        self._handle = (index, ball)

    def _dragged(self, vertex: int, centre) -> None:
        if self._selection == ("vertex", vertex) and not np.allclose(centre, self.mesh.positions[vertex]):
            self._guarded(self.move_vertex, vertex, centre)

    def _controls(self) -> list:
        import ipywidgets as widgets

        css = panel_css(self.look)
        kind, index = self._selection
        self._kind_box = widgets.Dropdown(options=KINDS, value=kind, description="select",
                                          layout=widgets.Layout(width=f"calc({css['button_width']} * 1.6)"))
        self._kind_box.style.description_width = "auto"
        self._index_box = self._number_box(index, "index")
        self._hint = widgets.HTML()
        self._kind_box.observe(lambda change: self._show_hint(change["new"]), names="value")
        self._show_hint(kind)
        self.buttons = {}
        choose = widgets.HBox([self._kind_box, self._index_box.widget,
                               self._later_button("select", "select this element",
                                                  lambda: self.select(self._kind_box.value, self._index_box.value))],
                              layout=widgets.Layout(flex_flow="row wrap"))
        key_of = {name: key for key, name in KEYS.items()}
        edits, whole = (widgets.HBox([self._later_button(name, f"key {key_of[name]}: {name} {what}",
                                                         lambda name=name: self.apply(name))
                                      for name in names], layout=widgets.Layout(flex_flow="row wrap"))
                        for names, what in ((OPERATIONS[:4], "the selection"), (WHOLE_MESH, "the whole mesh")))
        whole.children += (self._later_button("info", "key i: the selected element's pointers", self.info),)
        for button in whole.children[:-1]:                   # "downsample" is a longer word
            button.layout.width = f"calc({css['button_width']} * 1.4)"
        self._keys = widgets.Text(value="", placeholder="click, type " + " ".join(KEYS),
                                  description="keys", continuous_update=True,
                                  layout=widgets.Layout(width=f"calc({css['button_width']} * 2.6)"))
        self._keys.style.description_width = "auto"
        self._keys_seen = ""
        self._keys.observe(self._typed, names="value")
        undo = widgets.HBox([self._later_button("undo", "key z: back to before the last edit", self.undo), self._keys],
                            layout=widgets.Layout(flex_flow="row wrap"))
        self._sliders = [widgets.FloatSlider(description=axis, continuous_update=False, readout_format=".3f",
                                             layout=widgets.Layout(width=f"calc({css['button_width']} * 3.5)"))
                         for axis in "xyz"]
        for slider in self._sliders:
            slider.observe(self._slid, names="value")
        self._sync_controls()
        return [choose, self._hint, edits, whole, undo, widgets.VBox(self._sliders)]

    def _show_hint(self, kind: str) -> None:
        """Say how to select a ``kind`` here (only a widget value: safe on any thread)."""
        size = panel_css(self.look)["font"]
        a = "an" if kind == "edge" else "a"
        how = (f"right-click the view to pick {a} {kind}, or type its index" if self.mode == "live"
               else f"type {a} {kind} index and press select")
        self._hint.value = f'<span style="font-size:{size};color:#555">{html.escape(how)}</span>'


    def _later_button(self, label: str, tooltip: str, action: Callable[[], object]):
        """A panel button whose action runs on the main thread; errors go to the status line."""
        import ipywidgets as widgets

        css = panel_css(self.look)
        button = widgets.Button(description=label, tooltip=tooltip,
                                layout=widgets.Layout(height=css["button_height"], width=css["button_width"]))
        button.style.font_size = css["font"]
        button.style.font_weight = "bold"
        button.on_click(lambda _: call_on_main_thread(self._guarded, action))
        self.buttons[label] = button
        return button

    def _guarded(self, action: Callable[[], object], *args) -> None:
        try:
            action(*args)
        except (IndexError, ValueError) as error:
            self._say(str(error), error=True)

    def _typed(self, change) -> None:
        """The keys box's text arrived: the characters after the part it shares with the
        text seen last are the keys typed since, each one edit.

        Only the browser writes the box. (Clearing it from here raced the next key: the
        browser sent "ll" before the "" arrived, and three l made four edits.) A fast
        typist's keys may come several at once; deleting or a key the editor does not
        use does nothing.
        """
        text, seen = change["new"], self._keys_seen
        self._keys_seen = text
        shared = 0
        while shared < min(len(text), len(seen)) and text[shared] == seen[shared]:
            shared += 1
        for key in text[shared:].lower():
            if key in KEYS:
                call_on_main_thread(self._guarded, self.key, key)

    def _slid(self, change) -> None:
        if self._syncing or self._selection[0] != "vertex":
            return
        position = [slider.value for slider in self._sliders]
        v = self._selection[1]
        if np.allclose(position, self.mesh.positions[v]):
            return
        call_on_main_thread(self._guarded, self.move_vertex, v, position)

    def _picked(self, point) -> None:
        """A right-click in the live view: the element of the kind chosen in the dropdown."""
        self._guarded(self.pick_at, point, self._kind_box.value)

    def _sync_controls(self) -> None:
        """Bring the index box, kind and sliders to the selection, without editing."""
        if not hasattr(self, "_sliders"):
            return
        kind, index = self._selection
        self._syncing = True
        try:
            self._kind_box.value = kind
            self._index_box.value = index
            low, high = _slider_range(self.mesh)
            is_vertex = kind == "vertex"
            for axis, slider in enumerate(self._sliders):
                if low[axis] > slider.max:                   # min must stay below max at every step
                    slider.max, slider.min = float(high[axis]), float(low[axis])
                else:
                    slider.min, slider.max = float(low[axis]), float(high[axis])
                slider.step = float(high[axis] - low[axis]) / 200
                if is_vertex:
                    slider.value = float(self.mesh.positions[index, axis])
                slider.disabled = not is_vertex
        finally:
            self._syncing = False

    def _panel_html(self) -> str:
        self._sync_controls()
        size = panel_css(self.look)["font"]
        mesh = self.mesh
        colour = "#1B5E20" if self.valid else "#B00020"
        parts = [f'<div style="font-size:{size};margin:4px 0">{mesh.n_vertices} vertices, {mesh.n_edges} edges, '
                 f'{mesh.n_faces} faces: <b style="color:{colour}">{html.escape(self._validity)}</b><br>'
                 f"selected: <b>{html.escape(self._selection_text())}</b>; undo: {len(self._history)}</div>"]
        if self._last_check is not None and not self._last_check:
            parts.append(f'<div style="font-size:{size};color:{VERMILLION}">refused: {html.escape(self._last_text)}: '
                         f"{html.escape(self._last_check.reason)}</div>")
        elif self._last_log is not None:
            changes = self._last_log.changes
            rows = [([f"{c.kind} {c.index}", c.field, _shown(c.old), _shown(c.new)], _CHANGED_ROLE.get(c.kind))
                    for c in changes[:PANEL_DIFF_ROWS]]
            more = (f'<div style="font-size:{size}">... and {len(changes) - PANEL_DIFF_ROWS} more '
                    f"(describe() lists them all)</div>" if len(changes) > PANEL_DIFF_ROWS else "")
            parts.append(f'<div style="font-size:{size};margin-top:6px"><b>pointer diff</b>: '
                         f"{html.escape(self._last_text)}, {len(changes)} changes</div>"
                         + table_html(rows, self.look, header=("element", "field", "old", "new")) + more)
        return "".join(parts)


# -- geometry helpers ------------------------------------------------------------------------


def _as_tuple(position) -> tuple[float, float, float]:
    return tuple(float(c) for c in position)


def _shown(value) -> str:
    if isinstance(value, tuple):
        return "(" + ", ".join(f"{c:.4g}" for c in value) + ")"
    return str(value)


def _first_live(mesh, kind: str) -> int:
    deleted = {"vertex": mesh.vertex_deleted, "face": mesh.face_deleted, "edge": mesh.edge_deleted,
               "halfedge": mesh.halfedge_deleted}[kind]
    return int(np.flatnonzero(~deleted)[0])


def _pointers_text(mesh, kind: str, index: int) -> str:
    """What the key i says: the element and the pointers stored for it."""
    if kind == "vertex":
        v = mesh.vertex(index)
        h = v.halfedge
        return (f"vertex {index}: halfedge {h.index if h is not None else None}, degree {v.degree}, "
                f"{'on the boundary' if v.is_boundary else 'interior'}")
    if kind == "edge":
        e = mesh.edge(index)
        a, b = e.vertices
        faces = ", ".join(str(f.index) for f in e.faces()) or "none"
        return (f"edge {index}: halfedges {2 * index} and {2 * index + 1}, vertices {a.index} - {b.index}, "
                f"faces {faces}, length {e.length:.4g}")
    if kind == "halfedge":
        h = mesh.halfedge(index)
        face = h.face.index if h.face is not None else "none (boundary)"
        return (f"halfedge {index}: vertex {h.vertex.index}, tip {h.tip.index}, next {h.next.index}, "
                f"prev {h.prev.index}, twin {h.twin.index}, face {face}, edge {h.edge.index}")
    f = mesh.face(index)
    return (f"face {index}: halfedge {f.halfedge.index}, vertices {', '.join(str(v.index) for v in f.vertices())}, "
            f"area {f.area:.4g}")


def _is_live(mesh, kind: str, index: int) -> bool:
    if kind == "vertex":
        return index < mesh.n_vertex_slots and not mesh.vertex_deleted[index]
    if kind == "face":
        return index < mesh.n_face_slots and not mesh.face_deleted[index]
    return index < mesh.n_halfedge_slots and not mesh.edge_deleted[index >> 1]


def _selection_vertices(mesh, kind: str, index: int) -> list[int]:
    """The vertices of the selected element."""
    if kind == "vertex":
        return [index]
    if kind == "face":
        return [v.index for v in mesh.face(index).vertices()]
    h = 2 * index if kind == "edge" else index
    return [int(mesh.halfedge_vertex[h]), int(mesh.halfedge_vertex[h ^ 1])]


def _with_neighbours(mesh, vertices: list[int]) -> list[int]:
    """``vertices`` and their neighbours, sorted."""
    found = set(vertices)
    for v in vertices:
        found |= {u.index for u in mesh.vertex(v).neighbors()}
    return sorted(found)


def _slider_range(mesh) -> tuple[np.ndarray, np.ndarray]:
    """(3,), (3,): the live vertices' bounding box, grown by half its largest side."""
    points = mesh.positions[~mesh.vertex_deleted]                       # (V, 3)
    low, high = points.min(axis=0), points.max(axis=0)
    margin = 0.5 * max(float((high - low).max()), 1e-6)
    return low - margin, high + margin


def _nearest(mesh, kind: str, point: np.ndarray) -> int:
    """The live element of ``kind`` nearest to ``point`` (a face: by its centroid; a
    halfedge: of the nearest edge, the one whose face's centroid is nearer)."""
    positions = mesh.positions
    if kind == "vertex":
        live = np.flatnonzero(~mesh.vertex_deleted)
        return int(live[np.argmin(np.linalg.norm(positions[live] - point, axis=1))])
    if kind == "face":
        live = np.flatnonzero(~mesh.face_deleted)
        centroids = positions[mesh.face_vertices()[live]].mean(axis=1)   # (F, 3)
        return int(live[np.argmin(np.linalg.norm(centroids - point, axis=1))])
    live = np.flatnonzero(~mesh.edge_deleted)
    ends = mesh.edge_vertices()[live]                                    # (E, 2)
    a, b = positions[ends[:, 0]], positions[ends[:, 1]]
    along = np.einsum("ij,ij->i", point - a, b - a) / np.maximum(np.einsum("ij,ij->i", b - a, b - a), 1e-300)
    closest = a + np.clip(along, 0.0, 1.0)[:, None] * (b - a)            # (E, 3)
    e = int(live[np.argmin(np.linalg.norm(closest - point, axis=1))])
    if kind == "edge":
        return e
    sides = []
    for h in (2 * e, 2 * e + 1):
        f = int(mesh.halfedge_face[h])
        if f < 0:
            sides.append(np.inf)
        else:
            sides.append(float(np.linalg.norm(positions[mesh.face_vertices()[f]].mean(axis=0) - point)))
    return 2 * e + int(np.argmin(sides))
