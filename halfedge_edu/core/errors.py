"""The error types of halfedge_edu, and the warning for dropped vertices.

Every error names the element it is about, so that a student can go and look at it:
``MeshInputError`` for input that cannot become a halfedge mesh (a file line, a face,
an edge or a vertex), ``MeshInvariantError`` for a built mesh that breaks one of the
structure's rules, ``TopologyError`` for a local operation that is not allowed, and
``StaleHandleError`` for a handle kept across ``garbage_collect()``.
"""

from __future__ import annotations

from typing import Iterable

#: How many elements a message names before it only counts the rest: a message about a
#: file with a million copies of one face must stay one readable line, not megabytes.
MAX_NAMED = 8


def first_few(items: Iterable, *, total: int | None = None, limit: int = MAX_NAMED) -> str:
    """``"a, b, c, ... and 997 more"``: a list for a message, cut after ``limit`` items.

    Every message that lists elements goes through this, so that its length does not
    grow with the input. Items are shown with ``str``; only the first ``limit`` are
    looked at, so ``items`` may be a generator over a million elements.

    Args:
        items: the elements, or a generator of their descriptions.
        total: how many there are in all (default: counted from ``items``).
    """
    shown, count = [], 0
    for count, item in enumerate(items, start=1):
        if count <= limit:
            shown.append(str(item))
        elif total is not None:
            break
    total = count if total is None else total
    return ", ".join(shown) + (f", ... and {total - limit} more" if total > limit else "")


class MeshInputError(ValueError):
    """Input that cannot be turned into a halfedge mesh.

    Args:
        message: what is wrong, naming the element (and the file line) where there is one.
        element, line: as below; both keyword-only, both optional.

    Attributes:
        element: ``(kind, index)`` of the offending element, for example
            ``("face", 12)``, ``("edge", (3, 7))`` or ``("vertex", 5)``; None when the
            problem is not about one element (an unreadable file, say).
        line: the 1-based line of the source file where the problem is, or None.
    """

    element: tuple | None
    line: int | None

    def __init__(self, message: str, *, element: tuple | None = None, line: int | None = None):
        super().__init__(message)
        self.element = element
        self.line = line


class MeshInvariantError(Exception):
    """A built mesh breaks one of the halfedge structure's rules.

    Args:
        rule: a short name such as ``"twin-involution"`` or ``"next-cycle"``.
        element: ``(kind, index)`` of the first element found breaking it,
            for example ``("halfedge", 17)``.
        message: the sentence a student can act on; ``str(error)`` is
            ``"[rule] message"``.

    Attributes:
        rule, element: as given.
    """

    rule: str
    element: tuple

    def __init__(self, rule: str, element: tuple, message: str):
        super().__init__(f"[{rule}] {message}")
        self.rule = rule
        self.element = element


class TopologyError(ValueError):
    """A local operation (flip, split, collapse) that is not allowed on this element.

    The mesh is left exactly as it was.

    Args:
        reason: the same sentence that ``mesh.can_flip(e).reason`` (or ``can_split`` /
            ``can_collapse``) gives; also ``str(error)``.
        rule: the short name of the rule that refused the operation, for example
            ``"link-condition"`` (the ``.rule`` of the refusing ``OpCheck``); None when
            no named rule applies.
        elements: ``(kind, index)`` pairs of the elements the reason is about, e.g.
            ``(("edge", 5), ("vertex", 11))``, so a notebook can highlight them.

    Attributes:
        reason, rule, elements: as given.
    """

    reason: str
    rule: str | None
    elements: tuple

    def __init__(self, reason: str, *, rule: str | None = None, elements: tuple = ()):
        super().__init__(reason)
        self.reason = reason
        self.rule = rule
        self.elements = elements


class StaleHandleError(IndexError):
    """A handle taken before ``garbage_collect()`` renumbered its mesh, used after it.

    ``garbage_collect()`` closes the gaps that deletions left, so index 20 may afterwards
    name another element; a handle remembers the mesh's generation (how many
    renumbering collections it had seen) and refuses to act for a later one, instead
    of silently naming whatever now has its index. An ``IndexError``, like the error
    for an index that names no element.

    Args:
        kind: ``"vertex"``, ``"halfedge"``, ``"edge"`` or ``"face"``.
        index: the handle's index, from before the collection.
        handle_generation, mesh_generation: the mesh's generation when the handle was
            made, and now.

    Attributes:
        kind, index, handle_generation, mesh_generation: as given.
    """

    kind: str
    index: int
    handle_generation: int
    mesh_generation: int

    #: kind -> the field of ``GarbageCollectMaps`` that renumbers it.
    MAP_FIELDS = {"vertex": "vertices", "halfedge": "halfedges", "edge": "edges", "face": "faces"}

    def __init__(self, kind: str, index: int, handle_generation: int, mesh_generation: int):
        field = self.MAP_FIELDS[kind]
        missed = mesh_generation - handle_generation
        calls = "garbage_collect() renumbered" if missed == 1 else f"{missed} garbage_collect() calls renumbered"
        through = "" if missed == 1 else " (map it through each call's maps in turn)"
        super().__init__(
            f"{kind} {index} is a stale handle: it was taken before {calls} the mesh, so index {index} "
            f"may now name another {kind}. Use the maps garbage_collect() returned: maps.{field}[{index}] "
            f"is its new index (-1 if it was deleted){through}, then mesh.{kind}(new_index)"
        )
        self.kind = kind
        self.index = index
        self.handle_generation = handle_generation
        self.mesh_generation = mesh_generation


class MeshWarning(UserWarning):
    """Something about the input was changed on the way in (e.g. unreferenced vertices dropped)."""
