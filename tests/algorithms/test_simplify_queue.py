"""The course's one-collapse-at-a-time quadric simplification (priority queue, lazy deletion)."""

from __future__ import annotations

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.algorithms.simplify import simplify
from halfedge_edu.algorithms.simplify_queue import QuadricQueue, simplify_sequential


def test_reaches_the_target_and_keeps_topology():
    mesh = hx.sample("spot")
    result = simplify_sequential(mesh, 1000)
    result.validate()
    assert 999 <= result.n_faces <= 1000
    assert result.genus == 0 and result.is_closed
    assert not result.has_garbage


def test_open_mesh_keeps_its_boundary_loop():
    mesh = hx.sample("open_patch")
    result = simplify_sequential(mesh, 8)
    result.validate()
    assert result.n_boundary_loops == 1
    assert result.n_faces <= 8


def test_steps_are_reported_in_order_and_faces_drop_by_two_inside():
    mesh = hx.sample("icosphere")
    steps = []
    result = simplify_sequential(mesh, mesh.n_faces - 20, on_step=steps.append)
    assert [s.number for s in steps] == list(range(1, len(steps) + 1))
    faces = [mesh.n_faces] + [s.faces_left for s in steps]
    assert all(before - after == 2 for before, after in zip(faces, faces[1:]))  # a closed mesh
    assert faces[-1] == result.n_faces
    assert "collapse 1: edge" in steps[0].describe()
    # The candidates shown after a step are the queue's cheapest, cheapest first.
    costs = [cost for cost, _ in steps[0].next_candidates]
    assert costs == sorted(costs) and len(costs) == 5


def test_each_collapse_is_the_cheapest_allowed_entry_at_its_time():
    # Re-run the queue by hand beside the algorithm: the popped edge is the heap's minimum
    # among current entries, the rule "pop the cheapest before changing the queue".
    mesh = hx.sample("icosphere")
    steps = []
    simplify_sequential(mesh, mesh.n_faces - 10, on_step=steps.append)
    queue = QuadricQueue(mesh.copy())
    first_cost, first_edge = queue.pop()
    assert steps[0].cost == pytest.approx(first_cost)
    assert steps[0].edge == first_edge


def test_stale_entries_are_skipped():
    mesh = hx.sample("icosphere")
    queue = QuadricQueue(mesh.copy())
    _, e = queue.pop()
    queue.push(e)                      # a fresh entry for e
    queue.stamp[e] += 1                # ...made stale, as if e were re-priced elsewhere
    popped = []
    while (entry := queue.pop()) is not None:
        popped.append(entry[1])
    assert e not in popped
    assert len(popped) == mesh.n_edges - 1


def test_tetrahedron_stops_with_a_warning():
    with pytest.warns(hx.MeshWarning, match="no allowed collapse"):
        result = simplify_sequential(hx.sample("tetrahedron"), 2)
    assert result.n_faces == 4


def test_max_steps_stops_early_without_warning(recwarn):
    mesh = hx.sample("spot")
    result = simplify_sequential(mesh, 10, max_steps=3)
    assert result.n_faces == mesh.n_faces - 6
    assert not [w for w in recwarn if issubclass(w.category, hx.MeshWarning)]


def test_input_is_not_modified():
    mesh = hx.sample("spot")
    positions, nexts = mesh.positions.copy(), mesh.halfedge_next.copy()
    simplify_sequential(mesh, 3000)
    assert np.array_equal(mesh.positions, positions) and np.array_equal(mesh.halfedge_next, nexts)


def test_same_quality_as_the_fast_rounds():
    # Both versions minimise the same error; their results should be about as close to
    # the input (measured as the mean quadric-free distance of result vertices to it).
    import trimesh

    mesh = hx.sample("spot")
    original = mesh.to_trimesh()
    errors = []
    for result in (simplify_sequential(mesh, 600), simplify(mesh, 600)):
        _, distance, _ = trimesh.proximity.closest_point(original, result.to_arrays()[0])
        errors.append(distance.mean())
    slow, fast = errors
    assert fast <= 2.0 * slow and slow <= 2.0 * fast


def test_peek_finds_current_entries_behind_many_stale_ones():
    mesh = hx.sample("icosphere")
    queue = QuadricQueue(mesh.copy())
    cheapest = [queue.pop() for _ in range(3)]
    # Re-price the 40 cheapest remaining edges many times: the heap's top fills with stale entries.
    for _ in range(30):
        for _, e, _ in sorted(queue.heap)[:40]:
            queue.push(e)
    seen = queue.peek(5)
    assert len(seen) == 5
    assert all(queue.stamp[e] > 0 and not queue.mesh.edge_deleted[e] for _, e in seen)
    assert [c for c, _ in seen] == sorted(c for c, _ in seen)
    assert not {e for _, e in seen} & {e for _, e in cheapest}
