"""Checks for the exercises of chapter 11: one step of tangential smoothing (below), the
vertex normal, and the split, collapse and flip phases (at the end).

    from halfedge_edu.exercises.remesh_checks import check_tangential_smoothing
    check_tangential_smoothing(tangential_smoothing)

The contract: ``tangential_smoothing(mesh) -> (n_vertex_slots, 3)`` new positions,
computed from the old ones and returned (``mesh`` must not change):

1. the centroid ``c`` of every vertex's neighbours, *all of them first*, from the old
   positions (Jacobi);
2. for every interior vertex ``p`` with unit area-weighted normal ``n``: the step
   ``s = c - p`` without its normal part, ``p + s - (s . n) n``;
3. boundary vertices stay where they are.

A step damped by a weight ``w`` between 0 and 1, ``p + w (s - (s . n) n)`` (CMU's
notes use ``w = 1/5``), is accepted too, the same ``w`` every time; the congratulation
says why the library takes the full step.

The check compares the answer with the library's smoothing phase of
:func:`~halfedge_edu.algorithms.remesh.remesh` on small meshes, and at the first vertex
that differs says what the right position is and, where the answer matches a common
slip (the normal part kept, centroids taken from positions already moved, a normal
not of length 1 or not area-weighted, a boundary vertex moved), which slip it is.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from halfedge_edu.algorithms.normals import vertex_normals
from halfedge_edu.algorithms.remesh import tangential_smoothing
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.data import sample

from . import harness, hidden
from .harness import CheckResult


__all__ = ["check_collapse_short_edges", "check_flip_improves", "check_split_long_edges", "check_tangential_smoothing",
           "check_vertex_normal", "collapse_phase_cases", "collapse_short_edges_reference",
           "degree_deviation_after_flip", "flip_cases_for_degrees", "normal_cases", "smoothing_cases",
           "split_phase_cases", "tangential_smoothing_reference"]


def _bumpy(mesh: HalfedgeMesh, seed: int, amount: float) -> HalfedgeMesh:
    """The same mesh with every vertex nudged (on a perfect shape some slips cancel out)."""
    mesh = mesh.copy()
    rng = np.random.default_rng(seed)
    mesh.positions[:] += amount * rng.standard_normal(mesh.positions.shape)
    return mesh


def smoothing_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh]]:
    """The meshes ``check_tangential_smoothing`` uses, in order; with a ``seed``, the
    hidden cases: two nudged closed meshes (one after random flips) and a grid patch."""
    if seed is not None:
        rng = harness.hidden_rng(seed)
        shape, other = (str(name) for name in rng.choice(["cube", "octahedron", "icosphere(1)", "icosphere(2)"], 2,
                                                          replace=False))
        flips = int(rng.integers(3, 9))
        rows, columns = (int(n) for n in rng.integers(2, 5, 2))
        return [
            (harness.hidden_name(1, f"{shape}, nudged"), hidden.jittered(hidden.closed_mesh(shape), rng, 0.04)),
            (harness.hidden_name(2, f"{other} after {flips} random flips, nudged"),
             hidden.jittered(hidden.flipped(hidden.closed_mesh(other), flips, rng), rng, 0.04)),
            (harness.hidden_name(3, f"a {rows} x {columns} grid patch (a boundary)"),
             HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng))),
        ]
    patch = sample("open_patch")
    bumpy_patch = _bumpy(patch, 3, 0.05)
    return [
        ("octahedron (every vertex of degree 4)", _bumpy(sample("octahedron"), 1, 0.05)),
        ("icosphere (degrees 5 and 6)", _bumpy(sample("icosphere", subdivisions=1), 2, 0.03)),
        ("open patch (a boundary)", bumpy_patch),
        ("cube (triangles of two sizes)", _bumpy(sample("cube"), 4, 0.04)),
    ]


def tangential_smoothing_reference(mesh: HalfedgeMesh) -> np.ndarray:
    """One step of tangential smoothing, one vertex at a time (the exercise's answer).

    Returns (n_vertex_slots, 3) new positions; ``mesh`` is only read.
    """
    P = mesh.positions
    normals = vertex_normals(mesh)                                   # unit, area-weighted
    centroids = np.zeros_like(P)
    for v in mesh.vertices:                                          # all centroids first
        centroids[v.index] = np.mean([P[u.index] for u in v.neighbors()], axis=0)
    new = P.copy()
    for v in mesh.vertices:
        if v.is_boundary:
            continue
        step = centroids[v.index] - P[v.index]
        n = normals[v.index]
        new[v.index] = P[v.index] + step - (step @ n) * n
    return new


def _library(mesh: HalfedgeMesh) -> np.ndarray:
    """The remesher's own smoothing phase (on the compact arrays of a mesh without garbage)."""
    vertices, faces = mesh.to_arrays()
    return tangential_smoothing(vertices, faces)


def _gauss_seidel(mesh: HalfedgeMesh) -> np.ndarray:
    """The slip: vertices updated in index order, each centroid read from the positions so far."""
    P = mesh.positions.copy()
    normals = vertex_normals(mesh)
    for v in mesh.vertices:
        if v.is_boundary:
            continue
        step = np.mean([P[u.index] for u in v.neighbors()], axis=0) - P[v.index]
        n = normals[v.index]
        P[v.index] += step - (step @ n) * n
    return P


def _damping(before: np.ndarray, yours: np.ndarray, target: np.ndarray) -> float | None:
    """The weight ``w`` in ``yours = before + w (target - before)``, the same for every vertex,
    or None when no single ``w`` in (0, 1) fits.

    CMU's notes move each vertex ``q = p + w (c - p)`` with a damping weight (1/5 in their
    examples), and project the step on the tangent plane: the same step as the library's,
    scaled by ``w``.
    """
    step = target - before                                          # (n, 3)
    length_squared = float(np.sum(step * step))
    if length_squared == 0.0:
        return None
    weight = float(np.sum((yours - before) * step)) / length_squared
    if abs(weight - 1.0) < 1e-6:                  # the full step, with rounding: not a damped one
        return None
    if not 0.0 < weight < 1.0 or not harness.close(yours, before + weight * step):
        return None
    return weight


def _plain_centroids(mesh: HalfedgeMesh) -> np.ndarray:
    """(n_vertex_slots, 3): each interior vertex at its neighbours' centroid, the rest unmoved."""
    centroids = mesh.positions.copy()
    for vertex in mesh.vertices:
        if not vertex.is_boundary and vertex.halfedge is not None:
            centroids[vertex.index] = mesh.positions[[u.index for u in vertex.neighbors()]].mean(axis=0)
    return centroids


def _weight_text(weight: float) -> str:
    fifth = " (CMU's 1/5)" if abs(weight - 0.2) < 1e-9 else ""
    return f"w = {weight:.4g}{fifth}"


def _explain(mesh: HalfedgeMesh, v: int, yours: np.ndarray, wanted: np.ndarray) -> str:
    """Words for the first vertex where the learner's position differs from the library's."""
    P = mesh.positions
    vertex = mesh.vertex(v)
    ring = [u.index for u in vertex.neighbors()]
    p = P[v]
    if vertex.is_boundary:
        text = (f"vertex {v} is on the boundary, so it stays at {harness.point_text(p)}; yours moved it to {harness.point_text(yours)}. "
                f"Boundary vertices keep the outline of the surface: skip every vertex with v.is_boundary.")
        return text
    centroid = P[ring].mean(axis=0)
    n = vertex_normals(mesh)[v]
    step = centroid - p
    text = (f"vertex {v} is inside, with neighbours {ring}. Their centroid is c = {harness.point_text(centroid)}; the unit "
            f"normal is n = {harness.point_text(n)}; the step s = c - p has a normal part (s . n) n = {harness.point_text((step @ n) * n)}. "
            f"Without it the vertex goes to p + s - (s . n) n = {harness.point_text(wanted)}; yours is {harness.point_text(yours)}.")
    area_sum = np.zeros(3)
    for f in vertex.faces():
        a, b, c = (P[u.index] for u in f.vertices())
        area_sum += np.cross(b - a, c - a)
    uniform = vertex_normals(mesh, weighting="uniform")[v]
    angle = vertex_normals(mesh, weighting="angle")[v]
    if harness.close(yours, centroid):
        text += (" Yours is the centroid itself: the normal part of the step was kept. That is plain Laplacian "
                 "smoothing, which also moves vertices off the surface, so a curved mesh shrinks. Remove (s . n) n.")
    elif harness.close(yours, p):
        text += " Yours did not move the vertex at all. Every interior vertex takes its tangential step."
    elif harness.close(yours, p + (step @ n) * n):
        text += " Yours kept only the normal part of the step; it is the part to throw away."
    elif harness.close(yours, p + step + (step @ n) * n):
        text += " The sign of the normal part is flipped: subtract (s . n) n, do not add it."
    elif harness.close(yours, p + step - (step @ area_sum) * area_sum):
        text += (" Your normal is not of length 1: (s . n) n only removes the normal part when |n| = 1. "
                 "Divide the summed face normals by their length.")
    elif not harness.close(uniform, n) and harness.close(yours, p + step - (step @ uniform) * uniform):
        text += (" Your normal gives every face the same weight. The course weights each face normal by the "
                 "face's area (sum the un-normalized cross products, then normalize once), as "
                 "hx.vertex_normals(mesh) does.")
    elif not harness.close(angle, n) and harness.close(yours, p + step - (step @ angle) * angle):
        text += (" Your normal weights the faces by their corner angles; the course uses area weights, as "
                 "hx.vertex_normals(mesh) does.")
    elif harness.close(yours, _gauss_seidel(mesh)[v]):
        moved = [u for u in ring if u < v and not mesh.vertex(u).is_boundary]
        text += (f" Your centroid used positions that had already moved this step (vertex {v}'s neighbours "
                 f"{moved} were updated before it). Compute every centroid first, from the old positions, and "
                 f"only then move the vertices.")
    elif harness.close(yours, (p + P[ring].sum(axis=0)) / (len(ring) + 1)):
        text += " Yours averages the vertex with its neighbours; the centroid is of the neighbours only."
    return text


def check_tangential_smoothing(tangential_smoothing: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare the learner's ``tangential_smoothing(mesh)`` with the remesher's smoothing phase.

    Args:
        tangential_smoothing: ``(mesh) -> (n_vertex_slots, 3)`` the new positions; the
            mesh must not change.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.

    Returns:
        A :class:`~halfedge_edu.exercises.harness.CheckResult`; at the first vertex that
        differs it says what is wrong in words, and ``result.show()`` draws that vertex's
        one-ring.
    """
    name = "tangential_smoothing"
    cases = smoothing_cases(seed)
    if (blanks := harness.blanks_left(name, len(cases), tangential_smoothing)) is not None:
        return blanks
    return harness.counted(_check_tangential_smoothing(tangential_smoothing, cases), len(cases))


def _check_tangential_smoothing(tangential_smoothing: Callable, cases: list[tuple[str, HalfedgeMesh]]) -> CheckResult:
    """:func:`check_tangential_smoothing` on the given cases."""
    name = "tangential_smoothing"
    checked: list[str] = []
    weights: list[float] = []  # the learner's damping weight w, if they damp the step (CMU's notes)
    for case, mesh in cases:
        before = mesh.positions.copy()
        status, answer = harness.run(tangential_smoothing, mesh)
        trouble = harness.trouble(status, answer, name)
        if trouble:
            return harness.failed(name, checked, case, trouble, None, mesh, error=answer)
        if not np.array_equal(mesh.positions, before):
            mesh.positions[:] = before
            return harness.failed(name, checked, case, "your tangential_smoothing changed mesh.positions. Compute every "
                           "centroid first, from the old positions, and return the new positions as a new array "
                           "(new = P.copy(), then write into new).")
        try:
            yours = np.asarray(answer, dtype=np.float64)
        except (TypeError, ValueError):
            yours = np.zeros(0)
        if yours.shape != before.shape:
            return harness.failed(name, checked, case, f"tangential_smoothing should return one new position per vertex, "
                           f"shape {before.shape}, but yours has shape {yours.shape}.")
        wanted = _library(mesh)
        damping = _damping(before, yours, wanted)
        if damping is not None and weights and abs(damping - weights[0]) > 1e-9:
            return harness.failed(name, checked, case, f"your steps are damped with {_weight_text(damping)} here but "
                                  f"{_weight_text(weights[0])} before: use one weight for every step.")
        if damping is not None:
            weights.append(damping)
            checked.append(case if case.startswith("hidden") else case.split(" (")[0])
            continue
        wrong = np.flatnonzero(~np.isclose(yours, wanted, rtol=1e-7, atol=1e-9).all(axis=1))
        if len(wrong) == 0:
            checked.append(case if case.startswith("hidden") else case.split(" (")[0])
            continue
        v = int(wrong[0])
        kept_normal = _damping(before, yours, _plain_centroids(mesh))
        if kept_normal is not None:
            return harness.failed(name, checked, case, (
                f"your vertices move p + w (c - p) with {_weight_text(kept_normal)}, the damped step CMU's notes "
                f"start from, but with its normal part kept, so a curved surface shrinks. Remove the normal part "
                f"of the step before you scale it: s = c - p, s - (s . n) n, then p + w (s - (s . n) n)."),
                ("vertex", v), mesh)
        return harness.failed(name, checked, case, _explain(mesh, v, yours[v], wanted[v]), ("vertex", v), mesh)
    if weights:
        return harness.all_good(name, checked, "meshes", (
            f"You damp each step with {_weight_text(weights[0])}, as CMU's notes do: p + w (s - (s . n) n), "
            f"correct in that convention. The library (like pmp-library's remesher and Botsch and Kobbelt's "
            f"paper it follows) takes the full tangential step, w = 1, because the remesher's split, collapse "
            f"and flip passes run between smoothing steps and a full step evens the vertices out in fewer rounds; "
            f"a damped step moves more gently and needs more of them."))
    return harness.all_good(name, checked, "meshes", "That is the smoothing phase of the remesher: the vertices spread "
                     "out evenly and the surface keeps its shape.")


# --------------------------------------------------------------------------------------
# Area-weighted vertex normals (CS184's Vertex::normal, UChicago P4 and chapter 11's n)
# --------------------------------------------------------------------------------------

def normal_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh]]:
    """The meshes ``check_vertex_normal`` asks every vertex of: faces of different sizes
    around a vertex (where the weights matter), a boundary, other degrees."""
    if seed is not None:
        rng = harness.hidden_rng(seed)
        shape = str(rng.choice(["cube", "octahedron", "icosphere(1)"]))
        flips = int(rng.integers(3, 8))
        rows, columns = (int(n) for n in rng.integers(2, 4, 2))
        return [
            (harness.hidden_name(1, f"{shape}, nudged"), hidden.jittered(hidden.closed_mesh(shape), rng, 0.08)),
            (harness.hidden_name(2, f"icosphere(1) after {flips} random flips, nudged"),
             hidden.jittered(hidden.flipped(hidden.closed_mesh("icosphere(1)"), flips, rng), rng, 0.05)),
            (harness.hidden_name(3, f"a {rows} x {columns} grid patch, bent"),
             HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng, amount=0.3))),
        ]
    return [
        ("cube", sample("cube")),
        ("open patch, bent (a boundary)", _bumpy(sample("open_patch"), 7, 0.15)),
        ("icosphere, nudged", _bumpy(sample("icosphere", subdivisions=1), 8, 0.05)),
    ]


def _normal_words(mesh: HalfedgeMesh, v: int, yours: np.ndarray, wanted: np.ndarray) -> str:
    """What is wrong with one vertex normal, naming the slip where the answer shows it."""
    P = mesh.positions
    crosses = []
    for f in mesh.vertex(v).faces():
        a, b, c = (P[u.index] for u in f.vertices())
        crosses.append(np.cross(b - a, c - a))
    area_sum = np.sum(crosses, axis=0)
    text = (f"vertex {v} touches {len(crosses)} faces; the area-weighted normal sums their cross products "
            f"(b - a) x (c - a) (each is twice the face's area long) and divides by the length once: "
            f"{harness.point_text(wanted)}. Yours is {harness.point_text(yours)}.")
    unit = lambda x: x / np.linalg.norm(x)  # noqa: E731
    if harness.close(yours, -wanted):
        text += " It points inwards: take the corners in the face's own counter-clockwise order, a -> b -> c."
    elif harness.close(yours, area_sum) or harness.close(yours, 0.5 * area_sum):
        text += " Right direction, wrong length: a normal has length 1, so divide the sum by its length."
    elif harness.close(yours, unit(np.sum([unit(x) for x in crosses], axis=0))):
        text += (" That is every face counted the same (each cross product made unit first). Leave them as they "
                 "are: their lengths are the area weights, so big faces count more.")
    elif harness.close(yours, vertex_normals(mesh, weighting="angle")[v]):
        text += " That weights the faces by their corner angles; this exercise asks for area weights."
    elif any(harness.close(yours, unit(x)) for x in crosses):
        text += " That is the normal of one face only: sum over every face around the vertex (v.faces())."
    return text


def check_vertex_normal(vertex_normal: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare the learner's ``vertex_normal(mesh, v) -> (3,)`` with ``hx.vertex_normals(mesh)``
    (area weights) at every vertex of a few meshes.

    Args:
        vertex_normal: ``(mesh, v) -> (3,)``, the unit area-weighted normal of vertex
            ``v`` (a Vertex handle); the mesh must not change.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.
    """
    name = "vertex_normal"
    cases = normal_cases(seed)
    if (blanks := harness.blanks_left(name, len(cases), vertex_normal)) is not None:
        return blanks
    return harness.counted(_check_vertex_normal(vertex_normal, cases), len(cases))


def _check_vertex_normal(vertex_normal: Callable, cases: list[tuple[str, HalfedgeMesh]]) -> CheckResult:
    """:func:`check_vertex_normal` on the given meshes."""
    name = "vertex_normal"
    checked: list[str] = []
    for case, mesh in cases:
        wanted = vertex_normals(mesh)
        before = mesh.positions.copy()
        for vertex in mesh.vertices:
            status, answer = harness.run(vertex_normal, mesh, vertex)
            trouble = harness.trouble(status, answer, name)
            element = ("vertex", vertex.index)
            if trouble:
                return harness.failed(name, checked, case, f"at vertex {vertex.index}, {trouble}", element, mesh,
                                      error=answer)
            if not np.array_equal(mesh.positions, before):
                mesh.positions[:] = before
                return harness.failed(name, checked, case, "your vertex_normal changed mesh.positions; it should "
                                      "only read them.", element, mesh)
            try:
                yours = np.asarray(answer, dtype=np.float64).reshape(-1)
            except (TypeError, ValueError):
                yours = np.zeros(0)
            if yours.shape != (3,):
                return harness.failed(name, checked, case, f"vertex_normal should return 3 numbers, but at vertex "
                                      f"{vertex.index} yours returned {answer!r:.80}.", element, mesh)
            if not np.allclose(yours, wanted[vertex.index], rtol=1e-6, atol=1e-8):
                return harness.failed(name, checked, case, _normal_words(mesh, vertex.index, yours,
                                                                         wanted[vertex.index]), element, mesh)
        checked.append(case if case.startswith("hidden") else case.split(" (")[0])
    return harness.all_good(name, checked, "meshes", "That is the n chapter 11's smoothing projects the step with, "
                            "and the smooth shading of chapter 05.")


# --------------------------------------------------------------------------------------
# The flip phase's rule (CMU's remeshing step 3): flip when the degrees get closer to 6
# --------------------------------------------------------------------------------------

def degree_deviation_after_flip(mesh: HalfedgeMesh, e: int) -> tuple[int, int]:
    """``(before, after)``: the summed distance of edge ``e``'s four vertices from their ideal
    degree (6 inside, 4 on the boundary) now, and if ``e`` were flipped (its ends lose one
    edge, the two opposite vertices gain one)."""
    h = mesh.edge(e).halfedge
    a, b = h.vertex, h.tip
    c, d = h.prev.vertex, h.twin.prev.vertex
    before = after = 0
    for vertex, change in ((a, -1), (b, -1), (c, +1), (d, +1)):
        ideal = 4 if vertex.is_boundary else 6
        before += abs(vertex.degree - ideal)
        after += abs(vertex.degree + change - ideal)
    return before, after


def flip_cases_for_degrees(seed: int | None = None) -> list[tuple[str, HalfedgeMesh]]:
    """Meshes whose interior edges ``check_flip_improves`` asks about: degrees from 3 to 8 or so,
    inside and on a boundary. With a ``seed``, the hidden cases instead."""
    rng = harness.hidden_rng(12 if seed is None else seed)
    if seed is None:
        return [("cube", sample("cube")), ("icosphere after 8 random flips", hidden.flipped(sample("icosphere", subdivisions=1), 8, rng)),
                ("a 3 x 4 grid patch (a boundary, where the ideal degree is 4)",
                 HalfedgeMesh.from_faces(*hidden.grid(3, 4, np.random.default_rng(1))))]
    shape = str(rng.choice(["octahedron", "icosphere(1)", "icosphere(2)"]))
    flips = int(rng.integers(5, 15))
    rows, columns = (int(n) for n in rng.integers(2, 5, 2))
    return [(harness.hidden_name(1, f"{shape} after {flips} random flips"), hidden.flipped(hidden.closed_mesh(shape), flips, rng)),
            (harness.hidden_name(2, f"a {rows} x {columns} grid patch"), HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng))),
            (harness.hidden_name(3, "a cube after 4 random flips"), hidden.flipped(sample("cube"), 4, rng))]


