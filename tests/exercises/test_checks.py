"""check_build and check_one_ring: they pass correct answers and name planted mistakes.

Each planted mistake is one a student really makes; the test asserts the check stops on
the right mesh and element and says the sentence that helps.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.core.build import build_reference
from halfedge_edu.exercises import CheckResult, check_build, check_one_ring
from halfedge_edu.exercises import checks, harness
from halfedge_edu.exercises.checks import RING_SLIPS


# --------------------------------------------------------------------------------------
# Answers a student might write
# --------------------------------------------------------------------------------------

def student_build(faces):
    """The loop a student writes from chapter 02, with plain lists and dicts."""
    edge_of, vertex, face, next_ = {}, {}, {}, {}
    for f, (i, j, k) in enumerate(faces):
        made = []
        for a, b in ((i, j), (j, k), (k, i)):
            key = (min(a, b), max(a, b))
            if key not in edge_of:
                edge_of[key] = len(edge_of)
                h = 2 * edge_of[key]
            else:
                h = 2 * edge_of[key] + 1
            vertex[h], face[h] = int(a), f
            made.append(h)
        for n in range(3):
            next_[made[n]] = made[(n + 1) % 3]
    n_halfedges = 2 * len(edge_of)
    boundary = [h for h in range(n_halfedges) if h not in vertex]
    for h in boundary:
        vertex[h] = vertex[next_[h ^ 1]]
        face[h] = -1
    leaving = {vertex[h]: h for h in boundary}
    for h in boundary:
        next_[h] = leaving[vertex[h ^ 1]]
    return {
        "vertex": [vertex[h] for h in range(n_halfedges)],
        "face": [face[h] for h in range(n_halfedges)],
        "next": [next_[h] for h in range(n_halfedges)],
    }


def reference_build(faces):
    arrays = build_reference(faces)
    return {"vertex": arrays.halfedge_vertex, "face": arrays.halfedge_face, "next": arrays.halfedge_next,
            "prev": arrays.halfedge_prev, "vertex_halfedge": arrays.vertex_halfedge}


def changed(key, change):
    """A build that is the reference with ``change(array, faces)`` applied to one key."""
    def build(faces):
        answer = reference_build(faces)
        answer[key] = change(np.array(answer[key]), faces)
        return answer
    return build


def student_one_ring(mesh, v):
    start = v.halfedge
    ring, h = [], start
    while True:
        ring.append(h.tip.index)
        h = h.prev.twin
        if h == start:
            return ring


def walk(step, take=lambda h: h.tip.index, same=lambda a, b: a == b):
    def one_ring(mesh, v):
        start = v.halfedge
        ring, h = [], start
        while True:
            ring.append(take(h))
            h = step(h)
            if same(h, start):
                return ring
    return one_ring


# --------------------------------------------------------------------------------------
# check_build
# --------------------------------------------------------------------------------------

def test_check_build_passes_the_student_loop():
    result = check_build(student_build)
    assert result and result.passed
    assert repr(result).startswith("All good!")
    assert result.checked[0] == "two triangles" and "octahedron, shuffled" in result.checked


def test_check_build_passes_the_reference_with_optional_keys():
    assert check_build(reference_build)


def test_check_build_accepts_dicts_keyed_by_halfedge():
    def as_dicts(faces):
        return {key: dict(enumerate(values)) for key, values in student_build(faces).items()}

    assert check_build(as_dicts)


def test_missing_boundary_halfedges_are_named():
    def no_boundary(faces):
        answer = student_build(faces)
        return {key: values[: 3 * len(faces)] for key, values in answer.items()}

    result = check_build(no_boundary)
    assert not result and result.mesh_name == "two triangles"
    assert "make 10 halfedges" in result.message
    assert "the boundary halfedges are missing" in result.message


def test_twin_that_points_the_wrong_way_is_explained():
    def swap_first_edge(vertex, faces):
        vertex[[0, 1]] = vertex[[1, 0]]
        return vertex

    result = check_build(changed("vertex", swap_first_edge))
    assert result.element == ("halfedge", 0)
    assert "halfedge 0 is made by face 0 = [0, 1, 2], the first time edge 0 is seen" in result.message
    assert "It should run 0 -> 1, but yours runs 1 -> 0" in result.message
    assert "points the wrong way" in result.message


def test_edges_numbered_by_sorted_key_are_accepted_as_another_numbering():
    def sorted_numbering(faces):
        # Edges numbered by their sorted vertex pair instead of first sighting.
        answer = student_build(faces)
        vertex = np.array(answer["vertex"])
        keys = [tuple(sorted((vertex[2 * e], vertex[2 * e + 1]))) for e in range(len(vertex) // 2)]
        order = sorted(range(len(keys)), key=keys.__getitem__)
        new_edge = {old: new for new, old in enumerate(order)}
        new_h = lambda h: 2 * new_edge[h >> 1] + (h & 1)  # noqa: E731
        out = {key: [0] * len(vertex) for key in answer}
        for h in range(len(vertex)):
            out["vertex"][new_h(h)] = answer["vertex"][h]
            out["face"][new_h(h)] = answer["face"][h]
            out["next"][new_h(h)] = new_h(answer["next"][h])
        return out

    result = check_build(sorted_numbering)
    assert result.passed, result.message
    assert "whatever numbering you chose" in result.message


def uchicago_build(faces, *, pair_twins: bool = True, next_step: int = 1):
    """CMSC 23700's P1 order: face f allocates halfedges 3f, 3f + 1, 3f + 2 for (i, j),
    (j, k), (k, i); a side seen before gets its twin then; there are no boundary halfedges
    (twin None); a vertex's halfedge is the last one set."""
    n_halfedges = 3 * len(faces)
    vertex, face, next_ = [0] * n_halfedges, [0] * n_halfedges, [0] * n_halfedges
    twin: list[int | None] = [None] * n_halfedges
    vertex_halfedge: dict[int, int] = {}
    first_seen: dict[tuple[int, int], int] = {}
    for f, (i, j, k) in enumerate(faces.tolist()):
        for c, (a, b) in enumerate(((i, j), (j, k), (k, i))):
            h = 3 * f + c
            vertex[h], face[h], next_[h] = a, f, 3 * f + (c + next_step) % 3
            vertex_halfedge[a] = h
            key = (min(a, b), max(a, b))
            if key in first_seen:
                twin[h] = first_seen[key]
                if pair_twins:
                    twin[first_seen[key]] = h
            else:
                first_seen[key] = h
    return {"vertex": vertex, "face": face, "next": next_, "twin": twin,
            "vertex_halfedge": [vertex_halfedge[v] for v in range(len(vertex_halfedge))]}


