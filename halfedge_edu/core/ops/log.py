"""The step log: what a local operation gathered and every pointer it changed, in order.

Pass an :class:`OperationLog` to an operation to watch it work::

    log = OperationLog()
    collapse(mesh, 0, log=log)
    log.named["vB"]          # ('vertex', 0): the vertex that was removed
    log.changes[0]           # PointerChange(kind='vertex', index=4, field='position', ...)
    print(log.describe())    # one line per change: "halfedge 7 .next: 12 -> 3"

The operations write every pointer through a *writer*. Without a log they get the
plain :class:`Writer`, which only writes the arrays; with a log they get a
:class:`LoggingWriter`, which first notes the old value. Both run the very same
operation code, so the step-by-step form cannot drift from the real one, and the plain
form builds no log objects at all.

The fields a change can name:

| kind     | field      | meaning                                               |
|----------|------------|-------------------------------------------------------|
| halfedge | next, prev | the next / previous halfedge around its face or hole  |
| halfedge | vertex     | the vertex it leaves (its origin)                     |
| halfedge | face       | its face, -1 on the boundary                          |
| vertex   | halfedge   | its outgoing halfedge                                 |
| vertex   | position   | (x, y, z)                                             |
| face     | halfedge   | one of its halfedges                                  |
| any      | created    | ``False -> True``: the element was added              |
| any      | deleted    | ``False -> True``: the element was flagged deleted    |

A new element starts with every pointer -1 (and position None) before its "set" lines.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

if TYPE_CHECKING:
    from ..mesh import HalfedgeMesh

__all__ = ["LoggingWriter", "OperationLog", "PointerChange", "Writer", "writer_for"]


def _show(value) -> str:
    if isinstance(value, tuple):
        return "(" + ", ".join(f"{float(c):.6g}" for c in value) + ")"
    return str(value)


class PointerChange(NamedTuple):
    """One write an operation made: ``kind index .field: old -> new``."""

    kind: str  # "vertex", "halfedge", "edge" or "face"
    index: int
    field: str  # next, prev, vertex, face, halfedge, position, created, deleted
    old: object
    new: object

    def describe(self) -> str:
        return f"{self.kind} {self.index} .{self.field}: {_show(self.old)} -> {_show(self.new)}"


@dataclass
class OperationLog:
    """Everything one local operation did, in order; fill it by passing ``log=``.

    Attributes:
        operation: "flip", "split" or "collapse".
        edge: the edge the operation was called on.
        halfedge: the halfedge it started from (for collapse: ``h_BA``, from the
            removed vertex to the surviving one).
        named: name -> ``(kind, index)`` of the elements the operation gathered
            before changing anything, in the order it gathered them (the names are
            the ones in the operation's docstring picture).
        changes: every :class:`PointerChange`, in the order it was made. Writes that
            leave a value as it was are not changes and are not listed.
        created, deleted: ``(kind, index)`` of the elements added and removed
            (an edge's two halfedges are listed after it).
        phases: ``(start, title)``: the changes from position ``start`` on belong
            to the step called ``title`` (until the next phase starts).
        notes: sentences about this particular case, e.g. that the removed vertex
            had degree 3.
    """

    operation: str = ""
    edge: int = -1
    halfedge: int = -1
    named: dict = field(default_factory=dict)
    changes: list = field(default_factory=list)
    created: list = field(default_factory=list)
    deleted: list = field(default_factory=list)
    phases: list = field(default_factory=list)
    notes: list = field(default_factory=list)

    def begin(self, operation: str, edge: int, halfedge: int) -> None:
        """Start recording a new operation (clears anything recorded before)."""
        self.operation, self.edge, self.halfedge = operation, int(edge), int(halfedge)
        for record in (self.named, self.changes, self.created, self.deleted, self.phases, self.notes):
            record.clear()

    def name(self, **elements: tuple) -> None:
        """Record gathered elements: ``log.name(vA=("vertex", 4), h_AB=("halfedge", 7))``.

        Elements that do not exist here (a missing face at the boundary) are passed as
        ``(kind, -1)`` and left out.
        """
        for name, (kind, index) in elements.items():
            if index >= 0:
                self.named[name] = (kind, int(index))

    def names_of(self, kind: str, index: int) -> list[str]:
        """The names an element was gathered under (an element may have two)."""
        return [name for name, element in self.named.items() if element == (kind, index)]

    def describe(self) -> str:
        """Plain text: what was gathered, then one line per change, grouped by phase."""
        lines = [f"{self.operation} of edge {self.edge} (starting from halfedge {self.halfedge})"]
        if self.named:
            lines.append("gathered: " + ", ".join(f"{n} = {k} {i}" for n, (k, i) in self.named.items()))
        lines += self.notes
        bounds = [start for start, _ in self.phases[1:]] + [len(self.changes)]
        if self.phases and self.phases[0][0] > 0:
            lines += [change.describe() for change in self.changes[: self.phases[0][0]]]
        for (start, title), end in zip(self.phases, bounds):
            lines.append(f"# {title}")
            lines += [change.describe() for change in self.changes[start:end]] or ["(nothing to change here)"]
        if not self.phases:
            lines += [change.describe() for change in self.changes]
        if self.created:
            lines.append("created: " + ", ".join(f"{k} {i}" for k, i in self.created))
        if self.deleted:
            lines.append("deleted: " + ", ".join(f"{k} {i}" for k, i in self.deleted))
        return "\n".join(lines)

    def replay(self, mesh: "HalfedgeMesh", steps: int | None = None, start: int = 0) -> None:
        """Apply the first ``steps`` changes (all by default) to ``mesh``, from change ``start``.

        ``mesh`` must be the mesh as it was before the operation (e.g. a ``copy()``
        taken then), or with ``start`` the mesh after the first ``start`` changes.
        Replaying every change gives exactly the mesh after it; replaying
        fewer gives the in-between states a stepper shows, which are usually not
        valid meshes. The changes go through the same plain :class:`Writer` as the
        operation itself, so only the writer knows where each field is stored.
        """
        write = Writer(mesh)
        for change in self.changes[start:steps]:
            if change.field == "created":
                if change.kind != "halfedge":  # a halfedge comes with its edge
                    made = write.create(change.kind)
                    if made != change.index:
                        raise ValueError(f"replay: {change.kind} {change.index} would be created as {made}; "
                                         f"replay onto the mesh as it was before the operation")
            elif change.field == "deleted":
                if change.kind != "halfedge":  # deleted with its edge
                    write.delete(change.kind, change.index)
            else:
                write.set(change.kind, change.index, change.field, change.new)
        write.touch()

    def can_take_back(self, stop: int, start: int) -> bool:
        """Whether :meth:`take_back` can undo changes ``stop`` to ``start``: none of them
        created or deleted an element (an index cannot be given back)."""
        return not any(c.field in ("created", "deleted") for c in self.changes[stop:start])

    def take_back(self, mesh: "HalfedgeMesh", stop: int, start: int) -> None:
        """Undo changes ``stop`` to ``start`` of ``mesh``, the mesh after the first ``start``
        changes, newest first, leaving the mesh after the first ``stop`` (the way back
        of :meth:`replay`, for a stepper stepping back).

        Raises:
            ValueError: one of those changes created or deleted an element
                (see :meth:`can_take_back`); replay from the mesh before instead.
        """
        if not self.can_take_back(stop, start):
            raise ValueError(f"take_back: changes {stop} to {start} create or delete an element; "
                             f"replay from the mesh before the operation instead")
        write = Writer(mesh)
        for change in reversed(self.changes[stop:start]):
            write.set(change.kind, change.index, change.field, change.old)
        write.touch()


class Writer:
    """Writes an operation's changes straight into the mesh arrays, recording nothing.

    The one place that knows where each field of a :class:`PointerChange` is stored:
    :meth:`_refresh` takes the mesh's arrays and :data:`FIELDS` names the one a
    ``(kind, field)`` lives in. The operations call the named setters (``link``,
    ``set_vertex`` ...), which write directly; :meth:`OperationLog.replay` writes a
    recorded change with :meth:`set`. Both land in the same arrays.

    Attention: the array references are refreshed after each ``add_*``, since adding
    may move the arrays to bigger ones.
    """

    __slots__ = ("mesh", "next", "prev", "origin", "face", "vertex_halfedge", "face_halfedge", "positions")

    #: ``(kind, field)`` of a change -> the writer's attribute holding that array.
    FIELDS = {
        ("halfedge", "next"): "next",
        ("halfedge", "prev"): "prev",
        ("halfedge", "vertex"): "origin",
        ("halfedge", "face"): "face",
        ("vertex", "halfedge"): "vertex_halfedge",
        ("vertex", "position"): "positions",
        ("face", "halfedge"): "face_halfedge",
    }

    def __init__(self, mesh: "HalfedgeMesh"):
        self.mesh = mesh
        self._refresh()

    def _refresh(self) -> None:
        mesh = self.mesh
        self.next, self.prev = mesh._halfedge_next, mesh._halfedge_prev
        self.origin, self.face = mesh._halfedge_vertex, mesh._halfedge_face
        self.vertex_halfedge, self.face_halfedge = mesh._vertex_halfedge, mesh._face_halfedge
        self.positions = mesh._positions

    def phase(self, title: str) -> None:
        """Mark the start of a step of the operation (only a log keeps it)."""

    def set(self, kind: str, index: int, field: str, value) -> None:
        """Write ``value`` into ``field`` of element ``kind index`` (a :class:`PointerChange`'s terms)."""
        getattr(self, self.FIELDS[kind, field])[index] = value

    def link(self, h: int, n: int) -> None:
        """Make ``n`` follow ``h``: ``h.next = n`` and ``n.prev = h``."""
        self.next[h] = n
        self.prev[n] = h

    def cycle(self, a: int, b: int, c: int) -> None:
        """Make ``a -> b -> c -> a`` the ``next`` loop of a triangle (and the ``prev`` loop back)."""
        self.link(a, b)
        self.link(b, c)
        self.link(c, a)

    def make_face(self, f: int, a: int, b: int, c: int) -> None:
        """Face ``f`` is the triangle ``a -> b -> c``: :meth:`cycle`, then each halfedge's face is ``f``."""
        self.cycle(a, b, c)
        self.set_face(a, f)
        self.set_face(b, f)
        self.set_face(c, f)

    def set_vertex(self, h: int, v: int) -> None:
        """Halfedge ``h`` now leaves vertex ``v``."""
        self.origin[h] = v

    def set_face(self, h: int, f: int) -> None:
        self.face[h] = f

    def set_vertex_halfedge(self, v: int, h: int) -> None:
        self.vertex_halfedge[v] = h

    def set_face_halfedge(self, f: int, h: int) -> None:
        self.face_halfedge[f] = h

    def set_position(self, v: int, position) -> None:
        self.positions[v] = position

    def add_vertex(self, position) -> int:
        v = self.mesh.add_vertex(position)
        self._refresh()
        return v

    def add_edge(self, a: int, b: int) -> int:
        e = self.mesh.add_edge(a, b)
        self._refresh()
        return e

    def add_face(self, h: int) -> int:
        f = self.mesh.add_face(h)
        self._refresh()
        return f

    def create(self, kind: str) -> int:
        """Add a blank ``"vertex"``, ``"edge"`` or ``"face"`` (pointers -1, position 0) and return it."""
        if kind == "vertex":
            return self.add_vertex((0.0, 0.0, 0.0))
        if kind == "edge":
            return self.add_edge(-1, -1)
        return self.add_face(-1)

    def delete_vertex(self, v: int) -> None:
        self.mesh.delete_vertex(v)

    def delete_edge(self, e: int) -> None:
        self.mesh.delete_edge(e)

    def delete_face(self, f: int) -> None:
        self.mesh.delete_face(f)

    def delete(self, kind: str, index: int) -> None:
        """Flag ``kind index`` deleted (``"vertex"``, ``"edge"`` or ``"face"``)."""
        getattr(self, f"delete_{kind}")(index)

    def touch(self) -> None:
        """Tell the mesh its connectivity changed (derived arrays are stale)."""
        self.mesh._touch()


class LoggingWriter(Writer):
    """A :class:`Writer` that notes every change in an :class:`OperationLog` first.

    Every setter goes through :meth:`_write`, which notes the old value and writes
    only a real change.
    """

    __slots__ = ("log",)

    def __init__(self, mesh: "HalfedgeMesh", log: OperationLog):
        super().__init__(mesh)
        self.log = log

    def _note(self, kind: str, index: int, name: str, old, new) -> bool:
        """Record a change; False (and nothing recorded) when ``old == new``."""
        if old == new:
            return False
        self.log.changes.append(PointerChange(kind, int(index), name, old, new))
        return True

    def phase(self, title: str) -> None:
        self.log.phases.append((len(self.log.changes), title))

    def set(self, kind: str, index: int, field: str, value) -> None:
        self._write(getattr(self, self.FIELDS[kind, field]), kind, index, field, value)

    def _write(self, array, kind: str, index: int, field: str, value) -> None:
        """Note ``kind index .field: old -> value``, then write it, unless nothing changes."""
        if field == "position":
            old, new = tuple(float(c) for c in array[index]), tuple(float(c) for c in value)
        else:
            old, new = int(array[index]), int(value)
        if self._note(kind, index, field, old, new):
            array[index] = value

    def link(self, h: int, n: int) -> None:
        self._write(self.next, "halfedge", h, "next", n)
        self._write(self.prev, "halfedge", n, "prev", h)

    def set_vertex(self, h: int, v: int) -> None:
        self._write(self.origin, "halfedge", h, "vertex", v)

    def set_face(self, h: int, f: int) -> None:
        self._write(self.face, "halfedge", h, "face", f)

    def set_vertex_halfedge(self, v: int, h: int) -> None:
        self._write(self.vertex_halfedge, "vertex", v, "halfedge", h)

    def set_face_halfedge(self, f: int, h: int) -> None:
        self._write(self.face_halfedge, "face", f, "halfedge", h)

    def set_position(self, v: int, position) -> None:
        self._write(self.positions, "vertex", v, "position", position)

    def _created(self, kind: str, index: int) -> None:
        self._note(kind, index, "created", False, True)
        self.log.created.append((kind, int(index)))

    def _deleted(self, kind: str, index: int) -> None:
        self._note(kind, index, "deleted", False, True)
        self.log.deleted.append((kind, int(index)))

    def add_vertex(self, position) -> int:
        v = super().add_vertex(position)
        self._created("vertex", v)
        self._note("vertex", v, "position", None, tuple(float(c) for c in position))
        return v

    def add_edge(self, a: int, b: int) -> int:
        e = super().add_edge(a, b)
        self._created("edge", e)
        self._created("halfedge", 2 * e)
        self._created("halfedge", 2 * e + 1)
        self._note("halfedge", 2 * e, "vertex", -1, int(a))
        self._note("halfedge", 2 * e + 1, "vertex", -1, int(b))
        return e

    def add_face(self, h: int) -> int:
        f = super().add_face(h)
        self._created("face", f)
        self._note("face", f, "halfedge", -1, int(h))
        return f

    def delete_vertex(self, v: int) -> None:
        super().delete_vertex(v)
        self._deleted("vertex", v)

    def delete_edge(self, e: int) -> None:
        super().delete_edge(e)
        self._deleted("edge", e)
        self._deleted("halfedge", 2 * e)
        self._deleted("halfedge", 2 * e + 1)

    def delete_face(self, f: int) -> None:
        super().delete_face(f)
        self._deleted("face", f)


def writer_for(mesh: "HalfedgeMesh", log: OperationLog | None) -> Writer:
    """The plain :class:`Writer` when ``log`` is None, else a :class:`LoggingWriter` into it."""
    return Writer(mesh) if log is None else LoggingWriter(mesh, log)
