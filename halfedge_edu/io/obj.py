"""Reading and writing Wavefront OBJ files: the package's own parser (chapter 01).

An OBJ file is text, one record per line. The first word says what the line is:

    # a comment (also after a record: ``v 0 0 0  # origin``)
    v 0.0 1.0 2.0          a vertex position x y z (a 4th value ``w``, or colours, are ignored)
    f 1 2 3                a face: vertex indices, starting at 1, counter-clockwise
    f 1/4 2/5 3/6          ... with texture coordinate indices (``i/t``, ``i//n``, ``i/t/n``)
    f -3 -2 -1             ... negative: counted back from the last vertex defined so far

Every other record (``vt``, ``vn``, ``g``, ``o``, ``s``, ``usemtl``, ``mtllib``, ``l`` ...)
is skipped. A line ending in ``\\`` continues on the next line. Polygons with more than
three vertices are cut into a fan of triangles (i, j, k), (i, k, l), ...

The reader checks everything before it returns: a bad line raises ``MeshInputError``
whose ``.line`` is the 1-based line number and whose message quotes the line, and
nothing is half-loaded.
"""

from __future__ import annotations

import os
import secrets
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Iterator

import numpy as np

from halfedge_edu.core.errors import MeshInputError

__all__ = ["ObjData", "read_obj", "write_obj", "atomic_output"]

@dataclass
class ObjData:
    """What ``read_obj`` found in a file.

    Attributes:
        vertices: (n, 3) float64 positions, in file order (every ``v`` line).
        faces: (m, 3) int64 triangles, 0-based indices into ``vertices``.
        face_lines: (m,) int64, the 1-based line of the ``f`` record each triangle
            came from (the triangles of one polygon share its line).
        source: the file name, for messages.
        n_polygons_triangulated: how many ``f`` records had more than 3 vertices.
    """

    vertices: np.ndarray
    faces: np.ndarray
    face_lines: np.ndarray
    source: str
    n_polygons_triangulated: int = 0


#: Larger positive indices are rejected while parsing (the range check proper is at the end,
#: since a positive index may name a vertex defined further down the file).
_MAX_INDEX = 2**40


def _fail(source: str, line_no: int, text: str, problem: str) -> MeshInputError:
    """The error for one bad line: names the file, the line number and quotes the line."""
    return MeshInputError(f"{source}, line {line_no}: {problem}: {text.strip()!r}", line=line_no)


def _read_text(path_or_file) -> tuple[str, str]:
    """Return (text, source name). A missing file raises FileNotFoundError."""
    if hasattr(path_or_file, "read"):
        source = str(getattr(path_or_file, "name", "<file>"))
        data = path_or_file.read()
    else:
        source = Path(path_or_file).name
        try:
            with open(path_or_file, "rb") as file:
                data = file.read()
        except FileNotFoundError:
            raise
        except OSError as error:
            raise MeshInputError(f"{source}: cannot read the file ({error})") from error
    if isinstance(data, str):
        data = data.encode("utf-8", "surrogateescape")
    if b"\x00" in data:
        raise MeshInputError(f"{source}: this is a binary file, not a text OBJ file")
    # Invalid UTF-8 bytes (e.g. Latin-1 in a comment) become U+FFFD: harmless in
    # comments, and reported as an unparsable number if they are in a v or f record.
    return data.decode("utf-8", errors="replace"), source


def _logical_lines(text: str) -> Iterator[tuple[int, str]]:
    """Yield (1-based line number, line) with comments removed and ``\\`` continuations joined.

    A joined line carries the number of its first physical line.
    """
    pending, pending_no = "", 0
    for line_no, line in enumerate(text.split("\n"), start=1):
        line = line.split("#", 1)[0].rstrip()  # also drops the \r of CRLF files
        if line.endswith("\\"):
            if not pending:
                pending_no = line_no
            pending += line[:-1] + " "
            continue
        if pending:
            line, line_no, pending = pending + line, pending_no, ""
        yield line_no, line
    if pending:
        yield pending_no, pending


