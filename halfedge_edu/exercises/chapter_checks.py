"""The checks of chapters 01, 04, 05 and 08, which the chapters used to define in a cell.

    from halfedge_edu.exercises.chapter_checks import check_fan, check_cut, check_laplacian_step, check_collapse_is_safe
    check_fan(fan)                          # chapter 01: cut a polygon into a fan like the OBJ reader
    check_obj_io(read_obj, write_obj)       # chapter 01: an OBJ reader and writer (see io_checks)
    check_cut(cut_bowtie)                   # chapter 04: give the bowtie's second fan its own vertex
    check_laplacian_step(laplacian_step)    # chapter 05: one Jacobi step of uniform smoothing
    check_collapse_is_safe(collapse_is_safe)   # chapter 08: the link condition from one-rings (each course's statement)

They live in the package so that the grader (``halfedge_edu.exercises.grading``) can
run them on a learner's function; each returns a :class:`CheckResult` like the other
``check_*`` helpers: ``bool(result)`` says whether it passed, its text says what is
wrong first, in words. Each runs the learner's function under the same time limit
(``harness.TIME_LIMIT`` per call) and turns an exception into a sentence.
"""

from __future__ import annotations

import io
import warnings
from typing import Callable

import numpy as np

from halfedge_edu.algorithms.smoothing import smooth
from halfedge_edu.core.errors import MeshInputError, MeshWarning
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.core.ops import can_collapse, collapse, link_condition
from halfedge_edu.core.ops.link import BOUNDARY
from halfedge_edu.data import sample
from halfedge_edu.io import read_obj

from . import hidden
from .harness import TIME_LIMIT, CheckResult, counted, failed, hidden_name, hidden_rng, passed, run, trouble, unfinished
from .io_checks import check_obj_io, check_obj_reader, check_obj_writer

__all__ = ["BOWTIE_FACES", "BOWTIE_VERTICES", "FAN_SLIPS", "NONMANIFOLD_SLIPS", "check_nonmanifold", "check_collapse_is_safe", "check_cut", "check_fan",
           "check_laplacian_step", "check_obj_io", "check_obj_reader", "check_obj_writer", "smooth_once_in_place"]

#: Chapter 04's bowtie: two triangles that share only vertex 0.
BOWTIE_VERTICES = np.array([[0, 0, 0], [1, -0.5, 0], [1, 0.5, 0], [-1, 0.5, 0], [-1, -0.5, 0]], dtype=float)
BOWTIE_FACES = np.array([[0, 1, 2], [0, 3, 4]])


def _blanks_left(exercise: str, name: str, function: Callable) -> CheckResult | None:
    """The "fill in the blanks" failure if the learner's function still holds a ``...``."""
    words = unfinished(function, name)
    return failed(exercise, [], None, words) if words else None


def _call(exercise: str, name: str, function: Callable, *args, mesh_name: str | None = None,
          checked: list[str] | None = None, element: tuple | None = None,
          mesh: HalfedgeMesh | None = None) -> tuple[object, CheckResult | None]:
    """Run the learner's function: ``(value, None)``, or ``(None, a failed result saying why)``,
    carrying the case's ``mesh`` and ``element`` and, after an exception, ``rerun()``."""
    status, value = run(function, *args)
    if status == "timeout":
        return None, failed(exercise, checked or [], mesh_name,
                             f"your {name} did not return within {TIME_LIMIT:g} s: a loop probably never ends.", element, mesh)
    if status == "error":
        return None, failed(exercise, checked or [], mesh_name, trouble("error", value, name), element, mesh,
                            error=value)
    return value, None


def fan_cases(seed: int | None = None) -> list[tuple[str, list[int]]]:
    """``(name, corners)`` for :func:`check_fan`: 3 to 8 corners numbered 0, 1, 2, ...;
    with a ``seed``, the hidden cases: polygons of 3 to 12 corners with other vertex numbers."""
    if seed is None:
        return [(f"{n} corners", list(range(n))) for n in range(3, 9)]
    rng = hidden_rng(seed)
    cases = []
    for number, n in enumerate([3, *rng.integers(4, 13, 3).tolist()], start=1):
        corners = rng.choice(40, size=n, replace=False).tolist()
        cases.append((hidden_name(number, f"a face of {n} corners with other vertex numbers"), corners))
    return cases


