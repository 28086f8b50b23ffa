"""Step through a local operation one pointer change at a time: flip, split, collapse.

    from halfedge_edu.viz import CollapseStepper
    w = CollapseStepper(hx.sample("cube"), 0)
    w                     # step 0: the elements the collapse gathers, with the course's names
    w.step()              # the first change highlighted and listed, old -> new
    w.go("phase")         # to the start of the next phase; also "start", "end", "back", 5
    print(w.describe())

How it works: the stepper copies the mesh, runs the real operation on the copy with an
:class:`~halfedge_edu.core.ops.log.OperationLog`, and keeps the mesh as it was before. Step
``k`` shows "before, plus the first k changes applied" (``log.replay``), so going back
is as cheap as going forward and the pictures can never disagree with the operation.
A change that creates an element is shown together with the lines that fill in its
first pointers (``-1 -> ...``). In between, a face whose ``next`` loop is no longer a
triangle is drawn in a "rewiring" colour, and an arrow sits in the face it belongs to
before or after the operation, whichever matches its current ends.

The mesh passed in is never changed; ``w.result`` is the mesh after the operation.
An operation that is refused shows the edge and the reason instead of steps.
"""

from __future__ import annotations

import html
from collections import defaultdict

import numpy as np

from ..core.elements import Halfedge
from .keys import KeyArea
from .neighbourhood import ring_window
from .palette import panel_css, preset as _preset
from .pictures import grid_png, legend_png
from .screen import unit
from .scene import MAX_ARROWS, HalfedgeScene
from .widgets import StepperWidget, legend_html, panel_button, table_html

# Stepper roles by the kind of element they colour.
_CHANGED = {"halfedge": "changed", "vertex": "changed_vertex", "face": "changed_face"}
_OLD = {"halfedge": "old_target", "vertex": "old_vertex", "face": "old_face"}
_NEW = {"halfedge": "new_target", "vertex": "new_vertex", "face": "new_face"}
_DOOMED = {"halfedge": "doomed", "vertex": "doomed_vertex", "face": "doomed_face"}
_CREATED = {"halfedge": "created", "vertex": "created_vertex", "face": "created_face"}
_NAMED = {"halfedge": "named", "vertex": "named_vertex", "face": "named_face"}
# The kind of element a pointer field holds.
_TARGET = {("halfedge", "next"): "halfedge", ("halfedge", "prev"): "halfedge",
           ("halfedge", "vertex"): "vertex", ("halfedge", "face"): "face",
           ("vertex", "halfedge"): "halfedge", ("face", "halfedge"): "halfedge"}


def group_changes(changes) -> list[tuple[int, int]]:
    """Cut a log's changes into steps: ``[(start, stop), ...]`` ranges of ``changes``.

    Every change is its own step, except that creating an element takes along the
    changes right after it that fill in that element's first values (``-1 -> x``,
    ``None -> position``), and deleting an edge takes along its two halfedges.
    """
    groups, i, n = [], 0, len(changes)
    while i < n:
        change, j = changes[i], i + 1
        if change.field in ("created", "deleted"):
            family = {(change.kind, change.index)}
            if change.kind == "edge":
                family |= {("halfedge", 2 * change.index), ("halfedge", 2 * change.index + 1)}
            while j < n and (changes[j].kind, changes[j].index) in family and (
                changes[j].field == change.field
                or (change.field == "created" and changes[j].old in (-1, None))
            ):
                j += 1
        groups.append((i, j))
        i = j
    return groups


def _padded(array: np.ndarray, length: int, fill) -> np.ndarray:
    out = np.full((length,) + array.shape[1:], fill, dtype=array.dtype)
    out[: len(array)] = array
    return out