def test_the_uchicago_allocation_order_is_accepted():
    result = check_build(uchicago_build)
    assert result.passed, result.message
    assert "octahedron, shuffled" in result.checked and "annulus (two boundary loops)" in result.checked


def test_uchicago_twin_set_one_way_only_is_named():
    result = check_build(lambda faces: uchicago_build(faces, pair_twins=False))
    assert not result and result.mesh_name == "two triangles"
    assert "halfedge 2 (2 -> 0) has no twin (-1), but faces 0 and 1 share that edge" in result.message
    assert "Your halfedge 3 has 2 as its twin: set the pair both ways" in result.message


def test_uchicago_next_the_wrong_way_round_is_named():
    result = check_build(lambda faces: uchicago_build(faces, next_step=2))
    assert not result and result.element == ("face", 0)
    assert ("halfedge 0 leaves vertex 0, so its next should be the halfedge of this face that leaves vertex 1"
            in result.message)
    assert "That is the corner before, not after" in result.message


def test_three_per_face_without_a_twin_list_says_how_to_return_it():
    def no_twin(faces):
        answer = uchicago_build(faces)
        del answer["twin"]
        return answer

    result = check_build(no_twin)
    assert not result and "the boundary halfedges are missing" in result.message
    assert "if you also return 'twin'" in result.message


def test_boundary_halfedge_with_a_face_is_named():
    def boundary_gets_face_zero(face, faces):
        face[face < 0] = 0
        return face

    result = check_build(changed("face", boundary_gets_face_zero))
    assert result.element == ("halfedge", 1)
    assert "halfedge 1 (1 -> 0) is a boundary halfedge" in result.message
    assert "should be -1, but yours says 0" in result.message


