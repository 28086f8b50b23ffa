"""manifold_report on raw face arrays: each kind of problem, found and named."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import trimesh

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.core.manifold import manifold_report
from halfedge_edu.io import read_obj

MESHES = Path(__file__).resolve().parents[2] / "halfedge_edu" / "data"

# A closed tetrahedron, outward; and the same with apex vertex 0 shared by a second one.
TETRAHEDRON = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
TWO_CONES_AT_ONE_TIP = np.vstack([TETRAHEDRON, np.where(TETRAHEDRON > 0, TETRAHEDRON + 3, 0)])
ICOSPHERE = trimesh.creation.icosphere(subdivisions=2).faces


def test_clean_closed_mesh_is_manifold():
    report = manifold_report(ICOSPHERE)
    assert bool(report) and report.is_manifold
    for field in ("nonmanifold_edges", "inconsistent_edges", "nonmanifold_vertices", "degenerate_faces"):
        assert len(getattr(report, field)) == 0, field
    assert "manifold and consistently oriented" in str(report)


def test_spot_is_manifold():
    assert manifold_report(read_obj(MESHES / "spot.obj").faces)


def test_bunny_is_manifold_and_lists_its_unreferenced_vertices():
    data = read_obj(MESHES / "stanford-bunny.obj")
    report = manifold_report(data.faces, n_vertices=len(data.vertices))
    assert report  # unreferenced vertices do not make a mesh non-manifold
    assert len(report.unreferenced_vertices) == 35947 - 34834


def test_open_mesh_with_boundary_is_manifold():
    assert manifold_report([[0, 1, 2], [2, 1, 3]])


def test_three_faces_on_one_edge_is_edge_nonmanifold_but_vertex_manifold():
    faces = np.array([[0, 2, 1], [0, 3, 1], [0, 4, 1]])
    report = manifold_report(faces)
    assert not report
    assert report.nonmanifold_edges.tolist() == [[0, 1]]
    assert [f.tolist() for f in report.nonmanifold_edge_faces] == [[0, 1, 2]]
    # the faces around 0 (and 1) are joined through edge (0, 1): one fan each
    assert report.nonmanifold_vertices.tolist() == []


def test_two_cones_touching_at_a_tip_are_vertex_nonmanifold_but_edge_manifold():
    report = manifold_report(TWO_CONES_AT_ONE_TIP)
    assert not report
    assert report.nonmanifold_vertices.tolist() == [0]
    assert report.nonmanifold_edges.shape == (0, 2)
    assert report.inconsistent_edges.shape == (0, 2)


def test_bowtie_is_vertex_nonmanifold():
    report = manifold_report([[0, 1, 2], [0, 3, 4]])
    assert report.nonmanifold_vertices.tolist() == [0]
    assert len(report.nonmanifold_edges) == 0


def test_flipped_face_in_a_closed_mesh_gives_its_three_edges_as_inconsistent():
    faces = ICOSPHERE.copy()
    faces[17] = faces[17, ::-1]
    report = manifold_report(faces)
    assert not report
    flipped = faces[17]
    expected = sorted([[flipped[k], flipped[(k + 1) % 3]] for k in range(3)])
    assert sorted(report.inconsistent_edges.tolist()) == expected
    assert len(report.nonmanifold_edges) == 0 and len(report.nonmanifold_vertices) == 0


def test_duplicated_face_is_reported_with_its_crowded_edges():
    faces = np.vstack([ICOSPHERE, ICOSPHERE[5]])
    report = manifold_report(faces)
    assert not report
    assert report.duplicate_faces.tolist() == [len(ICOSPHERE)]
    assert len(report.nonmanifold_edges) == 3
    assert all(len(group) == 3 and len(ICOSPHERE) in group.tolist() for group in report.nonmanifold_edge_faces)
    assert len(report.inconsistent_edges) == 3


def test_reversed_duplicate_counts_as_duplicate():
    faces = np.vstack([ICOSPHERE, ICOSPHERE[5, ::-1]])
    assert manifold_report(faces).duplicate_faces.tolist() == [len(ICOSPHERE)]


def test_degenerate_faces_are_reported_and_left_out_of_the_other_checks():
    report = manifold_report([[0, 1, 2], [1, 1, 2], [2, 3, 3]])
    assert report.degenerate_faces.tolist() == [1, 2]
    assert len(report.inconsistent_edges) == 0 and len(report.nonmanifold_edges) == 0
    assert not report


def test_unreferenced_vertices_past_the_last_used_one_need_n_vertices():
    report = manifold_report([[0, 2, 3]], n_vertices=6)
    assert report.unreferenced_vertices.tolist() == [1, 4, 5]
    assert report


def test_empty_face_list_is_trivially_manifold():
    assert manifold_report(np.zeros((0, 3), dtype=int))


@pytest.mark.parametrize(
    "faces, n_vertices, message",
    [([[0, 1]], None, "shape"), ([[0, 1, 5]], 4, "face 0"), ([[0, -1, 2]], None, "face 0"), ([[0.5, 1, 2]], None, "integers")],
)
def test_bad_arrays_raise_mesh_input_error(faces, n_vertices, message):
    with pytest.raises(MeshInputError, match=message):
        manifold_report(faces, n_vertices)


def test_describe_names_the_elements_and_cuts_long_lists():
    faces = np.vstack([TWO_CONES_AT_ONE_TIP, [[0, 7, 8]]])  # a third fan at vertex 0
    text = manifold_report(faces).describe()
    assert "NOT manifold" in text
    assert "vertices whose faces form more than one fan (1): 0" in text

    many = np.arange(60).reshape(20, 3)  # 20 separate triangles ...
    many[:, 0] = 0  # ... all sharing vertex 0: one non-manifold vertex, many unreferenced below
    report = manifold_report(many, n_vertices=200)
    assert "... and" in report.describe(max_items=5)
    assert len(report.describe(max_items=5).splitlines()) == 3


def test_matches_a_reference_loop_on_random_soups():
    """The vectorized fan count agrees with a plain per-vertex walk."""
    rng = np.random.default_rng(7)
    for _ in range(30):
        faces = rng.integers(0, 12, size=(25, 3))
        faces = faces[(faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])]
        report = manifold_report(faces, n_vertices=12)
        assert report.nonmanifold_vertices.tolist() == _fan_counting_reference(faces, 12)


def _fan_counting_reference(faces: np.ndarray, n_vertices: int) -> list[int]:
    """Vertices with more than one fan, by flood fill over each vertex's faces."""
    result = []
    for v in range(n_vertices):
        around = [f for f in range(len(faces)) if v in faces[f]]
        if not around:
            continue
        seen, stack = {around[0]}, [around[0]]
        while stack:
            f = stack.pop()
            for g in around:
                shared = set(faces[f].tolist()) & set(faces[g].tolist())
                if g not in seen and len(shared) >= 2:  # they share an edge, which contains v
                    seen.add(g)
                    stack.append(g)
        if len(seen) < len(around):
            result.append(v)
    return result
