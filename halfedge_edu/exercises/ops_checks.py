"""Checks for the exercises of chapters 06 and 07: ``check_flip`` and ``check_collapse``.

A learner writes one local operation; the check runs it on copies of small meshes, step
by step, and after every step compares the learner's mesh with the package's own
operation. It stops at the *first* difference and explains it in a sentence that names
the mesh, the edge, the element that is wrong and the rule it breaks, using the names
of the operation's picture (``h0 ... h5, v0 ... v3`` for a flip, ``vA, vB, h_A_L ...``
for a collapse)::

    from halfedge_edu.exercises.ops_checks import check_flip, check_collapse
    check_flip(my_flip)            # "Not yet. On 'strip', flipping edge 2: ..." or a congratulation
    check_collapse(my_collapse)
    check_flip(my_flip).show()     # the offending element, drawn on the mesh before the step

The contracts (also stated in the chapters):

* ``flip(mesh, e)``: ``e`` is an edge index (an int) of an interior edge that may be
  flipped. Edit the mesh in place, writing the arrays ``mesh.halfedge_next``,
  ``halfedge_prev``, ``halfedge_vertex``, ``halfedge_face``, ``vertex_halfedge`` and
  ``face_halfedge``. Edge ``e`` must afterwards join the two vertices that were opposite
  it; no element is created, deleted or moved.
* ``collapse(mesh, h)``: ``h`` is a halfedge index (an int) of an interior edge that may
  be collapsed. ``h`` runs from ``vB``, the vertex that goes, to ``vA``, the vertex that
  stays and moves to the edge's midpoint. Delete (with ``mesh.delete_vertex``,
  ``delete_edge``, ``delete_face``) ``vB``, the edge, both its faces and one more edge of
  each of those faces; which of the two edges that become one is kept is up to you.

"Compared with the reference" means *up to relabelling*: every face is written as the
positions of its three corners, in counter-clockwise order, and the two meshes must
have the same faces. A flip or collapse that keeps other halfedge numbers than the
library's is just as right.

Callers never need to run the package's operations themselves: the meshes, the edges
and the expected results all come from here. Nothing here imports pyvista; only
``CheckResult.show()`` draws.
"""

from __future__ import annotations

import re
from typing import Callable

import numpy as np

from halfedge_edu.core.errors import MeshInvariantError
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.core.ops import OperationLog, can_collapse, can_flip, can_split, collapse, flip, split
from halfedge_edu.data import sample

from . import harness, hidden
from .harness import TIME_LIMIT, CheckResult


__all__ = ["COLLAPSE_PHASES", "check_collapse", "check_collapse_steps", "check_flip", "check_split", "collapse_cases", "flip_cases", "split_cases"]

#: Decimals that positions are rounded to when faces are compared by their corners.
_DECIMALS = 9


# --------------------------------------------------------------------------------------
# The meshes and edges
# --------------------------------------------------------------------------------------

def _random_steps(mesh: HalfedgeMesh, allowed, operate, count: int, seed: int, *, halfedges: bool) -> list[int]:
    """``count`` random allowed steps, each on the mesh as the earlier steps left it.

    Returns edge indices (or halfedge indices when ``halfedges``); ``mesh`` is not changed.
    """
    rng = np.random.default_rng(seed)
    work = mesh.copy()
    steps = []
    for _ in range(count):
        live = np.flatnonzero(~work.edge_deleted)
        for e in rng.permutation(live):
            if not work.edge(int(e)).is_boundary and allowed(work, int(e)):
                break
        else:
            break
        step = 2 * int(e) + int(rng.integers(0, 2)) if halfedges else int(e)
        operate(work, step)
        steps.append(step)
    return steps


def _hidden_step_cases(seed: int, allowed, operate, *, halfedges: bool, with_boundary: bool,
                       what: str) -> list[tuple[str, HalfedgeMesh, list[int]]]:
    """The hidden cases of ``check_flip`` / ``check_collapse``: random allowed steps on a
    closed mesh, on a jittered grid patch (a boundary nearby; ``with_boundary``) or a
    closed mesh after random flips (other degrees), and on an icosphere(2).

    ``check_collapse``'s contract has no boundary (the chapter's collapse is for closed
    meshes), so its hidden cases are all closed.
    """
    rng = harness.hidden_rng(seed)
    shape, other = (str(name) for name in rng.choice(["cube", "octahedron", "icosphere(1)"], 2, replace=False))
    rows, columns = (int(n) for n in rng.integers(3, 5, 2))
    flips = int(rng.integers(3, 8))
    second = ((f"a {rows} x {columns} grid patch", HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng)), 3)
              if with_boundary else
              (f"{other} after {flips} random flips", hidden.flipped(hidden.closed_mesh(other), flips, rng), 3))
    meshes = [
        (shape, hidden.closed_mesh(shape), int(rng.integers(3, 6))),
        second,
        ("icosphere(2)", sample("icosphere", subdivisions=2), int(rng.integers(6, 11))),
    ]
    cases = []
    for number, (name, mesh, count) in enumerate(meshes, start=1):
        steps = _random_steps(mesh, allowed, operate, count, int(rng.integers(2**31)), halfedges=halfedges)
        cases.append((harness.hidden_name(number, f"{name}, {len(steps)} random {what}"), mesh, steps))
    return cases