def check_flip_improves(flip_improves: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare the learner's ``flip_improves(mesh, e) -> bool`` with the flip phase's rule on
    every interior edge of a few meshes: True exactly when flipping ``e`` lowers the summed
    distance of its four vertices from their ideal degrees (6 inside, 4 on the boundary).

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    name = "flip_improves"
    cases = flip_cases_for_degrees(seed)
    if (blanks := harness.blanks_left(name, len(cases), flip_improves)) is not None:
        return blanks
    checked: list[str] = []
    for case, mesh in cases:
        for edge in mesh.edges:
            if edge.is_boundary:
                continue
            status, answer = harness.run(flip_improves, mesh, edge.index)
            trouble = harness.trouble(status, answer, name)
            element = ("halfedge", 2 * edge.index)
            if trouble:
                return harness.counted(harness.failed(name, checked, case, f"for edge {edge.index}, {trouble}", element,
                                                      mesh, error=answer), len(cases))
            before, after = degree_deviation_after_flip(mesh, edge.index)
            if bool(answer) == (after < before):
                continue
            h = edge.halfedge
            four = [(v.index, v.degree, 4 if v.is_boundary else 6) for v in (h.vertex, h.tip, h.prev.vertex, h.twin.prev.vertex)]
            text = (f"edge {edge.index}: its ends {four[0][0]} and {four[1][0]} have degrees {four[0][1]} and "
                    f"{four[1][1]}, the opposite vertices {four[2][0]} and {four[3][0]} have {four[2][1]} and "
                    f"{four[3][1]}. A flip takes one edge from each end and gives one to each opposite vertex, so the "
                    f"summed distance from the ideal degrees goes from {before} to {after}: flip only when it drops. "
                    f"Yours says {bool(answer)}.")
            if any(ideal == 4 for _, _, ideal in four):
                text += " On the boundary the ideal degree is 4, not 6."
            if after == before and answer:
                text += " Equal is not better: a flip that changes nothing would make the phase flip back and forth."
            return harness.counted(harness.failed(name, checked, case, text, element, mesh), len(cases))
        checked.append(case)
    return harness.counted(harness.all_good(name, checked, "meshes", "That is the flip phase's test: each flip brings "
                                            "the degrees closer to 6, so the phase ends."), len(cases))


# --------------------------------------------------------------------------------------
# The split phase (CMU's remeshing step 1): no edge longer than 4/3 L
# --------------------------------------------------------------------------------------

def split_phase_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh, float]]:
    """``(name, mesh, L)``: meshes whose edges need one or several rounds of splits to get
    below 4/3 L. With a ``seed``, the hidden cases instead."""
    if seed is None:
        return [("cube, L = 0.5 (edges of 1 and 1.41: split twice)", sample("cube"), 0.5),
                ("open patch, L = 0.4 (a boundary)", sample("open_patch"), 0.4),
                ("icosphere, L = 0.3", sample("icosphere", subdivisions=1), 0.3)]
    rng = harness.hidden_rng(seed)
    shape = str(rng.choice(["tetrahedron", "octahedron", "icosphere(1)"]))
    rows, columns = (int(n) for n in rng.integers(1, 4, 2))
    return [(harness.hidden_name(1, f"{shape}, nudged"), hidden.jittered(hidden.closed_mesh(shape), rng, 0.05),
             float(rng.uniform(0.2, 0.5))),
            (harness.hidden_name(2, f"a {rows} x {columns} grid patch"),
             HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng)), float(rng.uniform(0.3, 0.6))),
            (harness.hidden_name(3, "a cube, stretched"), _stretched_cube(rng), float(rng.uniform(0.4, 0.8)))]