def read_obj(path_or_file: str | os.PathLike | IO, *, triangulate: bool = True) -> ObjData:
    """Read the vertices and triangles of an OBJ file.

    Args:
        path_or_file: a path, or an open file (text or binary).
        triangulate: cut polygons into fans of triangles; if False, a polygon with
            more than 3 vertices raises ``MeshInputError`` naming its line.

    Returns:
        ``ObjData`` with 0-based (m, 3) faces and the file line of each face.

    Raises:
        FileNotFoundError: the file does not exist.
        MeshInputError: a line that cannot be read (with ``.line`` set and the line
            quoted), a binary or unreadable file, or a file without faces.

    Attention: vertices no face uses are kept here (``ObjData.vertices`` is every ``v``
    record); ``HalfedgeMesh.from_faces`` drops them with a warning. A negative index
    counts back from the vertices defined above its line; a positive one may also name
    a vertex defined further down.
    """
    text, source = _read_text(path_or_file)

    coordinates: list[list[str]] = []  # the x y z tokens of each v record, parsed below
    vertex_lines: list[int] = []
    faces: list[tuple[int, int, int]] = []  # 0-based, checked for range below
    face_lines: list[int] = []
    n_polygons = 0

    for line_no, line in _logical_lines(text):
        tokens = line.split()
        if not tokens:
            continue  # blank line or comment
        keyword = tokens[0]
        if keyword == "v":
            if len(tokens) < 4:
                raise _fail(source, line_no, line, "a vertex needs 3 coordinates x y z")
            coordinates.append(tokens[1:4])
            vertex_lines.append(line_no)
        elif keyword == "f":
            corners = []
            for token in tokens[1:]:
                try:
                    index = int(token.split("/", 1)[0])
                except ValueError:
                    raise _fail(source, line_no, line, f"{token!r} is not a vertex index") from None
                if index > _MAX_INDEX:  # would not fit an int64 array; no file has this many vertices
                    raise _fail(source, line_no, line, f"vertex index {index} is out of range")
                if index > 0:
                    corners.append(index - 1)  # OBJ counts from 1
                elif index < 0:
                    if -index > len(coordinates):
                        raise _fail(
                            source, line_no, line,
                            f"index {index} points before the first vertex "
                            f"(only {len(coordinates)} vertices are defined above this line)",
                        )
                    corners.append(len(coordinates) + index)  # -1 is the last one so far
                else:
                    raise _fail(source, line_no, line, "vertex index 0 is not allowed (OBJ indices start at 1)")
            if len(corners) < 3:
                raise _fail(source, line_no, line, f"a face needs at least 3 vertices, this one has {len(corners)}")
            if len(corners) > 3:
                if not triangulate:
                    raise _fail(
                        source, line_no, line,
                        f"a polygon with {len(corners)} vertices (read with triangulate=True to cut it into triangles)",
                    )
                n_polygons += 1
            for k in range(1, len(corners) - 1):  # fan: (i, j, k), (i, k, l), ...
                faces.append((corners[0], corners[k], corners[k + 1]))
                face_lines.append(line_no)

    vertices = _parse_coordinates(coordinates, vertex_lines, text, source)
    if not faces:
        raise MeshInputError(f"{source}: no faces found (no 'f' lines), so there is no mesh to build")
    faces_array = np.array(faces, dtype=np.int64)  # (m, 3)
    lines_array = np.array(face_lines, dtype=np.int64)  # (m,)

    out_of_range = np.flatnonzero((faces_array >= len(vertices)).any(axis=1))
    if len(out_of_range):
        first = out_of_range[0]
        line_no = int(lines_array[first])
        bad = int(faces_array[first].max()) + 1
        raise _fail(
            source, line_no, _physical_line(text, line_no),
            f"vertex index {bad} is out of range (the file has {len(vertices)} vertices)",
        )
    return ObjData(vertices, faces_array, lines_array, source, n_polygons)


