"""Quadric error simplification: the quadric algebra, the target, and what must survive."""

from __future__ import annotations

import sys
import warnings
from unittest import mock

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.algorithms.simplify import (
    _EdgePrices,
    _accumulate_rows,
    _face_quadric_rows,
    accumulate,
    cheapest_first,
    face_quadrics,
    optimal_points,
    quadric_cost,
    simplify,
    simplify_with_report,
    solve_symmetric_3x3,
)
from halfedge_edu.algorithms.collapse_rounds import FOLD_ANGLE, round_tables
from halfedge_edu.algorithms.simplify_queue import _best_point
from tests import strategies as shapes


def plane_quadric(normal, point) -> np.ndarray:
    """(4, 4) quadric of the plane through ``point`` with normal ``normal`` (any length)."""
    normal = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    p = np.append(normal, -normal @ np.asarray(point, dtype=float))
    return np.outer(p, p)


def test_face_quadric_measures_area_times_squared_distance_to_the_plane():
    # A right triangle of area 2 in the plane z = 1.
    vertices = np.array([[0.0, 0, 1], [2, 0, 1], [0, 2, 1]])
    quadric = face_quadrics(vertices, np.array([[0, 1, 2]]))
    points = np.array([[5.0, -3, 1], [0, 0, 4], [1, 1, -1]])
    expected = 2.0 * (points[:, 2] - 1.0) ** 2
    assert np.allclose(quadric_cost(np.repeat(quadric, 3, axis=0), points), expected)


def test_optimal_point_of_a_cube_corner_is_the_corner():
    # Three faces meeting at the corner (1, 1, 1) of the unit cube [0,1]^3: their planes meet there only.
    vertices = np.array([[1.0, 1, 1], [0, 1, 1], [1, 0, 1], [1, 1, 0]])
    faces = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1]])
    per_face = face_quadrics(vertices, faces)
    corner = accumulate(np.repeat(per_face, 3, axis=0), faces.reshape(-1), 4)[0]
    point, cost = optimal_points(corner[None], vertices[:1] + 0.3, vertices[:1] - 0.2)
    assert np.allclose(point[0], [1, 1, 1])
    assert cost[0] == pytest.approx(0.0, abs=1e-12)


def test_flat_region_keeps_the_midpoint():
    # One plane only: the 3x3 system is singular, any point on the plane is optimal.
    vertices = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    quadric = accumulate(np.repeat(face_quadrics(vertices, np.array([[0, 1, 2]])), 3, axis=0), np.array([0, 1, 2]), 3)
    a, b = vertices[[0]], vertices[[1]]
    point, cost = optimal_points(quadric[[0]] + quadric[[1]], a, b)
    assert np.allclose(point[0], 0.5 * (a[0] + b[0]))
    assert cost[0] == pytest.approx(0.0, abs=1e-15)


def test_an_edge_off_a_plane_moves_onto_it_at_the_nearest_point():
    # Plane z = 0, edge from (0, 0, 1) to (2, 0, 1): every point of the plane costs
    # nothing; the one nearest the midpoint (1, 0, 1) is (1, 0, 0).
    point, cost = optimal_points(plane_quadric([0, 0, 1], [0, 0, 0])[None],
                                 np.array([[0.0, 0, 1]]), np.array([[2.0, 0, 1]]))
    assert np.allclose(point[0], [1, 0, 0])
    assert cost[0] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize(("degrees", "to_crease"), [(2.0, 0.95), (5.0, 0.999)])
def test_a_crease_pulls_the_point_onto_its_line(degrees, to_crease):
    # Two planes through the y axis, tilted by +-degrees/2: their crease is the y axis.
    # The edge runs parallel to it at x = 1; its midpoint is (1, 0.5, 0).
    half = np.radians(degrees) / 2
    quadric = (plane_quadric([np.sin(half), 0, np.cos(half)], [0, 0, 0])
               + plane_quadric([-np.sin(half), 0, np.cos(half)], [0, 0, 0]))
    point, _ = optimal_points(quadric[None], np.array([[1.0, 0, 0]]), np.array([[1.0, 1, 0]]))
    assert point[0][0] <= 1.0 - to_crease          # moved (almost) all the way to x = 0
    assert point[0][1] == pytest.approx(0.5)       # along the crease it stays at the midpoint


