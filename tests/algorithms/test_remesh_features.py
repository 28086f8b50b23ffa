"""Remeshing that keeps features: creases and the boundary stay where they are (issue 15)."""

from __future__ import annotations

import importlib

import numpy as np
import pytest
import trimesh
from hypothesis import example, given
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.algorithms.features import (DEFAULT_FEATURE_ANGLE, Features, detect_features, feature_arrays,
                                              number_lines)
from halfedge_edu.cli import main
from halfedge_edu.core.corner_table import edge_table
from tests import strategies as shapes
from tests.algorithms.test_remesh import creased, distance_to_segments, mean_edge_length, smallest_relative_area

remesh_module = importlib.import_module("halfedge_edu.algorithms.remesh")
project_module = importlib.import_module("halfedge_edu.algorithms.remesh.project")
remesh = remesh_module.remesh


def dihedral_angles(vertices: np.ndarray, faces: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """(k,) the angle in degrees between the normals of the two faces at each edge of ``pairs``."""
    table = edge_table(faces, len(vertices))
    at = np.searchsorted(table.keys, pairs[:, 0] * len(vertices) + pairs[:, 1])
    normals = np.cross(vertices[faces[:, 1]] - vertices[faces[:, 0]], vertices[faces[:, 2]] - vertices[faces[:, 0]])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    first, second = normals[table.first[at] // 3], normals[table.second[at] // 3]
    return np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", first, second), -1.0, 1.0)))


def folded_sheet(n: int = 16, slope: float = 1.0) -> hx.HalfedgeMesh:
    """A square sheet of n x n quads folded along the grid line x = 0.5: a straight crease
    of edges (about 90 degrees for slope 1), four boundary sides and four boundary corners."""
    vertices, faces = shapes.grid(n, n)
    vertices = vertices / n                                  # the unit square, in the plane z = 0
    vertices[:, 2] = slope * np.abs(vertices[:, 0] - 0.5)
    return hx.HalfedgeMesh.from_faces(vertices, faces)


# ---- finding the features ---------------------------------------------------------------

def test_the_cube_has_twelve_feature_edges_and_eight_corners():
    cube = hx.sample("cube")
    features = detect_features(cube)
    vertices = cube.to_arrays()[0]
    assert len(features.edges) == 12                       # the face diagonals are flat: not features
    assert np.allclose(np.linalg.norm(vertices[features.edges[:, 0]] - vertices[features.edges[:, 1]], axis=1), 1.0)
    assert features.corners.sum() == 8 and features.counts().tolist() == [3] * 8


def test_a_flat_patch_has_only_its_boundary_with_the_square_corners():
    patch = hx.sample("open_patch")
    features = detect_features(patch)
    vertices, faces = patch.to_arrays()
    table = edge_table(faces, len(vertices))
    assert np.array_equal(features.edges, table.edges[table.count == 1])
    # The boundary turns by 90 degrees at the square's corners only.
    corner_points = vertices[features.corners]
    assert len(corner_points) == 4
    assert np.all((np.isclose(corner_points[:, :2], vertices[:, :2].min(axis=0))
                   | np.isclose(corner_points[:, :2], vertices[:, :2].max(axis=0))).all(axis=1))


def test_the_angle_decides_what_is_a_crease():
    sheet = folded_sheet(slope=0.2)                         # the fold: about 22.6 degrees
    assert len(detect_features(sheet, 20.0).edges) == len(detect_features(sheet, 25.0).edges) + 16


@pytest.mark.parametrize("bad", [-1.0, 181.0, float("nan")])
def test_a_feature_angle_outside_0_to_180_degrees_is_refused_by_name(bad):
    for call in (lambda: remesh(hx.sample("cube"), feature_angle=bad), lambda: detect_features(hx.sample("cube"), bad),
                 lambda: remesh_module.remesh_history(hx.sample("cube"), feature_angle=bad)):
        with pytest.raises(hx.MeshInputError, match="feature_angle"):
            call()


def test_features_follow_a_split_a_merge_and_a_compaction():
    # A line 0 - 1 - 2 along the boundary of two triangles; vertex 3 is off the line.
    faces = np.array([[0, 1, 3], [1, 2, 3]])  # vertices (0,0,0) (1,0,0) (2,0,0) (1,1,0)
    table = edge_table(faces, 4)
    features = Features(np.array([[0, 1], [1, 2]]), np.array([True, False, True, False]), np.array([7, 7]))
    midpoint_of = np.full(len(table.edges), -1)
    midpoint_of[np.searchsorted(table.keys, 0 * 4 + 1)] = 4          # split 0-1 at new vertex 4
    split = features.split(table, midpoint_of)
    assert split.edges.tolist() == [[0, 4], [1, 2], [1, 4]] and split.corners.tolist() == [True, False, True, False, False]
    assert split.lines.tolist() == [7, 7, 7]                        # the halves stay on their line
    merged = split.merge(np.array([4]), np.array([1]))               # collapse 1-4 onto 1
    assert merged.edges.tolist() == [[0, 1], [1, 2]] and merged.lines.tolist() == [7, 7]
    renumbered = merged.renumber(np.array([0, 1, 2, 3]))
    assert renumbered.edges.tolist() == [[0, 1], [1, 2]] and renumbered.corners.tolist() == [True, False, True, False]
    assert renumbered.vertex_lines().tolist() == [-1, 7, -1, -1]      # corners and vertex 3 are on no single line
    chain = Features(np.array([[0, 1], [1, 2]]), np.zeros(4, bool), np.zeros(2, int))
    assert chain.line_neighbours()[0].tolist() == [1]


def test_each_line_runs_from_corner_to_corner_and_has_its_own_number():
    cube = detect_features(hx.sample("cube"))
    assert sorted(np.unique(cube.lines)) == list(range(12))           # every edge joins two corners
    sheet = detect_features(folded_sheet(4))
    # The crease, and the outline cut at the four square corners and the crease's two ends.
    assert len(np.unique(sheet.lines)) == 7
    # Two edges meeting at a vertex that is not a corner are on one line; at a corner, not.
    edges = np.array([[0, 1], [1, 2], [2, 3]])
    assert number_lines(edges, np.array([True, False, False, True])).tolist() == [0, 0, 0]
    numbers = number_lines(edges, np.array([True, False, True, True]))
    assert numbers[0] == numbers[1] != numbers[2]


# ---- what remeshing keeps ---------------------------------------------------------------

@pytest.mark.parametrize("length", [0.1, 0.23])
def test_a_remeshed_cube_keeps_its_twelve_creases_and_eight_corners(length):
    cube = hx.sample("cube")
    input_vertices = cube.to_arrays()[0]
    result = remesh(cube, length, iterations=5)
    result.validate()
    vertices, faces = result.to_arrays()
    assert result.n_faces > 10 * cube.n_faces
    # Every face still lies in a face of the cube: its normal is an axis.
    normals = np.cross(vertices[faces[:, 1]] - vertices[faces[:, 0]], vertices[faces[:, 2]] - vertices[faces[:, 0]])
    assert np.allclose(np.abs(normals / np.linalg.norm(normals, axis=1)[:, None]).max(axis=1), 1.0, atol=1e-9)
    # The corners are kept exactly; the creases are still there, all 12, at 90 degrees.
    assert all((vertices == corner).all(axis=1).any() for corner in input_vertices)
    features = detect_features(result, DEFAULT_FEATURE_ANGLE)
    crease_segments = input_vertices[detect_features(cube).edges]
    assert distance_to_segments(vertices[np.unique(features.edges)], crease_segments).max() < 1e-12
    lengths = np.linalg.norm(vertices[features.edges[:, 0]] - vertices[features.edges[:, 1]], axis=1)
    assert lengths.sum() == pytest.approx(12.0)
    assert np.allclose(dihedral_angles(vertices, faces, features.edges), 90.0)
    assert features.corners.sum() == 8


def test_without_features_the_cube_is_rounded():
    cube = hx.sample("cube")
    rounded = remesh(cube, 0.1, iterations=5, feature_angle=None)
    vertices = rounded.to_arrays()[0]
    assert not all((vertices == corner).all(axis=1).any() for corner in cube.to_arrays()[0])


def test_a_folded_sheet_keeps_its_crease_and_its_outline():
    sheet = folded_sheet()
    input_vertices = sheet.to_arrays()[0]
    lines = input_vertices[detect_features(sheet).edges]            # crease and boundary
    result = remesh(sheet, 0.05, iterations=5)
    result.validate()
    vertices, faces = result.to_arrays()
    features = detect_features(result)
    on_lines = np.unique(features.edges)
    assert distance_to_segments(vertices[on_lines], lines).max() < 1e-12
    # The crease is one straight line of edges from y = 0 to y = 1, still sharp.
    crease = features.edges[np.isclose(vertices[features.edges, 0], 0.5).all(axis=1)]
    assert np.linalg.norm(vertices[crease[:, 0]] - vertices[crease[:, 1]], axis=1).sum() == pytest.approx(1.0)
    fold = dihedral_angles(input_vertices, sheet.to_arrays()[1], crease_pair(sheet))[0]
    assert np.allclose(dihedral_angles(vertices, faces, crease), fold)
    # The boundary stays on the old outline and the sheet's four corners stay.
    on_boundary = vertices[result.vertex_is_boundary()]
    assert distance_to_segments(on_boundary, input_vertices[boundary_pairs(sheet)]).max() < 1e-12
    for corner in input_vertices[detect_features(sheet).corners]:
        assert (vertices == corner).all(axis=1).any()


def crease_pair(mesh: hx.HalfedgeMesh) -> np.ndarray:
    """(1, 2) one interior feature edge of ``mesh`` (a crease edge)."""
    vertices, faces = mesh.to_arrays()
    table = edge_table(faces, len(vertices))
    edges = detect_features(mesh).edges
    inner = table.count[np.searchsorted(table.keys, edges[:, 0] * len(vertices) + edges[:, 1])] == 2
    return edges[inner][:1]


def boundary_pairs(mesh: hx.HalfedgeMesh) -> np.ndarray:
    vertices, faces = mesh.to_arrays()
    table = edge_table(faces, len(vertices))
    return table.edges[table.count == 1]


def test_without_features_the_crease_of_the_sheet_is_cut_off():
    sheet = folded_sheet()
    kept, rounded = (remesh(sheet, 0.05, iterations=5, feature_angle=angle) for angle in (DEFAULT_FEATURE_ANGLE, None))
    ridge = np.column_stack([np.full(11, 0.5), np.linspace(0.05, 0.95, 11), np.zeros(11)])   # points of the crease
    gaps = [trimesh.proximity.closest_point(mesh.to_trimesh(), ridge)[1].max() for mesh in (kept, rounded)]
    assert gaps[0] < 1e-9 < 1e-3 < gaps[1]


def test_smoothing_slides_line_vertices_along_their_line_and_leaves_corners():
    sheet = folded_sheet(8)
    vertices, faces = sheet.to_arrays()
    features = feature_arrays(vertices, faces, DEFAULT_FEATURE_ANGLE)
    rng = np.random.default_rng(5)
    moved = vertices.copy()
    on_crease = np.flatnonzero(np.isclose(vertices[:, 0], 0.5) & ~features.corners)
    moved[on_crease, 1] += rng.uniform(-0.03, 0.03, len(on_crease))  # along the crease (y)
    smoothed = remesh_module.tangential_smoothing(moved, faces, features)
    assert np.array_equal(smoothed[features.corners], vertices[features.corners])
    assert np.allclose(smoothed[on_crease, [0]], 0.5) and np.allclose(smoothed[on_crease, 2], 0.0)
    assert np.abs(smoothed[on_crease, 1] - vertices[on_crease, 1]).max() < np.abs(moved[on_crease, 1] - vertices[on_crease, 1]).max()
    # Without features the boundary stays put, as before features existed.
    boundary = sheet.vertex_is_boundary()
    assert np.array_equal(remesh_module.tangential_smoothing(moved, faces)[boundary], moved[boundary])


def test_smoothing_step_zero_leaves_the_smoothing_phase_still_and_one_is_the_default():
    spot = hx.sample("spot")
    history = remesh_module.remesh_history(spot, iterations=1, smoothing_step=0.0)
    by_phase = {step.phase: step.mesh.to_arrays()[0] for step in history}
    assert np.array_equal(by_phase["flip"], by_phase["smooth"])
    default, full = (remesh(spot, iterations=1, **options).to_arrays()[0] for options in ({}, {"smoothing_step": 1.0}))
    assert np.array_equal(default, full)


@pytest.mark.parametrize("bad", [-0.1, 1.5, float("inf")])
def test_a_smoothing_step_outside_0_to_1_is_refused_by_name(bad):
    with pytest.raises(hx.MeshInputError, match="smoothing_step"):
        remesh(hx.sample("cube"), smoothing_step=bad)


def test_smoothing_keeps_a_line_vertex_on_its_line_where_the_line_turns():
    # The boundary of a fan turns by 15 degrees at each rim vertex (less than the
    # feature angle, so no rim vertex is a corner but the first): the chord between a
    # vertex's two neighbours leaves the rim, the vertex's own two edges do not.
    vertices, faces = shapes.fan(24)
    features = feature_arrays(vertices, faces, DEFAULT_FEATURE_ANGLE)
    features = features._replace(corners=np.arange(len(vertices)) == 1)
    moved = vertices.copy()
    moved[2] = 0.7 * vertices[2] + 0.3 * vertices[3]                  # slid along its edge towards 3
    smoothed = remesh_module.tangential_smoothing(moved, faces, features)
    rim = np.stack([moved[1:], np.roll(moved[1:], -1, axis=0)], axis=1)   # the edges of the rim
    assert distance_to_segments(smoothed[1:], rim).max() < 1e-12
    assert np.array_equal(smoothed[1], moved[1])                     # the corner stays
    # Along a straight line the move is the one to the neighbours' midpoint, as before.
    sheet = folded_sheet(8)
    sheet_vertices, sheet_faces = sheet.to_arrays()
    sheet_features = feature_arrays(sheet_vertices, sheet_faces, DEFAULT_FEATURE_ANGLE)
    on_line, before, after = sheet_features.line_neighbours()
    # The vertices inside the lines along y (the crease and two sides), slid along them.
    along_y = ~sheet_features.corners[on_line] & (sheet_vertices[before, 0] == sheet_vertices[after, 0])
    on_line, before, after = on_line[along_y], before[along_y], after[along_y]
    shifted = sheet_vertices.copy()
    shifted[on_line, 1] += np.random.default_rng(3).uniform(-0.02, 0.02, len(on_line))
    straight = remesh_module.tangential_smoothing(shifted, sheet_faces, sheet_features)
    assert np.allclose(straight[on_line], 0.5 * (shifted[before] + shifted[after]), rtol=0, atol=1e-12)


def test_a_line_vertex_is_projected_onto_its_own_line_even_with_another_nearer():
    # Two parallel lines 1 apart, numbered 0 and 1; a point 0.4 from line 1 and 0.6
    # from line 0 that belongs to line 0 goes onto line 0.
    vertices = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0]])
    faces = np.array([[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]])
    lines = Features(np.array([[0, 1], [1, 2], [3, 4], [4, 5]]), np.zeros(6, bool), np.array([0, 0, 1, 1]))
    surface = remesh_module.InputSurface(vertices, faces, lines)
    points = np.array([[0.5, 0.6, 0.0], [1.5, 0.6, 0.0]])
    assert np.allclose(surface.project_to_lines(points, np.array([0, 1])), [[0.5, 0.0, 0.0], [1.5, 1.0, 0.0]])


