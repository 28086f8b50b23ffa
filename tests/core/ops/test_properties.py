"""Property tests: random sequences of flips, splits and collapses on random and real meshes.

After every step: ``validate()``; counts change exactly as stated; V - E + F, the number
of boundary loops and (every few steps) the genus stay the same; a refused operation
leaves the arrays bit-identical; a collapse from the other end gives the same mesh up
to relabelling; a logged operation replays to the same arrays. At the end,
``garbage_collect()`` gives the same mesh, compact.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.data import sample
from halfedge_edu.core.ops import (
    OperationLog, can_collapse, can_flip, can_split, collapse, flip, link_condition, split,
)
from tests.core.ops.helpers import (
    assert_replay_gives, assert_same_mesh, assert_unchanged, counts, jittered, pillow, snapshot,
)
from tests.strategies import build, cases

OPERATIONS = {"flip": (can_flip, flip), "split": (can_split, split), "collapse": (can_collapse, collapse)}
SMALL_SAMPLES = ["tetrahedron", "cube", "octahedron", "open_patch", "single_collapse", "strip", "figure8", "lone_triangle"]


def expected_delta(mesh: hx.HalfedgeMesh, operation: str, e: int) -> tuple[int, int, int]:
    boundary = mesh.edge(e).is_boundary
    if operation == "flip":
        return (0, 0, 0)
    if operation == "split":
        return (1, 2, 1) if boundary else (1, 3, 2)
    return (-1, -2, -1) if boundary else (-1, -3, -2)


def random_step(mesh: hx.HalfedgeMesh, rng: np.random.Generator, *, compare_ends: bool, log_every: int = 5) -> str:
    """One random operation on a random live edge, checked every way this module promises."""
    live = np.flatnonzero(~mesh.edge_deleted)
    e = int(rng.choice(live))
    operation = str(rng.choice(["flip", "split", "collapse"], p=[0.4, 0.2, 0.4]))
    can, act = OPERATIONS[operation]
    check = can(mesh, e)
    if operation == "collapse":
        condition = link_condition(mesh, e)
        assert condition.extra == condition.shared - condition.link_ab  # the ring-only answer is the textbook's
        if check.rule != "back-to-back":
            assert bool(condition) == bool(check), check.reason
    if not check:
        before = snapshot(mesh)
        with pytest.raises(hx.TopologyError):
            act(mesh, e)
        assert_unchanged(mesh, before)
        return "refused"

    before_counts, euler, loops = counts(mesh), mesh.euler_characteristic, mesh.n_boundary_loops
    delta = expected_delta(mesh, operation, e)
    other = None
    if operation == "collapse" and compare_ends:
        other = mesh.copy()
        collapse(other, other.halfedge(2 * e + 1))
    # A split at the exact midpoint could put two vertices on one spot (split a - b,
    # flip a - b back in, split it again), which canonical_form cannot tell apart.
    arguments = (e,)
    if operation == "split":
        arguments = (e, mesh.edge(e).midpoint + rng.normal(scale=1e-4, size=3))
    if rng.integers(log_every) == 0:
        before, log = mesh.copy(), OperationLog()
        act(mesh, *arguments, log=log)
        assert_replay_gives(before, mesh, log)
    else:
        act(mesh, *arguments)
    mesh.validate()
    assert tuple(a - b for a, b in zip(counts(mesh), before_counts)) == delta
    assert mesh.euler_characteristic == euler
    assert mesh.n_boundary_loops == loops
    if other is not None:
        other.validate()
        assert_same_mesh(mesh, other)
    return operation


def assert_garbage_collect_keeps_the_mesh(mesh: hx.HalfedgeMesh) -> None:
    compacted = mesh.copy()
    maps = compacted.garbage_collect()
    compacted.validate()
    assert not compacted.has_garbage
    assert (compacted.n_vertex_slots, compacted.n_edge_slots, compacted.n_face_slots) == counts(compacted)
    assert_same_mesh(compacted, mesh)
    live = np.flatnonzero(~mesh.vertex_deleted)
    np.testing.assert_array_equal(compacted.positions[maps.vertices[live]], mesh.positions[live])


@given(case=cases(), seed=st.integers(0, 2**32 - 1), n_steps=st.integers(1, 40))
def test_random_operations_on_random_closed_and_open_meshes(case, seed, n_steps):
    rng = np.random.default_rng(seed)
    mesh = jittered(build(case), seed)
    genus = mesh.genus
    for _ in range(n_steps):
        random_step(mesh, rng, compare_ends=True)
    assert mesh.genus == genus
    assert_garbage_collect_keeps_the_mesh(mesh)


@given(name=st.sampled_from(SMALL_SAMPLES), seed=st.integers(0, 2**32 - 1), n_steps=st.integers(1, 30))
def test_random_operations_on_the_small_sample_meshes(name, seed, n_steps):
    rng = np.random.default_rng(seed)
    mesh = jittered(sample(name), seed)
    for _ in range(n_steps):
        random_step(mesh, rng, compare_ends=True)
    assert_garbage_collect_keeps_the_mesh(mesh)


def test_operations_after_garbage_collect_keep_working():
    rng = np.random.default_rng(7)
    mesh = jittered(sample("icosphere", subdivisions=1), 7)
    for _ in range(3):
        for _step in range(30):
            random_step(mesh, rng, compare_ends=False)
        mesh.garbage_collect()
        mesh.validate()


@lru_cache(maxsize=None)
def _real(name: str) -> hx.HalfedgeMesh:
    return sample(name)


@pytest.mark.parametrize("name", ["spot", "bunny"])
@settings(max_examples=3)
@given(seed=st.integers(0, 2**32 - 1))
def test_random_operations_on_the_bundled_real_meshes(name, seed):
    rng = np.random.default_rng(seed)
    mesh = _real(name).copy()
    for step in range(40):
        random_step(mesh, rng, compare_ends=step % 10 == 0, log_every=10)
    assert_garbage_collect_keeps_the_mesh(mesh)


def test_the_pillow_is_refused_every_operation():
    mesh = pillow()
    for e in range(3):
        assert not can_flip(mesh, e) and not can_collapse(mesh, e) and not can_split(mesh, e)
        assert link_condition(mesh, e)  # the textbook condition alone would allow a collapse