def test_planes_that_meet_far_away_keep_the_point_near_the_edge():
    # Three nearly parallel planes (0.05 degrees apart), 0.01 apart near the edge, meet
    # about ten units away. The exact solution of A x = -q lies there, and moving a
    # vertex there would fold its faces: the point may go at most 1% of the way.
    tilt = np.radians(0.05)
    quadric = (plane_quadric([0, 0, 1], [0, 0, 0])
               + plane_quadric([np.sin(tilt), 0, np.cos(tilt)], [0, 0, 0.01])
               + plane_quadric([0, np.sin(tilt), np.cos(tilt)], [0, 0, -0.01]))
    exact = np.linalg.solve(quadric[:3, :3], -quadric[:3, 3])
    midpoint = np.array([0.5, 0, 0])
    assert np.linalg.norm(exact - midpoint) > 10
    point, cost = optimal_points(quadric[None], np.array([[0.0, 0, 0]]), np.array([[1.0, 0, 0]]))
    assert np.linalg.norm(point[0] - midpoint) < 0.01 * np.linalg.norm(exact - midpoint)
    assert cost[0] <= quadric_cost(quadric[None], midpoint[None])[0]


def quadric_and_edge(seed: int, n_planes: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A sum of ``n_planes`` random plane quadrics (area weights 0.1-10) and an edge near them."""
    rng = np.random.default_rng(seed)
    quadric = sum(rng.uniform(0.1, 10) * plane_quadric(rng.normal(size=3), rng.normal(size=3))
                  for _ in range(n_planes))
    return quadric, rng.normal(size=3), rng.normal(size=3)


@st.composite
def quadrics_and_edges(draw):
    """A sum of 1-5 random plane quadrics (area weights 0.1-10) and an edge near them."""
    return quadric_and_edge(draw(st.integers(0, 2**32 - 1)), draw(st.integers(1, 5)))


@given(quadrics_and_edges())
# The cost optimal_points returns and the cost of its point computed again differ by
# rounding, which grows with the terms of p^T Q p, not with the cost: an absolute 1e-12
# failed for 383 of 300,000 seeds (up to 2.0e-11 on costs of about 50, this example),
# so about one CI run in eight. Against the terms' size the gap was at most 6.3e-17.
@example(drawn=quadric_and_edge(37010, 3))
def test_the_point_never_costs_more_than_the_midpoint(drawn):
    quadric, a, b = drawn
    point, cost = optimal_points(quadric[None], a[None], b[None])
    midpoint_cost = quadric_cost(quadric[None], (0.5 * (a + b))[None])[0]
    assert cost[0] <= midpoint_cost * (1 + 1e-9) + 1e-12
    terms = np.abs(quadric).sum() * (1.0 + float(point[0] @ point[0]))     # the size of p^T Q p's terms
    assert cost[0] == pytest.approx(quadric_cost(quadric[None], point)[0], abs=1e-14 * terms)


@given(quadrics_and_edges())
# One plane: its quadric is singular, the point is pulled towards the edge, and the two
# ways of computing it round differently. Coordinate by coordinate (np.allclose) these two
# were 7.8e-9 apart at a coordinate of 0.0019, over its tolerance there; measured against
# the size of the scene they are 6.7e-9 apart. Of 200,000 one-plane seeds, 611 failed the
# coordinate-wise test and the largest gap was 1.2e-8 of the scene's size.
@example(drawn=quadric_and_edge(1209, 1))
def test_the_queue_prices_an_edge_like_the_rounds(drawn):
    quadric, a, b = drawn
    by_queue = _best_point(quadric, a, b)
    by_rounds = optimal_points(quadric[None], a[None], b[None])[0][0]
    # The gap as a length, against the scene's size (the edge's ends are about 1 from
    # the origin): a relative tolerance per coordinate gives a coordinate near 0 none at
    # all, and which coordinate is near 0 depends only on where the axes happen to be.
    scale = max(1.0, float(np.abs(a).max()), float(np.abs(b).max()))
    assert np.linalg.norm(by_queue - by_rounds) <= 1e-7 * scale


def test_solve_symmetric_3x3_matches_numpy():
    rng = np.random.default_rng(7)
    m = rng.normal(size=(50, 3, 3))
    matrices = m @ m.transpose(0, 2, 1) + 0.1 * np.eye(3)          # symmetric, invertible
    rhs = rng.normal(size=(50, 3))
    assert np.allclose(solve_symmetric_3x3(matrices, rhs), np.linalg.solve(matrices, rhs[:, :, None])[:, :, 0])


def test_accumulate_gives_each_face_quadric_to_its_three_corners():
    vertices, faces = hx.sample("spot").to_arrays()
    per_face = face_quadrics(vertices, faces)
    by_corner = accumulate(per_face, faces, len(vertices))
    one_by_one = np.zeros((len(vertices), 4, 4))
    for quadric, corners in zip(per_face, faces):
        one_by_one[corners] += quadric
    assert np.allclose(by_corner, one_by_one)
    assert np.allclose(accumulate(np.repeat(per_face, 3, axis=0), faces.reshape(-1), len(vertices)), one_by_one)


@pytest.mark.parametrize("fraction", [0.5, 0.1])
def test_reaches_the_target_exactly_or_one_below_and_stays_valid(fraction):
    mesh = hx.sample("spot")
    target = int(mesh.n_faces * fraction)
    result = simplify(mesh, target)
    result.validate()
    assert target - 1 <= result.n_faces <= target
    assert result.genus == mesh.genus == 0
    assert result.is_closed


def test_simplify_with_report_gives_the_mesh_simplify_gives_and_takes_only_its_options():
    mesh = hx.sample("spot")
    result = simplify_with_report(mesh, 900, max_normal_angle=60.0)
    alone = simplify(mesh, 900, max_normal_angle=60.0)
    assert all(np.array_equal(x, y) for x, y in zip(result.mesh.to_arrays(), alone.to_arrays()))
    assert (result.report.faces_before, result.report.faces_after) == (mesh.n_faces, alone.n_faces)
    with pytest.raises(TypeError, match="max_normal_angel"):
        simplify_with_report(mesh, 900, max_normal_angel=60.0)


def test_bunny_keeps_its_holes_and_genus():
    mesh = hx.sample("bunny")
    result, report = simplify_with_report(mesh, 3000)
    result.validate()
    assert report.reached_target
    assert 2999 <= result.n_faces <= 3000
    assert result.n_boundary_loops == mesh.n_boundary_loops
    assert result.genus == mesh.genus


def test_input_mesh_is_not_modified():
    mesh = hx.sample("spot")
    before = [array.copy() for array in (mesh.positions, mesh.halfedge_next, mesh.halfedge_vertex, mesh.face_halfedge)]
    simplify(mesh, 1000)
    after = (mesh.positions, mesh.halfedge_next, mesh.halfedge_vertex, mesh.face_halfedge)
    assert all(np.array_equal(x, y) for x, y in zip(before, after))


def test_the_same_input_gives_the_same_mesh_every_time():
    mesh = hx.sample("bunny")
    first = simplify(mesh, 2000).to_arrays()
    second = simplify(mesh.copy(), 2000).to_arrays()
    assert all(np.array_equal(a, b) for a, b in zip(first, second))


@pytest.mark.parametrize("name", ["spot", "bumpy grid"])
def test_pricing_in_small_blocks_gives_the_same_mesh(name):
    # PRICING_BLOCK only decides how many edges (and faces, for the first quadrics) are
    # worked out at a time; the test meshes are smaller than one block, so cut them into
    # blocks of seven: every price, and so the mesh, must come out the same. The grid is
    # open and bumpy, so blocks also hold boundary edges and edges pinned to the outline.
    if name == "spot":
        mesh = hx.sample("spot")
    else:
        vertices, faces = shapes.grid(30, 30)
        vertices[:, 2] = 0.05 * np.sin(3.0 * vertices[:, 0]) * np.cos(2.0 * vertices[:, 1])
        mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    target = mesh.n_faces // 5
    whole = simplify(mesh, target).to_arrays()
    with mock.patch.object(sys.modules["halfedge_edu.algorithms.simplify"], "PRICING_BLOCK", 7):
        in_blocks = simplify(mesh, target).to_arrays()
    assert all(np.array_equal(a, b) for a, b in zip(whole, in_blocks))


# Costs drawn from a few values so that ties are common, with neighbours one unit in the
# last place apart (they differ only in the low bits cheapest_first overwrites), negative
# costs, minus zero and NaN.
_TIED_COSTS = st.lists(
    st.sampled_from([0.0, -0.0, 1.0, np.nextafter(1.0, 2.0), np.nextafter(1.0, 0.0), 2.5, -3.0,
                     1e-300, 7e12, np.nextafter(7e12, 8e12), float("nan"), float("inf")]),
    min_size=0, max_size=300,
)


@given(costs=_TIED_COSTS, noise=st.booleans())
def test_cheapest_first_is_the_stable_argsort(costs, noise):
    cost = np.array(costs, dtype=float)
    if noise:                                   # many distinct costs as well
        cost = np.concatenate([cost, np.random.default_rng(len(costs)).normal(size=len(costs))])
    assert np.array_equal(cheapest_first(cost), np.argsort(cost, kind="stable"))


def test_edge_prices_read_through_slots_match_a_fresh_pricing_after_compaction():
    # Round after round, a third of the vertices move: every edge's cost, point and kept
    # end, carried forward through its slot (and moved to the front when the store fills
    # up), must equal a pricing of the same state from scratch.
    vertices, faces = hx.sample("spot").to_arrays()
    vertices = vertices.copy()
    n = len(vertices)
    quadrics = _accumulate_rows(_face_quadric_rows(vertices, faces), faces, n)
    tables = round_tables(faces, n)
    boundary_vertex = np.zeros(n, dtype=bool)
    rng = np.random.default_rng(5)
    kept_forward = _EdgePrices()
    changed = np.ones(n, dtype=bool)
    rows_used = []                               # rows of the store in use after each round
    for _ in range(8):
        cost = kept_forward.update(tables.edges, tables.boundary, boundary_vertex, vertices, quadrics, changed)
        rows_used.append(kept_forward._used)
        fresh = _EdgePrices()
        fresh_cost = fresh.update(tables.edges, tables.boundary, boundary_vertex, vertices, quadrics,
                                  np.ones(n, dtype=bool))
        every = np.arange(len(tables.edges))
        assert np.array_equal(cost, fresh_cost)
        assert np.array_equal(kept_forward.points(every), fresh.points(every))
        for forward_end, fresh_end in zip(kept_forward.ends(every), fresh.ends(every)):   # keep, then remove
            assert np.array_equal(forward_end, fresh_end)
        changed = rng.random(n) < 0.3
        vertices[changed] += rng.normal(scale=1e-3, size=(int(changed.sum()), 3))
        quadrics[changed] *= 1.5
    # A compaction moves the live rows to the front: the rows in use drop.
    assert any(later < earlier for earlier, later in zip(rows_used, rows_used[1:])), "never compacted"


def test_a_moved_point_is_kept_while_its_edge_stays_unchanged():
    # simplify moves an edge's point to an endpoint when the best point turns a face
    # over; the edge keeps that point in the next round if neither end changed.
    vertices, faces = hx.sample("spot").to_arrays()
    n = len(vertices)
    quadrics = _accumulate_rows(_face_quadric_rows(vertices, faces), faces, n)
    tables = round_tables(faces, n)
    no_boundary = np.zeros(n, dtype=bool)
    prices = _EdgePrices()
    prices.update(tables.edges, tables.boundary, no_boundary, vertices, quadrics, np.ones(n, dtype=bool))
    edge = np.array([3])
    prices.move(edge, vertices[prices.ends(edge)[0]])
    changed = np.zeros(n, dtype=bool)
    changed[tables.edges[10]] = True                     # another edge's ends, not edge 3's
    assert not np.isin(tables.edges[3], tables.edges[10]).any()
    prices.update(tables.edges, tables.boundary, no_boundary, vertices, quadrics, changed)
    assert np.array_equal(prices.points(edge), vertices[prices.ends(edge)[0]])


def test_a_flat_patch_stays_flat_and_keeps_its_outline():
    # A 9 x 9 grid in the plane z = 0: all collapses cost nothing, none may leave the plane
    # or move the square's outline.
    n = 9
    xs, ys = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    vertices = np.stack([xs.ravel(), ys.ravel(), np.zeros(n * n)], axis=1)
    faces = []
    for i in range(n - 1):
        for j in range(n - 1):
            v = i * n + j
            faces += [[v, v + 1, v + n + 1], [v, v + n + 1, v + n]]
    mesh = hx.HalfedgeMesh.from_faces(vertices, np.array(faces))
    result = simplify(mesh, 40)
    result.validate()
    positions = result.positions
    assert np.allclose(positions[:, 2], 0.0)
    boundary = result.vertex_is_boundary()
    on_outline = np.isclose(positions[boundary, :2], 0.0) | np.isclose(positions[boundary, :2], 1.0)
    assert on_outline.any(axis=1).all()
    assert result.n_boundary_loops == 1
    # The four corners of the square are still vertices.
    for corner in ([0, 0], [1, 0], [0, 1], [1, 1]):
        assert np.isclose(positions[:, :2], corner).all(axis=1).any()


def test_tetrahedron_cannot_go_lower_and_says_so():
    mesh = hx.sample("tetrahedron")
    with pytest.warns(hx.MeshWarning, match="no allowed collapse"):
        result, report = simplify_with_report(mesh, 2)
    assert result.n_faces == 4
    assert not report.reached_target
    result.validate()


def test_no_face_turns_over():
    mesh = hx.sample("bunny")
    result = simplify(mesh, 2000)
    # Compare each simplified face's normal with the original surface's nearby normal:
    # a turned-over face would point inward, against the original normals around it.
    import trimesh

    original = mesh.to_trimesh()
    simplified = result.to_trimesh()
    _, _, nearest_face = trimesh.proximity.closest_point(original, simplified.triangles_center)
    agreement = np.einsum("ij,ij->i", simplified.face_normals, original.face_normals[nearest_face])
    assert (agreement > -0.5).mean() > 0.99


def test_target_must_be_positive():
    with pytest.raises(ValueError):
        simplify(hx.sample("cube"), 0)


def test_progress_bar_does_not_change_the_result():
    mesh = hx.sample("spot")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        quiet = simplify(mesh, 800)
        loud = simplify(mesh, 800, progress=True)
    assert np.array_equal(quiet.to_arrays()[1], loud.to_arrays()[1])
    assert np.allclose(quiet.to_arrays()[0], loud.to_arrays()[0])


@given(case=shapes.cases(), fraction=st.sampled_from([0.8, 0.5, 0.2]))
def test_any_mesh_stays_valid_with_its_genus_and_boundary_loops(case, fraction):
    mesh = hx.HalfedgeMesh.from_faces(case.vertices, case.faces)
    target = max(1, int(fraction * mesh.n_faces))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result, report = simplify_with_report(mesh, target)
    result.validate()
    assert (result.genus, result.n_boundary_loops) == (case.genus, case.n_boundary_loops)
    assert result.n_faces == report.faces_after <= mesh.n_faces
    said_so = any(issubclass(w.category, hx.MeshWarning) for w in caught)
    if report.reached_target:
        assert target - 1 <= result.n_faces <= target and not said_so
    else:
        assert result.n_faces > target and said_so


def test_a_nearly_flat_mesh_keeps_its_shape():
    # Spot cut into four by midpoint subdivision: the same surface, with large flat
    # regions and creases of a degree or two between Spot's own faces. Halving the
    # faces must keep every vertex on that surface: on the planes and on the creases.
    import trimesh

    spot = hx.sample("spot").to_trimesh()
    vertices, faces = trimesh.remesh.subdivide(spot.vertices, spot.faces)
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    result = simplify(mesh, 2 * len(spot.faces))
    result.validate()
    _, distance, _ = trimesh.proximity.closest_point(spot, result.to_arrays()[0])
    assert distance.max() < 1e-5 * np.linalg.norm(spot.extents)


def _largest_fold(mesh: hx.HalfedgeMesh) -> float:
    """The largest angle, in degrees, between the normals of two faces that share an edge."""
    from halfedge_edu.core.corner_table import edge_table

    vertices, faces = mesh.to_arrays()
    table = edge_table(faces, len(vertices))
    inner = table.count == 2
    first, second = table.first[inner] // 3, table.second[inner] // 3
    cross = np.cross(vertices[faces[:, 1]] - vertices[faces[:, 0]], vertices[faces[:, 2]] - vertices[faces[:, 0]])
    normal = cross / np.maximum(np.linalg.norm(cross, axis=1), 1e-300)[:, None]
    cosine = np.clip(np.einsum("ij,ij->i", normal[first], normal[second]), -1.0, 1.0)
    return float(np.degrees(np.arccos(cosine)).max()) if len(cosine) else 0.0


@given(
    shape=st.sampled_from(["torus", "sphere", "grid"]),
    size=st.tuples(st.integers(6, 12), st.integers(5, 10)),
    creases=st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5), st.floats(0.5, 4.0), st.floats(0.5, 4.0)),
    fraction=st.sampled_from([0.5, 0.1]),
)
def test_simplify_never_folds_a_pair_that_was_not_folded(shape, size, creases, fraction):
    # Two sharp creases (|x - a| and |y - b| ridges) across a closed or open surface:
    # the faces on either side of a crease are tempted to swing towards each other.
    make = {"torus": shapes.torus, "sphere": shapes.uv_sphere, "grid": shapes.grid}[shape]
    vertices, faces = make(*size)
    at_x, at_y, slope_x, slope_y = creases
    vertices = vertices.copy()
    vertices[:, 2] += slope_x * np.abs(vertices[:, 0] - at_x) + slope_y * np.abs(vertices[:, 1] - at_y)
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    before = _largest_fold(mesh)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hx.MeshWarning)
        result = simplify(mesh, max(4, int(fraction * mesh.n_faces)))
    result.validate()
    assert _largest_fold(result) <= max(before, FOLD_ANGLE) + 1e-6
