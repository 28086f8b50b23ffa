"""Checks for chapter 09's exercises: Loop's edge and vertex points, and the 4-to-1 split.

    from halfedge_edu.exercises.loop_checks import check_loop_rules, check_upsample_connectivity
    check_loop_rules(edge_point, vertex_point)
    check_upsample_connectivity(upsample)

Each check calls the learner's function on a few small meshes, compares every answer
with the library (:func:`~halfedge_edu.algorithms.loop.loop_positions`, the
connectivity of :func:`~halfedge_edu.algorithms.loop.loop_subdivide`), and at the
first difference says in words what is wrong: which element, what was expected and
why, and, where the answer matches a common slip (a midpoint instead of an edge point,
``3/(8n)`` for a vertex of degree 3, every edge split with no flips), which slip it is.
The contracts:

* ``edge_point(mesh, edge) -> (3,)`` and ``vertex_point(mesh, vertex) -> (3,)``: the
  new position of one edge's edge point and of one old vertex, read from the old
  mesh (``edge`` and ``vertex`` are handles); the mesh must not be changed.
* ``upsample(mesh) -> HalfedgeMesh``: the 4-to-1 split (every old edge split, then
  the new edges that join an old and a new vertex flipped); it may work in place.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from halfedge_edu.algorithms.loop import loop_positions
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.data import sample

from . import harness, hidden
from .harness import CheckResult, hidden_name

__all__ = ["check_loop_rules", "check_upsample_connectivity", "loop_cases", "loop_original_beta", "warren_beta"]


# --------------------------------------------------------------------------------------
# Chapter 09: Loop's edge points and vertex points
# --------------------------------------------------------------------------------------

def warren_beta(n: int) -> float:
    """Warren's weight of each neighbour of an interior vertex of degree ``n``."""
    return 3.0 / 16.0 if n == 3 else 3.0 / (8.0 * n)


def _jittered(mesh: HalfedgeMesh, seed: int, amount: float = 0.08) -> HalfedgeMesh:
    """The same mesh with every vertex nudged (symmetric shapes can hide a wrong weight)."""
    mesh = mesh.copy()
    rng = np.random.default_rng(seed)
    mesh.positions[:] += amount * rng.standard_normal(mesh.positions.shape)
    return mesh


def loop_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh]]:
    """The meshes ``check_loop_rules`` uses, in order: degree 3, 4, 5-6, mixed, boundary.

    With a ``seed``, the hidden cases: two closed meshes after random flips (degrees
    from 3 to 8 or so), nudged, and a nudged grid patch (a boundary).
    """
    if seed is not None:
        rng = harness.hidden_rng(seed)
        first, second = (str(name) for name in rng.choice(["tetrahedron", "cube", "octahedron", "icosphere(1)"], 2,
                                                          replace=False))
        flips = [int(n) for n in rng.integers(2, 8, 2)]
        rows, columns = (int(n) for n in rng.integers(2, 4, 2))
        return [
            (hidden_name(1, f"{first} after {flips[0]} random flips, nudged"),
             hidden.jittered(hidden.flipped(hidden.closed_mesh(first), flips[0], rng), rng, 0.05)),
            (hidden_name(2, f"{second} after {flips[1]} random flips, nudged"),
             hidden.jittered(hidden.flipped(hidden.closed_mesh(second), flips[1], rng), rng, 0.05)),
            (hidden_name(3, f"a {rows} x {columns} grid patch (a boundary)"),
             HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng))),
        ]
    return [
        ("tetrahedron (every vertex of degree 3)", _jittered(sample("tetrahedron"), 1)),
        ("octahedron (degree 4)", _jittered(sample("octahedron"), 2)),
        ("icosphere (degrees 5 and 6)", _jittered(sample("icosphere", subdivisions=1), 3, 0.03)),
        ("cube (degrees 3 to 6)", _jittered(sample("cube"), 4)),
        ("open patch (a boundary)", _jittered(sample("open_patch"), 5)),
        ("strip (every vertex on the boundary)", _jittered(sample("strip"), 6)),
    ]


