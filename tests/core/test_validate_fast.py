"""The fast pass of ``validate()`` (``core/validate_fast.py``) is pinned to the rule-by-rule checks.

The fast pass only says True or False; ``validate()`` believes its True. So every test
here breaks a mesh and checks that the fast pass refuses it and that the rules, run one
by one, name the broken rule: on random meshes with one pointer overwritten
(hypothesis, with both memory layouts the pass can take), and on the shapes and the
block boundaries that a random overwrite rarely reaches.
"""

from __future__ import annotations

import re
from unittest import mock

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import halfedge_edu as hx
from halfedge_edu.core import validate as validate_module
from halfedge_edu.core import validate_fast
from halfedge_edu.core.build import HalfedgeArrays
from tests import strategies as shapes
from tests.strategies import build, meshes


def refused_by_fast_path_and_named(mesh: hx.HalfedgeMesh) -> hx.MeshInvariantError:
    """The error ``mesh.validate()`` raises, after checking that the all-rules-at-once fast
    path (``every_rule_holds``) refuses ``mesh`` too: a break it missed would leave
    only the rule-by-rule path to find it, on meshes that have no deleted elements."""
    assert not validate_fast.every_rule_holds(mesh)
    with pytest.raises(hx.MeshInvariantError) as caught:
        mesh.validate()
    return caught.value


def _mesh(arrays) -> hx.HalfedgeMesh:
    return hx.HalfedgeMesh.from_faces(*arrays)


def _raises(check) -> bool:
    try:
        check()
    except hx.MeshInvariantError:
        return True
    return False


# ---- the whole-mesh fast path and the rule-by-rule checks agree ------------------------------

ALL_POINTERS = {
    "next": lambda mesh: mesh.halfedge_next,
    "prev": lambda mesh: mesh.halfedge_prev,
    "vertex": lambda mesh: mesh.halfedge_vertex,
    "face": lambda mesh: mesh.halfedge_face,
    "vertex_halfedge": lambda mesh: mesh.vertex_halfedge,
    "face_halfedge": lambda mesh: mesh.face_halfedge,
}


@given(
    drawn=meshes(),
    field=st.sampled_from(sorted(ALL_POINTERS)),
    where=st.integers(0, 10**6),
    value=st.one_of(st.integers(0, 10**6), st.sampled_from(["-1", "one past the end"])),
)
def test_the_fast_path_fails_exactly_when_a_rule_by_rule_check_fails(drawn, field, where, value):
    # One pointer gets another pointer's value from the same array (or -1, or one past
    # the last slot); the fast path must say "broken" exactly when the rules name a rule.
    mesh = build(drawn)
    array = ALL_POINTERS[field](mesh)
    slot = where % len(array)
    array[slot] = {"-1": -1, "one past the end": len(array)}.get(value, array[int(value) % len(array)] if isinstance(value, int) else 0)
    fast_broken = _raises(lambda: not validate_fast.every_rule_holds(mesh) and _fail())
    with mock.patch.object(validate_fast, "every_rule_holds", lambda mesh: False):
        rules_broken = _raises(mesh.validate)
    assert fast_broken == rules_broken


def _fail() -> None:
    raise hx.MeshInvariantError("fast-path", ("mesh", 0), "the fast path found a broken rule")


def test_a_sound_mesh_takes_the_fast_path_and_a_broken_one_the_rules():
    mesh = _mesh(shapes.torus(8, 6))
    assert validate_fast.every_rule_holds(mesh)
    mesh.halfedge_prev[7] = mesh.halfedge_prev[8]
    found = refused_by_fast_path_and_named(mesh)
    assert found.rule == "next-prev-inverse"


