"""Checks for the exercises of chapters 02 and 03: ``check_build`` and ``check_one_ring``.

A learner writes one function; the check runs it on a handful of small meshes, compares
the answer with the package's reference, and stops at the *first* difference, which it
explains in a sentence that names the mesh, the face or vertex, and the halfedge::

    from halfedge_edu.exercises import check_build
    result = check_build(build)      # prints nothing; the notebook shows repr(result)
    result                           # "Not yet. On 'two triangles' ..." or a congratulation
    result.show()                    # a picture of the offending element (needs pyvista)

The contracts (also stated in the chapters):

* ``build(faces) -> dict`` with one entry per halfedge under each of the keys
  ``"vertex"`` (the vertex the halfedge leaves), ``"face"`` (its face, -1 on the
  boundary) and ``"next"``; optionally ``"prev"`` and ``"vertex_halfedge"`` (one entry per
  vertex), and ``"twin"`` when the twin is not ``h ^ 1``. Any numbering passes: the
  check judges by invariants (each face's three halfedges go round it by ``next`` in the
  row's order, twins pair up and run the other way, boundary halfedges chain along the
  boundary), so the same mesh is accepted whatever the halfedge ids. Two layouts the
  courses use: this package's (see ``halfedge_edu.core.build``; edge ``e`` owns ``2e``,
  its first sighting, and ``2e + 1``, its twin ``h ^ 1``, boundary halfedges included,
  ``"twin"`` not returned), and UChicago's (three halfedges per face, ``3f``, ``3f + 1``,
  ``3f + 2``, twins found afterwards and returned as ``"twin"``, ``-1`` or ``None`` on a
  side with no neighbour, because that course has no boundary halfedges). A vertex's
  halfedge may be any outgoing one (UChicago keeps the last one set), except that with
  boundary halfedges a boundary vertex keeps its boundary one, so ``v.halfedge.face is
  None`` says at once that ``v`` is on the boundary.
* ``one_ring(mesh, v) -> list`` of the neighbours of vertex ``v`` (given as a
  :class:`~halfedge_edu.Vertex` handle, which also works wherever an index does),
  starting with the tip of ``v.halfedge``, counter-clockwise (the chapter's walk) or
  clockwise (CMU's ``h.twin.next``; the congratulation then says why the chapter turns
  the other way). Vertex handles or ints.

A learner's function runs in :func:`~halfedge_edu.exercises.harness.run`, which stops
one that loops forever after ``TIME_LIMIT`` seconds where the platform allows it.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from halfedge_edu.core.build import build_reference
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.data import sample

from . import harness, hidden
from .harness import TIME_LIMIT, CheckResult

__all__ = ["check_build", "check_one_ring", "build_cases", "one_ring_cases"]


# --------------------------------------------------------------------------------------
# Words for a learner's function that raised or is not finished
# --------------------------------------------------------------------------------------

def _describe_error(name: str, error: Exception) -> str:
    if isinstance(error, NotImplementedError) or "ellipsis" in str(error).lower():
        return (f"{name} is not finished yet (it raised {type(error).__name__}: {error}). "
                f"Fill in the blanks marked ... and run the check again.")
    return f"your {name} raised {type(error).__name__}: {error}.{harness.own_line(error)}"


def _has_ellipsis(value) -> bool:
    if value is Ellipsis:
        return True
    if isinstance(value, (list, tuple)):
        return any(item is Ellipsis for item in value)
    return False


# --------------------------------------------------------------------------------------
# check_build
# --------------------------------------------------------------------------------------

def _shuffled(vertices, faces, seed: int):
    """The same surface with its vertices renumbered, faces reordered and each face's
    starting corner rotated (orientation kept)."""
    rng = np.random.default_rng(seed)
    vertices, faces = np.asarray(vertices, dtype=np.float64), np.asarray(faces, dtype=np.int64)
    new_number = rng.permutation(len(vertices))               # old vertex -> new
    new_vertices = np.empty_like(vertices)
    new_vertices[new_number] = vertices
    rotated = np.array([np.roll(face, -int(k)) for face, k in zip(faces, rng.integers(0, 3, len(faces)))])
    return new_vertices, new_number[rotated][rng.permutation(len(faces))]


def _annulus():
    """A square ring of 8 triangles around a square hole: two boundary loops."""
    outer = [[0, 0, 0], [3, 0, 0], [3, 3, 0], [0, 3, 0]]
    inner = [[1, 1, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0]]
    faces = []
    for s in range(4):
        o0, o1, i0, i1 = s, (s + 1) % 4, 4 + s, 4 + (s + 1) % 4
        faces += [[o0, o1, i1], [o0, i1, i0]]
    return outer + inner, faces


def build_cases(seed: int | None = None) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """The meshes ``check_build`` uses, in order: ``(name, vertices, faces)``.

    Small and open first (where mistakes are easy to read), then closed, several
    boundary loops, and a shuffled numbering. With a ``seed``, the hidden cases instead:
    a jittered grid, a closed mesh and a second grid, each renumbered at random.
    """
    if seed is not None:
        rng = harness.hidden_rng(seed)
        rows, columns = rng.integers(1, 4, 2)
        shape = str(rng.choice(list(hidden.CLOSED_SHAPES)))
        other_rows, other_columns = rng.integers(2, 5, 2)
        hidden_cases = [
            (f"a {rows} x {columns} grid patch, renumbered at random", *hidden.renumbered(*hidden.grid(rows, columns, rng), rng)),
            (f"{shape}, renumbered at random", *hidden.renumbered(*hidden.closed_mesh(shape).to_arrays(), rng)),
            (f"a {other_rows} x {other_columns} grid patch", *hidden.grid(other_rows, other_columns, rng)),
        ]
        return [(harness.hidden_name(k, name), v, f) for k, (name, v, f) in enumerate(hidden_cases, start=1)]
    cases = [("two triangles", [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]])]
    for name in ("lone_triangle", "strip", "tetrahedron", "cube", "open_patch"):
        cases.append((name.replace("_", " "), *sample(name).to_arrays()))
    cases.append(("annulus (two boundary loops)", *_annulus()))
    cases.append(("open patch, shuffled", *_shuffled(*sample("open_patch").to_arrays(), seed=7)))
    cases.append(("octahedron, shuffled", *_shuffled(*sample("octahedron").to_arrays(), seed=3)))
    return [(name, np.asarray(v, dtype=np.float64), np.asarray(f, dtype=np.int64)) for name, v, f in cases]


_BUILD_KEYS = ("vertex", "face", "next")
_OPTIONAL_BUILD_KEYS = ("prev", "vertex_halfedge", "twin")


def _as_index_array(value) -> np.ndarray | None:
    """An int array of the learner's list, dict {h: value} or array; None if it is not one."""
    if isinstance(value, dict):
        keys = sorted(value)
        if keys != list(range(len(keys))):
            return None
        value = [value[k] for k in keys]
    try:
        array = np.asarray(value)
    except Exception:
        return None
    if array.ndim != 1 or not (array.size == 0 or np.issubdtype(array.dtype, np.integer)):
        return None
    return array.astype(np.int64)


