"""Checks for chapter 10's exercises: the plane quadric, the optimal point, the whole downsampling loop.

    from halfedge_edu.exercises.quadric_checks import check_plane_quadric, check_optimal_point
    check_plane_quadric(plane_quadric)
    check_optimal_point(optimal_point)
    check_downsample(downsample)

Each check calls the learner's function on a few small cases, compares every answer
with the library (:func:`~halfedge_edu.algorithms.simplify.face_quadrics`, the queue's
best point, :func:`~halfedge_edu.algorithms.simplify_queue.simplify_sequential`), and
at the first difference says in words what is wrong and, where the answer matches a
common slip (a normal not scaled to length 1, ``d`` with the wrong sign, solving a
singular system anyway), which slip it is. The contracts:

* ``plane_quadric(a, b, c) -> (4, 4)``: ``K = p p^T`` with ``p = [n, d]``, ``n`` the
  unit normal of the triangle ``a b c`` and ``d = -n . a`` (no area weight).
* ``optimal_point(Q, a, b) -> (3,)``: the point minimizing ``[x, 1] Q [x, 1]^T``, the
  solution of ``A x = -q`` (``A = Q[:3, :3]``, ``q = Q[:3, 3]``), or the midpoint of
  ``a`` and ``b`` when ``A`` is singular.
* ``downsample(mesh, target_faces) -> HalfedgeMesh``: CMU's quadric simplification,
  judged by what it achieves (a valid mesh of the target size, corners kept, the
  sphere's shape kept), not by its order of collapses.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from halfedge_edu.algorithms.simplify import face_quadrics, optimal_points
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.data import sample

from . import harness, hidden
from .harness import CheckResult, hidden_name

__all__ = ["check_downsample", "check_optimal_point", "check_plane_quadric"]


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
    if (blanks := harness.blanks_left("plane_quadric", len(cases), plane_quadric)) is not None:
        return blanks
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
    if (blanks := harness.blanks_left("optimal_point", len(cases), optimal_point)) is not None:
        return blanks
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
        yours = harness.as_point(answer)
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
    if (blanks := harness.blanks_left(name, len(cases), downsample)) is not None:
        return blanks
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