# ---- properties on random creased meshes ---------------------------------------------------

@given(case=shapes.cases(), where=st.floats(-0.5, 0.5), slope=st.floats(0.5, 3.0),
       angle=st.sampled_from([1.0, 5.0, 10.0]))
def test_flips_never_flip_a_feature_edge(case, where, slope, angle):
    # Angles below the flip phase's own limit (MAX_FLIP_DIHEDRAL): only the feature rule stops these.
    vertices = creased(case.vertices, where, slope)
    features = feature_arrays(vertices, case.faces, angle)
    flipped, _ = remesh_module.flip_to_regular_degrees(vertices, case.faces, np.random.default_rng(0), features)
    keys = edge_table(flipped, len(vertices)).keys
    wanted = features.edges[:, 0] * len(vertices) + features.edges[:, 1]
    assert np.isin(wanted, keys).all()


def torus_case(n_around: int, n_tube: int, seed: int) -> shapes.MeshCase:
    """A torus with each quad's diagonal drawn from ``seed``, as :func:`shapes.cases` draws them."""
    diagonals = np.random.default_rng(seed).random((n_around, n_tube)) < 0.5
    return shapes.MeshCase("torus", *shapes.torus(n_around, n_tube, diagonals), genus=1, n_boundary_loops=0)


@given(case=shapes.cases(), where=st.floats(-0.5, 0.5), slope=st.floats(0.5, 3.0),
       scale=st.sampled_from([0.5, 1.0, 2.0]), angle=st.sampled_from([20.0, 45.0]))
