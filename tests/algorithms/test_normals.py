"""Face and vertex normals: hand-worked cases, trimesh as a reference, slots and edge cases."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given

import halfedge_edu as hx
from halfedge_edu.algorithms import corner_angles, face_areas, face_normals, vertex_normals
from tests import strategies as shapes
from tests.strategies import build, meshes


def _unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def test_face_normal_follows_the_right_hand_rule(square):
    # Both triangles run counter-clockwise seen from +z.
    assert np.array_equal(face_normals(square), [[0, 0, 1], [0, 0, 1]])


def test_reversing_a_face_reverses_its_normal():
    mesh = hx.HalfedgeMesh.from_faces(np.eye(3), [[0, 2, 1]])
    assert np.allclose(face_normals(mesh), -_unit([1, 1, 1]))


def test_face_areas_and_corner_angles_of_a_right_triangle():
    mesh = hx.HalfedgeMesh.from_faces([[0, 0, 0], [2, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    assert face_areas(mesh) == pytest.approx([1.0])
    assert corner_angles(mesh)[0] == pytest.approx([np.pi / 2, np.arctan2(1, 2), np.arctan2(2, 1)])


def test_area_weighting_by_hand():
    # Vertex 0 touches a face in the xy plane (legs 2 and 2: area 2, normal +z) and one
    # in the xz plane (legs 1 and 2: area 1, normal +y): area-weighted, 2 z + 1 y.
    vertices = [[0, 0, 0], [2, 0, 0], [0, 2, 0], [0, 0, 1]]
    mesh = hx.HalfedgeMesh.from_faces(vertices, [[0, 1, 2], [0, 3, 1]])
    assert np.allclose(vertex_normals(mesh, "area")[0], _unit([0, 1, 2]))
    assert np.allclose(vertex_normals(mesh, "uniform")[0], _unit([0, 1, 1]))
    # Both corners at vertex 0 are right angles, so angle weighting is uniform here.
    assert np.allclose(vertex_normals(mesh, "angle")[0], _unit([0, 1, 1]))


def test_sphere_normals_point_outwards(icosphere):
    for weighting in ("area", "angle", "uniform"):
        normals = vertex_normals(icosphere, weighting)
        assert np.allclose(np.linalg.norm(normals, axis=1), 1.0)
        assert (np.einsum("ij,ij->i", normals, icosphere.positions) > 0.95).all()


@given(meshes())
def test_matches_trimesh(drawn):
    mesh = build(drawn)
    tm = trimesh.Trimesh(*drawn, process=False)
    assert np.allclose(face_normals(mesh), tm.face_normals, atol=1e-12)
    assert np.allclose(face_areas(mesh), tm.area_faces, atol=1e-12)
    assert np.allclose(corner_angles(mesh), tm.face_angles, atol=1e-12)
    # trimesh's vertex normals are angle weighted.
    assert np.allclose(vertex_normals(mesh, "angle"), tm.vertex_normals, atol=1e-12)
    by_area = trimesh.geometry.mean_vertex_normals(len(tm.vertices), tm.faces, tm.face_normals * tm.area_faces[:, None])
    assert np.allclose(vertex_normals(mesh, "area"), trimesh.util.unitize(by_area), atol=1e-12)
    uniform = trimesh.geometry.mean_vertex_normals(len(tm.vertices), tm.faces, tm.face_normals)
    assert np.allclose(vertex_normals(mesh, "uniform"), trimesh.util.unitize(uniform), atol=1e-12)


@given(meshes())
def test_the_mesh_is_not_modified(drawn):
    mesh = build(drawn)
    before = mesh.copy()
    face_normals(mesh)
    for weighting in ("area", "angle", "uniform"):
        vertex_normals(mesh, weighting)
    assert np.array_equal(mesh.positions, before.positions)
    assert np.array_equal(mesh.halfedge_next, before.halfedge_next)


def test_zero_area_face_gives_zero_normal_not_nan():
    vertices = [[0, 0, 0], [1, 0, 0], [2, 0, 0]]          # three points on a line
    mesh = hx.HalfedgeMesh.from_faces(vertices, [[0, 1, 2]])
    assert np.array_equal(face_normals(mesh), [[0, 0, 0]])
    for weighting in ("area", "angle", "uniform"):
        assert np.array_equal(vertex_normals(mesh, weighting), np.zeros((3, 3)))


def test_rows_of_deleted_elements_are_zero():
    mesh = hx.HalfedgeMesh.from_faces(*shapes.grid(2, 2))
    # Flag a corner face and its lone corner vertex deleted by hand (as an operation would).
    corner_face = next(f.index for f in mesh.faces if 0 in [v.index for v in f.vertices()])
    corner_vertex = 0
    mesh.delete_face(corner_face)
    if len(mesh.vertex(corner_vertex).faces()) == 1:
        mesh.delete_vertex(corner_vertex)
    normals = face_normals(mesh)
    assert normals.shape == (mesh.n_face_slots, 3)
    assert np.array_equal(normals[corner_face], [0, 0, 0])
    assert np.allclose(np.delete(normals, corner_face, axis=0), [0, 0, 1])
    vertex = vertex_normals(mesh)
    assert vertex.shape == (mesh.n_vertex_slots, 3)
    assert np.array_equal(vertex[mesh.vertex_deleted], np.zeros((int(mesh.vertex_deleted.sum()), 3)))


def test_unknown_weighting_is_refused(square):
    with pytest.raises(ValueError, match="weighting"):
        vertex_normals(square, "cotangent")
