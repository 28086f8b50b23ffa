"""Arrow geometry: inside its face, twins apart, boundary arrows outside the mesh."""

from __future__ import annotations

import numpy as np

from halfedge_edu.data import sample
from halfedge_edu.viz.arrows import (POINTS_PER_ARROW, TRIANGLES_PER_ARROW, ArrowLayer, arrow_geometry,
                                     halfedge_corners, typical_edge_length)
from halfedge_edu.viz.palette import preset


def _arrows(mesh, halfedges):
    A, B, third = halfedge_corners(mesh, halfedges)
    points, triangles = arrow_geometry(A, B, third, scale=typical_edge_length(mesh))
    return points.reshape(len(halfedges), POINTS_PER_ARROW, 3), triangles


def _barycentric_xy(point, a, b, c):
    """Barycentric coordinates of ``point`` in triangle abc, in the xy-plane."""
    matrix = np.array([[a[0] - c[0], b[0] - c[0]], [a[1] - c[1], b[1] - c[1]]])
    l1, l2 = np.linalg.solve(matrix, point[:2] - c[:2])
    return np.array([l1, l2, 1 - l1 - l2])


def test_arrow_arrays_have_seven_points_and_three_triangles_each():
    mesh = sample("cube")
    halfedges = np.arange(mesh.n_halfedges)
    points, triangles = _arrows(mesh, halfedges)
    assert points.shape == (len(halfedges), POINTS_PER_ARROW, 3)
    assert triangles.shape == (TRIANGLES_PER_ARROW * len(halfedges), 3)
    assert triangles.max() == POINTS_PER_ARROW * len(halfedges) - 1


def test_interior_arrow_lies_inside_its_face():
    mesh = sample("open_patch")                       # flat, in the plane z = 0
    for h in np.flatnonzero(mesh.halfedge_face >= 0):
        points, _ = _arrows(mesh, np.array([h]))
        corners = mesh.positions[mesh.face_vertices()[mesh.halfedge_face[h]]]
        for point in points[0]:
            assert (_barycentric_xy(point, *corners) > 0).all(), f"halfedge {h} leaves its face"


def test_twins_are_two_separate_arrows_pointing_opposite_ways():
    mesh = sample("open_patch")
    h = int(np.flatnonzero((mesh.halfedge_face >= 0) & (mesh.halfedge_face[np.arange(mesh.n_halfedges) ^ 1] >= 0))[0])
    points, _ = _arrows(mesh, np.array([h, h ^ 1]))
    direction = points[:, 5] - points[:, 0]           # tail -> tip
    assert np.dot(direction[0], direction[1]) < 0
    gap = np.linalg.norm(points[0].mean(axis=0) - points[1].mean(axis=0))
    assert gap > 0.1 * typical_edge_length(mesh)


def test_boundary_arrow_lies_outside_the_mesh():
    mesh = sample("open_patch")                       # the square [0, 3] x [0, 3]
    boundary = np.flatnonzero(mesh.halfedge_face < 0)
    points, _ = _arrows(mesh, boundary)
    xy = points[:, :, :2].reshape(-1, 2)
    outside = (xy < 0).any(axis=1) | (xy > 3).any(axis=1)
    assert outside.all()


def test_arrow_points_from_origin_to_tip():
    mesh = sample("cube")
    points, _ = _arrows(mesh, np.array([0]))
    origin, tip = mesh.positions[mesh.halfedge_vertex[[0, 1]]]
    tail, head = points[0, 0], points[0, 5]
    assert np.dot(head - tail, tip - origin) > 0
    assert np.linalg.norm(head - tip) < np.linalg.norm(tail - tip)


class _NoActors:
    """Stands in for a scene's parts: the arrow layer's lookup needs no drawing."""

    def set(self, name, data) -> None:
        pass


def test_an_arrow_layer_finds_each_drawn_halfedge_in_its_arrow_list():
    """``slots`` answers as a table over every halfedge slot filled in arrow order would
    (a halfedge drawn twice, on a broken mesh, answers with its last arrow)."""
    mesh = sample("open_patch")
    drawn = np.array([30, 4, 17, 4, 9, 0, 51])
    layer = ArrowLayer(_NoActors(), preset("default"))
    layer.draw(mesh, drawn, 1.0)
    table = np.full(mesh.n_halfedge_slots, -1)
    table[drawn] = np.arange(len(drawn))                                 # the last write wins
    asked = np.array([-1, 0, 4, 5, 9, 17, 30, 51, 52, mesh.n_halfedge_slots + 3])
    expected = table[asked[(asked >= 0) & (asked < len(table))]]
    assert layer.slots(asked).tolist() == expected[expected >= 0].tolist() == [5, 3, 4, 2, 0, 6]
