"""Handles kept across garbage_collect(): refused by name, never silently another element."""

from __future__ import annotations

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.core import ops

ARRAY_NAMES = (
    "positions", "vertex_halfedge", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face",
    "face_halfedge",
)


def _snapshot(mesh: hx.HalfedgeMesh) -> dict[str, np.ndarray]:
    return {name: getattr(mesh, name).copy() for name in ARRAY_NAMES}


def _assert_unchanged(mesh: hx.HalfedgeMesh, before: dict[str, np.ndarray]) -> None:
    for name in ARRAY_NAMES:
        assert np.array_equal(getattr(mesh, name), before[name]), name


@pytest.fixture
def collected() -> tuple[hx.HalfedgeMesh, dict]:
    """The issue's example: handles taken, an edge collapsed, the mesh collected.

    Returns the mesh and the handles taken before the collection (edge 20 among them,
    whose index names another edge afterwards).
    """
    mesh = hx.sample("icosphere")
    kept = {"edge": mesh.edge(20), "halfedge": mesh.halfedge(41), "vertex": mesh.vertex(30),
            "face": mesh.face(25)}
    mesh.collapse(3)
    maps = mesh.garbage_collect()
    assert maps.edges[20] != 20  # so index 20 now names another edge: the silent case
    return mesh, kept


# ---- the example, through every operation ------------------------------------------

@pytest.mark.parametrize("operation", ["flip", "split", "collapse", "can_flip", "can_split", "can_collapse"])
@pytest.mark.parametrize("kind", ["edge", "halfedge"])
def test_an_operation_refuses_a_stale_edge_or_halfedge_and_leaves_the_mesh_untouched(collected, operation, kind):
    mesh, kept = collected
    before = _snapshot(mesh)
    with pytest.raises(hx.StaleHandleError, match=rf"maps\.{kind}s\[{kept[kind]._index}\]") as caught:
        getattr(mesh, operation)(kept[kind])
    assert (caught.value.kind, caught.value.index) == (kind, kept[kind]._index)
    assert (caught.value.handle_generation, caught.value.mesh_generation) == (0, 1)
    _assert_unchanged(mesh, before)


def test_the_free_functions_of_ops_refuse_a_stale_edge_too(collected):
    mesh, kept = collected
    for operation in (ops.flip, ops.split, ops.collapse, ops.can_flip, ops.can_split, ops.can_collapse):
        with pytest.raises(hx.StaleHandleError):
            operation(mesh, kept["edge"])


def test_a_stale_handle_error_is_an_index_error_that_names_the_element_and_the_maps(collected):
    mesh, kept = collected
    with pytest.raises(IndexError) as caught:
        mesh.flip(kept["edge"])
    message = str(caught.value)
    assert "edge 20" in message and "garbage_collect()" in message
    assert "maps.edges[20]" in message and "mesh.edge(new_index)" in message


# ---- navigation and accessors -------------------------------------------------------

@pytest.mark.parametrize("use", [
    lambda h: h.index, lambda h: int(h), lambda h: h.next, lambda h: h.prev, lambda h: h.twin,
    lambda h: h.vertex, lambda h: h.tip, lambda h: h.edge, lambda h: h.face, lambda h: h.is_boundary,
    lambda h: h.is_deleted, lambda h: h.vector, lambda h: h.mesh.halfedge(h),
], ids=["index", "int", "next", "prev", "twin", "vertex", "tip", "edge", "face", "is_boundary", "is_deleted",
        "vector", "mesh.halfedge"])
def test_navigating_from_a_stale_halfedge_raises(collected, use):
    _, kept = collected
    with pytest.raises(hx.StaleHandleError):
        use(kept["halfedge"])


@pytest.mark.parametrize("use", [
    lambda v: v.halfedge, lambda v: v.position, lambda v: v.outgoing(), lambda v: v.neighbors(),
    lambda v: v.faces(), lambda v: v.edges(), lambda v: v.degree, lambda v: v.is_boundary,
    lambda v: v.mesh.vertex(v), lambda v: v.mesh.find_halfedge(v, 0), lambda v: ([0.0] * 200)[v],
], ids=["halfedge", "position", "outgoing", "neighbors", "faces", "edges", "degree", "is_boundary",
        "mesh.vertex", "find_halfedge", "list index"])
def test_navigating_from_a_stale_vertex_raises(collected, use):
    _, kept = collected
    with pytest.raises(hx.StaleHandleError):
        use(kept["vertex"])


def test_a_stale_handle_as_a_numpy_index_is_refused_with_numpys_index_error(collected):
    mesh, kept = collected
    with pytest.raises(IndexError, match="valid indices"):  # numpy replaces the handle's own error
        mesh.positions[kept["vertex"]]


def test_validate_around_and_find_edge_refuse_stale_handles(collected):
    mesh, kept = collected
    with pytest.raises(hx.StaleHandleError):
        mesh.validate_around(vertices=[kept["vertex"]])
    with pytest.raises(hx.StaleHandleError):
        mesh.validate_around(edges=[kept["edge"]])
    with pytest.raises(hx.StaleHandleError):
        mesh.find_edge(kept["vertex"], 0)


def test_writing_the_position_of_a_stale_vertex_raises_and_moves_nothing(collected):
    mesh, kept = collected
    before = mesh.positions.copy()
    with pytest.raises(hx.StaleHandleError):
        kept["vertex"].position = (9.0, 9.0, 9.0)
    assert np.array_equal(mesh.positions, before)


