"""check_flip and check_collapse: they pass correct answers and name planted mistakes.

Each planted mistake is one a student really makes in chapters 06 and 07; the test
asserts the check stops on the right mesh, names the broken rule and the elements with
the operation's names (h0 ... h5, vA, vB, h_A_L ...), and says the sentence that helps.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from halfedge_edu.exercises.harness import CheckResult
from tests.exercises.chapter_solutions import chapter_namespace
from halfedge_edu.exercises.ops_checks import check_collapse, check_flip, collapse_cases, flip_cases
from halfedge_edu.core.ops import can_collapse, can_flip, collapse, flip


# --------------------------------------------------------------------------------------
# Answers a student might write: plain array code, the way chapters 06 and 07 teach it
# --------------------------------------------------------------------------------------

def link(mesh, h, n):
    mesh.halfedge_next[h] = n
    mesh.halfedge_prev[n] = h


def student_flip(mesh, e, *, keep_vertex_halfedges=True, set_faces=True, relink=None, moved=None):
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    h0, h1 = 2 * e, 2 * e + 1
    h2, h3, h4, h5 = int(nxt[h0]), int(prv[h0]), int(nxt[h1]), int(prv[h1])
    v0, v1, v2, v3 = int(origin[h0]), int(origin[h1]), int(origin[h3]), int(origin[h5])
    f0, f1 = int(face[h0]), int(face[h1])
    origin[h0], origin[h1] = v3, v2
    for a, b in relink or ((h0, h3), (h3, h4), (h4, h0), (h1, h5), (h5, h2), (h2, h1)):
        link(mesh, a, b)
    if set_faces:
        face[h4], face[h2] = f0, f1
        mesh.face_halfedge[f0], mesh.face_halfedge[f1] = h0, h1
    if keep_vertex_halfedges:
        if mesh.vertex_halfedge[v0] == h0:
            mesh.vertex_halfedge[v0] = h4
        if mesh.vertex_halfedge[v1] == h1:
            mesh.vertex_halfedge[v1] = h2
    if moved is not None:
        mesh.positions[v2] += moved


def _ring(mesh, h):
    """Halfedges leaving the origin of h, starting with h (h -> twin(prev(h)))."""
    ring, g = [h], int(mesh.halfedge_prev[h]) ^ 1
    while g != h:
        ring.append(g)
        g = int(mesh.halfedge_prev[g]) ^ 1
    return ring


def student_collapse(mesh, h, *, copy_first=False, delete_faces=True, delete_both=False, position=None,
                     remove="vB"):
    """The course's collapse (keeping vA's edges), with switches for planted mistakes."""
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    h_BA, h_AB = h, h ^ 1
    vB, vA = int(origin[h_BA]), int(origin[h_AB])
    h_A_L, h_L_B = int(nxt[h_BA]), int(prv[h_BA])
    h_B_R, h_R_A = int(nxt[h_AB]), int(prv[h_AB])
    h_B_L, h_R_B = h_L_B ^ 1, h_B_R ^ 1
    vL, vR = int(origin[h_L_B]), int(origin[h_R_A])
    fL, fR = int(face[h_BA]), int(face[h_AB])
    ring = _ring(mesh, h_BA)
    saved = {old: (int(prv[old]), int(nxt[old]), int(face[old])) for old in (h_B_L, h_R_B)}
    midpoint = 0.5 * (mesh.positions[vA] + mesh.positions[vB])
    mesh.positions[vA] = midpoint if position is None else position
    for g in ring:
        if g not in (h_BA, h_B_L, h_B_R):
            origin[g] = vA
    for old, new in ((h_B_L, h_A_L), (h_R_B, h_R_A)):
        before, after, f = saved[old] if copy_first else (int(prv[old]), int(nxt[old]), int(face[old]))
        link(mesh, before, new)
        link(mesh, new, after)
        face[new] = f
        if mesh.face_halfedge[f] == old:
            mesh.face_halfedge[f] = new
    if mesh.vertex_halfedge[vL] == h_L_B:
        mesh.vertex_halfedge[vL] = h_A_L ^ 1
    if mesh.vertex_halfedge[vR] == h_R_B:
        mesh.vertex_halfedge[vR] = h_R_A
    if mesh.vertex_halfedge[vA] == h_AB:
        mesh.vertex_halfedge[vA] = h_R_A ^ 1
    if delete_faces:
        mesh.delete_face(fL)
        mesh.delete_face(fR)
    mesh.delete_edge(h_BA >> 1)
    mesh.delete_edge(h_L_B >> 1)
    mesh.delete_edge(h_B_R >> 1)
    if delete_both:
        mesh.delete_edge(h_A_L >> 1)
    mesh.delete_vertex(vB if remove == "vB" else vA)


def collapse_keeping_vB_edges(mesh, h):
    """The mirror choice: of the two edges that merge on each side, keep vB's."""
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    h_BA, h_AB = h, h ^ 1
    vB, vA = int(origin[h_BA]), int(origin[h_AB])
    h_A_L, h_L_B = int(nxt[h_BA]), int(prv[h_BA])
    h_B_R, h_R_A = int(nxt[h_AB]), int(prv[h_AB])
    h_L_A, h_A_R, h_R_B = h_A_L ^ 1, h_R_A ^ 1, h_B_R ^ 1
    vL, vR = int(origin[h_L_B]), int(origin[h_R_A])
    fL, fR = int(face[h_BA]), int(face[h_AB])
    ring = _ring(mesh, h_BA)
    mesh.positions[vA] = 0.5 * (mesh.positions[vA] + mesh.positions[vB])
    for g in ring:
        if g != h_BA:
            origin[g] = vA
    for old, new in ((h_L_A, h_L_B), (h_A_R, h_B_R)):
        before, after, f = int(prv[old]), int(nxt[old]), int(face[old])
        link(mesh, before, new)
        link(mesh, new, after)
        face[new] = f
        if mesh.face_halfedge[f] == old:
            mesh.face_halfedge[f] = new
    if mesh.vertex_halfedge[vL] == h_L_A:
        mesh.vertex_halfedge[vL] = h_L_B
    if mesh.vertex_halfedge[vR] == h_R_A:
        mesh.vertex_halfedge[vR] = h_R_B
    if mesh.vertex_halfedge[vA] in (h_AB, h_A_L, h_A_R):
        mesh.vertex_halfedge[vA] = h_B_R
    mesh.delete_face(fL)
    mesh.delete_face(fR)
    mesh.delete_edge(h_BA >> 1)
    mesh.delete_edge(h_A_L >> 1)
    mesh.delete_edge(h_R_A >> 1)
    mesh.delete_vertex(vB)