def flip_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh, list[int]]]:
    """What ``check_flip`` runs: ``(name, mesh, edges)``, the edges flipped one after another.

    Small meshes first, where a mistake is easy to draw, then a run of random flips on
    an icosphere. Every listed flip is allowed at the moment it is made. With a
    ``seed``, the hidden cases instead (random flips on other meshes).
    """
    if seed is not None:
        return _hidden_step_cases(seed, can_flip, lambda mesh, e: flip(mesh, e), halfedges=False,
                                  with_boundary=True, what="flips")
    strip = sample("strip")
    cube = sample("cube")
    single = sample("single_collapse")
    sphere = sample("icosphere", subdivisions=1)
    flip_edge = lambda mesh, e: flip(mesh, e)  # noqa: E731
    return [
        ("strip", strip, [int(strip.find_edge(1, 2))]),
        ("cube", cube, [int(cube.find_edge(2, 4)), int(cube.find_edge(4, 6))]),
        ("single_collapse", single, [0, int(single.find_edge(1, 3))]),
        ("icosphere, 6 random flips", sphere, _random_steps(sphere, can_flip, flip_edge, 6, seed=6, halfedges=False)),
    ]


def collapse_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh, list[int]]]:
    """What ``check_collapse`` runs: ``(name, mesh, halfedges)``, collapsed one after another.

    Each halfedge runs from the vertex that goes (vB) to the one that stays (vA). The
    cube's halfedge 0 removes vertex 0, of degree 3 (the case where the faces beyond
    both removed edges are one and the same face); halfedge 1 removes vertex 4, of
    degree 5; ``single_collapse`` removes a vertex of degree 6. With a ``seed``, the
    hidden cases instead (random collapses on other meshes).
    """
    if seed is not None:
        return _hidden_step_cases(seed, can_collapse, lambda mesh, h: collapse(mesh, mesh.halfedge(h)),
                                  halfedges=True, with_boundary=False, what="collapses")
    single = sample("single_collapse")
    sphere = sample("icosphere", subdivisions=1)
    collapse_halfedge = lambda mesh, h: collapse(mesh, mesh.halfedge(h))  # noqa: E731
    return [
        ("single_collapse", single, [0]),
        ("cube, removing the degree-3 vertex 0", sample("cube"), [0]),
        ("cube, removing vertex 4 (degree 5)", sample("cube"), [1]),
        ("icosphere, 6 random collapses", sphere,
         _random_steps(sphere, can_collapse, collapse_halfedge, 6, seed=7, halfedges=True)),
    ]


# --------------------------------------------------------------------------------------
# Comparing two meshes up to relabelling
# --------------------------------------------------------------------------------------

def _corner_faces(mesh: HalfedgeMesh) -> dict[tuple, int]:
    """Every live face as the rounded positions of its corners, rotated to a fixed start.

    Maps ``((x, y, z), (x, y, z), (x, y, z))`` (counter-clockwise, smallest corner
    first) to the face index.
    """
    corners = mesh.face_vertices()
    positions = np.round(mesh.positions, _DECIMALS) + 0.0
    faces = {}
    for f in np.flatnonzero(~mesh.face_deleted):
        points = [tuple(float(c) for c in positions[v]) for v in corners[f]]
        k = points.index(min(points))
        faces[tuple(points[k:] + points[:k])] = int(f)
    return faces


def _vertex_at(mesh: HalfedgeMesh, point: tuple) -> int:
    """The live vertex at ``point`` (rounded positions), or -1."""
    close = np.flatnonzero(~mesh.vertex_deleted & np.all(np.round(mesh.positions, _DECIMALS) == point, axis=1))
    return int(close[0]) if len(close) else -1


def _face_words(mesh: HalfedgeMesh, corner_points: tuple) -> str:
    return "(" + ", ".join(str(_vertex_at(mesh, p)) for p in corner_points) + ")"


