"""repair_faces: any triangle soup comes out buildable, and clean meshes come out unchanged."""

from __future__ import annotations

import warnings
from functools import lru_cache

import numpy as np
import pytest
import trimesh
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from halfedge_edu.core.errors import MeshInputError, MeshWarning
from halfedge_edu.core.manifold import manifold_report
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.core.repair import repair_faces
from halfedge_edu.data import sample


@lru_cache(maxsize=None)
def icosphere(subdivisions: int) -> tuple[np.ndarray, np.ndarray]:
    sphere = trimesh.creation.icosphere(subdivisions=subdivisions)
    return np.array(sphere.vertices), np.array(sphere.faces, dtype=np.int64)


def build(vertices, faces) -> HalfedgeMesh:
    """Build and validate, ignoring the warning about vertices merged away."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        mesh = HalfedgeMesh.from_faces(vertices, faces)
    mesh.validate()
    return mesh


def assert_faces_come_from_the_input(faces_in, faces_out, report):
    """Each output face is its input face, renumbered through the copies, maybe flipped."""
    original = np.asarray(faces_in)[report.face_origin]
    renamed = report.vertex_origin[faces_out]
    flipped = np.isin(report.face_origin, report.flipped_faces)
    np.testing.assert_array_equal(renamed[~flipped], original[~flipped])
    np.testing.assert_array_equal(renamed[flipped], original[flipped][:, [0, 2, 1]])


@pytest.mark.parametrize("name", ["tetrahedron", "cube", "open_patch", "single_collapse", "figure8", "spot"])
def test_clean_mesh_passes_through_unchanged(name):
    vertices, faces = sample(name).to_arrays()
    out_vertices, out_faces, report = repair_faces(vertices, faces)
    assert not report
    assert "changed nothing" in str(report)
    np.testing.assert_array_equal(out_vertices, vertices)
    np.testing.assert_array_equal(out_faces, faces)
    assert out_faces is not faces


def test_a_flipped_face_is_flipped_back_and_the_rest_kept():
    vertices, faces = icosphere(2)
    broken = faces.copy()
    broken[[17, 200]] = broken[[17, 200], ::-1]
    out_vertices, out_faces, report = repair_faces(vertices, broken)
    assert report.flipped_faces.tolist() == [17, 200]
    assert len(report.vertex_copies) == 0 and len(out_vertices) == len(vertices)
    assert build(out_vertices, out_faces).n_faces == len(faces)
    assert "flipped faces (2): 17, 200" in str(report)


def test_an_all_reversed_mesh_stays_reversed_but_its_odd_face_follows():
    vertices, faces = icosphere(1)
    broken = faces[:, ::-1].copy()
    broken[3] = faces[3]  # the only face pointing outwards
    _, out_faces, report = repair_faces(vertices, broken)
    assert report.flipped_faces.tolist() == [3]  # the majority decides, not face 0


def test_duplicate_and_degenerate_faces_are_dropped():
    vertices, faces = icosphere(1)
    broken = np.vstack([faces, faces[4], faces[9, ::-1], [[0, 0, 5]], [[1, 2, 1]]])
    out_vertices, out_faces, report = repair_faces(vertices, broken)
    m = len(faces)
    assert report.dropped_duplicate.tolist() == [m, m + 1]
    assert report.dropped_degenerate.tolist() == [m + 2, m + 3]
    np.testing.assert_array_equal(out_faces, faces)
    np.testing.assert_array_equal(report.face_origin, np.arange(m))


def test_nonmanifold_edge_sample_falls_apart_into_its_three_pages():
    raw = sample("nonmanifold_edge")
    out_vertices, out_faces, report = repair_faces(raw.vertices, raw.faces)
    assert report.split_vertices.tolist() == [0, 1]
    assert len(report.vertex_copies) == 4  # two more copies of each end of the edge
    mesh = build(out_vertices, out_faces)
    assert mesh.n_components == 3
    np.testing.assert_array_equal(out_vertices[report.vertex_copies[:, 1]], raw.vertices[report.vertex_copies[:, 0]])


def test_nonmanifold_vertex_sample_splits_the_shared_tip():
    raw = sample("nonmanifold_vertex")
    out_vertices, out_faces, report = repair_faces(raw.vertices, raw.faces)
    assert report.vertex_copies.tolist() == [[0, 7]]
    mesh = build(out_vertices, out_faces)
    assert mesh.n_components == 2 and mesh.is_closed
    assert "0 -> [0, 7]" in str(report)


def test_face_glued_onto_an_edge_of_a_closed_mesh_is_cut_loose_there():
    vertices, faces = icosphere(1)
    a, b = faces[0, 0], faces[0, 1]
    vertices = np.vstack([vertices, [[2.0, 2.0, 2.0]]])
    broken = np.vstack([faces, [[b, a, len(vertices) - 1]]])
    out_vertices, out_faces, report = repair_faces(vertices, broken)
    assert sorted(report.split_vertices.tolist()) == sorted([a, b])
    mesh = build(out_vertices, out_faces)
    assert mesh.n_faces == len(broken) and mesh.n_components == 2


def test_moebius_strip_is_cut_where_it_cannot_be_oriented():
    n = 7
    angle = np.linspace(0, 2 * np.pi, n, endpoint=False)
    vertices = np.concatenate([np.stack([np.cos(angle), np.sin(angle), np.full(n, side)], axis=1) for side in (-0.3, 0.3)])
    faces = []
    for i in range(n):
        a, b = i, i + n  # the rung at i; the last rung glues to the first one swapped
        c, d = ((i + 1, i + 1 + n) if i < n - 1 else (n, 0))
        faces += [[a, c, d], [a, d, b]]
    faces = np.array(faces)
    assert not manifold_report(faces)  # orientation cannot be consistent
    out_vertices, out_faces, report = repair_faces(vertices, faces)
    assert report and len(report.vertex_copies) > 0
    assert manifold_report(out_faces)
    build(out_vertices, out_faces)
    assert_faces_come_from_the_input(faces, out_faces, report)


def test_bad_input_raises():
    with pytest.raises(MeshInputError, match="face 0"):
        repair_faces(np.zeros((2, 3)), [[0, 1, 2]])
    with pytest.raises(MeshInputError, match="shape"):
        repair_faces(np.zeros((3, 2)), [[0, 1, 2]])


@st.composite
def broken_spheres(draw):
    """An icosphere damaged in the ways real files are: flipped, duplicated, glued, merged."""
    vertices, faces = icosphere(draw(st.integers(0, 2)))
    vertices, faces = vertices.copy(), faces.copy()
    m, n = len(faces), len(vertices)
    face = st.integers(0, m - 1)

    flips = draw(st.lists(face, max_size=12))
    faces[flips] = faces[flips][:, ::-1]
    extra = []
    for f, reverse in draw(st.lists(st.tuples(face, st.booleans()), max_size=4)):  # duplicates
        extra.append(faces[f, ::-1] if reverse else faces[f])
    for f, k, apex in draw(st.lists(st.tuples(face, st.integers(0, 2), st.integers(-3, n - 1)), max_size=4)):
        a, b = faces[f, k], faces[f, (k + 1) % 3]  # a third face on edge (a, b)
        if apex < 0:  # ... with a new apex vertex
            vertices = np.vstack([vertices, vertices[a] * 1.5])
            apex = len(vertices) - 1
        extra.append([b, a, apex])
    faces = np.vstack([faces, np.array(extra, dtype=np.int64).reshape(-1, 3)])
    for keep, merge in draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=4)):
        faces[faces == merge] = keep  # two vertices welded into one
    order = draw(st.permutations(range(len(faces))))
    return vertices, faces[list(order)]


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(broken_spheres())
def test_any_broken_sphere_comes_out_buildable(soup):
    vertices, faces = soup
    out_vertices, out_faces, report = repair_faces(vertices, faces)
    assert manifold_report(out_faces, len(out_vertices))
    build(out_vertices, out_faces)
    assert_faces_come_from_the_input(faces, out_faces, report)
    assert len(out_faces) + len(report.dropped_degenerate) + len(report.dropped_duplicate) == len(faces)
    if manifold_report(faces, len(vertices)):
        assert not report
    else:
        assert report


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 9), st.integers(0, 9), st.integers(0, 9)), min_size=1, max_size=30))
def test_any_random_soup_comes_out_buildable(rows):
    faces = np.array(rows, dtype=np.int64)
    vertices = np.random.default_rng(0).normal(size=(10, 3))
    out_vertices, out_faces, report = repair_faces(vertices, faces)
    assert manifold_report(out_faces, len(out_vertices))
    if len(out_faces):
        build(out_vertices, out_faces)
    assert_faces_come_from_the_input(faces, out_faces, report)
