"""Step through a local operation one pointer change at a time: flip, split, collapse.

    from halfedge_edu.viz import CollapseStepper
    w = CollapseStepper(hx.sample("cube"), 0)
    w                     # step 0: the elements the collapse gathers, with the course's names
    w.step()              # the first change highlighted and listed, old -> new
    w.go("phase")         # to the start of the next phase; also "start", "end", "back", 5
    print(w.describe())

How it works: :class:`OperationSteps` copies the mesh, runs the real operation on the copy
with an :class:`~halfedge_edu.core.ops.log.OperationLog`, and keeps the mesh as it was
before. Step ``k`` is "before, plus the first k changes applied" (``log.replay``), so
going back is as cheap as going forward and the pictures can never disagree with the
operation. :class:`OperationPainter` draws a step as halfedge arrows with roles.
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
from .neighbourhood import ring_window
from .palette import panel_css
from .screen import unit
from .scene import MAX_ARROWS, HalfedgeScene
from .steps import Stepper, phase_moves
from .widgets import legend_html, table_html

# Stepper roles by the kind of element they colour.
CHANGED = {"halfedge": "changed", "vertex": "changed_vertex", "face": "changed_face"}
OLD = {"halfedge": "old_target", "vertex": "old_vertex", "face": "old_face"}
NEW = {"halfedge": "new_target", "vertex": "new_vertex", "face": "new_face"}
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


#: Rows of the change table shown at once (see OperationPainter.table_window).
TABLE_WINDOW = 12
#: How far across its edge, toward its face's third corner, an arrow is moved when it
#: would lie on another (a fraction of the distance from the edge to that corner).
OVERLAP_INSET = 0.3


def _operations():
    """operation name -> (its check, a call ``run(mesh, edge, position, log)``)."""
    from ..core.ops import can_collapse, can_flip, can_split, collapse, flip, split

    return {"flip": (can_flip, lambda mesh, edge, position, log: flip(mesh, edge, log=log)),
            "split": (can_split, lambda mesh, edge, position, log: split(mesh, edge, position, log=log)),
            "collapse": (can_collapse, lambda mesh, edge, position, log: collapse(mesh, edge, position, log=log))}


class OperationSteps:
    """The :class:`~.steps.Steps` of one local operation: step 0 the gathered elements,
    then one step per group of pointer changes (:func:`group_changes`) in its log.

    Args:
        mesh: the mesh; it is copied, never changed.
        edge: an edge index, an :class:`Edge`, or (collapse) a :class:`Halfedge` whose
            origin is removed.
        operation: "flip", "split" or "collapse".
        position: for split and collapse, where the new or merged vertex goes.

    ``before`` and ``after`` are the mesh before and after, ``check`` the operation's
    :class:`~halfedge_edu.core.ops.check.OpCheck` (a refused operation has no steps),
    ``log`` its :class:`~halfedge_edu.core.ops.log.OperationLog`, ``groups`` the
    ``(start, stop)`` of each step in ``log.changes``.
    """

    def __init__(self, mesh, edge, operation: str, position=None):
        from ..core.ops.log import OperationLog

        can, run = _operations()[operation]
        self.operation = operation
        self.before = mesh.copy()
        self.after = mesh.copy()
        argument = self.after.halfedge(edge.index) if isinstance(edge, Halfedge) else int(edge)
        self.check = can(self.after, argument)
        self.log = OperationLog()
        if self.check:
            run(self.after, argument, position, self.log)
        self.groups = group_changes(self.log.changes)
        self._shown = (None, 0)              # the state made last and its count of changes

    @property
    def n_steps(self) -> int:
        return len(self.groups)

    @property
    def result(self):
        return self.after.copy()

    def stop(self, k: int) -> int:
        """How many of the log's changes are applied at step ``k``."""
        return self.groups[k - 1][1] if k else 0

    def mesh(self, k: int):
        """The mesh before the operation with the changes of its first ``k`` steps applied.

        Replaying from the start copies the mesh before and grows every array an element
        is created in (about 3 ms on the bunny). From the state made last it is cheaper:
        a step forward copies that state (with the room its arrays have grown) and applies
        only the changes since; a step back writes the old values of the changes in
        between, newest first, unless one of them created or deleted an element (an
        index cannot be taken back: then it replays from the start).
        """
        stop = self.stop(k)
        shown, shown_stop = self._shown
        if shown is not None and stop == shown_stop:
            return shown
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

    def phase_steps(self) -> list[int]:
        """The step numbers at which a phase starts."""
        starts = []
        for position, _title in self.log.phases:
            for k, (start, stop) in enumerate(self.groups, start=1):
                if start <= position < stop:
                    starts.append(k)
                    break
        return sorted(set(starts))

    def phase_title(self, k: int) -> str:
        """The title of the phase step ``k`` belongs to ("gather the elements" at step 0)."""
        if k == 0:
            return "gather the elements"
        start = self.groups[k - 1][0]
        title = ""
        for position, phase in self.log.phases:
            if position <= start:
                title = phase
        return title

    def moves(self, k: int) -> dict[str, int]:
        """"phase" (the start of the next phase) and "phase back"."""
        return phase_moves(self.phase_steps(), k, self.n_steps)

    def resolve(self, target, k: int) -> int | None:
        return None

    def edge_index(self) -> int:
        """The edge the operation was asked about (also when it was refused), or -1."""
        if self.check:
            return self.log.edge
        for kind, index in self.check.elements:
            if kind == "edge":
                return index
        return -1