def _stretched_cube(rng: np.random.Generator) -> HalfedgeMesh:
    cube = sample("cube")
    cube.positions[:] *= rng.uniform(0.5, 2.0, 3)
    return cube


def check_split_long_edges(split_long_edges: Callable, *, seed: int | None = None) -> CheckResult:
    """Run the learner's ``split_long_edges(mesh, L)`` (in place: split every edge longer than
    4/3 L at its midpoint, again and again, until none is) and judge the result: a valid
    mesh, no edge longer than 4/3 L, the old vertices where they were, and every new vertex
    on the old surface. Any order of splits is right (the cross edges a split draws to the
    opposite corners may be short; the collapse phase deals with those).

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    from halfedge_edu.algorithms.remesh import closest_points_on_triangles
    from halfedge_edu.core.errors import MeshInvariantError

    name = "split_long_edges"
    cases = split_phase_cases(seed)
    if (blanks := harness.blanks_left(name, len(cases), split_long_edges)) is not None:
        return blanks
    checked: list[str] = []
    for case, mesh, L in cases:
        yours = mesh.copy()
        status, answer = harness.run(split_long_edges, yours, L)
        trouble = harness.trouble(status, answer, name)
        if trouble:
            return harness.counted(harness.failed(name, checked, case, trouble, None, mesh, error=answer), len(cases))
        yours.topology_changed()
        try:
            yours.validate()
        except MeshInvariantError as error:
            return harness.counted(harness.failed(name, checked, case, f"after your splits the mesh breaks the rule "
                                                  f"{error.rule}: {str(error).split('] ', 1)[-1]}", None, mesh),
                                   len(cases))
        ends = yours.edge_vertices()[~yours.edge_deleted]                   # (E, 2)
        lengths = np.linalg.norm(yours.positions[ends[:, 0]] - yours.positions[ends[:, 1]], axis=1)
        if lengths.max() > 4.0 / 3.0 * L + 1e-9:
            return harness.counted(harness.failed(name, checked, case, (
                f"an edge of length {lengths.max():.3g} is left, longer than 4/3 L = {4 * L / 3:.3g}. Splitting "
                f"makes two halves that may still be too long: keep splitting until no edge is longer (loop until "
                f"a pass splits nothing)."), None, mesh), len(cases))
        old = mesh.n_vertex_slots
        if not np.allclose(yours.positions[:old], mesh.positions):
            return harness.counted(harness.failed(name, checked, case, "your splits moved an old vertex; a split only "
                                                  "adds one, at the edge's midpoint."), len(cases))
        corners = mesh.positions[mesh.face_vertices()]                      # (F, 3, 3)
        new = yours.positions[old: yours.n_vertex_slots]
        if len(new):
            nearest = [np.min(np.linalg.norm(closest_points_on_triangles(np.repeat(p[None], len(corners), 0),
                                                                         corners[:, 0], corners[:, 1], corners[:, 2])
                                             - p, axis=1)) for p in new]
            if max(nearest) > 1e-9:
                return harness.counted(harness.failed(name, checked, case, (
                    "a new vertex lies off the old surface; put each at the midpoint of the edge it splits."), None,
                    mesh), len(cases))
        checked.append(case)
    return harness.counted(harness.all_good(name, checked, "meshes", "No edge is longer than 4/3 L, and the surface "
                                            "is the same: the split phase of the remesher."), len(cases))


# --------------------------------------------------------------------------------------
# The collapse phase (CMU's remeshing step 2): no edge shorter than 4/5 L that may go
# --------------------------------------------------------------------------------------

#: Seconds the learner's collapse phase may take on one mesh (a whole phase, a few hundred vertices).
COLLAPSE_PHASE_SECONDS = 5.0


def _edge_lengths(mesh: HalfedgeMesh) -> tuple[np.ndarray, np.ndarray]:
    """``(edges (E,) int, lengths (E,) float)`` of the live edges."""
    edges = np.flatnonzero(~mesh.edge_deleted)
    ends = mesh.edge_vertices()[edges]                                     # (E, 2)
    return edges, np.linalg.norm(mesh.positions[ends[:, 0]] - mesh.positions[ends[:, 1]], axis=1)


def _after_splits(mesh: HalfedgeMesh, count: int, rng: np.random.Generator) -> HalfedgeMesh:
    """A compact copy of ``mesh`` after ``count`` random splits (edges of half length, the
    split phase's leftovers the collapse phase is for)."""
    from halfedge_edu.core.ops import split

    work = mesh.copy()
    for e in rng.permutation(work.n_edge_slots)[:count].tolist():
        split(work, e)
    return HalfedgeMesh.from_faces(*work.to_arrays())


def _target_for(mesh: HalfedgeMesh, length: float) -> float:
    """``length``, raised if needed so that no edge of ``mesh`` is longer than 4/3 of it (as
    after a split phase): then every edge longer than 4/3 L at the end was made by a collapse."""
    return max(length, 0.75 * float(_edge_lengths(mesh)[1].max()) * 1.001)


def collapse_phase_cases(seed: int | None = None) -> list[tuple[str, HalfedgeMesh, float]]:
    """``(name, mesh, L)``: meshes with edges shorter than 4/5 L and none longer than 4/3 L.

    The tetrahedron (every edge short, none may go), the octahedron (collapses until the
    link condition stops them), an icosphere and a grid patch after random splits (the
    4/3 L rule holds back many collapses; the patch has short boundary edges). With a
    ``seed``, the hidden cases instead.
    """
    if seed is None:
        sphere = sample("icosphere", subdivisions=2)
        patch = HalfedgeMesh.from_faces(*hidden.grid(4, 5, np.random.default_rng(2)))
        split_sphere = _after_splits(sphere, 40, np.random.default_rng(1))
        split_patch = _after_splits(patch, 20, np.random.default_rng(3))
        return [("tetrahedron, L = 3.6 (every edge short, none may go)", sample("tetrahedron"), 3.6),
                ("octahedron, L = 2", sample("octahedron"), 2.0),
                ("icosphere after 40 splits", split_sphere,
                 _target_for(split_sphere, float(_edge_lengths(sphere)[1].mean()))),
                ("a 4 x 5 grid patch after 20 splits (a boundary)", split_patch, _target_for(split_patch, 1.2))]
    rng = harness.hidden_rng(seed)
    shape = str(rng.choice(["octahedron", "icosphere(1)", "icosphere(2)"]))
    small = str(rng.choice(["tetrahedron", "octahedron"]))
    rows, columns = (int(n) for n in rng.integers(3, 6, 2))
    closed = hidden.closed_mesh(shape)
    splits = int(rng.integers(0.2 * closed.n_edges, 0.4 * closed.n_edges))
    split_closed = _after_splits(hidden.jittered(closed, rng, 0.01), splits, rng)
    patch = _after_splits(HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng)), rows * columns, rng)
    nudged = hidden.jittered(hidden.closed_mesh(small), rng, 0.05)
    return [(harness.hidden_name(1, f"{shape} after {splits} random splits"), split_closed,
             _target_for(split_closed, float(_edge_lengths(closed)[1].mean()))),
            (harness.hidden_name(2, f"a {rows} x {columns} grid patch after random splits"), patch,
             _target_for(patch, float(rng.uniform(1.0, 1.3)))),
            (harness.hidden_name(3, f"{small}, nudged, every edge short"), nudged,
             _target_for(nudged, 1.3 * float(_edge_lengths(nudged)[1].max())))]


