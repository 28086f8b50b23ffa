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
  vertex). The numbering must be the course's (see ``halfedge_edu.core.build``): faces in
  row order, each face ``[i, j, k]`` making ``(i, j), (j, k), (k, i)``; edge ``e`` is
  numbered in the order edges are first seen and owns halfedges ``2e`` (the first
  sighting) and ``2e + 1`` (its twin, ``h ^ 1``). The twin is not returned: it is ``h ^ 1``.
* ``one_ring(mesh, v) -> list`` of the neighbours of vertex ``v`` (given as a
  :class:`~halfedge_edu.Vertex` handle, which also works wherever an index does),
  counter-clockwise, starting with the tip of ``v.halfedge``. Vertex handles or ints.

A learner's function runs in :func:`~halfedge_edu.exercises.harness.run`, which stops
one that loops forever after ``TIME_LIMIT`` seconds where the platform allows it.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from halfedge_edu.core.build import build_reference
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.data import sample

from . import harness
from .harness import TIME_LIMIT, CheckResult

__all__ = ["check_build", "check_one_ring", "build_cases", "one_ring_cases"]


# --------------------------------------------------------------------------------------
# Words for a learner's function that raised or is not finished
# --------------------------------------------------------------------------------------

def _describe_error(name: str, error: Exception) -> str:
    if isinstance(error, NotImplementedError) or "ellipsis" in str(error).lower():
        return (f"{name} is not finished yet (it raised {type(error).__name__}: {error}). "
                f"Fill in the blanks marked ... and run the check again.")
    return (f"your {name} raised {type(error).__name__}: {error}. Call it yourself on the faces above "
            f"to see the full traceback.")


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


def build_cases() -> list[tuple[str, np.ndarray, np.ndarray]]:
    """The meshes ``check_build`` uses, in order: ``(name, vertices, faces)``.

    Small and open first (where mistakes are easy to read), then closed, several
    boundary loops, and a shuffled numbering.
    """
    cases = [("two triangles", [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]])]
    for name in ("lone_triangle", "strip", "tetrahedron", "cube", "open_patch"):
        cases.append((name.replace("_", " "), *sample(name).to_arrays()))
    cases.append(("annulus (two boundary loops)", *_annulus()))
    cases.append(("open patch, shuffled", *_shuffled(*sample("open_patch").to_arrays(), seed=7)))
    cases.append(("octahedron, shuffled", *_shuffled(*sample("octahedron").to_arrays(), seed=3)))
    return [(name, np.asarray(v, dtype=np.float64), np.asarray(f, dtype=np.int64)) for name, v, f in cases]


_BUILD_KEYS = ("vertex", "face", "next")
_OPTIONAL_BUILD_KEYS = ("prev", "vertex_halfedge")


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


