"""Laplacian smoothing: the course's rules by hand, the loop version, trimesh as a reference."""

from __future__ import annotations

import sys

import numpy as np
import pytest
import trimesh
from hypothesis import given
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.algorithms import smooth, smooth_reference
from tests import strategies as shapes
from tests.strategies import build, closed_meshes, meshes, open_meshes


def _square_fan(center):
    """Four rim vertices around vertex 0 at ``center``: a closed fan with a boundary rim."""
    rim = [[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]]
    faces = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]]
    return hx.HalfedgeMesh.from_faces([center] + rim, faces)


def test_one_step_moves_a_vertex_onto_the_mean_of_its_neighbours():
    mesh = _square_fan([0.2, 0.1, 1.0])
    smoothed = smooth(mesh)
    assert np.array_equal(smoothed.positions[0], [0, 0, 0])
    assert np.array_equal(smoothed.positions[1:], mesh.positions[1:])    # the rim is fixed


def test_step_moves_part_of_the_way():
    mesh = _square_fan([0.2, 0.1, 1.0])
    assert np.allclose(smooth(mesh, step=0.25).positions[0], 0.75 * np.array([0.2, 0.1, 1.0]))


def test_every_vertex_uses_the_old_positions_of_its_neighbours(tetrahedron):
    # Jacobi: on a tetrahedron each vertex goes to the mean of the other three *old*
    # positions. (Gauss-Seidel would let vertex 1 already see vertex 0's new position.)
    old = tetrahedron.positions
    expected = (old.sum(axis=0) - old) / 3
    assert np.allclose(smooth(tetrahedron).positions, expected, atol=1e-15)


def test_result_does_not_depend_on_vertex_numbering():
    vertices, faces = shapes.icosphere(1)
    vertices = vertices + np.random.default_rng(3).normal(scale=0.05, size=vertices.shape)
    permutation = np.random.default_rng(4).permutation(len(vertices))
    inverse = np.argsort(permutation)
    first = smooth(hx.HalfedgeMesh.from_faces(vertices, faces), 3)
    second = smooth(hx.HalfedgeMesh.from_faces(vertices[permutation], inverse[faces]), 3)
    assert np.allclose(first.positions[permutation], second.positions, atol=1e-14)


def test_boundary_along_the_loop_by_hand():
    mesh = _square_fan([0.2, 0.1, 1.0])
    smoothed = smooth(mesh, boundary="along")
    old = mesh.positions
    # Interior vertex 0: all four rim neighbours. Rim vertex k: its two rim neighbours.
    assert np.allclose(smoothed.positions[0], old[1:].mean(axis=0))
    for k in range(1, 5):
        before, after = 1 + (k - 2) % 4, 1 + k % 4
        assert np.allclose(smoothed.positions[k], (old[before] + old[after]) / 2)


@given(open_meshes(), st.integers(1, 4))
def test_fixed_boundary_does_not_move(drawn, iterations):
    mesh = build(drawn)
    rim = mesh.vertex_is_boundary()
    smoothed = smooth(mesh, iterations)
    assert np.array_equal(smoothed.positions[rim], mesh.positions[rim])


def test_a_flat_patch_keeps_its_outline_only_with_the_fixed_boundary(grid):
    outline = grid.positions[grid.vertex_is_boundary()]
    assert np.array_equal(smooth(grid, 5).positions[grid.vertex_is_boundary()], outline)
    along = smooth(grid, 5, boundary="along").positions[grid.vertex_is_boundary()]
    assert np.ptp(along[:, 0]) < np.ptp(outline[:, 0])          # the rim shrank


@given(meshes(), st.sampled_from(["uniform", "cotangent"]), st.sampled_from(["fixed", "along"]),
       st.sampled_from([1.0, 0.5, -0.3]), st.integers(0, 3))
def test_fast_version_equals_the_loop(drawn, weights, boundary, step, iterations):
    mesh = build(drawn)
    fast = smooth(mesh, iterations, weights=weights, boundary=boundary, step=step)
    loop = smooth_reference(mesh, iterations, weights=weights, boundary=boundary, step=step)
    assert np.allclose(fast.positions, loop.positions, rtol=1e-12, atol=1e-12)


