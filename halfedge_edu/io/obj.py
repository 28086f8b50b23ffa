"""Reading and writing Wavefront OBJ files: the package's own parser (chapter 01).

An OBJ file is text, one record per line. The first word says what the line is:

    # a comment (also after a record: ``v 0 0 0  # origin``)
    v 0.0 1.0 2.0          a vertex position x y z (a 4th value ``w``, or colours, are ignored)
    f 1 2 3                a face: vertex indices, starting at 1, counter-clockwise
    f 1/4 2/5 3/6          ... with texture coordinate indices (``i/t``, ``i//n``, ``i/t/n``)
    f -3 -2 -1             ... negative: counted back from the last vertex defined so far

The other records of the OBJ format (``vt``, ``vn``, ``g``, ``o``, ``s``, ``usemtl``,
``mtllib``, ``l``, ``p``, the free-form ``curv``/``surf`` ... family) are skipped: they
are OBJ, just not triangles. A line that starts with any other word is not OBJ at all
and is an error naming its line, never skipped: skipping it could silently drop a
record (a ``v`` behind a stray character shifts every index after it). A line ending in
``\\`` continues on the next line. Polygons with more than three vertices are cut into a
fan of triangles (i, j, k), (i, k, l), ...

Encodings and line endings, each decided on purpose:

- UTF-8 and ASCII are read; a UTF-8 byte-order mark at the start is dropped.
- Lines may end in ``\\n`` (Unix), ``\\r\\n`` (Windows) or ``\\r`` alone (old Mac OS); a
  file may even mix them. Line numbers count lines as an editor shows them.
- Bytes that are not UTF-8 (Latin-1 in a comment, say) read as U+FFFD: harmless in a
  comment or a group name, an "is not a number" error with the line in a ``v``/``f``.
- UTF-16 and UTF-32 text (with or without a byte-order mark) is refused by name, and
  any other file with NUL bytes as binary: their records cannot be read line by line.

Numbers are read with OBJ's own syntax, as other OBJ readers read them, not Python's:
a coordinate is an optional sign, digits with an optional decimal point, and an
optional exponent (``1``, ``-0.5``, ``.5``, ``2.``, ``1e-3``, ``+1.5E+2``); an index is an
optional sign and digits. Anything else is an error naming its line: ``1_000`` (Python
reads it as 1000, other readers stop or refuse), ``nan`` and ``inf`` (not numbers a mesh
can use), ``0x10``, digits of other scripts.

The reader checks everything before it returns: a bad line raises ``MeshInputError``
whose ``.line`` is the 1-based line number and whose message quotes the line, and
nothing is half-loaded. Only regular files are read (a FIFO would block, a link to
``/dev/zero`` would never end).
"""

from __future__ import annotations

import codecs
import errno
import os
import re
import secrets
import stat
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Iterator

import numpy as np

from halfedge_edu.core.errors import MeshInputError

__all__ = ["ObjData", "read_obj", "write_obj", "atomic_output", "checked_arrays", "parse_coordinates",
           "path_error", "remove_stale_temporaries", "require_regular_file", "shown_path"]


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


#: Records of the OBJ format that carry no triangles (texture and normal data, grouping,
#: materials, lines and points, free-form geometry, display attributes): skipped.
SKIPPED_KEYWORDS = frozenset({
    "vt", "vn", "vp", "g", "o", "s", "mg", "usemtl", "mtllib", "usemap", "maplib", "l", "p",
    "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con",
    "lod", "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "ctech", "stech", "call", "csh",
})

#: One line break of any of the three conventions (Windows first, so \r\n is one break).
_LINE_BREAK = re.compile(r"\r\n|\r|\n")

#: A coordinate in OBJ's number syntax: optional sign, digits with an optional decimal
#: point (or a point then digits), optional exponent. ASCII only.
OBJ_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")

#: A vertex index in OBJ's syntax: optional sign, ASCII digits.
OBJ_INDEX = re.compile(r"[+-]?[0-9]+")

#: Any character that cannot appear in an OBJ number: the fast check before numpy parses.
_NOT_A_NUMBER_CHARACTER = re.compile(r"[^0-9eE.+-]")

#: Larger positive indices are rejected while parsing (the range check proper is at the end,
#: since a positive index may name a vertex defined further down the file).
_MAX_INDEX = 2**40


def _fail(source: str, line_no: int, text: str, problem: str) -> MeshInputError:
    """The error for one bad line: names the file, the line number and quotes the line."""
    return MeshInputError(f"{source}, line {line_no}: {problem}: {text.strip()!r}", line=line_no)