class OperationPainter:
    """How a step of a local operation looks (a :class:`~.steps.Painter`): the mesh as
    halfedge arrows, the gathered elements by name, the changes of the step in the
    "old -> new" colours, and a panel with the change table.

    Keys (mouse pointer over the panel below the buttons): → or space the next change,
    ← one back, PgDn the next phase, Home the start, End the end.
    """

    keys = {"PageDown": "phase"}
    moves_help = "a step number"

    def __init__(self, steps: OperationSteps):
        self.steps = steps
        self.before, self.after, self.log, self.check = steps.before, steps.after, steps.log, steps.check
        self.groups = steps.groups
        self.title = f"Edge {steps.operation}: step by step"
        self.buttons = () if not steps.check else (
            ("start", "back to the gathered elements", "start"),
            ("back", "one change back", "back"),
            ("step", "apply the next change", "step"),
            ("phase", "to the start of the next phase", "phase"),
            ("end", "all changes applied", "end"))
        self.names = self._element_names()

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

    def make_scene(self, mesh, look, **options) -> HalfedgeScene:
        """A scene of the mesh before, with the operation's faces kept apart."""
        self._prepare_references()
        vertices = self._operation_vertices()
        window = None
        if self.before.n_halfedges > MAX_ARROWS and len(vertices):
            # A large mesh: the arrows around the operation, and every halfedge it creates.
            _, around = ring_window(self.before, vertices, options["rings"])
            created = np.arange(self.before.n_halfedge_slots, self.after.n_halfedge_slots)
            window = np.unique(np.concatenate([around, created]))
        scene = HalfedgeScene(mesh, preset=look, follow=False, local_faces=self._touched_faces(),
                              corners=self._arrow_corners, face_corners=self._face_corners, window=window,
                              **options)
        if not self.check:
            # Face the refused edge itself; the other elements of the reason are lit up.
            edge = self.steps.edge_index()
            if edge >= 0:
                vertices = np.array([self.before.halfedge_vertex[2 * edge], self.before.halfedge_vertex[2 * edge + 1]])
        if len(vertices):
            scene.look_at(vertices)
        return scene

    def paint(self, scene, k: int) -> None:
        scene.set_mesh(self.steps.mesh(k), self.roles(k), names=self.names)

    def legend_html(self, scene, look) -> str:
        return legend_html(scene.legend_entries(), look)

    def roles(self, k: int) -> dict[str, list[int]]:
        """Role -> elements at step ``k``: named at step 0, then created, doomed, and the
        step's changes with their old and new targets; the refused elements if refused."""
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
        done = self.steps.stop(k)
        for position, change in enumerate(self.log.changes):
            if change.field == "created" and position < done:
                add(_CREATED, change.kind, change.index)
            elif change.field == "deleted" and position >= done:
                add(_DOOMED, change.kind, change.index)
        if k == 0:
            for kind, index in self.log.named.values():
                add(_NAMED, kind, index)
            return dict(roles)
        start, stop = self.groups[k - 1]
        for change in self.log.changes[start:stop]:
            if change.field in ("created", "deleted"):
                continue
            add(CHANGED, change.kind, change.index)
            target = _TARGET.get((change.kind, change.field))
            if target is not None:
                add(OLD, target, change.old)
                add(NEW, target, change.new)
        return dict(roles)

    # -- text ----------------------------------------------------------------------------

    def _value(self, kind: str | None, value) -> str:
        """A pointer value with the operation's name for it, e.g. ``16 (h2)``."""
        if kind is None or not isinstance(value, (int, np.integer)) or value < 0:
            if isinstance(value, tuple):
                return "(" + ", ".join(f"{float(c):.4g}" for c in value) + ")"
            return str(value)
        name = self.names.get((kind, int(value)))
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

    @staticmethod
    def _counts(mesh) -> str:
        return f"{mesh.n_vertices} vertices, {mesh.n_edges} edges, {mesh.n_faces} faces"

    def _heading(self) -> str:
        return f"{self.steps.operation} of edge {self.steps.edge_index()}"

    def describe(self, k: int) -> str:
        if not self.check:
            return f"{self._heading()}: refused ({self.check.rule})\nreason: {self.check.reason}"
        lines = [f"{self._heading()}: step {k} of {self.steps.n_steps} ({self.steps.phase_title(k)})"]
        if k == 0:
            lines.append("gathered: " + ", ".join(f"{name} = {kind} {index}"
                                                  for name, (kind, index) in self.log.named.items()))
            lines += self.log.notes
        else:
            lines += [f"now: {text}" for text in self._group_text(k)]
        lines.append(f"mesh: {self._counts(self.steps.mesh(k))}")
        return "\n".join(lines)

    # -- panel ---------------------------------------------------------------------------

    def panel_html(self, stepper) -> str:
        k = stepper.step_index
        css = panel_css(stepper.look)
        size = css["font"]
        if not self.check:
            return (f'<div style="font-size:{size}"><b>{html.escape(self._heading())}: refused</b> '
                    f'(<code>{html.escape(str(self.check.rule))}</code>)<br>{html.escape(self.check.reason)}</div>')
        top = (f'<div style="font-size:{size};margin:4px 0"><b>{html.escape(self._heading())}</b>: step '
               f"{k} of {self.steps.n_steps}<br><i>{html.escape(self.steps.phase_title(k))}</i></div>")
        if k == 0:
            rows = [([name, f"{kind} {index}"], _NAMED[kind] if kind in _NAMED else None)
                    for name, (kind, index) in self.log.named.items()]
            rows += [(["", ""], None)] * (self._window_rows() - len(rows) - len(self.log.notes))
            notes = "".join(f'<div style="font-size:{size}">{html.escape(n)}</div>' for n in self.log.notes)
            body = notes + table_html(rows, stepper.look, header=("name", "element"))
        else:
            rows, mark = [], None
            current = self.groups[k - 1]
            for j, (start, stop) in enumerate(self.groups, start=1):
                for position in range(start, stop):
                    change = self.log.changes[position]
                    role = CHANGED.get(change.kind) if j == k else None
                    text = self._change_text(change)
                    if j > k:
                        text = "  " + text
                    rows.append(([j, text], role))
                    if (start, stop) == current and mark is None:
                        mark = len(rows) - 1
            body = self._table_window(rows, mark, size, stepper.look)
        counts = (f'<div style="font-size:{size};margin-top:6px">before: {self._counts(self.before)}<br>'
                  f"now: {self._counts(self.steps.mesh(k))}<br>after: {self._counts(self.after)}</div>")
        return top + body + counts

    def _window_rows(self) -> int:
        """How many rows the panel's table shows at every step: enough for the named
        elements at step 0, and for a window of the change table later. One number for
        all steps keeps the panel's height from jumping as the learner steps."""
        return max(TABLE_WINDOW, len(self.log.named) + len(self.log.notes))

    def _table_window(self, rows, mark: int, size: str, look) -> str:
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

        return (more(first, "earlier") + table_html(window, look, header=("step", "change (old -> new)"),
                                                    mark_row=mark - first) + more(later, "later"))