def test_clockwise_next_inside_a_face_is_named():
    def next_is_prev(next_, faces):
        prev = np.array(build_reference(faces).halfedge_prev)
        return np.where(np.array(build_reference(faces).halfedge_face) >= 0, prev, next_)

    result = check_build(changed("next", next_is_prev))
    assert result.element == ("halfedge", 0)
    assert "its next should be halfedge 2 (1 -> 2), the next side of the same triangle" in result.message
    assert "but yours is 4 (2 -> 0)" in result.message


def test_boundary_next_that_does_not_start_at_the_tip_is_named():
    def boundary_next_is_itself(next_, faces):
        face = np.array(build_reference(faces).halfedge_face)
        return np.where(face < 0, np.arange(len(next_)), next_)

    result = check_build(changed("next", boundary_next_is_itself))
    assert result.element == ("halfedge", 1)
    assert "halfedge 1 (1 -> 0) runs along the boundary" in result.message
    assert "its next should be the boundary halfedge that leaves vertex 0, halfedge 9 (0 -> 3)" in result.message
    assert "must start where its halfedge ends, at vertex 0" in result.message


def test_boundary_next_that_turns_into_a_face_is_named():
    def boundary_next_is_twin(next_, faces):
        face = np.array(build_reference(faces).halfedge_face)
        h = np.arange(len(next_))
        return np.where(face < 0, h ^ 1, next_)

    result = check_build(changed("next", boundary_next_is_twin))
    assert "but yours is 0 (0 -> 1). That one is inside a face" in result.message


def test_wrong_prev_is_named():
    result = check_build(changed("prev", lambda prev, faces: np.roll(prev, 1)))
    assert result.element == ("halfedge", 0)
    assert "the prev of halfedge 0 (0 -> 1) should be halfedge 4 (2 -> 0)" in result.message


def test_boundary_vertex_must_keep_its_boundary_halfedge():
    def smallest_outgoing(vertex_halfedge, faces):
        origin = np.array(build_reference(faces).halfedge_vertex)
        return np.array([int(np.flatnonzero(origin == v)[0]) for v in range(len(vertex_halfedge))])

    result = check_build(changed("vertex_halfedge", smallest_outgoing))
    assert result.element == ("vertex", 0)
    assert "vertex 0 is on the boundary, so its halfedge must be its outgoing boundary halfedge, 9 (0 -> 3)" in (
        result.message)


def test_unfinished_stub_says_fill_in_the_blanks():
    def stub(faces):
        raise NotImplementedError("write build here")

    result = check_build(stub)
    assert "build is not finished yet" in result.message
    assert "Fill in the blanks" in result.message


def test_blanks_in_the_code_say_fill_them_in_without_running_it():
    def stub(faces):
        h = ...
        while True:  # would never end: the check must not run it
            pass
        return {"vertex": [h], "face": [], "next": []}

    result = check_build(stub)
    assert result.message == ("Not yet. Your build still has blanks (...) in it. Fill each one in (no ... left) "
                              "and run the check again.")


def test_blank_values_from_elsewhere_say_not_finished():
    blank = ...
    result = check_build(lambda faces: {"vertex": blank, "face": [], "next": []})
    assert "still contains a blank (...)" in result.message


def test_returning_none_asks_for_a_dict():
    result = check_build(lambda faces: None)
    assert "should return a dict with the keys 'vertex', 'face' and 'next'" in result.message


def test_a_learner_exception_is_reported_by_name():
    result = check_build(lambda faces: {}["vertex"])
    assert "your build raised KeyError" in result.message


def test_a_mistake_on_a_later_mesh_lists_what_agreed_first():
    def fails_on_big_meshes(faces):
        answer = reference_build(faces)
        if len(faces) > 12:
            answer["face"] = np.zeros_like(answer["face"])
        return answer

    result = check_build(fails_on_big_meshes)
    assert result.mesh_name == "open patch"
    assert "(It agreed on two triangles, lone triangle, strip, tetrahedron, cube first.)" in result.message


