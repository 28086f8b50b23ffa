"""The checks of chapters 01, 04, 05 and 08, which the chapters used to define in a cell.

    from halfedge_edu.exercises.chapter_checks import check_fan, check_cut, check_laplacian_step, check_collapse_is_safe
    check_fan(fan)                          # chapter 01: cut a polygon into a fan like the OBJ reader
    check_obj_io(read_obj, write_obj)       # chapter 01: an OBJ reader and writer (see io_checks)
    check_cut(cut_bowtie)                   # chapter 04: give the bowtie's second fan its own vertex
    check_laplacian_step(laplacian_step)    # chapter 05: one Jacobi step of uniform smoothing
    check_collapse_is_safe(collapse_is_safe)   # chapter 08: the link condition from one-rings

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
from halfedge_edu.core.repair import repair_faces
from halfedge_edu.data import sample
from halfedge_edu.io import read_obj

from .harness import TIME_LIMIT, CheckResult, failed, passed, run, trouble, unfinished
from .io_checks import check_obj_io, check_obj_reader, check_obj_writer

__all__ = ["BOWTIE_FACES", "BOWTIE_VERTICES", "check_collapse_is_safe", "check_cut", "check_fan",
           "check_laplacian_step", "check_obj_io", "check_obj_reader", "check_obj_writer", "smooth_once_in_place"]

#: Chapter 04's bowtie: two triangles that share only vertex 0.
BOWTIE_VERTICES = np.array([[0, 0, 0], [1, -0.5, 0], [1, 0.5, 0], [-1, 0.5, 0], [-1, -0.5, 0]], dtype=float)
BOWTIE_FACES = np.array([[0, 1, 2], [0, 3, 4]])


def _blanks_left(exercise: str, name: str, function: Callable) -> CheckResult | None:
    """The "fill in the blanks" failure if the learner's function still holds a ``...``."""
    words = unfinished(function, name)
    return failed(exercise, [], None, words) if words else None


def _call(exercise: str, name: str, function: Callable, *args, mesh_name: str | None = None,
          checked: list[str] | None = None) -> tuple[object, CheckResult | None]:
    """Run the learner's function: ``(value, None)``, or ``(None, a failed result saying why)``."""
    status, value = run(function, *args)
    if status == "timeout":
        return None, failed(exercise, checked or [], mesh_name,
                             f"your {name} did not return within {TIME_LIMIT:g} s: a loop probably never ends.")
    if status == "error":
        return None, failed(exercise, checked or [], mesh_name, trouble("error", value, name))
    return value, None


def check_fan(fan: Callable) -> CheckResult:
    """``fan(corners) -> [(a, b, c), ...]`` against the OBJ reader's fans of 3 to 8 corners."""
    if (blanks := _blanks_left("fan", "fan", fan)) is not None:
        return blanks
    checked: list[str] = []
    for n in range(3, 9):
        text = "v 0 0 0\n" * n + "f " + " ".join(str(i) for i in range(1, n + 1)) + "\n"
        expected = read_obj(io.StringIO(text)).faces.tolist()
        name = f"{n} corners"
        answer, failure = _call("fan", "fan", fan, list(range(n)), mesh_name=name, checked=checked)
        if failure is not None:
            return failure
        try:
            mine = [[int(corner) for corner in triangle] for triangle in answer]
        except TypeError:
            return failed("fan", checked, name, f"fan should return a list of triangles (a, b, c), "
                           f"but yours returned {answer!r:.60}.")
        if mine != expected:
            return failed("fan", checked, name, f"the reader makes {expected}, yours makes {mine}. Every "
                           f"triangle shares the first corner: (a, b, c), (a, c, d), ...")
        checked.append(name)
    return passed("fan", checked, "Your fan matches the reader.")


