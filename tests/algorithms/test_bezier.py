"""Bezier curves and surfaces: de Casteljau's levels, Bernstein polynomials, surface meshes."""

from __future__ import annotations

from math import comb

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from halfedge_edu.algorithms import (
    bezier_curve, bezier_surface, bezier_surface_points, de_casteljau, face_normals,
)

coordinates = st.floats(-10, 10, allow_nan=False, width=64)


def bernstein_point(control_points, t):
    """sum_i C(n, i) t^i (1 - t)^(n - i) P_i, written out."""
    control_points = np.asarray(control_points, dtype=float)
    n = len(control_points) - 1
    return sum(comb(n, i) * t**i * (1 - t) ** (n - i) * control_points[i] for i in range(n + 1))


def test_levels_shrink_by_one_point_down_to_the_curve_point():
    control = [[0, 0], [1, 2], [3, 2], [4, 0]]
    levels = de_casteljau(control, 0.25)
    assert [len(level) for level in levels] == [4, 3, 2, 1]
    assert np.array_equal(levels[0], control)
    assert np.allclose(levels[1][0], [0.25, 0.5])                 # a quarter of the way from P0 to P1


def test_quadratic_at_one_half_by_hand():
    # (P0 + 2 P1 + P2) / 4 for P = (0,0), (1,2), (2,0): (1, 1).
    levels = de_casteljau([[0, 0], [1, 2], [2, 0]], 0.5)
    assert np.allclose(levels[1], [[0.5, 1.0], [1.5, 1.0]])
    assert np.allclose(levels[-1], [[1.0, 1.0]])


@given(arrays(np.float64, st.tuples(st.integers(1, 8), st.integers(1, 3)), elements=coordinates),
       st.floats(0, 1))
def test_matches_the_bernstein_form(control, t):
    assert np.allclose(de_casteljau(control, t)[-1][0], bernstein_point(control, t), atol=1e-9)


@given(arrays(np.float64, st.tuples(st.integers(1, 8), st.integers(1, 3)), elements=coordinates),
       st.integers(2, 20))
def test_curve_interpolates_its_end_points(control, samples):
    curve = bezier_curve(control, samples)
    assert curve.shape == (samples, control.shape[1])
    assert np.allclose(curve[0], control[0]) and np.allclose(curve[-1], control[-1])
    middle = samples // 2
    assert np.allclose(curve[middle], bernstein_point(control, middle / (samples - 1)), atol=1e-9)


def _bicubic_grid(seed=0):
    u, v = np.meshgrid(np.arange(4.0), np.arange(4.0), indexing="ij")
    heights = np.random.default_rng(seed).uniform(-1, 1, size=(4, 4))
    return np.stack([u, v, heights], axis=-1)                     # (4, 4, 3)


def test_surface_corners_are_the_grid_corners():
    grid = _bicubic_grid()
    mesh = bezier_surface(grid, resolution=(7, 5))
    points = mesh.positions.reshape(7, 5, 3)
    for (i, j), (gi, gj) in zip([(0, 0), (-1, 0), (0, -1), (-1, -1)], [(0, 0), (-1, 0), (0, -1), (-1, -1)]):
        assert np.allclose(points[i, j], grid[gi, gj])
    assert (mesh.n_vertices, mesh.n_faces) == (35, 2 * 6 * 4)
    mesh.validate()


def test_surface_edges_are_the_boundary_curves():
    grid = _bicubic_grid(1)
    points = bezier_surface_points(grid, resolution=(9, 6))
    assert np.allclose(points[0], bezier_curve(grid[0], 6))        # u = 0: the first row of controls
    assert np.allclose(points[:, -1], bezier_curve(grid[:, -1], 9))


def test_surface_matches_the_tensor_bernstein_form():
    grid = _bicubic_grid(2)
    points = bezier_surface_points(grid, resolution=(5, 4))
    for i, u in enumerate(np.linspace(0, 1, 5)):
        for j, v in enumerate(np.linspace(0, 1, 4)):
            expected = sum(
                comb(3, a) * u**a * (1 - u) ** (3 - a) * comb(3, b) * v**b * (1 - v) ** (3 - b) * grid[a, b]
                for a in range(4) for b in range(4)
            )
            assert np.allclose(points[i, j], expected)


def test_planar_grid_gives_a_planar_surface_facing_up():
    u, v = np.meshgrid(np.linspace(0, 3, 4), np.linspace(0, 2, 3), indexing="ij")
    skew = np.random.default_rng(3).uniform(-0.2, 0.2, size=u.shape)
    grid = np.stack([u + skew, v, np.full_like(u, 0.5)], axis=-1)  # (4, 3, 3) all at z = 0.5
    mesh = bezier_surface(grid, resolution=8)
    assert np.allclose(mesh.positions[:, 2], 0.5)
    assert np.allclose(face_normals(mesh), [0, 0, 1])               # d/du x d/dv = x cross y = +z


def test_control_points_are_not_modified():
    grid = _bicubic_grid()
    before = grid.copy()
    bezier_surface(grid)
    de_casteljau(grid[0], 0.3)[0][0, 0] = 99.0                      # levels[0] is a copy
    assert np.array_equal(grid, before)


@pytest.mark.parametrize("call", [
    lambda: de_casteljau([], 0.5),
    lambda: de_casteljau([1.0, 2.0], 0.5),
    lambda: bezier_curve([[0, 0], [1, 1]], samples=1),
    lambda: bezier_curve([[0, 0], [np.nan, 1]]),
    lambda: bezier_surface(np.zeros((4, 4, 2))),
    lambda: bezier_surface(np.zeros((4, 4, 3)), resolution=(1, 5)),
])
def test_bad_input_is_refused(call):
    with pytest.raises(ValueError):
        call()