def test_a_build_that_never_ends_is_stopped():
    def forever(faces):
        while True:
            pass

    started = time.perf_counter()
    result = check_build(forever)
    assert time.perf_counter() - started < 10 * harness.TIME_LIMIT
    assert "did not finish within" in result.message


# --------------------------------------------------------------------------------------
# check_one_ring
# --------------------------------------------------------------------------------------

def test_check_one_ring_passes_the_counter_clockwise_walk():
    result = check_one_ring(student_one_ring)
    assert result and "annulus (two boundary loops)" in result.checked
    assert repr(result).startswith("All good!")


def test_check_one_ring_accepts_vertex_handles():
    assert check_one_ring(lambda mesh, v: v.neighbors())


def test_the_cmu_clockwise_walk_is_accepted_and_the_chapters_direction_explained():
    result = check_one_ring(walk(lambda h: h.twin.next))
    assert result.passed, result.message
    assert "annulus (two boundary loops)" in result.checked
    assert "Your walk turns clockwise (h = h.twin.next, as in the CMU notes)" in result.message
    assert "counter-clockwise (h = h.prev.twin) because" in result.message


def test_a_walk_that_changes_direction_between_vertices_is_named():
    def sometimes_clockwise(mesh, v):
        step = (lambda h: h.twin.next) if int(v) == 2 else (lambda h: h.prev.twin)
        return walk(step)(mesh, v)

    result = check_one_ring(sometimes_clockwise)
    assert not result and result.mesh_name == "open patch" and result.element == ("vertex", 2)
    assert "goes clockwise, but your rings before went counter-clockwise" in result.message


def test_a_clockwise_walk_from_the_wrong_start_is_named():
    def clockwise_from_the_next_one(mesh, v):
        ring = walk(lambda h: h.twin.next)(mesh, v)
        return ring[1:] + ring[:1]

    result = check_one_ring(clockwise_from_the_next_one)
    assert result.mesh_name == "open patch" and result.element == ("vertex", 0)
    assert "That is the clockwise order (CMU's h.twin.next walk, fine too) but from another start" in result.message


def test_wrong_start_is_named():
    def second_first(mesh, v):
        ring = [int(u) for u in v.neighbors()]
        return ring[1:] + ring[:1]

    result = check_one_ring(second_first)
    assert "Right order, wrong start: begin with the tip of v.halfedge, vertex 4" in result.message


def test_origins_instead_of_tips_are_named():
    result = check_one_ring(walk(lambda h: h.prev.twin, take=lambda h: h.vertex.index))
    assert "Every entry is v itself" in result.message


def test_walking_around_the_tip_is_named():
    result = check_one_ring(walk(lambda h: h.next.twin))
    assert "Every entry is vertex 4: the walk circles around that vertex" in result.message


def test_halfedges_instead_of_vertices_are_named():
    result = check_one_ring(lambda mesh, v: v.outgoing())
    assert "your ring contains halfedges" in result.message


def test_skipping_the_boundary_halfedge_is_named():
    def interior_only(mesh, v):
        return [h.tip.index for h in v.outgoing() if h.face is not None]

    result = check_one_ring(interior_only)
    assert result.mesh_name == "open patch" and result.element == ("vertex", 0)
    assert "vertex 0 lies on the boundary (its halfedge 9 is the boundary halfedge 0 -> 4)" in result.message
    assert "Missing [4]" in result.message and "pass through the boundary halfedge" in result.message


def test_comparing_handles_with_is_is_stopped_and_explained():
    started = time.perf_counter()
    result = check_one_ring(walk(lambda h: h.prev.twin, same=lambda a, b: a is b))
    assert time.perf_counter() - started < 10 * harness.TIME_LIMIT
    assert "did not return within" in result.message and "not `is`" in result.message


def test_forgotten_return_is_named():
    result = check_one_ring(lambda mesh, v: None)
    assert "did you forget `return`?" in result.message


def test_one_ring_stub_says_not_finished():
    def stub(mesh, v):
        raise NotImplementedError

    assert "one_ring is not finished yet" in check_one_ring(stub).message


