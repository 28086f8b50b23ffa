"""The checks of chapters 09, 10 and 12 pass the reference answers and name common slips."""

from __future__ import annotations

import numpy as np
import pytest

from halfedge_edu.algorithms.bezier import de_casteljau as library_de_casteljau
from halfedge_edu.exercises.algorithm_checks import (
    check_de_casteljau,
    check_loop_rules,
    check_optimal_point,
    check_plane_quadric,
    warren_beta,
)


def edge_point(mesh, edge):
    h = edge.halfedge
    a, b = h.vertex.position, h.tip.position
    if edge.is_boundary:
        return 0.5 * (a + b)
    return 0.375 * (a + b) + 0.125 * (h.prev.vertex.position + h.twin.prev.vertex.position)


def vertex_point(mesh, vertex):
    v = vertex.position
    if vertex.is_boundary:
        h = vertex.halfedge
        return 0.75 * v + 0.125 * (h.tip.position + h.prev.vertex.position)
    ring = [u.position for u in vertex.neighbors()]
    beta = warren_beta(len(ring))
    return (1 - len(ring) * beta) * v + beta * np.sum(ring, axis=0)


def plane_quadric(a, b, c):
    n = np.cross(b - a, c - a)
    n = n / np.linalg.norm(n)
    p = np.append(n, -n @ a)
    return np.outer(p, p)


def optimal_point(Q, a, b):
    A, q = Q[:3, :3], Q[:3, 3]
    if abs(np.linalg.det(A)) < 1e-9:
        return 0.5 * (a + b)
    return np.linalg.solve(A, -q)


def test_reference_answers_pass():
    for result in (check_loop_rules(edge_point, vertex_point), check_plane_quadric(plane_quadric),
                   check_optimal_point(optimal_point), check_de_casteljau(library_de_casteljau)):
        assert result, result.message
        assert result.message.startswith("All good!")


def test_loop_midpoint_edge_point_is_named():
    result = check_loop_rules(edge_point=lambda mesh, e: 0.5 * (e.halfedge.vertex.position + e.halfedge.tip.position))
    assert not result and "That is the midpoint" in result.message
    assert result.element == ("halfedge", 0)


def test_loop_degree_three_beta_slip_is_named():
    def naive(mesh, vertex):
        ring = [u.position for u in vertex.neighbors()]
        beta = 3 / (8 * len(ring))
        return (1 - len(ring) * beta) * vertex.position + beta * np.sum(ring, axis=0)

    result = check_loop_rules(vertex_point=naive)
    assert "for degree 3 Warren's rule has its own value, beta = 3/16" in result.message


def test_loop_interior_rule_on_the_boundary_is_judged_on_closed_meshes_and_the_slip_still_named():
    """The Loop assignment asks for closed meshes only: an interior rule used everywhere is right
    there, so the check passes on the closed meshes and says what the boundary got."""
    def everywhere(mesh, vertex):
        ring = [u.position for u in vertex.neighbors()]
        beta = warren_beta(len(ring))
        return (1 - len(ring) * beta) * vertex.position + beta * np.sum(ring, axis=0)

    result = check_loop_rules(edge_point, everywhere)
    assert result.passed, result.message
    assert "judged on the closed meshes only" in result.message
    assert "On 'open patch (a boundary)'" in result.message and "interior rule" in result.message


def closed_only_edge_point(mesh, edge):
    """The Loop assignment's edge point, written for closed meshes: both opposite corners exist."""
    h = edge.halfedge
    a, b = h.vertex.position, h.tip.position
    c, d = h.prev.vertex.position, h.twin.prev.vertex.position
    return 3 / 8 * (a + b) + 1 / 8 * (c + d)


def loop_original_vertex_point(mesh, vertex):
    """The Loop assignment's other choice of weights: Loop's own beta with the cosine."""
    ring = [u.position for u in vertex.neighbors()]
    n = len(ring)
    beta = (5 / 8 - (3 / 8 + 1 / 4 * np.cos(2 * np.pi / n)) ** 2) / n
    return (1 - n * beta) * vertex.position + beta * np.sum(ring, axis=0)