# Found by this property, on tiny creased tori (almost every vertex a corner):
# smoothing moved a line vertex along the chord of its turning line, 0.0044 L off it,
# and projecting it back would flatten a face with a vertex that went onto another line
# (now a line vertex slides along its own two edges, and goes back onto its own line);
@example(case=torus_case(3, 8, 188608786), where=-0.20028810946261522, slope=1.556718052994146, scale=0.5, angle=20.0)
# the projection put a line vertex on another line nearer to it, 0.12 L off its own;
@example(case=torus_case(8, 3, 820397721), where=0.497209935789211, slope=2.952088346940575, scale=0.5, angle=20.0)
# projecting would flatten a face of a line vertex and a vertex off the lines, and both
# were put back, the line vertex 0.001 L off its line (now the one off the lines goes first).
@example(case=torus_case(8, 3, 518323071), where=0.1994486316010482, slope=2.777602714904173, scale=0.5, angle=45.0)
def test_lines_stay_on_the_input_lines_and_corners_stay_exactly(case, where, slope, scale, angle):
    mesh = hx.HalfedgeMesh.from_faces(creased(case.vertices, where, slope), case.faces)
    input_vertices, input_faces = mesh.to_arrays()
    before = feature_arrays(input_vertices, input_faces, angle)
    lines = input_vertices[before.edges]                               # (k, 2, 3) the input's feature lines
    tolerance = 1e-9 * mean_edge_length(mesh)
    for _, phase, vertices, faces, features in remesh_module._phases(
            mesh, scale * mean_edge_length(mesh), 3, True, False, angle):
        # The tracked feature edges are edges of the mesh, and the corners are where they were.
        keys = edge_table(faces, len(vertices)).keys
        assert np.isin(features.edges[:, 0] * len(vertices) + features.edges[:, 1], keys).all(), phase
        assert np.array_equal(np.sort(vertices[features.corners], axis=0), np.sort(input_vertices[before.corners], axis=0))
        if phase == "project" and len(lines):
            on_lines = np.unique(features.edges)
            assert distance_to_segments(vertices[on_lines], lines).max() <= tolerance
    result = remesh(mesh, scale * mean_edge_length(mesh), iterations=3, feature_angle=angle)
    result.validate()
    assert (result.genus, result.n_boundary_loops) == (case.genus, case.n_boundary_loops)
    assert smallest_relative_area(result) > project_module.MIN_RELATIVE_AREA


