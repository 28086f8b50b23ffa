"""Checks for the exercises of chapters 09, 10 and 12: Loop's rules, quadrics, de Casteljau.

    from halfedge_edu.exercises.algorithm_checks import check_loop_rules
    check_loop_rules(edge_point, vertex_point)     # chapter 09
    check_plane_quadric(plane_quadric)             # chapter 10
    check_optimal_point(optimal_point)             # chapter 10
    check_de_casteljau(de_casteljau)               # chapter 12

Each check calls the learner's function on a few small cases, compares every answer
with the library (:func:`~halfedge_edu.algorithms.loop.loop_positions`,
:func:`~halfedge_edu.algorithms.simplify.face_quadrics`, the queue's best point,
:func:`~halfedge_edu.algorithms.bezier.de_casteljau`), and at the first difference says
in words what is wrong: which element, what was expected and why, and, where the
answer matches a common slip (a midpoint instead of an edge point, ``3/(8n)`` for a
vertex of degree 3, a normal not scaled to length 1, ``t`` and ``1 - t`` swapped), which
slip it is. The contracts:

* ``edge_point(mesh, edge) -> (3,)`` and ``vertex_point(mesh, vertex) -> (3,)``: the
  new position of one edge's edge point and of one old vertex, read from the old
  mesh (``edge`` and ``vertex`` are handles); the mesh must not be changed.
* ``plane_quadric(a, b, c) -> (4, 4)``: ``K = p p^T`` with ``p = [n, d]``, ``n`` the
  unit normal of the triangle ``a b c`` and ``d = -n . a`` (no area weight).
* ``optimal_point(Q, a, b) -> (3,)``: the point minimizing ``[x, 1] Q [x, 1]^T``, the
  solution of ``A x = -q`` (``A = Q[:3, :3]``, ``q = Q[:3, 3]``), or the midpoint of
  ``a`` and ``b`` when ``A`` is singular.
* ``de_casteljau(points, t) -> list``: every level, from the control points (level 0)
  to the single point on the curve (level n).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from halfedge_edu.algorithms.bezier import de_casteljau as _de_casteljau
from halfedge_edu.algorithms.loop import loop_positions
from halfedge_edu.algorithms.simplify import face_quadrics, optimal_points
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.data import sample

from . import harness, hidden
from .harness import CheckResult, hidden_name


__all__ = ["check_bezier_patch", "check_downsample", "check_upsample_connectivity", "check_loop_rules", "check_plane_quadric", "check_optimal_point", "check_de_casteljau",
           "patch_point",
           "loop_cases", "loop_original_beta", "warren_beta"]




def _as_point(value, size: int = 3) -> np.ndarray | None:
    try:
        array = np.asarray(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        return None
    return array if array.shape == (size,) else None








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
        unfinished = harness.unfinished(function, name)
        if unfinished:
            return harness.counted(harness.failed(label, [], None, unfinished), len(cases))
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
                yours = _as_point(answer)
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
# Chapter 10: the plane quadric of a face, and the optimal point
# --------------------------------------------------------------------------------------

def _quadric_cases(seed: int | None = None) -> list[tuple[str, np.ndarray]]:
    """Triangles (3, 3) for ``check_plane_quadric``: easy planes first; with a ``seed``,
    the hidden cases: random triangles (not too thin), one far from the origin."""
    if seed is not None:
        rng = harness.hidden_rng(seed)
        cases = []
        for number, (what, offset) in enumerate([("a random triangle", 0.0), ("a random triangle", 1.0),
                                                 ("a random triangle far from the origin", 20.0),
                                                 ("a random small triangle", 0.5)], start=1):
            while True:
                triangle = rng.uniform(-1.0, 1.0, (3, 3)) * (0.05 if "small" in what else 1.0) + offset * rng.standard_normal(3)
                a, b, c = triangle
                area = 0.5 * np.linalg.norm(np.cross(b - a, c - a))
                longest = max(np.linalg.norm(b - a), np.linalg.norm(c - b), np.linalg.norm(a - c))
                if area > 0.1 * longest ** 2:                       # not a sliver: the plane is well defined
                    break
            cases.append((hidden_name(number, what), triangle))
        return cases
    return [
        ("a triangle in the plane z = 0", np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)),
        ("a triangle in the plane z = 2", np.array([[0, 0, 2], [2, 0, 2], [0, 3, 2]], dtype=float)),
        ("a tilted triangle", np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)),
        ("a tilted triangle away from the origin", np.array([[1.5, -0.5, 2.0], [2.5, 0.2, 1.1], [0.7, 1.3, 2.6]])),
        ("a long thin triangle", np.array([[0, 0, 0], [10, 0.1, 0.3], [0, 0.05, 0.02]], dtype=float)),
    ]


def _plain_quadric(a, b, c) -> tuple[np.ndarray, np.ndarray, float]:
    """``(K (4, 4), p (4,), area)`` of one triangle."""
    cross = np.cross(b - a, c - a)
    area = 0.5 * np.linalg.norm(cross)
    quadric = face_quadrics(np.array([a, b, c]), np.array([[0, 1, 2]]))[0] / area
    n = cross / np.linalg.norm(cross)
    return quadric, np.append(n, -n @ a), area


def check_plane_quadric(plane_quadric: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare ``plane_quadric(a, b, c)`` with the library's face quadric (without its area weight).

    Args:
        plane_quadric: ``(a, b, c) -> (4, 4)``, ``K = p p^T`` with ``p = [n, d]``,
            ``n`` the unit normal, ``d = -n . a``.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.
    """
    cases = _quadric_cases(seed)
    unfinished = harness.unfinished(plane_quadric, "plane_quadric")
    if unfinished:
        return harness.counted(harness.failed("plane_quadric", [], None, unfinished), len(cases))
    return harness.counted(_check_plane_quadric(plane_quadric, cases), len(cases))