def _several_blocks(n_items: int, size: int) -> int:
    """The number of blocks of ``size`` that ``n_items`` fill (the last one partial),
    checked to be at least three: a block test means nothing on one block."""
    n_blocks = -(-n_items // size)
    assert n_blocks >= 3, "the mesh must span several blocks for this test to mean anything"
    return n_blocks


@pytest.mark.parametrize("block", ["first", "middle", "last"])
def test_the_fast_path_checks_every_block_of_halfedges(block):
    # The fast path reads the halfedges in blocks of _BLOCK; a broken pointer in any
    # block, the last (partial) one included, must be found. The broken face pointer is
    # put on a halfedge whose prev lies in the same block and that is not its face's
    # own halfedge, so only that block's next-cycle check can see it.
    mesh = _mesh(shapes.torus(120, 80))                      # 57,600 halfedges: several blocks
    size = validate_fast._BLOCK
    n_blocks = _several_blocks(mesh.n_halfedge_slots, size)
    index = {"first": 0, "middle": n_blocks // 2, "last": n_blocks - 1}[block]
    in_block = np.arange(index * size, min((index + 1) * size, mesh.n_halfedge_slots))
    seen_only_here = ((mesh.halfedge_prev[in_block] // size == index)
                      & (mesh.halfedge_face[in_block] >= 0)
                      & (mesh.face_halfedge[mesh.halfedge_face[in_block]] != in_block))
    assert seen_only_here.any()
    h = int(in_block[np.argmax(seen_only_here)])
    assert validate_fast.every_rule_holds(mesh)
    mesh.halfedge_face[h] = (mesh.halfedge_face[h] + 1) % mesh.n_face_slots
    found = refused_by_fast_path_and_named(mesh)
    assert found.rule == "next-cycle"


OUT_OF_RANGE = {
    "next past the end": ("halfedge_next", lambda mesh: mesh.n_halfedge_slots + 7),
    "prev -1": ("halfedge_prev", lambda mesh: -1),
    "prev past the end": ("halfedge_prev", lambda mesh: mesh.n_halfedge_slots),
    "vertex -1": ("halfedge_vertex", lambda mesh: -1),
    "vertex past the end": ("halfedge_vertex", lambda mesh: mesh.n_vertex_slots),
    "face -2": ("halfedge_face", lambda mesh: -2),
    "face past the end": ("halfedge_face", lambda mesh: mesh.n_face_slots),
}


@pytest.mark.parametrize("shape", ["closed", "open"])
@pytest.mark.parametrize("case", sorted(OUT_OF_RANGE))
def test_a_halfedge_pointer_out_of_range_in_a_middle_block_is_found(case, shape):
    # The fast path makes no pass of its own over next, prev, origin or face: face is
    # range-checked block by block, next by two look-ups, and prev and origin are in
    # range because other rules hold. One value out of range, on an interior halfedge
    # in a middle block (one with boundary halfedges on the open mesh), is still named.
    mesh = _mesh(shapes.torus(120, 80) if shape == "closed" else shapes.grid(150, 100))
    size = validate_fast._BLOCK
    n_blocks = _several_blocks(mesh.n_halfedge_slots, size)
    middle = np.arange((n_blocks // 2) * size, (n_blocks // 2 + 1) * size)
    assert (mesh.halfedge_face[middle] < 0).any() == (shape == "open")
    h = int(middle[len(middle) // 2:][np.argmax(mesh.halfedge_face[middle[len(middle) // 2:]] >= 0)])
    field, value = OUT_OF_RANGE[case]
    getattr(mesh, field)[h] = value(mesh)
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == ("deleted-reference", ("halfedge", h))


@pytest.mark.parametrize("shape", ["closed", "open"])
@pytest.mark.parametrize("end", ["first", "last"])
def test_a_next_that_a_clipped_gather_reads_as_in_range_is_found(end, shape):
    # The gathers at next(h) clip: next = -1 reads halfedge 0, next = n_h reads n_h - 1.
    # Given to the halfedge whose next really is that one, such a value passes every
    # rule read at next(h). Inside a face, next(next()) of the halfedge before it reads
    # the bad value and sees it; on the boundary, where next(next()) is not compared
    # (the open mesh's last halfedge is a boundary one), only the look-ups after the
    # loop do.
    mesh = _mesh(shapes.torus(120, 80) if shape == "closed" else shapes.grid(150, 100))
    n_h = mesh.n_halfedge_slots
    h = int(mesh.halfedge_prev[0 if end == "first" else n_h - 1])
    assert (mesh.halfedge_face[h] < 0) == (shape == "open" and end == "last")
    mesh.halfedge_next[h] = -1 if end == "first" else n_h
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == ("deleted-reference", ("halfedge", h))


@pytest.mark.parametrize("kind", ["face", "vertex"])
def test_an_element_halfedge_that_a_clipped_gather_reads_as_in_range_is_found(kind):
    # A face's (vertex's) halfedge n_h reads, clipped, as halfedge n_h - 1; given to the
    # face of n_h - 1 (the vertex it leaves), it passes face-halfedge
    # (vertex-halfedge-origin). Only the range check before them sees it (the walk,
    # which starts from the vertices' halfedges, is switched off as above).
    mesh = _mesh(shapes.torus(120, 80))
    last = mesh.n_halfedge_slots - 1
    owner = int((mesh.halfedge_face if kind == "face" else mesh.halfedge_vertex)[last])
    (mesh.face_halfedge if kind == "face" else mesh.vertex_halfedge)[owner] = last + 1
    with mock.patch.object(validate_fast, "_fans_hold", lambda *args: True):
        assert not validate_fast.every_rule_holds(mesh)
    with pytest.raises(hx.MeshInvariantError) as caught:
        mesh.validate()
    assert (caught.value.rule, caught.value.element) == ("deleted-reference", (kind, owner))


def _face_dropped(mesh: hx.HalfedgeMesh, g: int, label: int) -> hx.HalfedgeMesh:
    """``mesh`` without face ``g``: the last face takes its number, and g's halfedges get
    face ``label`` (-1 makes a hole, whose corners then point at its boundary halfedges)."""
    last = mesh.n_face_slots - 1
    face = mesh.halfedge_face.copy()
    dropped = np.flatnonzero(face == g)
    face[face == last] = g
    face[dropped] = label
    face_halfedge = mesh.face_halfedge.copy()
    face_halfedge[g] = face_halfedge[last]
    vertex_halfedge = mesh.vertex_halfedge.copy()
    vertex_halfedge[mesh.halfedge_vertex[dropped]] = dropped
    return hx.HalfedgeMesh(HalfedgeArrays(
        positions=mesh.positions, vertex_halfedge=vertex_halfedge, halfedge_next=mesh.halfedge_next,
        halfedge_prev=mesh.halfedge_prev, halfedge_vertex=mesh.halfedge_vertex, halfedge_face=face,
        face_halfedge=face_halfedge[:last]))


@pytest.mark.parametrize("label", ["past the end", "-2"])
def test_a_triangle_whose_face_is_out_of_range_is_found_in_a_middle_block(label):
    # A triangle loop whose three halfedges carry face n_f (or -2) and no face points
    # at it: every rule but deleted-reference holds (with face -1 the mesh is a sound
    # torus with one hole). Its halfedges lie in a middle block, the rest of which is
    # closed: only the block's own range check sees it.
    torus = _mesh(shapes.torus(120, 80))
    size = validate_fast._BLOCK
    n_blocks = _several_blocks(torus.n_halfedge_slots, size)
    g = int(torus.halfedge_face[(n_blocks // 2) * size + size // 2])
    _face_dropped(torus, g, -1).validate()
    out_of_range = {"past the end": torus.n_face_slots - 1, "-2": -2}[label]   # n_f of the mesh with a face fewer
    mesh = _face_dropped(torus, g, out_of_range)
    h = int(np.argmax(mesh.halfedge_face == out_of_range))
    assert h // size == n_blocks // 2
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == ("deleted-reference", ("halfedge", h))


@pytest.mark.parametrize("end", ["first", "last"])
def test_a_vertex_renumbered_out_of_range_everywhere_is_found(end):
    # Every halfedge of the first (last) vertex gets vertex -1 (n_v): all rules between
    # halfedges still hold, and there is no range pass over origin. vertex-halfedge-origin
    # sees it (the vertex's halfedge no longer leaves it), before the walks, which
    # show every other origin to be in range.
    mesh = _mesh(shapes.torus(120, 80))
    v, renumbered = (0, -1) if end == "first" else (mesh.n_vertex_slots - 1, mesh.n_vertex_slots)
    leaving = np.flatnonzero(mesh.halfedge_vertex == v)
    mesh.halfedge_vertex[leaving] = renumbered
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == ("deleted-reference", ("halfedge", int(leaving[0])))


# ---- the fast path's fan walk and packed rows --------------------------------------------
# Faces cannot describe two edges between the same two vertices, so these meshes are
# written as faces whose edges carry names: two edges with different names are different
# edges even when they join the same vertices.

def _arrays_from_named_edges(n_vertices: int, faces, edge_names) -> HalfedgeArrays:
    """Halfedge arrays of polygons ``faces`` whose edge from corner k to k + 1 is ``edge_names[f][k]``.

    The numbering is the build's: edges in order of first use, the first use gets
    halfedge ``2e``, the second ``2e + 1``; an edge used once gets a boundary halfedge
    ``2e + 1``, linked to the boundary halfedge that leaves its end.
    """
    number: dict = {}
    halfedge_of_corner = []
    for names in edge_names:
        row = []
        for name in names:
            if name in number:
                row.append(2 * number[name] + 1)
            else:
                number[name] = len(number)
                row.append(2 * number[name])
        halfedge_of_corner.append(row)
    n_h = 2 * len(number)
    nxt, origin, face = np.full(n_h, -1), np.full(n_h, -1), np.full(n_h, -1)
    for f, (corners, row) in enumerate(zip(faces, halfedge_of_corner)):
        for k in range(len(corners)):
            origin[row[k]], face[row[k]], nxt[row[k]] = corners[k], f, row[(k + 1) % len(corners)]
    boundary = [h for h in range(1, n_h, 2) if face[h] < 0]
    for h in boundary:
        origin[h] = origin[nxt[h ^ 1]]
    leaving = {int(origin[h]): h for h in boundary}
    for h in boundary:
        nxt[h] = leaving[int(origin[h ^ 1])]                  # it ends where its twin starts
    vertex_he = np.array([min(np.flatnonzero(origin == v)) for v in range(n_vertices)])
    for v, h in leaving.items():
        vertex_he[v] = h
    return HalfedgeArrays(
        positions=np.zeros((n_vertices, 3)), vertex_halfedge=vertex_he, halfedge_next=nxt,
        halfedge_prev=np.argsort(nxt), halfedge_vertex=origin, halfedge_face=face,
        face_halfedge=np.array([row[0] for row in halfedge_of_corner]))


def _lune_sphere(k: int, path: int = 1, fan_from_pole: bool = True, open_face: bool = False) -> hx.HalfedgeMesh:
    """A sphere cut into ``k`` lunes by ``k`` edges between its poles 0 and 1 (k - 1 duplicates).

    Lune i lies between meridians i and i + 1 and holds a path of ``path`` vertices
    ``c_1 .. c_path``, all joined to pole 0: faces (0, 1, c_1) along meridian i,
    (0, c_j, c_j+1), and (1, 0, c_path) along meridian i + 1. The polygon left between
    pole 1 and the path is filled by a fan from pole 1 (which then meets every c_j too)
    or from c_1 (pole 1 keeps three edges per lune). Pole 0 has k * (path + 1) edges,
    and the meridians are path + 1 steps apart round it. ``open_face`` leaves out lune
    0's last face.
    """
    faces, names = [], []

    def add(face, meridian=None):
        faces.append(face)
        names.append(tuple(("meridian", meridian) if {a, b} == {0, 1} else frozenset((a, b))
                           for a, b in zip(face, face[1:] + face[:1])))

    for i in range(k):
        c = [2 + i * path + j for j in range(path)]            # c[0] .. c[path - 1]: the lune's path
        add((0, 1, c[0]), meridian=i)
        for j in range(path - 1):
            add((0, c[j], c[j + 1]))
        if not (open_face and i == 0):
            add((1, 0, c[-1]), meridian=(i + 1) % k)
        for j in range(path - 1):
            add((1, c[j + 1], c[j]) if fan_from_pole else (c[0], c[j + 1], c[j]) if j else (c[0], 1, c[-1]))
    return hx.HalfedgeMesh(_arrays_from_named_edges(2 + k * path, faces, names))


def test_named_edges_build_what_the_build_builds():
    # The helper above agrees with HalfedgeMesh.from_faces when every name is a vertex pair.
    for drawn in (shapes.octahedron(), shapes.grid(3, 2), shapes.torus(5, 4)):
        faces = np.asarray(drawn[1])
        names = [tuple(frozenset((int(a), int(b))) for a, b in zip(face, np.roll(face, -1))) for face in faces]
        by_hand = _arrays_from_named_edges(len(drawn[0]), faces, names)
        built = _mesh(drawn)
        for field in ("vertex_halfedge", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face", "face_halfedge"):
            assert np.array_equal(getattr(by_hand, field), getattr(built, field)), field


LUNE_SPHERES = {
    # Both poles of low degree: the walk compares their neighbours pairwise.
    "poles of degree 4": dict(k=2), "poles of degree 6": dict(k=3), "poles of degree 8": dict(k=4),
    # Both poles of degree 20, the meridians 10 steps apart: only the sort sees them.
    "poles of degree 20": dict(k=2, path=9),
    # Pole 0 of degree 20 (sorted), pole 1 of degree 6 (compared pairwise).
    "poles of degree 20 and 6": dict(k=2, path=9, fan_from_pole=False),
}


def _only_broken_rule(mesh: hx.HalfedgeMesh, check: str, rule: str, element) -> None:
    """``mesh`` breaks only the rule that ``validate_module.<check>`` checks: with that
    check switched off validate() passes; the fast path sees it; validate() names
    ``rule`` and ``element``."""
    with mock.patch.object(validate_module, check, lambda *args: None):
        mesh.validate()                                       # every other rule holds
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == (rule, element)


def _hand_built(nxt, origin, face, vertex_halfedge, face_halfedge) -> hx.HalfedgeMesh:
    """A mesh from hand-written halfedge arrays (prev is next's inverse), all points at 0."""
    nxt = np.array(nxt)
    arrays = HalfedgeArrays(
        positions=np.zeros((len(vertex_halfedge), 3)),
        vertex_halfedge=np.array(vertex_halfedge),
        halfedge_next=nxt,
        halfedge_prev=np.argsort(nxt),
        halfedge_vertex=np.array(origin),
        halfedge_face=np.array(face),
        face_halfedge=np.array(face_halfedge),
    )
    return hx.HalfedgeMesh(arrays)


@pytest.mark.parametrize("open_face", [False, True], ids=["closed", "open"])
@pytest.mark.parametrize("shape", sorted(LUNE_SPHERES))
def test_parallel_edges_between_vertices_of_any_degree_are_found(shape, open_face):
    mesh = _lune_sphere(**LUNE_SPHERES[shape], open_face=open_face)
    assert mesh.euler_characteristic == (1 if open_face else 2)
    assert (mesh.halfedge_face < 0).sum() == (3 if open_face else 0)
    _only_broken_rule(mesh, "_no_duplicate_edges", "duplicate-edge", ("edge", (0, 1)))


def test_a_boundary_that_turns_back_along_a_second_edge_is_found():
    # Triangles (0, 1, 2) and (1, 0, 2), each with its own edge between 0 and 1: a disk
    # whose boundary runs 0 -> 1 -> 0 along those two edges (halfedges 0 and 6 in the
    # faces, 1 and 7 the boundary); edges 1 and 2 join both faces to vertex 2. Every
    # vertex has one fan and at most one boundary halfedge, so only the two edges
    # between 0 and 1 are wrong, and round vertices 0 and 1 the walk meets them one step
    # apart, across the boundary: only the boundary check of the fast path sees them.
    digon_disk = _hand_built(nxt=[2, 7, 4, 6, 0, 3, 5, 1], origin=[0, 1, 1, 2, 2, 0, 1, 0],
                             face=[0, -1, 0, 1, 0, 1, 1, -1], vertex_halfedge=[7, 1, 4], face_halfedge=[0, 6])
    _only_broken_rule(digon_disk, "_no_duplicate_edges", "duplicate-edge", ("edge", (0, 1)))


def test_a_vertex_on_two_pieces_of_boundary_is_not_manifold():
    # Triangles (0, 1, 2) and (0, 3, 4), touching only at vertex 0. Halfedges 0 2 4 and
    # 6 8 10 are the faces, their odd twins the boundary. At vertex 0 the boundary goes
    # from one triangle to the other (1 -> 0 -> 4 and 3 -> 0 -> 2), so there is one
    # boundary loop and the walk round vertex 0 meets all four of its edges; but two
    # boundary halfedges (5 and 11) leave it: two fans.
    bowtie = _hand_built(nxt=[2, 11, 4, 1, 0, 3, 8, 5, 10, 7, 6, 9], origin=[0, 1, 1, 2, 2, 0, 0, 3, 3, 4, 4, 0],
                         face=[0, -1, 0, -1, 0, -1, 1, -1, 1, -1, 1, -1], vertex_halfedge=[5, 1, 3, 7, 9],
                         face_halfedge=[0, 6])
    assert validate_module.ring_lengths(bowtie.vertex_halfedge, bowtie.halfedge_prev).sum() == bowtie.n_halfedge_slots
    _only_broken_rule(bowtie, "_one_piece_of_boundary", "vertex-manifold", ("vertex", 0))
    for seed in (0, 2, 4):                                    # vertex 0 itself, or in the ring
        with pytest.raises(hx.MeshInvariantError, match="vertex 0 lies on two pieces of boundary"):
            bowtie.validate_around(vertices=[seed])


def test_from_faces_refuses_what_validate_calls_two_pieces_of_boundary():
    # The same promise at both ends: a bowtie is refused when built, and refused by
    # validate() when made by hand.
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [-1, 0, 0], [-1, -1, 0]], dtype=float)
    with pytest.raises(hx.MeshInputError, match="2 separate pieces of boundary"):
        hx.HalfedgeMesh.from_faces(vertices, [[0, 1, 2], [0, 3, 4]])


def test_an_edge_between_two_boundaries_with_no_face_is_found_by_the_fast_path():
    # Triangles (0, 1, 2) and (3, 4, 5) and a bare edge 6 between vertices 2 and 3 that
    # the boundary runs along both ways: edge-halfedge is the first rule broken.
    mesh = _hand_built(nxt=[2, 5, 4, 1, 0, 12, 8, 13, 10, 7, 6, 9, 11, 3],
                       origin=[0, 1, 1, 2, 2, 0, 3, 4, 4, 5, 5, 3, 2, 3],
                       face=[0, -1, 0, -1, 0, -1, 1, -1, 1, -1, 1, -1, -1, -1],
                       vertex_halfedge=[5, 1, 3, 11, 7, 9], face_halfedge=[0, 6])
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == ("edge-halfedge", ("edge", 6))


@pytest.mark.parametrize("packed", [False, True], ids=["gathers", "packed rows"])
@given(
    drawn=meshes(),
    field=st.sampled_from(sorted(ALL_POINTERS)),
    where=st.integers(0, 10**6),
    value=st.integers(0, 10**6),
)
def test_the_fast_path_agrees_with_the_rules_with_and_without_packed_rows(packed, drawn, field, where, value):
    # As above, with the fast path forced to read next(h) from separate arrays or from
    # rows of four (the layout it takes for meshes in random order).
    mesh = build(drawn)
    array = ALL_POINTERS[field](mesh)
    array[where % len(array)] = array[value % len(array)]
    with mock.patch.object(validate_fast, "_jumps_far", lambda nxt: packed):
        fast_broken = not validate_fast.every_rule_holds(mesh)
    with mock.patch.object(validate_fast, "every_rule_holds", lambda mesh: False):
        rules_broken = _raises(mesh.validate)
    assert fast_broken == rules_broken


def test_meshes_in_random_order_take_the_packed_rows():
    # Large enough that a pointer to a random halfedge usually jumps _FAR or more.
    vertices, faces = shapes.torus(400, 250)                 # 600,000 halfedges
    assert not validate_fast._jumps_far(_mesh((vertices, faces)).halfedge_next)
    shuffled = _mesh((vertices, faces[np.random.default_rng(0).permutation(len(faces))]))
    assert validate_fast._jumps_far(shuffled.halfedge_next)
    assert validate_fast.every_rule_holds(shuffled)


@pytest.mark.parametrize("block", ["first", "middle", "last"])
def test_a_vertex_sharing_a_neighbours_halfedge_is_found_anywhere(block):
    # A vertex at the start, in the middle or at the end of the numbering points at its
    # neighbour's halfedge; the fast path checks every vertex before the fan walks.
    mesh = _mesh(shapes.torus(200, 120))                     # 24,000 vertices
    size = validate_fast._VERTEX_BLOCK
    n_blocks = _several_blocks(mesh.n_vertex_slots, size)
    v = {"first": 0, "middle": (n_blocks // 2) * size + 7, "last": mesh.n_vertex_slots - 1}[block]
    neighbour = int(mesh.halfedge_vertex[int(mesh.vertex_halfedge[v]) ^ 1])
    mesh.vertex_halfedge[v] = mesh.vertex_halfedge[neighbour]
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == ("vertex-halfedge-origin", ("vertex", v))


def _joined(*meshes: hx.HalfedgeMesh) -> hx.HalfedgeMesh:
    """One mesh holding ``meshes`` side by side, in that order: each one's elements come
    after the previous ones' (its indices shifted by their counts)."""
    parts: dict[str, list] = {field: [] for field in (
        "positions", "vertex_halfedge", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face",
        "face_halfedge")}
    n_v = n_h = n_f = 0
    for mesh in meshes:
        parts["positions"].append(mesh.positions)
        for field in ("vertex_halfedge", "halfedge_next", "halfedge_prev", "face_halfedge"):
            parts[field].append(getattr(mesh, field) + n_h)
        parts["halfedge_vertex"].append(mesh.halfedge_vertex + n_v)
        parts["halfedge_face"].append(np.where(mesh.halfedge_face >= 0, mesh.halfedge_face + n_f, -1))
        n_v, n_h, n_f = n_v + mesh.n_vertex_slots, n_h + mesh.n_halfedge_slots, n_f + mesh.n_face_slots
    return hx.HalfedgeMesh(HalfedgeArrays(**{field: np.concatenate(arrays) for field, arrays in parts.items()}))


@pytest.mark.parametrize("poles", ["poles of degree 6", "poles of degree 20"])
@pytest.mark.parametrize("block", ["first", "middle", "last"])
def test_the_fan_walk_checks_every_block_of_walks(block, poles):
    # The walks go _VERTEX_BLOCK at a time, in the order of the vertices' halfedges. A
    # sphere whose poles are joined by parallel edges (which only the walk sees; its
    # poles compared pairwise, or sorted) comes first, in the middle or last of a mesh
    # of several blocks, so that its poles' walks fall in that block.
    sphere = _lune_sphere(**LUNE_SPHERES[poles])
    torus = _mesh(shapes.torus(12, 8))                       # 96 vertices
    pieces = {"first": (sphere, torus, torus), "middle": (torus, sphere, torus), "last": (torus, torus, sphere)}
    mesh = _joined(*pieces[block])
    pole = pieces[block].index(sphere) * torus.n_vertex_slots  # the sphere's vertex 0
    size = 48
    with mock.patch.object(validate_fast, "_VERTEX_BLOCK", size):
        n_blocks = _several_blocks(mesh.n_vertex_slots, size)
        walk = int(np.searchsorted(np.sort(mesh.vertex_halfedge), mesh.vertex_halfedge[pole]))
        assert walk // size == {"first": 0, "middle": n_blocks // 2, "last": n_blocks - 1}[block]
        assert not validate_fast.every_rule_holds(mesh)
        with pytest.raises(hx.MeshInvariantError) as caught:
            mesh.validate()
    assert (caught.value.rule, caught.value.element) == ("duplicate-edge", ("edge", (pole, pole + 1)))


def test_a_face_of_one_halfedge_on_a_loop_edge_fails_the_fast_path():
    # Vertices 0 and 1; a loop edge at each (halfedges 0 1 at vertex 0, 6 7 at vertex 1)
    # and two edges between them (2 3 and 4 5). Triangles (0, 2, 4) and (3, 5, 6), and
    # halfedges 1 and 7 each a face of its own: next(h) == h. Every pointer rule the fast
    # path reads at next(h) holds for such a face (prev(h) == h == next(next(h)), and h
    # ends where it starts), and the walks round both vertices meet all four of their
    # edges with no neighbour twice but for steps next to each other, which the walk does
    # not compare: only twin-involution (halfedges 0 and 1 both start at vertex 0) is
    # left to refuse it, so the fast path must check it itself.
    mesh = _hand_built(nxt=[2, 1, 4, 5, 0, 6, 3, 7], origin=[0, 0, 0, 1, 1, 0, 1, 1],
                       face=[0, 2, 0, 1, 0, 1, 1, 3], vertex_halfedge=[0, 6], face_halfedge=[0, 3, 1, 7])
    assert mesh.euler_characteristic == 2
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == ("twin-involution", ("halfedge", 0))


@pytest.mark.parametrize("open_box", [False, True], ids=["closed cube", "open box"])
def test_a_mesh_of_quads_fails_the_fast_path(open_box):
    # A cube of six quads (or five: a box without its lid), written as halfedges: every
    # rule holds but next-cycle's "a loop of three"; the fast path has a branch for
    # closed meshes and one for meshes with boundary.
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    if open_box:
        del quads[1]
    names = [tuple(frozenset(pair) for pair in zip(quad, quad[1:] + quad[:1])) for quad in quads]
    mesh = hx.HalfedgeMesh(_arrays_from_named_edges(8, quads, names))
    assert mesh.euler_characteristic == (1 if open_box else 2)
    found = refused_by_fast_path_and_named(mesh)
    assert (found.rule, found.element) == ("next-cycle", ("halfedge", 0))


def test_arrays_given_as_strided_views_validate():
    # The fast path reads pairs of int32 as 64-bit words, which needs contiguous memory.
    built = _mesh(shapes.torus(6, 4))
    fields = ("vertex_halfedge", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face", "face_halfedge")
    strided = {field: np.repeat(getattr(built, field), 2)[::2] for field in fields}
    assert not strided["halfedge_next"].flags.c_contiguous
    mesh = hx.HalfedgeMesh(HalfedgeArrays(positions=built.positions.copy(), **strided))
    assert validate_fast.every_rule_holds(mesh)
    mesh.validate()


def test_the_tests_the_fast_pass_names_as_its_pins_exist():
    # validate_fast's docstring names the tests that pin it to the rules; a renamed or
    # removed test must not leave it citing one that is gone.
    named = set(re.findall(r"``(test_\w+)``", validate_fast.__doc__))
    assert len(named) >= 8
    assert named <= {name for name in globals() if name.startswith("test_")}
