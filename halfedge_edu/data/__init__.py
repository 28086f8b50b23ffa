"""The bundled sample meshes: ``sample(name)`` builds one, ``samples()`` lists them.

The small teaching meshes are made by code below, so you can read exactly which
vertices and faces they have. ``spot`` and ``bunny`` are read from the OBJ files in this
folder (see README.md here for their origin and credits).

Two samples cannot be halfedge meshes at all, because they are not manifold (chapter
04); for those ``sample`` returns a ``RawMesh(vertices, faces)`` of plain arrays, to
give to ``manifold_report`` or ``repair_faces``.

Attention: each call builds a new mesh (meshes are edited in place, so sharing one
would let one notebook cell change another's); only the arrays read from files are
cached.
"""

from __future__ import annotations

import difflib
from functools import lru_cache
from importlib import resources
from typing import NamedTuple

import numpy as np

from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.io.obj import read_obj

__all__ = ["RawMesh", "sample", "samples"]


class RawMesh(NamedTuple):
    """A face list that is not manifold, so it cannot become a ``HalfedgeMesh``.

    Attributes:
        vertices: (n, 3) float64 positions.
        faces: (m, 3) int64 triangles, 0-based.
    """

    vertices: np.ndarray
    faces: np.ndarray


_DESCRIPTIONS = {
    "tetrahedron": "4 vertices, 4 faces: the smallest closed mesh",
    "cube": "8 vertices, 12 triangles; vertex 0 (and 7) has degree 3, and edge 0 (0 -> 4) touches it",
    "octahedron": "6 vertices, 8 faces, every vertex of degree 4",
    "icosphere": "a subdivided icosahedron on the unit sphere; sample('icosphere', subdivisions=2)",
    "open_patch": "a flat 4 x 4 grid of vertices: 18 triangles, one boundary loop, 4 interior vertices",
    "single_collapse": "two interior vertices of degree 6 and the ring around them; edge 0 (0 -> 1) joins them",
    "strip": "3 triangles in a row: every vertex on the boundary",
    "figure8": "a strip of 8 triangles; edge 0 (2 -> 7) is interior but both its ends are on the boundary, "
    "so collapsing it would pinch the strip into a figure 8",
    "lone_triangle": "a single triangle: 3 vertices, 3 edges, 1 face",
    "spot": "Spot the cow by Keenan Crane (CC0): closed, genus 0, 2930 vertices, 5856 faces",
    "bunny": "the Stanford bunny: 34834 vertices, 69451 faces, holes in its base (unused vertices dropped)",
    "nonmanifold_edge": "RawMesh: three triangles on one edge (edge-non-manifold, but every vertex has one fan)",
    "nonmanifold_vertex": "RawMesh: two closed tetrahedra touching at vertex 0 (vertex-non-manifold, every edge has 2 faces)",
}


def samples() -> dict[str, str]:
    """The names of the sample meshes, each with a one-line description."""
    return dict(_DESCRIPTIONS)


def sample(name: str, **options) -> HalfedgeMesh | RawMesh:
    """Build the sample mesh called ``name`` (see ``samples()`` for the list).

    Options: ``sample("icosphere", subdivisions=2)`` (0 is the plain icosahedron).

    Returns:
        A new ``HalfedgeMesh``; for ``"nonmanifold_edge"`` and ``"nonmanifold_vertex"``
        a ``RawMesh`` of arrays, since those cannot be halfedge meshes.

    Raises:
        ValueError: an unknown name (the message suggests the closest one).
        TypeError: an option this sample does not take.
    """
    if name not in _MAKERS:
        close = difflib.get_close_matches(str(name), list(_MAKERS), n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        raise ValueError(f"no sample called {name!r}.{hint} Available: {', '.join(_MAKERS)}")
    vertices, faces = _MAKERS[name](**options)
    vertices = np.array(vertices, dtype=np.float64)
    faces = np.array(faces, dtype=np.int64)
    if name in ("nonmanifold_edge", "nonmanifold_vertex"):
        return RawMesh(vertices, faces)
    return HalfedgeMesh.from_faces(vertices, faces)


# --------------------------------------------------------------------------------------
# The meshes made by code. Each returns (vertices, faces), faces counter-clockwise seen
# from outside (closed meshes) or from +z (flat ones).
# --------------------------------------------------------------------------------------

def _tetrahedron():
    vertices = [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]]
    faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]
    return vertices, faces


def _cube():
    # Vertex i sits at (bit 0, bit 1, bit 2) of i: 0 = (0,0,0), 7 = (1,1,1).
    vertices = [[i & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)]
    # Each square's diagonal avoids corners 0 and 7, so they keep degree 3; the other
    # six corners have degree 5. Face 0 starts at vertex 0, so edge 0 is (0, 4).
    faces = [
        [0, 4, 2], [2, 4, 6],  # x = 0
        [7, 5, 3], [3, 5, 1],  # x = 1
        [0, 1, 4], [1, 5, 4],  # y = 0
        [7, 3, 6], [3, 2, 6],  # y = 1
        [0, 2, 1], [1, 2, 3],  # z = 0
        [7, 6, 5], [5, 6, 4],  # z = 1
    ]
    return vertices, faces