class _BuildStory:
    """Words for the reference halfedges of one mesh (what each one is and why)."""

    def __init__(self, faces: np.ndarray, reference):
        self.faces = faces
        self.ref = reference
        self.origin = reference.halfedge_vertex.astype(np.int64)
        self.face = reference.halfedge_face.astype(np.int64)

    def run(self, h: int) -> str:
        return f"{self.origin[h]} -> {self.origin[h ^ 1]}"

    def face_text(self, f: int) -> str:
        return f"face {f} = {self.faces[f].tolist()}"

    def what(self, h: int) -> str:
        """Why halfedge h is what it is, in the course's numbering."""
        f = int(self.face[h])
        if f < 0:
            return (f"halfedge {h} is a boundary halfedge: the twin of halfedge {h ^ 1} ({self.run(h ^ 1)}, in "
                    f"{self.face_text(int(self.face[h ^ 1]))}), which no other face shares")
        if h % 2 == 0:
            return f"halfedge {h} is made by {self.face_text(f)}, the first time edge {h >> 1} is seen"
        return (f"halfedge {h} is made by {self.face_text(f)}, the second time edge {h >> 1} is seen, "
                f"so it is the twin of halfedge {h ^ 1} ({self.run(h ^ 1)})")


def _learner_run(vertex: np.ndarray, h: int) -> str:
    tip = vertex[h ^ 1] if (h ^ 1) < len(vertex) else "?"
    return f"{vertex[h]} -> {tip}"


def _answer_arrays(answer) -> tuple[dict[str, np.ndarray] | None, str | None]:
    """The learner's dict as int arrays, or (None, what is wrong with it)."""
    if not isinstance(answer, dict):
        return None, (f"build(faces) should return a dict with the keys 'vertex', 'face' and 'next' "
                      f"(one entry per halfedge each), but yours returned {type(answer).__name__} {answer!r:.60}.")
    missing = [key for key in _BUILD_KEYS if key not in answer]
    if missing:
        return None, (f"the dict your build returns has no {', '.join(repr(k) for k in missing)}; it needs "
                      f"'vertex', 'face' and 'next' (one entry per halfedge each).")
    arrays = {}
    for key in _BUILD_KEYS + _OPTIONAL_BUILD_KEYS:
        if key not in answer:
            continue
        if _has_ellipsis(answer[key]):
            return None, (f"your {key!r} still contains a blank (...): build is not finished yet. "
                          f"Fill in the blanks and run the check again.")
        value = answer[key]
        if key == "twin":  # UChicago's twin is None where a face's side has no neighbour
            value = ({h: -1 if t is None else t for h, t in value.items()} if isinstance(value, dict)
                     else [-1 if t is None else t for t in value])
        array = _as_index_array(value)
        if array is None:
            return None, (f"your {key!r} should be a list of whole numbers, one per "
                          f"{'vertex' if key == 'vertex_halfedge' else 'halfedge'}, but it is {answer[key]!r:.80}.")
        arrays[key] = array
    return arrays, None