def _check_plane_quadric(plane_quadric: Callable, cases: list[tuple[str, np.ndarray]]) -> CheckResult:
    """:func:`check_plane_quadric` on the given triangles."""
    checked: list[str] = []
    for case, triangle in cases:
        a, b, c = triangle.copy()
        status, answer = harness.run(plane_quadric, a, b, c)
        trouble = harness.trouble(status, answer, "plane_quadric")
        if trouble:
            return harness.failed("plane_quadric", checked, case, trouble, error=answer)
        try:
            yours = np.asarray(answer, dtype=np.float64)
        except (TypeError, ValueError):
            yours = np.zeros(0)
        if yours.shape != (4, 4):
            return harness.failed("plane_quadric", checked, case, f"plane_quadric should return a 4 x 4 matrix, but yours "
                           f"has shape {yours.shape}. Build p = [nx, ny, nz, d] and return np.outer(p, p).")
        wanted, p, area = _plain_quadric(a, b, c)
        if harness.close(yours, wanted):
            checked.append(case)
            continue
        n, d = p[:3], p[3]
        text = (f"the triangle {harness.point_text(a)}, {harness.point_text(b)}, {harness.point_text(c)} lies in the plane n . x + d = 0 with unit normal "
                f"n = {harness.point_text(n)} and d = {d:.4g}, so K = p p^T with p = {harness.point_text(p)}.")
        raw = np.cross(b - a, c - a)
        if harness.close(yours, area * wanted):
            text += (" Yours is K times the triangle's area. That is what the library stores (big faces count "
                     "more), but the exercise asks for the plain K: leave the area out.")
        elif harness.close(yours, (raw @ raw) * wanted) or harness.close(yours, np.linalg.norm(raw) * wanted):
            text += (" Yours is K times a power of |(b - a) x (c - a)|: the normal must have length 1, or the "
                     "'distance' is measured in the wrong unit. Divide the cross product by its length.")
        elif harness.close(yours, np.outer(np.append(n, -d), np.append(n, -d))):
            text += (" Your d has the wrong sign: d = -n . a, so that n . x + d is 0 for every point x of the "
                     "plane (try x = a).")
        elif harness.close(yours[:3, :3], wanted[:3, :3]) and np.allclose(yours[3], 0) and np.allclose(yours[:, 3], 0):
            text += " The last row and column are zero: d is missing from p (it only vanishes when the plane passes through the origin)."
        elif not np.allclose(yours, yours.T):
            text += " Yours is not symmetric; p p^T always is. Use np.outer(p, p)."
        else:
            x = a + 2.0 * n
            value = np.append(x, 1.0) @ yours @ np.append(x, 1.0)
            text += (f" Test: the point a + 2n is 2 away from the plane, so [x, 1] K [x, 1]^T should be 4; "
                     f"yours gives {value:.4g}.")
        return harness.failed("plane_quadric", checked, case, text)
    return harness.all_good("plane_quadric", checked, "triangles", "[x, 1] K [x, 1]^T is now the squared distance from x to the face's plane.")


def _plane(n, point) -> np.ndarray:
    """(4, 4) the quadric of the plane through ``point`` with normal ``n`` (any length)."""
    n = np.asarray(n, dtype=float) / np.linalg.norm(n)
    p = np.append(n, -n @ np.asarray(point, dtype=float))
    return np.outer(p, p)


