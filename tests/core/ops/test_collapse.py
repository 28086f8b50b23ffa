"""Edge collapse: hand-worked results (both degree cases, either end), every refusal rule."""

from __future__ import annotations

import re

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.data import sample
from halfedge_edu.core.ops import OperationLog, apply_collapse, can_collapse, collapse, prepare_collapse
from tests.core.ops.helpers import (
    assert_same_mesh, assert_unchanged, counts, open_tetrahedron, pillow, snapshot,
)

H = np.sqrt(3) / 2
CUBE = [[i & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)]


# ---- hand-worked results ------------------------------------------------------------------

def test_collapse_of_an_interior_edge_merges_its_ends_at_the_midpoint():
    mesh = sample("single_collapse")  # edge 0 joins 0 (origin) and 1, both of degree 6
    survivor = collapse(mesh, 0)
    mesh.validate()
    assert survivor.index == 1  # halfedge 0 runs 0 -> 1: its origin goes, its tip survives
    np.testing.assert_array_equal(survivor.position, [0.5, 0, 0])
    ring = [[2, 0], [1.5, H], [0.5, H], [-0.5, H], [-1, 0], [-0.5, -H], [0.5, -H], [1.5, -H]]
    expected_vertices = [[0.5, 0, 0]] + [[x, y, 0] for x, y in ring]  # merged vertex, then 2..9
    expected_faces = [[0, 3, 4], [0, 4, 5], [0, 5, 6], [0, 6, 7], [0, 1, 2], [0, 2, 3], [0, 7, 8], [0, 8, 1]]
    assert_same_mesh(mesh, (expected_vertices, expected_faces))


def test_collapse_of_a_boundary_edge_removes_its_one_triangle():
    strip = sample("strip")  # edge 0 is the boundary edge 0 - 1 of face (0, 1, 2)
    collapse(strip, 0)
    strip.validate()
    assert_same_mesh(strip, ([[0.5, 0, 0], [0.5, 1, 0], [1.5, 1, 0], [2, 0, 0]], [[0, 2, 1], [0, 3, 2]]))
    assert strip.n_boundary_loops == 1


CUBE_EDGE_0 = (  # edge 0 - 4 collapsed to (0, 0, 0.5), numbered 0 (merged), 1, 2, 3, 5, 6, 7
    [[0, 0, 0.5]] + [CUBE[i] for i in (1, 2, 3, 5, 6, 7)],
    [[2, 0, 5], [6, 4, 3], [3, 4, 1], [1, 4, 0], [6, 3, 5], [3, 2, 5], [0, 2, 1], [1, 2, 3], [6, 5, 4], [4, 5, 0]],
)


def test_cube_corner_of_degree_3_collapsed_from_the_corner():
    cube = sample("cube")
    log = OperationLog()
    survivor = collapse(cube, 0, log=log)  # halfedge 0 runs 0 -> 4: corner 0 (degree 3) goes
    cube.validate()
    assert survivor.index == 4
    assert_same_mesh(cube, CUBE_EDGE_0)
    assert log.named["vB"] == ("vertex", 0)
    assert log.named["gL"] == log.named["gR"]  # vB's third face is on both sides
    assert not any(change.field == "vertex" for change in log.changes)  # no halfedge moves


def test_cube_corner_of_degree_3_collapsed_from_the_other_end():
    cube = sample("cube")
    log = OperationLog()
    survivor = collapse(cube, cube.halfedge(1), log=log)  # 4 (degree 5) goes, corner 0 survives
    cube.validate()
    assert survivor.index == 0
    assert_same_mesh(cube, CUBE_EDGE_0)
    assert log.named["vB"] == ("vertex", 4) and log.named["gL"] != log.named["gR"]
    assert sum(change.field == "vertex" for change in log.changes) == 2  # degree 5 - 3


def test_cube_edge_between_two_degree_5_vertices():
    cube = sample("cube")
    e = cube.find_edge(1, 5).index
    assert cube.vertex(1).degree == cube.vertex(5).degree == 5
    collapse(cube, e)
    cube.validate()
    assert_same_mesh(
        cube,
        (
            [CUBE[0], [1, 0, 0.5]] + [CUBE[i] for i in (2, 3, 4, 6, 7)],  # 1 and 5 merged
            [[0, 4, 2], [2, 4, 5], [6, 1, 3], [0, 1, 4], [6, 3, 5], [3, 2, 5], [0, 2, 1], [1, 2, 3], [6, 5, 1], [1, 5, 4]],
        ),
    )