# ---- the command line --------------------------------------------------------------------

@pytest.mark.parametrize("given_angle, angle", [(None, DEFAULT_FEATURE_ANGLE), ("30", 30.0), ("none", None)])
def test_the_command_line_passes_the_feature_angle(tmp_path, capsys, given_angle, angle):
    source, out = tmp_path / "cube.obj", tmp_path / "out.obj"
    hx.save(hx.sample("cube"), source)
    extra = [] if given_angle is None else ["--feature-angle", given_angle]
    assert main(["remesh", str(source), str(out), "--length", "0.25", "--iterations", "2", *extra]) == 0
    expected = remesh(hx.load(source), 0.25, 2, feature_angle=angle).to_arrays()[0]
    assert np.array_equal(hx.read_obj(out).vertices, expected)


@pytest.mark.parametrize("bad", ["200", "-5", "sharp"])
def test_the_command_line_refuses_a_bad_feature_angle(tmp_path, capsys, bad):
    source, out = tmp_path / "cube.obj", tmp_path / "out.obj"
    hx.save(hx.sample("cube"), source)
    with pytest.raises(SystemExit) as exit_:
        main(["remesh", str(source), str(out), "--feature-angle", bad])
    assert exit_.value.code == 2 and "--feature-angle" in capsys.readouterr().err
    assert not out.exists()


def test_the_command_line_help_states_the_default_angle(capsys):
    with pytest.raises(SystemExit):
        main(["remesh", "--help"])
    assert f"remesh's, {DEFAULT_FEATURE_ANGLE:g}" in capsys.readouterr().out.replace("\n", " ").replace("  ", " ")