class OperationStepper(Stepper):
    """Shared machinery of the flip, split and collapse steppers (use those): a
    :class:`~.steps.Stepper` over :class:`OperationSteps`, painted by :class:`OperationPainter`.

    Args:
        mesh: the mesh; it is copied, never changed.
        edge: an edge index, an :class:`Edge`, or (collapse) a :class:`Halfedge`
            whose origin is removed.
        position: for split and collapse, where the new or merged vertex goes
            (the midpoint by default).
        mode, preset, rings, window_size: as for every widget.

    ``before``, ``after``, ``check``, ``log`` and ``groups`` are those of its
    :class:`OperationSteps`. Keys (mouse pointer over the panel below the buttons): → or
    space the next change, ← one back, PgDn the next phase, Home the start, End the end.
    """

    operation = ""

    def __init__(self, mesh, edge, *, position=None, mode: str | None = None, preset="default",
                 rings: int = 2, window_size=None):
        steps = OperationSteps(mesh, edge, self.operation, position)
        super().__init__(steps, OperationPainter(steps), mode=mode, preset=preset, window_size=window_size,
                         rings=rings)

    @property
    def before(self):
        """The mesh before the operation (the steps' own copy: do not change it)."""
        return self.source.before

    @property
    def after(self):
        """The mesh after the operation (the steps' own copy; ``result`` gives a new one)."""
        return self.source.after

    @property
    def check(self):
        """The operation's :class:`~halfedge_edu.core.ops.check.OpCheck`."""
        return self.source.check

    @property
    def log(self):
        """The operation's :class:`~halfedge_edu.core.ops.log.OperationLog`."""
        return self.source.log

    @property
    def groups(self) -> list[tuple[int, int]]:
        """``(start, stop)`` in ``log.changes`` of each step after step 0."""
        return self.source.groups