def test_collapse_may_leave_a_single_triangle():
    mesh = open_tetrahedron()  # apex 0 (interior, degree 3) over the hole 1 - 2 - 3
    e = mesh.find_edge(0, 1).index
    assert can_collapse(mesh, e)
    collapse(mesh, e)
    mesh.validate()
    assert counts(mesh) == (3, 3, 1)


@pytest.mark.parametrize(
    ("name", "edge", "delta"),
    [("single_collapse", 0, (-1, -3, -2)), ("cube", 0, (-1, -3, -2)), ("strip", 0, (-1, -2, -1)), ("open_patch", 0, (-1, -2, -1))],
)
def test_collapse_removes_the_stated_elements(name, edge, delta):
    mesh = sample(name)
    before, euler = counts(mesh), mesh.euler_characteristic
    collapse(mesh, edge)
    mesh.validate()
    assert tuple(a - b for a, b in zip(counts(mesh), before)) == delta
    assert mesh.euler_characteristic == euler


@pytest.mark.parametrize(("name", "edge"), [("single_collapse", 0), ("strip", 0), ("cube", 3), ("open_patch", 4)])
def test_either_end_gives_the_same_mesh(name, edge):
    one, other = sample(name), sample(name)
    collapse(one, one.halfedge(2 * edge))
    collapse(other, other.halfedge(2 * edge + 1))
    assert_same_mesh(one, other)


def test_collapse_to_a_given_position():
    mesh = sample("single_collapse")
    survivor = collapse(mesh, 0, position=(0.25, 0.1, 0))
    np.testing.assert_array_equal(survivor.position, [0.25, 0.1, 0])


def test_a_bad_position_is_refused_before_anything_changes():
    mesh = sample("single_collapse")
    before = snapshot(mesh)
    with pytest.raises(ValueError, match="position"):
        collapse(mesh, 0, position=[np.inf, 0, 0])
    assert_unchanged(mesh, before)


def test_the_mesh_method_is_the_same_operation():
    mesh = sample("single_collapse")
    assert mesh.can_collapse(0)
    assert mesh.collapse(0).index == 1
    mesh.validate()


def test_collapse_after_collapse_on_a_boundary_edge_stored_hole_side_first():
    strip = sample("strip")
    collapse(strip, 0)  # edge 1 now has its face on halfedge 3, not 2
    assert strip.halfedge_face[2] < 0
    collapse(strip, 1)
    strip.validate()
    assert counts(strip) == (3, 3, 1)


# ---- refusals -----------------------------------------------------------------------------

def assert_refused(mesh, edge, rule, *words):
    """Refused with ``rule`` from both ends; ``collapse`` raises the reason and changes nothing."""
    before = snapshot(mesh)
    e = int(edge)
    check = can_collapse(mesh, e)
    assert not check and check.rule == rule, check
    assert can_collapse(mesh, mesh.halfedge(2 * e + 1)).rule == rule
    for word in words:
        assert word in check.reason
    for h in (2 * e, 2 * e + 1):
        with pytest.raises(hx.TopologyError) as raised:
            collapse(mesh, mesh.halfedge(h))
        assert raised.value.rule == rule
    assert_unchanged(mesh, before)
    return check


def test_figure8_middle_edge_joins_two_boundary_vertices_and_is_refused():
    assert_refused(sample("figure8"), 0, "both-ends-on-boundary", "edge 0 (vertices 2 and 7)", "figure 8")


@pytest.mark.parametrize("edge", range(3))
def test_a_lone_triangle_cannot_be_collapsed(edge):
    assert_refused(sample("lone_triangle"), edge, "lone-triangle", "face 0", "lone triangle", "bare edge")


@pytest.mark.parametrize("edge", range(6))
def test_the_tetrahedron_is_refused_by_the_full_link_condition(edge):
    mesh = sample("tetrahedron")
    check = assert_refused(mesh, edge, "tetrahedron", "closed tetrahedron", "back to back")
    assert check.reason.count("link") >= 1


def test_two_triangles_back_to_back_are_refused():
    assert_refused(pillow(), 0, "back-to-back", "back to back", "no triangle")


def test_a_shared_neighbour_that_is_not_opposite_the_edge_is_refused():
    cube = sample("cube")
    e = cube.find_edge(2, 4).index  # a face diagonal: 2 and 4 also share vertex 1
    check = assert_refused(
        cube, e, "link-condition", "share 3 neighbours (0, 1, 6)", "opposite the edge (0, 6)", "pinch the surface at 1"
    )
    assert ("vertex", 1) in check.elements