def _compare_faces(yours: HalfedgeMesh, wanted: HalfedgeMesh) -> str | None:
    """None if both meshes have the same faces (by corner positions); else what differs."""
    have, want = _corner_faces(yours), _corner_faces(wanted)
    missing = [key for key in want if key not in have]
    extra = [key for key in have if key not in want]
    if not missing and not extra:
        return None
    parts = []
    if missing:
        key = missing[0]
        reversed_key = (key[0], key[2], key[1])
        text = f"the face with corners {_face_words(wanted, key)} is missing"
        if reversed_key in have:
            text += (f": yours has face {have[reversed_key]} on the same corners but clockwise, "
                     f"{_face_words(yours, reversed_key)}; a face's halfedges must run counter-clockwise")
        parts.append(text)
    if extra and not (missing and (missing[0][0], missing[0][2], missing[0][1]) in have):
        key = extra[0]
        parts.append(f"your face {have[key]} has corners {_face_words(yours, key)}, which the result should not have")
    return "; ".join(parts)


# --------------------------------------------------------------------------------------
# Words
# --------------------------------------------------------------------------------------

def _named(log: OperationLog, kind: str, index: int) -> str:
    """``"halfedge 5 (h3)"``: an element with the names the operation gathered it under."""
    names = log.names_of(kind, int(index))
    return f"{kind} {index}" + (f" ({' = '.join(names)})" if names else "")


# "halfedge 5", "vertex 2", "face 1"; and halfedges written as "its next (9)" or "halfedge is 3".
_ELEMENT_WORDS = re.compile(r"\b(halfedge|vertex|face) (\d+)|\b(?:next|prev) \((\d+)\)|\bhalfedge is (\d+)")


def _names_in_error(message: str, log: OperationLog) -> str:
    """The picture's names of the elements a validation message mentions, as a sentence."""
    mentioned = []
    for kind, index, pointed, pointer in _ELEMENT_WORDS.findall(message):
        mentioned.append((kind, index) if kind else ("halfedge", pointed or pointer))
    said = []
    for kind, index in dict.fromkeys(mentioned):
        names = log.names_of(kind, int(index))
        if names:
            said.append(f"{kind} {index} is {' = '.join(names)}")
    return f" In the picture of the operation, {', '.join(said)}." if said else ""


def _describe_error(name: str, error: Exception) -> str:
    if isinstance(error, NotImplementedError):
        return (f"your {name} is not written yet (it raised NotImplementedError). Replace the raise with "
                f"your code and run the check again.")
    if "ellipsis" in str(error).lower():
        return f"your {name} still has a blank (...) in it. Fill it in and run the check again."
    return f"your {name} raised {type(error).__name__}: {error}.{harness.own_line(error)}"


def _validation_problem(mesh: HalfedgeMesh, log: OperationLog, doing: str) -> tuple[str, tuple] | None:
    try:
        mesh.validate()
    except MeshInvariantError as error:
        message = str(error).split("] ", 1)[-1]
        return (f"after {doing}, the mesh breaks the rule {error.rule}: {message}."
                f"{_names_in_error(message, log)}", error.element)
    return None


def _shown(element):
    """An element ``CheckResult.show`` can draw (an index it can look up), else None."""
    if element is None:
        return None
    kind, index = element
    if kind in ("halfedge", "vertex", "face") and isinstance(index, (int, np.integer)) and index >= 0:
        return kind, int(index)
    return None


# --------------------------------------------------------------------------------------
# Running the learner's operation step by step (both checks)
# --------------------------------------------------------------------------------------

def _picture_names(library: Callable, before: HalfedgeMesh, step: int) -> dict[tuple[str, int], str]:
    """``(kind, index) -> name`` of the operation's picture (``v0``, ``h3``, ``vA`` ...) for
    this step, so that ``result.show()`` labels the elements as the message names them."""
    log = OperationLog()
    try:
        library(before.copy(), step, log=log)
    except TypeError:                     # an operation that takes no log: label by index
        return {}
    return {element: name for name, element in log.named.items()}