def _longest_after_collapse(mesh: HalfedgeMesh, e: int) -> float:
    """The longest edge around the merged vertex if edge ``e`` were collapsed to its midpoint."""
    a, b = mesh.edge(e).vertices
    middle = 0.5 * (a.position + b.position)
    others = {u.index for u in (*a.neighbors(), *b.neighbors())} - {a.index, b.index}
    return max((float(np.linalg.norm(mesh.positions[u] - middle)) for u in others), default=0.0)


def collapse_short_edges_reference(mesh: HalfedgeMesh, L: float) -> None:
    """The collapse phase, one edge at a time (the exercise's answer), in place.

    Every interior edge shorter than 4/5 L whose collapse the link condition allows and
    that leaves no edge around the merged vertex longer than 4/3 L is collapsed to its
    midpoint; passes repeat until one collapses nothing. Boundary edges stay.
    """
    while True:
        collapsed = 0
        for e in range(mesh.n_edge_slots):
            if mesh.edge_deleted[e] or mesh.edge(e).is_boundary:
                continue
            a, b = mesh.edge(e).vertices
            if (np.linalg.norm(a.position - b.position) < 0.8 * L and mesh.can_collapse(e)
                    and _longest_after_collapse(mesh, e) <= 4.0 / 3.0 * L):
                mesh.collapse(e)
                collapsed += 1
        if not collapsed:
            return


