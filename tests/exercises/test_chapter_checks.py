"""The checks of chapters 01, 04, 05 and 08, moved from the chapters into the package."""

from __future__ import annotations

import numpy as np
import pytest

from halfedge_edu.exercises.chapter_checks import (
    check_collapse_is_safe, check_cut, check_fan, check_laplacian_step, smooth_once_in_place,
)


def right_fan(corners):
    return [(corners[0], corners[k], corners[k + 1]) for k in range(1, len(corners) - 1)]


def right_cut(vertices, faces):
    return np.vstack([vertices, vertices[0]]), [[0, 1, 2], [5, 3, 4]]


def right_laplacian_step(mesh):
    old, new = mesh.positions, mesh.positions.copy()
    for v in mesh.vertices:
        if not v.is_boundary:
            new[v.index] = old[[u.index for u in v.neighbors()]].mean(axis=0)
    return new


def right_collapse_is_safe(mesh, e):
    edge = mesh.edge(e)
    a, b = edge.vertices
    l, r = edge.halfedge.prev.vertex, edge.halfedge.twin.prev.vertex
    shared = {v.index for v in a.neighbors()} & {v.index for v in b.neighbors()}
    return shared == {l.index, r.index} and not (a.degree == 3 and b.degree == 3)


def stub(*arguments):
    raise NotImplementedError("write it")


CHECKS = [(check_fan, right_fan), (check_cut, right_cut), (check_laplacian_step, right_laplacian_step),
          (check_collapse_is_safe, right_collapse_is_safe)]


@pytest.mark.parametrize(("check", "right"), CHECKS, ids=[check.__name__ for check, _ in CHECKS])
def test_a_right_answer_passes(check, right):
    result = check(right)
    assert result and result.message.startswith("All good!")


@pytest.mark.parametrize(("check", "right"), CHECKS, ids=[check.__name__ for check, _ in CHECKS])
def test_a_stub_is_not_finished_yet_and_never_raises(check, right):
    result = check(stub)
    assert not result and "not finished yet" in result.message and "NotImplementedError" in result.message


def test_check_fan_names_the_polygon_that_differs():
    result = check_fan(lambda corners: [tuple(corners[:3])])
    assert not result and "4 corners" in result.message


def test_check_cut_says_what_repair_faces_gives():
    result = check_cut(lambda vertices, faces: (vertices, faces))
    assert not result and "non-manifold" in result.message


def test_check_laplacian_step_recognises_gauss_seidel():
    result = check_laplacian_step(lambda mesh: smooth_once_in_place(mesh, range(mesh.n_vertices)))
    assert not result and "Gauss-Seidel" in result.message and result.element[0] == "vertex"


def test_check_laplacian_step_refuses_a_function_that_moves_the_mesh():
    def in_place(mesh):
        mesh.positions[:] = right_laplacian_step(mesh)
        return mesh.positions

    result = check_laplacian_step(in_place)
    assert not result and "changed mesh.positions" in result.message


def test_check_collapse_is_safe_names_the_shared_neighbour_of_a_function_that_allows_everything():
    """By UChicago's statement the tetrahedron passes, so 'return True' is caught on the cube."""
    result = check_collapse_is_safe(lambda mesh, e: True, vertices_only=True)
    assert not result and result.mesh_name == "cube" and "doubled edge" in result.message


def blank_fan(corners):
    return ...


def test_a_blank_left_in_the_function_is_named_before_it_runs():
    result = check_fan(blank_fan)
    assert not result and "still has blanks (...)" in result.message


def test_check_cut_accepts_a_triangle_written_from_another_corner():
    """[5, 3, 4] is the triangle [3, 4, 5] started at its third corner: the same face."""
    rotated = check_cut(lambda vertices, faces: (np.vstack([vertices, vertices[0]]), [[0, 1, 2], [3, 4, 5]]))
    assert rotated.passed, rotated.message


def test_check_cut_names_a_turned_face_as_an_orientation_slip():
    turned = check_cut(lambda vertices, faces: (np.vstack([vertices, vertices[0]]), [[0, 1, 2], [5, 4, 3]]))
    assert not turned.passed
    assert "runs the other way round" in turned.message
    assert "give the second fan the copy" not in turned.message


def uchicago_laplacian_step(mesh):
    """UChicago's P5, written as its assignment says ('you will not need to worry about checking
    boundaries'): every vertex to the mean of its neighbours."""
    old = mesh.positions
    return np.array([old[[u.index for u in v.neighbors()]].mean(axis=0) for v in mesh.vertices])


def test_uchicagos_smoothing_that_ignores_boundaries_is_judged_on_the_closed_meshes_and_said():
    result = check_laplacian_step(uchicago_laplacian_step)
    assert result.passed, result.message
    assert "UChicago's assignment says not to worry about boundaries" in result.message
    assert "'open_patch'" in result.message
    assert result.total == len(result.checked) == 3


def test_uchicagos_smoothing_passes_the_hidden_cases_too():
    assert check_laplacian_step(uchicago_laplacian_step, seed=4).passed


def test_moving_only_some_boundary_vertices_is_still_a_slip():
    def moves_one_boundary_vertex(mesh):
        new = right_laplacian_step(mesh)
        boundary = [v.index for v in mesh.vertices if v.is_boundary]
        if boundary:
            new[boundary[0]] += 0.1
        return new
    result = check_laplacian_step(moves_one_boundary_vertex)
    assert not result.passed and "is on the boundary and should stay" in result.message


FAN_SLIP_CODE = {
    "too few or too many triangles":
        lambda corners: [(corners[0], corners[k], corners[k + 1]) for k in range(1, len(corners) - 2)],
    "turned the other way":
        lambda corners: [(corners[0], corners[k + 1], corners[k]) for k in range(1, len(corners) - 1)],
    "a strip, not a fan":
        lambda corners: [(corners[k], corners[k + 1], corners[k + 2]) for k in range(len(corners) - 2)],
    "vertex 0 instead of the first corner":
        lambda corners: [(0, corners[k], corners[k + 1]) for k in range(1, len(corners) - 1)],
}


@pytest.mark.parametrize("slip", sorted(FAN_SLIP_CODE))
def test_each_fan_slip_gets_its_own_sentence(slip):
    from halfedge_edu.exercises.chapter_checks import FAN_SLIPS

    sentences = {name: sentence.split("{")[0][:40] for name, _, sentence in FAN_SLIPS}
    assert set(sentences) == set(FAN_SLIP_CODE)
    result = check_fan(FAN_SLIP_CODE[slip], seed=2) if slip.startswith("vertex 0") else check_fan(FAN_SLIP_CODE[slip])
    assert not result.passed and sentences[slip] in result.message, result.message
    assert all(words not in result.message for name, words in sentences.items() if name != slip)