class OperationStepper(StepperWidget):
    """Shared machinery of the flip, split and collapse steppers (use those).

    Args:
        mesh: the mesh; it is copied, never changed.
        edge: an edge index, an :class:`Edge`, or (collapse) a :class:`Halfedge`
            whose origin is removed.
        position: for split and collapse, where the new or merged vertex goes
            (the midpoint by default).
        mode, preset, rings, window_size: as for every widget.

    Keys (mouse pointer over the panel below the buttons): → or space the next change,
    ← one back, PgDn the next phase, Home the start, End the end.
    """

    operation = ""
    KEYS = {**StepperWidget.KEYS, "PageDown": "phase"}

    def __init__(self, mesh, edge, *, position=None, mode: str | None = None, preset="default",
                 rings: int = 2, window_size=None):
        from ..core.ops.log import OperationLog

        self.before = mesh.copy()
        self.after = mesh.copy()
        argument = self.after.halfedge(edge.index) if isinstance(edge, Halfedge) else int(edge)
        self.check = self._can(self.after, argument)
        self.log = OperationLog()
        if self.check:
            self._run(self.after, argument, position, self.log)
        self.groups = group_changes(self.log.changes)
        self._step = 0
        self._names = self._element_names()
        self._shown = (None, 0)              # the state shown last and its count of changes
        super().__init__(self.before.copy(), mode=mode, preset=preset, labels=None, rings=rings,
                         window_size=window_size)

    # -- what subclasses provide ---------------------------------------------------------

    def _can(self, mesh, edge):
        raise NotImplementedError

    def _run(self, mesh, edge, position, log) -> None:
        raise NotImplementedError

    # -- public --------------------------------------------------------------------------

    @property
    def n_steps(self) -> int:
        """How many steps after step 0 (the gathered elements)."""
        return len(self.groups)

    @property
    def result(self):
        """A copy of the mesh after the operation (the mesh as it was, if refused)."""
        return self.after.copy()

    @property
    def state(self):
        """The mesh as it is at the current step (usually not valid half way)."""
        return self.scene.mesh

    def _named_moves(self) -> dict[str, int]:
        """Also "phase" (the start of the next phase) and "phase back"."""
        return {**super()._named_moves(), **self._phase_moves(self._phase_steps())}

    # -- the scene -----------------------------------------------------------------------

    def _element_names(self) -> dict[tuple[str, int], str]:
        found: dict[tuple[str, int], list[str]] = defaultdict(list)
        for name, (kind, index) in self.log.named.items():
            found[(kind, index)].append(name)
        return {key: "/".join(names) for key, names in found.items()}

    def _touched_faces(self) -> np.ndarray:
        faces = {index for kind, index in self.log.named.values() if kind == "face"}
        faces |= {index for kind, index in self.log.created + self.log.deleted if kind == "face"}
        n_before = self.before.n_halfedge_slots
        for change in self.log.changes:
            if change.kind == "face":
                faces.add(change.index)
            elif change.kind == "vertex" and change.field == "position":
                # A vertex that moves drags every face around it along.
                for mesh in (self.before, self.after):
                    if change.index < mesh.n_vertex_slots and not mesh.vertex_deleted[change.index]:
                        faces |= {f.index for f in mesh.vertex(change.index).faces()}
            elif change.kind == "halfedge":
                if change.field == "face":
                    faces |= {f for f in (change.old, change.new) if f >= 0}
                if change.index < n_before:
                    faces.add(int(self.before.halfedge_face[change.index]))
        if not self.check:
            for kind, index in self.check.elements:
                if kind == "edge":
                    faces |= {int(self.before.halfedge_face[h]) for h in (2 * index, 2 * index + 1)}
        faces.discard(-1)
        return np.array(sorted(faces), dtype=np.int64)

    def _operation_vertices(self) -> np.ndarray:
        vertices = {index for kind, index in self.log.named.values() if kind == "vertex"}
        for kind, index in self.check.elements:
            if kind == "vertex":
                vertices.add(index)
            elif kind == "edge":
                vertices |= {int(self.before.halfedge_vertex[2 * index]), int(self.before.halfedge_vertex[2 * index + 1])}
        vertices = {v for v in vertices if v < self.before.n_vertex_slots}
        return np.array(sorted(vertices), dtype=np.int64)

    def _prepare_references(self) -> None:
        """Before and after arrays padded to the same length, for placing arrows."""
        n = self.after.n_halfedge_slots
        self._reference = []
        for mesh in (self.after, self.before):
            self._reference.append((
                _padded(mesh.halfedge_vertex, n, -1),
                _padded(mesh.halfedge_prev, n, -1),
                _padded(mesh.halfedge_face, n, -1),
                _padded(~mesh.halfedge_deleted, n, False),
            ))
        self._after_next = _padded(self.after.halfedge_next, n, -1)
        n_faces = self.after.n_face_slots
        self._reference_faces = [
            (_padded(mesh.face_vertices(), n_faces, -1), _padded(~mesh.face_deleted, n_faces, False))
            for mesh in (self.after, self.before)
        ]

    def _arrow_corners(self, mesh, halfedges):
        """Arrow ends from the current state; the side it sits on from before or after.

        An arrow moves into its place after the operation once all its pointers
        (ends, next, prev, face) have their final values; until then it stays where it
        was before, as long as its ends are still those of before; in between (its ends
        changed, its links not yet), it sits in its place after the operation.
        """
        halfedges = np.asarray(halfedges, dtype=np.int64)
        origin = mesh.halfedge_vertex[halfedges]
        tip = mesh.halfedge_vertex[halfedges ^ 1]
        (a_origin, a_prev, a_face, a_live), (b_origin, b_prev, b_face, b_live) = self._reference
        after_match = (a_live[halfedges] & (a_origin[halfedges] == origin) & (a_origin[halfedges ^ 1] == tip)
                       & (a_prev[halfedges] == mesh.halfedge_prev[halfedges])
                       & (self._after_next[halfedges] == mesh.halfedge_next[halfedges])
                       & (a_face[halfedges] == mesh.halfedge_face[halfedges]))
        before_match = b_live[halfedges] & (b_origin[halfedges] == origin) & (b_origin[halfedges ^ 1] == tip)
        n_vertices = mesh.n_vertex_slots

        def opposite_in(origin_of, prev_of, face_of):
            face = face_of[halfedges]
            side = np.where(face < 0, halfedges ^ 1, halfedges)
            opposite = origin_of[np.maximum(prev_of[side], 0)]
            return face, np.where((opposite >= 0) & (opposite < n_vertices), opposite, -1)

        after_face, after_opposite = opposite_in(a_origin, a_prev, a_face)
        before_face, before_opposite = opposite_in(b_origin, b_prev, b_face)
        use_after = after_match | (~before_match & a_live[halfedges])
        use_after &= (after_opposite >= 0) | (before_opposite < 0)
        face = np.where(use_after, after_face, before_face)
        opposite = np.where(use_after, after_opposite, before_opposite)
        positions = mesh.positions
        A, B = positions[origin], positions[tip]
        third = np.where((opposite < 0)[:, None], A, positions[np.maximum(opposite, 0)])
        third = np.where(((face < 0) & (opposite >= 0))[:, None], A + B - third, third)
        # Half way through its change an arrow may get the same ends and side as another
        # one (the flip's h0 lies on h5 at step 1) and hide under it: the one half way
        # through is drawn further inside its face, so the change stays in sight. Its
        # whole triangle slides toward the third corner (across the edge, not along it),
        # so the arrow keeps its length and its head.
        between = ~after_match & ~before_match
        key = np.stack([origin, tip, opposite], axis=1)                   # (k, 3)
        # Only the few arrows half way through are compared with every arrow (a row
        # matches itself, so "hidden" is a second match).
        hidden = np.zeros((len(halfedges), 1), dtype=bool)
        changing = np.flatnonzero(between & (opposite >= 0))
        if len(changing):
            same = (key[changing][:, None, :] == key[None, :, :]).all(axis=2)   # (c, k)
            hidden[changing, 0] = same.sum(axis=1) > 1
        along = unit(B - A)                                                # (k, 3)
        across = (third - A) - ((third - A) * along).sum(axis=1)[:, None] * along
        shift = np.where(hidden, OVERLAP_INSET * across, 0.0)              # (k, 3)
        return A + shift, B + shift, third + shift

    def _face_corners(self, faces):
        """Corners for faces that are half rewired: their triangle after, else before."""
        (a_corners, a_live), (b_corners, b_live) = self._reference_faces
        faces = np.asarray(faces, dtype=np.int64)
        inside = faces < len(a_live)
        use_after = np.zeros(len(faces), dtype=bool)
        use_after[inside] = a_live[faces[inside]]
        corners = np.full((len(faces), 3), -1, dtype=np.int64)
        corners[use_after] = a_corners[faces[use_after]]
        from_before = ~use_after & (faces < len(b_live))
        from_before[from_before] &= b_live[faces[from_before]]
        corners[from_before] = b_corners[faces[from_before]]
        return corners

    def _make_scene(self, mesh, **options) -> HalfedgeScene:
        """A scene of the mesh before, with the operation's faces kept apart."""
        self._prepare_references()
        vertices = self._operation_vertices()
        window = None
        if self.before.n_halfedges > MAX_ARROWS and len(vertices):
            # A large mesh: the arrows around the operation, and every halfedge it creates.
            _, around = ring_window(self.before, vertices, options["rings"])
            created = np.arange(self.before.n_halfedge_slots, self.after.n_halfedge_slots)
            window = np.unique(np.concatenate([around, created]))
        scene = HalfedgeScene(mesh, preset=self.look, follow=False, local_faces=self._touched_faces(),
                              corners=self._arrow_corners, face_corners=self._face_corners, window=window,
                              **options)
        if not self.check:
            # Face the refused edge itself; the other elements of the reason are lit up.
            edge = self._edge_index()
            if edge >= 0:
                vertices = np.array([self.before.halfedge_vertex[2 * edge], self.before.halfedge_vertex[2 * edge + 1]])
        if len(vertices):
            scene.look_at(vertices)
        return scene

    def _show(self) -> None:
        stop = self.groups[self._step - 1][1] if self._step else 0
        self.scene.set_mesh(self._state_after(stop), self._roles(), names=self._names)

    def _state_after(self, stop: int):
        """A new mesh: the mesh before the operation with its first ``stop`` changes applied.

        Replaying from the start copies the mesh before and grows every array an element
        is created in (about 3 ms on the bunny). From the state shown last it is cheaper:
        a step forward copies that state (with the room its arrays have grown) and applies
        only the changes since; a step back writes the old values of the changes in
        between, newest first, unless one of them created or deleted an element (an
        index cannot be taken back: then it replays from the start).
        """
        shown, shown_stop = self._shown
        if shown is None or (stop < shown_stop and not self.log.can_take_back(stop, shown_stop)):
            state = self.before.copy()
            self.log.replay(state, stop)
        elif stop >= shown_stop:
            state = shown.copy()
            self.log.replay(state, stop, start=shown_stop)
        else:
            state = shown.copy()
            self.log.take_back(state, stop, shown_stop)
        self._shown = (state, stop)
        return state

    def _roles(self) -> dict[str, list[int]]:
        roles: dict[str, list[int]] = defaultdict(list)

        def add(table, kind, index):
            if kind == "edge":
                roles[table["halfedge"]] += [2 * index, 2 * index + 1]
            elif index is not None and index >= 0:
                roles[table[kind]].append(int(index))

        if not self.check:
            for kind, index in self.check.elements:
                if kind == "edge":
                    roles["refused"] += [2 * index, 2 * index + 1]
                elif kind == "vertex":
                    roles["refused_vertex"].append(index)
            return dict(roles)
        done = self.groups[self._step - 1][1] if self._step else 0
        for position, change in enumerate(self.log.changes):
            if change.field == "created" and position < done:
                add(_CREATED, change.kind, change.index)
            elif change.field == "deleted" and position >= done:
                add(_DOOMED, change.kind, change.index)
        if self._step == 0:
            for kind, index in self.log.named.values():
                add(_NAMED, kind, index)
            return dict(roles)
        start, stop = self.groups[self._step - 1]
        for change in self.log.changes[start:stop]:
            if change.field in ("created", "deleted"):
                continue
            add(_CHANGED, change.kind, change.index)
            target = _TARGET.get((change.kind, change.field))
            if target is not None:
                add(_OLD, target, change.old)
                add(_NEW, target, change.new)
        return dict(roles)

    # -- text ----------------------------------------------------------------------------

    def _phase_steps(self) -> list[int]:
        """The step numbers at which a phase starts."""
        starts = []
        for position, _title in self.log.phases:
            for k, (start, stop) in enumerate(self.groups, start=1):
                if start <= position < stop:
                    starts.append(k)
                    break
        return sorted(set(starts))

    def _phase_title(self) -> str:
        if self._step == 0:
            return "gather the elements"
        start = self.groups[self._step - 1][0]
        title = ""
        for position, phase in self.log.phases:
            if position <= start:
                title = phase
        return title

    def _value(self, kind: str | None, value) -> str:
        """A pointer value with the operation's name for it, e.g. ``16 (h2)``."""
        if kind is None or not isinstance(value, (int, np.integer)) or value < 0:
            if isinstance(value, tuple):
                return "(" + ", ".join(f"{float(c):.4g}" for c in value) + ")"
            return str(value)
        name = self._names.get((kind, int(value)))
        return f"{value} ({name})" if name else str(value)

    def _change_text(self, change) -> str:
        target = _TARGET.get((change.kind, change.field))
        element = self._value(change.kind, change.index)
        if change.field == "created":
            return f"create {change.kind} {element}"
        if change.field == "deleted":
            return f"delete {change.kind} {element}"
        return (f"{change.kind} {element} .{change.field}: "
                f"{self._value(target, change.old)} -> {self._value(target, change.new)}")

    def _group_text(self, k: int) -> list[str]:
        start, stop = self.groups[k - 1]
        return [self._change_text(change) for change in self.log.changes[start:stop]]

    def _counts(self, mesh) -> str:
        return f"{mesh.n_vertices} vertices, {mesh.n_edges} edges, {mesh.n_faces} faces"

    def _heading(self) -> str:
        return f"{self.operation} of edge {self.log.edge if self.check else self._edge_index()}"

    def _edge_index(self) -> int:
        for kind, index in self.check.elements:
            if kind == "edge":
                return index
        return -1

    def describe(self) -> str:
        if not self.check:
            return f"{self._heading()}: refused ({self.check.rule})\nreason: {self.check.reason}"
        lines = [f"{self._heading()}: step {self._step} of {self.n_steps} ({self._phase_title()})"]
        if self._step == 0:
            lines.append("gathered: " + ", ".join(f"{name} = {kind} {index}"
                                                  for name, (kind, index) in self.log.named.items()))
            lines += self.log.notes
        else:
            lines += [f"now: {text}" for text in self._group_text(self._step)]
        state = self.scene.mesh if hasattr(self, "scene") else self.before
        lines.append(f"mesh: {self._counts(state)}")
        return "\n".join(lines)

    # -- panel ---------------------------------------------------------------------------

    @property
    def title(self) -> str:  # type: ignore[override]
        return f"Edge {self.operation}: step by step"

    def _controls(self) -> list:
        if not self.check:
            self.buttons = {}
            return []
        return self._button_row([
            ("start", "back to the gathered elements", lambda: self.go("start")),
            ("back", "one change back", self.back),
            ("step", "apply the next change", self.step),
            ("phase", "to the start of the next phase", lambda: self.go("phase")),
            ("end", "all changes applied", lambda: self.go("end")),
        ])

    def _panel_html(self) -> str:
        css = panel_css(self.look)
        size = css["font"]
        if not self.check:
            return (f'<div style="font-size:{size}"><b>{html.escape(self._heading())}: refused</b> '
                    f'(<code>{html.escape(str(self.check.rule))}</code>)<br>{html.escape(self.check.reason)}</div>')
        top = (f'<div style="font-size:{size};margin:4px 0"><b>{html.escape(self._heading())}</b>: step '
               f"{self._step} of {self.n_steps}<br><i>{html.escape(self._phase_title())}</i></div>")
        if self._step == 0:
            rows = [([name, f"{kind} {index}"], _NAMED[kind] if kind in _NAMED else None)
                    for name, (kind, index) in self.log.named.items()]
            rows += [(["", ""], None)] * (self._window_rows() - len(rows) - len(self.log.notes))
            notes = "".join(f'<div style="font-size:{size}">{html.escape(n)}</div>' for n in self.log.notes)
            body = notes + table_html(rows, self.look, header=("name", "element"))
        else:
            rows, mark = [], None
            current = self.groups[self._step - 1]
            for k, (start, stop) in enumerate(self.groups, start=1):
                for position in range(start, stop):
                    change = self.log.changes[position]
                    role = _CHANGED.get(change.kind) if k == self._step else None
                    text = self._change_text(change)
                    if k > self._step:
                        text = "  " + text
                    rows.append(([k, text], role))
                    if (start, stop) == current and mark is None:
                        mark = len(rows) - 1
            body = self._table_window(rows, mark, size)
        counts = (f'<div style="font-size:{size};margin-top:6px">before: {self._counts(self.before)}<br>'
                  f"now: {self._counts(self.scene.mesh)}<br>after: {self._counts(self.after)}</div>")
        return top + body + counts


    def _window_rows(self) -> int:
        """How many rows the panel's table shows at every step: enough for the named
        elements at step 0, and for a window of the change table later. One number for
        all steps keeps the panel's height from jumping as the learner steps."""
        return max(TABLE_WINDOW, len(self.log.named) + len(self.log.notes))

    def _table_window(self, rows, mark: int, size: str) -> str:
        """The change table cut to :meth:`_window_rows` rows around the marked one (so the
        current change is always in sight), with a line above and below saying how many
        rows are left out."""
        shown = self._window_rows() - 2                      # the two "more" lines count as rows
        first = min(max(mark - 2, 0), max(len(rows) - shown, 0))
        window = rows[first:first + shown]
        window += [(["", ""], None)] * (shown - len(window))
        later = max(len(rows) - first - shown, 0)

        def more(count: int, where: str) -> str:
            text = f"... {count} {where} row{'s' if count != 1 else ''}" if count else "&nbsp;"
            return f'<div style="font-size:{size};color:#666666">{text}</div>'

        return (more(first, "earlier") + table_html(window, self.look, header=("step", "change (old -> new)"),
                                                    mark_row=mark - first) + more(later, "later"))