def _edge_story(mesh: HalfedgeMesh, e: int) -> tuple[int, int, int | None, int | None]:
    """Ends a, b and opposite corners c (beside halfedge 2e) and d (beside 2e + 1); None on the boundary."""
    h = mesh.halfedge(2 * e)
    a, b = h.vertex.index, h.tip.index
    c = None if h.face is None else h.prev.vertex.index
    d = None if h.twin.face is None else h.twin.prev.vertex.index
    return a, b, c, d


def _edge_problem(mesh: HalfedgeMesh, e: int, yours: np.ndarray, wanted: np.ndarray) -> str:
    P = mesh.positions
    a, b, c, d = _edge_story(mesh, e)
    where = f"edge {e} joins vertices {a} and {b}"
    midpoint = 0.5 * (P[a] + P[b])
    if c is None or d is None:
        text = (f"{where} and lies on the boundary (only one triangle touches it), so its edge point is "
                f"the midpoint (a + b) / 2 = {harness.point_text(wanted)}; yours is {harness.point_text(yours)}.")
        one = c if c is not None else d
        if harness.close(yours, 0.375 * (P[a] + P[b]) + 0.125 * P[one]) or harness.close(yours, 0.375 * (P[a] + P[b]) + 0.25 * P[one]):
            text += (" You used the interior rule with the one opposite corner there is. On the boundary the "
                     "inside must not count, so that the boundary is refined as a curve of its own.")
        return text
    text = (f"{where}; its two triangles have the opposite corners {c} and {d}, so the edge point is "
            f"3/8 (a + b) + 1/8 (c + d) = {harness.point_text(wanted)}; yours is {harness.point_text(yours)}.")
    if harness.close(yours, midpoint):
        text += (" That is the midpoint. The edge point is pulled a little towards the two opposite corners "
                 "(the 'wings'); that pull is what makes the limit surface smooth.")
    elif harness.close(yours, 0.125 * (P[a] + P[b]) + 0.375 * (P[c] + P[d])):
        text += " The weights are swapped: the edge's own ends get 3/8 each, the opposite corners 1/8."
    elif harness.close(yours, 0.375 * (P[a] + P[b]) + 0.25 * P[c]) or harness.close(yours, 0.375 * (P[a] + P[b]) + 0.25 * P[d]):
        text += (" Yours counts one opposite corner twice: c is opposite the edge in the face of h, d in the "
                 "face of h.twin (h.prev.vertex and h.twin.prev.vertex).")
    return text


def _vertex_problem(mesh: HalfedgeMesh, v: int, yours: np.ndarray, wanted: np.ndarray) -> str:
    P = mesh.positions
    vertex = mesh.vertex(v)
    ring = [u.index for u in vertex.neighbors()]
    n = len(ring)
    ring_sum = P[ring].sum(axis=0)
    if vertex.is_boundary:
        out = vertex.halfedge                       # the outgoing boundary halfedge
        after, before = out.tip.index, out.prev.vertex.index
        text = (f"vertex {v} is on the boundary; its neighbours along the boundary are {before} and {after}, so it "
                f"moves to 3/4 v + 1/8 ({before} + {after}) = {harness.point_text(wanted)}; yours is {harness.point_text(yours)}.")
        beta = warren_beta(n)
        if harness.close(yours, (1 - n * beta) * P[v] + beta * ring_sum):
            text += (" You used the interior rule over all its neighbours. A boundary vertex only listens to "
                     "its two boundary neighbours, so the boundary stays a curve of its own.")
        elif harness.close(yours, P[v]):
            text += " The old boundary vertices move too (unless you pin them on purpose, which the course does not)."
        return text
    beta = warren_beta(n)
    text = (f"vertex {v} is inside with degree n = {n} (neighbours {ring}); Warren's beta is "
            f"{'3/16' if n == 3 else f'3/(8 * {n})'} = {beta:.6g}, so it moves to (1 - n beta) v + beta * "
            f"(sum of the neighbours) = {harness.point_text(wanted)}; yours is {harness.point_text(yours)}.")
    if n == 3 and harness.close(yours, (1 - 3 * (1.0 / 8.0)) * P[v] + (1.0 / 8.0) * ring_sum):
        text += " You used 3/(8n) = 1/8, but for degree 3 Warren's rule has its own value, beta = 3/16."
    elif harness.close(yours, P[v]):
        text += " The old vertices move too: each becomes a weighted average of itself and its ring."
    elif harness.close(yours, ring_sum / n):
        text += " That is the mean of the neighbours (Laplacian smoothing); Loop keeps the largest share, 1 - n beta, for v itself."
    elif harness.close(yours, beta * ring_sum):
        text += " The vertex's own share, (1 - n beta) v, is missing."
    elif harness.close(yours, (1 - beta) * P[v] + beta * ring_sum):
        text += " The vertex's own weight is 1 - n beta (so that all weights add up to 1), not 1 - beta."
    return text


