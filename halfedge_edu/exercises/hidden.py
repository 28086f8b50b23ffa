"""Meshes for the hidden cases: made from a grading run's seed, never shown in a chapter.

Every check takes ``seed=None`` (the public cases its chapter's check cell shows) or an
int: then it runs only hidden cases, built here from ``harness.hidden_rng(seed)``. They
are the same kinds of case as the public ones (closed meshes, boundaries, low and high
degrees) on other meshes, numberings, positions and steps, so an answer that is right
by its course's text passes them, and an answer fitted to the public cases does not.

    rng = hidden_rng(seed)
    vertices, faces = grid(3, 4, rng)            # a flat, jittered patch with one boundary loop
    vertices, faces = renumbered(vertices, faces, rng)
    mesh = flipped(sample("icosphere", subdivisions=2), 8, rng)   # other degrees than 5 and 6
"""

from __future__ import annotations

import numpy as np

from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.core.ops import can_flip, flip
from halfedge_edu.data import sample

__all__ = ["closed_mesh", "flipped", "grid", "jittered", "renumbered", "CLOSED_SHAPES"]

#: Closed sample meshes a hidden case may start from, with the words its name uses.
CLOSED_SHAPES: dict[str, dict] = {
    "tetrahedron": {}, "cube": {}, "octahedron": {},
    "icosphere(1)": {"subdivisions": 1}, "icosphere(2)": {"subdivisions": 2},
}


def closed_mesh(shape: str) -> HalfedgeMesh:
    """The closed sample mesh named in :data:`CLOSED_SHAPES` (``"icosphere(2)"`` and so on)."""
    return sample(shape.split("(")[0], **CLOSED_SHAPES[shape])


def grid(rows: int, columns: int, rng: np.random.Generator, amount: float = 0.15) -> tuple[np.ndarray, np.ndarray]:
    """A flat patch of ``rows x columns`` squares, each cut into two triangles along a
    random diagonal, its inner vertices nudged in the plane and a little out of it.

    Returns ``(vertices (V, 3) float, faces (2 * rows * columns, 3) int)``, counter-clockwise
    seen from +z; one boundary loop, corners of degree 2 or 3.
    """
    xs, ys = np.meshgrid(np.arange(columns + 1, dtype=np.float64), np.arange(rows + 1, dtype=np.float64))
    vertices = np.column_stack([xs.ravel(), ys.ravel(), np.zeros(xs.size)])   # (V, 3)
    inner = (xs.ravel() % columns != 0) & (ys.ravel() % rows != 0)            # (V,) bool
    vertices[inner] += amount * rng.uniform(-1.0, 1.0, (int(inner.sum()), 3))
    faces = []
    for r in range(rows):
        for c in range(columns):
            a, b = r * (columns + 1) + c, r * (columns + 1) + c + 1
            d, e = a + columns + 1, b + columns + 1                           # the row above
            faces += [[a, b, e], [a, e, d]] if rng.integers(0, 2) else [[a, b, d], [b, e, d]]
    return vertices, np.asarray(faces, dtype=np.int64)


def renumbered(vertices, faces, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """The same surface with its vertices renumbered, its faces reordered and each face's
    starting corner rotated (orientation kept)."""
    vertices, faces = np.asarray(vertices, dtype=np.float64), np.asarray(faces, dtype=np.int64)
    new_number = rng.permutation(len(vertices))                               # old vertex -> new
    new_vertices = np.empty_like(vertices)
    new_vertices[new_number] = vertices
    turns = rng.integers(0, 3, len(faces))
    rotated = np.array([np.roll(face, -int(k)) for face, k in zip(faces, turns)])
    return new_vertices, new_number[rotated][rng.permutation(len(faces))]


def jittered(mesh: HalfedgeMesh, rng: np.random.Generator, amount: float) -> HalfedgeMesh:
    """A copy of ``mesh`` with every vertex nudged (a symmetric shape can hide a wrong weight)."""
    mesh = mesh.copy()
    mesh.positions[:] += amount * rng.standard_normal(mesh.positions.shape)
    return mesh


def flipped(mesh: HalfedgeMesh, count: int, rng: np.random.Generator) -> HalfedgeMesh:
    """A compact copy of ``mesh`` after ``count`` random allowed flips: other degrees, same shape."""
    work = mesh.copy()
    for _ in range(count):
        edges = [e for e in rng.permutation(work.n_edge_slots).tolist()
                 if not work.edge_deleted[e] and not work.edge(e).is_boundary and can_flip(work, e)]
        if not edges:
            break
        flip(work, edges[0])
    return HalfedgeMesh.from_faces(*work.to_arrays())