#: Rows of the change table shown at once (see OperationStepper._table_window).
TABLE_WINDOW = 12
#: How far across its edge, toward its face's third corner, an arrow is moved when it
#: would lie on another (a fraction of the distance from the edge to that corner).
OVERLAP_INSET = 0.3


class FlipStepper(OperationStepper):
    """Step through an edge flip (chapter 06): the quadrilateral's six halfedges, four
    vertices and two faces, then each pointer the flip rewrites."""

    operation = "flip"

    def _can(self, mesh, edge):
        from ..core.ops import can_flip

        return can_flip(mesh, edge)

    def _run(self, mesh, edge, position, log) -> None:
        from ..core.ops import flip

        flip(mesh, edge, log=log)


class SplitStepper(OperationStepper):
    """Step through an edge split (chapter 06): the new vertex m, the new edges and
    faces, then each pointer that links them in."""

    operation = "split"

    def _can(self, mesh, edge):
        from ..core.ops import can_split

        return can_split(mesh, edge)

    def _run(self, mesh, edge, position, log) -> None:
        from ..core.ops import split

        split(mesh, edge, position, log=log)


class CollapseStepper(OperationStepper):
    """Step through an edge collapse (chapter 07): vA survives, vB goes; the halfedges
    around them are named h_AB, h_BA, h_A_L ... as in ``ops/collapse.py``."""

    operation = "collapse"

    def _can(self, mesh, edge):
        from ..core.ops import can_collapse

        return can_collapse(mesh, edge)

    def _run(self, mesh, edge, position, log) -> None:
        from ..core.ops import collapse

        collapse(mesh, edge, position, log=log)


