"""Chapter 08's check accepts the link condition as each course states it, and names real mistakes.

UChicago's assignment: "the intersection of the one-ring of a with the one-ring of b
should be exactly two vertices" (vertices only: the tetrahedron passes). CMU's: ignore
requests to collapse boundary edges, and think about the tetrahedron. The package:
link(a) ∩ link(b) = link(ab) with edges, the boundary counted as one more vertex.
"""

from __future__ import annotations

import pytest

from halfedge_edu.exercises.chapter_checks import check_collapse_is_safe


def ring(vertex) -> set[int]:
    return {u.index for u in vertex.neighbors()}


def uchicago_is_safe(mesh, e):
    """The UChicago statement, word for word: the two one-rings share exactly two vertices."""
    a, b = mesh.edge(e).vertices
    return len(ring(a) & ring(b)) == 2


def uchicago_with_boundary(mesh, e):
    """UChicago's rule with the boundary as one more shared neighbour (chapter 08, section 4),
    and a lone triangle (all three edges on the boundary) refused."""
    edge = mesh.edge(e)
    a, b = edge.vertices
    inside = edge.halfedge.twin if edge.halfedge.is_boundary else edge.halfedge
    if all(h.twin.is_boundary for h in (inside, inside.next, inside.prev)):
        return False
    shared = ring(a) & ring(b) | ({-1} if a.is_boundary and b.is_boundary else set())
    opposite = {h.prev.vertex.index if not h.is_boundary else -1 for h in (edge.halfedge, edge.halfedge.twin)}
    return shared == opposite


def cmu_neighbours(vertex) -> set[int]:
    """CMU's walk: h = h.twin.next around the vertex (clockwise)."""
    found, h = set(), vertex.halfedge
    while True:
        found.add(h.twin.vertex.index)
        h = h.twin.next
        if h == vertex.halfedge:
            return found


def cmu_is_safe(mesh, e):
    """CMU's way: refuse boundary edges at once; the rings share only the opposite vertices;
    and, as the assignment hints, a tetrahedron would not survive (fewer than four faces left)."""
    edge = mesh.edge(e)
    h, t = edge.halfedge, edge.halfedge.twin
    if h.is_boundary or t.is_boundary:
        return False
    a, b = edge.vertices
    if a.is_boundary and b.is_boundary:
        return False
    if cmu_neighbours(a) & cmu_neighbours(b) != {h.prev.vertex.index, t.prev.vertex.index}:
        return False
    return mesh.n_faces - 2 >= 4


def package_is_safe(mesh, e):
    from halfedge_edu.core.ops import can_collapse

    return bool(can_collapse(mesh, e))


@pytest.mark.parametrize(("is_safe", "vertices_only"), [(uchicago_is_safe, True), (cmu_is_safe, False),
                                                      (package_is_safe, False)], ids=["uchicago", "cmu", "package"])
def test_each_courses_rule_is_accepted_on_closed_meshes(is_safe, vertices_only):
    result = check_collapse_is_safe(is_safe, vertices_only=vertices_only)
    assert result and result.message.startswith("All good!"), result.message
    assert len(result.checked) == 4


def test_the_uchicago_rule_on_the_tetrahedron_is_accepted_as_uchicago_states_it_and_the_package_rule_explained():
    message = check_collapse_is_safe(uchicago_is_safe, vertices_only=True).message
    assert "as UChicago's assignment states it" in message
    assert "'tetrahedron'" in message and "two triangles glued back to back" in message


def rings_only(mesh, e):
    """Chapter 08's 'vertex part alone': the rings share exactly the opposite vertices."""
    edge = mesh.edge(e)
    a, b = edge.vertices
    return ring(a) & ring(b) == {edge.halfedge.prev.vertex.index, edge.halfedge.twin.prev.vertex.index}


@pytest.mark.parametrize("is_safe", [rings_only, uchicago_is_safe], ids=["rings-only", "uchicago"])
def test_the_vertex_part_alone_is_refused_where_the_chapter_asks_for_the_whole_link_condition(is_safe):
    result = check_collapse_is_safe(is_safe)
    assert not result.passed and result.mesh_name == "tetrahedron"
    assert "lies in both links" in result.message and "vertices_only=True" in result.message


def test_return_true_is_refused_on_the_tetrahedron_with_the_link_edge_named():
    result = check_collapse_is_safe(lambda mesh, e: True)
    assert not result.passed and result.mesh_name == "tetrahedron" and "lies in both links" in result.message
    assert not check_collapse_is_safe(lambda mesh, e: True, vertices_only=True).passed


def test_a_function_that_agrees_with_the_package_everywhere_gets_no_note():
    message = check_collapse_is_safe(package_is_safe, with_boundary=True).message
    assert message.endswith("It agrees with link_condition on every edge.")


@pytest.mark.parametrize(("is_safe", "vertices_only"), [(uchicago_with_boundary, True), (cmu_is_safe, False),
                                                      (package_is_safe, False)],
                         ids=["uchicago-with-boundary", "cmu", "package"])
def test_each_courses_rule_is_accepted_with_boundary(is_safe, vertices_only):
    result = check_collapse_is_safe(is_safe, with_boundary=True, vertices_only=vertices_only)
    assert result and len(result.checked) == 8, result.message


def test_cmus_refusal_of_boundary_edges_is_accepted_and_said():
    message = check_collapse_is_safe(cmu_is_safe, with_boundary=True).message
    assert "as CMU's assignment asks" in message


def at_least_the_opposite_vertices(mesh, e):
    edge = mesh.edge(e)
    a, b = edge.vertices
    return ring(a) & ring(b) >= {edge.halfedge.prev.vertex.index, edge.halfedge.twin.prev.vertex.index}


def rings_with_themselves(mesh, e):
    a, b = mesh.edge(e).vertices
    return len((ring(a) | {a.index}) & (ring(b) | {b.index})) == 2


def at_most_two_shared(mesh, e):
    a, b = mesh.edge(e).vertices
    return len(ring(a) & ring(b)) <= 2


@pytest.mark.parametrize(("is_safe", "with_boundary", "where", "named"), [
    (at_least_the_opposite_vertices, False, "cube", "would become one doubled edge"),
    (rings_with_themselves, False, "cube", "not the vertex itself"),
    (at_most_two_shared, True, "cube without its first triangle", "On a boundary edge there is only one opposite"),
    (uchicago_is_safe, True, "cube without its first triangle", "not how many"),
    (lambda mesh, e: uchicago_with_boundary(mesh, e) or not mesh.edge(e).is_boundary and
     len(ring(mesh.edge(e).vertices[0]) & ring(mesh.edge(e).vertices[1])) == 2, True, "open_patch",
     "This is the boundary case"),
    (lambda mesh, e: uchicago_with_boundary(mesh, e) or mesh.n_faces == 1, True, "lone_triangle",
     "lone triangle"),
])
def test_a_wrong_rule_is_refused_naming_the_mistake(is_safe, with_boundary, where, named):
    result = check_collapse_is_safe(is_safe, with_boundary=with_boundary, vertices_only=True)
    assert not result and result.mesh_name == where and named in result.message, result.message
    assert result.element[0] == "halfedge"
