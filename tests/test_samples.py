"""The bundled samples: each builds, has the shape its description promises, and is fresh."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.core.manifold import manifold_report
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.data import RawMesh, sample, samples

RAW = ("nonmanifold_edge", "nonmanifold_vertex")
MESHES = [name for name in samples() if name not in RAW]
CLOSED = ("tetrahedron", "cube", "octahedron", "icosphere", "spot")
FLAT = ("open_patch", "single_collapse", "strip", "figure8", "lone_triangle")


def test_samples_lists_every_name_with_a_description():
    listed = samples()
    assert set(listed) == {
        "tetrahedron", "cube", "octahedron", "icosphere", "open_patch", "single_collapse", "strip",
        "figure8", "lone_triangle", "spot", "bunny", "nonmanifold_edge", "nonmanifold_vertex",
    }
    assert all(isinstance(text, str) and text and "\n" not in text for text in listed.values())


@pytest.mark.parametrize("name", MESHES)
def test_each_mesh_sample_builds_quietly_and_validates(name):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a sample loads without warnings (the bunny too)
        mesh = sample(name)
    assert isinstance(mesh, HalfedgeMesh)
    mesh.validate()


@pytest.mark.parametrize(
    "name, counts",
    [
        ("tetrahedron", (4, 6, 4)),
        ("cube", (8, 18, 12)),
        ("octahedron", (6, 12, 8)),
        ("icosphere", (162, 480, 320)),
        ("open_patch", (16, 33, 18)),
        ("single_collapse", (10, 19, 10)),
        ("strip", (5, 7, 3)),
        ("figure8", (10, 17, 8)),
        ("lone_triangle", (3, 3, 1)),
        ("spot", (2930, 8784, 5856)),
        ("bunny", (34834, 104288, 69451)),
    ],
)
def test_counts(name, counts):
    mesh = sample(name)
    assert (mesh.n_vertices, mesh.n_edges, mesh.n_faces) == counts


@pytest.mark.parametrize("name", CLOSED)
def test_closed_samples_face_outwards(name):
    vertices, faces = sample(name).to_arrays()
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    signed_volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
    assert sample(name).is_closed and signed_volume > 0


@pytest.mark.parametrize("name", FLAT)
def test_flat_samples_face_up(name):
    vertices, faces = sample(name).to_arrays()
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    assert (np.cross(b - a, c - a)[:, 2] > 0).all()
    assert sample(name).n_boundary_loops == 1


def test_cube_edge_0_touches_the_degree_3_corner():
    cube = sample("cube")
    assert cube.halfedge(0).vertex.index == 0 and cube.halfedge(0).tip.index == 4
    assert {v.index for v in cube.edge(0).vertices} == {0, 4}
    degrees = [cube.vertex(i).degree for i in range(8)]
    assert degrees == [3, 5, 5, 5, 5, 5, 5, 3]


def test_icosphere_takes_a_subdivision_level():
    assert [sample("icosphere", subdivisions=k).n_vertices for k in (0, 1, 3)] == [12, 42, 642]
    vertices, _ = sample("icosphere", subdivisions=1).to_arrays()
    np.testing.assert_allclose(np.linalg.norm(vertices, axis=1), 1.0)


def test_single_collapse_edge_0_joins_two_interior_vertices_of_degree_6():
    mesh = sample("single_collapse")
    ends = mesh.edge(0).vertices
    assert sorted(v.index for v in ends) == [0, 1]
    assert all(v.degree == 6 and not v.is_boundary for v in ends)
    assert not mesh.edge(0).is_boundary


def test_figure8_edge_0_is_interior_with_both_ends_on_the_boundary():
    mesh = sample("figure8")
    edge = mesh.edge(0)
    assert sorted(v.index for v in edge.vertices) == [2, 7]
    assert not edge.is_boundary
    assert all(v.is_boundary for v in edge.vertices)


def test_every_vertex_of_the_strip_is_on_the_boundary():
    mesh = sample("strip")
    assert all(v.is_boundary for v in mesh.vertices)


def test_nonmanifold_edge_sample_is_edge_nonmanifold_but_vertex_manifold():
    raw = sample("nonmanifold_edge")
    assert isinstance(raw, RawMesh) and raw.vertices.shape == (5, 3)
    report = manifold_report(raw.faces, len(raw.vertices))
    assert report.nonmanifold_edges.tolist() == [[0, 1]]
    assert report.nonmanifold_vertices.tolist() == []
    with pytest.raises(MeshInputError):
        HalfedgeMesh.from_faces(*raw)


def test_nonmanifold_vertex_sample_is_vertex_nonmanifold_but_edge_manifold():
    vertices, faces = sample("nonmanifold_vertex")
    report = manifold_report(faces, len(vertices))
    assert report.nonmanifold_vertices.tolist() == [0]
    assert report.nonmanifold_edges.shape == (0, 2)
    assert report.inconsistent_edges.shape == (0, 2)  # each cone is consistently oriented
    with pytest.raises(MeshInputError):
        HalfedgeMesh.from_faces(vertices, faces)


def test_each_call_gives_a_fresh_mesh():
    first = sample("spot")
    first.vertex(0).position = [9.0, 9.0, 9.0]
    second = sample("spot")
    assert second is not first
    assert not np.allclose(second.vertex(0).position, [9.0, 9.0, 9.0])


def test_raw_samples_are_fresh_arrays_too():
    first = sample("nonmanifold_vertex")
    first.faces[0] = [1, 1, 1]
    assert sample("nonmanifold_vertex").faces[0].tolist() != [1, 1, 1]


def test_unknown_name_suggests_the_closest_one():
    with pytest.raises(ValueError, match="Did you mean 'cube'"):
        sample("cbue")


def test_options_are_checked():
    with pytest.raises(TypeError):
        sample("cube", subdivisions=2)
    with pytest.raises(ValueError, match="subdivisions"):
        sample("icosphere", subdivisions=-1)