def _check_steps(exercise: str, learner: Callable, cases: list, doing: str, element_of: Callable,
                 timeout_hint: str, problem_of: Callable, library: Callable, praise: str) -> CheckResult:
    """Run ``learner(mesh, step)`` on a copy before every step of every case; stop at the first difference.

    Args:
        exercise: "flip" or "collapse", for the messages.
        cases: ``(name, mesh, steps)`` from :func:`flip_cases` or :func:`collapse_cases`.
        doing: what one step is, with ``{}`` for the step, e.g. ``"flipping edge {}"``.
        element_of: step -> the ``(kind, index)`` to draw when the learner's function fails.
        timeout_hint: what to look for when the function does not finish.
        problem_of: ``(before, yours, step, notes) -> (words, element) | None``, the
            comparison; it may add to ``notes`` (a dict used as an ordered set) the
            sentence naming a course's convention it recognised, said once on success.
        library: ``(mesh, step)``, the package's operation, which moves the case on.
        praise: the last sentence of the congratulation.
    """
    checked: list[str] = []
    notes: dict[str, None] = {}
    for name, mesh, steps in cases:
        for step in steps:
            before = mesh.copy()
            yours = mesh.copy()
            status, answer = harness.run(learner, yours, step)
            if status == "timeout":
                text = f"your {exercise} did not finish within {TIME_LIMIT:g} s. {timeout_hint}"
            elif status == "error":
                text = _describe_error(exercise, answer)
            else:
                yours.topology_changed()  # the learner wrote the arrays by hand
                problem = problem_of(before, yours, step, notes)
                if problem is None:
                    library(mesh, step)
                    continue
                text, element = problem
                return harness.failed(exercise, checked, name, text, _shown(element), before,
                                      names=_picture_names(library, before, step))
            return harness.failed(exercise, checked, name, f"{doing.format(step)}, {text}", element_of(step), before,
                                  error=answer if status == "error" else None,
                                  names=_picture_names(library, before, step))
        checked.append(name)
    return harness.passed(exercise, checked, " ".join([praise, *notes]))


# --------------------------------------------------------------------------------------
# check_flip
# --------------------------------------------------------------------------------------

def _flip_problem(before: HalfedgeMesh, yours: HalfedgeMesh, e: int,
                  notes: dict[str, None] | None = None) -> tuple[str, tuple | None] | None:
    """None if ``yours`` is ``before`` with edge ``e`` flipped; else (words, element)."""
    log = OperationLog()
    wanted = before.copy()
    flip(wanted, e, log=log)
    ids = {n: index for n, (_, index) in log.named.items()}
    v0, v1, v2, v3 = ids["v0"], ids["v1"], ids["v2"], ids["v3"]
    doing = f"your flip of edge {e}"
    picture = f"(v0 = {v0}, v1 = {v1}; opposite it v2 = {v2} and v3 = {v3})"

    counts = [(kind, getattr(before, f"n_{kind}"), getattr(yours, f"n_{kind}")) for kind in ("vertices", "edges", "faces")]
    changed = [f"{have} {kind} instead of {had}" for kind, had, have in counts if had != have]
    if changed:
        return (f"after {doing} the mesh has {', '.join(changed)}. A flip creates and deletes nothing: it reuses "
                f"the same edge, its two halfedges and the two faces.", ("halfedge", 2 * e))
    if before.n_vertex_slots != yours.n_vertex_slots or before.n_edge_slots != yours.n_edge_slots \
            or before.n_face_slots != yours.n_face_slots:
        return (f"{doing} added elements (and deleted as many). A flip only rewires pointers: reuse the edge's "
                f"halfedges and the two faces.", ("halfedge", 2 * e))
    moved = np.flatnonzero(np.any(yours.positions != before.positions, axis=1))
    if len(moved):
        return (f"{doing} moved vertex {int(moved[0])}. A flip changes only connectivity; positions stay.",
                ("vertex", int(moved[0])))
    problem = _validation_problem(yours, log, doing)
    if problem is not None:
        return problem
    ends = sorted(int(v) for v in yours.edge(e).vertices)
    if ends != sorted((v2, v3)):
        return (f"after {doing} {picture}, edge {e} joins vertices {ends[0]} and {ends[1]}; it should join "
                f"v2 and v3, the two vertices that were opposite it (in the picture, h0 = {2 * e} then runs "
                f"v3 -> v2 and h1 = {2 * e + 1} runs v2 -> v3).", ("halfedge", 2 * e))
    different = _compare_faces(yours, wanted)
    if different is not None:
        return (f"after {doing} {picture}, {different}. The two triangles should be (v3, v2, v0) and "
                f"(v2, v3, v1), and no other face may change.", ("halfedge", 2 * e))
    return None


def check_flip(learner_flip: Callable, *, seed: int | None = None) -> CheckResult:
    """Run ``learner_flip(mesh, e)`` on copies of small meshes and compare with the library's flip.

    Args:
        learner_flip: a function ``(mesh, e) -> anything`` that flips edge ``e`` (an int)
            of ``mesh`` in place. It is only called on edges that may be flipped.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.

    Returns:
        A :class:`~halfedge_edu.exercises.CheckResult`: at the first difference, what it
        is in words and which element (``result.show()`` draws it on the mesh as it was
        before that flip); otherwise a short congratulation.
    """
    cases = flip_cases(seed)
    return harness.counted(_check_steps(
        "flip", learner_flip, cases, "flipping edge {}", lambda e: ("halfedge", 2 * e),
        "A flip is a fixed number of pointer writes; look for a loop that never ends.",
        _flip_problem, lambda mesh, e, log=None: flip(mesh, e, log=log),
        "Every pointer ends up where it should, and the mesh is still valid.",
    ), len(cases))


