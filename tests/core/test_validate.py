"""``validate()``: a sound mesh passes; each rule, broken on purpose, is the one reported.

Each case breaks a valid mesh by writing into its public arrays (or, for the one shape
that faces cannot describe, builds the arrays by hand) so that exactly one rule fails
first, and checks the error's ``rule``, ``element`` and that the sentence names it.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.core import validate as validate_module
from halfedge_edu.core.build import HalfedgeArrays
from tests import strategies as shapes
from tests.strategies import build, meshes, open_meshes

# The rows of the rule table in validate.py's docstring (the header row says "rule").
RULES_IN_DOCSTRING = set(re.findall(r"^\| ([a-z-]+) +\|", validate_module.__doc__, flags=re.MULTILINE)) - {"rule"}



def _mesh(arrays) -> hx.HalfedgeMesh:
    return hx.HalfedgeMesh.from_faces(*arrays)


def _first_halfedge_leaving(mesh: hx.HalfedgeMesh, v: int) -> int:
    return int(np.flatnonzero(mesh.halfedge_vertex == v)[0])


# ---- a sound mesh passes ---------------------------------------------------------------

@given(meshes())
def test_built_meshes_are_valid(drawn):
    assert build(drawn).validate() is None


@given(meshes())
def test_a_copy_is_valid_and_independent(drawn):
    mesh = build(drawn)
    twin = mesh.copy()
    twin.validate()
    twin.halfedge_next[0] = twin.halfedge_next[1]
    with pytest.raises(hx.MeshInvariantError):
        twin.validate()
    mesh.validate()


@given(meshes())
def test_validate_changes_nothing(drawn):
    mesh = build(drawn)
    before = [array.copy() for array in (mesh.halfedge_next, mesh.halfedge_prev, mesh.vertex_halfedge)]
    mesh.validate()
    after = (mesh.halfedge_next, mesh.halfedge_prev, mesh.vertex_halfedge)
    assert all(np.array_equal(a, b) for a, b in zip(before, after))


def test_deleted_elements_are_not_checked(two_spheres):
    # Removing the whole tetrahedron (the second piece) by flags leaves a sound octahedron.
    for f in range(8, 12):
        two_spheres.delete_face(f)
    for e in range(12, 18):
        two_spheres.delete_edge(e)
    for v in range(6, 10):
        two_spheres.delete_vertex(v)
    two_spheres.halfedge_next[24:] = -7               # garbage in deleted slots is ignored
    two_spheres.validate()


# ---- each rule, broken on purpose -----------------------------------------------------------
# A case is a function that breaks a fresh mesh and returns (mesh, rule, element, words),
# where `words` is what the sentence must contain to point the student at the element.

def next_out_of_range():
    mesh = _mesh(shapes.grid(2, 2))
    mesh.halfedge_next[3] = mesh.n_halfedge_slots
    return mesh, "deleted-reference", ("halfedge", 3), "halfedge 3"


def prev_negative():
    mesh = _mesh(shapes.grid(2, 2))
    mesh.halfedge_prev[5] = -1
    return mesh, "deleted-reference", ("halfedge", 5), "halfedge 5"


def origin_is_a_deleted_vertex():
    mesh = _mesh(shapes.tetrahedron())
    mesh.delete_vertex(2)
    return mesh, "deleted-reference", ("halfedge", _first_halfedge_leaving(mesh, 2)), "was deleted"


def face_out_of_range():
    mesh = _mesh(shapes.grid(2, 2))
    mesh.halfedge_face[4] = mesh.n_face_slots
    return mesh, "deleted-reference", ("halfedge", 4), "halfedge 4"


def face_was_deleted():
    mesh = _mesh(shapes.square())
    mesh.delete_face(1)
    return mesh, "deleted-reference", ("halfedge", 5), "halfedge 5"


def next_is_a_deleted_halfedge():
    mesh = _mesh(shapes.tetrahedron())
    mesh.delete_edge(2)
    first = int(np.flatnonzero((mesh.halfedge_next >> 1) == 2)[0])
    return mesh, "deleted-reference", ("halfedge", first), f"halfedge {first}"


def face_halfedge_out_of_range():
    mesh = _mesh(shapes.octahedron())
    mesh.face_halfedge[1] = -1
    return mesh, "deleted-reference", ("face", 1), "face 1"


def vertex_halfedge_out_of_range():
    mesh = _mesh(shapes.octahedron())
    mesh.vertex_halfedge[2] = 10**6
    return mesh, "deleted-reference", ("vertex", 2), "vertex 2"


def orphan_vertex():
    mesh = _mesh(shapes.tetrahedron())
    mesh.add_vertex([5.0, 5.0, 5.0])
    mesh.halfedge_vertex[0] = 4  # a halfedge leaves it, so it is not isolated
    return mesh, "vertex-halfedge-origin", ("vertex", 4), "vertex 4"


def vertex_without_halfedge():
    mesh = _mesh(shapes.tetrahedron())
    mesh.vertex_halfedge[2] = -1
    return mesh, "vertex-halfedge-origin", ("vertex", 2), "vertex 2"


def next_skips_a_halfedge():
    mesh = _mesh(shapes.tetrahedron())
    mesh.halfedge_next[3] = mesh.halfedge_prev[3]     # a 2-loop, but prev still says otherwise
    return mesh, "next-prev-inverse", ("halfedge", 3), "halfedge 3"


def prev_points_elsewhere():
    mesh = _mesh(shapes.octahedron())
    old_prev = int(mesh.halfedge_prev[5])
    mesh.halfedge_prev[5] = mesh.halfedge_next[5]
    return mesh, "next-prev-inverse", ("halfedge", old_prev), f"halfedge {old_prev}"


def twins_start_at_the_same_vertex():
    mesh = _mesh(shapes.octahedron())
    mesh.halfedge_vertex[1] = mesh.halfedge_vertex[0]
    return mesh, "twin-involution", ("halfedge", 0), "halfedge 0"


def origin_moved_to_a_third_vertex():
    mesh = _mesh(shapes.octahedron())
    h = 6
    ends = {int(mesh.halfedge_vertex[h]), int(mesh.halfedge_vertex[h ^ 1])}
    mesh.halfedge_vertex[h] = min(set(range(6)) - ends)
    # Two halfedges now end where their next does not start: prev(h) and twin(h).
    first = min(int(mesh.halfedge_prev[h]), h ^ 1)
    return mesh, "next-origin", ("halfedge", first), f"halfedge {first}"


def halfedge_in_the_wrong_face():
    mesh = _mesh(shapes.grid(2, 2))
    h = 7 if mesh.halfedge_face[7] >= 0 else 6
    other = (int(mesh.halfedge_face[h]) + 1) % mesh.n_faces
    mesh.halfedge_face[h] = other
    # h's next is in its old face, and prev(h)'s next (h) is no longer in prev(h)'s face.
    first = min(h, int(mesh.halfedge_prev[h]))
    return mesh, "next-cycle", ("halfedge", first), f"halfedge {first}"


def face_loop_of_six():
    # The square's two triangles, halfedges 0 2 4 and 5 6 8, are joined into one loop
    # 0 -> 2 -> 6 -> 8 -> 5 -> 4 (both 2 and 5 end at vertex 2, so the origins still
    # match), all in face 0, and face 1 is deleted: a quad-like loop of six halfedges.
    mesh = _mesh(shapes.square())
    mesh.halfedge_next[2], mesh.halfedge_next[5] = 6, 4
    mesh.halfedge_prev[6], mesh.halfedge_prev[4] = 2, 5
    mesh.halfedge_face[[5, 6, 8]] = 0
    mesh.delete_face(1)
    return mesh, "next-cycle", ("halfedge", 0), "halfedge 0"


def face_halfedge_in_another_face():
    mesh = _mesh(shapes.square())
    mesh.face_halfedge[0] = 5
    return mesh, "face-halfedge", ("face", 0), "face 0"


def edge_without_faces():
    # Delete the square's face 1 and make its halfedges boundary: edge 3 (vertices 2, 3)
    # is left with no face on either side, a dangling edge.
    mesh = _mesh(shapes.square())
    mesh.delete_face(1)
    mesh.halfedge_face[[5, 6, 8]] = -1
    return mesh, "edge-halfedge", ("edge", 3), "edge 3"


def vertex_halfedge_leaves_another_vertex():
    mesh = _mesh(shapes.tetrahedron())
    mesh.vertex_halfedge[0] = _first_halfedge_leaving(mesh, 1)
    return mesh, "vertex-halfedge-origin", ("vertex", 0), "vertex 0"


def boundary_vertex_points_inside():
    mesh = _mesh(shapes.grid(2, 2))
    corner = mesh.vertex(0)
    inside = next(h for h in corner.outgoing() if not h.is_boundary)
    mesh.vertex_halfedge[0] = inside.index
    return mesh, "boundary-vertex-halfedge", ("vertex", 0), "vertex 0"


def _merge_vertex(mesh: hx.HalfedgeMesh, gone: int, kept: int) -> None:
    """Make every halfedge of vertex ``gone`` use ``kept`` instead, and delete ``gone``."""
    mesh.halfedge_vertex[mesh.halfedge_vertex == gone] = kept
    mesh.delete_vertex(gone)


def bowtie():
    # Two separate triangles 0 1 2 and 3 4 5, then vertex 3 is glued onto vertex 0.
    mesh = _mesh((np.arange(18.0).reshape(6, 3), [[0, 1, 2], [3, 4, 5]]))
    _merge_vertex(mesh, 3, 0)
    return mesh, "vertex-manifold", ("vertex", 0), "vertex 0"


def two_cones_touching():
    # Two tetrahedra, the second's vertex 4 glued onto vertex 0: 3 of vertex 0's 6 edges
    # are reachable from its halfedge.
    mesh = _mesh(shapes.disjoint_union(shapes.tetrahedron(), shapes.tetrahedron()))
    _merge_vertex(mesh, 4, 0)
    return mesh, "vertex-manifold", ("vertex", 0), "3 of its 6 edges"


def two_edges_between_two_vertices():
    # A sphere made of two digons: vertices 0 and 1 are joined by two edges, e0 (halfedges
    # 0, 1) and e1 (halfedges 2, 3); vertex 2 sits inside one digon and vertex 3 inside
    # the other. Faces cannot describe it (both edges are "(0, 1)"), so the arrays are
    # written out:  face 0 = 0 -> 6 -> 5 (0 1 2), face 1 = 3 -> 4 -> 7 (1 0 2),
    # face 2 = 1 -> 8 -> 11 (1 0 3), face 3 = 2 -> 10 -> 9 (0 1 3).
    nxt = np.array([6, 8, 10, 4, 7, 0, 5, 3, 11, 2, 9, 1])
    arrays = HalfedgeArrays(
        positions=np.array([[0, 0, 1], [0, 0, -1], [1, 0, 0], [-1, 0, 0]], dtype=float),
        vertex_halfedge=np.array([0, 1, 5, 9]),
        halfedge_next=nxt,
        halfedge_prev=np.argsort(nxt),
        halfedge_vertex=np.array([0, 1, 0, 1, 0, 2, 1, 2, 0, 3, 1, 3]),
        halfedge_face=np.array([0, 2, 3, 1, 1, 0, 0, 1, 2, 3, 3, 2]),
        face_halfedge=np.array([0, 3, 1, 2]),
    )
    return hx.HalfedgeMesh(arrays), "duplicate-edge", ("edge", (0, 1)), "vertices 0 and 1"


def face_flagged_deleted_by_hand():
    # No earlier deletions: the counters say "nothing deleted", the flag says otherwise.
    mesh = _mesh(shapes.grid(2, 2))
    mesh.face_deleted[3] = True
    return mesh, "deletion-count", ("face", 3), "face 3"


CASES = [
    face_flagged_deleted_by_hand, next_out_of_range, prev_negative, origin_is_a_deleted_vertex, face_out_of_range, face_was_deleted,
    next_is_a_deleted_halfedge, face_halfedge_out_of_range, vertex_halfedge_out_of_range, orphan_vertex,
    vertex_without_halfedge, next_skips_a_halfedge, prev_points_elsewhere, twins_start_at_the_same_vertex,
    origin_moved_to_a_third_vertex, halfedge_in_the_wrong_face, face_loop_of_six, face_halfedge_in_another_face,
    edge_without_faces, vertex_halfedge_leaves_another_vertex, boundary_vertex_points_inside, bowtie,
    two_cones_touching, two_edges_between_two_vertices,
]


@pytest.mark.parametrize("case", CASES, ids=[case.__name__ for case in CASES])
def test_broken_rule_is_reported_with_its_element(case):
    mesh, rule, element, words = case()
    with pytest.raises(hx.MeshInvariantError) as caught:
        mesh.validate()
    assert (caught.value.rule, caught.value.element) == (rule, element)
    assert str(caught.value).startswith(f"[{rule}] ")
    assert words in str(caught.value)


def test_every_rule_in_the_docstring_has_a_case():
    assert len(RULES_IN_DOCSTRING) >= 11
    covered = {case()[1] for case in CASES}
    assert covered == RULES_IN_DOCSTRING


def test_the_digon_sphere_is_sound_apart_from_its_double_edge():
    # Guards the duplicate-edge case: its arrays must pass every other rule.
    mesh, *_ = two_edges_between_two_vertices()
    assert mesh.euler_characteristic == 2
    for v in mesh.vertices:
        assert v.degree == len(v.outgoing()) == (4 if v.index < 2 else 2)
    for f in mesh.faces:
        assert len(f.halfedges()) == 3


@given(open_meshes())
def test_any_boundary_vertex_pointing_inside_is_caught(drawn):
    mesh = build(drawn)
    v = next(v for v in mesh.vertices if v.is_boundary and v.degree > 1)
    mesh.vertex_halfedge[v.index] = v.outgoing()[1].index
    with pytest.raises(hx.MeshInvariantError) as caught:
        mesh.validate()
    assert (caught.value.rule, caught.value.element) == ("boundary-vertex-halfedge", ("vertex", v.index))


@given(meshes())
def test_any_broken_next_pointer_is_caught(drawn):
    mesh = build(drawn)
    h = mesh.n_halfedges // 2
    mesh.halfedge_next[h] = mesh.halfedge_next[mesh.halfedge_next[h]]
    with pytest.raises(hx.MeshInvariantError) as caught:
        mesh.validate()
    assert (caught.value.rule, caught.value.element) == ("next-prev-inverse", ("halfedge", h))


@given(drawn=meshes(), kind=st.sampled_from(["vertex", "edge", "face"]), pick=st.integers(0, 10**6))
def test_any_deleted_flag_set_by_hand_is_caught_before_to_arrays_can_mislead(drawn, kind, pick):
    mesh = build(drawn)
    flags = {"vertex": mesh.vertex_deleted, "edge": mesh.edge_deleted, "face": mesh.face_deleted}[kind]
    index = pick % len(flags)
    flags[index] = True
    with pytest.raises(hx.MeshInvariantError) as caught:
        mesh.validate()
    assert (caught.value.rule, caught.value.element) == ("deletion-count", (kind, index))


def test_a_flag_moved_by_hand_after_a_real_deletion_is_caught(two_spheres):
    # The counts agree (one face deleted, one flagged) but the flagged face is still in use.
    two_spheres.delete_face(8)
    two_spheres.face_deleted[8] = False
    two_spheres.face_deleted[0] = True
    with pytest.raises(hx.MeshInvariantError) as caught:
        two_spheres.validate()
    assert caught.value.rule == "deleted-reference"


# ---- validate_around: the local check after one operation ----------------------------------

def _operate(mesh: hx.HalfedgeMesh, kind: str, pick: int) -> dict | None:
    """Apply one allowed flip, split or collapse (the edge chosen by ``pick``); return what it touched."""
    live_edges = np.flatnonzero(~mesh.edge_deleted)
    edge = int(live_edges[pick % len(live_edges)])
    if kind == "flip" and mesh.can_flip(edge):
        return {"edges": [mesh.flip(edge)]}
    if kind == "split" and mesh.can_split(edge):
        return {"vertices": [mesh.split(edge)]}
    if kind == "collapse" and mesh.can_collapse(edge):
        return {"vertices": [mesh.collapse(edge)]}
    return None


def _raises(check) -> bool:
    try:
        check()
    except hx.MeshInvariantError:
        return True
    return False


POINTERS = {
    "next": lambda mesh: mesh.halfedge_next,
    "prev": lambda mesh: mesh.halfedge_prev,
    "vertex": lambda mesh: mesh.halfedge_vertex,
    "face": lambda mesh: mesh.halfedge_face,
}


@pytest.mark.parametrize("field", sorted(POINTERS))
@pytest.mark.parametrize("kind", ["flip", "split", "collapse"])
def test_one_pointer_broken_next_to_an_operation_is_caught_by_the_local_check(kind, field):
    mesh = _mesh(shapes.torus(8, 6))
    touched = _operate(mesh, kind, 17)
    assert touched is not None
    validate_module.validate_around(mesh, **touched)          # sound after the operation
    # Break a pointer of a halfedge that leaves the vertex the operation worked on.
    vertex = int(touched["vertices"][0]) if "vertices" in touched else int(mesh.halfedge_vertex[2 * int(touched["edges"][0])])
    h = int(mesh.vertex_halfedge[vertex])
    array = POINTERS[field](mesh)
    array[h] = array[h ^ 1]                                     # its twin's: wrong for every field
    assert _raises(mesh.validate)
    with pytest.raises(hx.MeshInvariantError):
        validate_module.validate_around(mesh, **touched)


def test_the_local_check_reaches_the_one_ring_of_the_touched_vertex():
    mesh = _mesh(shapes.torus(8, 6))
    v = int(mesh.split(5))
    neighbour = int(mesh.halfedge_vertex[int(mesh.vertex_halfedge[v]) ^ 1])
    far_side = int(mesh.vertex_halfedge[neighbour])
    mesh.vertex_halfedge[neighbour] = far_side ^ 1             # now it leaves another vertex
    with pytest.raises(hx.MeshInvariantError) as caught:
        validate_module.validate_around(mesh, vertices=[v])
    assert caught.value.rule == "vertex-halfedge-origin"
    assert caught.value.element == ("vertex", neighbour)


def test_the_local_check_refuses_elements_that_are_not_in_the_mesh():
    mesh = _mesh(shapes.tetrahedron())
    with pytest.raises(hx.MeshInputError, match="vertex 99"):
        validate_module.validate_around(mesh, vertices=[99])


@given(
    drawn=meshes(),
    steps=st.lists(st.tuples(st.sampled_from(["flip", "split", "collapse"]), st.integers(0, 10**6)),
                   min_size=1, max_size=8),
    corrupt=st.one_of(st.none(), st.tuples(st.sampled_from(sorted(POINTERS)), st.integers(0, 10**6),
                                           st.integers(0, 10**6))),
)
def test_the_local_and_the_full_check_agree_after_random_operations(drawn, steps, corrupt):
    mesh = build(drawn)
    touched = None
    for kind, pick in steps:
        done = _operate(mesh, kind, pick)
        if done is not None:
            touched = done
            validate_module.validate_around(mesh, **touched)   # every operation leaves it sound
    if touched is None:
        return
    if corrupt is not None:
        # One pointer of a halfedge near the last operation gets a value of the same kind.
        field, which, value = corrupt
        vertex = (int(touched["vertices"][0]) if "vertices" in touched
                  else int(mesh.halfedge_vertex[2 * int(touched["edges"][0])]))
        ring = [int(mesh.vertex_halfedge[vertex])]
        for _ in range(20):
            following = int(mesh.halfedge_prev[ring[-1]]) ^ 1
            if following == ring[0]:
                break
            ring.append(following)
        h = ring[which % len(ring)] ^ (value & 1)
        array = POINTERS[field](mesh)
        array[h] = array[int(np.flatnonzero(~mesh.halfedge_deleted)[value % mesh.n_halfedges])]
    assert _raises(lambda: validate_module.validate_around(mesh, **touched)) == _raises(mesh.validate)