def _compare_build(answer, faces: np.ndarray, n_vertices: int) -> tuple[str, tuple | None] | None:
    """None if ``answer`` is a correct build of ``faces`` in any course's numbering; else
    (words, element).

    Judged by invariants (:func:`_judge_structure`), so a correct build in another
    numbering passes. When it fails and the answer is laid out as this package's (no
    ``"twin"``: twin is ``h ^ 1``), the words compare it with the package's reference,
    which names the exact halfedge; otherwise they name the broken invariant.
    """
    arrays, reason = _answer_arrays(answer)
    if arrays is None:
        return reason, None
    if "vertex_halfedge" in arrays and len(arrays["vertex_halfedge"]) != n_vertices:
        return (f"there are {n_vertices} vertices, so 'vertex_halfedge' should have {n_vertices} "
                f"entries, but yours has {len(arrays['vertex_halfedge'])}.", None)
    problem = _judge_structure(arrays, faces, n_vertices)
    if problem is None or "twin" in arrays:
        return problem
    return _reference_problem(arrays, faces, n_vertices) or problem


def _reference_problem(arrays: dict[str, np.ndarray], faces: np.ndarray,
                       n_vertices: int) -> tuple[str, tuple | None] | None:
    """The first difference from the package's own numbering (twin = h ^ 1), in words."""
    reference = build_reference(faces, n_vertices)
    story = _BuildStory(faces, reference)
    n_halfedges = len(reference.halfedge_next)
    n_edges = n_halfedges // 2
    for key, array in arrays.items():
        if key != "vertex_halfedge" and len(array) != n_halfedges:
            hint = ""
            if len(array) == 3 * len(faces) and len(array) < n_halfedges:
                hint = (" You have three per face: the boundary halfedges are missing. Every edge that only one "
                        "face uses still gets a second halfedge, running the other way, with face -1. (Three "
                        "per face with no boundary halfedges, as UChicago's build allocates them, is fine too "
                        "if you also return 'twin', -1 where a side has no neighbour.)")
            elif len(array) == 3 * len(faces):
                hint = (" You have three per face, which is too many here: a shared edge's second sighting is "
                        "not a new halfedge, it is the twin 2e + 1 of the first.")
            return (f"{len(faces)} faces with {n_edges} edges make {n_halfedges} halfedges (two per edge, "
                    f"boundary ones included), but your {key!r} has {len(array)} entries.{hint}", None)

    vertex = arrays["vertex"]
    for h in range(n_halfedges):
        if vertex[h] != story.origin[h] or vertex[h ^ 1] != story.origin[h ^ 1]:
            if not (vertex[h] == story.origin[h ^ 1] and vertex[h ^ 1] == story.origin[h]):
                return None  # another numbering: the broken invariant says more than the difference
            return (f"{story.what(h)}. It should run {story.run(h)}, but yours runs {_learner_run(vertex, h)}. "
                    f"It points the wrong way: the first sighting of an edge gets the even number 2e and "
                    f"runs the way that face uses it; the second sighting is the odd twin 2e + 1.", ("halfedge", h))

    face = arrays["face"]
    for h in range(n_halfedges):
        if face[h] != story.face[h]:
            if story.face[h] < 0:
                text = (f"halfedge {h} ({story.run(h)}) is a boundary halfedge: no face lies on its side, so its "
                        f"face should be -1, but yours says {face[h]}.")
            else:
                text = (f"halfedge {h} ({story.run(h)}) belongs to {story.face_text(int(story.face[h]))}, "
                        f"but your face says {face[h]}.")
            return text, ("halfedge", h)

    next_ = arrays["next"]
    for h in range(n_halfedges):
        want, got = int(reference.halfedge_next[h]), int(next_[h])
        if got == want:
            continue
        got_text = f"{got} ({story.run(got)})" if 0 <= got < n_halfedges else f"{got}, which is not a halfedge"
        if story.face[h] >= 0:
            text = (f"halfedge {h} ({story.run(h)}) is in {story.face_text(int(story.face[h]))}; its next should "
                    f"be halfedge {want} ({story.run(want)}), the next side of the same triangle, "
                    f"counter-clockwise, but yours is {got_text}.")
        else:
            text = (f"halfedge {h} ({story.run(h)}) runs along the boundary; its next should be the boundary "
                    f"halfedge that leaves vertex {story.origin[h ^ 1]}, halfedge {want} ({story.run(want)}), "
                    f"but yours is {got_text}.")
            if not 0 <= got < n_halfedges or story.origin[got] != story.origin[h ^ 1]:
                text += f" A next must start where its halfedge ends, at vertex {story.origin[h ^ 1]}."
            elif story.face[got] >= 0:
                text += " That one is inside a face; a boundary halfedge's next runs along the boundary too."
        return text, ("halfedge", h)

    if "prev" in arrays:
        prev = arrays["prev"]
        for h in range(n_halfedges):
            want = int(reference.halfedge_prev[h])
            if prev[h] != want:
                return (f"the prev of halfedge {h} ({story.run(h)}) should be halfedge {want} ({story.run(want)}), "
                        f"the one whose next is {h}, but yours is {prev[h]}.", ("halfedge", h))

    if "vertex_halfedge" in arrays:
        vertex_halfedge = arrays["vertex_halfedge"]
        for v in range(n_vertices):
            want = int(reference.vertex_halfedge[v])
            if vertex_halfedge[v] == want:
                continue
            got = int(vertex_halfedge[v])
            if story.face[want] < 0:
                rule = f"vertex {v} is on the boundary, so its halfedge must be its outgoing boundary halfedge"
            else:
                rule = f"vertex {v} is inside, and the course picks its outgoing halfedge with the smallest number"
            got_text = f"{got} ({story.run(got)})" if 0 <= got < n_halfedges else str(got)
            return (f"{rule}, {want} ({story.run(want)}), but yours is {got_text}.", ("vertex", v))
    return None