def require_regular_file(path: str | os.PathLike) -> None:
    """Raise ``MeshInputError`` unless ``path`` is a regular file (symbolic links followed).

    Reading a FIFO blocks until some other program writes to it, and a device such as
    ``/dev/zero`` never ends: a mesh is a file, so anything else is refused before it
    is opened. A missing file raises ``FileNotFoundError``.
    """
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise
    except OSError as error:
        raise path_error(path, error, "read") from error
    if stat.S_ISDIR(mode):
        raise MeshInputError(f"{Path(path).name}: cannot read the file (it is a folder, not a file)")
    if not stat.S_ISREG(mode):
        kind = "a FIFO (named pipe)" if stat.S_ISFIFO(mode) else "a device or socket"
        raise MeshInputError(f"{Path(path).name}: is {kind}, not a regular file; only mesh files can be read")


#: The longest path a message shows whole; a longer one is cut in the middle.
MAX_SHOWN_PATH = 120


def shown_path(path: str | os.PathLike) -> str:
    """``path`` for a message: whole, or if very long its start and end and its length.

    A path can be thousands of characters long; a message that quotes it whole is not
    one readable line any more.
    """
    text = os.fsdecode(path)
    if len(text) <= MAX_SHOWN_PATH:
        return text
    return f"{text[:60]}...{text[-40:]} ({len(text)} characters)"


def path_error(path: str | os.PathLike, error: OSError, action: str) -> MeshInputError:
    """The ``MeshInputError`` for a path the system refuses to ``action`` ("read" or "write").

    An over-long path (``ENAMETOOLONG``: a name over 255 bytes, or a whole path over
    the system's limit, 4096 bytes on Linux) is named as such, with the lengths; any
    other refusal gives the system's reason.
    """
    if error.errno == errno.ENAMETOOLONG:
        encoded = os.fsencode(path)
        longest = max((len(part) for part in encoded.split(b"/")), default=0)
        return MeshInputError(
            f"{shown_path(path)}: cannot {action} the file: the path is too long for this system "
            f"({len(encoded)} bytes, its longest name {longest} bytes; most systems allow names of up to "
            f"255 bytes and paths of up to 4096); use a shorter name or folder"
        )
    return MeshInputError(f"{shown_path(Path(path).name)}: cannot {action} the file ({error.strerror or error})")


def _read_text(path_or_file) -> tuple[str, str]:
    """Return (text, source name), decoded as the module docstring says.

    A missing file raises FileNotFoundError.
    """
    if hasattr(path_or_file, "read"):
        source = str(getattr(path_or_file, "name", "<file>"))
        data = path_or_file.read()
    else:
        source = Path(path_or_file).name
        require_regular_file(path_or_file)
        try:
            with open(path_or_file, "rb") as file:
                data = file.read()
        except OSError as error:
            raise MeshInputError(f"{source}: cannot read the file ({error.strerror or error})") from error
    if isinstance(data, str):
        data = data.encode("utf-8", "surrogateescape")
    wide = _wide_encoding(data)
    if wide:
        raise MeshInputError(f"{source}: the file is {wide} text; save it as UTF-8 (or ASCII) to read it")
    if b"\x00" in data:
        raise MeshInputError(f"{source}: this is a binary file, not a text OBJ file")
    data = data.removeprefix(codecs.BOM_UTF8)
    return data.decode("utf-8", errors="replace"), source


def _wide_encoding(data: bytes) -> str | None:
    """"UTF-16" or "UTF-32" if ``data`` looks like text in one of them, else None.

    Either the byte-order mark says so, or (without one) every second byte of the
    start is NUL, as in UTF-16 text of ASCII characters.
    """
    if data.startswith((codecs.BOM_UTF32_LE, codecs.BOM_UTF32_BE)):
        return "UTF-32"
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        return "UTF-16"
    start = data[:1024]
    if len(start) >= 4 and (start[0::2].count(0) == len(start[0::2]) or start[1::2].count(0) == len(start[1::2])):
        return "UTF-16"
    return None


