"""check_tangential_smoothing passes the reference answer and names the common slips."""

from __future__ import annotations

import numpy as np
import pytest

from halfedge_edu.algorithms.normals import vertex_normals
from halfedge_edu.exercises.remesh_checks import (
    _library,
    check_tangential_smoothing,
    smoothing_cases,
    tangential_smoothing_reference,
)


def smoothing(mesh, *, normal="area", keep_normal_part=False, jacobi=True, move_boundary=False, unit=True):
    """A tangential smoothing step with one slip switched on by keyword."""
    P = mesh.positions
    if unit:
        normals = vertex_normals(mesh, weighting=normal)
    else:
        normals = np.zeros_like(P)
        for f in mesh.faces:
            a, b, c = (P[v.index] for v in f.vertices())
            for v in f.vertices():
                normals[v.index] += np.cross(b - a, c - a)
    new = P.copy()
    source = P if jacobi else new
    centroids = {v.index: np.mean([P[u.index] for u in v.neighbors()], axis=0) for v in mesh.vertices}
    for v in mesh.vertices:
        if v.is_boundary and not move_boundary:
            continue
        centroid = centroids[v.index] if jacobi else np.mean([source[u.index] for u in v.neighbors()], axis=0)
        step = centroid - P[v.index]
        n = normals[v.index]
        new[v.index] = P[v.index] + (step if keep_normal_part else step - (step @ n) * n)
    return new


def test_the_reference_agrees_with_the_library_on_every_case():
    for _, mesh in smoothing_cases():
        assert np.allclose(tangential_smoothing_reference(mesh), _library(mesh), rtol=1e-7, atol=1e-9)


def test_the_reference_answer_passes():
    result = check_tangential_smoothing(tangential_smoothing_reference)
    assert result, result.message
    assert result.message.startswith("All good!") and len(result.checked) == 4


@pytest.mark.parametrize("slip, words", [
    (dict(keep_normal_part=True), "Yours is the centroid itself"),
    (dict(jacobi=False), "Compute every centroid first"),
    (dict(unit=False), "Your normal is not of length 1"),
    (dict(normal="uniform"), "gives every face the same weight"),
    (dict(move_boundary=True), "is on the boundary, so it stays"),
])
def test_each_slip_is_named(slip, words):
    result = check_tangential_smoothing(lambda mesh: smoothing(mesh, **slip))
    assert not result
    assert words in result.message, result.message
    assert result.element[0] == "vertex" and result.mesh is not None


def test_changing_the_mesh_in_place_is_reported_and_undone():
    def in_place(mesh):
        mesh.positions[:] = smoothing(mesh)
        return mesh.positions

    result = check_tangential_smoothing(in_place)
    assert not result and "changed mesh.positions" in result.message


def test_blanks_are_reported_before_running():
    def blank(mesh):
        return ...

    assert "still has blanks" in check_tangential_smoothing(blank).message


def test_a_wrong_shape_is_reported():
    result = check_tangential_smoothing(lambda mesh: mesh.positions[:3].copy())
    assert not result and "shape" in result.message


def damped(weight, **slips):
    """CMU's vertex averaging: q = p + w (step), the step the same as the library's."""
    def step(mesh):
        return mesh.positions + weight * (smoothing(mesh, **slips) - mesh.positions)
    return step


def test_cmus_damping_weight_of_one_fifth_is_accepted_and_named():
    result = check_tangential_smoothing(damped(0.2))
    assert result.passed, result.message
    assert "You damp each step with w = 0.2 (CMU's 1/5)" in result.message
    assert "takes the full tangential step, w = 1, because" in result.message


def test_damping_that_keeps_the_normal_part_is_named():
    result = check_tangential_smoothing(damped(0.2, keep_normal_part=True))
    assert not result.passed
    assert "your vertices move p + w (c - p) with w = 0.2 (CMU's 1/5)" in result.message
    assert "with its normal part kept" in result.message


def test_a_weight_that_changes_between_meshes_is_named():
    weights = iter([0.2, 0.5, 0.5, 0.5])

    def changing(mesh):
        return damped(next(weights))(mesh)

    result = check_tangential_smoothing(changing)
    assert not result.passed and result.mesh_name.startswith("icosphere")
    assert "damped with w = 0.5 here but w = 0.2 (CMU's 1/5) before" in result.message


def test_the_exact_answer_is_not_praised_as_a_damped_step():
    """Rounding makes the fitted weight 0.99999999...: that is the full step, not CMU's damping."""
    from halfedge_edu.exercises.remesh_checks import check_tangential_smoothing, tangential_smoothing_reference

    for seed in (None, 1, 2):
        result = check_tangential_smoothing(tangential_smoothing_reference, seed=seed)
        assert result.passed and "damp" not in result.message, result.message


def _cross_products(v):
    for f in v.faces():
        a, b, c = (u.position for u in f.vertices())
        yield np.cross(b - a, c - a)


def area_weighted_normal(mesh, v):
    total = sum(_cross_products(v))
    return total / np.linalg.norm(total)