def _link_damage(mesh: HalfedgeMesh) -> str | None:
    """What a collapse the link condition refuses leaves behind, in words, or None: two edges
    between the same two vertices, two faces on the same three, or a vertex the boundary
    passes through twice (a pinch)."""
    edges = np.flatnonzero(~mesh.edge_deleted)
    pairs = np.sort(mesh.edge_vertices()[edges], axis=1)                    # (E, 2)
    _, first, counts = np.unique(pairs, axis=0, return_index=True, return_counts=True)
    if (counts > 1).any():
        a, b = pairs[first[np.argmax(counts > 1)]]
        return f"two edges join vertices {int(a)} and {int(b)}"
    faces = np.flatnonzero(~mesh.face_deleted)
    corners = np.sort(mesh.face_vertices()[faces], axis=1)                  # (F, 3)
    _, first, counts = np.unique(corners, axis=0, return_index=True, return_counts=True)
    if (counts > 1).any():
        return f"two faces lie on the same three vertices {corners[first[np.argmax(counts > 1)]].tolist()}, back to back"
    live = np.flatnonzero(~mesh.halfedge_deleted)
    on_boundary = live[mesh.halfedge_face[live] < 0]
    leaving = np.bincount(mesh.halfedge_vertex[on_boundary], minlength=mesh.n_vertex_slots)
    if (leaving > 1).any():
        return f"the boundary passes through vertex {int(np.argmax(leaving > 1))} twice (a pinch)"
    return None


