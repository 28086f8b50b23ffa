"""Every public algorithm on the smallest and most degenerate meshes, and with hostile arguments.

The promise (issue 10): each answer is a valid mesh (checked with ``validate()``) or a
typed error naming the real cause: ``MeshInputError`` for bad input (naming the
argument or the vertex), ``TopologyError`` for a mesh the operation cannot work on.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.cli import transform
from halfedge_edu.algorithms import (
    arguments, bezier_curve, bezier_surface, corner_angles, de_casteljau, face_areas, grid_triangles,
    loop_positions, loop_subdivide_by_operations, remesh_history, remesh_step_by_step, simplify_with_report,
    smooth_reference,
)
from halfedge_edu.algorithms.arguments import ArgumentTypeError
from halfedge_edu.core.build import INDEX, build_arrays

TETRAHEDRON = ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
SMALL_MESHES = {
    "single triangle": ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]),
    "two triangles": ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], [[0, 1, 2], [1, 3, 2]]),
    "strip": ([[i, j, 0] for i in range(4) for j in range(2)],
              [[0, 2, 1], [1, 2, 3], [2, 4, 3], [3, 4, 5], [4, 6, 5], [5, 6, 7]]),
    "tetrahedron": TETRAHEDRON,
    "cube": hx.sample("cube").to_arrays(),
    "empty": (np.zeros((0, 3)), np.zeros((0, 3), dtype=int)),
}


def small_mesh(name: str) -> hx.HalfedgeMesh:
    return hx.HalfedgeMesh.from_faces(*SMALL_MESHES[name])


def pillow() -> hx.HalfedgeMesh:
    """Two triangles glued back to back, built from arrays (``from_faces`` refuses it)."""
    return hx.HalfedgeMesh(build_arrays(np.eye(3), np.array([[0, 1, 2], [0, 2, 1]], dtype=INDEX)))


def _half(mesh: hx.HalfedgeMesh) -> int:
    return max(1, mesh.n_faces // 2)


# Every algorithm that returns a mesh, as (name, call).
MESH_ALGORITHMS = {
    "smooth": lambda m: hx.smooth(m, 3),
    "smooth cotangent along": lambda m: hx.smooth(m, 3, weights="cotangent", boundary="along"),
    "smooth_reference": lambda m: smooth_reference(m, 2, weights="cotangent"),
    "loop_subdivide": lambda m: hx.loop_subdivide(m, 2),
    "loop_subdivide_by_operations": lambda m: loop_subdivide_by_operations(m),
    "simplify": lambda m: hx.simplify(m, _half(m)),
    "simplify_with_report": lambda m: simplify_with_report(m, _half(m)).mesh,
    "simplify_sequential": lambda m: hx.simplify_sequential(m, _half(m)),
    "remesh": lambda m: hx.remesh(m, iterations=2),
    "remesh short edges": lambda m: hx.remesh(m, 0.3, iterations=2),
    "remesh_history": lambda m: remesh_history(m, iterations=1)[-1].mesh,
    "remesh_step_by_step": lambda m: list(remesh_step_by_step(m, iterations=1))[-1].mesh,
}
# Every algorithm that returns per-element arrays, as (name, call, rows it must have).
ARRAY_ALGORITHMS = {
    "vertex_normals area": (lambda m: hx.vertex_normals(m), lambda m: m.n_vertex_slots),
    "vertex_normals angle": (lambda m: hx.vertex_normals(m, "angle"), lambda m: m.n_vertex_slots),
    "vertex_normals uniform": (lambda m: hx.vertex_normals(m, "uniform"), lambda m: m.n_vertex_slots),
    "face_normals": (hx.face_normals, lambda m: m.n_face_slots),
    "face_areas": (face_areas, lambda m: m.n_face_slots),
    "corner_angles": (corner_angles, lambda m: m.n_face_slots),
}


@pytest.mark.parametrize("shape", SMALL_MESHES)
@pytest.mark.parametrize("algorithm", MESH_ALGORITHMS)
def test_every_mesh_algorithm_returns_a_valid_mesh_on_small_meshes(algorithm, shape):
    mesh = small_mesh(shape)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hx.MeshWarning)   # "stopped at N faces": no collapse allowed
        result = MESH_ALGORITHMS[algorithm](mesh)
    result.validate()
    assert np.isfinite(result.to_arrays()[0]).all()
    assert result.euler_characteristic == mesh.euler_characteristic
    assert result.n_boundary_loops == mesh.n_boundary_loops


@pytest.mark.parametrize("algorithm", MESH_ALGORITHMS)
def test_every_mesh_algorithm_returns_the_empty_mesh_unchanged(algorithm):
    result = MESH_ALGORITHMS[algorithm](small_mesh("empty"))
    result.validate()
    assert (result.n_vertices, result.n_edges, result.n_faces) == (0, 0, 0)


@pytest.mark.parametrize("shape", SMALL_MESHES)
@pytest.mark.parametrize("algorithm", ARRAY_ALGORITHMS)
def test_every_array_algorithm_gives_finite_rows_on_small_meshes(algorithm, shape):
    mesh = small_mesh(shape)
    compute, rows = ARRAY_ALGORITHMS[algorithm]
    values = compute(mesh)
    assert len(values) == rows(mesh)
    assert np.isfinite(values).all()


def test_quality_report_refuses_the_empty_mesh_by_name():
    with pytest.raises(hx.MeshInputError, match="no faces"):
        hx.quality_report(small_mesh("empty"))


# ---- the pillow: two triangles glued back to back -----------------------------------------

@pytest.mark.parametrize("algorithm", [
    "loop_subdivide", "loop_subdivide_by_operations", "remesh", "remesh short edges", "remesh_history",
    "remesh_step_by_step", "simplify", "simplify_with_report", "simplify_sequential",
])
def test_algorithms_that_change_connectivity_refuse_a_hand_built_pillow_naming_it(algorithm):
    mesh = pillow()
    with pytest.raises(hx.TopologyError, match="faces 0 and 1 are glued back to back"):
        MESH_ALGORITHMS[algorithm](mesh)


def test_loop_positions_refuses_nothing_on_a_pillow_but_subdivision_does():
    # The positions are well defined; it is the new connectivity that cannot exist.
    vertex_points, edge_points = loop_positions(pillow())
    assert np.isfinite(vertex_points).all() and np.isfinite(edge_points).all()


@pytest.mark.parametrize("algorithm", [
    "smooth", "smooth cotangent along", "smooth_reference",
])
def test_algorithms_that_only_move_vertices_leave_a_pillow_valid(algorithm):
    result = MESH_ALGORITHMS[algorithm](pillow())
    result.validate()
    assert result.n_faces == 2


@pytest.mark.parametrize("algorithm", ARRAY_ALGORITHMS)
def test_normals_of_a_pillow_are_finite(algorithm):
    compute, rows = ARRAY_ALGORITHMS[algorithm]
    assert np.isfinite(compute(pillow())).all()


# ---- huge but finite coordinates -----------------------------------------------------------

def scaled(size: float) -> hx.HalfedgeMesh:
    """The icosphere with its largest coordinate ``size``."""
    vertices, faces = hx.sample("icosphere").to_arrays()
    return hx.HalfedgeMesh.from_faces(vertices * (size / np.abs(vertices).max()), faces)


# "remesh short edges" asks for edges of 0.3 whatever the size, so it is left out here.
ALL_ALGORITHMS = {
    **{name: call for name, call in MESH_ALGORITHMS.items() if name != "remesh short edges"},
    **{name: compute for name, (compute, _) in ARRAY_ALGORITHMS.items()},
    "quality_report": hx.quality_report,
    "loop_positions": loop_positions,
}


@pytest.mark.parametrize("algorithm", ALL_ALGORITHMS)
def test_coordinates_at_the_limit_give_finite_results_without_warnings(algorithm):
    with warnings.catch_warnings():
        warnings.simplefilter("error")                 # no overflow warning from numpy either
        warnings.simplefilter("ignore", hx.MeshWarning)
        result = ALL_ALGORITHMS[algorithm](scaled(arguments.MAX_COORDINATE))
    assert_finite(result)


def assert_finite(result) -> None:
    """Whatever an algorithm returned (a mesh, arrays, a quality report) is valid and finite;
    a quality report measures edges of a positive mean length."""
    if isinstance(result, hx.HalfedgeMesh):
        result.validate()
        assert np.isfinite(result.to_arrays()[0]).all()
    elif isinstance(result, tuple):
        assert all(np.isfinite(part).all() for part in result)
    elif isinstance(result, np.ndarray):
        assert np.isfinite(result).all()
    else:
        assert math.isfinite(result.edge_length_mean) and result.edge_length_mean > 0


@pytest.mark.parametrize("size", [1e41, 1e51, 1e77, 1e154, 1e308])
@pytest.mark.parametrize("algorithm", ALL_ALGORITHMS)
def test_coordinates_beyond_the_limit_are_refused_as_too_large(algorithm, size):
    mesh = scaled(size)
    with pytest.raises(hx.MeshInputError, match="too large for the computation") as caught:
        ALL_ALGORITHMS[algorithm](mesh)
    assert caught.value.element[0] == "vertex"
    assert np.abs(mesh.positions[caught.value.element[1]]).max() > arguments.MAX_COORDINATE


# ---- tiny coordinates: the other end of the range -------------------------------------------

def shrunk(extent: float) -> hx.HalfedgeMesh:
    """The icosphere, shrunk until its bounding box is ``extent`` across."""
    vertices, faces = hx.sample("icosphere").to_arrays()
    return hx.HalfedgeMesh.from_faces(vertices * (extent / np.ptp(vertices, axis=0).max()), faces)


@pytest.mark.parametrize("algorithm", ALL_ALGORITHMS)
def test_a_mesh_as_small_as_the_limit_gives_finite_results(algorithm):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hx.MeshWarning)
        result = ALL_ALGORITHMS[algorithm](shrunk(arguments.MIN_EXTENT))
    assert_finite(result)


@pytest.mark.parametrize("kind", ["face", "vertex"])
def test_normals_of_a_mesh_as_small_as_the_limit_are_unit_vectors(kind):
    # Below the limit the cross products round to zero and every normal would be (0, 0, 0).
    normals = (hx.face_normals if kind == "face" else hx.vertex_normals)(shrunk(arguments.MIN_EXTENT))
    assert np.allclose(np.linalg.norm(normals, axis=1), 1.0)


@pytest.mark.parametrize("extent", [1e-41, 1e-100, 1e-200, 1e-320, 0.0])
@pytest.mark.parametrize("algorithm", ALL_ALGORITHMS)
def test_a_mesh_smaller_than_the_limit_is_refused_as_too_small(algorithm, extent):
    with pytest.raises(hx.MeshInputError, match="too small for the computation") as caught:
        ALL_ALGORITHMS[algorithm](shrunk(extent))
    assert caught.value.element[0] == "argument"


def test_a_coordinate_set_to_nan_after_construction_is_named():
    mesh = small_mesh("cube")
    mesh.positions[5, 1] = np.nan
    with pytest.raises(hx.MeshInputError, match="vertex 5 .*not a finite number") as caught:
        hx.smooth(mesh)
    assert caught.value.element == ("vertex", 5)


def _grid(side: int) -> hx.HalfedgeMesh:
    """A flat ``side`` x ``side`` grid of vertices, two triangles per square, 1 across."""
    i, j = np.meshgrid(np.arange(side), np.arange(side), indexing="ij")
    vertices = np.stack([i.ravel(), j.ravel(), np.zeros(side * side)], axis=1) / (side - 1)
    corner = (i[:-1, :-1] * side + j[:-1, :-1]).ravel()
    faces = np.concatenate([np.stack([corner, corner + side, corner + 1], axis=1),
                            np.stack([corner + 1, corner + side, corner + side + 1], axis=1)])
    return hx.HalfedgeMesh.from_faces(vertices, faces)


def test_the_extent_counts_every_vertex_not_only_the_first_ones():
    # check_mesh measures the first EXTENT_SAMPLE vertices first; a mesh whose first
    # vertices sit on one point but whose others spread out is not too small.
    mesh = _grid(40)
    assert mesh.n_vertices > arguments.EXTENT_SAMPLE
    mesh.positions[:arguments.EXTENT_SAMPLE] = 0.5
    arguments.check_mesh(mesh)
    mesh.positions[:] = 0.5
    mesh.positions[-1] += arguments.MIN_EXTENT / 2        # the last vertex alone sets the extent
    with pytest.raises(hx.MeshInputError, match="too small for the computation"):
        arguments.check_mesh(mesh)


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf, 2 * arguments.MAX_COORDINATE])
def test_the_offending_vertex_is_named_wherever_it_is(value):
    mesh = _grid(40)
    for vertex in (0, 777, mesh.n_vertices - 1):
        mesh.positions[vertex, 2] = value
        with pytest.raises(hx.MeshInputError) as caught:
            arguments.check_mesh(mesh)
        assert caught.value.element == ("vertex", vertex)
        mesh.positions[vertex, 2] = 0.0
    arguments.check_mesh(mesh)


def test_the_command_line_and_the_library_share_one_coordinate_limit():
    assert transform.MAX_COORDINATE == arguments.MAX_COORDINATE
    assert transform.MIN_EXTENT == arguments.MIN_EXTENT


# ---- hostile arguments ------------------------------------------------------------------------

CUBE = hx.sample("cube")
OUT_OF_RANGE = [
    # (call, the argument it names)
    (lambda: hx.smooth(CUBE, -1), "iterations"),
    (lambda: hx.smooth(CUBE, 1.5), "iterations"),
    (lambda: hx.smooth(CUBE, math.nan), "iterations"),
    (lambda: hx.smooth(CUBE, step=math.nan), "step"),
    (lambda: hx.smooth(CUBE, step=0), "step"),
    (lambda: hx.smooth(CUBE, weights="cotan"), "weights"),
    (lambda: hx.smooth(CUBE, boundary="free"), "boundary"),
    (lambda: smooth_reference(CUBE, step=math.inf), "step"),
    (lambda: hx.loop_subdivide(CUBE, -1), "levels"),
    (lambda: hx.loop_subdivide(CUBE, weights="catmull"), "weights"),
    (lambda: hx.simplify(CUBE, 0), "target_faces"),
    (lambda: hx.simplify(CUBE, 6, max_normal_angle=math.nan), "max_normal_angle"),
    (lambda: hx.simplify(CUBE, 6, max_normal_angle=-1), "max_normal_angle"),
    (lambda: hx.simplify(CUBE, 6, max_normal_angle=181), "max_normal_angle"),
    (lambda: hx.simplify(CUBE, 6, boundary_weight=-1), "boundary_weight"),
    (lambda: hx.simplify(CUBE, 6, boundary_weight=math.inf), "boundary_weight"),
    (lambda: hx.simplify(CUBE, 6, candidate_fraction=0), "candidate_fraction"),
    (lambda: hx.simplify(CUBE, 6, candidate_fraction=2), "candidate_fraction"),
    (lambda: simplify_with_report(CUBE, 6, max_normal_angle=math.nan), "max_normal_angle"),
    (lambda: hx.simplify_sequential(CUBE, 6, max_normal_angle=math.nan), "max_normal_angle"),
    (lambda: hx.simplify_sequential(CUBE, 6, max_steps=-1), "max_steps"),
    (lambda: hx.remesh(CUBE, math.nan), "target_length"),
    (lambda: hx.remesh(CUBE, 0), "target_length"),
    (lambda: hx.remesh(CUBE, iterations=-2), "iterations"),
    (lambda: remesh_history(CUBE, -1.0), "target_length"),
    (lambda: remesh_step_by_step(CUBE, iterations=math.inf), "iterations"),
    (lambda: hx.quality_report(CUBE, bins=0), "bins"),
    (lambda: hx.vertex_normals(CUBE, "mean"), "weighting"),
    (lambda: de_casteljau([[0, 0], [1, 1]], math.nan), "t"),
    (lambda: bezier_curve([[0, 0], [1, 1]], samples=1), "samples"),
    (lambda: bezier_surface(np.zeros((2, 2, 3)), resolution=(4, math.nan)), "resolution"),
    (lambda: grid_triangles(2.5, 3), "n_u"),
]
WRONG_TYPE = [
    (lambda: hx.smooth("cube"), "mesh"),
    (lambda: hx.face_normals(CUBE.to_arrays()), "mesh"),
    (lambda: hx.smooth(CUBE, True), "iterations"),
    (lambda: hx.smooth(CUBE, "3"), "iterations"),
    (lambda: hx.smooth(CUBE, step=1j), "step"),
    (lambda: hx.smooth(CUBE, progress="yes"), "progress"),
    (lambda: hx.loop_subdivide(CUBE, "2"), "levels"),
    (lambda: hx.simplify(CUBE, 6, max_normal_angle=80 + 0j), "max_normal_angle"),
    (lambda: hx.simplify(CUBE, 6, progress=1), "progress"),
    (lambda: hx.simplify_sequential(CUBE, 6, on_step="print"), "on_step"),
    (lambda: hx.remesh(CUBE, "0.1"), "target_length"),
    (lambda: hx.remesh(CUBE, project=None), "project"),
    (lambda: loop_subdivide_by_operations(CUBE, on_step=3), "on_step"),
    (lambda: hx.vertex_normals(CUBE, 0), "weighting"),
    (lambda: de_casteljau([[0, 0], [1, 1]], "half"), "t"),
]


@pytest.mark.parametrize("call, name", OUT_OF_RANGE, ids=[f"{i}-{name}" for i, (_, name) in enumerate(OUT_OF_RANGE)])
def test_an_argument_out_of_range_is_a_mesh_input_error_naming_it(call, name):
    with pytest.raises(hx.MeshInputError) as caught:
        call()
    assert str(caught.value).startswith(name)
    assert caught.value.element == ("argument", name)


@pytest.mark.parametrize("call, name", WRONG_TYPE, ids=[f"{i}-{name}" for i, (_, name) in enumerate(WRONG_TYPE)])
def test_an_argument_of_the_wrong_type_is_a_type_error_naming_it(call, name):
    with pytest.raises(ArgumentTypeError) as caught:
        call()
    assert isinstance(caught.value, TypeError) and isinstance(caught.value, hx.MeshInputError)
    assert str(caught.value).startswith(f"{name} must be")
    assert caught.value.element == ("argument", name)


def test_complex_control_points_are_refused_not_truncated():
    with pytest.raises(hx.MeshInputError, match="control_points must be real numbers, got complex"):
        bezier_curve([[0, 0], [1j, 1]])


def test_whole_floats_and_numpy_scalars_are_accepted_as_counts():
    assert hx.loop_subdivide(CUBE, np.int64(1)).n_faces == hx.loop_subdivide(CUBE, 1.0).n_faces == 48
    assert hx.smooth(CUBE, np.float32(2.0), step=np.float64(0.5)).n_vertices == 8