def check_loop_rules(edge_point: Callable | None = None, vertex_point: Callable | None = None, *,
                     seed: int | None = None) -> CheckResult:
    """Compare the learner's Loop rules with ``loop_positions`` on six small meshes.

    Args:
        edge_point: ``edge_point(mesh, edge) -> (3,)`` the new vertex on ``edge``.
        vertex_point: ``vertex_point(mesh, vertex) -> (3,)`` where old ``vertex`` moves.
            Either may be None, to check only the other one.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.

    Returns:
        A :class:`CheckResult`; on the first difference it names the mesh and element,
        the rule with its numbers, and a likely slip; ``result.show()`` draws the element.
    """
    functions = [(name, f) for name, f in (("edge_point", edge_point), ("vertex_point", vertex_point)) if f is not None]
    label = " and ".join(name for name, _ in functions) or "Loop rules"
    if not functions:
        return harness.failed(label, [], None, "give check_loop_rules your edge_point, your vertex_point, or both.")
    cases = loop_cases(seed)
    for name, function in functions:
        if (blanks := harness.blanks_left(label, len(cases), function, name)) is not None:
            return blanks
    return harness.counted(_check_loop_rules(functions, label, cases), len(cases))


def loop_original_beta(n: int) -> float:
    """Loop's own weight of each neighbour of an interior vertex of degree ``n`` (the cos rule)."""
    return (5.0 / 8.0 - (3.0 / 8.0 + 0.25 * np.cos(2.0 * np.pi / n)) ** 2) / n


def _vertex_point_with(mesh: HalfedgeMesh, v: int, beta: Callable[[int], float]) -> np.ndarray:
    """(3,) where interior vertex ``v`` moves with the neighbour weight ``beta(n)``."""
    ring = [u.index for u in mesh.vertex(v).neighbors()]
    n = len(ring)
    return (1.0 - n * beta(n)) * mesh.positions[v] + beta(n) * mesh.positions[ring].sum(axis=0)


#: The two weightings the Loop assignment lets a student choose ("document which one you used").
_BETAS = {"Warren's": warren_beta, "Loop's original": loop_original_beta}

_CLOSED_ONLY_NOTE = (
    "Your rules were judged on the closed meshes only: the Loop assignment asks only for meshes without "
    "boundary, so rules that do not handle one are right there. On {case}, at the boundary, {words} "
    "(Chapter 09's boundary rules are what you need for open meshes.)")