def test_a_boundary_edge_of_a_triangular_hole_is_refused():
    mesh = open_tetrahedron()
    e = mesh.find_edge(1, 2).index
    assert_refused(mesh, e, "link-condition", "opposite this boundary edge (0)", "pinch the surface at 3")


def test_a_deleted_edge_is_an_index_error():
    mesh = sample("single_collapse")
    collapse(mesh, 0)
    with pytest.raises(IndexError, match="deleted"):
        can_collapse(mesh, 0)
    with pytest.raises(IndexError, match="halfedge 1 was deleted"):
        collapse(mesh, hx.Halfedge(mesh, 1))


# ---- prepare, then do -------------------------------------------------------------------

@pytest.mark.parametrize(("name", "h"), [("single_collapse", 0), ("cube", 0), ("cube", 1), ("strip", 0), ("open_patch", 3)])
def test_prepare_then_apply_is_the_collapse(name, h):
    by_collapse, by_steps = sample(name), sample(name)
    assert can_collapse(by_collapse, h >> 1)
    collapse(by_collapse, by_collapse.halfedge(h))
    before = snapshot(by_steps)
    record = prepare_collapse(by_steps, by_steps.halfedge(h))
    assert_unchanged(by_steps, before)  # preparing changes nothing
    assert (record.h_BA, record.vB, record.vA) == (h, by_steps.halfedge(h).vertex.index, by_steps.halfedge(h).tip.index)
    apply_collapse(by_steps, record)
    assert snapshot(by_steps) == snapshot(by_collapse)


def test_a_refused_collapse_prepares_nothing():
    mesh = sample("tetrahedron")
    before = snapshot(mesh)
    assert prepare_collapse(mesh, 0) is None and can_collapse(mesh, 0).rule == "tetrahedron"
    assert_unchanged(mesh, before)


def test_a_record_that_no_longer_fits_is_refused():
    mesh = sample("single_collapse")
    record = prepare_collapse(mesh, 0)
    collapse(mesh, 0)
    before = snapshot(mesh)
    with pytest.raises(ValueError, match="prepare it again"):
        apply_collapse(mesh, record)
    assert_unchanged(mesh, before)


def test_the_record_names_what_the_log_names():
    mesh = sample("cube")
    record = prepare_collapse(mesh, mesh.halfedge(1))
    log = OperationLog()
    apply_collapse(mesh, record, log=log)
    assert log.named == {name: element for name, element in record.names().items() if element[1] >= 0}


# ---- without the link condition (a teaching switch) ---------------------------------------

def test_without_the_link_condition_the_cube_gets_a_doubled_edge_that_validate_names():
    cube = sample("cube")
    e = int(cube.find_edge(2, 4))
    assert can_collapse(cube, e).rule == "link-condition"
    vA = cube.collapse(e, check_link=False)
    with pytest.raises(hx.MeshInvariantError) as caught:
        cube.validate()
    assert caught.value.rule == "duplicate-edge"
    pair = {int(v) for v in re.findall(r"vertices (\d+) and (\d+)", str(caught.value))[0]}
    assert pair == {vA.index, 1}  # the merged vertex and vertex 1, the neighbour both ends shared


def test_without_the_link_condition_a_real_mesh_breaks_and_validate_says_why():
    bunny = hx.sample("bunny")
    e = next(e for e in range(bunny.n_edges) if can_collapse(bunny, e).rule == "link-condition")
    collapse(bunny, e, check_link=False)
    with pytest.raises(hx.MeshInvariantError, match="two different edges"):
        bunny.validate()


def test_without_the_link_condition_the_tetrahedron_becomes_a_pillow():
    mesh = sample("tetrahedron")
    collapse(mesh, 0, check_link=False)
    assert (mesh.n_vertices, mesh.n_edges, mesh.n_faces) == (3, 3, 2)
    assert all(not mesh.can_flip(e) and not mesh.can_split(e) and not mesh.can_collapse(e) for e in range(6)
               if not mesh.edge_deleted[e])


def test_without_the_link_condition_back_to_back_is_still_refused():
    mesh = pillow()
    before = snapshot(mesh)
    with pytest.raises(hx.TopologyError) as caught:
        collapse(mesh, 0, check_link=False)
    assert caught.value.rule == "back-to-back"
    assert_unchanged(mesh, before)
    assert prepare_collapse(mesh, 0, check_link=False) is None