NORMAL_SLIPS = {
    "every face counted the same": lambda mesh, v: (lambda t: t / np.linalg.norm(t))(
        sum(x / np.linalg.norm(x) for x in _cross_products(v))),
    "It points inwards": lambda mesh, v: -area_weighted_normal(mesh, v),
    "Right direction, wrong length": lambda mesh, v: sum(_cross_products(v)),
    "the normal of one face only": lambda mesh, v: (lambda x: x / np.linalg.norm(x))(next(_cross_products(v))),
}


def test_the_area_weighted_normal_passes_public_and_hidden_cases():
    from halfedge_edu.exercises import check_vertex_normal

    assert check_vertex_normal(area_weighted_normal).passed
    assert all(check_vertex_normal(area_weighted_normal, seed=seed).passed for seed in (1, 2, 3))


@pytest.mark.parametrize("named", sorted(NORMAL_SLIPS))
def test_each_normal_slip_is_named(named):
    from halfedge_edu.exercises import check_vertex_normal

    result = check_vertex_normal(NORMAL_SLIPS[named])
    assert not result.passed and named in result.message, result.message


def _four(mesh, e):
    h = mesh.edge(e).halfedge
    return [(h.vertex, -1), (h.tip, -1), (h.prev.vertex, +1), (h.twin.prev.vertex, +1)]


def flip_improves(mesh, e):
    """CMU's remeshing step 3: flip when the four vertices' distance from their ideal degree drops."""
    ideal = lambda v: 4 if v.is_boundary else 6  # noqa: E731
    four = _four(mesh, e)
    return sum(abs(v.degree + c - ideal(v)) for v, c in four) < sum(abs(v.degree - ideal(v)) for v, _ in four)


def test_the_flip_rule_passes_public_and_hidden_cases():
    from halfedge_edu.exercises import check_flip_improves

    assert check_flip_improves(flip_improves).passed
    assert all(check_flip_improves(flip_improves, seed=seed).passed for seed in (1, 2, 3))


@pytest.mark.parametrize(("slip", "named"), [
    (lambda mesh, e: sum(abs(v.degree + c - 6) for v, c in _four(mesh, e)) < sum(abs(v.degree - 6) for v, _ in _four(mesh, e)),
     "On the boundary the ideal degree is 4"),
    (lambda mesh, e: sum(abs(v.degree + c - 6) for v, c in _four(mesh, e)[:2]) < sum(abs(v.degree - 6) for v, _ in _four(mesh, e)[:2]),
     "gives one to each opposite vertex"),
])
def test_flip_rule_slips_are_refused_with_the_degrees_named(slip, named):
    from halfedge_edu.exercises import check_flip_improves

    result = check_flip_improves(slip)
    assert not result.passed and named in result.message, result.message


def split_long_edges(mesh, L):
    """CMU's remeshing step 1: split every edge longer than 4/3 L, round after round, until none is."""
    from halfedge_edu.core.ops import split

    while True:
        ends = mesh.edge_vertices()
        long = [e for e in range(mesh.n_edge_slots) if not mesh.edge_deleted[e]
                and np.linalg.norm(mesh.positions[ends[e, 0]] - mesh.positions[ends[e, 1]]) > 4 / 3 * L]
        if not long:
            return
        for e in long:
            split(mesh, e)


def test_the_split_phase_passes_public_and_hidden_cases():
    from halfedge_edu.exercises import check_split_long_edges

    assert check_split_long_edges(split_long_edges).passed
    assert all(check_split_long_edges(split_long_edges, seed=seed).passed for seed in (1, 2, 3))


def test_a_single_round_of_splits_is_told_to_keep_splitting():
    from halfedge_edu.core.ops import split
    from halfedge_edu.exercises import check_split_long_edges

    def one_round(mesh, L):
        ends = mesh.edge_vertices()
        for e in [e for e in range(mesh.n_edge_slots)
                  if np.linalg.norm(mesh.positions[ends[e, 0]] - mesh.positions[ends[e, 1]]) > 4 / 3 * L]:
            split(mesh, e)

    result = check_split_long_edges(one_round)
    assert not result.passed and "keep splitting until no edge is longer" in result.message


# --------------------------------------------------------------------------------------
# The collapse phase: code a CMU student would write for step 2
# --------------------------------------------------------------------------------------