class FlipStepper(OperationStepper):
    """Step through an edge flip (chapter 06): the quadrilateral's six halfedges, four
    vertices and two faces, then each pointer the flip rewrites."""

    operation = "flip"


class SplitStepper(OperationStepper):
    """Step through an edge split (chapter 06): the new vertex m, the new edges and
    faces, then each pointer that links them in."""

    operation = "split"


class CollapseStepper(OperationStepper):
    """Step through an edge collapse (chapter 07): vA survives, vB goes; the halfedges
    around them are named h_AB, h_BA, h_A_L ... as in ``ops/collapse.py``."""

    operation = "collapse"


# ----------------------------------------------------------------------------------------
# Still pictures of an operation's log (chapters 06 and 07)
# ----------------------------------------------------------------------------------------

def gathered_roles(log) -> dict[str, list[int]]:
    """The palette roles of what ``log``'s operation gathered: ``named`` (halfedges),
    ``named_vertex`` and ``named_face``."""
    return {role: [index for kind, index in log.named.values() if kind == kind_of]
            for role, kind_of in (("named", "halfedge"), ("named_vertex", "vertex"), ("named_face", "face"))}


def created_roles(log) -> dict[str, list[int]]:
    """The palette roles of what ``log``'s operation created: ``created`` (halfedges),
    ``created_vertex`` and ``created_face``."""
    return {role: [index for kind, index in log.created if kind == kind_of]
            for role, kind_of in (("created", "halfedge"), ("created_vertex", "vertex"), ("created_face", "face"))}


def named_picture(mesh, log, roles=None, *, size=(400, 300), labels=("vertex",), only_created: bool = False,
                  camera=None, follow="auto", legend: bool = False) -> bytes:
    """A picture (PNG bytes) of ``mesh`` with the elements of ``log`` labelled by the
    names the operation gave them (``v0``, ``h_AB``, ``gL/gR`` where one element has two).

    Args:
        mesh: the mesh before or after the operation (a deleted element is left out).
        log: the operation's :class:`~halfedge_edu.core.ops.log.OperationLog`.
        roles: palette role -> elements to colour (default :func:`gathered_roles`).
        size: the picture's size in pixels.
        labels: which kinds of element get index labels, as for :class:`HalfedgeScene`.
        only_created: name only the vertices and the elements the operation created.
        camera: a camera position ``[eye, focus, up]`` (default: the scene's own).
        follow: whether the camera turns toward the highlight, as for :class:`HalfedgeScene`.
        legend: draw the roles' legend in the picture.
    """
    from .scene import scene_picture

    names: dict[tuple[str, int], str] = {}
    for name, element in log.named.items():
        if only_created and element not in log.created and element[0] != "vertex":
            continue
        names[element] = f"{names[element]}/{name}" if element in names else name
    roles = gathered_roles(log) if roles is None else roles

    def show(scene):
        if camera is not None:
            scene.plotter.camera_position = camera
        scene.set_roles(roles, names=names)       # deleted elements are left out

    return scene_picture(mesh, show, window_size=size, legend=legend, labels=labels, follow=follow)
