"""The answer of ``can_flip`` / ``can_split`` / ``can_collapse``, argument checking, and the
quadrilateral around an edge that flip and split both name.

Every local operation is *check, then act*: the ``can_*`` function looks at the mesh
without changing it and returns an :class:`OpCheck`; the operation itself calls the same
check first and raises :class:`~halfedge_edu.core.errors.TopologyError` with the same
reason if it fails, so a refused operation never touches the mesh.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..elements import Edge, Halfedge, _Handle
from ..errors import TopologyError

if TYPE_CHECKING:
    from ..mesh import HalfedgeMesh


class OpCheck:
    """Whether a local operation is allowed: truthy when it is, falsy when refused.

    Attributes:
        allowed: True or False (also what ``bool(check)`` gives).
        rule: short name of the rule that refused the operation (for example
            ``"link-condition"``), or None when it is allowed.
        reason: a sentence naming the elements involved and the rule, for a student
            to act on; for an allowed operation, a sentence saying so.
        elements: ``(kind, index)`` pairs of the elements the reason is about, so a
            notebook can highlight them, e.g. ``(("edge", 5), ("vertex", 11))``.
    """

    __slots__ = ("allowed", "rule", "reason", "elements")

    def __init__(self, allowed: bool, reason: str, rule: str | None = None, elements: tuple = ()):
        self.allowed = allowed
        self.reason = reason
        self.rule = rule
        self.elements = elements

    @classmethod
    def ok(cls, reason: str, elements: tuple = ()) -> "OpCheck":
        return cls(True, reason, None, elements)

    @classmethod
    def refuse(cls, rule: str, reason: str, elements: tuple = ()) -> "OpCheck":
        return cls(False, reason, rule, elements)

    def __bool__(self) -> bool:
        return self.allowed

    def error(self) -> TopologyError:
        """The :class:`TopologyError` an operation raises for this refusal.

        The error carries the same ``reason``, plus ``rule`` and ``elements``.
        """
        return TopologyError(self.reason, rule=self.rule, elements=self.elements)

    def __repr__(self) -> str:
        if self.allowed:
            return f"OpCheck(allowed: {self.reason})"
        return f"OpCheck(refused by {self.rule!r}: {self.reason})"


def edge_argument(mesh: "HalfedgeMesh", edge, operation: str) -> tuple[int, int]:
    """Turn the ``edge`` a user passed into ``(edge index e, halfedge h)``.

    ``edge`` may be an :class:`Edge` handle or an int (then ``h = 2e``, the edge's
    own halfedge) or a :class:`Halfedge` handle (then ``h`` is that halfedge, which
    gives collapse its direction).

    Raises:
        IndexError: no such edge, or it was deleted by an earlier operation.
        TypeError: a vertex or face handle, or something that is not an index.
        ValueError: a handle of another mesh.
    """
    if isinstance(edge, _Handle):
        if edge.mesh is not mesh:
            raise ValueError(f"{operation}: {edge!r} belongs to another mesh")
        if isinstance(edge, Halfedge):
            h = edge.index
            if not 0 <= h < 2 * mesh._n_edge_slots:
                raise IndexError(f"{operation}: there is no halfedge {h}")
            if mesh._edge_deleted[h >> 1]:
                raise IndexError(
                    f"{operation}: halfedge {h} was deleted (its edge {h >> 1} was removed by an "
                    f"earlier operation; indices are compacted by garbage_collect())"
                )
            return h >> 1, h
        if not isinstance(edge, Edge):
            raise TypeError(f"{operation} works on an edge (or a halfedge), not on {edge!r}")
    elif isinstance(edge, bool) or not hasattr(edge, "__index__"):
        raise TypeError(f"{operation} needs an edge, an edge index or a halfedge, not {edge!r}")
    e = edge.__index__()
    if not 0 <= e < mesh._n_edge_slots:
        last = mesh._n_edge_slots - 1
        raise IndexError(f"{operation}: there is no edge {e}: edges are numbered 0 to {last}")
    if mesh._edge_deleted[e]:
        raise IndexError(
            f"{operation}: edge {e} was deleted by an earlier operation "
            f"(indices are compacted by garbage_collect())"
        )
    return e, 2 * e


def position_argument(mesh: "HalfedgeMesh", e: int, position, operation: str) -> np.ndarray:
    """Check a user's ``position`` (None, or three finite numbers) before anything changes.

    Returns:
        (3,) the point; for None, the midpoint of edge ``e``.

    Raises:
        ValueError: not three numbers, or not finite.
    """
    if position is None:
        origin_of, positions = mesh._halfedge_vertex.item, mesh._positions
        return 0.5 * (positions[origin_of(2 * e)] + positions[origin_of(2 * e + 1)])
    try:
        point = np.array(position, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{operation}: position must be three numbers (x, y, z), not {position!r}") from None
    if point.shape != (3,):
        raise ValueError(f"{operation}: position must be three numbers (x, y, z), not shape {point.shape}")
    if not np.isfinite(point).all():
        raise ValueError(f"{operation}: position must be finite, not {tuple(point)}")
    return point


class Quad(NamedTuple):
    """The two triangles beside an edge, named as in the pictures of ``flip.py`` and ``split.py``.

    ``h0`` runs ``v0 -> v1`` in ``f0 = (h0, h2, h3)``; its twin ``h1`` runs ``v1 -> v0`` in
    ``f1 = (h1, h4, h5)``; ``v2`` is opposite the edge in ``f0`` and ``v3`` in ``f1``.
    Where ``h1`` is a boundary halfedge, ``f1`` and ``v3`` are -1 and ``h4``, ``h5`` are
    its neighbours along the boundary loop.
    """

    h0: int
    h1: int
    h2: int
    h3: int
    h4: int
    h5: int
    v0: int
    v1: int
    v2: int
    v3: int
    f0: int
    f1: int

    def names(self) -> dict[str, tuple[str, int]]:
        """Name -> ``(kind, index)`` for every element, in order, for ``OperationLog.name``."""
        kinds = {"h": "halfedge", "v": "vertex", "f": "face"}
        return {name: (kinds[name[0]], index) for name, index in zip(self._fields, self)}


def quad_around(mesh: "HalfedgeMesh", h0: int) -> Quad:
    """Gather the :class:`Quad` of the edge of halfedge ``h0``, ``h0`` being its ``h0``. Constant work."""
    next_of, prev_of = mesh._halfedge_next.item, mesh._halfedge_prev.item
    origin_of, face_of = mesh._halfedge_vertex.item, mesh._halfedge_face.item
    h1 = h0 ^ 1
    h2, h3, h4, h5 = next_of(h0), prev_of(h0), next_of(h1), prev_of(h1)
    f1 = face_of(h1)
    v3 = origin_of(h5) if f1 >= 0 else -1
    return Quad(h0, h1, h2, h3, h4, h5, origin_of(h0), origin_of(h1), origin_of(h3), v3, face_of(h0), f1)
