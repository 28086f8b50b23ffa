"""Every algorithm works on a mesh that keeps isolated vertices (the bunny file has 1113).

Loading keeps every vertex of the file at its index; the vertices no face uses have no
halfedge. The algorithms must run on such a mesh, leave those vertices alone where they
keep vertex numbers, and give a mesh that validates.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.algorithms import loop_subdivide, remesh, simplify, smooth, vertex_normals
from halfedge_edu.core.ops import collapse, flip, split

BUNNY = Path(__file__).resolve().parents[2] / "halfedge_edu" / "data" / "stanford-bunny.obj"


@pytest.fixture(scope="module")
def bunny() -> hx.HalfedgeMesh:
    return hx.load(BUNNY)


@pytest.fixture(scope="module")
def small_bunny(bunny) -> hx.HalfedgeMesh:
    """A few thousand faces, with the isolated vertices put back after simplifying."""
    return simplify(bunny, target_faces=3000)


def test_the_bunny_keeps_its_isolated_vertices_and_validates(bunny):
    isolated = np.flatnonzero(bunny.vertex_halfedge == -1)
    assert len(isolated) == 1113
    bunny.validate()
    vertex = bunny.vertex(int(isolated[0]))
    assert vertex.halfedge is None or int(vertex.halfedge) == -1
    compact_vertices, _ = bunny.to_arrays(compact=True)
    assert len(compact_vertices) == 34834


def test_normals_leave_isolated_vertices_finite(bunny):
    normals = vertex_normals(bunny)
    assert normals.shape == (35947, 3) and np.isfinite(normals).all()


def test_smoothing_keeps_isolated_vertices_in_place(bunny):
    smoothed = smooth(bunny, iterations=2)
    isolated = bunny.vertex_halfedge == -1
    positions = smoothed.positions if hasattr(smoothed, "positions") else np.asarray(smoothed)
    assert np.array_equal(positions[isolated], bunny.positions[isolated])
    assert not np.array_equal(positions[~isolated], bunny.positions[~isolated])


def test_simplify_runs_on_the_bunny_with_isolated_vertices(small_bunny):
    small_bunny.validate()
    assert small_bunny.n_faces <= 3000


def test_loop_and_remesh_run_on_a_mesh_with_isolated_vertices(small_bunny):
    vertices, faces = small_bunny.to_arrays(compact=True)
    with_isolated = hx.HalfedgeMesh.from_faces(np.vstack([[[9.0, 9.0, 9.0]], vertices]), faces + 1)
    assert with_isolated.vertex_halfedge[0] == -1
    loop_subdivide(with_isolated, 1).validate()
    remesh(with_isolated, iterations=1).validate()


def test_local_operations_work_beside_isolated_vertices(bunny):
    mesh = bunny.copy()
    interior = [e.index for e in mesh.edges if not e.is_boundary][:30]
    flip(mesh, interior[0])
    split(mesh, interior[10])
    collapse(mesh, interior[20])
    mesh.validate()