# --------------------------------------------------------------------------------------
# check_collapse
# --------------------------------------------------------------------------------------

def _deleted(before: HalfedgeMesh, yours: HalfedgeMesh, kind: str) -> set[int]:
    flags = {"vertex": "vertex_deleted", "edge": "edge_deleted", "face": "face_deleted"}[kind]
    old, new = getattr(before, flags), getattr(yours, flags)
    return {int(i) for i in np.flatnonzero(new[: len(old)] & ~old)}


#: Said once when a learner's collapse keeps ``h.vertex`` instead of ``h.tip``.
_KEPT_OTHER_END_NOTE = (
    "Your collapse keeps the other endpoint, h.vertex, and deletes h.tip: UChicago's assignment leaves the "
    "choice of which vertex to keep free, so that is accepted (judged as the collapse of h.twin). The chapter "
    "keeps vA = h.tip so that its pictures and pointer tables have one name for each element.")


def _kept_end(before: HalfedgeMesh, yours: HalfedgeMesh, h: int) -> int:
    """The halfedge whose collapse ``yours`` matches in which endpoint survives: ``h`` when
    ``h.tip`` survives (the chapter's convention), ``h ^ 1`` when only ``h.vertex`` does."""
    tip, origin = int(before.halfedge_vertex[h ^ 1]), int(before.halfedge_vertex[h])
    gone = _deleted(before, yours, "vertex")
    live_halfedges = np.repeat(~yours.edge_deleted, 2)                       # (n_halfedge_slots,) bool
    tip_still_used = bool(np.any(yours.halfedge_vertex[live_halfedges] == tip))
    return h ^ 1 if gone == {tip} and origin not in gone and not tip_still_used else h


def _collapse_problem(before: HalfedgeMesh, yours: HalfedgeMesh, h: int,
                      notes: dict[str, None] | None = None) -> tuple[str, tuple | None] | None:
    """None if ``yours`` is ``before`` with halfedge ``h`` collapsed; else (words, element).

    Either endpoint may survive (UChicago leaves it free): when only ``h.tip`` is
    deleted, the answer is judged as the collapse of ``h.twin`` and ``notes`` says so.
    """
    if _kept_end(before, yours, h) != h:
        problem = _collapse_problem(before, yours, h ^ 1)
        if problem is None and notes is not None:
            notes[_KEPT_OTHER_END_NOTE] = None
        return problem
    log = OperationLog()
    wanted = before.copy()
    collapse(wanted, wanted.halfedge(h), log=log)
    ids = {n: index for n, (_, index) in log.named.items()}
    vA, vB, e = ids["vA"], ids["vB"], h >> 1
    doing = f"your collapse of halfedge {h}"
    picture = f"(vB = {vB} goes, vA = {vA} stays; fL = {ids['fL']}, fR = {ids['fR']}, vL = {ids['vL']}, vR = {ids['vR']})"

    if before.n_vertex_slots != yours.n_vertex_slots or before.n_edge_slots != yours.n_edge_slots \
            or before.n_face_slots != yours.n_face_slots:
        return (f"{doing} added elements. A collapse only deletes: the surviving vertex, halfedges and faces are "
                f"reused.", ("halfedge", h))
    gone = {kind: _deleted(before, yours, kind) for kind in ("vertex", "edge", "face")}
    if vA in gone["vertex"]:
        return (f"{doing} {picture} deleted vertex {vA}, vA, but its halfedges still start at it. Halfedge {h} runs "
                f"from vB to vA: the chapter keeps vA = h.tip (at the midpoint) and deletes vB = h.vertex. Keeping "
                f"vB instead is fine too (UChicago leaves it free), but then every halfedge that left vA must "
                f"leave vB.", ("vertex", vA))
    if gone["vertex"] != {vB}:
        if not gone["vertex"]:
            text = f"{doing} {picture} deleted no vertex; vB = {vB} must go (mesh.delete_vertex(vB))."
        else:
            text = f"{doing} {picture} deleted vertices {sorted(gone['vertex'])}; only vB = {vB} should go."
        return text, ("vertex", vB)
    if e not in gone["edge"]:
        return (f"{doing} {picture} did not delete edge {e}, the collapsed edge itself "
                f"(mesh.delete_edge({e})).", ("halfedge", h))
    for side in ("fL", "fR"):
        if ids[side] not in gone["face"]:
            return (f"{doing} {picture} did not delete face {ids[side]} ({side}). Both faces beside the edge "
                    f"shrink to nothing and must be deleted.", ("face", ids[side]))
    extra_faces = gone["face"] - {ids["fL"], ids["fR"]}
    if extra_faces:
        f = min(extra_faces)
        return (f"{doing} {picture} deleted face {f} too; only fL and fR should go. "
                f"{_named(log, 'face', f).capitalize()} survives the collapse.", ("face", f))
    for side, first, second in (("L", "h_A_L", "h_L_B"), ("R", "h_R_A", "h_B_R")):
        pair = {ids[first] >> 1, ids[second] >> 1}
        count = len(gone["edge"] & pair)
        if count != 1:
            a, b = sorted(pair)
            what = "neither" if count == 0 else "both"
            return (f"{doing} {picture} deleted {what} of edges {a} and {b}, the other two edges of f{side}. "
                    f"They become one edge when vB and vA merge, so exactly one of them must go "
                    f"(either one).", ("face", ids["f" + side]))
    others = gone["edge"] - {e} - {ids[n] >> 1 for n in ("h_A_L", "h_L_B", "h_R_A", "h_B_R")}
    if others:
        other = min(others)
        return (f"{doing} {picture} deleted edge {other} too. A collapse deletes 3 edges: the edge itself and one "
                f"more from each of its two faces.", ("halfedge", 2 * other))
    midpoint = 0.5 * (before.positions[vA] + before.positions[vB])
    if not np.allclose(yours.positions[vA], midpoint):
        return (f"after {doing}, vA = {vA} is at {np.round(yours.positions[vA], 4).tolist()}; it should be at the "
                f"midpoint of the edge, {np.round(midpoint, 4).tolist()}.", ("vertex", vA))
    live = ~before.vertex_deleted
    live[vB] = live[vA] = False
    moved = np.flatnonzero(live & np.any(yours.positions != before.positions, axis=1))
    if len(moved):
        return (f"{doing} moved vertex {int(moved[0])}; only vA moves (to the midpoint).", ("vertex", int(moved[0])))
    problem = _validation_problem(yours, log, doing)
    if problem is not None:
        text, element = problem
        if before.vertex(vB).degree == 3:
            text += (f" Here vB has degree 3, so gL and gR are the same face ({ids['gL']}): replacing h_R_B "
                     f"must read the pointers that replacing h_B_L has just changed. Read each neighbour "
                     f"right before you rewrite it, not all of them at the start.")
        return text, element
    different = _compare_faces(yours, wanted)
    if different is not None:
        return (f"after {doing} {picture}, {different}. Every face that used vB should now use vA, and no "
                f"other face changes.", ("halfedge", h))
    return None