def _check_loop_rules(functions: list[tuple[str, Callable]], label: str,
                      cases: list[tuple[str, HalfedgeMesh]]) -> CheckResult:
    """:func:`check_loop_rules` on the given cases.

    Two conventions of the Loop assignment are recognised and said: Loop's original
    beta instead of Warren's (the same choice at every vertex), and rules for closed
    meshes only (a boundary element that disagrees or raises does not fail the check; the
    mesh is judged on its interior and the congratulation says what the boundary got).
    """
    checked: list[str] = []
    beta_rule: tuple[str, str] | None = None     # (which beta, where it was first told apart)
    boundary_note: str | None = None             # the first boundary element that used a closed-only rule
    for case, mesh in cases:
        vertex_points, edge_points = loop_positions(mesh)
        before = mesh.positions.copy()
        for name, function in functions:
            elements = mesh.edges if name == "edge_point" else mesh.vertices
            for element in elements:
                status, answer = harness.run(function, mesh, element)
                trouble = harness.trouble(status, answer, name)
                kind = ("halfedge", 2 * element.index) if name == "edge_point" else ("vertex", element.index)
                what = f"edge {element.index}" if name == "edge_point" else f"vertex {element.index}"
                on_boundary = element.is_boundary
                if trouble and on_boundary and status == "error" and not trouble.startswith(name):
                    boundary_note = boundary_note or _CLOSED_ONLY_NOTE.format(case=repr(case), words=f"on {what}, {trouble}")
                    continue
                if trouble:
                    return harness.failed(label, checked, case, f"on {what}, {trouble}", kind, mesh, error=answer)
                if not np.array_equal(mesh.positions, before):
                    return harness.failed(label, checked, case,
                                   f"your {name} changed mesh.positions (at {what}). Every new position must be "
                                   f"computed from the old mesh, before anything moves: read the positions, never "
                                   f"write them.", kind, mesh)
                yours = harness.as_point(answer)
                if yours is None:
                    return harness.failed(label, checked, case, f"your {name} should return 3 numbers (a position), but for "
                                   f"{what} it returned {answer!r:.80}.", kind, mesh)
                wanted = edge_points[element.index] if name == "edge_point" else vertex_points[element.index]
                if name == "vertex_point" and not on_boundary:
                    matching = [rule for rule, beta in _BETAS.items()
                                if harness.close(yours, _vertex_point_with(mesh, element.index, beta))]
                    if len(matching) == 1:                # the two rules differ here (degree not 3 or 6)
                        if beta_rule and beta_rule[0] != matching[0]:
                            return harness.failed(label, checked, case, (
                                f"at {what} your vertex point uses {matching[0]} beta, but at {beta_rule[1]} it "
                                f"used {beta_rule[0]}: choose one weighting and use it at every vertex."), kind, mesh)
                        beta_rule = beta_rule or (matching[0], f"{what} of {case!r}")
                    if matching:
                        continue
                if not harness.close(yours, wanted):
                    explain = _edge_problem if name == "edge_point" else _vertex_problem
                    words = explain(mesh, element.index, yours, wanted)
                    if on_boundary:
                        boundary_note = boundary_note or _CLOSED_ONLY_NOTE.format(case=repr(case), words=words)
                        continue
                    return harness.failed(label, checked, case, words, kind, mesh)
        checked.append(case if case.startswith("hidden") else case.split(" (")[0])
    praise = "Together they are one level of Loop's positions; the connectivity is the 4-to-1 split you stepped through."
    if beta_rule and beta_rule[0] != "Warren's":
        praise += (" Your vertex points use Loop's original beta, (5/8 - (3/8 + 1/4 cos(2 pi / n))^2) / n, which "
                   "the Loop assignment lets you choose (document it in your README); the chapter and the library "
                   "use Warren's simpler 3/16 for n = 3 and 3/(8n) otherwise. The two agree at degrees 3 and 6.")
    if boundary_note:
        if all(any(mesh.vertex(v.index).is_boundary for v in mesh.vertices) for _, mesh in cases):
            return harness.failed(label, [], None, "every mesh here has a boundary and your rules do not handle "
                                  "it, so they cannot be judged on a closed one. " + boundary_note)
        praise += " " + boundary_note
    return harness.all_good(label, checked, "meshes", praise)


# --------------------------------------------------------------------------------------
# Chapter 09, second exercise: the 4-to-1 connectivity (CS184's and CMU's upsample)
# --------------------------------------------------------------------------------------

def _upsample_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh]]:
    """Closed meshes (the two courses' upsampling assumes no boundary) of several degrees;
    with a ``seed``, the hidden cases: closed meshes after random flips, nudged."""
    if seed is None:
        return [("tetrahedron", _jittered(sample("tetrahedron"), 11)), ("octahedron", _jittered(sample("octahedron"), 12)),
                ("cube", _jittered(sample("cube"), 13))]
    rng = harness.hidden_rng(seed)
    cases = []
    for number, shape in enumerate(rng.choice(["tetrahedron", "cube", "octahedron", "icosphere(1)"], 3, replace=False),
                                   start=1):
        flips = int(rng.integers(0, 5))
        mesh = hidden.jittered(hidden.flipped(hidden.closed_mesh(str(shape)), flips, rng), rng, 0.05)
        cases.append((hidden_name(number, f"{shape} after {flips} random flips, nudged"), mesh))
    return cases