def _octahedron():
    vertices = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
    faces = [
        [0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],  # upper half, around +z
        [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5],  # lower half, around -z
    ]
    return vertices, faces


def _icosphere(subdivisions: int = 2):
    import trimesh

    if not isinstance(subdivisions, (int, np.integer)) or subdivisions < 0:
        raise ValueError(f"subdivisions must be a whole number >= 0, not {subdivisions!r}")
    sphere = trimesh.creation.icosphere(subdivisions=int(subdivisions), radius=1.0)
    return sphere.vertices, sphere.faces


def _open_patch():
    # Vertex 4 * row + column at (column, row, 0); each square cut along the same diagonal.
    vertices = [[column, row, 0] for row in range(4) for column in range(4)]
    faces = []
    for row in range(3):
        for column in range(3):
            a = 4 * row + column  # lower left corner of the square
            faces += [[a, a + 1, a + 5], [a, a + 5, a + 4]]
    return vertices, faces


def _single_collapse():
    # On a triangular lattice: vertex 0 at the origin, vertex 1 one step to the right,
    # and the 8 lattice points around them, counter-clockwise from (2, 0).
    h = np.sqrt(3) / 2
    ring = [[2, 0], [1.5, h], [0.5, h], [-0.5, h], [-1, 0], [-0.5, -h], [0.5, -h], [1.5, -h]]
    vertices = [[0, 0, 0], [1, 0, 0]] + [[x, y, 0] for x, y in ring]  # ring vertices are 2..9
    faces = [
        [0, 1, 4],  # face 0: its first edge 0 -> 1 is the edge to collapse
        [0, 4, 5], [0, 5, 6], [0, 6, 7], [0, 7, 8],
        [0, 8, 1],
        [1, 2, 3], [1, 3, 4], [1, 8, 9], [1, 9, 2],
    ]
    return vertices, faces


def _strip():
    vertices = [[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [1.5, 1, 0], [2, 0, 0]]
    faces = [[0, 1, 2], [1, 3, 2], [1, 4, 3]]
    return vertices, faces


def _figure8():
    # Bottom row 0..4 at y = 0, top row 5..9 at y = 1; 4 squares, 2 triangles each.
    vertices = [[x, 0, 0] for x in range(5)] + [[x, 1, 0] for x in range(5)]
    faces = [
        [2, 7, 1],  # face 0: its first edge 2 -> 7 is the middle rung
        [1, 7, 6],
        [0, 1, 6], [0, 6, 5],
        [2, 3, 8], [2, 8, 7],
        [3, 4, 9], [3, 9, 8],
    ]
    return vertices, faces


def _lone_triangle():
    return [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]


def _nonmanifold_edge():
    # Edge (0, 1) on the z axis; three pages at 120 degrees around it.
    angles = np.radians([0, 120, 240])
    pages = [[np.cos(a), np.sin(a), 0.5] for a in angles]
    vertices = [[0, 0, 0], [0, 0, 1]] + pages
    faces = [[0, 2, 1], [0, 3, 1], [0, 4, 1]]
    return vertices, faces


def _nonmanifold_vertex():
    # Two tetrahedra, tips at vertex 0: one points down onto it, one points up from it.
    h = np.sqrt(3) / 2
    below = [[1, 0, -1], [-0.5, h, -1], [-0.5, -h, -1]]  # vertices 1, 2, 3
    above = [[1, 0, 1], [-0.5, h, 1], [-0.5, -h, 1]]  # vertices 4, 5, 6
    vertices = [[0, 0, 0]] + below + above
    faces = [
        [0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2],  # lower cone, base facing down
        [0, 5, 4], [0, 6, 5], [0, 4, 6], [4, 5, 6],  # upper cone, base facing up
    ]
    return vertices, faces


@lru_cache(maxsize=None)
def _bundled(filename: str, drop_unreferenced: bool) -> tuple[np.ndarray, np.ndarray]:
    """Read an OBJ file shipped in this folder once; the arrays are cached read-only."""
    with resources.files(__name__).joinpath(filename).open("rb") as file:
        data = read_obj(file)
    vertices, faces = data.vertices, data.faces
    if drop_unreferenced:  # keep only the vertices some face uses, in their order
        used, faces = np.unique(faces, return_inverse=True)
        vertices, faces = vertices[used], faces.reshape(-1, 3)
    vertices.flags.writeable = False
    faces.flags.writeable = False
    return vertices, faces


def _spot():
    return _bundled("spot.obj", drop_unreferenced=False)


def _bunny():
    # The file has 1113 vertices that no face uses; a sample should load quietly, so
    # they are dropped here without a warning (hx.load on the file does warn).
    return _bundled("stanford-bunny.obj", drop_unreferenced=True)


_MAKERS = {
    "tetrahedron": _tetrahedron,
    "cube": _cube,
    "octahedron": _octahedron,
    "icosphere": _icosphere,
    "open_patch": _open_patch,
    "single_collapse": _single_collapse,
    "strip": _strip,
    "figure8": _figure8,
    "lone_triangle": _lone_triangle,
    "spot": _spot,
    "bunny": _bunny,
    "nonmanifold_edge": _nonmanifold_edge,
    "nonmanifold_vertex": _nonmanifold_vertex,
}