def test_both_versions_agree_once_smoothing_has_made_corners_meet():
    """A shuffled annulus (found by hypothesis): one cotangent step with the boundary
    moving along its loops puts vertices 2 and 6 (and 1 and 15, 9 and 13, 4 and 5) on
    the same point up to rounding. The two versions' positions then differ by 2e-16,
    and before flat triangles counted as flat, the cotangents at those corners were
    ratios of rounding errors: the second step moved vertices 3, 7 and 10 apart by up
    to 1.6."""
    # The drawn positions exactly, rounding noise included: the case depends on it.
    vertices = np.array([
        [3.0, 0.0, 0.0], [-4.0, 4.8985872e-16, 0.0], [4.0, 0.0, 0.0], [-3.0, 3.6739404e-16, 0.0],
        [1.0, 0.0, 0.0], [6.123234e-17, 1.0, 0.0], [2.4492936e-16, 4.0, 0.0], [1.2246468e-16, 2.0, 0.0],
        [-5.5109106e-16, -3.0, 0.0], [-1.8369702e-16, -1.0, 0.0], [1.8369702e-16, 3.0, 0.0],
        [-2.0, 2.4492936e-16, 0.0], [-3.6739404e-16, -2.0, 0.0], [-1.0, 1.2246468e-16, 0.0], [2.0, 0.0, 0.0],
        [-7.34788079e-16, -4.0, 0.0]])
    faces = [[0, 12, 8], [0, 8, 15], [10, 3, 7], [14, 12, 0], [9, 14, 4], [2, 10, 0], [13, 5, 7], [1, 10, 6],
             [3, 11, 7], [0, 7, 14], [3, 15, 8], [12, 9, 13], [1, 3, 10], [15, 3, 1], [7, 0, 10], [4, 7, 5],
             [13, 7, 11], [14, 7, 4], [2, 0, 15], [10, 2, 6], [12, 14, 9], [13, 11, 12], [11, 3, 8], [12, 11, 8]]
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    once = smooth(mesh, 1, weights="cotangent", boundary="along")
    meeting = np.linalg.norm(once.positions[[2, 1, 9, 4]] - once.positions[[6, 15, 13, 5]], axis=1)
    assert meeting.max() < 1e-12                      # the corners have met: the case this test is about
    fast = smooth(mesh, 2, weights="cotangent", boundary="along")
    loop = smooth_reference(mesh, 2, weights="cotangent", boundary="along")
    assert np.allclose(fast.positions, loop.positions, rtol=1e-12, atol=1e-12)


@given(meshes(), st.sampled_from(["uniform", "cotangent"]), st.sampled_from(["fixed", "along"]))
def test_the_input_is_not_modified(drawn, weights, boundary):
    mesh = build(drawn)
    before = mesh.copy()
    smoothed = smooth(mesh, 2, weights=weights, boundary=boundary)
    assert smoothed is not mesh
    for name in ("positions", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face",
                 "vertex_halfedge", "face_halfedge"):
        assert np.array_equal(getattr(mesh, name), getattr(before, name)), name
    assert np.array_equal(smoothed.face_vertices(), mesh.face_vertices())
    smoothed.validate()


@given(closed_meshes(), st.integers(1, 4), st.sampled_from([1.0, 0.5]))
def test_matches_trimesh_filter_laplacian_on_closed_meshes(drawn, iterations, step):
    # trimesh: v += lamb * (mean of neighbours - v), every vertex, no volume fix-up.
    tm = trimesh.Trimesh(*drawn, process=False)
    trimesh.smoothing.filter_laplacian(tm, lamb=step, iterations=iterations, volume_constraint=False)
    assert np.allclose(smooth(build(drawn), iterations, step=step).positions, tm.vertices, atol=1e-12)


