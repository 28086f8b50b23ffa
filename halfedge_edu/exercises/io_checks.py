"""The check of chapter 01's OBJ exercise: a reader and a writer of your own.

    from halfedge_edu.exercises.chapter_checks import check_obj_io, check_obj_reader, check_obj_writer
    check_obj_reader(read_obj)          # read_obj(text or pathlib.Path) -> (vertices, faces)
    check_obj_writer(write_obj)         # write_obj(vertices, faces) -> the OBJ text
    check_obj_io(read_obj, write_obj)   # both, then your writer's text back through your reader

This is the first task of the Loop-subdivision assignment (read and write Wavefront OBJ).
The reference is the package's own reader, :func:`halfedge_edu.io.read_obj`: each case
is a small OBJ text made to show one thing a reader must get right (comments, blank
lines, ``vt``/``vn`` records, ``v/vt/vn`` and ``v//vn`` corners, negative indices, a
quad, Windows line ends, a last line without a line break), and a difference is told
as the file line, what it should give, what the learner's function gave and, where the
answer shows it, the mistake by name.

**Faces.** The exercise expects each ``f`` record as one face, its 0-based corners in
the file's order, so a quad stays a list of four. Faces cut into fans the way
``hx.read_obj`` cuts them, ``(a, b, c), (a, c, d), ...``, are accepted too. The Loop
assignment lets a reader skip or refuse polygons; these files have a quad, so skipping
or refusing it is reported, with that said.

**Writer.** ``write_obj(vertices, faces)`` returns the file's text; it is judged by
reading that text with ``hx.read_obj``: the same vertices (to 1e-6, the six decimals
many exporters write; ``repr(x)`` writes each float exactly) and the same faces in the
same corner order (the order is the face's orientation).
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Callable

import numpy as np

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io import read_obj as reference_read_obj

from .harness import CheckResult, all_good, counted, failed, hidden_name, hidden_rng, run, trouble, unfinished

__all__ = ["READER_CASES", "ReaderCase", "check_obj_io", "check_obj_reader", "check_obj_writer"]

#: How close a written coordinate must read back (six decimals, as many exporters write).
COORDINATE_TOLERANCE = 1e-6


@dataclass(frozen=True)
class ReaderCase:
    """One OBJ text for the reader, and the rule it is there to test, in words (the hint).

    ``beyond_loop`` names what the case has that the Loop assignment's reader need not
    read (it asks only for ``v``, ``f`` and ``#`` comment lines, triangles), or is ""
    when the case is within that spec.
    """

    name: str
    text: str
    rule: str
    beyond_loop: str = ""


def _grid_text(corner: Callable[[int, int, int], str]) -> str:
    """Twelve vertices, six texture coordinates, two normals, and two faces whose corners
    ``corner(vertex, texture, normal)`` writes (1-based): vertex numbers up to 12, so a
    reader that takes one character of a corner gets them wrong."""
    vertices = "".join(f"v {x} {y} 0\n" for y in range(3) for x in range(4))
    records = "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 0.5 0\nvt 0 0.5\nvn 0 0 1\nvn 0 0 -1\n"
    faces = (f"f {corner(10, 4, 2)} {corner(11, 3, 2)} {corner(7, 6, 2)}\n"
             f"f {corner(11, 1, 2)} {corner(12, 5, 2)} {corner(8, 2, 2)}\n")
    return "o grid\nmtllib grid.mtl\n" + vertices + records + "g top\nusemtl red\ns off\n" + faces


_PYRAMID = """\
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0.5 0.5 0.8
f 1 4 3 2
f 1 2 5
f 2 3 5
f 3 4 5
f 4 1 5
"""

_COMMENTED = """\
# a square of two triangles

v 0 0 0   # the origin
v 1 0 0
v 0 1 0

v 1 1 0
# the faces
f 1 2 3   # the first one
   \t
f 2 4 3
"""

#: The reader's cases, in the order they are checked.
READER_CASES: tuple[ReaderCase, ...] = (
    ReaderCase("one triangle", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
               "'f 1 2 3' names the first three vertices, 0, 1 and 2 in Python (OBJ counts from 1)"),
    ReaderCase("comment lines", "# a triangle\nv 0 0 0\nv 1 0 0\n# its third corner\nv 0 1 0\nf 1 2 3\n",
               "a line whose first character is '#' is a comment: skip it"),
    ReaderCase("comments and blank lines", _COMMENTED,
               "skip blank lines and everything from a '#' to the end of its line",
               "blank lines and comments after a record"),
    ReaderCase("spaces and tabs", "v  0\t0 0\nv 1   0 0\nv\t0 1 0\nf 1  2\t3\n",
               "the words of a record may be separated by several spaces or tabs: split on any whitespace"),
    ReaderCase("vt/vn records and v/vt/vn corners", _grid_text(lambda v, t, n: f"{v}/{t}/{n}"),
               "only a line whose first word is exactly 'v' is a vertex ('vt', 'vn', 'o', 'g', 'usemtl', 's', "
               "'mtllib' are other records), and in a corner 'v/vt/vn' the vertex is the number before the "
               "first '/'", "vt/vn records and v/vt/vn corners"),
    ReaderCase("v//vn and v/vt corners", _grid_text(lambda v, t, n: f"{v}//{n}" if v != 11 else f"{v}/{t}"),
               "in a corner 'v//vn' or 'v/vt' the vertex is the number before the first '/'", "v//vn and v/vt corners"),
    ReaderCase("negative indices", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nv 2 1 0\nf 2 -2 -1\nv 5 5 5\n",
               "a negative index counts back from the last vertex defined ABOVE its line (-1 is the newest "
               "so far), not from the end of the file", "negative indices"),
    ReaderCase("a quad", _PYRAMID,
               "a face may have more than three corners: keep the polygon as one face (what this exercise "
               "expects), or cut it into the fan (a, b, c), (a, c, d) as hx.read_obj does", "a face of four corners"),
    ReaderCase("Windows line ends (CRLF)", _COMMENTED.replace("\n", "\r\n"),
               "a line may end in '\\r\\n': str.splitlines() and str.split() take the '\\r' away",
               "blank lines and comments after a record"),
    ReaderCase("no line break at the end", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3",
               "the last line may have no line break after it and is a record all the same"),
)


def _reference(text: str) -> tuple[np.ndarray, list[tuple[int, list[int]]], list[list[int]]]:
    """What ``hx.read_obj`` makes of ``text``: vertices, (line, polygon) per ``f`` record, fan triangles.

    The reader cuts each polygon into a fan ``(a, b, c), (a, c, d), ...`` and keeps the
    line of each triangle; the polygon ``a, b, c, d, ...`` is put back together from them.
    """
    data = reference_read_obj(io.StringIO(text))
    polygons: dict[int, list[int]] = {}
    for (a, b, c), line in zip(data.faces.tolist(), data.face_lines.tolist()):
        polygons.setdefault(line, [a, b]).append(c)
    return data.vertices, list(polygons.items()), data.faces.tolist()


def _vertices_above(text: str, line: int) -> int:
    """How many ``v`` records come before 1-based ``line`` of ``text``."""
    return sum(1 for record in text.splitlines()[: line - 1] if record.split()[:1] == ["v"])


def _faces_of(answer) -> list[list[int]] | None:
    """The learner's faces as lists of ints, or None if they are not a list of index lists."""
    try:
        return [[int(corner) for corner in face] for face in answer]
    except (TypeError, ValueError):
        return None


def _shifted(faces: list[list[int]], by: int) -> list[list[int]]:
    return [[corner + by for corner in face] for face in faces]


def _corner_numbers(record: str, part: int) -> list[int] | None:
    """The ``part``-th number (0 vertex, 1 texture, 2 normal) of each corner of an ``f`` record, 0-based."""
    numbers = []
    for corner in record.split("#", 1)[0].split()[1:]:
        pieces = corner.split("/")
        if len(pieces) <= part or not pieces[part]:
            return None
        numbers.append(int(pieces[part]) - 1)
    return numbers


def _face_mistake(case: ReaderCase, line: int, expected: list[int], yours: list[int]) -> str:
    """The mistake one wrong face shows, in words (the case's rule when none is recognised)."""
    record = case.text.splitlines()[line - 1].strip()
    if yours == [corner + 1 for corner in expected]:
        return "your indices are the file's, counted from 1: subtract 1 (OBJ's 'f 1 2 3' is vertices 0, 1, 2)."
    for part, what in ((1, "texture coordinate"), (2, "normal")):
        if "/" in record and yours == _corner_numbers(record, part):
            return (f"yours took the {what} index of each corner: in 'v/vt/vn', 'v//vn' and 'v/vt' the vertex "
                    f"index is the number before the first '/'.")
    if any(word.startswith("-") for word in record.split()[1:]):
        above = _vertices_above(case.text, line)
        total = sum(1 for r in case.text.splitlines() if r.split()[:1] == ["v"])
        from_the_end = [total + int(w.split("/")[0]) if w.startswith("-") else int(w.split("/")[0]) - 1
                        for w in record.split("#", 1)[0].split()[1:]]
        words = (f"a negative index counts back from the last vertex defined above its line: {above} vertices "
                 f"are defined above line {line}, so -1 there is vertex {above - 1}.")
        if yours == from_the_end:
            words += (f" Yours counted back from the end of the whole file ({total} vertices), as Python's "
                      f"list[-1] does; vertices defined below the face do not count.")
        return words
    return f"{case.rule}."


def _judge_reader_answer(case: ReaderCase, answer) -> str | None:
    """What is wrong with ``read_obj``'s answer for ``case``, in words; None if it is right."""
    vertices, polygons, fans = _reference(case.text)
    try:
        your_vertices, your_faces = answer
        your_vertices = np.asarray(your_vertices, dtype=float)
    except (TypeError, ValueError):
        return (f"read_obj should return (vertices, faces), an (n, 3) array of floats and a list of faces; "
                f"yours returned {answer!r:.80}.")
    faces = _faces_of(your_faces)
    if faces is None:
        return f"the faces should be a list of faces, each a list of vertex indices; yours are {your_faces!r:.80}."
    if your_vertices.size == 0 and len(vertices):
        your_vertices = your_vertices.reshape(0, 3)
    if your_vertices.ndim != 2 or your_vertices.shape[1] != 3:
        return (f"the vertices should be an (n, 3) array, one row x y z per 'v' line; yours have shape "
                f"{your_vertices.shape}.")
    records = case.text.splitlines()
    if len(your_vertices) != len(vertices):
        others = sum(1 for r in records if r.split()[:1] in (["vt"], ["vn"]))
        words = f"the file has {len(vertices)} 'v' lines, your read_obj returned {len(your_vertices)} vertices."
        if others and len(your_vertices) == len(vertices) + others:
            return words + (" It also read the 'vt' and 'vn' lines as vertices: a vertex is a line whose first "
                            "word is exactly 'v'.")
        return words + f" Here: {case.rule}."
    wrong = np.flatnonzero(~np.isclose(your_vertices, vertices).all(axis=1))
    if len(wrong):
        i = int(wrong[0])
        return (f"vertex {i} should be {vertices[i].tolist()}, yours is {your_vertices[i].tolist()}: each 'v' "
                f"line's three numbers, x y z, in the file's order.")
    wanted = [corners for _, corners in polygons]
    if faces in (wanted, fans):
        return None
    if _shifted(faces, -1) in (wanted, fans):
        return "your indices are the file's, counted from 1: subtract 1 (OBJ's 'f 1 2 3' is vertices 0, 1, 2)."
    if len(faces) != len(wanted) and len(faces) != len(fans):
        lines = [line for line, _ in polygons]
        if faces in (wanted[:-1], fans[: -(len(polygons[-1][1]) - 2)]) and not case.text.endswith("\n"):
            return (f"the last line, {records[-1]!r}, has no line break after it, and your read_obj dropped it: "
                    f"read every line, the last one too (str.splitlines() gives it).")
        skipped = [line for line, corners in polygons if len(corners) > 3]
        if skipped and faces == [corners for corners in wanted if len(corners) == 3]:
            return (f"your read_obj skipped the quad on line {skipped[0]} ({records[skipped[0] - 1].strip()!r}). "
                    f"The Loop assignment allows that; this exercise has polygons: keep it as one face of four "
                    f"corners (expected), or cut it into a fan as hx.read_obj does (also accepted).")
        return (f"the file has {len(wanted)} 'f' lines (on lines {', '.join(map(str, lines))}), your read_obj "
                f"returned {len(faces)} faces. Here: {case.rule}.")
    # Compare face by face in the learner's own form: polygons kept, or fans.
    as_polygons = (len(faces) == len(wanted) and any(len(face) > 3 for face in faces)) or len(faces) != len(fans)
    reference, lines = (wanted, [line for line, _ in polygons]) if as_polygons else (
        fans, [line for line, corners in polygons for _ in range(len(corners) - 2)])
    k = next(k for k, (mine, right) in enumerate(zip(faces, reference)) if mine != right)
    record = records[lines[k] - 1].strip()
    return (f"line {lines[k]}, {record!r}, should give the face {reference[k]}, yours is {faces[k]}: "
            + _face_mistake(case, lines[k], reference[k], faces[k]))


def _random_polygons(rng: np.random.Generator, n_vertices: int, count: int, largest: int) -> list[list[int]]:
    """``count`` faces of 3 to ``largest`` distinct corners each (0-based), at random."""
    return [rng.choice(n_vertices, size=int(rng.integers(3, largest + 1)), replace=False).tolist()
            for _ in range(count)]


def _random_vertices(rng: np.random.Generator, count: int) -> np.ndarray:
    """(count, 3) coordinates with four decimals, some negative."""
    return np.round(rng.uniform(-5.0, 5.0, (count, 3)), 4)


def _rule(name: str) -> ReaderCase:
    """The public reader case called ``name`` (its rule and what it has beyond the Loop spec)."""
    return next(case for case in READER_CASES if case.name == name)


def _hidden_reader_cases(rng: np.random.Generator) -> list[ReaderCase]:
    """OBJ texts of the same kinds as :data:`READER_CASES`, with other numbers: triangles
    with comment lines (within the Loop assignment's spec); ``v/vt/vn`` corners past
    vertex 9; negative indices; polygons."""
    cases = []
    n = int(rng.integers(12, 20))
    vertices = _random_vertices(rng, n)
    v_lines = [f"v {x} {y} {z}" for x, y, z in vertices.tolist()]

    triangles = _random_polygons(rng, n, 4, 3)
    lines = ["# a random soup", *v_lines[:3], "# more vertices", *v_lines[3:], "# the faces",
             *(f"f {' '.join(str(c + 1) for c in face)}" for face in triangles)]
    comments = _rule("comment lines")
    cases.append(ReaderCase("comment lines", "\n".join(lines) + "\n", comments.rule))

    faces = [[c for c in face] for face in _random_polygons(rng, n, 4, 3)]
    faces[0][0] = max(faces[0][0], 10)                           # a vertex number of two digits
    corners = "\n".join("f " + " ".join(f"{c + 1}/{int(rng.integers(1, 4))}/1" for c in face) for face in faces)
    text = "\n".join(v_lines) + "\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n" + corners + "\n"
    corner_case = _rule("vt/vn records and v/vt/vn corners")
    cases.append(ReaderCase(corner_case.name, text, corner_case.rule, corner_case.beyond_loop))

    first = int(rng.integers(4, n - 3))
    negative = rng.choice(first, size=3, replace=False).tolist()   # among the vertices above the face
    face_line = "f " + " ".join(str(c - first) for c in negative)  # c - first counts back from vertex first - 1
    text = "\n".join(v_lines[:first]) + "\n" + face_line + "\n" + "\n".join(v_lines[first:]) + \
        "\nf " + " ".join(str(c + 1) for c in _random_polygons(rng, n, 1, 3)[0]) + "\n"
    negative_case = _rule("negative indices")
    cases.append(ReaderCase(negative_case.name, text, negative_case.rule, negative_case.beyond_loop))

    polygons = _random_polygons(rng, n, 3, 6)
    polygons[0] = polygons[0] + [c for c in range(n) if c not in polygons[0]][: 4 - len(polygons[0])] \
        if len(polygons[0]) < 4 else polygons[0]                    # at least one polygon of 4 or more corners
    text = "\n".join(v_lines) + "\n" + "\n".join("f " + " ".join(str(c + 1) for c in face) for face in polygons) + "\n"
    quad = _rule("a quad")
    cases.append(ReaderCase("polygons", text, quad.rule, "faces of more than three corners"))
    return [ReaderCase(hidden_name(number, f"a random OBJ text with {case.name}"), case.text, case.rule,
                       case.beyond_loop) for number, case in enumerate(cases, start=1)]


def _hidden_writer_cases(rng: np.random.Generator) -> tuple:
    """Writer cases like :data:`WRITER_CASES`: random vertices, random triangles (as an
    array) and random polygons (as lists)."""
    n = int(rng.integers(5, 14))
    triangles = np.asarray(_random_polygons(rng, n, int(rng.integers(2, 6)), 3))
    m = int(rng.integers(6, 12))
    return ((hidden_name(5, f"{n} random vertices and {len(triangles)} triangles"), rng.uniform(-1.0, 1.0, (n, 3)),
             triangles),
            (hidden_name(6, f"{m} random vertices and polygons of 3 to 6 corners"), _random_vertices(rng, m),
             _random_polygons(rng, m, 4, 6)))


#: The congratulation's sentence for a reader or writer that follows the Loop assignment's OBJ spec.
_LOOP_SPEC_NOTE = (
    "Your {which} follows the Loop assignment's OBJ spec ('v', 'f' and '#' lines, triangles), which is all "
    "that assignment asks for, so it is accepted. Beyond that spec it {refusals}. Chapter 01 goes further; "
    "for the first of these: {hint}")


def _loop_refusal(case: ReaderCase, status: str, answer) -> str | None:
    """How a reader written to the Loop assignment's spec turned down ``case`` (which has
    something beyond that spec), in words; None if it did not simply turn it down.

    Turning down is: raising an error (not NotImplementedError: that is a blank), skipping
    the faces of more than three corners (the assignment allows "skip or report an
    error"), or leaving negative indices as the numbers they are, minus one (a reader
    that never heard of them).
    """
    if not case.beyond_loop:
        return None
    if status == "error":
        if isinstance(answer, NotImplementedError) or "ellipsis" in str(answer).lower():
            return None
        return f"raised {type(answer).__name__} on {case.beyond_loop} ({case.name!r})"
    if status != "ok":
        return None
    try:
        _, your_faces = answer
    except (TypeError, ValueError):
        return None
    faces = _faces_of(your_faces)
    if faces is None:
        return None
    _, polygons, _ = _reference(case.text)
    triangles_only = [corners for _, corners in polygons if len(corners) == 3]
    if len(triangles_only) < len(polygons) and faces == triangles_only:
        return f"skipped {case.beyond_loop} ({case.name!r}), as that assignment allows"
    records = [line.split("#", 1)[0].split() for line in case.text.splitlines()]
    raw = [[int(word.split("/")[0]) - 1 for word in record[1:]] for record in records if record[:1] == ["f"]]
    if "negative" in case.beyond_loop and faces == raw:
        return f"leaves negative indices as they are ({case.name!r})"
    return None


def _reader_failure(read_obj: Callable, checked: list[str], cases: tuple[ReaderCase, ...] = READER_CASES,
                    with_real_file: bool = True, refusals: list[tuple[str, str]] | None = None) -> CheckResult | None:
    """Run ``read_obj`` on every case and on a real file; the first failure, or None.

    A case beyond the Loop assignment's spec that the reader turns down the way a reader
    of that spec would (:func:`_loop_refusal`) is not a failure: it goes into
    ``refusals`` as ``(what it did, the rule chapter 01 teaches there)``.
    """
    refusals = [] if refusals is None else refusals
    for case in cases:
        status, answer = run(read_obj, case.text)
        refusal = _loop_refusal(case, status, answer)
        problem = trouble(status, answer, "read_obj")
        words = None if problem is not None else _judge_reader_answer(case, answer)
        if refusal is not None and (problem is not None or words is not None):
            refusals.append((refusal, f"{case.rule}."))
            checked.append(f"{case.name} (beyond the Loop spec)")
            continue
        if problem is not None:
            if status == "error" and not isinstance(answer, NotImplementedError):
                problem += f" Here: {case.rule}."
            return failed("obj_io", checked, case.name, problem, error=answer)
        if words is not None:
            return failed("obj_io", checked, case.name, words)
        checked.append(case.name)
    if not with_real_file:
        return None
    with resources.as_file(resources.files("halfedge_edu.data").joinpath("spot.obj")) as spot:
        status, answer = run(read_obj, Path(spot))
        name = "spot.obj, given as a pathlib.Path"
        real = ReaderCase(name, spot.read_text(), "a real exporter's file: v and v/vt corners", "v/vt corners")
        problem = trouble(status, answer, "read_obj")
        words = None if problem is not None else _judge_reader_answer(real, answer)
        refusal = _loop_refusal(real, status, answer)
        if refusal is not None and (problem is not None or words is not None):
            refusals.append((refusal, f"{real.rule}."))
            checked.append("spot.obj (beyond the Loop spec)")
            return None
        if problem is not None:
            return failed("obj_io", checked, name, problem + " read_obj should also read a file given as a "
                          "pathlib.Path (Path.read_text() gives its text).", error=answer)
    if words is not None:
        return failed("obj_io", checked, name, words)
    checked.append("spot.obj")
    return None


def _loop_praise(which: str, refusals: list[tuple[str, str]]) -> str:
    """The sentence naming the Loop assignment's convention, or "" when the reader/writer did it all."""
    if not refusals:
        return ""
    return " " + _LOOP_SPEC_NOTE.format(which=which, refusals="; ".join(r for r, _ in refusals), hint=refusals[0][1])


#: The writer's cases: (name, vertices, faces as the learner gets them).
WRITER_CASES = (
    ("tetrahedron with awkward coordinates",
     np.array([[0.0, 0.0, 0.0], [1 / 3, 0.0, 0.0], [0.0, 2 / 3, 1e-7], [0.1, 0.2, 0.3]]),
     np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])),
    ("pyramid with a square floor", reference_read_obj(io.StringIO(_PYRAMID)).vertices,
     [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]),
)