# --------------------------------------------------------------------------------------
# check_build: any numbering (relabel-invariant judge)
# --------------------------------------------------------------------------------------

def _judge_structure(arrays: dict[str, np.ndarray], faces: np.ndarray,
                     n_vertices: int) -> tuple[str, tuple | None] | None:
    """None if ``arrays`` is *a* correct halfedge structure of ``faces``, in any numbering.

    Judged by invariants only, so every course's numbering passes: this package's (edge
    ``e`` owns ``2e`` and ``2e + 1``, boundary halfedges included, ``twin`` not returned
    because it is ``h ^ 1``) and UChicago's (three halfedges per face, ``3f``, ``3f + 1``,
    ``3f + 2`` for (i, j), (j, k), (k, i), twins found afterwards and returned as
    ``"twin"``, -1 where a face's side has no neighbour: that course has no boundary
    halfedges). Faces keep their row numbers in every course, so a halfedge's face is
    compared with the row. The offending element is named in the *package's* numbering
    (a face or a vertex), which is the same in every convention.
    """
    vertex, face, next_ = arrays["vertex"], arrays["face"], arrays["next"]
    n_halfedges = len(vertex)
    for key in ("face", "next") + tuple(k for k in ("prev", "twin") if k in arrays):
        if len(arrays[key]) != n_halfedges:
            return (f"your 'vertex' has {n_halfedges} entries but your {key!r} has {len(arrays[key])}: "
                    f"every halfedge needs one entry in each.", None)
    if "twin" in arrays:
        twin = arrays["twin"]
    elif n_halfedges % 2:
        return (f"you return {n_halfedges} halfedges and no 'twin', so the twin would be h ^ 1, which needs an "
                f"even count. Return 'twin' too if your halfedges are not paired that way (three per face, as "
                f"in the UChicago build, is fine with a 'twin' list).", None)
    else:
        twin = np.arange(n_halfedges) ^ 1

    for h in range(n_halfedges):
        if not 0 <= vertex[h] < n_vertices:
            return f"halfedge {h} leaves vertex {vertex[h]}, but the vertices are 0 to {n_vertices - 1}.", None
        if not 0 <= next_[h] < n_halfedges:
            return f"the next of halfedge {h} is {next_[h]}, which is not one of your halfedges.", None
        if not -1 <= twin[h] < n_halfedges:
            return f"the twin of halfedge {h} is {twin[h]}, which is not one of your halfedges (or -1).", None
        if not -1 <= face[h] < len(faces):
            return f"halfedge {h} says its face is {face[h]}, but the faces are 0 to {len(faces) - 1}.", None

    def run(h: int) -> str:  # meaningful once every face's next is right (checked first)
        return f"{vertex[h]} -> {vertex[next_[h]]}"

    for f, corners in enumerate(faces.tolist()):
        mine = np.flatnonzero(face == f)
        words = f"face {f} = {corners}"
        if len(mine) != 3:
            return (f"{words} is a triangle, so three halfedges should say face {f}, but {len(mine)} of yours "
                    f"do ({mine.tolist()}).", ("face", f))
        origins = sorted(int(vertex[g]) for g in mine)
        if origins != sorted(corners):
            return (f"{words}: its three halfedges should leave its corners {corners[0]}, {corners[1]} and "
                    f"{corners[2]}, one each, but yours ({mine.tolist()}) leave {origins}.", ("face", f))
        for g in mine.tolist():
            a = int(vertex[g])
            after = corners[(corners.index(a) + 1) % 3]
            n = int(next_[g])
            if face[n] != f or vertex[n] != after:
                leaves = f"leaves vertex {vertex[n]}" + ("" if face[n] == f else f" in face {face[n]}")
                hint = (" That is the corner before, not after: next goes round the face in the row's order "
                        "(counter-clockwise)." if face[n] == f else "")
                return (f"{words}: halfedge {g} leaves vertex {a}, so its next should be the halfedge of this face "
                        f"that leaves vertex {after}, the next corner in the row, but your next, {n}, "
                        f"{leaves}.{hint}", ("face", f))

    uses: dict[tuple[int, int], list[int]] = {}
    for f, corners in enumerate(faces.tolist()):
        for c in range(3):
            a, b = corners[c], corners[(c + 1) % 3]
            uses.setdefault((min(a, b), max(a, b)), []).append(f)
    has_boundary_halfedges = bool(np.any(face < 0))
    for h in range(n_halfedges):
        t = int(twin[h])
        a, b = int(vertex[h]), int(vertex[next_[h]])
        key = (min(a, b), max(a, b))
        if t < 0:
            if face[h] < 0 or len(uses[key]) > 1 or has_boundary_halfedges:
                where = ("faces " + " and ".join(str(g) for g in uses[key]) + " share that edge"
                         if len(uses[key]) > 1 else "with boundary halfedges, every halfedge has a twin")
                pointing = np.flatnonzero(twin == h)
                hint = (f" Your halfedge {int(pointing[0])} has {h} as its twin: set the pair both ways, when "
                        f"the second sighting finds the first." if len(pointing) else "")
                return (f"halfedge {h} ({run(h)}) has no twin (-1), but {where}.{hint}", ("vertex", a))
            continue
        if twin[t] != h or t == h:
            return (f"the twin of halfedge {h} ({run(h)}) is {t}, but the twin of {t} is {twin[t]}: twins come in "
                    f"pairs, each the twin of the other.", ("vertex", a))
        if (int(vertex[t]), int(vertex[next_[t]])) != (b, a):
            return (f"halfedge {h} runs {run(h)}, so its twin should run {b} -> {a}, but your twin {t} runs "
                    f"{run(t)}.", ("vertex", a))
    for h in np.flatnonzero(face < 0).tolist():
        g = int(next_[h])
        if face[g] >= 0:
            return (f"halfedge {h} ({run(h)}) runs along the boundary (face -1); its next should be the boundary "
                    f"halfedge leaving vertex {vertex[g]}, but yours, {g}, is inside face {face[g]}.",
                    ("vertex", int(vertex[g])))
    n_edges = len(uses)
    n_boundary_edges = sum(1 for faces_of in uses.values() if len(faces_of) == 1)
    if has_boundary_halfedges and n_halfedges != 2 * n_edges:
        return (f"{len(faces)} faces with {n_edges} edges make {2 * n_edges} halfedges with the boundary ones, but "
                f"you have {n_halfedges}.", None)
    if not has_boundary_halfedges and n_halfedges != 3 * len(faces):
        hint = (f" The {n_boundary_edges} boundary edges each need a halfedge with face -1, or none at all "
                f"(then return 'twin', -1 where a side has no neighbour)." if n_boundary_edges else "")
        return (f"{len(faces)} faces make {3 * len(faces)} halfedges, but you have {n_halfedges}.{hint}", None)

    if "prev" in arrays:
        prev = arrays["prev"]
        for h in range(n_halfedges):
            if not 0 <= prev[h] < n_halfedges or next_[prev[h]] != h:
                return (f"the prev of halfedge {h} ({run(h)}) should be the halfedge whose next is {h}, but yours "
                        f"is {prev[h]}.", ("vertex", int(vertex[h])))
    if "vertex_halfedge" in arrays:
        vertex_halfedge = arrays["vertex_halfedge"]
        for v in range(n_vertices):
            got = int(vertex_halfedge[v])
            got_text = f"{got} ({run(got)})" if 0 <= got < n_halfedges else str(got)
            if not 0 <= got < n_halfedges or vertex[got] != v:
                return (f"vertex {v}'s halfedge should leave vertex {v}, but yours is {got_text}.", ("vertex", v))
            # With boundary halfedges, a boundary vertex keeps its boundary one, so that
            # `v.halfedge.face is None` says at once that v is on the boundary and a walk from
            # it goes round the fan in one piece. Without them (UChicago) any outgoing one is fine.
            on_boundary = np.flatnonzero((face < 0) & (vertex == v))
            if has_boundary_halfedges and len(on_boundary) and face[got] >= 0:
                wanted = int(on_boundary[0])
                return (f"vertex {v} is on the boundary, so its halfedge must be its outgoing boundary halfedge, "
                        f"{wanted} ({run(wanted)}), but yours is {got_text} (with boundary halfedges, "
                        f"`v.halfedge.face is None` then says at once that v is on the boundary).",
                        ("vertex", v))
    return None


