"""Quadric error simplification: the quadric algebra, the target, and what must survive."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.algorithms.simplify import (
    accumulate,
    face_quadrics,
    optimal_points,
    quadric_cost,
    simplify,
)


def test_face_quadric_measures_area_times_squared_distance_to_the_plane():
    # A right triangle of area 2 in the plane z = 1.
    vertices = np.array([[0.0, 0, 1], [2, 0, 1], [0, 2, 1]])
    quadric = face_quadrics(vertices, np.array([[0, 1, 2]]))
    points = np.array([[5.0, -3, 1], [0, 0, 4], [1, 1, -1]])
    expected = 2.0 * (points[:, 2] - 1.0) ** 2
    assert np.allclose(quadric_cost(np.repeat(quadric, 3, axis=0), points), expected)


def test_optimal_point_of_a_cube_corner_is_the_corner():
    # Three faces meeting at the corner (1, 1, 1) of the unit cube [0,1]^3: their planes meet there only.
    vertices = np.array([[1.0, 1, 1], [0, 1, 1], [1, 0, 1], [1, 1, 0]])
    faces = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1]])
    per_face = face_quadrics(vertices, faces)
    corner = accumulate(np.repeat(per_face, 3, axis=0), faces.reshape(-1), 4)[0]
    point, cost = optimal_points(corner[None], vertices[:1] + 0.3, vertices[:1] - 0.2)
    assert np.allclose(point[0], [1, 1, 1])
    assert cost[0] == pytest.approx(0.0, abs=1e-12)


def test_flat_region_falls_back_to_the_cheapest_of_ends_and_midpoint():
    # One plane only: the 3x3 system is singular, any point on the plane is optimal.
    vertices = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    quadric = accumulate(np.repeat(face_quadrics(vertices, np.array([[0, 1, 2]])), 3, axis=0), np.array([0, 1, 2]), 3)
    a, b = vertices[[0]], vertices[[1]]
    point, cost = optimal_points(quadric[[0]] + quadric[[1]], a, b)
    assert any(np.allclose(point[0], option) for option in (a[0], b[0], 0.5 * (a[0] + b[0])))
    assert cost[0] == pytest.approx(0.0, abs=1e-15)


@pytest.mark.parametrize("fraction", [0.5, 0.1])
def test_reaches_the_target_exactly_or_one_below_and_stays_valid(fraction):
    mesh = hx.sample("spot")
    target = int(mesh.n_faces * fraction)
    result = simplify(mesh, target)
    result.validate()
    assert target - 1 <= result.n_faces <= target
    assert result.genus == mesh.genus == 0
    assert result.is_closed


def test_bunny_keeps_its_holes_and_genus():
    mesh = hx.sample("bunny")
    result, report = simplify(mesh, 3000, return_report=True)
    result.validate()
    assert report.reached_target
    assert 2999 <= result.n_faces <= 3000
    assert result.n_boundary_loops == mesh.n_boundary_loops
    assert result.genus == mesh.genus


def test_input_mesh_is_not_modified():
    mesh = hx.sample("spot")
    before = [array.copy() for array in (mesh.positions, mesh.halfedge_next, mesh.halfedge_vertex, mesh.face_halfedge)]
    simplify(mesh, 1000)
    after = (mesh.positions, mesh.halfedge_next, mesh.halfedge_vertex, mesh.face_halfedge)
    assert all(np.array_equal(x, y) for x, y in zip(before, after))


def test_a_flat_patch_stays_flat_and_keeps_its_outline():
    # A 9 x 9 grid in the plane z = 0: all collapses cost nothing, none may leave the plane
    # or move the square's outline.
    n = 9
    xs, ys = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    vertices = np.stack([xs.ravel(), ys.ravel(), np.zeros(n * n)], axis=1)
    faces = []
    for i in range(n - 1):
        for j in range(n - 1):
            v = i * n + j
            faces += [[v, v + 1, v + n + 1], [v, v + n + 1, v + n]]
    mesh = hx.HalfedgeMesh.from_faces(vertices, np.array(faces))
    result = simplify(mesh, 40)
    result.validate()
    positions = result.positions
    assert np.allclose(positions[:, 2], 0.0)
    boundary = result.vertex_is_boundary()
    on_outline = np.isclose(positions[boundary, :2], 0.0) | np.isclose(positions[boundary, :2], 1.0)
    assert on_outline.any(axis=1).all()
    assert result.n_boundary_loops == 1
    # The four corners of the square are still vertices.
    for corner in ([0, 0], [1, 0], [0, 1], [1, 1]):
        assert np.isclose(positions[:, :2], corner).all(axis=1).any()


def test_tetrahedron_cannot_go_lower_and_says_so():
    mesh = hx.sample("tetrahedron")
    with pytest.warns(hx.MeshWarning, match="no allowed collapse"):
        result, report = simplify(mesh, 2, return_report=True)
    assert result.n_faces == 4
    assert not report.reached_target
    result.validate()


def test_no_face_turns_over():
    mesh = hx.sample("bunny")
    result = simplify(mesh, 2000)
    # Compare each simplified face's normal with the original surface's nearby normal:
    # a turned-over face would point inward, against the original normals around it.
    import trimesh

    original = mesh.to_trimesh()
    simplified = result.to_trimesh()
    _, _, nearest_face = trimesh.proximity.closest_point(original, simplified.triangles_center)
    agreement = np.einsum("ij,ij->i", simplified.face_normals, original.face_normals[nearest_face])
    assert (agreement > -0.5).mean() > 0.99


def test_target_must_be_positive():
    with pytest.raises(ValueError):
        simplify(hx.sample("cube"), 0)


def test_progress_bar_does_not_change_the_result():
    mesh = hx.sample("spot")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        quiet = simplify(mesh, 800)
        loud = simplify(mesh, 800, progress=True)
    assert np.array_equal(quiet.to_arrays()[1], loud.to_arrays()[1])
    assert np.allclose(quiet.to_arrays()[0], loud.to_arrays()[0])