def _compare_build(answer, faces: np.ndarray, n_vertices: int) -> tuple[str, tuple | None] | None:
    """None if ``answer`` equals the reference build of ``faces``; else (words, element)."""
    reference = build_reference(faces, n_vertices)
    story = _BuildStory(faces, reference)
    n_halfedges = len(reference.halfedge_next)
    n_edges = n_halfedges // 2

    if not isinstance(answer, dict):
        return (f"build(faces) should return a dict with the keys 'vertex', 'face' and 'next' "
                f"(one entry per halfedge each), but yours returned {type(answer).__name__} {answer!r:.60}.", None)
    missing = [key for key in _BUILD_KEYS if key not in answer]
    if missing:
        return (f"the dict your build returns has no {', '.join(repr(k) for k in missing)}; it needs "
                f"'vertex', 'face' and 'next' (one entry per halfedge each).", None)
    arrays = {}
    for key in _BUILD_KEYS + _OPTIONAL_BUILD_KEYS:
        if key not in answer:
            continue
        if _has_ellipsis(answer[key]):
            return (f"your {key!r} still contains a blank (...): build is not finished yet. "
                    f"Fill in the blanks and run the check again.", None)
        array = _as_index_array(answer[key])
        if array is None:
            return (f"your {key!r} should be a list of whole numbers, one per "
                    f"{'vertex' if key == 'vertex_halfedge' else 'halfedge'}, but it is {answer[key]!r:.80}.", None)
        arrays[key] = array

    for key, array in arrays.items():
        wanted = n_vertices if key == "vertex_halfedge" else n_halfedges
        if len(array) != wanted:
            if key == "vertex_halfedge":
                return (f"there are {n_vertices} vertices, so 'vertex_halfedge' should have {n_vertices} "
                        f"entries, but yours has {len(array)}.", None)
            hint = ""
            if len(array) == 3 * len(faces) and len(array) < n_halfedges:
                hint = (" You have three per face: the boundary halfedges are missing. Every edge that only one "
                        "face uses still gets a second halfedge, running the other way, with face -1.")
            elif len(array) == 3 * len(faces):
                hint = (" You have three per face, which is too many here: a shared edge's second sighting is "
                        "not a new halfedge, it is the twin 2e + 1 of the first.")
            return (f"{len(faces)} faces with {n_edges} edges make {n_halfedges} halfedges (two per edge, "
                    f"boundary ones included), but your {key!r} has {len(array)} entries.{hint}", None)

    vertex = arrays["vertex"]
    for h in range(n_halfedges):
        if vertex[h] != story.origin[h] or vertex[h ^ 1] != story.origin[h ^ 1]:
            hint = ""
            if vertex[h] == story.origin[h ^ 1] and vertex[h ^ 1] == story.origin[h]:
                hint = (" It points the wrong way: the first sighting of an edge gets the even number 2e and "
                        "runs the way that face uses it; the second sighting is the odd twin 2e + 1.")
            else:
                same = np.flatnonzero((story.origin == vertex[h]) &
                                      (story.origin[np.arange(n_halfedges) ^ 1] ==
                                       (vertex[h ^ 1] if (h ^ 1) < len(vertex) else -1)))
                if len(same):
                    hint = (f" Your halfedge {h} is the course's halfedge {int(same[0])}: the numbering differs. "
                            f"Edges are numbered in the order they are first seen, face by face, going "
                            f"(i, j), (j, k), (k, i) around each face.")
            return (f"{story.what(h)}. It should run {story.run(h)}, but yours runs "
                    f"{_learner_run(vertex, h)}.{hint}", ("halfedge", h))

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


def check_build(learner_build: Callable) -> CheckResult:
    """Run ``learner_build(faces)`` on several meshes and compare with ``build_reference``.

    Args:
        learner_build: a function ``faces -> dict`` with lists ``"vertex"``, ``"face"``,
            ``"next"`` (one entry per halfedge, course numbering, twin = ``h ^ 1``) and
            optionally ``"prev"`` and ``"vertex_halfedge"``. ``faces`` is an (m, 3) int
            array; rows are triangles counter-clockwise.

    Returns:
        A :class:`CheckResult`: on the first difference, what it is in words and which
        halfedge (``result.show()`` draws it); otherwise a short congratulation.
    """
    unfinished = harness.unfinished(learner_build, "build")
    if unfinished:
        return harness.failed("build", [], None, unfinished)
    checked: list[str] = []
    for name, vertices, faces in build_cases():
        status, answer = harness.run(learner_build, faces.copy())
        mesh = HalfedgeMesh.from_faces(vertices, faces)
        intro = f"faces {faces.tolist()}: " if len(faces) <= 4 else ""
        if status == "timeout":
            return harness.failed("build", checked, name, f"{intro}your build did not finish within {TIME_LIMIT:g} s. "
                           "A loop probably never ends: check the walks that should come back to their start.",
                           None, mesh)
        if status == "error":
            return harness.failed("build", checked, name, intro + _describe_error("build", answer), None, mesh)
        problem = _compare_build(answer, faces, len(vertices))
        if problem is not None:
            text, element = problem
            return harness.failed("build", checked, name, intro + text, element, mesh)
        checked.append(name)
    return harness.passed("build", checked, "Your loop builds the same halfedges, in the same order, as the library.")


# --------------------------------------------------------------------------------------
# check_one_ring
# --------------------------------------------------------------------------------------