def _hidden_optimal_cases(seed: int) -> list[tuple[str, np.ndarray, np.ndarray, np.ndarray, bool]]:
    """The hidden cases of ``check_optimal_point``: sums of random planes, three or more
    (one best point) and one or two (a plane or a line of best points: the midpoint)."""
    rng = harness.hidden_rng(seed)
    cases = []
    for number, (what, count, well_posed) in enumerate([
            ("four random planes", 4, True), ("three random planes", 3, True),
            ("one random plane, counted twice (A is singular)", 1, False),
            ("two random planes meeting in a line (A is singular)", 2, False)], start=1):
        while True:
            normals = rng.standard_normal((count, 3))
            through = rng.uniform(-1.0, 1.0, (count, 3))
            weights = rng.uniform(0.5, 2.0, count)
            Q = sum(w * _plane(n, x) for w, n, x in zip(weights, normals, through))
            if count == 1:
                Q = 2.0 * Q
            singular_values = np.linalg.svd(Q[:3, :3], compute_uv=False)
            if not well_posed or singular_values[-1] > 0.05 * singular_values[0]:
                break                                                # well posed: not nearly singular either
        a, b = rng.uniform(-1.5, 1.5, (2, 3))
        if not well_posed:                                           # both ends on the planes, as on a mesh
            A, q = Q[:3, :3], Q[:3, 3]
            projector = np.linalg.pinv(A) @ A
            a, b = (x - projector @ x - np.linalg.pinv(A) @ q for x in (a, b))
        cases.append((hidden_name(number, what), Q, a, b, well_posed))
    return cases


def _optimal_cases(seed: int | None = None) -> list[tuple[str, np.ndarray, np.ndarray, np.ndarray, bool]]:
    """``(name, Q, a, b, well_posed)`` for ``check_optimal_point``; hidden ones with a ``seed``."""
    if seed is not None:
        return _hidden_optimal_cases(seed)
    plane = _plane

    corner = plane([1, 0, 0], [1, 0, 0]) + plane([0, 1, 0], [0, 2, 0]) + plane([0, 0, 1], [0, 0, 3])
    tilted = plane([1, 1, 0], [1, 0, 0]) + plane([0, 1, 1], [0, 1, 1]) + 0.5 * plane([1, -1, 2], [0.5, 0.5, 0.2])
    flat = 2.0 * plane([0, 0, 1], [0, 0, 0.5])
    ridge = plane([1, 0, 1], [0, 0, 0]) + plane([-1, 0, 1], [0, 0, 0])
    sphere = sample("icosphere", subdivisions=2)
    mesh_q = face_quadrics(sphere.positions, sphere.face_vertices())
    e = sphere.edge(17)
    a_index, b_index = (v.index for v in e.vertices)
    around = {f.index for f in sphere.vertex(a_index).faces()} | {f.index for f in sphere.vertex(b_index).faces()}
    sphere_q = mesh_q[sorted(around)].sum(axis=0)
    return [
        ("the corner of a box (three planes x = 1, y = 2, z = 3)", corner, np.array([0.5, 2.5, 3.0]),
         np.array([1.5, 1.5, 2.5]), True),
        ("three tilted planes", tilted, np.array([0.0, 0.0, 0.0]), np.array([1.0, 1.0, 1.0]), True),
        ("an edge of an icosphere (the quadrics of the faces around both ends)", sphere_q,
         sphere.positions[a_index].copy(), sphere.positions[b_index].copy(), True),
        ("a flat region (one plane z = 0.5: A is singular)", flat, np.array([0.0, 0.0, 0.5]),
         np.array([1.0, 0.4, 0.5]), False),
        ("a ridge (two planes meeting along the y axis: A is singular)", ridge, np.array([0.0, 0.0, 0.0]),
         np.array([0.0, 2.0, 0.0]), False),
        ("a tilted flat region of a mesh (18 coplanar faces: A is singular, but rounding leaves det(A) "
         "about 1e-30, not 0)", *_tilted_flat_region(), False),
    ]


def _tilted_flat_region() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(Q, a, b)``: the summed quadrics of a flat 3 x 3 grid turned out of the axes, and an
    inner edge's ends. Exactly singular on paper; in floating point its determinant is a
    tiny number, not 0, which is what a real mesh's flat region gives."""
    vertices, faces = hidden.grid(3, 3, np.random.default_rng(0), amount=0.0)
    turn, _ = np.linalg.qr(np.array([[1.0, 2.0, 3.0], [0.3, -1.0, 2.0], [2.0, 0.5, -1.0]]))
    vertices = vertices @ turn.T + [0.3, 0.1, 0.2]
    return face_quadrics(vertices, faces).sum(axis=0), vertices[5].copy(), vertices[6].copy()


