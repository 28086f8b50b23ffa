"""The halfedge mesh: flat numpy arrays inside, light element handles outside.

Storage (the model is pmp-library's ``SurfaceMesh``)::

    positions         (V, 3) float64   where each vertex is
    vertex_halfedge   (V,)   int32     one outgoing halfedge (the boundary one, if any)
    halfedge_vertex   (H,)   int32     the vertex a halfedge leaves (its origin, or tail)
    halfedge_next     (H,)   int32     the next halfedge around the same face (CCW)
    halfedge_prev     (H,)   int32     the previous one
    halfedge_face     (H,)   int32     its face, or -1 for a boundary halfedge
    face_halfedge     (F,)   int32     one halfedge of the face
    *_deleted         bool             flags set by local operations

There is no ``twin`` array and no ``edge`` array: edge ``e`` owns halfedges ``2e`` and
``2e + 1``, so ``twin(h) = h ^ 1`` and ``edge(h) = h >> 1``. That halves the bookkeeping
and means a twin can never be missing.

Local operations delete elements by setting a flag; indices of everything else stay
put until :meth:`HalfedgeMesh.garbage_collect` compacts the arrays. The arrays have
spare capacity at the end, so adding an element is constant work (amortized).

The public arrays (``mesh.halfedge_next`` and friends) are *views* of the live slots;
writing into them edits the mesh. Attention: after changing connectivity by hand, call
``mesh.topology_changed()`` so cached one-rings and adjacency are rebuilt. Algorithms read them directly; students mostly use
the handles (``mesh.halfedge(0).next.twin.vertex``).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .build import INDEX, HalfedgeArrays, build_arrays, check_input, restore_unreferenced
from .build import drop_unreferenced as _drop_unreferenced
from . import ops
from .elements import Edge, Face, Halfedge, Vertex
from .errors import MeshInvariantError
from .ops.check import OpCheck
from .rings import RingWalk, walk_rings


class GarbageCollectMaps(NamedTuple):
    """Old-index -> new-index maps returned by :meth:`HalfedgeMesh.garbage_collect`.

    Each is an int array over the *old* slots; deleted elements map to -1.
    """

    vertices: np.ndarray
    halfedges: np.ndarray
    edges: np.ndarray
    faces: np.ndarray


class _ElementList:
    """The live elements of one kind, for ``for v in mesh.vertices`` and ``len(...)``.

    A snapshot of the live indices, like the handles it gives: kept across a
    renumbering ``garbage_collect()``, its handles raise ``StaleHandleError``.
    """

    def __init__(self, mesh: "HalfedgeMesh", kind: type, deleted: np.ndarray):
        self._mesh = mesh
        self._kind = kind
        self._live = np.flatnonzero(~deleted)
        self._generation = mesh._generation

    def __len__(self) -> int:
        return len(self._live)

    def __iter__(self):
        return (self._handle(i) for i in self._live.tolist())

    def __getitem__(self, position: int):
        return self._handle(int(self._live[position]))

    def _handle(self, index: int):
        """The handle of ``index``, of the generation the list was taken in (so stale if that is past)."""
        handle = self._kind(self._mesh, index)
        handle._generation = self._generation
        return handle

    def __repr__(self) -> str:
        return f"<{len(self)} live {self._kind.__name__.lower()}s>"


class _LiveElements:
    """``mesh.vertices`` and friends: the live elements of one kind, as an :class:`_ElementList`."""

    def __init__(self, kind: type, deleted: str):
        self.kind = kind
        self.deleted = deleted  # the name of the mesh's (n_slots,) "is it deleted" array
        self.__doc__ = f"The live {kind.__name__.lower()}s, as :class:`{kind.__name__}` handles."

    def __get__(self, mesh: "HalfedgeMesh | None", owner: type | None = None) -> "_ElementList | _LiveElements":
        if mesh is None:
            return self
        return _ElementList(mesh, self.kind, getattr(mesh, self.deleted))


def _grown(array: np.ndarray, capacity: int, fill) -> np.ndarray:
    """A copy of ``array`` with room for ``capacity`` rows, the new rows set to ``fill``."""
    bigger = np.full((capacity,) + array.shape[1:], fill, dtype=array.dtype)
    bigger[: len(array)] = array
    return bigger


class _LiveSlots:
    """One of the mesh's public arrays: a view of the slots in use of its storage array.

    ``mesh.halfedge_next`` is ``mesh._halfedge_next[: mesh.n_halfedge_slots]``: the storage
    array has spare capacity at the end, which the view leaves out. Writing into the
    view edits the mesh.
    """

    #: kind -> (the mesh's count of slots in use, slots per counted element): a halfedge
    #: array has two slots per edge.
    _COUNTS = {"vertex": ("_n_vertex_slots", 1), "halfedge": ("_n_edge_slots", 2),
               "edge": ("_n_edge_slots", 1), "face": ("_n_face_slots", 1)}

    def __init__(self, kind: str, doc: str):
        self.count, self.per_element = self._COUNTS[kind]
        self.__doc__ = doc

    def __set_name__(self, owner: type, name: str) -> None:
        self.storage = "_" + name  # positions -> _positions, halfedge_next -> _halfedge_next

    def __get__(self, mesh: "HalfedgeMesh | None", owner: type | None = None) -> "np.ndarray | _LiveSlots":
        if mesh is None:
            return self
        return getattr(mesh, self.storage)[: self.per_element * getattr(mesh, self.count)]


class HalfedgeMesh:
    """A manifold triangle mesh stored as halfedges. Build one with :meth:`from_faces`.

    Attention: indices are stable under local operations (deleted elements are only
    flagged) and are compacted by :meth:`garbage_collect`.
    """

    # ----------------------------------------------------------------------------------
    # Construction
    # ----------------------------------------------------------------------------------

    def __init__(self, arrays: HalfedgeArrays):
        """Wrap already-built arrays. Most code wants :meth:`from_faces` instead."""
        n_vertices = len(arrays.vertex_halfedge)
        n_halfedges = len(arrays.halfedge_next)
        n_faces = len(arrays.face_halfedge)
        self._positions = np.array(arrays.positions, dtype=np.float64).reshape(-1, 3)
        self._vertex_halfedge = arrays.vertex_halfedge.astype(INDEX, copy=False)
        self._halfedge_next = arrays.halfedge_next.astype(INDEX, copy=False)
        self._halfedge_prev = arrays.halfedge_prev.astype(INDEX, copy=False)
        self._halfedge_vertex = arrays.halfedge_vertex.astype(INDEX, copy=False)
        self._halfedge_face = arrays.halfedge_face.astype(INDEX, copy=False)
        self._face_halfedge = arrays.face_halfedge.astype(INDEX, copy=False)
        self._vertex_deleted = np.zeros(n_vertices, dtype=bool)
        self._edge_deleted = np.zeros(n_halfedges // 2, dtype=bool)
        self._face_deleted = np.zeros(n_faces, dtype=bool)
        # Slots in use (live + deleted); arrays may be longer (spare capacity).
        self._n_vertex_slots = n_vertices
        self._n_edge_slots = n_halfedges // 2
        self._n_face_slots = n_faces
        self._n_deleted_vertices = 0
        self._n_deleted_edges = 0
        self._n_deleted_faces = 0
        #: Bumped by every change of connectivity, so derived arrays know when to refresh.
        self.topology_version = 0
        self._generation = 0
        self._cache: dict[str, tuple[int, object]] = {}

    @classmethod
    def from_faces(
        cls,
        vertices,
        faces,
        *,
        face_lines=None,
        source: str | None = None,
        drop_unreferenced: bool = False,
    ) -> "HalfedgeMesh":
        """Build a mesh from vertex positions and triangles.

        Args:
            vertices: (n, 3) positions.
            faces: (m, 3) vertex indices, 0-based, counter-clockwise seen from outside.
            face_lines: optional (m,) the file line each face came from, for messages.
            source: optional file name, for messages.
            drop_unreferenced: False (the default) keeps every vertex at its input
                index: vertex ``i`` of ``vertices`` is ``mesh.vertex(i)``, and a vertex no
                face uses is an isolated vertex (no halfedge; ``validate`` accepts it), as
                in pmp-library and OpenMesh. True drops those vertices with a
                :class:`MeshWarning` and renumbers the rest in their order.

        Raises:
            MeshInputError: the input is not a manifold, consistently oriented triangle
                mesh; the message names the face, edge or vertex (and the line).
        """
        all_positions, face_array = check_input(vertices, faces, face_lines, source)
        positions, face_array, kept = _drop_unreferenced(all_positions, face_array, warn=drop_unreferenced)
        # Errors name vertices by ``kept``: the caller's numbers, not the compacted ones.
        arrays = build_arrays(positions, face_array, face_lines, source, vertex_ids=kept)
        if drop_unreferenced:
            return cls(arrays)
        return cls(restore_unreferenced(arrays, all_positions, kept))

    @classmethod
    def from_trimesh(cls, tm) -> "HalfedgeMesh":
        """Build from a ``trimesh.Trimesh`` (its vertices and faces, as they are)."""
        return cls.from_faces(np.asarray(tm.vertices), np.asarray(tm.faces))

    def copy(self) -> "HalfedgeMesh":
        """An independent copy (same indices, deleted slots included)."""
        twin = object.__new__(HalfedgeMesh)
        for name, value in self.__dict__.items():
            twin.__dict__[name] = value.copy() if isinstance(value, np.ndarray) else value
        twin._cache = {}
        return twin

    # ----------------------------------------------------------------------------------
    # The arrays (views of the slots in use)
    # ----------------------------------------------------------------------------------

    positions = _LiveSlots("vertex", "(n_vertex_slots, 3) float64 positions; rows of deleted vertices are stale.")
    vertex_halfedge = _LiveSlots("vertex", "(n_vertex_slots,) an outgoing halfedge of each vertex (boundary one if any).")
    vertex_deleted = _LiveSlots("vertex", "(n_vertex_slots,) True for vertices flagged deleted.")
    halfedge_next = _LiveSlots("halfedge", "(n_halfedge_slots,) next halfedge around the face (or boundary loop).")
    halfedge_prev = _LiveSlots("halfedge", "(n_halfedge_slots,) previous halfedge around the face (or boundary loop).")
    halfedge_vertex = _LiveSlots("halfedge", "(n_halfedge_slots,) the vertex each halfedge leaves (its origin).")
    halfedge_face = _LiveSlots("halfedge", "(n_halfedge_slots,) face of each halfedge; -1 on the boundary.")
    edge_deleted = _LiveSlots("edge", "(n_edge_slots,) True for edges (and so both their halfedges) flagged deleted.")
    face_halfedge = _LiveSlots("face", "(n_face_slots,) one halfedge of each face.")
    face_deleted = _LiveSlots("face", "(n_face_slots,) True for faces flagged deleted.")

    @property
    def halfedge_deleted(self) -> np.ndarray:
        """(n_halfedge_slots,) a halfedge is deleted when its edge is (a fresh array)."""
        return np.repeat(self.edge_deleted, 2)

    # ----------------------------------------------------------------------------------
    # Counts
    # ----------------------------------------------------------------------------------

    @property
    def n_vertices(self) -> int:
        """Live vertices."""
        return self._n_vertex_slots - self._n_deleted_vertices

    @property
    def n_edges(self) -> int:
        return self._n_edge_slots - self._n_deleted_edges

    @property
    def n_halfedges(self) -> int:
        return 2 * self.n_edges

    @property
    def n_faces(self) -> int:
        return self._n_face_slots - self._n_deleted_faces

    @property
    def n_vertex_slots(self) -> int:
        """Live and deleted vertices: the length of the vertex arrays."""
        return self._n_vertex_slots

    @property
    def n_edge_slots(self) -> int:
        return self._n_edge_slots

    @property
    def n_halfedge_slots(self) -> int:
        return 2 * self._n_edge_slots

    @property
    def n_face_slots(self) -> int:
        return self._n_face_slots

    @property
    def has_garbage(self) -> bool:
        """True when some element is flagged deleted (see :meth:`garbage_collect`)."""
        return bool(self._n_deleted_vertices or self._n_deleted_edges or self._n_deleted_faces)

    @property
    def euler_characteristic(self) -> int:
        """V - E + F: 2 for a sphere, 0 for a torus, 1 for a disc."""
        return self.n_vertices - self.n_edges + self.n_faces

    @property
    def n_boundary_loops(self) -> int:
        """How many separate boundary loops (holes) the mesh has."""
        return len(self.boundary_loops())

    @property
    def n_components(self) -> int:
        """How many connected pieces the mesh has."""
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        ends = self.edge_vertices()[~self.edge_deleted]           # (E, 2)
        n = self._n_vertex_slots
        graph = coo_matrix((np.ones(len(ends)), (ends[:, 0], ends[:, 1])), shape=(n, n))
        _, labels = connected_components(graph, directed=False)
        return len(np.unique(labels[~self.vertex_deleted]))

    @property
    def genus(self) -> int:
        """Number of handles, from V - E + F = sum over pieces of (2 - 2g - b).

        A sphere or a disc has genus 0, a torus 1. For several pieces it is the total.
        """
        return (2 * self.n_components - self.n_boundary_loops - self.euler_characteristic) // 2

    @property
    def is_closed(self) -> bool:
        """True when the mesh has no boundary."""
        live_halfedges = self.halfedge_deleted == False  # noqa: E712 (array comparison)
        return not bool((self.halfedge_face[live_halfedges] == -1).any())

    def __repr__(self) -> str:
        return (
            f"HalfedgeMesh(vertices={self.n_vertices}, edges={self.n_edges}, "
            f"faces={self.n_faces}, boundary_loops={self.n_boundary_loops})"
        )

    # ----------------------------------------------------------------------------------
    # Element handles
    # ----------------------------------------------------------------------------------

    #: How many times ``garbage_collect()`` renumbered the mesh (a class default, so a
    #: mesh made without ``__init__`` has one too). Handles remember it: see ``generation``.
    _generation = 0

    @property
    def generation(self) -> int:
        """How many times :meth:`garbage_collect` has renumbered this mesh.

        Every handle remembers the generation it was made in and raises
        :class:`~halfedge_edu.core.errors.StaleHandleError` when used in a later one.
        """
        return self._generation

    def _check_index(self, kind: str, index: int, n_slots: int, deleted: np.ndarray) -> int:
        index = int(index)
        if not 0 <= index < n_slots:
            plural = {"vertex": "vertices"}.get(kind, kind + "s")
            raise IndexError(f"there is no {kind} {index}: {plural} are numbered 0 to {n_slots - 1}")
        if deleted[index]:
            raise IndexError(f"{kind} {index} was deleted (indices are compacted by garbage_collect())")
        return index

    def vertex(self, index: int) -> Vertex:
        return Vertex(self, self._check_index("vertex", index, self._n_vertex_slots, self._vertex_deleted))

    def halfedge(self, index: int) -> Halfedge:
        return Halfedge(self, self._check_index("halfedge", index, 2 * self._n_edge_slots, _HalfedgeDeleted(self)))

    def edge(self, index: int) -> Edge:
        return Edge(self, self._check_index("edge", index, self._n_edge_slots, self._edge_deleted))

    def face(self, index: int) -> Face:
        return Face(self, self._check_index("face", index, self._n_face_slots, self._face_deleted))

    vertices = _LiveElements(Vertex, "vertex_deleted")
    halfedges = _LiveElements(Halfedge, "halfedge_deleted")
    edges = _LiveElements(Edge, "edge_deleted")
    faces = _LiveElements(Face, "face_deleted")

    def find_halfedge(self, i: int, j: int) -> Halfedge | None:
        """The halfedge from vertex ``i`` to vertex ``j``, or None if they are not joined."""
        start = int(self._vertex_halfedge[int(i)])
        if start < 0:
            return None
        h = start
        while True:
            if self._halfedge_vertex[h ^ 1] == j:
                return Halfedge(self, h)
            h = int(self._halfedge_prev[h]) ^ 1
            if h == start:
                return None

    def find_edge(self, i: int, j: int) -> Edge | None:
        """The edge between vertices ``i`` and ``j``, or None."""
        h = self.find_halfedge(i, j)
        return None if h is None else h.edge

    # ----------------------------------------------------------------------------------
    # Whole-mesh arrays (what algorithms use instead of Python loops)
    # ----------------------------------------------------------------------------------

    def _cached(self, name: str, compute):
        """Keep a topology-derived array until the connectivity changes."""
        hit = self._cache.get(name)
        if hit is not None and hit[0] == self.topology_version:
            return hit[1]
        value = compute()
        self._cache[name] = (self.topology_version, value)
        return value

    def halfedge_tip(self) -> np.ndarray:
        """(n_halfedge_slots,) the vertex each halfedge points to."""
        return self.halfedge_vertex[np.arange(2 * self._n_edge_slots) ^ 1]

    def edge_vertices(self) -> np.ndarray:
        """(n_edge_slots, 2) the two vertices of each edge: origin and tip of halfedge 2e."""
        return self.halfedge_vertex.reshape(-1, 2)

    def face_vertices(self) -> np.ndarray:
        """(n_face_slots, 3) the three vertices of each face in CCW order; -1 rows if deleted.

        The first vertex is the origin of the face's ``halfedge``, so a freshly built
        mesh gives back its input rows exactly.
        """
        h0 = self.face_halfedge
        h1 = self.halfedge_next[h0]
        h2 = self.halfedge_next[h1]
        corners = np.stack([self.halfedge_vertex[h0], self.halfedge_vertex[h1], self.halfedge_vertex[h2]], axis=1)
        corners[self.face_deleted] = -1
        return corners

    def vertex_degrees(self) -> np.ndarray:
        """(n_vertex_slots,) how many edges meet at each vertex (0 for deleted ones)."""
        live = ~self.halfedge_deleted
        return np.bincount(self.halfedge_vertex[live], minlength=self._n_vertex_slots)

    def vertex_is_boundary(self) -> np.ndarray:
        """(n_vertex_slots,) True for vertices on a boundary loop (False for isolated ones)."""
        live = ~self.vertex_deleted
        result = np.zeros(self._n_vertex_slots, dtype=bool)
        outgoing = self.vertex_halfedge[live]
        # An isolated vertex has halfedge -1, which must not be read as the last halfedge.
        result[live] = (outgoing >= 0) & (self.halfedge_face[outgoing] == -1)
        return result

    def one_rings(self) -> RingWalk:
        """Every live vertex's outgoing halfedges in CCW order, in CSR form (cached).

        ``walk.halfedges[walk.offsets[i]:walk.offsets[i+1]]`` is the ring of
        ``walk.vertices[i]``; tips of those halfedges are its neighbours.
        """

        def compute() -> RingWalk:
            live = np.flatnonzero(~self.vertex_deleted)
            degree = self.vertex_degrees()[live]
            return walk_rings(live, self.vertex_halfedge, self.halfedge_prev, degree)

        return self._cached("one_rings", compute)

    def vertex_adjacency(self) -> tuple[np.ndarray, np.ndarray]:
        """CSR vertex adjacency over all vertex slots: ``(offsets (V+1,), neighbors)``.

        The neighbours of vertex ``v`` are ``neighbors[offsets[v]:offsets[v+1]]``, in CCW
        order; deleted vertices have none. Cached until the connectivity changes.
        """

        def compute():
            walk = self.one_rings()
            counts = np.zeros(self._n_vertex_slots, dtype=np.int64)
            counts[walk.vertices] = np.diff(walk.offsets)
            offsets = np.zeros(self._n_vertex_slots + 1, dtype=np.int64)
            np.cumsum(counts, out=offsets[1:])
            # Live vertices are walked in increasing order, so the rows line up.
            neighbors = self.halfedge_vertex[walk.halfedges ^ 1]
            return offsets, neighbors

        return self._cached("vertex_adjacency", compute)

    def boundary_loops(self) -> list[np.ndarray]:
        """Each boundary loop as an array of its halfedges, in ``next`` order."""

        def compute():
            live = ~self.halfedge_deleted
            on_boundary = np.flatnonzero(live & (self.halfedge_face == -1))
            seen = np.zeros(2 * self._n_edge_slots, dtype=bool)
            loops = []
            for start in on_boundary:
                if seen[start]:
                    continue
                loop = [int(start)]
                seen[start] = True
                h = int(self._halfedge_next[start])
                while h != start and len(loop) <= len(on_boundary):
                    loop.append(h)
                    seen[h] = True
                    h = int(self._halfedge_next[h])
                loops.append(np.array(loop, dtype=INDEX))
            return loops

        return self._cached("boundary_loops", compute)

    # ----------------------------------------------------------------------------------
    # Export
    # ----------------------------------------------------------------------------------

    def to_arrays(self, *, compact: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """Copies ``(V (n, 3) float64, F (m, 3) int64)`` of the live mesh.

        Vertices and faces keep their relative order; deleted ones are left out.
        Isolated vertices (no halfedge, e.g. a file's vertices that no face uses) stay,
        so a mesh loaded from a file without deletions gives back the file's numbering;
        ``compact=True`` leaves them out too.

        Raises ``MeshInvariantError`` ("deleted-reference") when a live face uses a
        deleted vertex (a flag set by hand), instead of returning a face with -1 in it.
        """
        live_vertices = ~self.vertex_deleted
        if compact:
            live_vertices &= self.vertex_halfedge >= 0
        new_index = np.full(self._n_vertex_slots, -1, dtype=np.int64)
        new_index[live_vertices] = np.arange(int(live_vertices.sum()))
        live_faces = np.flatnonzero(~self.face_deleted)
        faces = new_index[self.face_vertices()[live_faces]]  # (m, 3) int64
        broken = np.flatnonzero((faces < 0).any(axis=1))
        if len(broken):
            face = int(live_faces[broken[0]])
            raise MeshInvariantError("deleted-reference", ("face", face),
                                     f"face {face} uses a deleted vertex; run mesh.validate() to see where")
        return self.positions[live_vertices].copy(), faces

    def to_trimesh(self):
        """A ``trimesh.Trimesh`` of the live mesh (``process=False``: nothing merged)."""
        import trimesh

        vertices, faces = self.to_arrays()
        return trimesh.Trimesh(vertices=vertices, faces=faces, process=False)

    def to_pyvista(self):
        """A ``pyvista.PolyData`` of the live mesh (imports pyvista only now)."""
        import pyvista

        vertices, faces = self.to_arrays()
        return pyvista.PolyData.from_regular_faces(vertices, faces)

    # ----------------------------------------------------------------------------------
    # Growing and deleting (used by local operations)
    # ----------------------------------------------------------------------------------

    def topology_changed(self) -> None:
        """Say that connectivity changed (cached one-rings, adjacency, loops become stale).

        The operations in ``core/ops/`` call this themselves; call it after writing into the
        pointer arrays by hand.
        """
        self.topology_version += 1

    _touch = topology_changed

    def add_vertex(self, position) -> int:
        """Append an isolated vertex and return its index.

        Attention: the new vertex has no halfedge (-1) until an operation links it;
        ``validate()`` rejects it until then.
        """
        v = self._n_vertex_slots
        if v == len(self._vertex_halfedge):
            capacity = max(8, 2 * v)
            self._positions = _grown(self._positions, capacity, 0.0)
            self._vertex_halfedge = _grown(self._vertex_halfedge, capacity, -1)
            self._vertex_deleted = _grown(self._vertex_deleted, capacity, False)
        self._positions[v] = position
        self._vertex_halfedge[v] = -1
        self._vertex_deleted[v] = False
        self._n_vertex_slots += 1
        self._touch()
        return v

    def add_edge(self, a: int, b: int) -> int:
        """Append an edge from vertex ``a`` to ``b`` and return its index ``e``.

        Halfedge ``2e`` runs a -> b and ``2e + 1`` runs b -> a; their next, prev and face
        are -1 until the caller links them.
        """
        e = self._n_edge_slots
        if e == len(self._edge_deleted):
            capacity = max(8, 2 * e)
            self._edge_deleted = _grown(self._edge_deleted, capacity, False)
            for name in ("_halfedge_next", "_halfedge_prev", "_halfedge_vertex", "_halfedge_face"):
                setattr(self, name, _grown(getattr(self, name), 2 * capacity, -1))
        h = 2 * e
        self._halfedge_vertex[h] = a
        self._halfedge_vertex[h + 1] = b
        for array in (self._halfedge_next, self._halfedge_prev, self._halfedge_face):
            array[h] = -1
            array[h + 1] = -1
        self._edge_deleted[e] = False
        self._n_edge_slots += 1
        self._touch()
        return e

    def add_face(self, halfedge: int) -> int:
        """Append a face whose ``halfedge`` is given and return its index.

        Attention: the caller sets ``halfedge_face`` of the face's three halfedges.
        """
        f = self._n_face_slots
        if f == len(self._face_halfedge):
            capacity = max(8, 2 * f)
            self._face_halfedge = _grown(self._face_halfedge, capacity, -1)
            self._face_deleted = _grown(self._face_deleted, capacity, False)
        self._face_halfedge[f] = halfedge
        self._face_deleted[f] = False
        self._n_face_slots += 1
        self._touch()
        return f

    def delete_vertex(self, v: int) -> None:
        """Flag vertex ``v`` deleted (its slot stays until garbage_collect())."""
        if not self._vertex_deleted[v]:
            self._vertex_deleted[v] = True
            self._n_deleted_vertices += 1
            self._touch()

    def delete_edge(self, e: int) -> None:
        """Flag edge ``e`` (and so both its halfedges) deleted."""
        if not self._edge_deleted[e]:
            self._edge_deleted[e] = True
            self._n_deleted_edges += 1
            self._touch()

    def delete_face(self, f: int) -> None:
        """Flag face ``f`` deleted."""
        if not self._face_deleted[f]:
            self._face_deleted[f] = True
            self._n_deleted_faces += 1
            self._touch()

    def garbage_collect(self) -> GarbageCollectMaps:
        """Remove deleted elements, renumber the rest in order, and return the maps.

        After this, indices run 0..n-1 with no gaps and every pointer is renumbered.
        Elements keep their relative order, so an untouched mesh is unchanged.

        Attention: handles taken before a collection that removed something are stale
        afterwards (their index may name another element): using one raises
        :class:`~halfedge_edu.core.errors.StaleHandleError`. Take fresh handles, or map
        old indices with the returned maps: ``mesh.edge(maps.edges[old])``. A collection
        with nothing to remove renumbers nothing and leaves handles usable.
        """
        renumbers = bool(self.vertex_deleted.any() or self.edge_deleted.any() or self.face_deleted.any())
        vertex_map = _old_to_new(self.vertex_deleted)
        edge_map = _old_to_new(self.edge_deleted)
        face_map = _old_to_new(self.face_deleted)
        halfedge_map = np.full(2 * self._n_edge_slots, -1, dtype=np.int64)
        live_edges = ~self.edge_deleted
        halfedge_map[0::2][live_edges] = 2 * edge_map[live_edges]
        halfedge_map[1::2][live_edges] = 2 * edge_map[live_edges] + 1

        # Appending -1 to a map makes "-1 -> -1" work: index -1 reads the last entry.
        def through(mapping: np.ndarray, values: np.ndarray) -> np.ndarray:
            return np.append(mapping, -1)[values].astype(INDEX)

        live_v = ~self.vertex_deleted
        live_h = np.repeat(live_edges, 2)
        live_f = ~self.face_deleted
        self._positions = self.positions[live_v].copy()
        self._vertex_halfedge = through(halfedge_map, self.vertex_halfedge[live_v])
        self._halfedge_next = through(halfedge_map, self.halfedge_next[live_h])
        self._halfedge_prev = through(halfedge_map, self.halfedge_prev[live_h])
        self._halfedge_vertex = through(vertex_map, self.halfedge_vertex[live_h])
        self._halfedge_face = through(face_map, self.halfedge_face[live_h])
        self._face_halfedge = through(halfedge_map, self.face_halfedge[live_f])
        self._vertex_deleted = np.zeros(len(self._positions), dtype=bool)
        self._edge_deleted = np.zeros(len(self._halfedge_next) // 2, dtype=bool)
        self._face_deleted = np.zeros(len(self._face_halfedge), dtype=bool)
        self._n_vertex_slots = len(self._positions)
        self._n_edge_slots = len(self._edge_deleted)
        self._n_face_slots = len(self._face_halfedge)
        self._n_deleted_vertices = self._n_deleted_edges = self._n_deleted_faces = 0
        if renumbers:
            self._generation += 1  # every handle taken before now is stale
        self._touch()
        return GarbageCollectMaps(vertex_map, halfedge_map, edge_map, face_map)

    # ----------------------------------------------------------------------------------
    # Checking, and the local operations (they live in core/ops/)
    # ----------------------------------------------------------------------------------

    def validate(self) -> None:
        """Check every invariant of the structure; raise :class:`MeshInvariantError` if one fails.

        The error's ``rule`` names the invariant and ``element`` the first element
        that breaks it. Returns None when the mesh is sound.
        """
        from .validate import validate

        validate(self)

    def validate_around(self, vertices=(), halfedges=(), edges=(), faces=()) -> None:
        """Check every rule but deletion-count on these elements and two rings around them.

        The cheap check after one local operation: its work does not grow with the mesh
        (hundreds of times cheaper than :meth:`validate` on a million faces). Raises
        ``MeshInvariantError`` like :meth:`validate`.
        """
        from .validate import validate_around

        validate_around(self, vertices, halfedges, edges, faces)

    # The local operations live in core/ops/, one readable file each (flip.py, split.py,
    # collapse.py); they belong to the mesh, as in pmp-library, so these methods simply
    # hand over. ops/ reads the mesh's arrays and writes them through one Writer.

    def can_flip(self, edge) -> OpCheck:
        """Whether :meth:`flip` is allowed on ``edge``: truthy result with a ``.reason``."""
        return ops.can_flip(self, edge)

    def flip(self, edge) -> Edge:
        """Turn ``edge`` inside its two triangles; returns the same edge. See ``core/ops/flip.py``."""
        return ops.flip(self, edge)

    def can_split(self, edge) -> OpCheck:
        """Whether :meth:`split` is allowed on ``edge``: truthy result with a ``.reason``."""
        return ops.can_split(self, edge)

    def split(self, edge, position=None) -> Vertex:
        """Split ``edge`` at ``position`` (midpoint by default); returns the new vertex."""
        return ops.split(self, edge, position)

    def can_collapse(self, edge) -> OpCheck:
        """Whether :meth:`collapse` is allowed (the link condition and boundary rules)."""
        return ops.can_collapse(self, edge)

    def collapse(self, edge, position=None, *, check_link: bool = True) -> Vertex:
        """Merge the two ends of ``edge`` at ``position`` (midpoint by default); returns the survivor.

        ``check_link=False`` is a teaching switch: it skips the link condition, so the
        result may not be a valid mesh (``validate()`` says why). See ``core/ops/collapse.py``.
        """
        return ops.collapse(self, edge, position, check_link=check_link)


def _old_to_new(deleted: np.ndarray) -> np.ndarray:
    """Map each old slot to its new index (live ones in order), or -1 if deleted."""
    mapping = np.full(len(deleted), -1, dtype=np.int64)
    live = ~deleted
    mapping[live] = np.arange(int(live.sum()))
    return mapping


class _HalfedgeDeleted:
    """Index-like view "is halfedge h deleted?" without building a full array."""

    def __init__(self, mesh: HalfedgeMesh):
        self._edge_deleted = mesh._edge_deleted

    def __getitem__(self, h: int) -> bool:
        return bool(self._edge_deleted[h >> 1])