# --------------------------------------------------------------------------------------
# check_flip
# --------------------------------------------------------------------------------------

def test_check_flip_passes_the_student_flip():
    result = check_flip(student_flip)
    assert isinstance(result, CheckResult)
    assert result.passed, result.message
    assert result.message.startswith("All good!")
    assert result.checked == [name for name, _, _ in flip_cases()]


def test_check_flip_passes_the_library_flip():
    assert check_flip(lambda mesh, e: flip(mesh, e)).passed


def test_forgotten_vertex_halfedge_is_named_with_the_picture_names():
    result = check_flip(lambda mesh, e: student_flip(mesh, e, keep_vertex_halfedges=False))
    assert not result.passed
    assert "rule vertex-halfedge-origin" in result.message
    assert "vertex 2 is v1" in result.message
    assert result.element == ("vertex", 2)


def test_next_that_does_not_start_at_the_tip_is_named():
    def wrong_order(mesh, e):
        h0, h1 = 2 * e, 2 * e + 1
        h2, h3 = int(mesh.halfedge_next[h0]), int(mesh.halfedge_prev[h0])
        h4, h5 = int(mesh.halfedge_next[h1]), int(mesh.halfedge_prev[h1])
        student_flip(mesh, e, relink=((h0, h4), (h4, h3), (h3, h0), (h1, h5), (h5, h2), (h2, h1)))

    result = check_flip(wrong_order)
    assert result.mesh_name == "strip"
    assert "rule next-origin" in result.message
    assert "halfedge 0 is h3" in result.message
    assert "next must start where the halfedge ends" in result.message


def test_halfedges_left_in_their_old_face_are_named():
    result = check_flip(lambda mesh, e: student_flip(mesh, e, set_faces=False))
    assert "rule next-cycle" in result.message
    assert "face 0 is f0" in result.message


def test_moving_a_vertex_is_not_a_flip():
    result = check_flip(lambda mesh, e: student_flip(mesh, e, moved=0.5))
    assert "moved vertex" in result.message
    assert "positions stay" in result.message