def check_build(learner_build: Callable, *, seed: int | None = None) -> CheckResult:
    """Run ``learner_build(faces)`` on several meshes and compare with ``build_reference``.

    Args:
        learner_build: a function ``faces -> dict`` with lists ``"vertex"``, ``"face"``,
            ``"next"`` (one entry per halfedge, any numbering) and optionally ``"prev"``,
            ``"vertex_halfedge"`` and ``"twin"`` (without it the twin is ``h ^ 1``).
            ``faces`` is an (m, 3) int array; rows are triangles counter-clockwise.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it (see :mod:`halfedge_edu.exercises.hidden`).

    Returns:
        A :class:`CheckResult`: on the first difference, what it is in words and which
        halfedge (``result.show()`` draws it); otherwise a short congratulation.
    """
    cases = build_cases(seed)
    unfinished = harness.unfinished(learner_build, "build")
    if unfinished:
        return harness.counted(harness.failed("build", [], None, unfinished), len(cases))
    return harness.counted(_check_build(learner_build, cases), len(cases))


def _check_build(learner_build: Callable, cases: list[tuple[str, np.ndarray, np.ndarray]]) -> CheckResult:
    """:func:`check_build` on the given cases."""
    checked: list[str] = []
    for name, vertices, faces in cases:
        status, answer = harness.run(learner_build, faces.copy())
        mesh = HalfedgeMesh.from_faces(vertices, faces)
        intro = f"faces {faces.tolist()}: " if len(faces) <= 4 else ""
        if status == "timeout":
            return harness.failed("build", checked, name, f"{intro}your build did not finish within {TIME_LIMIT:g} s. "
                           "A loop probably never ends: check the walks that should come back to their start.",
                           None, mesh)
        if status == "error":
            return harness.failed("build", checked, name, intro + _describe_error("build", answer), None, mesh,
                                      error=answer)
        problem = _compare_build(answer, faces, len(vertices))
        if problem is not None:
            text, element = problem
            return harness.failed("build", checked, name, intro + text, element, mesh)
        checked.append(name)
    return CheckResult("build", True, f"All good! Your build makes a correct halfedge structure on {len(checked)} "
                       f"meshes ({', '.join(checked)}): each face goes round by next, twins pair up, and every "
                       f"edge is there, whatever numbering you chose.", list(checked))