def test_loop_original_beta_and_closed_only_rules_are_accepted_and_the_conventions_said():
    result = check_loop_rules(closed_only_edge_point, loop_original_vertex_point)
    assert result.passed, result.message
    assert "Loop's original beta" in result.message and "judged on the closed meshes only" in result.message
    assert check_loop_rules(closed_only_edge_point, loop_original_vertex_point, seed=3).passed


def test_switching_between_the_two_betas_is_refused():
    def mixed(mesh, vertex):
        ring = [u.position for u in vertex.neighbors()]
        chosen = vertex_point if len(ring) == 4 else loop_original_vertex_point
        return chosen(mesh, vertex)

    result = check_loop_rules(vertex_point=mixed)
    assert not result.passed and "choose one weighting" in result.message


def test_loop_writing_positions_is_refused():
    def moving(mesh, edge):
        mesh.positions[0] = 0.0
        return edge_point(mesh, edge)

    assert "changed mesh.positions" in check_loop_rules(edge_point=moving).message


def test_blanks_are_reported_before_running():
    def unfinished(mesh, edge):
        return ...

    assert "still has blanks" in check_loop_rules(edge_point=unfinished).message


def test_quadric_slips_are_named():
    def unnormalized(a, b, c):
        n = np.cross(b - a, c - a)
        return np.outer(np.append(n, -n @ a), np.append(n, -n @ a))

    def wrong_sign(a, b, c):
        n = np.cross(b - a, c - a)
        n = n / np.linalg.norm(n)
        return np.outer(np.append(n, n @ a), np.append(n, n @ a))

    def weighted(a, b, c):
        return 0.5 * np.linalg.norm(np.cross(b - a, c - a)) * plane_quadric(a, b, c)

    assert "length 1" in check_plane_quadric(unnormalized).message
    assert "wrong sign" in check_plane_quadric(wrong_sign).message
    assert "leave the area out" in check_plane_quadric(weighted).message


def test_optimal_point_needs_the_solve_and_the_fallback():
    assert "only the fallback" in check_optimal_point(lambda Q, a, b: 0.5 * (a + b)).message
    solve_only = check_optimal_point(lambda Q, a, b: np.linalg.solve(Q[:3, :3], -Q[:3, 3]))
    assert "LinAlgError" in solve_only.message and "midpoint" in solve_only.message
    assert "sign is off" in check_optimal_point(lambda Q, a, b: np.linalg.solve(Q[:3, :3], Q[:3, 3])).message


def test_de_casteljau_slips_are_named():
    def swapped(points, t):
        return library_de_casteljau(points, 1 - t)

    assert "swapped t and 1 - t" in check_de_casteljau(swapped).message
    assert "level 0, the control points themselves, is missing" in check_de_casteljau(
        lambda points, t: library_de_casteljau(points, t)[1:]).message
    assert "a list of levels" in check_de_casteljau(lambda points, t: library_de_casteljau(points, t)[-1][0]).message


def test_a_learner_function_that_overwrites_the_control_points_is_told():
    def in_place(points, t):
        levels = [points.copy()]
        while len(points) > 1:
            points[:-1] = (1 - t) * points[:-1] + t * points[1:]
            points = points[:-1]
            levels.append(points.copy())
        return levels

    assert "changed the control points" in check_de_casteljau(in_place).message


def cmu_optimal_point(Q, a, b):
    """CMU's notes: x = A.inv() * b with b = -Q[:3, 3], and the midpoint when A cannot be inverted."""
    A, minus_q = Q[:3, :3], -Q[:3, 3]
    if abs(np.linalg.det(A)) < 1e-10:
        return (a + b) / 2
    return np.linalg.inv(A) @ minus_q


def exact_determinant_test(Q, a, b):
    A, q = Q[:3, :3], Q[:3, 3]
    if np.linalg.det(A) == 0:
        return (a + b) / 2
    return np.linalg.solve(A, -q)