def collapse_phase(*, guard=True, ask_link=True, check_link=True, skip_boundary=True, below=0.8, rounds=None):
    """A learner's ``collapse_short_edges(mesh, L)``, right by default; each keyword is one slip.

    guard=False: no 4/3 L test around the merged vertex; ask_link=False: no can_collapse;
    check_link=False: the teaching switch that skips the link condition; skip_boundary=False:
    boundary edges collapsed too; below: the threshold as a multiple of L; rounds: stop
    after that many rounds instead of going round until nothing changes.
    """
    def collapse_short_edges(mesh, L):
        done_rounds = 0
        while True:
            collapsed = 0
            for e in range(mesh.n_edge_slots):
                if mesh.edge_deleted[e]:
                    continue
                edge = mesh.edge(e)
                a, b = edge.vertices
                if (skip_boundary and edge.is_boundary) or np.linalg.norm(a.position - b.position) >= below * L:
                    continue
                if ask_link and check_link and not mesh.can_collapse(e):
                    continue
                middle = (a.position + b.position) / 2
                ring = {u.index for u in a.neighbors()} | {u.index for u in b.neighbors()}
                if guard and any(np.linalg.norm(mesh.positions[u] - middle) > 4 / 3 * L
                                 for u in ring - {a.index, b.index}):
                    continue
                mesh.collapse(e, check_link=check_link)
                collapsed += 1
            done_rounds += 1
            if collapsed == 0 or done_rounds == rounds:
                return

    return collapse_short_edges


def test_the_collapse_phase_passes_public_and_hidden_cases():
    from halfedge_edu.exercises import check_collapse_short_edges

    right = collapse_phase()
    result = check_collapse_short_edges(right)
    assert result.passed and result.total == 4, result.message
    assert all(check_collapse_short_edges(right, seed=seed).passed for seed in (1, 2, 3, 4, 5))


def test_the_collapse_phase_accepts_any_order_of_collapses():
    from halfedge_edu.exercises import check_collapse_short_edges

    def shortest_first(mesh, L):
        """Each round takes the edges shortest first (as a priority queue would), not in index order."""
        def length(edge):
            a, b = edge.vertices
            return np.linalg.norm(a.position - b.position)

        def may_go(edge):
            a, b = edge.vertices
            if edge.is_boundary or length(edge) >= 0.8 * L or not mesh.can_collapse(edge.index):
                return False
            middle = (a.position + b.position) / 2
            ring = ({u.index for u in a.neighbors()} | {u.index for u in b.neighbors()}) - {a.index, b.index}
            return all(np.linalg.norm(mesh.positions[u] - middle) <= 4 / 3 * L for u in ring)

        while True:
            collapsed = 0
            for e in sorted((edge.index for edge in mesh.edges), key=lambda e: length(mesh.edge(e))):
                if not mesh.edge_deleted[e] and may_go(mesh.edge(e)):
                    mesh.collapse(e)
                    collapsed += 1
            if not collapsed:
                return

    assert check_collapse_short_edges(shortest_first).passed
    assert check_collapse_short_edges(shortest_first, seed=2).passed


def test_cmus_recipe_as_written_without_the_4_3_test_is_accepted_and_named():
    """CMU's text says only "collapse all edges that are shorter than 4L/5": that answer is
    right by its course, and the check says which convention it recognised."""
    from halfedge_edu.exercises import check_collapse_short_edges

    cmu = collapse_phase(guard=False)
    result = check_collapse_short_edges(cmu)
    assert result.passed and "CMU's recipe as written" in result.message, result.message
    assert all(check_collapse_short_edges(cmu, seed=seed).passed for seed in (1, 2, 3))
    assert "Botsch and Kobbelt's rule" in check_collapse_short_edges(collapse_phase()).message


def test_cmus_recipe_as_written_that_stops_early_is_told_to_go_round_again():
    from halfedge_edu.exercises import check_collapse_short_edges

    results = [check_collapse_short_edges(collapse_phase(guard=False, rounds=1), seed=seed) for seed in range(6)]
    refused = [result for result in results if not result.passed]
    assert refused and all("go round again" in r.message for r in refused), [r.message for r in results]


@pytest.mark.parametrize(("slip", "named"), [
    ({"ask_link": False}, "Ask mesh.can_collapse(e) first"),
    ({"check_link": False}, "the link condition"),
    ({"skip_boundary": False}, "you collapsed boundary edges"),
    ({"below": 1.0}, "compare with 0.8 * L, not L"),
    ({"below": 0.5}, "could still go"),
])
def test_collapse_phase_slips_are_refused_with_the_slip_named(slip, named):
    from halfedge_edu.exercises import check_collapse_short_edges

    result = check_collapse_short_edges(collapse_phase(**slip))
    assert not result.passed and named in result.message, result.message


def test_a_single_round_of_collapses_is_told_to_go_round_again():
    from halfedge_edu.exercises import check_collapse_short_edges

    one_round = collapse_phase(rounds=1)
    results = [check_collapse_short_edges(one_round, seed=seed) for seed in range(6)]
    refused = [result for result in results if not result.passed]
    assert refused and all("go round again until a pass collapses nothing" in r.message for r in refused)


def test_a_damaged_mesh_from_skipping_the_link_condition_is_named():
    from halfedge_edu.exercises.remesh_checks import _link_damage
    from halfedge_edu.data import sample

    tetrahedron = sample("tetrahedron")
    tetrahedron.collapse(0, check_link=False)
    tetrahedron.topology_changed()
    assert "back to back" in _link_damage(tetrahedron) or "two edges join" in _link_damage(tetrahedron)
    assert _link_damage(sample("icosphere", subdivisions=1)) is None