# --------------------------------------------------------------------------------------
# check_one_ring
# --------------------------------------------------------------------------------------

def one_ring_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh]]:
    """The meshes ``check_one_ring`` walks around, every vertex of each, in order.

    A flat patch comes first: its pictures are the easiest to read, and it has corner,
    rim and interior vertices. With a ``seed``, the hidden cases instead: a renumbered
    grid patch, a closed mesh after random flips (degrees from 3 up), and another grid.
    """
    if seed is not None:
        rng = harness.hidden_rng(seed)
        rows, columns = rng.integers(2, 4, 2)
        shape = str(rng.choice(["cube", "octahedron", "icosphere(1)", "icosphere(2)"]))
        flips = int(rng.integers(4, 12))
        hidden_cases = [
            (f"a {rows} x {columns} grid patch, renumbered at random",
             HalfedgeMesh.from_faces(*hidden.renumbered(*hidden.grid(rows, columns, rng), rng))),
            (f"{shape} after {flips} random flips", hidden.flipped(hidden.closed_mesh(shape), flips, rng)),
            ("a 1 x 3 grid patch (every vertex on the boundary)", HalfedgeMesh.from_faces(*hidden.grid(1, 3, rng))),
        ]
        return [(harness.hidden_name(k, name), mesh) for k, (name, mesh) in enumerate(hidden_cases, start=1)]
    cases = [(name.replace("_", " "), sample(name)) for name in ("open_patch", "strip", "tetrahedron", "cube",
                                                               "single_collapse")]
    cases.append(("octahedron, shuffled", HalfedgeMesh.from_faces(*_shuffled(*sample("octahedron").to_arrays(), 3))))
    cases.append(("annulus (two boundary loops)", HalfedgeMesh.from_faces(*_annulus())))
    return cases


def _ring_as_ints(answer) -> tuple[list[int] | None, str | None]:
    """The learner's ring as a list of ints, or (None, reason)."""
    from halfedge_edu.core.elements import Halfedge

    if answer is None:
        return None, "your one_ring returned None; it should return the list of neighbours (did you forget `return`?)."
    if _has_ellipsis(answer):
        return None, "your ring still contains a blank (...): one_ring is not finished yet. Fill in the blanks."
    try:
        items = list(answer)
    except TypeError:
        return None, f"one_ring should return a list of vertex indices, but yours returned {answer!r:.60}."
    if any(isinstance(item, Halfedge) for item in items):
        return None, ("your ring contains halfedges; it should contain vertices: the neighbour a halfedge "
                      "points to is its tip, h.tip.")
    try:
        return [int(item) for item in items], None
    except (TypeError, ValueError):
        return None, f"one_ring should return vertex indices (or Vertex handles), but yours returned {items!r:.80}."