def _fans(faces) -> list[list[int]]:
    return [[int(face[0]), int(face[k]), int(face[k + 1])] for face in faces for k in range(1, len(face) - 1)]


def _writer_refusal(faces, status: str, text) -> str | None:
    """How a writer of the Loop assignment's spec (triangles only) turned down faces of more
    than three corners, in words: it raised, or wrote only their first three corners, or
    left them out. None if ``faces`` are all triangles or the writer did something else."""
    if all(len(face) == 3 for face in faces):
        return None
    if status == "error":
        if isinstance(text, NotImplementedError) or "ellipsis" in str(text).lower():
            return None
        return f"raised {type(text).__name__} on faces of more than three corners"
    if status != "ok" or not isinstance(text, str):
        return None
    try:
        read_back = reference_read_obj(io.StringIO(text)).faces.tolist()
    except MeshInputError:
        return None
    if read_back == [[int(c) for c in face[:3]] for face in faces]:
        return "wrote only the first three corners of each face of more than three"
    if read_back == [[int(c) for c in face] for face in faces if len(face) == 3]:
        return "left out the faces of more than three corners"
    return None


def _writer_failure(write_obj: Callable, checked: list[str], cases: tuple = WRITER_CASES,
                    refusals: list[tuple[str, str]] | None = None) -> CheckResult | None:
    """Run ``write_obj`` on every case and read its text with ``hx.read_obj``; the first failure, or None.

    Faces of more than three corners turned down as a writer of the Loop assignment's
    spec would (:func:`_writer_refusal`) go into ``refusals`` instead of failing.
    """
    refusals = [] if refusals is None else refusals
    for name, vertices, faces in cases:
        status, text = run(write_obj, vertices.copy(), [list(face) for face in faces]
                           if isinstance(faces, list) else faces.copy())
        refusal = _writer_refusal(faces, status, text)
        if refusal is not None:
            refusals.append((refusal, "write each face as one 'f' line with all its corners, a quad too."))
            checked.append(f"{name} (beyond the Loop spec)")
            continue
        problem = trouble(status, text, "write_obj")
        if problem is not None:
            return failed("obj_io", checked, name, problem, error=text)
        if not isinstance(text, str):
            return failed("obj_io", checked, name, f"write_obj should return the file's text (a str); yours "
                          f"returned {type(text).__name__}.")
        try:
            again = reference_read_obj(io.StringIO(text))
        except MeshInputError as error:
            words = f"hx.read_obj cannot read your file: {error}."
            if "index 0" in str(error):
                words += " OBJ counts from 1: write each index + 1."
            return failed("obj_io", checked, name, words)
        if again.vertices.shape != vertices.shape:
            return failed("obj_io", checked, name, f"your file has {len(again.vertices)} 'v' lines for "
                          f"{len(vertices)} vertices: one line 'v x y z' per vertex.")
        wrong = np.flatnonzero(~np.isclose(again.vertices, vertices, rtol=0, atol=COORDINATE_TOLERANCE).all(axis=1))
        if len(wrong):
            i = int(wrong[0])
            return failed("obj_io", checked, name, f"vertex {i} is {vertices[i].tolist()}, but your file gives "
                          f"{again.vertices[i].tolist()}: write enough digits (repr(x) writes the float exactly).")
        wanted, read_back = _fans(faces), again.faces.tolist()
        if read_back == wanted:
            checked.append(name)
            continue
        if read_back == _shifted(wanted, -1):
            words = "your file has the 0-based indices: OBJ counts from 1, write each index + 1."
        elif len(read_back) != len(wanted):
            words = (f"your file gives {len(read_back)} triangles for faces {[list(map(int, f)) for f in faces]}: "
                     f"write each face as one 'f' line with all its corners, a quad too.")
        else:
            k = next(k for k, (mine, right) in enumerate(zip(read_back, wanted)) if mine != right)
            words = (f"triangle {k} should read back as {wanted[k]}, yours is {read_back[k]}: write each face's "
                     f"corners in the order given (the order is the face's orientation), each index + 1.")
        return failed("obj_io", checked, name, words)
    return None