def check_collapse(learner_collapse: Callable, *, seed: int | None = None) -> CheckResult:
    """Run ``learner_collapse(mesh, h)`` on copies of small meshes and compare with the library's collapse.

    Args:
        learner_collapse: a function ``(mesh, h) -> anything`` that collapses the edge of
            halfedge ``h`` (an int) in place: ``h.vertex`` (vB) goes, ``h.tip`` (vA) stays
            and moves to the midpoint. It is only called on interior edges that may be
            collapsed, some of them on meshes that already have deleted elements.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.

    Returns:
        A :class:`~halfedge_edu.exercises.CheckResult`: at the first difference, what it
        is in words and which element (``result.show()`` draws it on the mesh as it was
        before that collapse); otherwise a short congratulation.
    """
    cases = collapse_cases(seed)
    return harness.counted(_check_steps(
        "collapse", learner_collapse, cases, "collapsing halfedge {}", lambda h: ("halfedge", h),
        "The walk around vB (h = twin(prev(h))) probably never comes back to its start: compare halfedge "
        "indices, and stop before you change the pointers you walk along.",
        _collapse_problem, lambda mesh, h, log=None: collapse(mesh, mesh.halfedge(h), log=log),
        "Both cases work, degree 3 and higher, and the mesh stays valid.",
    ), len(cases))


# --------------------------------------------------------------------------------------
# check_split (CS184 and CMU's task 2)
# --------------------------------------------------------------------------------------

def split_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh, list[int]]]:
    """What ``check_split`` runs: ``(name, mesh, edges)``, interior edges split one after another.

    The strip's middle edge first (small enough to draw), then the cube's diagonal and a
    side, then random splits on an icosphere. With a ``seed``, the hidden cases instead.
    """
    split_edge = lambda mesh, e: split(mesh, e)  # noqa: E731
    if seed is not None:
        return _hidden_step_cases(seed, can_split, split_edge, halfedges=False, with_boundary=True, what="splits")
    strip = sample("strip")
    cube = sample("cube")
    sphere = sample("icosphere", subdivisions=1)
    return [
        ("strip", strip, [int(strip.find_edge(1, 2))]),
        ("cube", cube, [1, 0]),
        ("icosphere, 5 random splits", sphere, _random_steps(sphere, can_split, split_edge, 5, seed=5, halfedges=False)),
    ]


