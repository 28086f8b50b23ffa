"""Isotropic remeshing: what it keeps, what it improves, and each phase on its own."""

from __future__ import annotations

import importlib

import numpy as np
import pytest
import trimesh
from hypothesis import given
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.core.corner_table import edge_table
from tests import strategies as shapes

remesh_module = importlib.import_module("halfedge_edu.algorithms.remesh")
flip_module = importlib.import_module("halfedge_edu.algorithms.remesh.flip")
project_module = importlib.import_module("halfedge_edu.algorithms.remesh.project")
split_module = importlib.import_module("halfedge_edu.algorithms.remesh.split")
remesh = remesh_module.remesh
remesh_step_by_step = remesh_module.remesh_step_by_step
remesh_history = remesh_module.remesh_history
quality_report = remesh_module.quality_report
SPLIT_ABOVE, COLLAPSE_BELOW = remesh_module.SPLIT_ABOVE, remesh_module.COLLAPSE_BELOW


def edge_lengths(mesh: hx.HalfedgeMesh) -> np.ndarray:
    vertices, faces = mesh.to_arrays()
    edges = edge_table(faces, len(vertices)).edges
    return np.linalg.norm(vertices[edges[:, 0]] - vertices[edges[:, 1]], axis=1)


def mean_edge_length(mesh: hx.HalfedgeMesh) -> float:
    return float(edge_lengths(mesh).mean())


def boundary_segments(mesh: hx.HalfedgeMesh) -> np.ndarray:
    """(S, 2, 3) the boundary edges of ``mesh`` as segments."""
    vertices, faces = mesh.to_arrays()
    table = edge_table(faces, len(vertices))
    return vertices[table.edges[table.count == 1]]