def _check_one(function: Callable, name: str, find_failure: Callable, praise: str, total: int) -> CheckResult:
    """Run one of the two finders (``_reader_failure``, ``_writer_failure``, already given
    their cases) on ``function``; ``total`` is how many cases that runs."""
    if words := unfinished(function, name):
        return counted(failed("obj_io", [], None, words), total)
    checked: list[str] = []
    refusals: list[tuple[str, str]] = []
    failure = find_failure(function, checked, refusals)
    if failure is None:
        failure = all_good("obj_io", checked, "cases", praise + _loop_praise(name, refusals))
    return counted(failure, total)


def _io_cases(seed: int | None) -> tuple[tuple[ReaderCase, ...], bool, tuple, tuple[np.ndarray, list[list[int]]], str]:
    """Everything the OBJ checks run: reader cases, whether to read spot.obj, writer cases,
    the round trip's (vertices, polygons) and its name. Hidden ones with a ``seed``."""
    if seed is None:
        pyramid_vertices, pyramid_polygons, _ = _reference(_PYRAMID)
        return (READER_CASES, True, WRITER_CASES, (pyramid_vertices, [corners for _, corners in pyramid_polygons]),
                "round trip: the pyramid through your write_obj and your read_obj")
    rng = hidden_rng(seed)
    readers, writers = _hidden_reader_cases(rng), _hidden_writer_cases(rng)
    n = int(rng.integers(5, 10))
    return (tuple(readers), False, writers, (_random_vertices(rng, n), _random_polygons(rng, n, 3, 5)),
            hidden_name(7, "random polygons through your write_obj and your read_obj"))