@given(open_meshes(), st.integers(1, 3))
def test_matches_trimesh_with_pinned_boundary_on_open_meshes(drawn, iterations):
    mesh = build(drawn)
    tm = trimesh.Trimesh(*drawn, process=False)
    pinned = np.flatnonzero(mesh.vertex_is_boundary())
    operator = trimesh.smoothing.laplacian_calculation(tm, pinned_vertices=pinned)
    trimesh.smoothing.filter_laplacian(tm, lamb=1.0, iterations=iterations, volume_constraint=False,
                                       laplacian_operator=operator)
    assert np.allclose(smooth(mesh, iterations).positions, tm.vertices, atol=1e-12)


def _jittered_triangle_grid(n=6, jitter=0.08, seed=0):
    """A flat grid of near-equilateral triangles, interior vertices jittered in the plane."""
    rows = [[(i + 0.5 * (j % 2), j * np.sqrt(3) / 2, 0.0) for i in range(n)] for j in range(n)]
    vertices = np.array(rows).reshape(-1, 3)
    faces = []
    for j in range(n - 1):
        for i in range(n - 1):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i, (j + 1) * n + i + 1
            faces += [[a, b, d], [a, d, c]] if j % 2 else [[a, b, c], [b, d, c]]
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    interior = ~mesh.vertex_is_boundary()
    noise = np.random.default_rng(seed).uniform(-jitter, jitter, size=(int(interior.sum()), 2))
    mesh.positions[interior, :2] += noise
    return mesh


def test_cotangent_weights_leave_a_flat_mesh_in_place():
    # Cotangent weights reproduce linear functions, so on a flat mesh with acute
    # triangles every weighted mean is the vertex itself; uniform weights still move it.
    mesh = _jittered_triangle_grid()
    assert np.allclose(smooth(mesh, 3, weights="cotangent").positions, mesh.positions, atol=1e-12)
    assert not np.allclose(smooth(mesh, 3).positions, mesh.positions, atol=1e-3)


def test_cotangent_weights_survive_obtuse_and_zero_area_triangles():
    vertices = [[0, 0, 0], [1, 0, 0], [0.5, 0.01, 0], [0.5, -1, 0.3], [2, 0, 0]]
    faces = [[0, 1, 2], [1, 0, 3], [1, 4, 2], [3, 4, 1]]
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    for boundary in ("fixed", "along"):
        result = smooth(mesh, 2, weights="cotangent", boundary=boundary)
        assert np.isfinite(result.positions).all()
        assert np.allclose(result.positions, smooth_reference(mesh, 2, weights="cotangent", boundary=boundary).positions)
    flat = hx.HalfedgeMesh.from_faces([[0, 0, 0], [1, 0, 0], [2, 0, 0], [1, 1, 0]], [[0, 1, 3], [1, 2, 3], [0, 3, 2]])
    assert np.isfinite(smooth(flat, 2, weights="cotangent", boundary="along").positions).all()


def test_zero_iterations_return_an_equal_copy(icosphere):
    copy = smooth(icosphere, 0)
    assert copy is not icosphere
    assert np.array_equal(copy.positions, icosphere.positions)


def test_deleted_vertices_keep_their_slots():
    mesh = hx.HalfedgeMesh.from_faces(*shapes.grid(2, 2))
    corner = next(f.index for f in mesh.faces if 0 in [v.index for v in f.vertices()])
    mesh.delete_face(corner)
    mesh.delete_vertex(0)
    smoothed = smooth(mesh, 2, boundary="along")
    assert smoothed.n_vertex_slots == mesh.n_vertex_slots
    assert np.array_equal(smoothed.positions[0], mesh.positions[0])


def test_progress_bar_is_optional(icosphere, monkeypatch):
    with_bar = smooth(icosphere, 3, progress=True)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)          # as if tqdm were not installed
    without_tqdm = smooth(icosphere, 3, progress=True)
    assert np.array_equal(with_bar.positions, smooth(icosphere, 3).positions)
    assert np.array_equal(without_tqdm.positions, with_bar.positions)


@pytest.mark.parametrize("arguments", [
    {"iterations": -1}, {"iterations": 1.5}, {"weights": "mean"}, {"boundary": "free"},
    {"step": 0.0}, {"step": float("nan")},
])
def test_bad_arguments_are_refused(square, arguments):
    with pytest.raises(ValueError):
        smooth(square, **arguments)
    with pytest.raises(ValueError):
        smooth_reference(square, **arguments)
