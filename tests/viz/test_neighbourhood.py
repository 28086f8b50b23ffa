"""Rings walked only where asked give the answers of the whole-mesh adjacency, on every
in-between state a stepper shows (where rings need not close)."""

from __future__ import annotations

import numpy as np
import pytest

from halfedge_edu.core.ops import OperationLog, collapse, flip, split
from halfedge_edu.data import sample
from halfedge_edu.viz.neighbourhood import Origins, Rings, ranges
from halfedge_edu.viz.steppers import group_changes


def _whole_mesh_mark(mesh, seeds: np.ndarray, rings: int) -> np.ndarray:
    """The reference: breadth-first over ``mesh.vertex_adjacency()`` (every ring walked)."""
    offsets, neighbors = mesh.vertex_adjacency()
    mark = np.zeros(mesh.n_vertex_slots, dtype=bool)
    mark[seeds] = True
    frontier = seeds
    for _ in range(rings):
        reached = neighbors[ranges(offsets[frontier], offsets[frontier + 1])]
        frontier = np.unique(reached[~mark[reached]])
        if len(frontier) == 0:
            break
        mark[frontier] = True
    return mark


def _whole_mesh_window(mesh, seeds: np.ndarray, rings: int) -> tuple[np.ndarray, np.ndarray]:
    """The reference window: the marked vertices and, from ``mesh.one_rings()``, the
    halfedges between them."""
    mark = _whole_mesh_mark(mesh, seeds, rings)
    inside = np.flatnonzero(mark)
    offsets, _ = mesh.vertex_adjacency()
    outgoing = mesh.one_rings().halfedges[ranges(offsets[inside], offsets[inside + 1])].astype(np.int64)
    return inside, np.sort(outgoing[mark[mesh.halfedge_vertex[outgoing ^ 1]]])


def _states(mesh, operation, edge):
    """The mesh before ``operation`` on ``edge``, then after each step a stepper shows
    (:func:`group_changes`); and the vertices the operation named."""
    before, after, log = mesh.copy(), mesh.copy(), OperationLog()
    operation(after, edge, log=log)
    named = np.array(sorted({index for kind, index in log.named.values() if kind == "vertex"}), dtype=np.int64)
    states = []
    for stop in [0] + [stop for _, stop in group_changes(log.changes)]:
        state = before.copy()
        log.replay(state, stop)
        states.append(state)
    return states, named


@pytest.mark.parametrize("name, edge, operation", [
    (name, edge, operation) for name, edge in (("bunny", 5000), ("cube", 3), ("open_patch", 12))
    for operation in (flip, split, collapse)
] + [("open_patch", 0, split), ("open_patch", 0, collapse)])       # a boundary edge
def test_rings_agree_with_the_whole_mesh_adjacency_on_every_step(name, edge, operation):
    states, named = _states(sample(name), operation, edge)
    origins = Origins(states[0])
    for state in states:
        rings = Rings(state)
        # Seeds that still exist, and the new vertex of a split once it does.
        seeds = named[(named < state.n_vertex_slots)]
        seeds = seeds[~state.vertex_deleted[seeds]]
        for depth in (1, 2, 3):
            assert np.array_equal(rings.mark(seeds, depth), _whole_mesh_mark(state, seeds, depth))
        inside, window = rings.window(seeds, 2)
        assert np.array_equal(Rings(state, origins.degree(state)).mark(seeds, 2), rings.mark(seeds, 2))
        expected_inside, expected_window = _whole_mesh_window(state, seeds, 2)
        assert np.array_equal(inside, expected_inside) and np.array_equal(window, expected_window)


def test_the_collapse_steps_include_rings_that_do_not_close():
    """The comparison above covers broken rings: some step of a collapse has a live vertex
    whose walk does not come back to its start after its degree."""
    states, _ = _states(sample("bunny"), collapse, 5000)
    assert any(not state.one_rings().closed.all() for state in states)


def test_rings_are_for_one_mesh_until_its_connectivity_changes():
    mesh = sample("cube")
    rings = Rings(mesh)
    assert rings.is_for(mesh) and not rings.is_for(mesh.copy())
    flip(mesh, 3)
    assert not rings.is_for(mesh)


def test_a_vertex_flagged_deleted_has_no_ring_even_with_halfedges_still_leaving_it():
    """As in the whole-mesh adjacency, which walks live vertices only: a collapse may flag
    its removed vertex before the last pointers leave it."""
    mesh = sample("bunny")
    removed = int(mesh.halfedge_vertex[10000])
    mesh.delete_vertex(removed)
    seeds = np.array([int(mesh.halfedge_vertex[10001])])               # a neighbour of it
    for depth in (1, 2, 3):
        assert np.array_equal(Rings(mesh).mark(seeds, depth), _whole_mesh_mark(mesh, seeds, depth))


@pytest.mark.parametrize("name, edge, operation", [
    ("bunny", 5000, flip), ("bunny", 5000, split), ("bunny", 5000, collapse), ("cube", 0, collapse),
    ("open_patch", 0, split), ("open_patch", 12, collapse),
])
def test_origins_answer_as_the_whole_arrays_do_on_every_step(name, edge, operation):
    """The table made before the operation, with the halfedges changed since, gives each
    state's degrees and the halfedges leaving any vertex, as a pass over the state would."""
    states, named = _states(sample(name), operation, edge)
    origins = Origins(states[0])
    for state in states:
        assert np.array_equal(origins.degree(state), state.vertex_degrees())
        live = np.flatnonzero(~state.halfedge_deleted)
        vertices = np.unique(np.concatenate([named, [0, 7]]))
        vertices = vertices[vertices < state.n_vertex_slots]
        expected = live[np.isin(state.halfedge_vertex[live], vertices)]
        assert np.array_equal(origins.leaving(state, vertices), expected)
    assert len(origins.changed(states[-1])) > 0


def test_origins_start_again_on_a_mesh_with_fewer_slots():
    mesh = sample("bunny")
    origins = Origins(mesh)
    small = sample("cube")
    assert np.array_equal(origins.degree(small), small.vertex_degrees())
    assert np.array_equal(origins.leaving(small, [0]), np.flatnonzero(small.halfedge_vertex == 0))


def test_marks_asked_in_any_order_are_levels_of_one_walk_per_seeds():
    mesh = sample("bunny")
    rings, seeds, other = Rings(mesh), np.array([10, 11]), np.array([500])
    for asked_seeds, depth in ((seeds, 2), (seeds, 1), (seeds, 3), (other, 1), (seeds, 0), (seeds, 2)):
        assert np.array_equal(rings.mark(asked_seeds, depth), _whole_mesh_mark(mesh, asked_seeds, depth))
    rings.mark(seeds, 2)[:] = True                        # an answer is the caller's to change
    assert np.array_equal(rings.mark(seeds, 2), _whole_mesh_mark(mesh, seeds, 2))