def _logical_lines(text: str) -> Iterator[tuple[int, str]]:
    """Yield (1-based line number, line) with comments removed and ``\\`` continuations joined.

    A joined line carries the number of its first physical line.
    """
    pending, pending_no = "", 0
    for line_no, line in enumerate(_LINE_BREAK.split(text), start=1):
        line = line.split("#", 1)[0].rstrip()
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
            quoted), a binary or unreadable file, a file of zero bytes, or vertices
            without faces. A file of comments only is the empty mesh (no vertices, no faces).

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
            # int() alone would also take Python's "1_0" and digits of other scripts: one
            # look at the whole line, then a token-by-token one only if it has either.
            python_only = "_" in line or not line.isascii()
            for token in tokens[1:]:
                vertex_part = token.split("/", 1)[0]
                try:
                    if python_only and not OBJ_INDEX.fullmatch(vertex_part):
                        raise ValueError(vertex_part)
                    index = int(vertex_part)
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
        elif keyword not in SKIPPED_KEYWORDS:
            raise _fail(
                source, line_no, line,
                f"{keyword[:20]!r} is not an OBJ record (v and f are read; vt, vn, g, o, s, usemtl ... are skipped)",
            )

    vertices = parse_coordinates(coordinates, vertex_lines, text, source)
    if not faces:
        _refuse_faceless(text, len(vertices), source)
    faces_array = np.array(faces, dtype=np.int64).reshape(-1, 3)  # (m, 3)
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


def _refuse_faceless(text: str, n_vertices: int, source: str) -> None:
    """Raise for a file without faces, unless it is the empty mesh.

    A file of comments and blank lines only is the empty mesh (``hx.save`` writes the
    empty mesh as two comment lines). Vertices without faces are a point cloud, not a
    mesh, and a file of zero bytes is far more often a failed write than a mesh: both
    are refused by name.
    """
    if not text:
        raise MeshInputError(f"{source}: the file is empty (0 bytes): no vertices and no faces")
    if n_vertices:
        raise MeshInputError(
            f"{source}: {n_vertices} vertices but no faces found (no 'f' lines): a point cloud, not a mesh"
        )


def parse_coordinates(coordinates: list[list[str]], vertex_lines: list[int], text: str, source: str) -> np.ndarray:
    """Turn the x y z tokens into an (n, 3) float64 array, all at once.

    Every token must be an ``OBJ_NUMBER`` and finite. numpy parses the strings in one
    call (much faster than ``float()`` per token) after one search for a character no
    OBJ number has; only if either fails do we go back line by line to name the bad one.
    (numpy alone would take ``1_000``, ``nan`` and ``inf``.) Also used for ASCII STL.
    """
    if not coordinates:
        return np.zeros((0, 3))
    try:
        if _NOT_A_NUMBER_CHARACTER.search("".join(map("".join, coordinates))):
            raise ValueError("a character no number has")
        vertices = np.array(coordinates, dtype=np.str_).astype(np.float64)  # (n, 3)
    except ValueError:
        vertices = np.array([_parse_row(row, line_no, text, source) for row, line_no in zip(coordinates, vertex_lines)])
    not_finite = np.flatnonzero(~np.isfinite(vertices).all(axis=1))
    if len(not_finite):  # e.g. 1e999, which overflows to inf
        line_no = vertex_lines[not_finite[0]]
        raise _fail(source, line_no, _physical_line(text, line_no), "a coordinate is not finite (too large for float64)")
    return vertices


def _parse_row(row: list[str], line_no: int, text: str, source: str) -> list[float]:
    """The slow path: parse one record's tokens, naming the line if one is not an OBJ number."""
    values = []
    for token in row:
        if not OBJ_NUMBER.fullmatch(token):
            if token.lower().lstrip("+-") in ("nan", "inf", "infinity"):
                problem = f"{token!r} is not finite: no position"
            else:
                problem = f"{token[:40]!r} is not a number (sign, digits, decimal point, exponent: e.g. -1.5e3)"
            raise _fail(source, line_no, _physical_line(text, line_no), problem)
        values.append(float(token))
    return values


def _physical_line(text: str, line_no: int) -> str:
    """Line ``line_no`` (1-based) of ``text``, for an error message."""
    return _LINE_BREAK.split(text, maxsplit=line_no)[line_no - 1]