def check_optimal_point(optimal_point: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare ``optimal_point(Q, a, b)`` with the solution of ``A x = -q`` (midpoint when singular).

    Args:
        optimal_point: ``(Q (4, 4), a (3,), b (3,)) -> (3,)``.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.
    """
    cases = _optimal_cases(seed)
    unfinished = harness.unfinished(optimal_point, "optimal_point")
    if unfinished:
        return harness.counted(harness.failed("optimal_point", [], None, unfinished), len(cases))
    return harness.counted(_check_optimal_point(optimal_point, cases), len(cases))


def _solved_anyway(A: np.ndarray, q: np.ndarray, yours: np.ndarray) -> bool:
    """Whether ``yours`` is what ``np.linalg.solve`` or ``np.linalg.inv`` gives for a singular
    ``A`` whose rounded determinant is not exactly 0 (the exact ``det(A) == 0`` test's slip)."""
    candidates = []
    for solve in (lambda: np.linalg.solve(A, -q), lambda: np.linalg.inv(A) @ -q):
        try:
            candidates.append(solve())
        except np.linalg.LinAlgError:
            pass
    return any(np.allclose(yours, x, rtol=1e-3, atol=1e-6) for x in candidates)


def _check_optimal_point(optimal_point: Callable, cases: list) -> CheckResult:
    """:func:`check_optimal_point` on the given cases (singular A: the midpoint, CMU's and
    the chapter's fallback; in every case here the edge's ends cost least, so the
    library's choice, the best point nearest the midpoint, is the midpoint too)."""
    checked: list[str] = []
    for case, Q, a, b, well_posed in cases:
        status, answer = harness.run(optimal_point, Q.copy(), a.copy(), b.copy())
        if status == "error" and isinstance(answer, np.linalg.LinAlgError):
            return harness.failed("optimal_point", checked, case, f"np.linalg.solve raised LinAlgError ({answer}). A is "
                           f"singular here: many points are equally good (a whole plane or line of them). Check "
                           f"abs(np.linalg.det(A)) first and fall back to the midpoint (a + b) / 2 when it is tiny.")
        trouble = harness.trouble(status, answer, "optimal_point")
        if trouble:
            return harness.failed("optimal_point", checked, case, trouble, error=answer)
        yours = _as_point(answer)
        if yours is None:
            return harness.failed("optimal_point", checked, case, f"optimal_point should return 3 numbers, but yours "
                           f"returned {answer!r:.80}.")
        midpoint = 0.5 * (a + b)
        if well_posed:
            wanted = np.linalg.solve(Q[:3, :3], -Q[:3, 3])
        else:
            wanted = midpoint
        library = optimal_points(Q[None], a[None], b[None])[0][0]
        if harness.close(yours, wanted):
            checked.append(case if case.startswith("hidden") else case.split(" (")[0])
            continue
        cost = lambda x: float(np.append(x, 1.0) @ Q @ np.append(x, 1.0))  # noqa: E731
        text = f"the best point is {harness.point_text(wanted)} (cost {cost(wanted):.3g}); yours is {harness.point_text(yours)} (cost {cost(yours):.3g})."
        if well_posed:
            if harness.close(yours, midpoint):
                text += (" That is the midpoint. Here A = Q[:3, :3] is invertible, so solve A x = -q (q = Q[:3, 3]) "
                         "for the one point of least error; the midpoint is only the fallback.")
            elif harness.close(yours, np.linalg.solve(Q[:3, :3], Q[:3, 3])):
                text += " The sign is off: the gradient of [x, 1] Q [x, 1]^T is 2 (A x + q), zero at A x = -q."
        else:
            text += (" A is singular here (det(A) is 0: every point of a plane or a line costs the same), so the "
                     "course takes the midpoint (a + b) / 2.")
            A, q = Q[:3, :3], Q[:3, 3]
            if np.linalg.det(A) != 0.0 and _solved_anyway(A, q, yours):
                text += (f" Yours is what solving A x = -q gives anyway: det(A) is {np.linalg.det(A):.2g} here, not "
                         f"exactly 0, because every entry of A carries rounding. A test like det(A) == 0 misses it; "
                         f"compare abs(np.linalg.det(A)) (or np.linalg.cond(A)) with a tolerance instead.")
            elif abs(cost(yours) - cost(wanted)) < 1e-9:
                text += (" Yours costs as little, but it can lie far from the edge, and the new vertex would "
                         "wander off; the midpoint keeps it in place.")
            if not harness.close(library, midpoint):
                text += (f" (The library picks {harness.point_text(library)}: of the points that cost least, the one "
                         f"nearest the midpoint.)")
        return harness.failed("optimal_point", checked, case, text)
    return harness.all_good("optimal_point", checked, "quadrics", "That is the point each queue entry stores with its cost.")


# --------------------------------------------------------------------------------------
# Chapter 12: de Casteljau
# --------------------------------------------------------------------------------------

def _casteljau_cases(seed: int | None = None) -> list[tuple[str, np.ndarray, float]]:
    """``(name, control points, t)`` for ``check_de_casteljau``; with a ``seed``, the
    hidden cases: random control points of degree 1 to 6 in 2D and 3D, random t (and t = 1)."""
    if seed is not None:
        rng = harness.hidden_rng(seed)
        cases = []
        for number, (degree, dimension, t) in enumerate([
                (int(rng.integers(2, 4)), 2, float(rng.uniform(0.05, 0.45))),
                (int(rng.integers(3, 7)), 3, float(rng.uniform(0.55, 0.95))),
                (int(rng.integers(1, 5)), 2, 1.0),
                (int(rng.integers(2, 6)), 3, float(rng.uniform(0.0, 1.0)))], start=1):
            points = rng.uniform(-2.0, 2.0, (degree + 1, dimension))
            cases.append((hidden_name(number, f"random degree {degree} curve in {dimension}D at a t of its own"), points, t))
        return cases
    quadratic = np.array([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])
    cubic = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])
    space = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 2.0], [0.0, 2.0, 1.0], [1.0, 3.0, 0.0]])
    return [
        ("a line (degree 1) at t = 0.25", np.array([[0.0, 0.0], [4.0, 2.0]]), 0.25),
        ("a quadratic at t = 0.5", quadratic, 0.5),
        ("a cubic at t = 0.3", cubic, 0.3),
        ("a cubic at t = 0", cubic, 0.0),
        ("a cubic at t = 1", cubic, 1.0),
        ("a degree 4 curve in 3D at t = 0.7", space, 0.7),
    ]


