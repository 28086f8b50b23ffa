"""Random manifold triangle meshes for property tests (hypothesis), and the shapes they come from.

Import from any test module::

    from tests.strategies import meshes, closed_meshes, open_meshes, build, cases

    @given(meshes())
    def test_something(drawn):
        mesh = build(drawn)          # drawn is (vertices (n, 3) float64, faces (m, 3) int64)

Every drawn mesh is a manifold, consistently oriented triangle mesh (faces CCW seen from
outside) with no unreferenced vertices, at most a few hundred faces, and is connected.
Its vertex numbering, face order and the starting corner of each face are shuffled by
:func:`relabel`, so tests do not depend on the tidy order of the generators.

:func:`cases` draws the same meshes together with what is known about them by
construction (genus, boundary loops), for tests of counts and topology.

The plain shape builders (:func:`tetrahedron`, :func:`grid`, :func:`torus`, ...) are
deterministic and return ``(vertices, faces)`` arrays; ``tests/conftest.py`` wraps
them into named fixtures.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.core.manifold import manifold_report

__all__ = [
    "MeshCase", "annulus", "build", "cases", "closed_cases", "closed_meshes", "compact",
    "disjoint_union", "fan", "grid", "icosphere", "meshes", "octahedron", "open_cases",
    "open_fan", "open_meshes", "relabel", "remove_faces", "square", "tetrahedron",
    "torus", "uv_sphere",
]


@dataclass(frozen=True)
class MeshCase:
    """A drawn mesh and what its construction says about it."""

    name: str
    vertices: np.ndarray           # (n, 3) float64
    faces: np.ndarray              # (m, 3) int64
    genus: int
    n_boundary_loops: int
    n_components: int = 1

    @property
    def arrays(self) -> tuple[np.ndarray, np.ndarray]:
        return self.vertices, self.faces

    @property
    def euler_characteristic(self) -> int:
        return 2 * self.n_components - 2 * self.genus - self.n_boundary_loops


def build(drawn) -> hx.HalfedgeMesh:
    """``HalfedgeMesh.from_faces`` of a drawn ``(vertices, faces)`` pair (or a :class:`MeshCase`)."""
    vertices, faces = drawn.arrays if isinstance(drawn, MeshCase) else drawn
    return hx.HalfedgeMesh.from_faces(vertices, faces)


def _arrays(vertices, faces) -> tuple[np.ndarray, np.ndarray]:
    return np.asarray(vertices, dtype=np.float64).reshape(-1, 3), np.asarray(faces, dtype=np.int64).reshape(-1, 3)


# --------------------------------------------------------------------------------------
# Closed shapes (faces counter-clockwise seen from outside)
# --------------------------------------------------------------------------------------

def tetrahedron() -> tuple[np.ndarray, np.ndarray]:
    """4 vertices, 6 edges, 4 faces; every vertex has degree 3."""
    vertices = [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]]
    faces = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]
    return _arrays(vertices, faces)


def octahedron() -> tuple[np.ndarray, np.ndarray]:
    """6 vertices, 12 edges, 8 faces; every vertex has degree 4."""
    vertices = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
    faces = [
        [0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],
        [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5],
    ]
    return _arrays(vertices, faces)


def icosphere(subdivisions: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """trimesh's icosphere: 20 * 4**subdivisions faces."""
    import trimesh

    sphere = trimesh.creation.icosphere(subdivisions=subdivisions)
    return _arrays(sphere.vertices, sphere.faces)


def uv_sphere(n_around: int = 8, n_rings: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """A latitude-longitude sphere: two poles, ``n_rings`` rings of ``n_around`` vertices.

    Needs ``n_around >= 3`` and ``n_rings >= 1``. Faces: ``2 * n_around * n_rings``.
    """
    azimuth = 2 * np.pi * np.arange(n_around) / n_around
    polar = np.pi * np.arange(1, n_rings + 1) / (n_rings + 1)
    ring_points = np.stack(
        [
            np.outer(np.sin(polar), np.cos(azimuth)),
            np.outer(np.sin(polar), np.sin(azimuth)),
            np.outer(np.cos(polar), np.ones(n_around)),
        ],
        axis=-1,
    ).reshape(-1, 3)
    north, south = 0, 1 + n_rings * n_around
    vertices = np.vstack([[0, 0, 1], ring_points, [0, 0, -1]])

    def ring(k, j):  # vertex j (mod n_around) of ring k, rings counted from the north
        return 1 + k * n_around + j % n_around

    faces = []
    for j in range(n_around):
        faces.append([north, ring(0, j), ring(0, j + 1)])
        for k in range(n_rings - 1):
            upper, lower, lower_next, upper_next = ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1)
            faces += [[upper, lower, lower_next], [upper, lower_next, upper_next]]
        faces.append([south, ring(n_rings - 1, j + 1), ring(n_rings - 1, j)])
    return _arrays(vertices, faces)