def _parse_coordinates(coordinates: list[list[str]], vertex_lines: list[int], text: str, source: str) -> np.ndarray:
    """Turn the x y z tokens into an (n, 3) float64 array, all at once.

    numpy parses the strings in one call (much faster than ``float()`` per token); only
    if that fails do we go back line by line to find the bad one.
    """
    if not coordinates:
        return np.zeros((0, 3))
    try:
        vertices = np.array(coordinates, dtype=np.str_).astype(np.float64)  # (n, 3)
    except ValueError:
        vertices = np.array([_parse_row(row, line_no, text, source) for row, line_no in zip(coordinates, vertex_lines)])
    not_finite = np.flatnonzero(~np.isfinite(vertices).all(axis=1))
    if len(not_finite):
        line_no = vertex_lines[not_finite[0]]
        raise _fail(source, line_no, _physical_line(text, line_no), "a coordinate is not finite (nan or inf)")
    return vertices


def _parse_row(row: list[str], line_no: int, text: str, source: str) -> list[float]:
    """The slow path: parse one v record's tokens, naming the line if one is not a number."""
    values = []
    for token in row:
        try:
            values.append(float(token))
        except ValueError:
            raise _fail(source, line_no, _physical_line(text, line_no), f"{token!r} is not a number") from None
    return values


def _physical_line(text: str, line_no: int) -> str:
    """Line ``line_no`` (1-based) of ``text``, for an error message."""
    return text.split("\n", line_no)[line_no - 1]


@contextmanager
def atomic_output(path: str | os.PathLike, mode: str = "w") -> Iterator[IO]:
    """Open a temporary file beside ``path``; on success move it onto ``path``.

    If the body raises, the temporary file is removed and ``path`` is untouched, so a
    failed save never leaves a partial file behind.
    """
    path = Path(path)
    temporary = path.with_name(f".{path.name}.{secrets.token_hex(4)}.tmp")
    # os.open with 0o666 lets the umask set the permissions, as for a plain open().
    descriptor = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
    try:
        with os.fdopen(descriptor, mode, **({} if "b" in mode else {"encoding": "utf-8", "newline": "\n"})) as file:
            yield file
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def write_obj(
    path: str | os.PathLike | IO,
    vertices: np.ndarray,
    faces: np.ndarray,
    *,
    header: str | None = "written by halfedge_edu",
) -> None:
    """Write vertices and triangles as an OBJ file with 1-based indices.

    Coordinates are written with Python's ``repr`` (the shortest text that reads back
    as the same float64), so ``read_obj`` gives back exactly the same arrays.

    Args:
        path: where to write; the file is written beside it and moved into place, so
            a failure leaves no partial file. An open text file also works.
        vertices: (n, 3) float positions.
        faces: (m, 3) int triangles, 0-based.
        header: comment text for the top of the file (each line gets a ``#``); None for none.

    Raises:
        MeshInputError: wrong shapes, non-finite coordinates or out-of-range indices.
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise MeshInputError(f"vertices must have shape (n, 3), not {vertices.shape}")
    if faces.ndim != 2 or faces.shape[1] != 3 or (faces.size and not np.issubdtype(faces.dtype, np.integer)):
        raise MeshInputError(f"faces must be an (m, 3) integer array, not {faces.dtype} {faces.shape}")
    if not np.isfinite(vertices).all():
        bad = int(np.flatnonzero(~np.isfinite(vertices).all(axis=1))[0])
        raise MeshInputError(f"vertex {bad} has a non-finite coordinate", element=("vertex", bad))
    if faces.size and (faces.min() < 0 or faces.max() >= len(vertices)):
        bad = int(np.flatnonzero(((faces < 0) | (faces >= len(vertices))).any(axis=1))[0])
        raise MeshInputError(
            f"face {bad} {faces[bad].tolist()} has an index outside 0..{len(vertices) - 1}", element=("face", bad)
        )

    parts = []
    if header:
        parts.extend(f"# {line}".rstrip() + "\n" for line in header.splitlines())
        parts.append(f"# {len(vertices)} vertices, {len(faces)} faces\n")
    parts.extend("v %r %r %r\n" % tuple(row) for row in vertices.tolist())
    parts.extend("f %d %d %d\n" % tuple(row) for row in (faces.astype(np.int64) + 1).tolist())
    text = "".join(parts)

    if hasattr(path, "write"):
        path.write(text)
        return
    with atomic_output(path) as file:
        file.write(text)