def _split_problem(before: HalfedgeMesh, yours: HalfedgeMesh, e: int,
                   notes: dict[str, None] | None = None) -> tuple[str, tuple | None] | None:
    """None if ``yours`` is ``before`` with interior edge ``e`` split at its midpoint; else (words, element)."""
    log = OperationLog()
    wanted = before.copy()
    split(wanted, e, log=log)
    ids = {n: index for n, (_, index) in log.named.items()}
    doing = f"your split of edge {e}"
    picture = f"(v0 = {ids['v0']}, v1 = {ids['v1']}; opposite it v2 = {ids['v2']} and v3 = {ids['v3']})"
    counts = [(kind, getattr(before, f"n_{kind}"), getattr(yours, f"n_{kind}"), add)
              for kind, add in (("vertices", 1), ("edges", 3), ("faces", 2))]
    wrong = [f"{have - had} new {kind} instead of {add}" for kind, had, have, add in counts if have - had != add]
    if wrong:
        return (f"after {doing} {picture} the mesh has {', '.join(wrong)}. A split of an interior edge adds 1 vertex "
                f"m, 3 edges (m - v1, m - v2, m - v3; the old edge keeps its v0 half) and 2 faces "
                f"(mesh.add_vertex, mesh.add_edge, mesh.add_face).", ("halfedge", 2 * e))
    m = int(np.flatnonzero(~yours.vertex_deleted)[-1]) if yours.n_vertex_slots > before.n_vertex_slots else -1
    midpoint = 0.5 * (before.positions[ids["v0"]] + before.positions[ids["v1"]])
    if m < 0 or not np.allclose(yours.positions[m], midpoint):
        where = f"at {np.round(yours.positions[m], 4).tolist()}" if m >= 0 else "nowhere"
        return (f"after {doing} {picture}, the new vertex is {where}; it goes at the midpoint of the edge, "
                f"{np.round(midpoint, 4).tolist()}.", ("halfedge", 2 * e))
    moved = np.flatnonzero(np.any(yours.positions[: before.n_vertex_slots] != before.positions, axis=1))
    if len(moved):
        return f"{doing} moved vertex {int(moved[0])}; a split only adds m.", ("vertex", int(moved[0]))
    problem = _validation_problem(yours, log, doing)
    if problem is not None:
        return problem
    different = _compare_faces(yours, wanted)
    if different is not None:
        return (f"after {doing} {picture}, {different}. The four triangles around m are (v0, m, v2), (m, v1, v2), "
                f"(m, v0, v3) and (v1, m, v3), and no other face changes.", ("halfedge", 2 * e))
    return None


def check_split(learner_split: Callable, *, seed: int | None = None) -> CheckResult:
    """Run ``learner_split(mesh, e)`` on copies of small meshes and compare with the library's split.

    Args:
        learner_split: a function ``(mesh, e) -> anything`` that splits interior edge ``e``
            (an int) in place: a new vertex ``m`` at the midpoint, joined to the two
            opposite vertices (CS184's and CMU's task). Any numbering of the new elements.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.

    Returns:
        A :class:`~halfedge_edu.exercises.CheckResult`: at the first difference, what it
        is in words, with the picture's names; otherwise a short congratulation.
    """
    cases = split_cases(seed)
    if (words := harness.unfinished(learner_split, "split")) is not None:
        return harness.counted(harness.failed("split", [], None, words), len(cases))
    return harness.counted(_check_steps(
        "split", learner_split, cases, "splitting edge {}", lambda e: ("halfedge", 2 * e),
        "A split is a fixed number of allocations and pointer writes; look for a loop that never ends.",
        _split_problem, lambda mesh, e, log=None: split(mesh, e, log=log),
        "Four triangles around the new vertex, +1 vertex, +3 edges, +2 faces, and the mesh stays valid.",
    ), len(cases))


# --------------------------------------------------------------------------------------
# check_collapse_steps: chapter 07's intermediate checks, one per phase of the collapse
# --------------------------------------------------------------------------------------

#: Chapter 07's phases, by the last step each one ends with.
COLLAPSE_PHASES = {2: "move vA and reassign vB's halfedges (steps 1 and 2)",
                   4: "relink h_A_L and h_R_A in place of h_B_L and h_R_B (steps 3 and 4)",
                   5: "give vL, vR and vA live halfedges (step 5)",
                   6: "delete (step 6): the whole collapse"}