def _quads_to_triangles(a, b, c, d, diagonals) -> np.ndarray:
    """Split quads ``a b c d`` (CCW) along ``a-c`` where ``diagonals`` is False, else ``b-d``."""
    a, b, c, d = (np.ravel(x) for x in (a, b, c, d))
    flip = np.ravel(diagonals).astype(bool)
    first = np.where(flip[:, None], np.stack([a, b, d], 1), np.stack([a, b, c], 1))
    second = np.where(flip[:, None], np.stack([b, c, d], 1), np.stack([a, c, d], 1))
    return np.concatenate([first, second])


def torus(n_around: int = 6, n_tube: int = 4, diagonals=None, radii=(2.0, 0.7)) -> tuple[np.ndarray, np.ndarray]:
    """A torus of genus 1: an ``n_around`` x ``n_tube`` grid whose indices wrap both ways.

    Needs both sizes ``>= 3`` (otherwise two quads share two edges). ``diagonals``
    (n_around, n_tube) bool picks each quad's diagonal (default: all ``a-c``).
    """
    big, small = radii
    i, j = np.meshgrid(np.arange(n_around), np.arange(n_tube), indexing="ij")
    theta, phi = 2 * np.pi * i / n_around, 2 * np.pi * j / n_tube
    vertices = np.stack(
        [(big + small * np.cos(phi)) * np.cos(theta), (big + small * np.cos(phi)) * np.sin(theta), small * np.sin(phi)],
        axis=-1,
    ).reshape(-1, 3)

    def index(ii, jj):
        return (ii % n_around) * n_tube + jj % n_tube

    if diagonals is None:
        diagonals = np.zeros((n_around, n_tube), dtype=bool)
    faces = _quads_to_triangles(index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1), diagonals)
    return _arrays(vertices, faces)


# --------------------------------------------------------------------------------------
# Shapes with boundary (faces counter-clockwise seen from +z)
# --------------------------------------------------------------------------------------

def square() -> tuple[np.ndarray, np.ndarray]:
    """The unit square as two triangles sharing the diagonal 0-2::

        3 --- 2
        |   / |
        | /   |
        0 --- 1
    """
    vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
    faces = [[0, 1, 2], [0, 2, 3]]
    return _arrays(vertices, faces)


def grid(n_x: int = 3, n_y: int = 2, diagonals=None) -> tuple[np.ndarray, np.ndarray]:
    """A flat ``n_x`` x ``n_y`` grid of quads, each split in two: a disc, one boundary loop.

    Vertex ``(i, j)`` (``0 <= i <= n_x``, ``0 <= j <= n_y``) is number ``i * (n_y + 1) + j``
    at position ``(i, j, 0)``. ``diagonals`` (n_x, n_y) bool picks each quad's diagonal.
    """
    i, j = np.meshgrid(np.arange(n_x + 1), np.arange(n_y + 1), indexing="ij")
    vertices = np.stack([i, j, np.zeros_like(i)], axis=-1).reshape(-1, 3)
    qi, qj = np.meshgrid(np.arange(n_x), np.arange(n_y), indexing="ij")

    def index(ii, jj):
        return ii * (n_y + 1) + jj

    if diagonals is None:
        diagonals = np.zeros((n_x, n_y), dtype=bool)
    faces = _quads_to_triangles(index(qi, qj), index(qi + 1, qj), index(qi + 1, qj + 1), index(qi, qj + 1), diagonals)
    return _arrays(vertices, faces)