def check_cut(cut_bowtie: Callable) -> CheckResult:
    """``cut_bowtie(vertices, faces) -> (vertices, faces)`` against ``repair_faces`` on the bowtie."""
    if (blanks := _blanks_left("cut", "cut_bowtie", cut_bowtie)) is not None:
        return blanks
    answer, failure = _call("cut", "cut_bowtie", cut_bowtie, BOWTIE_VERTICES.copy(), BOWTIE_FACES.copy(),
                            mesh_name="bowtie")
    if failure is not None:
        return failure
    try:
        cut_vertices, cut_faces = answer
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", MeshWarning)   # an unused copy is dropped: still a mesh
            mesh = HalfedgeMesh.from_faces(cut_vertices, cut_faces)
    except MeshInputError as error:
        return failed("cut", [], "bowtie", f"your faces do not build a halfedge mesh: {error}")
    except (TypeError, ValueError) as error:
        return failed("cut", [], "bowtie", f"cut_bowtie should return (vertices, faces); building from "
                       f"yours failed: {type(error).__name__}: {error}")
    _, repaired, _ = repair_faces(BOWTIE_VERTICES, BOWTIE_FACES)
    if np.array_equal(np.asarray(cut_faces), repaired):
        return passed("cut", ["bowtie"], f"{mesh}: the same faces as repair_faces.")
    return failed("cut", [], "bowtie", f"it builds ({mesh}), but repair_faces gives {repaired.tolist()} "
                   f"and yours {np.asarray(cut_faces).tolist()}: give the second fan the copy, vertex 5.")


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


def check_laplacian_step(step: Callable) -> CheckResult:
    """``step(mesh) -> (V, 3)`` positions against ``smooth(mesh, 1)`` on three meshes."""
    if (blanks := _blanks_left("laplacian_step", "laplacian_step", step)) is not None:
        return blanks
    patch = sample("open_patch")
    patch.vertex(5).position = [1.0, 1.0, 0.5]        # something to smooth
    meshes = {"cube": sample("cube"), "open_patch": patch, "icosphere": sample("icosphere", subdivisions=1)}
    checked: list[str] = []
    for name, mesh in meshes.items():
        before = mesh.positions.copy()
        answer, failure = _call("laplacian_step", "laplacian_step", step, mesh, mesh_name=name, checked=checked)
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
    return passed("laplacian_step", checked, "It agrees with smooth(mesh, 1).")


def _vertex_set(vertices) -> str:
    return "{" + ", ".join("∂" if v == BOUNDARY else str(v) for v in sorted(vertices)) + "}"


def _edge_set(edges) -> str:
    return "{" + ", ".join(("∂" if i == BOUNDARY else str(i)) + "-" + str(j) for i, j in sorted(edges)) + "}"


def check_collapse_is_safe(is_safe: Callable) -> CheckResult:
    """``is_safe(mesh, e) -> bool`` against ``link_condition`` on every edge of four closed meshes.

    The last mesh is an icosphere after 25 random collapses, which leaves vertices of
    low degree, where the interesting cases live.
    """
    if (blanks := _blanks_left("collapse_is_safe", "collapse_is_safe", is_safe)) is not None:
        return blanks
    sphere = sample("icosphere", subdivisions=1)
    rng = np.random.default_rng(8)
    for _ in range(25):
        allowed = [e.index for e in sphere.edges if can_collapse(sphere, e)]
        collapse(sphere, int(rng.choice(allowed)))
    meshes = {"tetrahedron": sample("tetrahedron"), "cube": sample("cube"),
              "octahedron": sample("octahedron"), "icosphere after 25 collapses": sphere}
    checked: list[str] = []
    for name, mesh in meshes.items():
        for edge in mesh.edges:
            answer, failure = _call("collapse_is_safe", "collapse_is_safe", is_safe, mesh, edge.index,
                                    mesh_name=name, checked=checked)
            if failure is not None:
                return failure
            lc = link_condition(mesh, edge.index)
            if bool(answer) == bool(lc):
                continue
            words = (f"edge {edge.index} (a = {lc.a}, b = {lc.b}): the rings share {_vertex_set(lc.shared.vertices)}, "
                     f"the opposite vertices are {_vertex_set(lc.link_ab.vertices)}")
            element = ("halfedge", 2 * edge.index)
            if lc.extra.edges and not lc.extra.vertices:
                return failed("collapse_is_safe", checked, name, words + (
                    f", so the vertex part holds; but the edge {_edge_set(lc.extra.edges)} lies in both links "
                    "(both a and b make a triangle with it), so the collapse is NOT safe. Also test whether the "
                    "two opposite vertices are joined by an edge whose triangles reach both a and b."), element, mesh)
            verdict = "safe" if lc else "NOT safe"
            return failed("collapse_is_safe", checked, name, words + (
                f", so the collapse is {verdict}; yours says {'safe' if answer else 'not safe'}."), element, mesh)
        checked.append(name)
    return passed("collapse_is_safe", checked, "It agrees with link_condition on every edge.")