def check_obj_reader(read_obj: Callable, *, seed: int | None = None) -> CheckResult:
    """``read_obj(text or Path) -> (vertices, faces)`` against ``hx.read_obj`` on the cases of this module.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    readers, real_file, _, _, _ = _io_cases(seed)
    return _check_one(read_obj, "read_obj",
                      lambda f, checked, refusals: _reader_failure(f, checked, readers, real_file, refusals),
                      "Your reader reads what hx.read_obj reads.", len(readers) + real_file)


def check_obj_writer(write_obj: Callable, *, seed: int | None = None) -> CheckResult:
    """``write_obj(vertices, faces) -> str`` read back with ``hx.read_obj``: the same vertices and faces.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    _, _, writers, _, _ = _io_cases(seed)
    return _check_one(write_obj, "write_obj",
                      lambda f, checked, refusals: _writer_failure(f, checked, writers, refusals),
                      "hx.read_obj reads your files back as they were written.", len(writers))


def check_obj_io(read_obj: Callable, write_obj: Callable, *, seed: int | None = None) -> CheckResult:
    """The reader, the writer, then the writer's text read back by the learner's own reader.

    A reader and writer written to the Loop assignment's spec (only ``v``, ``f`` and ``#``
    lines, triangles; polygons skipped or refused) pass: what they turned down is said,
    and their round trip is made with triangles.

    ``seed``: None for the public cases (the chapter's); an int for only the hidden cases made from it.
    """
    readers, real_file, writers, round_trip, name = _io_cases(seed)
    total = len(readers) + real_file + len(writers) + 1
    for function_name, function in (("read_obj", read_obj), ("write_obj", write_obj)):
        if words := unfinished(function, function_name):
            return counted(failed("obj_io", [], None, words), total)
    return counted(_check_obj_io(read_obj, write_obj, readers, real_file, writers, round_trip, name), total)