def _is_clockwise(want: list[int], ring: list[int]) -> bool:
    """Whether ``ring`` is ``want`` walked the other way round from the same start (the CMU
    notes' ``h = h.twin.next`` walk), on a vertex with at least three neighbours (with
    fewer, both ways round are the same list)."""
    return len(want) > 2 and ring == want[:1] + want[1:][::-1]


def _is_run_of(ring: list[int], want: list[int]) -> bool:
    """Whether ``ring`` is a piece of ``want`` read without gaps, either way round (a walk that
    started or stopped too early)."""
    n = len(ring)
    return 0 < n < len(want) and any(ring == order[k:k + n] for order in (want, want[::-1])
                                     for k in range(len(want) - n + 1))


#: The one_ring slips a ring can show, in the order they are tried: (name, detector, sentence).
#: A detector gets ``(v, ring, want, on_boundary)``; the sentence may use ``{v}``, ``{first}``
#: (ring[0]), ``{start_tip}`` and ``{missing}``. Each row is tested with the slip's own code in
#: tests/exercises/test_checks.py (``RING_SLIPS``), so no sentence names a bug it did not see.
RING_SLIPS: tuple[tuple[str, Callable, str], ...] = (
    ("origins instead of tips",
     lambda v, ring, want, on_boundary: bool(ring) and all(u == v for u in ring),
     "Every entry is v itself: append the tip of each outgoing halfedge (h.tip), not h.vertex."),
    ("walking around a face (h = h.next)",
     lambda v, ring, want, on_boundary: v in ring,
     "Your ring contains vertex {v} itself, so the walk went round a triangle: h.next follows the face "
     "(its tip, the face's third corner, then v). To turn around v, step from one outgoing halfedge of v "
     "to the next: h = h.prev.twin."),
    ("a step that gives back its own halfedge (h = h.twin.twin)",
     lambda v, ring, want, on_boundary: ring == want[:1] and len(want) > 1,
     "Your walk stopped after one step: the step gave back the halfedge it started from (a twin's twin is "
     "the halfedge itself, h.twin.twin == h), so the loop ended at once. Step to the next outgoing halfedge "
     "of v: h = h.prev.twin."),
    ("circling around the tip (h = h.next.twin)",
     lambda v, ring, want, on_boundary: len(ring) > 1 and len(set(ring)) == 1 and len(want) > 1,
     "Every entry is vertex {first}: the walk circles around that vertex instead of around v (h.next.twin "
     "does that). Step with h = h.prev.twin to stay at v."),
    ("right order, wrong start",
     lambda v, ring, want, on_boundary: len(ring) == len(want) and any(ring == want[k:] + want[:k]
                                                                        for k in range(len(want))),
     "Right order, wrong start: begin with the tip of v.halfedge, vertex {start_tip}."),
    ("clockwise from another start",
     lambda v, ring, want, on_boundary: len(ring) == len(want) and any(ring == want[::-1][k:] + want[::-1][:k]
                                                                        for k in range(len(want))),
     "That is the clockwise order (CMU's h.twin.next walk, fine too) but from another start: begin with the "
     "tip of v.halfedge, vertex {start_tip}."),
    ("right neighbours, out of order",
     lambda v, ring, want, on_boundary: sorted(ring) == sorted(want),
     "Same neighbours, but not in order around v (either way round is fine, one step at a time)."),
    ("stopping at the boundary halfedge",
     lambda v, ring, want, on_boundary: on_boundary and _is_run_of(ring, want),
     "Missing {missing}: the neighbours you have are in order, but the walk stopped (or started) at the "
     "boundary. On the boundary the walk must also pass through the boundary halfedge: h = h.prev.twin does that by itself, "
     "so don't stop at h.face is None."),
)