def distance_to_segments(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """(k,) distance of each point to the nearest of the segments (brute force)."""
    a, b = segments[None, :, 0], segments[None, :, 1]
    ab = b - a
    t = np.clip(np.einsum("psj,psj->ps", points[:, None] - a, ab) / np.einsum("psj,psj->ps", ab, ab), 0, 1)
    nearest = a + ab * t[:, :, None]
    return np.linalg.norm(nearest - points[:, None], axis=2).min(axis=1)


@pytest.fixture(scope="module")
def bunny_remeshed():
    bunny = hx.sample("bunny")
    return bunny, remesh(bunny)


@pytest.fixture(scope="module")
def spot_history():
    spot = hx.sample("spot")
    return spot, (remesh(spot, iterations=3), remesh_history(spot, iterations=3))


# ---- what is kept --------------------------------------------------------------------

@pytest.mark.parametrize("name, options", [("spot", {}), ("open_patch", {}), ("icosphere", {"subdivisions": 2})])
@pytest.mark.parametrize("scale", [1.0, 0.4])
def test_result_is_valid_and_keeps_genus_boundary_loops_and_components(name, options, scale):
    mesh = hx.sample(name, **options)
    result = remesh(mesh, scale * mean_edge_length(mesh), iterations=3)
    result.validate()
    assert (result.genus, result.n_boundary_loops, result.n_components) == (
        mesh.genus, mesh.n_boundary_loops, mesh.n_components)


@given(case=shapes.cases(), scale=st.sampled_from([0.5, 1.0, 2.0]))
def test_any_mesh_stays_valid_with_its_genus_and_boundary_loops(case, scale):
    mesh = hx.HalfedgeMesh.from_faces(case.vertices, case.faces)
    result = remesh(mesh, scale * mean_edge_length(mesh), iterations=2)
    result.validate()
    assert (result.genus, result.n_boundary_loops) == (case.genus, case.n_boundary_loops)


def test_bunny_keeps_its_five_holes_and_genus(bunny_remeshed):
    bunny, result = bunny_remeshed
    result.validate()
    assert result.n_boundary_loops == bunny.n_boundary_loops == 5
    assert result.genus == bunny.genus


def test_torus_keeps_genus_one():
    torus = hx.HalfedgeMesh.from_trimesh(trimesh.creation.torus(1.0, 0.4, major_sections=24, minor_sections=12))
    result = remesh(torus, 0.5 * mean_edge_length(torus), iterations=3)
    result.validate()
    assert result.genus == torus.genus == 1


def test_boundary_vertices_stay_on_the_input_boundary_polyline(bunny_remeshed):
    bunny, result = bunny_remeshed
    vertices = result.to_arrays()[0]
    on_boundary = vertices[result.vertex_is_boundary()[~result.vertex_deleted]]
    gap = distance_to_segments(on_boundary, boundary_segments(bunny))
    assert gap.max() <= 1e-9 * mean_edge_length(bunny)


def test_a_flat_patch_stays_flat_and_keeps_its_outline():
    patch = hx.sample("open_patch")
    result = remesh(patch, 0.3, iterations=4)
    vertices = result.to_arrays()[0]
    assert np.allclose(vertices[:, 2], 0.0)
    outline = boundary_segments(patch)
    on_boundary = vertices[result.vertex_is_boundary()]
    assert distance_to_segments(on_boundary, outline).max() < 1e-12
    # The corners of the square survive (a corner is never collapsed away along the boundary).
    corners = np.array([[x, y, 0.0] for x in (vertices[:, 0].min(), vertices[:, 0].max())
                        for y in (vertices[:, 1].min(), vertices[:, 1].max())])
    original = patch.to_arrays()[0]
    assert np.allclose(np.sort(corners, axis=0), np.sort(np.array(
        [[x, y, 0.0] for x in (original[:, 0].min(), original[:, 0].max())
         for y in (original[:, 1].min(), original[:, 1].max())]), axis=0))
    assert trimesh.Trimesh(*result.to_arrays(), process=False).area == pytest.approx(
        trimesh.Trimesh(*patch.to_arrays(), process=False).area)


def test_input_is_not_modified():
    mesh = hx.sample("spot")
    before = [array.copy() for array in (mesh.positions, mesh.halfedge_next, mesh.halfedge_vertex, mesh.face_halfedge)]
    remesh(mesh, iterations=2)
    after = (mesh.positions, mesh.halfedge_next, mesh.halfedge_vertex, mesh.face_halfedge)
    assert all(np.array_equal(x, y) for x, y in zip(before, after))


def test_result_stays_close_to_the_input_surface(spot_history):
    spot, (result, _) = spot_history
    length = mean_edge_length(spot)
    spot_surface, result_surface = spot.to_trimesh(), result.to_trimesh()
    # The result's vertices lie on the input (projection) ...
    _, on_input, _ = trimesh.proximity.closest_point(spot_surface, result.to_arrays()[0])
    assert on_input.max() < 1e-6 * length
    # ... and the input's vertices are near the result: chords of edges about L long.
    _, to_result, _ = trimesh.proximity.closest_point(result_surface, spot.to_arrays()[0])
    assert to_result.mean() < 0.1 * length
    assert to_result.max() < 1.0 * length


def test_same_input_gives_the_same_result():
    mesh = hx.sample("spot")
    first, second = remesh(mesh, iterations=2), remesh(mesh, iterations=2)
    assert all(np.array_equal(x, y) for x, y in zip(first.to_arrays(), second.to_arrays()))


def test_zero_iterations_gives_back_the_input():
    mesh = hx.sample("spot")
    result = remesh(mesh, iterations=0)
    assert result is not mesh
    assert all(np.array_equal(x, y) for x, y in zip(result.to_arrays(), mesh.to_arrays()))


@pytest.mark.parametrize("bad", [{"target_length": 0.0}, {"target_length": -1.0}, {"target_length": float("nan")},
                                 {"iterations": -1}, {"iterations": 1.5}])
def test_bad_arguments_raise_value_error(bad):
    with pytest.raises(ValueError):
        remesh(hx.sample("icosphere"), **bad)


# ---- what is improved ----------------------------------------------------------------

def test_no_edge_is_longer_than_four_thirds_after_each_split_and_collapse_phase(spot_history):
    spot, (_, history) = spot_history
    limit = SPLIT_ABOVE * mean_edge_length(spot) * (1 + 1e-12)
    for step in history:
        if step.phase in ("split", "collapse"):
            assert edge_lengths(step.mesh).max() <= limit, (step.iteration, step.phase)


@pytest.mark.parametrize("which", ["spot", "bunny"])
def test_most_edges_end_between_four_fifths_and_four_thirds(which, spot_history, bunny_remeshed):
    mesh, result = (spot_history[0], spot_history[1][0]) if which == "spot" else bunny_remeshed
    relative = edge_lengths(result) / mean_edge_length(mesh)
    inside = (relative >= COLLAPSE_BELOW) & (relative <= SPLIT_ABOVE)
    assert inside.mean() > 0.9
    assert relative.max() < 2.0


def test_edge_length_spread_and_angles_improve(bunny_remeshed):
    bunny, result = bunny_remeshed
    before, after = quality_report(bunny), quality_report(result)
    assert after.edge_length_spread < 0.6 * before.edge_length_spread
    assert after.min_angle_mean > before.min_angle_mean + 5


def test_degrees_move_towards_six_on_a_cylinder_with_fan_caps():
    # Each cap is a fan: its centre has degree 48, its rim vertices are crowded.
    cylinder = hx.HalfedgeMesh.from_trimesh(trimesh.creation.cylinder(radius=1.0, height=2.0, sections=48))
    result = remesh(cylinder, 0.2)
    result.validate()
    assert quality_report(result).degree_deviation < 0.5 * quality_report(cylinder).degree_deviation
    assert result.vertex_degrees().max() <= 10


def test_degrees_move_towards_six_on_a_uv_sphere():
    sphere = hx.HalfedgeMesh.from_trimesh(trimesh.creation.uv_sphere(radius=1.0, count=[16, 16]))
    result = remesh(sphere)
    assert quality_report(result).degree_deviation < quality_report(sphere).degree_deviation


# ---- the stepper -----------------------------------------------------------------------

def test_history_starts_with_the_input_and_lists_every_phase_in_order(spot_history):
    spot, (result, history) = spot_history
    assert (history[0].iteration, history[0].phase) == (0, "input")
    assert history[0].mesh is not spot
    expected = [(i, phase) for i in (1, 2, 3) for phase in remesh_module.PHASES]
    assert [(step.iteration, step.phase) for step in history[1:]] == expected
    assert all(np.array_equal(x, y) for x, y in zip(history[-1].mesh.to_arrays(), result.to_arrays()))


def test_remesh_history_takes_only_the_options_of_remesh():
    with pytest.raises(TypeError, match="iteration"):
        remesh_history(hx.sample("cube"), iteration=2)


def test_step_by_step_ends_where_remesh_ends():
    mesh = hx.sample("spot")
    steps = list(remesh_step_by_step(mesh, iterations=1, project=False))
    assert [step.phase for step in steps] == ["input", "split", "collapse", "flip", "smooth"]
    final = remesh(mesh, iterations=1, project=False)
    assert all(np.array_equal(x, y) for x, y in zip(steps[-1].mesh.to_arrays(), final.to_arrays()))


def test_flips_and_smoothing_keep_the_connectivity_or_the_positions(spot_history):
    _, (_, history) = spot_history
    by_phase = {(step.iteration, step.phase): step.mesh for step in history}
    collapsed, flipped, smoothed = by_phase[1, "collapse"], by_phase[1, "flip"], by_phase[1, "smooth"]
    assert np.array_equal(collapsed.to_arrays()[0], flipped.to_arrays()[0])       # flips move nothing
    assert collapsed.n_edges == flipped.n_edges
    assert np.array_equal(flipped.to_arrays()[1], smoothed.to_arrays()[1])        # smoothing keeps the faces


# ---- the phases one at a time ----------------------------------------------------------

@pytest.mark.parametrize("corners, long_edges", [
    ([[0.0, 0, 0], [3, 0, 0], [1.5, 1, 0]], 1),      # sides 3, 1.8, 1.8
    ([[0.0, 0, 0], [1, 0, 0], [0.5, 3, 0]], 2),      # sides 1, 3.04, 3.04
    ([[0.0, 0, 0], [4, 0, 0], [0, 4, 0]], 3),        # sides 4, 5.66, 4
])
def test_split_templates_cut_a_triangle_with_k_long_edges_into_k_plus_one(corners, long_edges):
    vertices = np.array(corners)
    new_vertices, new_faces, _, n_split = split_module._split_pass(vertices, np.array([[0, 1, 2]]), 2.0)
    assert n_split == long_edges
    assert len(new_faces) == long_edges + 1
    hx.HalfedgeMesh.from_faces(new_vertices, new_faces).validate()   # manifold and oriented, or it raises
    double_areas = np.cross(new_vertices[new_faces[:, 1]] - new_vertices[new_faces[:, 0]],
                            new_vertices[new_faces[:, 2]] - new_vertices[new_faces[:, 0]])[:, 2]
    assert (double_areas > 0).all()                                  # orientation kept
    assert 0.5 * double_areas.sum() == pytest.approx(0.5 * np.cross(vertices[1] - vertices[0], vertices[2] - vertices[0])[2])


def test_one_split_pass_cuts_every_long_edge_once_at_its_midpoint():
    vertices = np.array([[0.0, 0, 0], [3, 0, 0], [0, 1, 0], [3, 1, 0]])
    faces = np.array([[0, 1, 2], [1, 3, 2]])
    # Edges 0-1 and 2-3 (length 3) and the diagonal 1-2 (about 3.16) are long; 0-2, 1-3 are not.
    new_vertices, new_faces, _, n_split = split_module._split_pass(vertices, faces, 2.0)
    assert n_split == 3
    assert len(new_faces) == 3 + 3                      # each face has two long edges: 3 pieces
    hx.HalfedgeMesh.from_faces(new_vertices, new_faces).validate()
    midpoints = new_vertices[4:]
    expected = 0.5 * np.array([vertices[0] + vertices[1], vertices[1] + vertices[2], vertices[2] + vertices[3]])
    assert np.allclose(np.sort(midpoints, axis=0), np.sort(expected, axis=0))


def test_collapse_phase_removes_short_edges_without_making_long_ones():
    mesh = hx.sample("icosphere", subdivisions=3)
    vertices, faces = mesh.to_arrays()
    length = 2.0 * mean_edge_length(mesh)              # every edge is short for this L
    new_vertices, new_faces, _ = remesh_module.collapse_short_edges(vertices, faces, length)
    result = hx.HalfedgeMesh.from_faces(new_vertices, new_faces)
    result.validate()
    assert result.genus == 0
    assert result.n_faces < 0.6 * mesh.n_faces
    assert edge_lengths(result).max() <= SPLIT_ABOVE * length


def test_flip_pass_lowers_the_total_degree_deviation_and_keeps_counts():
    sphere = hx.HalfedgeMesh.from_trimesh(trimesh.creation.uv_sphere(radius=1.0, count=[12, 12]))
    vertices, faces = sphere.to_arrays()

    def deviation(f):
        degree = np.bincount(edge_table(f, len(vertices)).edges.reshape(-1), minlength=len(vertices))
        return np.abs(degree - 6).sum()

    flipped, n_flipped, _ = flip_module._flip_pass(vertices, faces, np.random.default_rng(0),
                                                     np.cos(np.radians(20.0)))
    assert n_flipped > 0
    assert deviation(flipped) < deviation(faces)
    result = hx.HalfedgeMesh.from_faces(vertices, flipped)
    result.validate()
    assert (result.n_edges, result.n_faces) == (sphere.n_edges, sphere.n_faces)


def test_tangential_smoothing_keeps_a_flat_patch_in_its_plane_and_its_rim_fixed():
    patch = hx.sample("open_patch")
    vertices, faces = patch.to_arrays()
    rng = np.random.default_rng(3)
    inside = ~patch.vertex_is_boundary()
    vertices = vertices.copy()
    vertices[inside, :2] += rng.normal(scale=0.1, size=(inside.sum(), 2))
    smoothed = remesh_module.tangential_smoothing(vertices, faces)
    assert np.allclose(smoothed[:, 2], 0.0)
    assert np.array_equal(smoothed[~inside], vertices[~inside])
    # In the plane the tangential step is the plain step to the neighbours' centroid.
    offsets, neighbours = patch.vertex_adjacency()
    v = int(np.flatnonzero(inside)[0])
    assert np.allclose(smoothed[v], vertices[neighbours[offsets[v]:offsets[v + 1]]].mean(axis=0))


def test_tangential_smoothing_does_not_move_a_vertex_along_its_normal():
    # A regular icosahedron: each vertex's neighbour centroid lies straight below it.
    mesh = hx.sample("icosphere", subdivisions=0)
    vertices, faces = mesh.to_arrays()
    assert np.allclose(remesh_module.tangential_smoothing(vertices, faces), vertices)


def test_closest_points_on_triangles_match_trimesh_in_every_region():
    rng = np.random.default_rng(7)
    triangles = rng.normal(size=(2000, 3, 3))
    points = 2.0 * rng.normal(size=(2000, 3))
    ours = remesh_module.closest_points_on_triangles(points, triangles[:, 0], triangles[:, 1], triangles[:, 2])
    theirs = trimesh.triangles.closest_point(triangles, points)
    assert np.allclose(ours, theirs, atol=1e-9)


# ---- resting on the input's vertices ----------------------------------------------------

def test_snapping_puts_a_near_point_on_the_input_vertex_and_only_one_point_per_vertex():
    # A flat square of 2 x 2 quads: vertex 4, the centre, is the only one off the boundary.
    vertices, faces = shapes.grid(2, 2)
    vertices = vertices.astype(float)
    surface = remesh_module.InputSurface(vertices, faces)
    points = np.array([[1.05, 1.0, 0.0], [1.0, 1.02, 0.0], [0.5, 0.5, 0.0], [0.05, 0.0, 0.0]])
    snapped = surface.project(points, snap_radius=0.1)
    # The nearer of the first two goes onto the centre; the other stays, and so do the
    # point far from any vertex and the one near a boundary vertex (on the outline).
    assert np.allclose(snapped, [[1.05, 1.0, 0.0], [1.0, 1.0, 0.0], [0.5, 0.5, 0.0], [0.05, 0.0, 0.0]], rtol=0, atol=1e-15)
    assert np.array_equal(snapped[1], vertices[4])                   # exactly on it
    assert np.allclose(surface.project(points), points, rtol=0, atol=1e-15)   # without a radius: the nearest points


def noisy_sphere(seed: int = 0) -> hx.HalfedgeMesh:
    """An icosphere (2,562 vertices) with every vertex moved along its radius by up to 2% of
    the radius: the bumps of a scan at the scale of its edges."""
    sphere = trimesh.creation.icosphere(subdivisions=4)
    radial = 1.0 + np.random.default_rng(seed).uniform(-0.02, 0.02, len(sphere.vertices))
    vertices = sphere.vertices * radial[:, None]
    return hx.HalfedgeMesh.from_faces(vertices, sphere.faces)


def test_resting_on_input_vertices_brings_the_result_closer_to_a_noisy_input(monkeypatch):
    sphere = noisy_sphere()
    input_vertices = sphere.to_arrays()[0]
    length = mean_edge_length(sphere)
    gaps = []
    for radius in (remesh_module.SNAP_TO_INPUT_VERTEX, 0.0):
        monkeypatch.setattr(remesh_module, "SNAP_TO_INPUT_VERTEX", radius)
        result = remesh(sphere, length, smoothing_step=0.5)
        result.validate()
        vertices = result.to_arrays()[0]
        assert len(np.unique(vertices, axis=0)) == len(vertices)      # no two vertices on one point
        gaps.append(trimesh.proximity.closest_point(result.to_trimesh(), input_vertices)[1].mean() / length)
        on_input = (vertices[:, None] == input_vertices[None]).all(axis=2).any(axis=1)
        if radius > 0:
            assert on_input.mean() > 0.2                              # many rest on input vertices
    assert gaps[0] < 0.8 * gaps[1]


# ---- the quality report ----------------------------------------------------------------

def test_quality_report_of_the_icosahedron():
    report = quality_report(hx.sample("icosphere", subdivisions=0))
    assert report.n_faces == 20 and report.n_vertices == 12
    assert report.edge_length_spread == pytest.approx(0.0, abs=1e-12)
    assert report.degree_histogram.tolist() == [0, 0, 0, 0, 0, 12]
    assert report.degree_deviation == pytest.approx(1.0)
    assert report.min_angle_mean == pytest.approx(60.0)
    counts, edges = report.min_angle_histogram
    assert counts.sum() == 20 and edges[0] == 0.0 and edges[-1] == 60.0
    assert report.edge_length_histogram[0].sum() == 30


def test_quality_report_counts_boundary_vertices_against_four():
    # open_patch: 12 boundary vertices (4 corners of degree 2 or 3, 8 sides of degree 4), 4 inside of degree 6.
    patch = hx.sample("open_patch")
    report = quality_report(patch)
    degree = patch.vertex_degrees()
    ideal = np.where(patch.vertex_is_boundary(), 4, 6)
    assert report.degree_deviation == pytest.approx(np.abs(degree - ideal).mean())


# ---- no face flattened -----------------------------------------------------------------

def creased(vertices: np.ndarray, where: float, slope: float) -> np.ndarray:
    """The surface folded into a V along the plane x = where: a sharp crease, as in CAD parts."""
    folded = vertices.copy()
    folded[:, 2] += slope * np.abs(folded[:, 0] - where)
    return folded


def smallest_relative_area(mesh: hx.HalfedgeMesh) -> float:
    """min over faces of twice the area over the squared longest edge (0 for a flat face)."""
    vertices, faces = mesh.to_arrays()
    corners = vertices[faces]
    double_area = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    sides = corners - np.roll(corners, 1, axis=1)
    return float((double_area / np.einsum("fkd,fkd->fk", sides, sides).max(axis=1)).min())


# Found by the property below: the projection put two corners of a face on one point.
FLATTENED_BY_PROJECTION = [
    (shapes.torus(3, 4), -0.07089300133418885, 0.7306825413832303, 1.0),
    (shapes.uv_sphere(7, 2), 0.20318755459481097, 2.2212737489525076, 2.0),
    (shapes.torus(5, 4), 0.2036425120535994, 2.3054965138525536, 2.0),
]


@pytest.mark.parametrize("arrays, where, slope, scale", FLATTENED_BY_PROJECTION)
def test_projection_onto_a_crease_flattens_no_face(arrays, where, slope, scale):
    mesh = hx.HalfedgeMesh.from_faces(creased(arrays[0], where, slope), arrays[1])
    result = remesh(mesh, scale * mean_edge_length(mesh), iterations=3)
    result.validate()
    assert smallest_relative_area(result) > project_module.MIN_RELATIVE_AREA


@given(case=shapes.cases(), where=st.floats(-0.5, 0.5), slope=st.floats(0.5, 3.0),
       scale=st.sampled_from([0.5, 1.0, 2.0]))
def test_remesh_never_makes_a_zero_area_face_on_creased_meshes(case, where, slope, scale):
    mesh = hx.HalfedgeMesh.from_faces(creased(case.vertices, where, slope), case.faces)
    assert smallest_relative_area(mesh) > project_module.MIN_RELATIVE_AREA
    result = remesh(mesh, scale * mean_edge_length(mesh), iterations=3)
    assert smallest_relative_area(result) > project_module.MIN_RELATIVE_AREA
