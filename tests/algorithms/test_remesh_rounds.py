"""The shortcuts of the fast remesher give what the plain versions give.

* A collapse round after the first looks only at the faces near the short edges still
  to try (``_faces_near``); it must choose exactly what a round on the whole mesh
  chooses, on closed and open meshes, with and without feature lines.
* A round ranks its short edges by class of length, with a fixed shuffle inside a
  class (``_collapse_order``): where lengths rise gradually across the mesh it takes
  many more edges than strict shortest-first order, so the rounds stay few.
* The rounds stop once one collapses at most ``MIN_COLLAPSE_SHARE`` of the busiest
  round: chains of collapses that make the next one possible go on to the next iteration.
* ``Features.edge_mask`` takes the keys of part of a mesh and leaves out the feature
  edges that are not among them.
* The projection's candidates (the triangle with the nearest centroid and the three
  beside it) find the true nearest point of the input for almost every point, and a
  point on the input surface always.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.algorithms import collapse_rounds
from halfedge_edu.algorithms.features import feature_arrays
from halfedge_edu.core.corner_table import edge_table
from tests import strategies as shapes
from tests.algorithms.test_remesh import mean_edge_length
from tests.algorithms.test_remesh_features import folded_sheet

remesh_module = importlib.import_module("halfedge_edu.algorithms.remesh")
collapse_module = importlib.import_module("halfedge_edu.algorithms.remesh.collapse")
flip_module = importlib.import_module("halfedge_edu.algorithms.remesh.flip")


def split_then_collapse(mesh: hx.HalfedgeMesh, scale: float, feature_angle: float | None):
    """One split phase and one collapse phase at ``scale`` times the mean edge length."""
    vertices, faces = mesh.to_arrays()
    length = scale * mean_edge_length(mesh)
    features = feature_arrays(vertices, faces, feature_angle) if feature_angle is not None else None
    vertices, faces, features = remesh_module.split_long_edges(vertices, faces, length, features)
    return remesh_module.collapse_short_edges(vertices, faces, length, features)


def bumpy_sheet(n: int = 24) -> hx.HalfedgeMesh:
    """An open grid of n x n quads, its vertices shaken in the plane (edges of many
    lengths) and lifted into bumps: a boundary, and creases where the bumps fold."""
    vertices, faces = shapes.grid(n, n)
    rng = np.random.default_rng(5)
    vertices = vertices / n
    vertices[:, :2] += rng.uniform(-0.3, 0.3, size=(len(vertices), 2)) / n
    vertices[:, 2] = 0.1 * np.sin(6 * vertices[:, 0]) * np.cos(5 * vertices[:, 1])
    return hx.HalfedgeMesh.from_faces(vertices, faces)


CASES = [("spot", 1.6, 30.0), ("spot", 1.2, None), ("bumpy", 1.5, 30.0), ("bumpy", 1.5, None),
         ("sheet", 1.4, 30.0)]


@pytest.mark.parametrize("name, scale, feature_angle", CASES)
def test_collapse_rounds_on_a_region_choose_what_rounds_on_the_whole_mesh_choose(monkeypatch, name, scale,
                                                                                  feature_angle):
    made = {"sheet": lambda: folded_sheet(slope=0.6), "bumpy": bumpy_sheet}
    mesh = made[name]() if name in made else hx.sample(name)
    regions = []
    faces_near = collapse_module._faces_near

    def recording(faces, marked):
        region = faces_near(faces, marked)
        regions.append((len(region), len(faces)))
        return region

    monkeypatch.setattr(collapse_module, "_faces_near", recording)
    by_region = split_then_collapse(mesh, scale, feature_angle)
    # At least two rounds ran on a region, and some region left faces out: the case tests something.
    assert len(regions) >= 2 and any(size < total for size, total in regions)

    monkeypatch.setattr(collapse_module, "_faces_near", lambda faces, marked: np.arange(len(faces)))
    whole = split_then_collapse(mesh, scale, feature_angle)
    assert np.array_equal(by_region[1], whole[1])
    assert np.array_equal(by_region[0], whole[0])
    if feature_angle is not None:
        assert np.array_equal(by_region[2].edges, whole[2].edges)
        assert np.array_equal(by_region[2].corners, whole[2].corners)


def test_edge_mask_of_part_of_the_edges_leaves_out_the_feature_edges_elsewhere():
    cube = hx.sample("cube")
    vertices, faces = cube.to_arrays()
    features = feature_arrays(vertices, faces, 30.0)
    n = len(vertices)
    part = edge_table(faces[: len(faces) // 3], n)                     # the edges of a third of the faces
    feature_keys = set((features.edges[:, 0] * n + features.edges[:, 1]).tolist())
    expected = np.array([key in feature_keys for key in part.keys.tolist()])
    assert expected.any() and len(feature_keys) > expected.sum()     # some feature edges are outside the part
    assert np.array_equal(features.edge_mask(part.keys), expected)
    whole = edge_table(faces, n)
    assert np.array_equal(features.mask(whole), features.edge_mask(whole.keys))
    assert features.mask(whole).sum() == len(features.edges)


def test_projection_finds_the_nearest_point_of_the_input_for_almost_every_point():
    spot = hx.sample("spot")
    vertices, faces = spot.to_arrays()
    surface = remesh_module.InputSurface(vertices, faces)
    rng = np.random.default_rng(3)
    length = mean_edge_length(spot)
    points = vertices[rng.choice(len(vertices), 300, replace=False)] + rng.normal(scale=0.1 * length, size=(300, 3))
    found = surface.project(points)

    corners = vertices[faces]                                          # brute force: every triangle
    repeated = np.repeat(points, len(faces), axis=0)
    tiled = np.tile(corners, (len(points), 1, 1))
    nearest = remesh_module.closest_points_on_triangles(repeated, tiled[:, 0], tiled[:, 1], tiled[:, 2])
    best = np.linalg.norm(nearest - repeated, axis=1).reshape(len(points), len(faces)).min(axis=1)
    ours = np.linalg.norm(found - points, axis=1)
    assert np.all(ours >= best - 1e-12)
    assert np.mean(ours <= best + 1e-9 * length) >= 0.99
    assert np.all(ours <= best + 0.5 * length)
    # Each point found lies on the input surface: on one of its triangles.
    on_input = remesh_module.InputSurface(vertices, faces).project(found)
    assert np.allclose(on_input, found, atol=1e-9 * length)


@pytest.mark.parametrize("name", ["spot", "bumpy"])
def test_edge_uses_kept_up_to_date_through_flip_passes_equal_a_fresh_table(name):
    mesh = bumpy_sheet() if name == "bumpy" else hx.sample(name)
    vertices, faces = mesh.to_arrays()
    vertices, faces, _ = remesh_module.split_long_edges(vertices, faces, 0.7 * mean_edge_length(mesh), None)
    n = len(vertices)
    uses = flip_module._EdgeUses.of(faces, n)
    rng = np.random.default_rng(0)
    flipped = 0
    for _ in range(3):
        faces, n_flipped, uses = flip_module._flip_pass(vertices, faces, rng, np.cos(np.radians(20.0)), uses=uses)
        flipped += n_flipped
        fresh = edge_table(faces, n)
        # The table made from the uses is the fresh one (up to which use of an edge is first).
        table = uses.table()
        for field in ("edges", "corner_edge", "count", "keys"):
            assert np.array_equal(getattr(table, field), getattr(fresh, field)), field
        # The same two directed edges per edge, in either order.
        assert np.array_equal(np.sort(np.stack([table.first, table.second], axis=1), axis=1),
                              np.sort(np.stack([fresh.first, fresh.second], axis=1), axis=1))
        assert np.array_equal(table.boundary_vertices(n), fresh.boundary_vertices(n))
        # Each slot's key is its edge's, the degrees are counted as the flips go, and the
        # look-up of an edge by key knows the edges the flips made and forgets the ones they removed.
        assert np.array_equal(np.sort(uses.keys), fresh.keys)
        assert np.array_equal(uses.degree, np.bincount(fresh.edges.reshape(-1), minlength=n))
        pairs = rng.integers(0, n, size=(2000, 2))
        asked = np.concatenate([fresh.keys, uses.start_keys,
                                np.minimum(pairs[:, 0], pairs[:, 1]) * n + np.maximum(pairs[:, 0], pairs[:, 1])])
        assert np.array_equal(uses.contains(asked), np.isin(asked, fresh.keys))
    assert flipped > 0


def graded_strip(columns: int = 40, rows: int = 30) -> tuple[np.ndarray, np.ndarray]:
    """A flat grid whose columns widen gradually, from 0.55 to 0.75 (rows 0.8 apart):
    every edge across a column is short for L = 1, each column a little longer than the
    one before, and no edge is longer than 4/3 L."""
    vertices, faces = shapes.grid(columns, rows)
    edges_x = np.concatenate([[0.0], np.cumsum(np.linspace(0.55, 0.75, columns))])   # (columns + 1,)
    column, row = np.rint(vertices[:, 0]).astype(int), np.rint(vertices[:, 1]).astype(int)
    return np.stack([edges_x[column], 0.8 * row, np.zeros(len(vertices))], axis=1), faces


def first_round_collapses(vertices: np.ndarray, faces: np.ndarray, target_length: float) -> int:
    """How many edges the first collapse round (on the whole mesh) collapses."""
    refused = collapse_module._Refused(len(vertices))
    max_normal_cos = np.cos(np.radians(collapse_module.MAX_COLLAPSE_NORMAL_ANGLE))
    _, _, n_collapsed, _ = collapse_module._collapse_round(vertices.copy(), faces, None, target_length, max_normal_cos,
                                                          refused, None)
    return n_collapsed


def test_collapse_order_puts_shorter_classes_first_and_shuffles_inside_a_class():
    target_length = 1.0
    width = remesh_module.COLLAPSE_BELOW * target_length / collapse_module.COLLAPSE_LENGTH_CLASSES
    # Two classes, each with lengths rising with the key (strict order would keep the keys in order).
    length = np.concatenate([np.linspace(0.1, 0.9, 50), np.linspace(3.1, 3.9, 50)]) * width
    keys = np.arange(100, dtype=np.int64) * 1001
    order = collapse_module._collapse_order(length, keys, target_length)
    assert np.array_equal(np.sort(order), np.arange(100))
    assert set(order[:50].tolist()) == set(range(50))                  # the shorter class first
    assert not np.array_equal(order[:50], np.arange(50))               # ... not shortest first inside it
    # The order follows the keys, not where an edge stands in the arrays: a round on
    # part of the mesh ranks its edges as a round on all of it does.
    shuffle = np.random.default_rng(1).permutation(100)
    reordered = collapse_module._collapse_order(length[shuffle], keys[shuffle], target_length)
    assert np.array_equal(keys[shuffle][reordered], keys[order])
    # A length just under 4/5 L stays in the last class.
    last = collapse_module._collapse_order(np.array([0.0, np.nextafter(0.8, 0.0)]), np.array([7, 3]), target_length)
    assert np.array_equal(last, [0, 1])


def test_collapse_order_puts_the_smaller_key_first_where_two_shuffled_numbers_agree():
    # spread_ties_keys keeps the top 59 bits of a 64-bit hash: distinct for keys below
    # 2**30, not always above. This key hashes to 14 (key * hash factor = 14 mod 2**64),
    # so its number equals key 0's.
    colliding = 4191503622821399894
    keys = np.array([colliding, 0], dtype=np.int64)
    length = np.array([0.5, 0.5])
    priority = collapse_rounds.spread_ties_keys(np.zeros(2, dtype=np.int64), keys)
    assert priority[0] == priority[1]
    assert np.array_equal(collapse_module._collapse_order(length, keys, 1.0), [1, 0])
    assert np.array_equal(collapse_module._collapse_order(length, keys[::-1].copy(), 1.0), [0, 1])


def test_a_round_takes_many_more_edges_than_shortest_first_where_lengths_rise_gradually(monkeypatch):
    vertices, faces = graded_strip()
    ranked = first_round_collapses(vertices, faces, 1.0)
    monkeypatch.setattr(collapse_module, "_collapse_order",
                        lambda length, keys, target_length: np.argsort(length, kind="stable"))
    shortest_first = first_round_collapses(vertices, faces, 1.0)
    # Shortest first takes little more than the narrowest column (18 edges); by class, 136.
    assert ranked >= 4 * shortest_first


def collapse_round_counts(monkeypatch, vertices: np.ndarray, faces: np.ndarray, target_length: float) -> list[int]:
    """The collapses of every round of one split and one collapse phase."""
    counts = []
    collapse_round = collapse_module._collapse_round

    def counting(*args, **kwargs):
        result = collapse_round(*args, **kwargs)
        counts.append(result[2])
        return result

    monkeypatch.setattr(collapse_module, "_collapse_round", counting)
    vertices, faces, _ = remesh_module.split_long_edges(vertices, faces, target_length, None)
    remesh_module.collapse_short_edges(vertices, faces, target_length, None)
    return counts


def test_collapse_rounds_stop_when_only_chains_of_single_collapses_are_left(monkeypatch):
    # A torus of 6,020 faces at its mean edge length: once the bulk is done, a few
    # chains go on collapsing one edge per round each (a collapsed vertex of degree 4
    # leaves its neighbour with degree 4), around the tube.
    vertices, faces = shapes.torus(86, 35, radii=(1.0, 0.4))
    target_length = float(remesh_module.edge_lengths(vertices, edge_table(faces, len(vertices)).edges).mean())
    counts = collapse_round_counts(monkeypatch, vertices, faces, target_length)
    assert len(counts) <= 12, counts                                  # 30 (the cap) without the share rule
    assert counts[-1] <= collapse_module.MIN_COLLAPSE_SHARE * max(counts)


def collapse_places_one_edge_at_a_time(vertices, edges, a, b, first, allowed, limit) -> np.ndarray:
    """The reference for ``_collapse_places``: for each edge, try the midpoint, the end
    ``first``, the other end, in turn, measuring every edge the collapse would make."""
    neighbours_of = {}
    for x, y in edges.tolist():
        neighbours_of.setdefault(x, set()).add(y)
        neighbours_of.setdefault(y, set()).add(x)
    choices = []
    for i in range(len(a)):
        around = sorted(neighbours_of[a[i]] | neighbours_of[b[i]])
        second = b[i] if first[i] == a[i] else a[i]
        places = (0.5 * (vertices[a[i]] + vertices[b[i]]), vertices[first[i]], vertices[second])
        fitting = [k for k, place in enumerate(places)
                   if allowed[i, k] and np.linalg.norm(vertices[around] - place, axis=1).max() <= limit]
        choices.append(fitting[0] if fitting else -1)
    return np.array(choices)


@pytest.mark.parametrize("block", [1, 3, 8192])
def test_collapse_places_measured_a_block_at_a_time_equal_one_edge_at_a_time(monkeypatch, block):
    monkeypatch.setattr(collapse_module, "PLACE_CHECK_BLOCK", block)
    mesh = bumpy_sheet(12)
    vertices, faces = mesh.to_arrays()
    length = 1.3 * mean_edge_length(mesh)
    vertices, faces, _ = remesh_module.split_long_edges(vertices, faces, length, None)
    tables = collapse_rounds.round_tables(faces, len(vertices))
    edge_length = remesh_module.edge_lengths(vertices, tables.edges)
    short = np.flatnonzero(edge_length < remesh_module.COLLAPSE_BELOW * length)
    a, b = tables.edges[short, 0], tables.edges[short, 1]
    rng = np.random.default_rng(2)
    first = np.where(rng.random(len(short)) < 0.5, a, b)
    allowed = rng.random((len(short), 3)) < 0.7                          # every mix of allowed places
    limit = remesh_module.SPLIT_ABOVE * length
    reach = collapse_module._longest_edge_at(len(vertices), tables.edges, edge_length)
    choice = collapse_module._collapse_places(vertices, tables.neighbours, reach, a, b, first, edge_length[short],
                                            allowed, limit)
    expected = collapse_places_one_edge_at_a_time(vertices, tables.edges, a, b, first, allowed, limit)
    assert np.array_equal(choice, expected)
    assert len(set(choice.tolist())) == 4                                # each place, and none, occurs