def test_deleting_in_a_flip_is_explained():
    def deleting(mesh, e):
        student_flip(mesh, e)
        mesh.delete_face(int(mesh.halfedge_face[2 * e]))

    result = check_flip(deleting)
    assert "A flip creates and deletes nothing" in result.message


def test_flipping_another_edge_says_which_vertices_it_should_join():
    def neighbour(mesh, e):
        other = int(mesh.halfedge_next[2 * e]) >> 1
        if can_flip(mesh, other):
            flip(mesh, other)

    result = check_flip(neighbour)
    assert result.mesh_name == "strip"
    assert "edge 1 joins vertices 1 and 2; it should join v2 and v3" in result.message


def test_unfinished_flip_says_not_written_yet():
    def stub(mesh, e):
        raise NotImplementedError("write flip")

    result = check_flip(stub)
    assert result.mesh_name == "strip"
    assert "not written yet" in result.message


def test_a_blank_left_in_the_flip_is_pointed_out():
    def blank(mesh, e):
        mesh.halfedge_vertex[2 * e] = ...

    assert "still has a blank (...)" in check_flip(blank).message


def test_a_learner_exception_is_reported_by_name():
    result = check_flip(lambda mesh, e: mesh.halfedge_next[10**6])
    assert "raised IndexError" in result.message


def test_a_later_mistake_lists_what_agreed_first():
    def fails_on_the_sphere(mesh, e):
        student_flip(mesh, e, keep_vertex_halfedges=mesh.n_vertices < 20)

    result = check_flip(fails_on_the_sphere)
    assert result.mesh_name.startswith("icosphere")
    assert "(It agreed on strip, cube, single_collapse first.)" in result.message


def test_every_listed_flip_is_allowed_when_it_is_made():
    for name, mesh, edges in flip_cases():
        for e in edges:
            assert can_flip(mesh, e), (name, e)
            flip(mesh, e)
            mesh.validate()


# --------------------------------------------------------------------------------------
# check_collapse
# --------------------------------------------------------------------------------------

def test_check_collapse_passes_the_student_collapse():
    result = check_collapse(student_collapse)
    assert result.passed, result.message
    assert result.checked == [name for name, _, _ in collapse_cases()]


def test_check_collapse_passes_the_library_collapse():
    assert check_collapse(lambda mesh, h: collapse(mesh, mesh.halfedge(h))).passed


def test_keeping_the_other_of_the_merged_edges_is_just_as_right():
    assert check_collapse(collapse_keeping_vB_edges).passed


def test_copying_pointers_first_fails_on_the_degree_3_vertex_with_the_reason():
    result = check_collapse(lambda mesh, h: student_collapse(mesh, h, copy_first=True))
    assert result.mesh_name == "cube, removing the degree-3 vertex 0"
    assert result.checked == ["single_collapse"]
    assert "Here vB has degree 3, so gL and gR are the same face (8)" in result.message
    assert "halfedge 5 is h_B_L" in result.message


def test_removing_the_surviving_end_is_explained():
    result = check_collapse(lambda mesh, h: student_collapse(mesh, h, remove="vA"))
    assert "deleted vertex 1, vA" in result.message
    assert result.element == ("vertex", 1)


def test_forgotten_faces_are_named():
    result = check_collapse(lambda mesh, h: student_collapse(mesh, h, delete_faces=False))
    assert "did not delete face 0 (fL)" in result.message
    assert result.element == ("face", 0)


def test_deleting_both_merged_edges_is_explained():
    result = check_collapse(lambda mesh, h: student_collapse(mesh, h, delete_both=True))
    assert "deleted both of edges" in result.message
    assert "exactly one of them must go" in result.message


def test_the_surviving_vertex_goes_to_the_midpoint():
    result = check_collapse(lambda mesh, h: student_collapse(mesh, h, position=np.zeros(3)))
    assert "it should be at the midpoint of the edge, [0.5, 0.0, 0.0]" in result.message


def test_a_collapse_that_never_ends_is_stopped():
    def walks_forever(mesh, h):
        g = h
        while True:
            g = int(mesh.halfedge_next[g])

    start = time.perf_counter()
    result = check_collapse(walks_forever)
    assert time.perf_counter() - start < 10
    assert "did not finish" in result.message


