"""Shared helpers for the tests of local operations: comparing meshes up to relabelling,
snapshots for "the mesh is exactly as it was", and small hand-made meshes."""

from __future__ import annotations

import numpy as np

import halfedge_edu as hx
from halfedge_edu.core.build import INDEX, build_arrays


def canonical_form(mesh: hx.HalfedgeMesh) -> tuple[np.ndarray, np.ndarray]:
    """``(positions (n, 3), faces (m, 3))`` of the live mesh in a numbering-free form.

    Vertices are sorted by position (x, then y, then z), faces renumbered to match,
    each face rotated so its smallest vertex comes first (keeping its orientation),
    and the faces sorted. Two meshes are the same up to relabelling exactly when their
    canonical forms are equal. Deleted elements are left out, so a mesh and its
    ``garbage_collect()``-ed copy have the same form.

    Attention: needs distinct positions (jitter symmetric meshes first).
    """
    vertices, faces = mesh.to_arrays()
    order = np.lexsort(vertices.T[::-1])                      # by x, then y, then z
    sorted_vertices = vertices[order]
    repeated = (np.diff(sorted_vertices, axis=0) == 0).all(axis=1)
    assert not repeated.any(), "canonical_form needs distinct vertex positions; jitter the mesh"
    rank = np.empty(len(order), dtype=np.int64)
    rank[order] = np.arange(len(order))
    faces = rank[faces]
    first = faces.argmin(axis=1)
    rows = np.arange(len(faces))[:, None]
    faces = faces[rows, (first[:, None] + np.arange(3)[None, :]) % 3]
    faces = faces[np.lexsort(faces.T[::-1])]
    return sorted_vertices, faces


def assert_same_mesh(mesh: hx.HalfedgeMesh, other) -> None:
    """Assert ``mesh`` equals ``other`` (a mesh, or ``(vertices, faces)``) up to relabelling.

    Positions must be equal exactly, not just close.
    """
    if not isinstance(other, hx.HalfedgeMesh):
        other = hx.HalfedgeMesh.from_faces(*other)
    vertices, faces = canonical_form(mesh)
    expected_vertices, expected_faces = canonical_form(other)
    np.testing.assert_array_equal(vertices, expected_vertices)
    np.testing.assert_array_equal(faces, expected_faces)


def snapshot(mesh: hx.HalfedgeMesh) -> dict:
    """Everything a mesh stores (arrays as bytes, with their spare capacity, and counts)."""
    state = {}
    for name, value in vars(mesh).items():
        if name == "_cache":
            continue
        state[name] = (value.dtype.str, value.shape, value.tobytes()) if isinstance(value, np.ndarray) else value
    return state


def assert_unchanged(mesh: hx.HalfedgeMesh, before: dict) -> None:
    """Assert the mesh is bit for bit what :func:`snapshot` saw."""
    after = snapshot(mesh)
    changed = [name for name in before if before[name] != after[name]]
    assert not changed, f"a refused operation changed {changed}"


def counts(mesh: hx.HalfedgeMesh) -> tuple[int, int, int]:
    return mesh.n_vertices, mesh.n_edges, mesh.n_faces


def jittered(mesh: hx.HalfedgeMesh, seed: int = 0, scale: float = 1e-3) -> hx.HalfedgeMesh:
    """The same mesh with every position moved a little (so all positions are distinct)."""
    rng = np.random.default_rng(seed)
    mesh._positions[: mesh.n_vertex_slots] += rng.normal(scale=scale, size=(mesh.n_vertex_slots, 3))
    return mesh


def pillow() -> hx.HalfedgeMesh:
    """Two triangles glued back to back: 3 vertices, 3 edges, 2 faces, closed.

    ``from_faces`` refuses it (two faces on the same three vertices), so it is built
    from the halfedge arrays directly, as hand-made arrays can be: the operations must
    still refuse it.
    """
    return hx.HalfedgeMesh(build_arrays(np.eye(3), np.array([[0, 1, 2], [0, 2, 1]], dtype=INDEX)))


def tent() -> hx.HalfedgeMesh:
    """A tetrahedron 0, 2, 3, 4 whose face (0, 3, 2) is replaced by a fan through vertex 1::

        faces (0, 1, 2), (1, 0, 3), (0, 2, 4), (0, 4, 3), (2, 3, 4)

    Edge 0 (0 - 1) is interior; vertex 0 has degree 4 and vertex 1 is on the boundary,
    but its opposite vertices 2 and 3 are already joined, so it cannot be flipped.
    """
    vertices = [[0, 0, 0], [0.2, 0.2, -1], [1, 0, 0], [0, 1, 0], [0.3, 0.3, 1]]
    return hx.HalfedgeMesh.from_faces(vertices, [[0, 1, 2], [1, 0, 3], [0, 2, 4], [0, 4, 3], [2, 3, 4]])


def open_tetrahedron() -> hx.HalfedgeMesh:
    """A tetrahedron without its bottom face: apex 0 over a triangular hole 1 - 2 - 3."""
    vertices = [[0, 0, 1], [1, 0, 0], [-0.5, 0.8, 0], [-0.5, -0.8, 0]]
    return hx.HalfedgeMesh.from_faces(vertices, [[0, 1, 2], [0, 2, 3], [0, 3, 1]])


_ARRAYS = (
    "_positions", "_vertex_halfedge", "_halfedge_next", "_halfedge_prev", "_halfedge_vertex",
    "_halfedge_face", "_face_halfedge", "_vertex_deleted", "_edge_deleted", "_face_deleted",
)


def assert_replay_gives(before: hx.HalfedgeMesh, after: hx.HalfedgeMesh, log) -> None:
    """Replaying ``log``'s changes on a copy of ``before`` gives ``after`` exactly.

    So the log is complete: no pointer was changed without a line saying so.
    """
    replayed = before.copy()
    log.replay(replayed)
    for name in _ARRAYS:
        np.testing.assert_array_equal(getattr(replayed, name), getattr(after, name), err_msg=name)
    assert counts(replayed) == counts(after)