@pytest.mark.parametrize("use", [
    lambda e: e.halfedge, lambda e: e.vertices, lambda e: e.length, lambda e: e.midpoint, lambda e: e.faces(),
    lambda e: e.is_boundary, lambda e: e.mesh.edge(e),
], ids=["halfedge", "vertices", "length", "midpoint", "faces", "is_boundary", "mesh.edge"])
def test_navigating_from_a_stale_edge_raises(collected, use):
    _, kept = collected
    with pytest.raises(hx.StaleHandleError):
        use(kept["edge"])


@pytest.mark.parametrize("use", [
    lambda f: f.halfedge, lambda f: f.halfedges(), lambda f: f.vertices(), lambda f: f.edges(),
    lambda f: f.normal, lambda f: f.area, lambda f: f.centroid, lambda f: f.is_deleted, lambda f: f.mesh.face(f),
], ids=["halfedge", "halfedges", "vertices", "edges", "normal", "area", "centroid", "is_deleted", "mesh.face"])
def test_navigating_from_a_stale_face_raises(collected, use):
    _, kept = collected
    with pytest.raises(hx.StaleHandleError):
        use(kept["face"])


# ---- what still works ------------------------------------------------------------------

def test_a_stale_handle_still_compares_hashes_and_shows_without_raising(collected):
    mesh, kept = collected
    assert repr(kept["edge"]) == "Edge(20: stale, taken before garbage_collect())"
    assert kept["edge"].is_stale and not mesh.edge(20).is_stale
    assert kept["edge"] != mesh.edge(20)  # the same index, but another element now
    assert hash(kept["edge"]) == hash(mesh.edge(20))
    assert {kept["edge"], mesh.edge(20)} == {kept["edge"], mesh.edge(20)}


def test_integers_and_handles_taken_after_collecting_still_work(collected):
    mesh, _ = collected
    assert mesh.can_flip(20)
    assert mesh.flip(mesh.edge(20)) == mesh.edge(20)
    assert mesh.flip(20).index == 20
    mesh.validate()


def test_the_maps_turn_an_old_index_into_a_fresh_handle():
    mesh = hx.sample("icosphere")
    old = mesh.edge(20)
    ends = {int(v) for v in old.vertices}
    mesh.collapse(3)
    maps = mesh.garbage_collect()
    fresh = mesh.edge(maps.edges[old._index])
    assert {int(maps.vertices[v]) for v in ends} == {int(v) for v in fresh.vertices}


def test_local_operations_keep_handles_valid():
    mesh = hx.sample("icosphere")
    edge, vertex = mesh.edge(20), mesh.vertex(30)
    mesh.flip(5)
    mesh.collapse(3)
    assert not edge.is_stale and edge.index == 20 and vertex.position is not None


def test_collecting_a_mesh_without_deletions_renumbers_nothing_and_keeps_handles(square):
    edge = square.edge(1)
    square.garbage_collect()
    assert square.generation == 0 and edge.index == 1 and edge.vertices


def test_each_renumbering_collection_starts_a_new_generation_and_copies_keep_theirs(square):
    vertex = square.vertex(0)
    square.split(2)
    square.collapse(2)
    square.garbage_collect()
    copy = square.copy()
    assert square.generation == copy.generation == 1
    with pytest.raises(hx.StaleHandleError):
        vertex.position
    assert copy.vertex(0).position is not None


def test_a_handle_two_collections_old_says_to_map_through_each():
    mesh = hx.sample("icosphere")
    vertex = mesh.vertex(0)
    for _ in range(2):
        mesh.collapse(next(e for e in range(mesh.n_edge_slots) if mesh.can_collapse(e)))
        mesh.garbage_collect()
    with pytest.raises(hx.StaleHandleError, match="2 garbage_collect\\(\\) calls .* each call's maps"):
        vertex.halfedge
    assert mesh.generation == 2


def test_a_handle_of_another_mesh_is_still_refused_first(collected):
    mesh, kept = collected
    with pytest.raises(ValueError, match="another mesh"):
        mesh.copy().flip(mesh.edge(20))
    with pytest.raises(ValueError, match="another mesh"):
        hx.sample("icosphere").flip(kept["edge"])


def test_no_handle_kept_across_a_renumbering_collection_names_any_element():
    """The issue's survey: keep every handle, collapse at random, collect; none may act."""
    rng = np.random.default_rng(25)
    mesh = hx.sample("icosphere")
    kept = ([mesh.vertex(i) for i in range(mesh.n_vertex_slots)] + [mesh.edge(i) for i in range(mesh.n_edge_slots)]
            + [mesh.halfedge(i) for i in range(mesh.n_halfedge_slots)] + [mesh.face(i) for i in range(mesh.n_face_slots)])
    for e in rng.permutation(mesh.n_edge_slots)[:40].tolist():
        if not mesh.edge_deleted[e] and mesh.can_collapse(e):
            mesh.collapse(e)
    mesh.garbage_collect()
    for handle in kept:
        with pytest.raises(hx.StaleHandleError):
            int(handle)
    assert all(handle.is_stale for handle in kept)


def test_a_list_of_live_elements_kept_across_a_collection_gives_stale_handles():
    mesh = hx.sample("icosphere")
    edges = mesh.edges
    mesh.collapse(3)
    mesh.garbage_collect()
    with pytest.raises(hx.StaleHandleError):
        next(iter(edges)).index
    with pytest.raises(hx.StaleHandleError):
        mesh.flip(edges[20])
    assert not mesh.edges[20].is_stale