def test_cmus_inverse_with_the_midpoint_fallback_is_accepted_on_every_flat_region():
    assert check_optimal_point(cmu_optimal_point).passed
    for seed in (1, 2, 3):
        assert check_optimal_point(cmu_optimal_point, seed=seed).passed


def test_an_exact_determinant_test_is_rejected_on_a_meshs_flat_region_and_the_slip_named():
    result = check_optimal_point(exact_determinant_test)
    assert not result.passed
    assert "a tilted flat region of a mesh" in result.message
    assert "det(A) == 0 misses it" in result.message


def chapter_patch_point(grid, u, v):
    columns = [library_de_casteljau(grid[:, j], u)[-1][0] for j in range(grid.shape[1])]
    return library_de_casteljau(np.array(columns), v)[-1][0]


def cs184_patch_point(grid, u, v):
    """CS184's BezierPatch::evaluate: de Casteljau along each row at u, then through the rows at v."""
    rows = [library_de_casteljau(grid[i], u)[-1][0] for i in range(grid.shape[0])]
    return library_de_casteljau(np.array(rows), v)[-1][0]


def test_both_patch_conventions_pass_and_cs184s_is_named():
    from halfedge_edu.exercises import check_bezier_patch

    assert check_bezier_patch(chapter_patch_point).passed
    cs184 = check_bezier_patch(cs184_patch_point)
    assert cs184.passed and "CS184's convention" in cs184.message
    assert all(check_bezier_patch(f, seed=s).passed for f in (chapter_patch_point, cs184_patch_point) for s in (1, 2))


def test_a_patch_point_that_switches_convention_is_refused():
    from halfedge_edu.exercises import check_bezier_patch

    def switching(grid, u, v):
        return (chapter_patch_point if grid.shape == (4, 4, 3) else cs184_patch_point)(grid, u, v)

    result = check_bezier_patch(switching)
    assert not result.passed and "u must run along the same index" in result.message


@pytest.mark.parametrize(("slip", "named"), [
    (lambda grid, u, v: library_de_casteljau(grid[:, 0], u)[-1][0], "one column's curve"),
    (lambda grid, u, v: chapter_patch_point(grid, 1 - u, 1 - v), "swapped t and 1 - t"),
])
def test_patch_slips_are_named(slip, named):
    from halfedge_edu.exercises import check_bezier_patch

    result = check_bezier_patch(slip)
    assert not result.passed and named in result.message, result.message


def upsample_by_operations(mesh):
    """CS184's and CMU's upsample, connectivity only: split every old edge, flip old-new cross edges."""
    from halfedge_edu.core.ops import flip, split

    n_old_vertices = mesh.n_vertices
    across = []
    for e in range(mesh.n_edges):
        ends = {int(v) for v in mesh.edge(e).vertices}
        m = split(mesh, e)
        across += [h.edge.index for h in m.outgoing() if h.tip.index not in ends]
    for e in across:
        a, b = (int(v) for v in mesh.edge(e).vertices)
        if (a < n_old_vertices) != (b < n_old_vertices):
            flip(mesh, e)
    return mesh


def test_the_upsample_connectivity_passes_at_midpoints_and_at_loops_positions():
    from halfedge_edu.algorithms.loop import loop_subdivide
    from halfedge_edu.exercises import check_upsample_connectivity

    assert check_upsample_connectivity(upsample_by_operations).passed
    assert check_upsample_connectivity(lambda mesh: loop_subdivide(mesh)).passed
    assert all(check_upsample_connectivity(upsample_by_operations, seed=s).passed for s in (1, 2, 3))


def test_splitting_without_flipping_is_named():
    from halfedge_edu.core.ops import split
    from halfedge_edu.exercises import check_upsample_connectivity

    def no_flips(mesh):
        for e in range(mesh.n_edges):
            split(mesh, e)
        return mesh

    result = check_upsample_connectivity(no_flips)
    assert not result.passed and "every edge split with no flips" in result.message