def test_every_listed_collapse_is_allowed_when_it_is_made():
    for name, mesh, halfedges in collapse_cases():
        for h in halfedges:
            assert can_collapse(mesh, h >> 1), (name, h)
            assert not mesh.edge(h >> 1).is_boundary
            collapse(mesh, mesh.halfedge(h))
            mesh.validate()


def test_the_cube_case_removes_the_degree_3_vertex():
    name, mesh, halfedges = collapse_cases()[1]
    assert halfedges == [0]
    assert mesh.halfedge(0).vertex.degree == 3


def test_show_draws_the_offending_element():
    pytest.importorskip("pyvista")
    result = check_collapse(lambda mesh, h: student_collapse(mesh, h, delete_faces=False))
    picture = result.show(window_size=(200, 150))
    assert picture is not None and picture.data[:4] == b"\x89PNG"


def test_a_collapse_that_keeps_the_other_endpoint_is_accepted_and_the_convention_named():
    """UChicago's P6: 'which vertex to keep will be ambiguous'; keeping h.vertex is right there."""
    result = check_collapse(lambda mesh, h: collapse(mesh, mesh.halfedge(h ^ 1)))
    assert result.passed, result.message
    assert "UChicago's assignment leaves the choice of which vertex to keep free" in result.message


def split_keeping_face_halfedges(mesh, e):
    """A split that relinks every halfedge but leaves f0 pointing at h2, which has moved to f2."""
    right = CHAPTER_06_SPLIT
    f0 = int(mesh.halfedge_face[2 * e])
    kept = int(mesh.face_halfedge[f0])
    m = right(mesh, e)
    mesh.face_halfedge[f0] = kept
    return m


CHAPTER_06_SPLIT = chapter_namespace("06")["my_split"]


def test_check_split_names_a_face_left_pointing_at_a_halfedge_that_moved():
    from halfedge_edu.exercises import check_split

    result = check_split(split_keeping_face_halfedges)
    assert not result.passed and "face-halfedge" in result.message and "is f0" in result.message


def test_check_split_counts_the_new_elements():
    from halfedge_edu.exercises import check_split

    result = check_split(lambda mesh, e: mesh.add_vertex([0.0, 0.0, 0.0]))
    assert not result.passed and "0 new edges instead of 3" in result.message


def test_a_failed_operation_labels_its_picture_with_the_names_its_message_uses():
    result = check_flip(lambda mesh, e: student_flip(mesh, e, keep_vertex_halfedges=False))
    assert not result.passed and result.names
    named = {name for name in result.names.values()}
    assert {"v0", "v1", "v2", "v3", "h0", "h1"} <= named
    for kind, index in [result.element]:
        if (kind, index) in result.names:
            assert result.names[(kind, index)] in result.message


def test_the_phase_checks_pass_the_library_collapse_at_every_phase():
    from halfedge_edu.exercises.ops_checks import check_collapse_steps

    for upto in (2, 4, 5, 6):
        assert check_collapse_steps(lambda mesh, h: collapse(mesh, mesh.halfedge(h)), upto).passed


def test_the_phase_check_after_steps_1_and_2_passes_a_collapse_written_that_far():
    from halfedge_edu.exercises.ops_checks import check_collapse_steps

    def steps_1_and_2(mesh, h):
        vB, vA = int(mesh.halfedge_vertex[h]), int(mesh.halfedge_vertex[h ^ 1])
        h_L_B, h_B_R = int(mesh.halfedge_prev[h]), int(mesh.halfedge_next[h ^ 1])
        ring = _ring(mesh, h)
        mesh.positions[vA] = 0.5 * (mesh.positions[vA] + mesh.positions[vB])
        for g in ring:
            if g not in (h, h_L_B ^ 1, h_B_R):
                mesh.halfedge_vertex[g] = vA

    assert check_collapse_steps(steps_1_and_2, 2).passed
    later = check_collapse_steps(steps_1_and_2, 4)
    assert not later.passed and "step 3: h_A_L" in later.message


def test_the_phase_check_of_steps_3_and_4_names_reading_the_neighbours_too_early():
    from halfedge_edu.exercises.ops_checks import check_collapse_steps

    result = check_collapse_steps(lambda mesh, h: student_collapse(mesh, h, copy_first=True), 4)
    assert not result.passed and result.mesh_name == "cube, removing the degree-3 vertex 0"
    assert "read before you change anything of it" in result.message