def _collapsed_too_long(before: HalfedgeMesh, yours: HalfedgeMesh, L: float) -> tuple[int, int, float] | None:
    """``(a, b, length)``: an edge of ``before`` not shorter than 4/5 L whose midpoint a vertex
    of ``yours`` sits at, and no vertex of ``before`` did (so it was collapsed), or None."""
    edges, lengths = _edge_lengths(before)
    long_enough = lengths >= 0.8 * L
    ends = before.edge_vertices()[edges[long_enough]]                      # (k, 2)
    if not len(ends):
        return None
    middles = 0.5 * (before.positions[ends[:, 0]] + before.positions[ends[:, 1]])   # (k, 3)
    old = before.positions[~before.vertex_deleted]                         # (n, 3)
    for p in yours.positions[~yours.vertex_deleted]:
        at = np.flatnonzero(np.linalg.norm(middles - p, axis=1) < 1e-9)
        if len(at) and np.min(np.linalg.norm(old - p, axis=1)) > 1e-9:
            a, b = (int(v) for v in ends[at[0]])
            return a, b, float(lengths[long_enough][at[0]])
    return None


def check_collapse_short_edges(collapse_short_edges: Callable, *, seed: int | None = None) -> CheckResult:
    """Run the learner's ``collapse_short_edges(mesh, L)`` (in place: collapse, with
    ``mesh.collapse(e)``, every interior edge shorter than 4/5 L, again and again, until
    none can go) and judge the result, whatever order the collapses came in.

    Two conventions are right, and the check says which one it recognised:

    - Botsch and Kobbelt's (CMU's aim, "keep edges no longer than 4/3 L and no shorter
      than 4/5 L"): an edge goes when the link condition allows it
      (``mesh.can_collapse(e)``) and no edge around the merged vertex (at the midpoint)
      would be longer than 4/3 L. No edge longer than 4/3 L may appear.
    - CMU's recipe as written ("collapse all edges that are shorter than 4L/5"): every
      short edge the link condition allows goes, and the edges it lengthens are left to
      the next split phase. Recognised when the result has an edge longer than 4/3 L;
      then no short interior edge the link condition allows may be left.

    Either way boundary edges stay (CMU: "ignore requests to collapse boundary edges");
    an interior edge with an end on the boundary may be collapsed or left. The result
    must be a valid mesh with no damage of a refused collapse, as many boundary edges
    as before, no edge of 4/5 L or more collapsed, and no short interior edge left that
    could still go by the convention recognised.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    from halfedge_edu.core.errors import MeshInvariantError, TopologyError

    name = "collapse_short_edges"
    cases = collapse_phase_cases(seed)
    if (blanks := harness.blanks_left(name, len(cases), collapse_short_edges)) is not None:
        return blanks
    checked: list[str] = []
    as_written: list[str] = []     # the cases judged by CMU's recipe as written (no 4/3 L test)

    def failed(case: str, text: str, mesh: HalfedgeMesh, element: tuple | None = None, error=None) -> CheckResult:
        return harness.counted(harness.failed(name, checked, case, text, element, mesh, error=error), len(cases))

    for case, mesh, L in cases:
        yours = mesh.copy()
        status, answer = harness.run(collapse_short_edges, yours, L, seconds=COLLAPSE_PHASE_SECONDS)
        if status == "error" and isinstance(answer, TopologyError):
            return failed(case, (f"your {name} asked for a collapse the library refuses ({answer}). Ask "
                                 f"mesh.can_collapse(e) first (the link condition of chapter 08, and the boundary "
                                 f"rules) and skip the edges it refuses.{harness.own_line(answer)}"), mesh,
                          error=answer)
        if status == "timeout":
            return failed(case, f"your {name} did not finish within {COLLAPSE_PHASE_SECONDS:g} s: a loop probably "
                                f"never ends (a round that collapses nothing must end the phase).", mesh)
        trouble = harness.trouble(status, answer, name)
        if trouble:
            return failed(case, trouble, mesh, error=answer)
        yours.topology_changed()
        damage = _link_damage(yours)
        if damage is not None:
            return failed(case, (f"after your collapses {damage}: that is what a collapse the link condition "
                                 f"refuses leaves behind (collapse(..., check_link=False), or your own collapse "
                                 f"without the check). Ask mesh.can_collapse(e) before every collapse and skip the "
                                 f"edges it refuses."), mesh)
        try:
            yours.validate()
        except MeshInvariantError as error:
            return failed(case, (f"after your collapses the mesh breaks the rule {error.rule}: "
                                 f"{str(error).split('] ', 1)[-1]}"), mesh)
        boundary_before = sum(edge.is_boundary for edge in mesh.edges)
        boundary_after = sum(edge.is_boundary for edge in yours.edges)
        if boundary_after < boundary_before:
            return failed(case, (f"the boundary had {boundary_before} edges and has {boundary_after} after your "
                                 f"collapses: you collapsed boundary edges. CMU's collapse ignores requests to "
                                 f"collapse a boundary edge, and the remesher keeps the outline where it is "
                                 f"(section 9): skip every edge with edge.is_boundary."), mesh)
        edges, lengths = _edge_lengths(yours)
        # An edge longer than 4/3 L (none was before): the collapses did not keep
        # Botsch and Kobbelt's bound, so this is CMU's recipe as written, judged as such.
        recipe_as_written = bool(len(lengths) and lengths.max() > 4.0 / 3.0 * L + 1e-9)
        too_long = _collapsed_too_long(mesh, yours, L)
        if too_long is not None:
            a, b, length = too_long
            return failed(case, (f"you collapsed the edge between vertices {a} and {b}, which is {length:.3g} long, "
                                 f"not shorter than 4/5 L = {0.8 * L:.3g} (a vertex of yours sits at its midpoint). "
                                 f"Only edges shorter than 4/5 L go: compare with 0.8 * L, not L."), mesh,
                          ("vertex", a))
        for e, length in zip(edges.tolist(), lengths.tolist()):
            edge = yours.edge(e)
            if length >= 0.8 * L or edge.is_boundary or any(v.is_boundary for v in edge.vertices):
                continue
            if not yours.can_collapse(e):
                continue
            if recipe_as_written:
                return failed(case, (f"edge {e} is {length:.3g} long, shorter than 4/5 L = {0.8 * L:.3g}, and it "
                                     f"could still go: the link condition allows it. (Your collapses made edges "
                                     f"longer than 4/3 L, so this is judged by CMU's recipe as written: every short "
                                     f"edge the link condition allows goes.) A collapse can make another edge short "
                                     f"or collapsible: go round again until a pass collapses nothing."),
                              yours, ("halfedge", 2 * e))
            longest = _longest_after_collapse(yours, e)
            if longest <= 4.0 / 3.0 * L:
                return failed(case, (f"edge {e} is {length:.3g} long, shorter than 4/5 L = {0.8 * L:.3g}, and it "
                                     f"could still go: the link condition allows it, and the longest edge around "
                                     f"the merged vertex would be {longest:.3g}, not longer than 4/3 L = "
                                     f"{4 * L / 3:.3g}. A collapse can make room for another (or shorten an edge): "
                                     f"go round again until a pass collapses nothing."), yours, ("halfedge", 2 * e))
        if recipe_as_written:
            as_written.append(case)
        checked.append(case if case.startswith("hidden") else case.split(" (")[0])
    if as_written:
        convention = (f"Recognised CMU's recipe as written (\"collapse all edges that are shorter than 4L/5\") on "
                      f"{len(as_written)} of {len(cases)} meshes: edges longer than 4/3 L appeared, which the next "
                      f"split phase cuts again. Botsch and Kobbelt also skip a collapse that would make an edge "
                      f"longer than 4/3 L (measure the midpoint's distance to both ends' neighbours): fewer edges "
                      f"undone and redone.")
    else:
        convention = ("Recognised Botsch and Kobbelt's rule (CMU's aim): no edge longer than 4/3 L was made.")
    return harness.counted(harness.all_good(name, checked, "meshes", (
        "No interior edge shorter than 4/5 L is left that could go, and the boundary is whole: the collapse "
        f"phase of the remesher. {convention}")), len(cases))