def check_fan(fan: Callable, *, seed: int | None = None) -> CheckResult:
    """``fan(corners) -> [(a, b, c), ...]`` against the OBJ reader's fans of 3 to 8 corners.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    cases = fan_cases(seed)
    if (blanks := _blanks_left("fan", "fan", fan)) is not None:
        return counted(blanks, len(cases))
    return counted(_check_fan(fan, cases), len(cases))


def _strip(corners: list[int]) -> list[list[int]]:
    """The triangles of a strip over the corners, (a, b, c), (b, c, d), ... (the slip's answer)."""
    return [list(corners[k:k + 3]) for k in range(len(corners) - 2)]


#: The fan slips, in the order they are tried: (name, detector, sentence). A detector gets
#: ``(corners, mine, expected)``; the sentence may use ``{n}``, ``{count}``, ``{got}`` and
#: ``{first}``. Each row is tested with the slip's own code in tests/exercises/test_chapter_checks.py.
FAN_SLIPS: tuple[tuple[str, Callable, str], ...] = (
    ("too few or too many triangles",
     lambda corners, mine, expected: len(mine) != len(expected),
     "A face of {n} corners makes n - 2 = {count} triangles, yours makes {got}: the fan's second corner "
     "runs over corners[1] to corners[n - 2] (k in range(1, n - 1))."),
    ("turned the other way",
     lambda corners, mine, expected: mine == [[a, c, b] for a, b, c in expected],
     "Your triangles have the right corners but turn the other way: keep the polygon's order, (a, b, c) and "
     "not (a, c, b), so that every triangle faces the same side as the polygon."),
    ("a strip, not a fan",
     lambda corners, mine, expected: mine == _strip(corners) != expected,
     "Your triangles are a strip, each starting at the second corner of the one before; a fan keeps the "
     "first corner in every triangle: (a, b, c), (a, c, d), ..."),
    ("vertex 0 instead of the first corner",
     lambda corners, mine, expected: corners[0] != 0 and all(t[0] == 0 for t in mine)
     and [[corners[0], *t[1:]] for t in mine] == expected,
     "Every triangle of yours starts at vertex 0, but this face's first corner is vertex {first}: use "
     "corners[0], not 0 (the faces of a file are not all numbered from 0)."),
)


def _check_fan(fan: Callable, cases: list[tuple[str, list[int]]]) -> CheckResult:
    """:func:`check_fan` on the given cases."""
    checked: list[str] = []
    for name, corners in cases:
        n_vertices = max(corners) + 1
        text = "v 0 0 0\n" * n_vertices + "f " + " ".join(str(c + 1) for c in corners) + "\n"
        expected = read_obj(io.StringIO(text)).faces.tolist()
        answer, failure = _call("fan", "fan", fan, list(corners), mesh_name=name, checked=checked)
        if failure is not None:
            return failure
        try:
            mine = [[int(corner) for corner in triangle] for triangle in answer]
        except TypeError:
            return failed("fan", checked, name, f"fan should return a list of triangles (a, b, c), "
                           f"but yours returned {answer!r:.60}.")
        if mine != expected:
            sentence = next((sentence for _, detector, sentence in FAN_SLIPS if detector(corners, mine, expected)),
                            "Every triangle shares the first corner: (a, b, c), (a, c, d), ...")
            words = sentence.format(n=len(corners), count=len(expected), got=len(mine), first=corners[0])
            return failed("fan", checked, name, f"the reader makes {expected}, yours makes {mine}. {words}")
        checked.append(name)
    return passed("fan", checked, "Your fan matches the reader.")


def cut_cases(seed: int | None = None) -> list[tuple[str, np.ndarray]]:
    """``(name, vertices)`` for :func:`check_cut`: the bowtie's faces on these positions.

    Public: chapter 04's bowtie. With a ``seed``, the hidden cases: the same two
    triangles touching at vertex 0, stretched, turned and moved at random.
    """
    if seed is None:
        return [("bowtie", BOWTIE_VERTICES.copy())]
    rng = hidden_rng(seed)
    cases = []
    for number in range(1, 4):
        rotation, _ = np.linalg.qr(rng.standard_normal((3, 3)))
        stretched = BOWTIE_VERTICES * rng.uniform(0.5, 2.0, 3)
        stretched[1:] += 0.2 * rng.uniform(-1.0, 1.0, (4, 3)) * [1, 1, 0]
        vertices = stretched @ rotation.T + rng.uniform(-3.0, 3.0, 3)
        cases.append((hidden_name(number, "a bowtie of another shape, turned and moved"), vertices))
    return cases


def check_cut(cut_bowtie: Callable, *, seed: int | None = None) -> CheckResult:
    """``cut_bowtie(vertices, faces) -> (vertices, faces)``: the bowtie cut apart, judged by shape.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    cases = cut_cases(seed)
    if (blanks := _blanks_left("cut", "cut_bowtie", cut_bowtie)) is not None:
        return counted(blanks, len(cases))
    return counted(_check_cut(cut_bowtie, cases), len(cases))


def _corner_points(vertices: np.ndarray, face) -> list[tuple[float, ...]]:
    """A face as the rounded positions of its corners, turned to start at the smallest one."""
    points = [tuple(np.round(vertices[int(v)], 9).tolist()) for v in face]
    k = points.index(min(points))
    return points[k:] + points[:k]


def _cut_problem(vertices: np.ndarray, cut_vertices, cut_faces) -> str | None:
    """What is wrong with a cut of the bowtie, judged by shape, not by numbers: None if right.

    Right means: it builds a halfedge mesh; it has the bowtie's two triangles, each with
    the same corner positions in the same turning order (starting at any corner, so
    ``[3, 4, 5]`` and ``[5, 3, 4]`` are one triangle); and the two fans no longer share a vertex.
    """
    cut_vertices = np.asarray(cut_vertices, dtype=np.float64)
    cut_faces = np.asarray(cut_faces)
    wanted = [_corner_points(vertices, face) for face in BOWTIE_FACES]
    yours = [_corner_points(cut_vertices, face) for face in cut_faces]
    if len(yours) != len(wanted):
        return (f"the bowtie has {len(wanted)} triangles, yours {len(yours)}: cutting changes which vertex a "
                f"face uses, not how many faces there are.")
    for k, face in enumerate(cut_faces.tolist()):
        if yours[k] in wanted:
            continue
        turned = [yours[k][0], yours[k][2], yours[k][1]]
        if turned in wanted:
            return (f"your face {k}, {face}, has the right corners but runs the other way round (clockwise): "
                    f"the copy takes the place of vertex 0 in the same position of the row, so the face keeps "
                    f"its orientation. Rotating a row ([5, 3, 4] for [3, 4, 5]) is fine; swapping two corners is not.")
        return (f"your face {k}, {face}, has corners at positions that no bowtie triangle has: the copy must sit "
                f"exactly where vertex 0 is, and the other corners stay.")
    used = [set(int(v) for v in face) for face in cut_faces]
    if used[0] & used[1]:
        shared = sorted(used[0] & used[1])
        return (f"your two triangles still share vertex {shared[0]}: give one of the two fans the copy.")
    return None


def _check_cut(cut_bowtie: Callable, cases: list[tuple[str, np.ndarray]]) -> CheckResult:
    """:func:`check_cut` on the given cases."""
    checked: list[str] = []
    for name, vertices in cases:
        answer, failure = _call("cut", "cut_bowtie", cut_bowtie, vertices.copy(), BOWTIE_FACES.copy(),
                                mesh_name=name, checked=checked)
        if failure is not None:
            return failure
        try:
            cut_vertices, cut_faces = answer
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", MeshWarning)   # an unused copy is dropped: still a mesh
                mesh = HalfedgeMesh.from_faces(cut_vertices, cut_faces)
        except MeshInputError as error:
            return failed("cut", checked, name, f"your faces do not build a halfedge mesh: {error}")
        except (TypeError, ValueError, IndexError) as error:
            return failed("cut", checked, name, f"cut_bowtie should return (vertices, faces); building from "
                           f"yours failed: {type(error).__name__}: {error}")
        problem = _cut_problem(vertices, cut_vertices, cut_faces)
        if problem is not None:
            return failed("cut", checked, name, f"it builds ({mesh}), but {problem}")
        checked.append(name)
    return passed("cut", checked, f"{mesh}: the same two triangles as the bowtie, no longer touching "
                  f"(repair_faces does the same for every pinched vertex).")


def smooth_once_in_place(mesh: HalfedgeMesh, order) -> np.ndarray:
    """The classic mistake of chapter 05: one smoothing pass that reads and writes one array.

    Returns the (V, 3) positions after visiting the vertices in ``order``; each vertex
    already sees its earlier neighbours' *new* positions (Gauss-Seidel, not Jacobi).
    """
    positions = mesh.positions.copy()                    # read AND write here: the mistake
    for i in order:
        vertex = mesh.vertex(i)
        if not vertex.is_boundary:
            positions[i] = positions[[u.index for u in vertex.neighbors()]].mean(axis=0)
    return positions


def laplacian_cases(seed: int | None = None) -> dict[str, HalfedgeMesh]:
    """The meshes of :func:`check_laplacian_step` by name: a cube, a patch with one vertex
    raised, an icosphere; with a ``seed``, the hidden cases: a jittered closed mesh, a
    jittered grid patch and a closed mesh after random flips (other degrees)."""
    if seed is None:
        patch = sample("open_patch")
        patch.vertex(5).position = [1.0, 1.0, 0.5]        # something to smooth
        return {"cube": sample("cube"), "open_patch": patch, "icosphere": sample("icosphere", subdivisions=1)}
    rng = hidden_rng(seed)
    shape, other = (str(name) for name in rng.choice(["cube", "octahedron", "icosphere(1)", "icosphere(2)"], 2,
                                                      replace=False))
    rows, columns = (int(n) for n in rng.integers(2, 5, 2))
    flips = int(rng.integers(3, 9))
    return {
        hidden_name(1, f"{shape}, every vertex nudged"): hidden.jittered(hidden.closed_mesh(shape), rng, 0.05),
        hidden_name(2, f"a {rows} x {columns} grid patch, nudged"): HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng)),
        hidden_name(3, f"{other} after {flips} random flips"): hidden.flipped(hidden.closed_mesh(other), flips, rng),
    }


def check_laplacian_step(step: Callable, *, seed: int | None = None) -> CheckResult:
    """``step(mesh) -> (V, 3)`` positions against ``smooth(mesh, 1)`` on three meshes.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    meshes = laplacian_cases(seed)
    if (blanks := _blanks_left("laplacian_step", "laplacian_step", step)) is not None:
        return counted(blanks, len(meshes))
    return counted(_check_laplacian_step(step, meshes), len(meshes))


#: Said when a learner's smoothing moves boundary vertices too, as UChicago's P5 may (its meshes have none).
_NO_BOUNDARY_NOTE = (
    "On {names} your step also moves the boundary vertices to the mean of their neighbours. UChicago's "
    "assignment says not to worry about boundaries (its meshes have none), so there your answer is right: it "
    "was judged on the closed meshes, where it agrees. This chapter keeps boundary vertices where they are, "
    "because averaging a boundary vertex with its inside neighbours pulls the outline inwards and the patch "
    "shrinks a little at every step.")


def _every_vertex_averaged(mesh: HalfedgeMesh) -> np.ndarray:
    """(V, 3): every vertex, boundary ones too, at the mean of its neighbours' old positions."""
    old = mesh.positions
    new = old.copy()
    for vertex in mesh.vertices:
        new[vertex.index] = old[[u.index for u in vertex.neighbors()]].mean(axis=0)
    return new


def _check_laplacian_step(step: Callable, meshes: dict[str, HalfedgeMesh]) -> CheckResult:
    """:func:`check_laplacian_step` on the given meshes.

    A step that averages boundary vertices too (UChicago's, written for closed meshes) is
    judged only on the closed meshes; the open ones are named in the congratulation.
    """
    checked: list[str] = []
    not_judged: list[str] = []     # meshes with a boundary, where the learner followed UChicago's no-boundary rule
    for name, mesh in meshes.items():
        before = mesh.positions.copy()
        answer, failure = _call("laplacian_step", "laplacian_step", step, mesh, mesh_name=name, checked=checked,
                                mesh=mesh)
        if failure is not None:
            return failure
        if not np.array_equal(mesh.positions, before):
            return failed("laplacian_step", checked, name, "your function changed mesh.positions. Return a new "
                           "array instead; the mesh should stay as it was.")
        yours = np.asarray(answer, dtype=float)
        if yours.shape != before.shape:
            return failed("laplacian_step", checked, name,
                           f"expected an array of shape {before.shape}, got {yours.shape}.")
        wanted = smooth(mesh, 1).positions
        wrong = np.flatnonzero(~np.isclose(yours, wanted).all(axis=1))
        if len(wrong) == 0:
            checked.append(name)
            continue
        v = mesh.vertex(int(wrong[0]))
        element = ("vertex", v.index)
        if v.is_boundary and np.allclose(yours, _every_vertex_averaged(mesh)):
            not_judged.append(name)
            checked.append(f"{name} (interior only)")
            continue
        if v.is_boundary:
            return failed("laplacian_step", checked, name, f"vertex {v.index} is on the boundary and should stay "
                           f"at {before[v.index].round(4)}, but yours moved it.", element, mesh)
        if np.allclose(yours, smooth_once_in_place(mesh, range(mesh.n_vertices))):
            return failed("laplacian_step", checked, name,
                           f"vertex {v.index} should be at {wanted[v.index].round(4)}, yours is at "
                           f"{yours[v.index].round(4)}. Your result matches updating the positions in place "
                           f"(Gauss-Seidel): read every neighbour from a copy of the old positions.", element, mesh)
        return failed("laplacian_step", checked, name,
                       f"vertex {v.index} should move to the mean of its neighbours "
                       f"{[u.index for u in v.neighbors()]}, {wanted[v.index].round(4)}, but yours is at "
                       f"{yours[v.index].round(4)}.", element, mesh)
    if not_judged:
        if len(not_judged) == len(meshes):
            return failed("laplacian_step", [], None, "your step also moves boundary vertices (UChicago's rule, "
                          "meant for closed meshes), and every mesh here has a boundary, so it cannot be judged "
                          "on a closed one. Keep boundary vertices where they are (skip v.is_boundary).")
        return passed("laplacian_step", checked, "It agrees with smooth(mesh, 1) on the closed meshes. "
                      + _NO_BOUNDARY_NOTE.format(names=", ".join(repr(n) for n in not_judged)))
    return passed("laplacian_step", checked, "It agrees with smooth(mesh, 1).")


def _vertex_set(vertices) -> str:
    return "{" + ", ".join("∂" if v == BOUNDARY else str(v) for v in sorted(vertices)) + "}"


#: What the check adds when a learner's answer follows a course's own rule where the package's differs.
_TETRAHEDRON_NOTE = (
    "On the tetrahedron your function calls the collapse safe: that is the link condition as UChicago's "
    "assignment states it (the one-rings of a and b share exactly two vertices), and with vertices_only=True "
    "it is accepted. This "
    "package also compares the links' edges and refuses it (can_collapse's rule 'tetrahedron'): the edge "
    "between the two opposite vertices lies in both links, and the collapse would leave two triangles glued "
    "back to back on three vertices, a two-face 'pillow' with no inside on which no flip, split or collapse "
    "works any more (pmp-library and OpenMesh allow it)."
)
#: The failure's words when the vertex part holds but the links share an edge, and the full condition is asked.
_LINK_EDGE_WORDS = (
    ", exactly the vertices opposite the edge, so the vertex part holds; but the edge {l} - {r} between those "
    "two opposite vertices lies in both links, so the collapse is NOT safe: it would leave two triangles glued "
    "back to back on three vertices, a two-face 'pillow' with no inside. The link condition compares the "
    "links' edges too, and this chapter asks for all of it. (Only the vertex part is the link condition as "
    "UChicago's assignment states it: if you follow that assignment, check_collapse_is_safe(your_function, "
    "vertices_only=True) judges it that way.)"
)
_BOUNDARY_NOTE = (
    "Your function refuses boundary edges that the link condition allows, as CMU's assignment asks (ignore "
    "requests to collapse boundary edges): accepted. This package collapses a boundary edge when the link "
    "condition holds with the boundary counted as one more vertex, as chapter 08 shows."
)


def _hidden_collapse_meshes(seed: int, with_boundary: bool) -> dict[str, HalfedgeMesh]:
    """The hidden meshes of :func:`check_collapse_is_safe`: closed meshes after random
    collapses and flips (low degrees, where the link condition fails), and with
    ``with_boundary`` a grid patch after random collapses."""
    rng = hidden_rng(seed)

    def collapsed(mesh: HalfedgeMesh, count: int) -> HalfedgeMesh:
        for _ in range(count):
            allowed = [e.index for e in mesh.edges if can_collapse(mesh, e)]
            if not allowed:
                break
            collapse(mesh, int(rng.choice(allowed)))
        return HalfedgeMesh.from_faces(*mesh.to_arrays())

    first, second = int(rng.integers(15, 30)), int(rng.integers(2, 5))
    flips = int(rng.integers(3, 8))
    meshes = {
        f"icosphere(1) after {first} random collapses": collapsed(sample("icosphere", subdivisions=1), first),
        f"octahedron after {flips} random flips": hidden.flipped(sample("octahedron"), flips, rng),
        f"cube after {second} random collapses": collapsed(sample("cube"), second),
    }
    if with_boundary:
        rows, columns = (int(n) for n in rng.integers(2, 4, 2))
        patch = HalfedgeMesh.from_faces(*hidden.grid(rows, columns, rng))
        meshes[f"a {rows} x {columns} grid patch after 2 random collapses"] = collapsed(patch, 2)
    return {hidden_name(number, name): mesh for number, (name, mesh) in enumerate(meshes.items(), start=1)}


def _collapse_meshes(with_boundary: bool) -> dict[str, HalfedgeMesh]:
    """The meshes of :func:`check_collapse_is_safe`: four closed ones, and four with boundary on request."""
    sphere = sample("icosphere", subdivisions=1)
    rng = np.random.default_rng(8)
    for _ in range(25):
        allowed = [e.index for e in sphere.edges if can_collapse(sphere, e)]
        collapse(sphere, int(rng.choice(allowed)))
    meshes = {"tetrahedron": sample("tetrahedron"), "cube": sample("cube"),
              "octahedron": sample("octahedron"), "icosphere after 25 collapses": sphere}
    if with_boundary:
        cube_vertices, cube_faces = sample("cube").to_arrays()
        meshes.update({"cube without its first triangle": HalfedgeMesh.from_faces(cube_vertices, cube_faces[1:]),
                       "open_patch": sample("open_patch"), "figure8": sample("figure8"),
                       "lone_triangle": sample("lone_triangle")})
    return meshes


def _unsafe_words(lc, on_boundary: bool) -> str:
    """Why the collapse of an edge that the learner called safe is not, naming the likely mistake."""
    others = sorted(v for v in lc.shared.vertices - lc.link_ab.vertices if v != BOUNDARY)
    if BOUNDARY in lc.extra.vertices:
        return (", and the edge has a triangle on each side but both its ends lie on the boundary: the merged "
                "vertex would lie on the boundary twice (a figure-8 pinch), so the collapse is NOT safe. This is "
                "the boundary case: count the boundary as one more neighbour ∂ of every boundary vertex (chapter "
                "08, section 4), or refuse an interior edge whose two ends are on the boundary.")
    if not others:   # what is left of the link condition: an edge from ∂ in both links
        return (", and its triangle has all three edges on the boundary (a lone triangle): collapsing it would "
                "leave a bare edge with no face, so the collapse is NOT safe. This is a boundary case: with the "
                "boundary counted as a vertex ∂, the edge from ∂ to the opposite vertex lies in both links.")
    words = (f", so they also share {_vertex_set(others)}: its edges to a and to b would become one doubled edge, "
             f"and the collapse is NOT safe.")
    if on_boundary:
        return words + (" On a boundary edge there is only one opposite vertex: 'the rings share exactly two "
                        "vertices' (UChicago's statement) assumes an edge with a triangle on each side; compare "
                        "WHICH vertices are shared with the opposite ones, not how many.")
    return words + " Only the vertices opposite the edge may be shared."


def check_collapse_is_safe(is_safe: Callable, *, with_boundary: bool = False, vertices_only: bool = False,
                           seed: int | None = None) -> CheckResult:
    """``is_safe(mesh, e) -> bool`` against ``link_condition`` on every edge of four closed meshes.

    The last closed mesh is an icosphere after 25 random collapses, which leaves
    vertices of low degree, where the interesting cases live. ``with_boundary=True``
    adds four meshes with boundary (a cube without one triangle, ``open_patch``,
    ``figure8``, ``lone_triangle``).

    Each course's stated rule is accepted where it differs from the package's alone:

    * UChicago's "the two one-rings share exactly two vertices" looks at vertices only
      and calls the tetrahedron's edges safe; the package also compares the links'
      edges and refuses them. With ``vertices_only=True`` (a UChicago learner) that is
      accepted, and the passing message says why the package refuses (the two-face
      pillow); by default (chapter 08 asks for the whole link condition) it is refused,
      and the failure names UChicago's statement and ``vertices_only``.
    * CMU's "ignore requests to collapse boundary edges" refuses boundary edges the
      package allows. Accepted, and said.

    Everything else must agree with ``link_condition`` (the boundary counted as ∂):
    a shared neighbour besides the opposite vertices, an interior edge with both ends
    on the boundary, a lone triangle are each named when called safe.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases
    made from it (closed meshes after random collapses and flips).
    """
    meshes = _collapse_meshes(with_boundary) if seed is None else _hidden_collapse_meshes(seed, with_boundary)
    if (blanks := _blanks_left("collapse_is_safe", "collapse_is_safe", is_safe)) is not None:
        return counted(blanks, len(meshes))
    return counted(_check_collapse_is_safe(is_safe, meshes, vertices_only), len(meshes))


def _check_collapse_is_safe(is_safe: Callable, meshes: dict[str, HalfedgeMesh], vertices_only: bool) -> CheckResult:
    """:func:`check_collapse_is_safe` on the given meshes (``vertices_only``: UChicago's statement)."""
    checked: list[str] = []
    notes: dict[str, None] = {}   # the course rules the learner's function followed, in order, once each
    for name, mesh in meshes.items():
        for edge in mesh.edges:
            answer, failure = _call("collapse_is_safe", "collapse_is_safe", is_safe, mesh, edge.index,
                                    mesh_name=name, checked=checked, element=("halfedge", 2 * edge.index), mesh=mesh)
            if failure is not None:
                return failure
            lc = link_condition(mesh, edge.index)
            if bool(answer) == bool(lc):
                continue
            vertex_part_holds = not lc.extra.vertices and all(BOUNDARY not in pair for pair in lc.extra.edges)
            if answer and vertex_part_holds and vertices_only:
                notes[_TETRAHEDRON_NOTE] = None        # the vertex part holds: UChicago's rule
                continue
            if not answer and edge.is_boundary:
                notes[_BOUNDARY_NOTE] = None           # CMU refuses every boundary edge
                continue
            words = (f"edge {edge.index} (a = {lc.a}, b = {lc.b}): the rings share {_vertex_set(lc.shared.vertices)}, "
                     f"the opposite vertices are {_vertex_set(lc.link_ab.vertices)}")
            if answer and vertex_part_holds:
                l, r = sorted(v for v in lc.link_ab.vertices if v != BOUNDARY)
                words += _LINK_EDGE_WORDS.format(l=l, r=r)
            elif answer:
                words += _unsafe_words(lc, edge.is_boundary)
            else:
                words += (", exactly the vertices opposite the edge, so the collapse is safe; yours says not safe. "
                          "A one-ring holds a vertex's neighbours, not the vertex itself, and the opposite vertices "
                          "are those of the edge's own triangles (h.prev.vertex for h and h.twin).")
            return failed("collapse_is_safe", checked, name, words, ("halfedge", 2 * edge.index), mesh)
        checked.append(name)
    return passed("collapse_is_safe", checked, " ".join(["It agrees with link_condition on every edge." if not notes
                  else "It follows a course's own rule where the package's differs.", *notes]))


# --------------------------------------------------------------------------------------
# Chapter 04, second exercise: UChicago P3, non-manifold detection on a soup topology
# --------------------------------------------------------------------------------------

def _two_fans_joined_elsewhere() -> np.ndarray:
    """Two triangles at vertex 0 joined through faces that do not touch 0: one connected surface
    (0-1-2 reaches 0-3-4 across edges (1, 2), (1, 5), (5, 4), (4, 3)), but two fans at 0."""
    return np.array([[0, 1, 2], [0, 3, 4], [2, 1, 5], [5, 4, 3], [5, 1, 4]])


def _pinched_grids(rng: np.random.Generator) -> tuple[str, np.ndarray]:
    """Two grid patches sharing only one corner vertex (a pinch), renumbered at random."""
    rows, columns = (int(n) for n in rng.integers(1, 3, 2))
    _, first = hidden.grid(rows, columns, rng)
    _, second = hidden.grid(rows, columns, rng)
    n = int(first.max()) + 1
    second = second + n
    second[second == n] = 0                                   # the second patch's corner 0 is the first's
    faces = np.vstack([first, second])
    used = np.unique(faces)
    renumber = np.full(int(used.max()) + 1, -1)
    renumber[used] = rng.permutation(len(used))
    return f"two {rows} x {columns} grid patches touching at one corner", renumber[faces]


def _extra_page(rng: np.random.Generator) -> tuple[str, np.ndarray]:
    """A closed mesh with one more triangle on one of its edges (three faces there)."""
    shape = str(rng.choice(["tetrahedron", "cube", "octahedron"]))
    _, faces = hidden.closed_mesh(shape).to_arrays()
    a, b = (int(v) for v in faces[int(rng.integers(len(faces)))][:2])
    page = np.array([[a, b, int(faces.max()) + 1]])
    return f"{shape} with a third face on one edge", np.vstack([faces, page])


def nonmanifold_cases(seed: int | None = None) -> list[tuple[str, np.ndarray]]:
    """``(name, faces)`` for :func:`check_nonmanifold`: manifold meshes with and without
    boundary, the book (three faces on an edge), two cones touching at a tip, the bowtie,
    two fans joined away from their vertex. With a ``seed``, the hidden cases instead."""
    if seed is not None:
        rng = hidden_rng(seed)
        rows, columns = (int(n) for n in rng.integers(2, 4, 2))
        shape = str(rng.choice(list(hidden.CLOSED_SHAPES)))
        cases = [(f"a {rows} x {columns} grid patch, renumbered", hidden.renumbered(*hidden.grid(rows, columns, rng), rng)[1]),
                 (f"{shape}, renumbered", hidden.renumbered(*hidden.closed_mesh(shape).to_arrays(), rng)[1]),
                 _pinched_grids(rng), _extra_page(rng)]
        return [(hidden_name(k, name), np.asarray(faces)) for k, (name, faces) in enumerate(cases, start=1)]
    return [
        ("cube", sample("cube").to_arrays()[1]),
        ("open_patch", sample("open_patch").to_arrays()[1]),
        ("strip (every vertex on the boundary)", sample("strip").to_arrays()[1]),
        ("the book: three faces on edge (0, 1)", sample("nonmanifold_edge").faces),
        ("two tetrahedra touching at vertex 0", sample("nonmanifold_vertex").faces),
        ("the bowtie", BOWTIE_FACES.copy()),
        ("two fans at vertex 0, joined away from it", _two_fans_joined_elsewhere()),
    ]


#: The non-manifold slips, in the order tried: (name, detector, sentence). A detector gets
#: ``(question, soup, answer)`` with ``question`` "edges" or "vertices" and the learner's
#: (wrong) answer; the sentence may use ``{edge}``, ``{v}``, ``{fans}``. Each row is tested
#: with the slip's own code in tests/exercises/test_nonmanifold_check.py.
NONMANIFOLD_SLIPS: tuple[tuple[str, Callable, str], ...] = (
    ("a boundary edge called non-manifold",
     lambda question, soup, answer: question == "edges" and answer
     and any(len(soup.faces_of_edge(*e)) == 1 for e in soup.edges()),
     "No edge here has more than two faces; edge {edge} has just one, which makes it a boundary edge, and a "
     "boundary edge is manifold: an edge is manifold with one face or two."),
    ("a boundary vertex called non-manifold",
     lambda question, soup, answer: question == "vertices" and answer
     and any(len(soup.faces_of_edge(*e)) == 1 for e in soup.edges()),
     "Every vertex here has its faces in one fan. On the boundary (vertex {v}) the fan does not close into a "
     "full ring, and that is still manifold: the rule is one fan, not a closed one."),
    ("faces connected anywhere instead of across edges at the vertex",
     lambda question, soup, answer: question == "vertices" and not answer and _fans_joined_elsewhere(soup),
     "Vertex {v}'s faces form {count} fans, {fans}: they are joined through other faces, but not across an edge "
     "at vertex {v}. Walk from face to face only across the edges that touch the vertex."),
)


def _fans_joined_elsewhere(soup) -> bool:
    """Whether some non-manifold vertex's fans are joined through faces away from it."""
    for v in soup.nonmanifold_vertices():
        faces = soup.faces_of_vertex(v)
        reached, stack = {faces[0]}, [faces[0]]
        while stack:
            f = stack.pop()
            for k in range(3):
                a, b = (int(x) for x in (soup.faces[f][k], soup.faces[f][(k + 1) % 3]))
                for g in soup.faces_of_edge(a, b):
                    if g not in reached:
                        reached.add(g)
                        stack.append(g)
        if set(faces) <= reached:
            return True
    return False


def check_nonmanifold(has_nonmanifold_edges: Callable, has_nonmanifold_vertices: Callable, *,
                      seed: int | None = None) -> CheckResult:
    """``has_nonmanifold_edges(soup) -> bool`` and ``has_nonmanifold_vertices(soup) -> bool``
    (``soup`` a :class:`~halfedge_edu.core.soup.SoupTopology`) against the library's answers.

    As UChicago's P3 says, the vertex question is not judged on a face list that is not
    edge-manifold ("you do not need to check vertex manifoldness when the mesh is not edge
    manifold"); the congratulation says so.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    cases = nonmanifold_cases(seed)
    for name, function in (("has_nonmanifold_edges", has_nonmanifold_edges),
                           ("has_nonmanifold_vertices", has_nonmanifold_vertices)):
        if (blanks := _blanks_left("nonmanifold", name, function)) is not None:
            return counted(blanks, len(cases))
    return counted(_check_nonmanifold(has_nonmanifold_edges, has_nonmanifold_vertices, cases), len(cases))


def _check_nonmanifold(has_nonmanifold_edges: Callable, has_nonmanifold_vertices: Callable,
                       cases: list[tuple[str, np.ndarray]]) -> CheckResult:
    """:func:`check_nonmanifold` on the given face lists."""
    from halfedge_edu.core.soup import SoupTopology

    checked: list[str] = []
    for name, faces in cases:
        soup = SoupTopology(faces)
        edge_problem = soup.has_nonmanifold_edges()
        for question, function in (("edges", has_nonmanifold_edges), ("vertices", has_nonmanifold_vertices)):
            if question == "vertices" and edge_problem:
                continue                     # UChicago: vertices need not be judged when an edge is not manifold
            answer, failure = _call("nonmanifold", f"has_nonmanifold_{question}", function, soup, mesh_name=name,
                                    checked=checked)
            if failure is not None:
                return failure
            wanted = soup.has_nonmanifold_edges() if question == "edges" else soup.has_nonmanifold_vertices()
            if not isinstance(answer, (bool, np.bool_)):
                return failed("nonmanifold", checked, name, f"has_nonmanifold_{question} should return True or "
                              f"False, but yours returned {answer!r:.60}.")
            if bool(answer) == wanted:
                continue
            words = (f"has_nonmanifold_{question} says {bool(answer)}, but it should be {wanted}. ")
            if question == "edges" and wanted:
                edge = soup.nonmanifold_edges()[0]
                words += (f"Edge {edge} has {len(soup.faces_of_edge(*edge))} faces ({soup.faces_of_edge(*edge)}); an "
                          f"edge is manifold with one face or two. soup.faces_of_edge(a, b) lists them.")
            elif question == "vertices" and wanted and not _fans_joined_elsewhere(soup):
                v = soup.nonmanifold_vertices()[0]
                words += (f"Vertex {v}'s faces form {len(soup.fans(v))} fans, {soup.fans(v)}: you cannot walk from "
                          f"one to the other across edges at vertex {v}.")
            boundary_edge = next((e for e in soup.edges() if len(soup.faces_of_edge(*e)) == 1), None)
            boundary_vertex = boundary_edge[0] if boundary_edge else None
            for _, detector, sentence in NONMANIFOLD_SLIPS:
                if detector(question, soup, answer):
                    v = soup.nonmanifold_vertices()[0] if soup.nonmanifold_vertices() else boundary_vertex
                    fans = soup.fans(v) if v is not None else []
                    words += sentence.format(edge=boundary_edge, v=v, fans=fans, count=len(fans))
                    break
            return failed("nonmanifold", checked, name, words)
        checked.append(name)
    return passed("nonmanifold", checked, (
        "Your two questions agree with the library on every face list, built without breaking. As UChicago's "
        "P3 allows, the vertex question was not asked where an edge is already non-manifold."))