class CollapseAtlas:
    """The collapse cases side by side, stepped together one phase at a time, and the
    collapses the link condition refuses, each with its reason (chapters 07 and 08).

    Args:
        cases: ``(title, mesh, edge)`` of the allowed collapses to compare; by default
            the removed vertex of degree 3 (the cube's edge 0) and of degree > 3 (the
            single-collapse mesh's edge 0).
        refused: ``(title, mesh, edge)`` of collapses that are refused; by default the
            tetrahedron, the figure-8 strip and the lone triangle.
        mode, preset: as for every widget. The refused cases are small still pictures.

    ``atlas.step()`` (or ``go("phase")``) moves every case to the end of the next phase
    of the collapse; ``go("start")``, ``go("end")``, ``go("back")`` or a phase number.
    Each case is a :class:`CollapseStepper` (``atlas.steppers``) and can also be
    stepped on its own.

    Keys (mouse pointer over the two lines under the buttons: the keys and the phase):
    → space or PgDn the next phase, ← one back, Home the start, End the end;
    ``atlas.key_area.press(key)`` from code.
    """

    KEYS = {"ArrowRight": "phase", "Space": "phase", "PageDown": "phase", "ArrowLeft": "back",
            "Home": "start", "End": "end"}

    title = "Edge collapse: the cases side by side"

    def __init__(self, cases=None, refused=None, *, mode: str | None = None, preset="default"):
        import ipywidgets as widgets

        from ..data import sample
        from .renderer import choose_mode

        self.mode = choose_mode(mode)
        self.look = _preset(preset)
        large = self.look.name == "large"
        if cases is None:
            cases = [("removed vertex of degree 3", sample("cube"), 0),
                     ("removed vertex of degree > 3", sample("single_collapse"), 0)]
        if refused is None:
            refused = [("tetrahedron", sample("tetrahedron"), 0), ("figure 8", sample("figure8"), 0),
                       ("lone triangle", sample("lone_triangle"), 0)]
        case_size = (600, 450) if large else (440, 330)
        thumb_size = (400, 300) if large else (300, 225)
        self.titles = [title for title, _, _ in cases]
        self.steppers = [CollapseStepper(mesh, edge, mode=self.mode, preset=self.look, window_size=case_size)
                         for _, mesh, edge in cases]
        self.refused_titles = [title for title, _, _ in refused]
        self.refused = [CollapseStepper(mesh, edge, mode="static", preset=self.look, window_size=thumb_size)
                        for _, mesh, edge in refused]
        for stepper in self.refused:
            self._show_refused(stepper)
        self.phases = [title for _, title in self.steppers[0].log.phases] if self.steppers else []
        self._phase = 0

        css = panel_css(self.look)
        self._status = widgets.HTML()
        self._legend = widgets.HTML(layout=widgets.Layout(margin="0 0 0 12px"))
        self._captions = [widgets.HTML(layout=widgets.Layout(width=f"{case_size[0]}px")) for _ in self.steppers]
        buttons = widgets.HBox([
            self._button("start", lambda: self.go("start")),
            self._button("back", self.back),
            self._button("phase", self.step),
            self._button("end", lambda: self.go("end")),
        ])
        self.buttons = {b.description: b for b in buttons.children}
        columns = widgets.HBox([
            widgets.VBox([widgets.HTML(f'<b style="font-size:{css["font"]}">{html.escape(title)}</b>'),
                          stepper.view.widget, caption])
            for title, stepper, caption in zip(self.titles, self.steppers, self._captions)
        ] + [self._legend], layout=widgets.Layout(flex_flow="row wrap"))     # narrow: the legend goes below
        refusals = widgets.HBox([
            widgets.VBox([widgets.HTML(f'<b style="font-size:{css["font"]}">{html.escape(title)}</b>'),
                          stepper.view.widget,
                          widgets.HTML(f'<div style="font-size:{css["font"]};width:{thumb_size[0]}px">'
                                       f'<code>{html.escape(str(stepper.check.rule))}</code>: '
                                       f"{html.escape(stepper.check.reason)}</div>")],
                         layout=widgets.Layout(margin="0 12px 0 0"))
            for title, stepper in zip(self.refused_titles, self.refused)
        ], layout=widgets.Layout(flex_flow="row wrap"))
        heading = f'<b style="font-size:calc({css["font"]} * 1.25)">{html.escape(self.title)}</b>'
        self.key_area = KeyArea([self._status], self.buttons, self.KEYS, self.look)
        self.widget = widgets.VBox([
            widgets.HTML(heading), buttons, self.key_area.widget, columns,
            widgets.HTML(f'<b style="font-size:calc({css["font"]} * 1.15)">Refused: the link condition and '
                         f"the boundary rules</b>"),
            refusals,
        ])
        self._refresh()

    def _button(self, label: str, action):
        return panel_button(self.look, label, "", action)

    @staticmethod
    def _show_refused(stepper) -> None:
        """Show a refused collapse so its reason can be followed: the edge and its ends'
        neighbours fill the picture, seen at a slant (a tetrahedron seen along its edge is
        a flat rhombus), and every vertex there is labelled, as the reason names vertices."""
        mesh, scene = stepper.before, stepper.scene
        edge = next(index for kind, index in stepper.check.elements if kind == "edge")
        ends = mesh.edge_vertices()[edge]                                      # (2,)
        neighbours = [h.tip.index for v in ends for h in mesh.vertex(int(v)).outgoing()]
        near = np.unique(np.concatenate([ends, neighbours]))
        points = mesh.positions[near]                                         # (k, 3)
        centre = mesh.positions[ends].mean(axis=0)
        _, spread, axes = np.linalg.svd(points - points.mean(axis=0))
        if spread[-1] < 1e-9 * spread[0]:
            direction = axes[2]                  # a flat patch: straight onto its plane
        else:
            # A solid: from outside the edge, turned aside and a little along the edge.
            along = unit(mesh.positions[ends[1]] - mesh.positions[ends[0]])
            outward = unit(centre - mesh.positions[~mesh.vertex_deleted].mean(axis=0))
            side = unit(np.cross(along, outward))
            direction = unit(outward + 0.3 * along + 0.3 * side)
        camera = scene.plotter.camera
        camera.focal_point = tuple(centre)
        camera.position = tuple(centre + direction)
        scene.plotter.reset_camera(bounds=np.column_stack([points.min(axis=0), points.max(axis=0)]).ravel())
        scene.set_roles(scene.roles, names={("vertex", int(v)): f"v{int(v)}" for v in near})
        stepper.view.update()

    @property
    def phase(self) -> int:
        """0 (gathered) to ``len(self.phases)`` (done): every phase up to this one is applied."""
        return self._phase

    def _end_of_phase(self, stepper, phase: int) -> int:
        """The step of ``stepper`` at which its phases up to ``phase`` are all applied."""
        if phase == 0:
            return 0
        phases = stepper.log.phases
        stop = phases[phase][0] if phase < len(phases) else len(stepper.log.changes)
        return sum(1 for _, end in stepper.groups if end <= stop)

    def go(self, target) -> int:
        """Show every case at the end of a phase: "phase" (next), "back", "start", "end", or a number."""
        last, move = len(self.phases), None
        if isinstance(target, str):
            moves = {"phase": self._phase + 1, "next": self._phase + 1, "step": self._phase + 1,
                     "back": self._phase - 1, "start": 0, "end": last}
            if target not in moves:
                raise ValueError(f"unknown move {target!r}: use {', '.join(repr(m) for m in moves)} or a phase number")
            move, target = target, min(max(moves[target], 0), last)
            if target == self._phase:
                self._refresh(f"{move}: phase {self._phase} of {last} is the "
                              + ("last one; ← back or Home to go through it again" if target == last
                                 else "start; → or space goes forward"))
                return self._phase
        target = int(target)
        if not 0 <= target <= last:
            raise IndexError(f"there is no phase {target}: phases run from 0 to {last}")
        self._phase = target
        for stepper in self.steppers:
            stepper.go(self._end_of_phase(stepper, target))
            if target and self._end_of_phase(stepper, target) == self._end_of_phase(stepper, target - 1):
                self._without_changes(stepper)
        self._refresh()
        return self._phase

    @staticmethod
    def _without_changes(stepper) -> None:
        """Take the "changes now" highlight off a case that changes nothing in this phase
        (it would still show the last change of an earlier phase)."""
        scene = stepper.scene
        now = {*_CHANGED.values(), *_OLD.values(), *_NEW.values()}
        scene.set_roles({role: members for role, members in scene.roles.items() if role not in now},
                        names=scene.names)
        stepper.view.update()

    def step(self) -> int:
        """Every case to the end of the next phase."""
        return self.go("phase")

    def back(self) -> int:
        return self.go("back")

    def _phase_title(self) -> str:
        if self._phase == 0:
            return "gather the elements"
        return self.phases[self._phase - 1]

    def _refresh(self, note: str = "") -> None:
        """The phase in words, and ``note`` (why a move did not move) below it."""
        size = panel_css(self.look)["font"]
        self._status.value = (f'<div style="font-size:{size}">phase {self._phase} of {len(self.phases)}: '
                              f"<i>{html.escape(self._phase_title())}</i></div>"
                              + (f'<div style="font-size:{size};color:#555">{html.escape(note)}</div>' if note else ""))
        self._legend.value = legend_html(self.legend_entries(), self.look)
        for caption, stepper in zip(self._captions, self.steppers):
            state = stepper.state
            notes = "".join(f"<div>{html.escape(n)}</div>" for n in stepper.log.notes)
            caption.value = (f'<div style="font-size:{size}">{notes}<div>V - E + F = {state.n_vertices} - '
                             f"{state.n_edges} + {state.n_faces} = {state.euler_characteristic}</div></div>")

    def describe(self) -> str:
        """Each case at the current phase, then each refused case with its reason."""
        lines = [f"phase {self._phase} of {len(self.phases)}: {self._phase_title()}"]
        for title, stepper in zip(self.titles, self.steppers):
            state = stepper.state
            lines.append(f"{title}: collapse of edge {stepper.log.edge}, step {stepper.step_index} of "
                         f"{stepper.n_steps}; V - E + F = {state.n_vertices} - {state.n_edges} + "
                         f"{state.n_faces} = {state.euler_characteristic}")
            lines += [f"  {note}" for note in stepper.log.notes]
        for title, stepper in zip(self.refused_titles, self.refused):
            lines.append(f"refused, {title} ({stepper.check.rule}): {stepper.check.reason}")
        return "\n".join(lines)

    def legend_entries(self) -> list[tuple[str, str, str]]:
        """What the colours of every picture of the atlas mean now, each once:
        ``(text, "#RRGGBB", kind)`` as :meth:`HalfedgeScene.legend_entries`."""
        entries: dict[tuple[str, str, str], None] = {}
        for stepper in self.steppers + self.refused:
            entries.update(dict.fromkeys(stepper.scene.legend_entries()))
        return list(entries)

    def screenshot(self, path=None) -> bytes:
        """Every picture of the atlas in one PNG, titled: the cases in a row with the
        legend beside them, the refusals below."""
        phase = f"phase {self._phase} of {len(self.phases)}"
        return grid_png([[s.screenshot() for s in self.steppers] + [legend_png(self.legend_entries())],
                         [s.screenshot() for s in self.refused]],
                        [[f"{title} ({phase})" for title in self.titles] + ["legend"],
                         [f"refused: {title}" for title in self.refused_titles]], path=path)

    def close(self) -> None:
        self.key_area.close()
        self.widget.close()
        for stepper in self.steppers + self.refused:
            stepper.close()

    def _repr_mimebundle_(self, include=None, exclude=None):
        import base64

        for stepper in self.steppers + self.refused:   # their pictures are part of this widget
            stepper.view.shown()
        bundle = self.widget._repr_mimebundle_(include=include, exclude=exclude)
        bundle["text/plain"] = self.describe()
        bundle["image/png"] = base64.b64encode(self.screenshot()).decode("ascii")
        return bundle