@contextmanager
def atomic_output(path: str | os.PathLike, mode: str = "w") -> Iterator[IO]:
    """Open a temporary file beside ``path``; on success move it onto ``path``.

    If the body raises (also ``KeyboardInterrupt``, or whatever a signal handler raises:
    the command line turns SIGTERM into an exception for this), the temporary file is
    removed and ``path`` is untouched, so a failed save never leaves a partial file.

    The temporary name is short (``.halfedge_edu-XXXXXXXX.tmp``), not the output's
    name plus a suffix, so that an output name near the file system's limit of 255
    bytes can still be written. An error in creating or moving it names ``path``, the
    file the caller asked for, not the temporary.

    The data is flushed to the disk (``fsync``) before the rename, and the folder after
    it, so that after a crash ``path`` is the old file or the whole new one. A process
    killed with SIGKILL cannot remove its temporary file; the command line removes such
    leftovers later (``remove_stale_temporaries``).
    """
    path = Path(path)
    temporary = path.with_name(f"{TEMPORARY_PREFIX}{secrets.token_hex(4)}{TEMPORARY_SUFFIX}")
    # One try from the moment the file may exist: a signal (Ctrl-C, SIGTERM) that lands
    # just after os.open made it must still remove it. ``ours`` is False only when
    # os.open itself failed, so a file we did not make is never removed.
    ours = True
    try:
        try:
            # os.open with 0o666 lets the umask set the permissions, as for a plain open().
            descriptor = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except OSError as error:
            ours = False
            raise OSError(error.errno, error.strerror, str(path)) from None
        with os.fdopen(descriptor, mode, **({} if "b" in mode else {"encoding": "utf-8", "newline": "\n"})) as file:
            yield file
            # On the disk before the rename: else a crash soon after can leave the new name
            # pointing at an empty or partial file (the rename reached the disk, the data not).
            file.flush()
            os.fsync(file.fileno())
        try:
            os.replace(temporary, path)
        except OSError as error:
            raise OSError(error.errno, error.strerror, str(path)) from None
        _sync_folder(path.parent)
    except BaseException:
        if ours:
            temporary.unlink(missing_ok=True)
        raise


#: The names of ``atomic_output``'s temporary files: prefix, 8 hex digits, suffix.
TEMPORARY_PREFIX = ".halfedge_edu-"
TEMPORARY_SUFFIX = ".tmp"
_TEMPORARY_NAME = re.compile(re.escape(TEMPORARY_PREFIX) + r"[0-9a-f]{8}" + re.escape(TEMPORARY_SUFFIX))

#: A temporary file untouched this long (seconds) belongs to no running write: a write
#: changes its file all the time, and takes seconds even for millions of faces.
STALE_AFTER_SECONDS = 600


def _sync_folder(folder: Path) -> None:
    """Flush the folder's entry list (the rename) to the disk, where the system allows it."""
    try:
        descriptor = os.open(folder, os.O_RDONLY)
    except OSError:
        return  # e.g. Windows cannot open a folder; its rename is as durable as it gets
    try:
        os.fsync(descriptor)
    except OSError:
        pass  # some file systems refuse fsync on a folder: nothing more can be done
    finally:
        os.close(descriptor)


def remove_stale_temporaries(folder: str | os.PathLike, *, older_than: float = STALE_AFTER_SECONDS) -> list[Path]:
    """Remove ``atomic_output``'s temporary files in ``folder`` untouched for ``older_than`` seconds.

    A write killed with SIGKILL (or a power cut) leaves its ``.halfedge_edu-XXXXXXXX.tmp``
    behind: nothing in the process runs to remove it. Only regular files with exactly
    that name pattern are removed (never a link, never another program's file), and
    only old ones, so a write still running in another process keeps its file.

    Returns:
        The files removed. A file that cannot be removed is left, silently: cleaning
        up is a courtesy, and must never stop the command that does it.
    """
    removed = []
    now = time.time()
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    for entry in entries:
        if not _TEMPORARY_NAME.fullmatch(entry.name):
            continue
        try:
            if entry.is_file(follow_symlinks=False) and now - entry.stat(follow_symlinks=False).st_mtime > older_than:
                os.unlink(entry.path)
                removed.append(Path(entry.path))
        except OSError:
            continue
    return removed


def checked_arrays(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(vertices, faces)`` as arrays, after the checks every writer makes before writing.

    Every format refuses the same things, so that no file holds what a reader would
    refuse or read back differently: wrong shapes, a non-finite coordinate (nan, inf),
    a face index outside the vertices.

    Raises:
        MeshInputError: naming the first offending vertex or face.
    """
    vertices = np.asarray(vertices)
    if np.iscomplexobj(vertices):
        raise MeshInputError(f"vertices must be real numbers, not {vertices.dtype}")
    vertices = vertices.astype(np.float64)
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
    return vertices, faces


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
    vertices, faces = checked_arrays(vertices, faces)

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