def _faces_by_points(vertices: np.ndarray, faces: np.ndarray) -> set[tuple]:
    """Every face as its corners' rounded positions, turned to start at the smallest."""
    found = set()
    for face in faces.tolist():
        points = [tuple(np.round(vertices[v], 9).tolist()) for v in face]
        k = points.index(min(points))
        found.add(tuple(points[k:] + points[:k]))
    return found


def _split_only(mesh: HalfedgeMesh) -> HalfedgeMesh:
    """The slip's result: every old edge split at its midpoint, no flips."""
    from halfedge_edu.core.ops import split

    work = mesh.copy()
    for e in range(mesh.n_edge_slots):
        split(work, e)
    return work


def check_upsample_connectivity(upsample: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare the learner's ``upsample(mesh) -> HalfedgeMesh`` (the 4-to-1 split by
    splitting every old edge, then flipping the new edges that join an old and a new
    vertex) with ``loop_subdivide``'s connectivity.

    The new vertices may sit at the edges' midpoints (connectivity only) or at Loop's
    positions (Warren's weights); either is recognised. The mesh passed in may be changed
    (the function may work in place and return it).

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    from halfedge_edu.algorithms.loop import loop_subdivide

    name = "upsample"
    cases = _upsample_cases(seed)
    if (blanks := harness.blanks_left(name, len(cases), upsample)) is not None:
        return blanks
    checked: list[str] = []
    for case, mesh in cases:
        status, answer = harness.run(upsample, mesh.copy())
        trouble = harness.trouble(status, answer, name)
        if trouble:
            return harness.counted(harness.failed(name, checked, case, trouble, None, mesh, error=answer), len(cases))
        if not isinstance(answer, HalfedgeMesh):
            return harness.counted(harness.failed(name, checked, case, f"upsample should return the subdivided "
                                                  f"HalfedgeMesh, but yours returned {type(answer).__name__}."),
                                   len(cases))
        answer.topology_changed()
        V, E, F = mesh.n_vertices, mesh.n_edges, mesh.n_faces
        counts = (answer.n_vertices, answer.n_edges, answer.n_faces)
        if counts != (V + E, 2 * E + 3 * F, 4 * F):
            text = (f"the result has {counts[0]} vertices, {counts[1]} edges and {counts[2]} faces; the 4-to-1 split "
                    f"of {V} vertices, {E} edges and {F} faces has V + E = {V + E}, 2E + 3F = {2 * E + 3 * F} and 4F = "
                    f"{4 * F}: one new vertex per edge, each old face four.")
            return harness.counted(harness.failed(name, checked, case, text, None, mesh), len(cases))
        subdivided = loop_subdivide(mesh)
        faces = subdivided.to_arrays()[1]
        midpoints = np.vstack([mesh.positions[:V], 0.5 * mesh.positions[mesh.edge_vertices()].sum(axis=1)])
        yours = _faces_by_points(*answer.to_arrays())
        if yours in (_faces_by_points(midpoints, faces), _faces_by_points(subdivided.positions, faces)):
            checked.append(case)
            continue
        text = "the counts are right, but not every old triangle became its four: the centre triangle of three new " \
               "vertices and a corner triangle at each old one."
        if yours == _faces_by_points(*_split_only(mesh).to_arrays()):
            text += (" Yours is every edge split with no flips: some cross edges still join a new vertex to an old "
                     "corner. Flip each new edge that joins an old vertex and a new one (and only those).")
        return harness.counted(harness.failed(name, checked, case, text, None, mesh), len(cases))
    return harness.counted(harness.all_good(name, checked, "meshes", "Every old triangle is four, the connectivity "
                                            "of one level of Loop subdivision."), len(cases))