def _compare_ring(mesh: HalfedgeMesh, v: int, ring: list[int]) -> str | None:
    """None if ``ring`` is vertex ``v``'s ring (either way round); else what is wrong, with the
    sentence of the first slip in :data:`RING_SLIPS` the ring shows, or what is missing or extra."""
    vertex = mesh.vertex(v)
    want = [int(u) for u in vertex.neighbors()]
    if ring == want or _is_clockwise(want, ring):
        return None
    start = vertex.halfedge
    where = (f"vertex {v} lies on the boundary (its halfedge {start.index} is the boundary halfedge "
             f"{v} -> {int(start.tip)})" if vertex.is_boundary else
             f"vertex {v} has halfedge {start.index} ({v} -> {int(start.tip)})")
    head = f"{where}; its ring, counter-clockwise from {int(start.tip)}, is {want}, but yours is {ring}."
    for _, detector, sentence in RING_SLIPS:
        if detector(v, ring, want, vertex.is_boundary):
            missing = [u for u in want if u not in ring]
            return head + " " + sentence.format(v=v, first=ring[0] if ring else None, start_tip=int(start.tip),
                                                missing=missing)
    extra = sorted(set(ring) - set(want))
    missing = [u for u in want if u not in ring]
    parts = []
    if missing:
        parts.append(f"missing {missing}")
    if extra:
        parts.append(f"{extra} {'is' if len(extra) == 1 else 'are'} not next to vertex {v}")
    if len(ring) > len(set(ring)):
        parts.append("some neighbours appear twice (stop when you are back at the start halfedge)")
    found = "; ".join(parts)
    return head + " " + found[:1].upper() + found[1:] + "."


_CLOCKWISE_PRAISE = (
    "Your walk turns clockwise (h = h.twin.next, as in the CMU notes): the same neighbours from the same "
    "start, the other way round, which is correct for that convention. This chapter and the library walk "
    "counter-clockwise (h = h.prev.twin) because then v, r[i], r[i + 1] is always one of the mesh's faces in "
    "its own counter-clockwise order, so the cross products of chapter 05's normals point outwards without a "
    "sign flip; reverse ring[1:] (or step with h.prev.twin) when you use the library's rings.")


def check_one_ring(learner_one_ring: Callable, *, seed: int | None = None) -> CheckResult:
    """Run ``learner_one_ring(mesh, v)`` on every vertex of several meshes.

    Args:
        learner_one_ring: a function ``(mesh, v) -> list`` of the neighbours of vertex
            ``v`` (a Vertex handle; ``int(v)`` is its index), starting with the tip of
            ``v.halfedge``, counter-clockwise (the chapter's ``h.prev.twin``) or clockwise
            (the CMU notes' ``h.twin.next``), the same way at every vertex. Vertex
            handles or ints in the list.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.

    Returns:
        A :class:`CheckResult` naming the first vertex whose ring differs and why
        (``result.show()`` draws that vertex's ring); otherwise a congratulation.
    """
    cases = one_ring_cases(seed)
    unfinished = harness.unfinished(learner_one_ring, "one_ring")
    if unfinished:
        return harness.counted(harness.failed("one_ring", [], None, unfinished), len(cases))
    return harness.counted(_check_one_ring(learner_one_ring, cases), len(cases))


def _check_one_ring(learner_one_ring: Callable, cases: list[tuple[str, HalfedgeMesh]]) -> CheckResult:
    """:func:`check_one_ring` on the given cases."""
    checked: list[str] = []
    turns: tuple[str, int] | None = None  # which way the learner's rings go, and where that was first seen
    for name, mesh in cases:
        for vertex in mesh.vertices:
            status, answer = harness.run(learner_one_ring, mesh, vertex)
            v = vertex.index
            if status == "timeout":
                return harness.failed("one_ring", checked, name,
                               f"your one_ring did not return within {TIME_LIMIT:g} s for vertex {v}. The walk "
                               f"probably never comes back to its start halfedge: each step must give another "
                               f"halfedge leaving v (h.prev.twin does), and halfedges are compared with ==, not `is` "
                               f"(each h.prev.twin is a new handle object).",
                               ("vertex", v), mesh)
            if status == "error":
                return harness.failed("one_ring", checked, name, f"for vertex {v}, " + _describe_error("one_ring", answer),
                               ("vertex", v), mesh, error=answer)
            ring, reason = _ring_as_ints(answer)
            if ring is None:
                return harness.failed("one_ring", checked, name, f"for vertex {v}, {reason}", ("vertex", v), mesh)
            problem = _compare_ring(mesh, v, ring)
            if problem is not None:
                return harness.failed("one_ring", checked, name, problem, ("vertex", v), mesh)
            want = [int(u) for u in vertex.neighbors()]
            if len(want) > 2:
                turn = "clockwise" if _is_clockwise(want, ring) else "counter-clockwise"
                if turns and turn not in turns:
                    return harness.failed(
                        "one_ring", checked, name,
                        f"vertex {v}'s ring {ring} goes {turn}, but your rings before went {turns[0]} "
                        f"(at vertex {turns[1]}): one walk turns one way at every vertex. Step with h.prev.twin "
                        f"(counter-clockwise) or h.twin.next (clockwise), the same everywhere.", ("vertex", v), mesh)
                turns = turns or (turn, v)
        checked.append(name)
    if turns and turns[0] == "clockwise":
        return CheckResult("one_ring", True, f"All good! Your one_ring finds the same neighbours as the library on "
                           f"{len(checked)} meshes ({', '.join(checked)}). {_CLOCKWISE_PRAISE}", list(checked))
    return harness.passed("one_ring", checked, "You can walk around any vertex, inside or on the boundary.")