def check_de_casteljau(de_casteljau: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare the learner's ``de_casteljau(points, t)`` (every level) with the library's.

    Args:
        de_casteljau: ``(points (n + 1, d), t) -> list`` of ``n + 1`` levels, level k
            holding ``n + 1 - k`` points.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.
    """
    cases = _casteljau_cases(seed)
    unfinished = harness.unfinished(de_casteljau, "de_casteljau")
    if unfinished:
        return harness.counted(harness.failed("de_casteljau", [], None, unfinished), len(cases))
    return harness.counted(_check_de_casteljau(de_casteljau, cases), len(cases))


def _check_de_casteljau(de_casteljau: Callable, cases: list[tuple[str, np.ndarray, float]]) -> CheckResult:
    """:func:`check_de_casteljau` on the given cases."""
    checked: list[str] = []
    for case, points, t in cases:
        given = points.copy()
        status, answer = harness.run(de_casteljau, given, t)
        trouble = harness.trouble(status, answer, "de_casteljau")
        if trouble:
            return harness.failed("de_casteljau", checked, case, trouble, error=answer)
        if not np.array_equal(given, points):
            return harness.failed("de_casteljau", checked, case, "your de_casteljau changed the control points it was "
                           "given. Build each level as a new array (or list) instead of overwriting the input.")
        wanted = _de_casteljau(points, t)
        n = len(points) - 1
        try:
            levels = [np.asarray(level, dtype=np.float64).reshape(-1, points.shape[1]) for level in answer]
        except (TypeError, ValueError):
            levels = None
        if levels is None or (len(levels) and np.ndim(answer[0]) == 0):
            return harness.failed("de_casteljau", checked, case, f"de_casteljau should return a list of levels (arrays of "
                           f"points), but yours returned {answer!r:.80}.")
        if len(levels) == n and n > 0 and all(len(levels[k]) == n - k for k in range(n)):
            return harness.failed("de_casteljau", checked, case, f"a degree {n} curve has {n + 1} levels, but yours has {n}: "
                           f"level 0, the control points themselves, is missing. Start the list with them.")
        if len(levels) != n + 1:
            return harness.failed("de_casteljau", checked, case, f"a degree {n} curve ({n + 1} control points) has "
                           f"{n + 1} levels, from {n + 1} points down to 1, but yours has {len(levels)}.")
        for k, (mine, right) in enumerate(zip(levels, wanted)):
            if len(mine) != len(right):
                return harness.failed("de_casteljau", checked, case, f"level {k} should have {len(right)} points (one fewer "
                               f"than level {k - 1}), but yours has {len(mine)}." if k else
                               f"level 0 should be the {len(right)} control points, but yours has {len(mine)} points.")
            if not harness.close(mine, right):
                i = int(np.flatnonzero(~np.isclose(mine, right).all(axis=1))[0])
                text = (f"at t = {t:g}, point {i} of level {k} should be (1 - t) * level[{k - 1}][{i}] + t * "
                        f"level[{k - 1}][{i + 1}] = {harness.point_text(right[i])}, but yours is {harness.point_text(mine[i])}."
                        if k else f"level 0 should be the control points themselves; point {i} differs.")
                swapped = _de_casteljau(points, 1.0 - t)
                if k and harness.close(mine, swapped[k]):
                    text += (" You swapped t and 1 - t: with (1 - t) P_i + t P_(i+1), t = 0 gives P_0 and the "
                             "curve runs from P_0 to P_n as t goes from 0 to 1.")
                elif k and harness.close(mine[i], 0.5 * (wanted[k - 1][i] + wanted[k - 1][i + 1])):
                    text += " Yours is the midpoint: that is the construction at t = 0.5 only; use t."
                return harness.failed("de_casteljau", checked, case, text)
        checked.append(case)
    return harness.all_good("de_casteljau", checked, "curves", "The last level is the curve's point; the levels are the construction lines.")


# --------------------------------------------------------------------------------------
# Chapter 12, second exercise: a point of a Bezier patch (CS184's BezierPatch::evaluate)
# --------------------------------------------------------------------------------------

def patch_point(grid: np.ndarray, u: float, v: float) -> np.ndarray:
    """(3,) the chapter's ``S(u, v)``: ``u`` runs down the columns (first index), ``v`` along the rows."""
    columns = np.array([_de_casteljau(grid[:, j], u)[-1][0] for j in range(grid.shape[1])])
    return _de_casteljau(columns, v)[-1][0]


def _patch_cases(seed: int | None = None) -> list[tuple[str, np.ndarray, list[tuple[float, float]]]]:
    """``(name, grid (m + 1, n + 1, 3), [(u, v), ...])`` for ``check_bezier_patch``: lopsided
    grids (so that swapping u and v shows), corners and inner parameters, a grid that is
    not 4 x 4. With a ``seed``, the hidden cases: random grids and parameters."""
    rng = np.random.default_rng(12) if seed is None else harness.hidden_rng(seed)
    if seed is None:
        flat = np.stack([*np.meshgrid(np.arange(4.0), np.arange(4.0), indexing="ij"), np.zeros((4, 4))], axis=-1)
        raised = flat.copy()
        raised[1, 2, 2] = 3.0
        raised[2, 1, 2] = -1.0
        wide = np.concatenate([rng.uniform(-1, 1, (3, 5, 2)), rng.uniform(0, 2, (3, 5, 1))], axis=-1)
        return [
            ("a 4 x 4 grid with two points moved, at its corners", raised, [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]),
            ("the same grid inside", raised, [(0.2, 0.7), (0.5, 0.5), (0.9, 0.3)]),
            ("a 3 x 5 grid (degree 2 by 4)", wide, [(0.3, 0.6), (0.75, 0.1)]),
        ]
    cases = []
    for number, shape in enumerate([(4, 4), (3, 5), (5, 3)], start=1):
        grid = rng.uniform(-2.0, 2.0, (*shape, 3))
        parameters = [tuple(float(x) for x in rng.uniform(0.05, 0.95, 2)) for _ in range(3)]
        cases.append((hidden_name(number, f"a random {shape[0]} x {shape[1]} grid at three (u, v) of its own"), grid,
                      parameters))
    return cases


def check_bezier_patch(patch_point_function: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare the learner's ``patch_point(grid, u, v) -> (3,)`` with the Bezier surface.

    Two conventions are right, the same one at every point: the chapter's (``u`` down
    the columns, the grid's first index) and CS184's (``u`` along each row, the second
    index, so its ``S(u, v)`` is the chapter's ``S(v, u)``); the congratulation says
    which one it recognised.

    Args:
        patch_point_function: ``(grid (m + 1, n + 1, 3), u, v) -> (3,)``.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.
    """
    name = "patch_point"
    cases = _patch_cases(seed)
    if (words := harness.unfinished(patch_point_function, name)) is not None:
        return harness.counted(harness.failed(name, [], None, words), len(cases))
    return harness.counted(_check_bezier_patch(patch_point_function, cases), len(cases))


def _check_bezier_patch(patch_point_function: Callable, cases: list) -> CheckResult:
    """:func:`check_bezier_patch` on the given cases."""
    name = "patch_point"
    checked: list[str] = []
    convention: tuple[str, str] | None = None        # which one, and where it was first told apart
    for case, grid, parameters in cases:
        for u, v in parameters:
            given = grid.copy()
            status, answer = harness.run(patch_point_function, given, u, v)
            trouble = harness.trouble(status, answer, name)
            where = f"at (u, v) = ({u:g}, {v:g})"
            if trouble:
                return harness.failed(name, checked, case, f"{where}, {trouble}", error=answer)
            if not np.array_equal(given, grid):
                return harness.failed(name, checked, case, "your patch_point changed the control grid; build each "
                                      "row of points as a new array instead.")
            yours = _as_point(answer)
            if yours is None:
                return harness.failed(name, checked, case, f"patch_point should return one point (3 numbers), but "
                                      f"{where} yours returned {answer!r:.80}.")
            chapter, cs184 = patch_point(grid, u, v), patch_point(grid, v, u)
            matching = [label for label, point in (("the chapter's", chapter), ("CS184's", cs184))
                        if harness.close(yours, point)]
            if len(matching) == 1:
                if convention and convention[0] != matching[0]:
                    return harness.failed(name, checked, case, (
                        f"{where} your point follows {matching[0]} convention, but {convention[1]} it followed "
                        f"{convention[0]}: u must run along the same index of the grid every time."))
                convention = convention or (matching[0], f"{where} of {case!r}")
            if matching:
                continue
            text = (f"{where} the surface point is {harness.point_text(chapter)} (u down the columns, as the "
                    f"chapter) or {harness.point_text(cs184)} (u along the rows, as CS184); yours is "
                    f"{harness.point_text(yours)}.")
            corners = grid[[0, 0, -1, -1], [0, -1, 0, -1]]
            bilinear = ((1 - u) * (1 - v) * corners[0] + (1 - u) * v * corners[1] + u * (1 - v) * corners[2]
                        + u * v * corners[3])
            if harness.close(yours, patch_point(grid, 1 - u, 1 - v)) or harness.close(yours, patch_point(grid, 1 - v, 1 - u)):
                text += " You swapped t and 1 - t in de Casteljau's step: (1 - t) P_i + t P_(i+1)."
            elif harness.close(yours, bilinear):
                text += (" That mixes the four corners only (bilinear); every control point counts: run de Casteljau "
                         "over each column at u, then once more over those points at v.")
            elif any(harness.close(yours, _de_casteljau(grid[:, j], u)[-1][0]) for j in range(grid.shape[1])):
                text += (" That is a point of one column's curve at u: run the second pass too, through the points of "
                         "all the columns, at v.")
            return harness.failed(name, checked, case, text)
        checked.append(case)
    words = "Your patch_point evaluates the surface: de Casteljau down each column, then once across."
    if convention and convention[0] == "CS184's":
        words = ("Your patch_point follows CS184's convention (u along each row of the grid, its second index), "
                 "correct there; the chapter and hx.bezier_surface_points run u down the columns, so your S(u, v) "
                 "is the chapter's S(v, u) (or pass grid.transpose(1, 0, 2)).")
    return harness.all_good(name, checked, "grids", words)


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
    if (words := harness.unfinished(upsample, name)) is not None:
        return harness.counted(harness.failed(name, [], None, words), len(cases))
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


# --------------------------------------------------------------------------------------
# Chapter 10, the whole loop: CMU's downsampling (a priority queue of quadric costs)
# --------------------------------------------------------------------------------------

def _flat_faced(mesh: HalfedgeMesh, levels: int) -> HalfedgeMesh:
    """``mesh`` with every triangle cut 4-to-1 ``levels`` times, new vertices at midpoints:
    the same flat faces, many more triangles."""
    from halfedge_edu.algorithms.loop import loop_subdivide

    for _ in range(levels):
        finer = loop_subdivide(mesh)
        midpoints = 0.5 * mesh.positions[mesh.edge_vertices()].sum(axis=1)
        positions = np.vstack([mesh.positions[: mesh.n_vertices], midpoints])
        mesh = HalfedgeMesh.from_faces(positions, finer.to_arrays()[1])
    return mesh


def _downsample_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh, int, np.ndarray | None]]:
    """``(name, mesh, target_faces, corners)``: flat-faced solids whose corners a right loop
    keeps exactly (``corners`` (k, 3)), and a sphere whose error is compared with the library's
    (``corners`` None)."""
    if seed is None:
        cube = _flat_faced(sample("cube"), 2)
        return [("a cube of 192 flat triangles, down to 12", cube, 12, sample("cube").positions.copy()),
                ("an icosphere(2), down to 80 faces", sample("icosphere", subdivisions=2), 80, None)]
    rng = harness.hidden_rng(seed)
    turn, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    scale, shift = rng.uniform(0.5, 2.0, 3), rng.uniform(-2.0, 2.0, 3)
    cube = _flat_faced(sample("cube"), 2)
    cube.positions[:] = (cube.positions * scale) @ turn.T + shift
    octahedron = _flat_faced(sample("octahedron"), 2)
    sphere = sample("icosphere", subdivisions=2)
    sphere.positions[:] = sphere.positions @ turn.T
    target = int(rng.integers(30, 45)) * 2
    return [
        (hidden_name(1, "a stretched, turned cube of 192 flat triangles, down to 12"), cube, 12,
         (sample("cube").positions * scale) @ turn.T + shift),
        (hidden_name(2, "an octahedron of 128 flat triangles, down to 8"), octahedron, 8, sample("octahedron").positions.copy()),
        (hidden_name(3, f"a turned icosphere(2), down to {target} faces"), sphere, target, None),
    ]


#: Seconds a learner's whole downsampling loop may take on one case (a Python loop of
#: collapses with quadrics; the solution takes about 0.3 s on the larger case).
DOWNSAMPLE_SECONDS = 10.0


def check_downsample(downsample: Callable, *, seed: int | None = None) -> CheckResult:
    """Run the learner's ``downsample(mesh, target_faces) -> HalfedgeMesh`` (CMU's quadric
    simplification: a priority queue of edges by quadric cost, pop the cheapest, collapse
    it to its optimal point, update the costs around the new vertex).

    Judged by what the loop must achieve, not by its order of collapses (ties may fall
    either way): a valid mesh of ``target_faces`` faces (or one fewer); on a solid of flat
    faces, only its corners left, exactly where they were; on a sphere, an error no more
    than twice the library's (``simplify_sequential``).

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    from halfedge_edu.algorithms.simplify_queue import simplify_sequential
    from halfedge_edu.core.errors import MeshInvariantError

    name = "downsample"
    cases = _downsample_cases(seed)
    if (words := harness.unfinished(downsample, name)) is not None:
        return harness.counted(harness.failed(name, [], None, words), len(cases))
    checked: list[str] = []
    for case, mesh, target, corners in cases:
        status, answer = harness.run(downsample, mesh.copy(), target, seconds=DOWNSAMPLE_SECONDS)
        trouble = harness.trouble(status, answer, name)
        if trouble:
            return harness.counted(harness.failed(name, checked, case, trouble, None, mesh, error=answer), len(cases))
        if not isinstance(answer, HalfedgeMesh):
            return harness.counted(harness.failed(name, checked, case, f"downsample should return the simplified "
                                                  f"HalfedgeMesh, but yours returned {type(answer).__name__}."), len(cases))
        result = answer.copy()
        result.topology_changed()
        if result.has_garbage:
            result.garbage_collect()
        try:
            result.validate()
        except MeshInvariantError as error:
            return harness.counted(harness.failed(name, checked, case, (
                f"your result is not a valid mesh ({error.rule}: {str(error).split('] ', 1)[-1]}). Skip an edge that "
                f"may not collapse (can_collapse) instead of collapsing it."), None, mesh), len(cases))
        if result.n_faces not in (target, target - 1):
            return harness.counted(harness.failed(name, checked, case, (
                f"your result has {result.n_faces} faces; stop when the mesh has {target} (a collapse removes two "
                f"faces, so {target} or {target - 1})."), None, mesh), len(cases))
        points = result.to_arrays()[0]
        if corners is not None:
            off = [p for p in points if not np.any(np.all(np.isclose(p, corners, atol=1e-6), axis=1))]
            if off:
                return harness.counted(harness.failed(name, checked, case, (
                    f"{len(off)} of your {len(points)} vertices are not corners of the solid, e.g. "
                    f"{harness.point_text(off[0])}. On flat faces every collapse can cost 0: a vertex on one face "
                    f"may go anywhere in its plane, one on an edge along its line, and a corner's three planes pin "
                    f"it. Put each new vertex at its edge's optimal point (the midpoint only when A is singular) "
                    f"and pop the cheapest edge first, and only the corners are left, exactly."), None, mesh),
                    len(cases))
        else:
            library = simplify_sequential(mesh, target).to_arrays()[0]
            error = lambda p: float(np.abs(np.linalg.norm(p, axis=1) - 1.0).max())  # noqa: E731
            if error(points) > max(2.0 * error(library), error(library) + 0.01):
                return harness.counted(harness.failed(name, checked, case, (
                    f"your result strays up to {error(points):.3g} from the sphere, the library's {error(library):.3g}. "
                    f"Pop the cheapest edge each time, and after a collapse give the new vertex the sum of both "
                    f"quadrics and put the edges around it back in the queue with their new costs (entries of "
                    f"edges whose ends have changed since are stale: skip them)."), None, mesh), len(cases))
        checked.append(case)
    return harness.counted(harness.all_good(name, checked, "meshes", "Cheapest edge first, each to its optimal "
                                            "point: the corners stay exactly and the sphere keeps its shape."),
                           len(cases))