def one_ring_cases() -> list[tuple[str, HalfedgeMesh]]:
    """The meshes ``check_one_ring`` walks around, every vertex of each, in order.

    A flat patch comes first: its pictures are the easiest to read, and it has corner,
    rim and interior vertices.
    """
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


def _compare_ring(mesh: HalfedgeMesh, v: int, ring: list[int]) -> str | None:
    vertex = mesh.vertex(v)
    want = [int(u) for u in vertex.neighbors()]
    if ring == want:
        return None
    start = vertex.halfedge
    where = (f"vertex {v} lies on the boundary (its halfedge {start.index} is the boundary halfedge "
             f"{v} -> {int(start.tip)})" if vertex.is_boundary else
             f"vertex {v} has halfedge {start.index} ({v} -> {int(start.tip)})")
    head = f"{where}; its ring, counter-clockwise from {int(start.tip)}, is {want}, but yours is {ring}."
    if ring and all(u == v for u in ring):
        return head + " Every entry is v itself: append the tip of each outgoing halfedge (h.tip), not h.vertex."
    if len(ring) > 1 and len(set(ring)) == 1 and len(want) > 1:
        return head + (f" Every entry is vertex {ring[0]}: the walk circles around that vertex instead of "
                       f"around v (h.next.twin does that). Step with h = h.prev.twin to stay at v.")
    if len(ring) == len(want) and ring[:1] == want[:1] and ring[1:] == want[1:][::-1]:
        return head + (" You walked clockwise. h.twin.next turns clockwise around v; to turn "
                       "counter-clockwise, step h = h.prev.twin.")
    if len(ring) == len(want) and any(ring == want[k:] + want[:k] for k in range(len(want))):
        return head + f" Right order, wrong start: begin with the tip of v.halfedge, vertex {int(start.tip)}."
    reversed_ring = want[::-1]
    if len(ring) == len(want) and any(ring == reversed_ring[k:] + reversed_ring[:k] for k in range(len(want))):
        return head + (" That is the clockwise order; turn counter-clockwise with h = h.prev.twin, "
                       "starting at v.halfedge.")
    if sorted(ring) == sorted(want):
        return head + " Same neighbours, but not in counter-clockwise order around v."
    extra = sorted(set(ring) - set(want))
    missing = [u for u in want if u not in ring]
    parts = []
    if missing:
        parts.append(f"missing {missing}")
    if extra:
        parts.append(f"{extra} {'is' if len(extra) == 1 else 'are'} not next to vertex {v}")
    if len(ring) > len(set(ring)):
        parts.append("some neighbours appear twice (stop when you are back at the start halfedge)")
    hint = ""
    if missing and vertex.is_boundary:
        hint = (" On the boundary the walk must also pass through the boundary halfedge: h = h.prev.twin "
                "does that by itself, so don't stop at h.face is None.")
    found = "; ".join(parts)
    return head + " " + found[:1].upper() + found[1:] + "." + hint


def check_one_ring(learner_one_ring: Callable) -> CheckResult:
    """Run ``learner_one_ring(mesh, v)`` on every vertex of several meshes.

    Args:
        learner_one_ring: a function ``(mesh, v) -> list`` of the neighbours of vertex
            ``v`` (a Vertex handle; ``int(v)`` is its index), counter-clockwise, starting
            with the tip of ``v.halfedge``. Vertex handles or ints in the list.

    Returns:
        A :class:`CheckResult` naming the first vertex whose ring differs and why
        (``result.show()`` draws that vertex's ring); otherwise a congratulation.
    """
    unfinished = harness.unfinished(learner_one_ring, "one_ring")
    if unfinished:
        return harness.failed("one_ring", [], None, unfinished)
    checked: list[str] = []
    for name, mesh in one_ring_cases():
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
                               ("vertex", v), mesh)
            ring, reason = _ring_as_ints(answer)
            if ring is None:
                return harness.failed("one_ring", checked, name, f"for vertex {v}, {reason}", ("vertex", v), mesh)
            problem = _compare_ring(mesh, v, ring)
            if problem is not None:
                return harness.failed("one_ring", checked, name, problem, ("vertex", v), mesh)
        checked.append(name)
    return harness.passed("one_ring", checked, "You can walk around any vertex, inside or on the boundary.")