def test_flipping_every_cross_edge_is_refused():
    from halfedge_edu.core.ops import can_flip, flip, split
    from halfedge_edu.exercises import check_upsample_connectivity

    def flips_all(mesh):
        across = []
        for e in range(mesh.n_edges):
            ends = {int(v) for v in mesh.edge(e).vertices}
            m = split(mesh, e)
            across += [h.edge.index for h in m.outgoing() if h.tip.index not in ends]
        for e in across:
            if can_flip(mesh, e):
                flip(mesh, e)
        return mesh

    result = check_upsample_connectivity(flips_all)
    assert not result.passed and "not every old triangle became its four" in result.message


# --------------------------------------------------------------------------------------
# check_downsample: CMU's downsampling loop
# --------------------------------------------------------------------------------------

import heapq  # noqa: E402
import itertools  # noqa: E402

from halfedge_edu.algorithms.simplify import face_quadrics  # noqa: E402
from halfedge_edu.core.ops import can_collapse, collapse  # noqa: E402


def optimal_point_with_fallback(Q, a, b):
    A, q = Q[:3, :3], Q[:3, 3]
    if abs(np.linalg.det(A)) < 1e-9:
        return 0.5 * (a + b)
    return np.linalg.solve(A, -q)


def _downsampler(optimal_point, *, stale_slip=False):
    """The chapter's loop (a heap of edges with lazy deletion) with the point rule given; with
    ``stale_slip``, only the survivor's old queue entries are marked stale after a collapse
    (the first draft of the chapter's answer), not the removed vertex's."""
    def downsample(mesh, target_faces):
        mesh = mesh.copy()
        corners = mesh.face_vertices()
        K = face_quadrics(mesh.positions, corners)
        Q = np.zeros((mesh.n_vertex_slots, 4, 4))
        for f in range(len(corners)):
            for v in corners[f]:
                Q[v] += K[f]
        version = np.zeros(mesh.n_vertex_slots, dtype=int)
        heap, order = [], itertools.count()

        def push(e):
            a, b = (int(v) for v in mesh.edge(e).vertices)
            x = optimal_point(Q[a] + Q[b], mesh.positions[a], mesh.positions[b])
            cost = float(np.append(x, 1.0) @ (Q[a] + Q[b]) @ np.append(x, 1.0))
            heapq.heappush(heap, (cost, next(order), e, a, b, version[a], version[b], x))

        for edge in mesh.edges:
            push(edge.index)
        while mesh.n_faces > target_faces and heap:
            _, _, e, a, b, version_a, version_b, x = heapq.heappop(heap)
            if mesh.edge_deleted[e] or (version[a], version[b]) != (version_a, version_b) or not can_collapse(mesh, e):
                continue
            survivor = collapse(mesh, e, position=x).index
            Q[survivor] = Q[a] + Q[b]
            for v in ((survivor,) if stale_slip else (a, b)):
                version[v] += 1
            for h in mesh.vertex(survivor).outgoing():
                push(h.edge.index)
        mesh.garbage_collect()
        return mesh
    return downsample


def test_the_downsampling_loop_passes_public_and_hidden_cases():
    from halfedge_edu.exercises import check_downsample

    right = _downsampler(optimal_point_with_fallback)
    assert check_downsample(right).passed
    assert all(check_downsample(right, seed=seed).passed for seed in (1, 2, 3))


def test_midpoints_instead_of_optimal_points_lose_the_corners():
    from halfedge_edu.exercises import check_downsample

    result = check_downsample(_downsampler(lambda Q, a, b: 0.5 * (a + b)))
    assert not result.passed and "are not corners of the solid" in result.message


def test_entries_of_the_removed_vertex_left_in_the_queue_are_caught():
    """The first draft of the chapter's answer: after a collapse only the survivor's old queue
    entries were marked stale, so an edge of the removed vertex was collapsed with its old point."""
    from halfedge_edu.exercises import check_downsample

    result = check_downsample(_downsampler(optimal_point_with_fallback, stale_slip=True))
    assert not result.passed and "not corners of the solid" in result.message