def _check_obj_io(read_obj: Callable, write_obj: Callable, readers: tuple[ReaderCase, ...], real_file: bool,
                  writers: tuple, round_trip: tuple[np.ndarray, list[list[int]]], name: str) -> CheckResult:
    """:func:`check_obj_io` on the given cases."""
    checked: list[str] = []
    reader_refusals: list[tuple[str, str]] = []
    writer_refusals: list[tuple[str, str]] = []
    failure = _reader_failure(read_obj, checked, readers, real_file, reader_refusals)   # a failed result is falsy
    if failure is None:
        failure = _writer_failure(write_obj, checked, writers, writer_refusals)
    if failure is not None:
        return failure
    trip_vertices, trip_faces = round_trip
    if reader_refusals or writer_refusals:        # the Loop spec: make the round trip with triangles
        trip_faces = _fans(trip_faces)
        name += " (as triangles, the Loop spec)"
    status, answer = run(write_obj, trip_vertices.copy(), [list(face) for face in trip_faces])
    if status == "ok":
        status, answer = run(read_obj, answer)
    if (problem := trouble(status, answer, "read_obj or write_obj")) is not None:
        return failed("obj_io", checked, name, problem, error=answer)
    try:
        vertices, faces = answer
    except (TypeError, ValueError):
        return failed("obj_io", checked, name, f"read_obj should return (vertices, faces); on your writer's text "
                      f"it returned {answer!r:.80}.")
    faces = _faces_of(faces)
    same = np.allclose(np.asarray(vertices, dtype=float), trip_vertices, rtol=0, atol=COORDINATE_TOLERANCE)
    if not same or faces not in (trip_faces, _fans(trip_faces)):
        return failed("obj_io", checked, name, f"writing these faces and reading them back gives {faces} (faces), "
                      f"not {trip_faces}: the writer and the reader should be inverses.")
    checked.append("round trip")
    return all_good("obj_io", checked, "cases", "Your reader and writer agree with hx.read_obj and with each other."
                    + _loop_praise("read_obj", reader_refusals) + _loop_praise("write_obj", writer_refusals))