def _phase_problem(before: HalfedgeMesh, yours: HalfedgeMesh, h: int, upto: int) -> tuple[str, tuple] | None:
    """What steps 1..``upto`` of the chapter's collapse got wrong on ``yours``, or None."""
    log = OperationLog()
    wanted = before.copy()
    collapse(wanted, wanted.halfedge(h), log=log)
    ids = {n: index for n, (_, index) in log.named.items()}
    vA, vB = ids["vA"], ids["vB"]
    midpoint = 0.5 * (before.positions[vA] + before.positions[vB])
    if not np.allclose(yours.positions[vA], midpoint):
        return (f"step 1: vA = {vA} is at {np.round(yours.positions[vA], 4).tolist()}, not at the edge's midpoint "
                f"{np.round(midpoint, 4).tolist()}.", ("vertex", vA))
    skipped = {ids["h_BA"], ids["h_L_B"] ^ 1, ids["h_B_R"]}
    for g in before.vertex(vB).outgoing():
        if g.index not in skipped and yours.halfedge_vertex[g.index] != vA:
            return (f"step 2: halfedge {g.index} left vB = {vB}; it should now leave vA = {vA}, but yours leaves "
                    f"{int(yours.halfedge_vertex[g.index])}.", ("halfedge", g.index))
    if upto < 4:
        return None
    for new, old in (("h_A_L", "h_B_L"), ("h_R_A", "h_R_B")):
        g = ids[new]
        for array, word in (("halfedge_next", "next"), ("halfedge_prev", "prev"), ("halfedge_face", "face")):
            if getattr(yours, array)[g] != getattr(wanted, array)[g]:
                return (f"step {3 if new == 'h_A_L' else 4}: {new} = halfedge {g} takes the place of {old} = "
                        f"halfedge {ids[old]}, so its {word} should be {int(getattr(wanted, array)[g])} (what {old}'s "
                        f"was, read before you change anything of it), but yours is {int(getattr(yours, array)[g])}.",
                        ("halfedge", g))
    if upto < 5:
        return None
    going = {ids["h_BA"] >> 1, ids["h_L_B"] >> 1, ids["h_B_R"] >> 1}
    for name in ("vL", "vR", "vA"):
        v = ids[name]
        g = int(yours.vertex_halfedge[v])
        if yours.halfedge_vertex[g] != v or (g >> 1) in going:
            return (f"step 5: {name} = vertex {v}'s halfedge is {g}, which "
                    f"{'is on an edge that step 6 deletes' if (g >> 1) in going else 'does not leave it'}; point it "
                    f"at a live halfedge that leaves {name}.", ("vertex", v))
    return None


def check_collapse_steps(learner_collapse: Callable, upto: int) -> CheckResult:
    """Chapter 07's intermediate check: the steps of ``learner_collapse`` up to ``upto`` (2, 4,
    5 or 6), on ``single_collapse`` and the cube's two cases, before the rest is written.

    It runs the learner's function (steps after ``upto`` may still be missing) and
    compares only what steps 1 to ``upto`` change with the library's collapse, in the
    chapter's numbering (``h_A_L`` and ``h_R_A`` are the edges kept). ``upto=6`` is
    :func:`check_collapse` itself.
    """
    if upto not in COLLAPSE_PHASES:
        raise ValueError(f"upto must be one of {sorted(COLLAPSE_PHASES)}, the last step of a phase; got {upto!r}")
    if upto == 6:
        return check_collapse(learner_collapse)
    name = "collapse"
    cases = [(case, mesh, steps) for case, mesh, steps in collapse_cases()[:3]]
    checked: list[str] = []
    for case, mesh, steps in cases:
        h = steps[0]
        yours = mesh.copy()
        status, answer = harness.run(learner_collapse, yours, h)
        trouble = harness.trouble(status, answer, name)
        if trouble:
            return harness.counted(harness.failed(name, checked, case, f"collapsing halfedge {h}, {trouble}",
                                                  ("halfedge", h), mesh, error=answer), len(cases))
        problem = _phase_problem(mesh, yours, h, upto)
        if problem is not None:
            text, element = problem
            return harness.counted(harness.failed(name, checked, case, f"collapsing halfedge {h}, {text}", element,
                                                  mesh, names=_picture_names(
                                                      lambda m, s, log=None: collapse(m, m.halfedge(s), log=log),
                                                      mesh, h)), len(cases))
        checked.append(case)
    following = min(k for k in COLLAPSE_PHASES if k > upto)
    return harness.counted(harness.passed(name, checked, f"Steps 1 to {upto} are right. Next: "
                                          f"{COLLAPSE_PHASES[following]}, then check_collapse_steps(my_collapse, "
                                          f"{following})."), len(cases))