def fan(n_rim: int = 6) -> tuple[np.ndarray, np.ndarray]:
    """A closed fan (a wheel): interior vertex 0 at the origin, ``n_rim >= 3`` rim vertices.

    Face ``k`` is ``[0, 1 + k, 1 + (k + 1) % n_rim]``; rim vertex ``1 + k`` sits at angle
    ``2 pi k / n_rim``, so the ring of vertex 0 is CCW in increasing angle.
    """
    angle = 2 * np.pi * np.arange(n_rim) / n_rim
    vertices = np.vstack([[0, 0, 0], np.stack([np.cos(angle), np.sin(angle), np.zeros(n_rim)], 1)])
    faces = [[0, 1 + k, 1 + (k + 1) % n_rim] for k in range(n_rim)]
    return _arrays(vertices, faces)


def open_fan(n_faces: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """An open fan: ``n_faces >= 1`` triangles around vertex 0, which is on the boundary.

    Rim vertex ``1 + k`` sits at angle ``k * pi / (n_faces + 1)`` (a half disc, CCW).
    """
    angle = np.pi * np.arange(n_faces + 1) / (n_faces + 1)
    vertices = np.vstack([[0, 0, 0], np.stack([np.cos(angle), np.sin(angle), np.zeros(n_faces + 1)], 1)])
    faces = [[0, 1 + k, 2 + k] for k in range(n_faces)]
    return _arrays(vertices, faces)


def annulus(n_around: int = 6, n_radial: int = 1, diagonals=None) -> tuple[np.ndarray, np.ndarray]:
    """A flat ring (genus 0, two boundary loops): ``n_around >= 3`` quads around, ``n_radial`` out.

    Vertex ``(i, j)`` is number ``i * (n_radial + 1) + j`` at angle ``2 pi i / n_around``
    and radius ``1 + j``.
    """
    i, j = np.meshgrid(np.arange(n_around), np.arange(n_radial + 1), indexing="ij")
    theta, radius = 2 * np.pi * i / n_around, 1.0 + j
    vertices = np.stack([radius * np.cos(theta), radius * np.sin(theta), np.zeros_like(theta)], -1).reshape(-1, 3)
    qi, qj = np.meshgrid(np.arange(n_around), np.arange(n_radial), indexing="ij")

    def index(ii, jj):
        return (ii % n_around) * (n_radial + 1) + jj

    if diagonals is None:
        diagonals = np.zeros((n_around, n_radial), dtype=bool)
    # Radius first, then angle: a -> b runs outward, b -> c turns CCW, so faces face +z.
    faces = _quads_to_triangles(index(qi, qj), index(qi, qj + 1), index(qi + 1, qj + 1), index(qi + 1, qj), diagonals)
    return _arrays(vertices, faces)


# --------------------------------------------------------------------------------------
# Editing face lists
# --------------------------------------------------------------------------------------

def compact(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Drop vertices no face uses, keeping the others in order."""
    used = np.zeros(len(vertices), dtype=bool)
    used[faces.ravel()] = True
    new_index = np.cumsum(used) - 1
    return vertices[used].copy(), new_index[faces].astype(np.int64)


def remove_faces(vertices: np.ndarray, faces: np.ndarray, remove) -> tuple[np.ndarray, np.ndarray]:
    """The mesh without the faces ``remove`` (indices or bool mask), compacted."""
    keep = np.ones(len(faces), dtype=bool)
    keep[remove] = False
    return compact(vertices, faces[keep])


def disjoint_union(*pieces) -> tuple[np.ndarray, np.ndarray]:
    """Several ``(vertices, faces)`` pieces side by side in one mesh, shifted apart in x."""
    all_vertices, all_faces, offset, shift = [], [], 0, 0.0
    for vertices, faces in pieces:
        moved = np.array(vertices, dtype=np.float64)
        moved[:, 0] += shift - moved[:, 0].min()
        shift = moved[:, 0].max() + 1.0
        all_vertices.append(moved)
        all_faces.append(np.asarray(faces, dtype=np.int64) + offset)
        offset += len(vertices)
    return np.vstack(all_vertices), np.vstack(all_faces)


def relabel(vertices: np.ndarray, faces: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """The same surface with shuffled numbering: vertex permutation, face order, corner rotation.

    Rotating a face's corners (``[a, b, c] -> [b, c, a]``) keeps its orientation.
    Returns new arrays; ``faces_new`` row ``r`` is a rotation of ``old_to_new[faces[order[r]]]``.
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    new_to_old = rng.permutation(len(vertices))
    old_to_new = np.empty_like(new_to_old)
    old_to_new[new_to_old] = np.arange(len(vertices))
    shuffled = old_to_new[faces[rng.permutation(len(faces))]]
    shift = rng.integers(0, 3, size=len(faces))
    rotated = shuffled[np.arange(len(faces))[:, None], (np.arange(3)[None, :] + shift[:, None]) % 3]
    return vertices[new_to_old].copy(), rotated.astype(np.int64)


def _disc_of_faces(faces: np.ndarray, seed_face: int, size: int) -> np.ndarray:
    """Up to ``size`` faces grown from ``seed_face`` across shared edges (breadth first)."""
    edge_faces: dict[tuple[int, int], list[int]] = {}
    for f, (a, b, c) in enumerate(faces.tolist()):
        for u, v in ((a, b), (b, c), (c, a)):
            edge_faces.setdefault((min(u, v), max(u, v)), []).append(f)
    chosen, frontier = [seed_face], [seed_face]
    taken = {seed_face}
    while frontier and len(chosen) < size:
        f = frontier.pop(0)
        a, b, c = faces[f].tolist()
        for u, v in ((a, b), (b, c), (c, a)):
            for g in edge_faces[(min(u, v), max(u, v))]:
                if g not in taken and len(chosen) < size:
                    taken.add(g)
                    chosen.append(g)
                    frontier.append(g)
    return np.array(chosen)


# --------------------------------------------------------------------------------------
# Strategies
# --------------------------------------------------------------------------------------

_seeds = st.integers(min_value=0, max_value=2**32 - 1)


@st.composite
def _closed_shape(draw) -> MeshCase:
    kind = draw(st.sampled_from(["tetrahedron", "octahedron", "icosphere", "uv_sphere", "torus"]))
    if kind == "tetrahedron":
        return MeshCase(kind, *tetrahedron(), genus=0, n_boundary_loops=0)
    if kind == "octahedron":
        return MeshCase(kind, *octahedron(), genus=0, n_boundary_loops=0)
    if kind == "icosphere":
        return MeshCase(kind, *icosphere(draw(st.integers(0, 1))), genus=0, n_boundary_loops=0)
    if kind == "uv_sphere":
        n_around, n_rings = draw(st.integers(3, 12)), draw(st.integers(1, 6))
        return MeshCase(kind, *uv_sphere(n_around, n_rings), genus=0, n_boundary_loops=0)
    n_around, n_tube = draw(st.integers(3, 10)), draw(st.integers(3, 8))
    rng = np.random.default_rng(draw(_seeds))
    diagonals = rng.random((n_around, n_tube)) < 0.5
    return MeshCase(kind, *torus(n_around, n_tube, diagonals), genus=1, n_boundary_loops=0)


@st.composite
def _open_shape(draw) -> MeshCase:
    kind = draw(st.sampled_from(["grid", "fan", "open_fan", "annulus", "cut_closed"]))
    rng = np.random.default_rng(draw(_seeds))
    if kind == "grid":
        n_x, n_y = draw(st.integers(1, 10)), draw(st.integers(1, 10))
        return MeshCase(kind, *grid(n_x, n_y, rng.random((n_x, n_y)) < 0.5), genus=0, n_boundary_loops=1)
    if kind == "fan":
        return MeshCase(kind, *fan(draw(st.integers(3, 12))), genus=0, n_boundary_loops=1)
    if kind == "open_fan":
        return MeshCase(kind, *open_fan(draw(st.integers(1, 8))), genus=0, n_boundary_loops=1)
    if kind == "annulus":
        n_around, n_radial = draw(st.integers(3, 12)), draw(st.integers(1, 4))
        diagonals = rng.random((n_around, n_radial)) < 0.5
        return MeshCase(kind, *annulus(n_around, n_radial, diagonals), genus=0, n_boundary_loops=2)
    # A closed shape with a disc of faces cut out: one face, the star of a vertex, or a
    # patch grown face by face (kept only if what is left is still manifold).
    closed = draw(_closed_shape())
    vertices, faces = closed.arrays
    how = draw(st.sampled_from(["face", "star", "patch"]))
    remove = np.array([int(rng.integers(len(faces)))])
    if how == "star":
        remove = np.flatnonzero((faces == int(rng.integers(len(vertices)))).any(axis=1))
    elif how == "patch":
        patch = _disc_of_faces(faces, int(remove[0]), int(rng.integers(2, max(3, len(faces) // 2))))
        rest = np.delete(faces, patch, axis=0)
        if manifold_report(compact(vertices, rest)[1]) and _is_connected(rest):
            remove = patch
    cut_vertices, cut_faces = remove_faces(vertices, faces, remove)
    # A patch need not be a disc (it may wrap around a torus), so the loops and the genus
    # of what is left are counted here, independently of the library.
    loops = _count_boundary_loops(cut_faces)
    sides = np.concatenate([cut_faces[:, [0, 1]], cut_faces[:, [1, 2]], cut_faces[:, [2, 0]]])
    chi = len(cut_vertices) - len(np.unique(np.sort(sides, axis=1), axis=0)) + len(cut_faces)
    genus = (2 - loops - chi) // 2
    return MeshCase(f"{closed.name}-minus-{how}", cut_vertices, cut_faces, genus=genus, n_boundary_loops=loops)


def _is_connected(faces: np.ndarray) -> bool:
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    used = np.unique(faces)
    remap = np.searchsorted(used, faces)
    rows = remap.ravel()
    cols = remap[:, [1, 2, 0]].ravel()
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(used), len(used)))
    return connected_components(graph, directed=False)[0] == 1


def _count_boundary_loops(faces: np.ndarray) -> int:
    """Boundary loops of a manifold face list, counted independently of the library."""
    directed = {(int(a), int(b)) for a, b in np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])}
    boundary_next = {b: a for a, b in directed if (b, a) not in directed}   # reversed boundary edges
    loops, seen = 0, set()
    for start in boundary_next:
        if start in seen:
            continue
        loops += 1
        v = start
        while v not in seen:
            seen.add(v)
            v = boundary_next[v]
    return loops


def _shuffled(case_strategy):
    @st.composite
    def shuffled(draw) -> MeshCase:
        case = draw(case_strategy)
        rng = np.random.default_rng(draw(_seeds))
        vertices, faces = relabel(case.vertices, case.faces, rng)
        if draw(st.booleans()):
            # A small jitter keeps positions generic (no exactly flat or symmetric spots).
            vertices = vertices + rng.normal(scale=1e-3, size=vertices.shape)
        return MeshCase(case.name, vertices, faces, case.genus, case.n_boundary_loops, case.n_components)

    return shuffled()


def closed_cases() -> st.SearchStrategy[MeshCase]:
    """Closed connected meshes (spheres of several kinds, tori) as :class:`MeshCase`."""
    return _shuffled(_closed_shape())


def open_cases() -> st.SearchStrategy[MeshCase]:
    """Connected meshes with boundary (grids, fans, annuli, closed meshes with a hole)."""
    return _shuffled(_open_shape())


def cases() -> st.SearchStrategy[MeshCase]:
    """Either :func:`closed_cases` or :func:`open_cases`."""
    return st.one_of(closed_cases(), open_cases())


def closed_meshes() -> st.SearchStrategy[tuple[np.ndarray, np.ndarray]]:
    """``(vertices (n, 3) float64, faces (m, 3) int64)`` of a closed connected manifold mesh."""
    return closed_cases().map(lambda case: case.arrays)


def open_meshes() -> st.SearchStrategy[tuple[np.ndarray, np.ndarray]]:
    """``(vertices, faces)`` of a connected manifold mesh with at least one boundary loop."""
    return open_cases().map(lambda case: case.arrays)


def meshes() -> st.SearchStrategy[tuple[np.ndarray, np.ndarray]]:
    """``(vertices, faces)`` from :func:`closed_meshes` or :func:`open_meshes`."""
    return st.one_of(closed_meshes(), open_meshes())