def test_one_ring_with_blanks_is_not_run():
    def stub(mesh, v):
        start = v.halfedge
        ring, h = [], start
        while True:
            ring.append(...)
            h = ...
            if h == start:
                return ring

    started = time.perf_counter()
    result = check_one_ring(stub)
    assert time.perf_counter() - started < harness.TIME_LIMIT
    assert "Your one_ring still has blanks (...)" in result.message


# --------------------------------------------------------------------------------------
# The result object
# --------------------------------------------------------------------------------------

def test_result_reads_as_its_message():
    result = check_one_ring(walk(lambda h: h.next.twin))
    assert isinstance(result, CheckResult)
    assert repr(result) == result.message and result.message.startswith("Not yet. On 'open patch': ")
    assert isinstance(result.mesh, hx.HalfedgeMesh)


def test_show_draws_nothing_for_a_pass():
    assert check_one_ring(student_one_ring).show() is None


def test_the_exercises_are_not_loaded_by_the_package():
    import subprocess
    import sys

    code = "import sys, halfedge_edu; print('halfedge_edu.exercises' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout.strip() == "False"


@pytest.mark.parametrize("name", ["two triangles", "open patch, shuffled", "annulus (two boundary loops)"])
def test_build_cases_are_valid_meshes(name):
    cases = {case[0]: case for case in checks.build_cases()}
    _, vertices, faces = cases[name]
    hx.HalfedgeMesh.from_faces(vertices, faces).validate()


# --------------------------------------------------------------------------------------
# Every row of the slip table, from the slip's own code
# --------------------------------------------------------------------------------------

def _walk_until_back(step):
    """A learner's one_ring with one step rule; at most 50 steps, so a walk that never comes back ends."""
    def one_ring(mesh, v):
        start = v.halfedge
        ring, h = [], start
        for _ in range(50):
            ring.append(h.tip.index)
            h = step(h)
            if h == start:
                break
        return ring
    return one_ring


SLIP_CODE = {
    "origins instead of tips": walk(lambda h: h.prev.twin, take=lambda h: h.vertex.index),
    "walking around a face (h = h.next)": _walk_until_back(lambda h: h.next),
    "a step that gives back its own halfedge (h = h.twin.twin)": _walk_until_back(lambda h: h.twin.twin),
    "circling around the tip (h = h.next.twin)": walk(lambda h: h.next.twin),
    "right order, wrong start": lambda mesh, v: [int(u) for u in v.neighbors()][1:] + [int(u) for u in v.neighbors()][:1],
    "clockwise from another start":
        lambda mesh, v: (lambda r: r[1:] + r[:1])(walk(lambda h: h.twin.next)(mesh, v)),
    "right neighbours, out of order":     # two neighbours swapped: not a turn of the ring either way
        lambda mesh, v: (lambda r: r[:1] + r[2:3] + r[1:2] + r[3:] if len(r) > 3 else r)([int(u) for u in v.neighbors()]),
    "stopping at the boundary halfedge": lambda mesh, v: [h.tip.index for h in v.outgoing() if h.face is not None],
}
SENTENCES = {name: sentence for name, _, sentence in RING_SLIPS}


@pytest.mark.parametrize("slip", sorted(SLIP_CODE))
def test_each_ring_slip_gets_its_own_sentence_and_no_other(slip):
    result = check_one_ring(SLIP_CODE[slip])
    assert not result.passed
    own = SENTENCES[slip].split("{")[0][:40]
    assert own in result.message, result.message
    for other, sentence in SENTENCES.items():
        if other != slip and not sentence.startswith(SENTENCES[slip][:20]):
            assert sentence.split("{")[0][:40] not in result.message, (other, result.message)


def test_twin_twin_is_not_told_to_pass_the_boundary_halfedge():
    result = check_one_ring(SLIP_CODE["a step that gives back its own halfedge (h = h.twin.twin)"])
    assert "h.twin.twin == h" in result.message
    assert "so don't stop at h.face is None" not in result.message


def test_every_row_of_the_slip_table_is_tested_with_its_code():
    assert {name for name, _, _ in RING_SLIPS} == set(SLIP_CODE)
