"""Reading STL files, binary and ASCII: the package's own small reader.

Why not trimesh's: trimesh reads a binary STL whose triangle count does not match its
length as if it were ASCII, and an ASCII STL without its closing ``endsolid`` (an
interrupted download) as nothing at all. Both come back as the empty mesh, with no
error: a damaged file would load as another mesh. An STL file says enough about
itself to be checked, so this reader checks it:

- **Binary**: an 80-byte header, the triangle count ``n`` (uint32, little-endian), then
  ``n`` records of 50 bytes (normal, three corners as float32, a 2-byte attribute). The
  file is exactly ``84 + 50 n`` bytes long; any other length is a wrong count or a
  truncated file, and is refused naming both numbers.
- **ASCII**: ``solid name``, then per triangle the same seven lines::

      facet normal nx ny nz
        outer loop
          vertex x y z          (three times)
        endloop
      endfacet

  and ``endsolid name``. (Several solids one after the other are read as one mesh.)
  A line out of this order, a file that ends inside a solid, or anything after the
  last ``endsolid`` is refused naming its line. Line ends may be ``\\n``, ``\\r\\n`` or
  ``\\r`` alone, as for OBJ; coordinates use OBJ's number syntax.

A file is binary when its length matches its count; else ASCII when it starts with
``solid`` and holds no NUL byte (binary headers often start with "solid" too); else a
binary file whose length does not match. The result is what trimesh gives for a sound
file: each triangle's three corners as three vertices, in order (``load`` then merges
corners at the same position into one vertex).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io.obj import _LINE_BREAK, parse_coordinates

__all__ = ["read_stl"]

#: One binary triangle record: 50 bytes, little-endian as the format says.
BINARY_RECORD = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])

#: The 80-byte header and the uint32 triangle count before the records.
BINARY_HEADER_BYTES = 84

#: The first word of each of the seven lines of one ASCII triangle, in order.
FACET_LINES = ("facet", "outer", "vertex", "vertex", "vertex", "endloop", "endfacet")


def read_stl(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """The corners and triangles of an STL file, binary or ASCII, after checking it.

    Returns:
        ``(vertices, faces)``: (3m, 3) float64 corners, three per triangle in file order,
        and (m, 3) int64 faces ``[[0, 1, 2], [3, 4, 5], ...]``.

    Raises:
        MeshInputError: naming the file, for a binary file whose length does not match
            its triangle count (declared and found), an ASCII file out of order or cut
            short (with the line), or a file too short to be either.
    """
    name = path.name
    try:
        data = path.read_bytes()
    except OSError as error:
        raise MeshInputError(f"{name}: cannot read the file ({error.strerror or error})") from error
    declared = int.from_bytes(data[80:84], "little") if len(data) >= BINARY_HEADER_BYTES else None
    if declared is not None and len(data) == BINARY_HEADER_BYTES + BINARY_RECORD.itemsize * declared:
        return _binary(data, declared)
    if data.lstrip()[:5].lower() == b"solid" and b"\x00" not in data:
        return _ascii(data.decode("utf-8", errors="replace"), name)
    if not data:
        raise MeshInputError(f"{name}: the file is empty (0 bytes): not an STL file")
    if declared is None:
        raise MeshInputError(
            f"{name}: {len(data)} bytes is too short for a binary STL (at least {BINARY_HEADER_BYTES}: "
            f"an 80-byte header and the triangle count), and it is not ASCII STL (which starts with 'solid')"
        )
    whole, left_over = divmod(len(data) - BINARY_HEADER_BYTES, BINARY_RECORD.itemsize)
    over = f" and {left_over} bytes more" if left_over else ""
    raise MeshInputError(
        f"{name}: the binary STL header declares {declared} triangles ({BINARY_HEADER_BYTES} + 50 x {declared} "
        f"bytes), but the file has {len(data)} bytes, room for {whole} triangles{over}: "
        f"a wrong count or a truncated file"
    )


def _binary(data: bytes, count: int) -> tuple[np.ndarray, np.ndarray]:
    """Corners and faces of a binary STL whose length matches ``count``."""
    records = np.frombuffer(data, dtype=BINARY_RECORD, count=count, offset=BINARY_HEADER_BYTES)
    vertices = records["corners"].reshape(-1, 3).astype(np.float64)  # (3m, 3)
    return vertices, np.arange(3 * count, dtype=np.int64).reshape(-1, 3)


def _ascii(text: str, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Corners and faces of an ASCII STL, checked line by line against the seven-line pattern."""
    records = [(line_no, line.split()) for line_no, line in enumerate(_LINE_BREAK.split(text), start=1)]
    records = [(line_no, words) for line_no, words in records if words]  # blank lines are nothing
    corners: list[list[str]] = []  # the x y z words of every vertex line
    corner_lines: list[int] = []
    position = 0
    while position < len(records):
        line_no, words = records[position]
        if words[0].lower() != "solid":
            raise _line_error(name, line_no, words, "expected 'solid' (after the last 'endsolid' only another "
                                                    "solid may follow)")
        solid_line, position = line_no, position + 1
        while True:
            if position == len(records):
                raise MeshInputError(
                    f"{name}: the file ends inside the solid that starts at line {solid_line}, after "
                    f"{len(corners) // 3} complete triangles, without 'endsolid': a truncated file",
                    line=records[-1][0],
                )
            line_no, words = records[position]
            if words[0].lower() == "endsolid":
                position += 1
                break
            position = _facet(records, position, name, corners, corner_lines)
    vertices = parse_coordinates(corners, corner_lines, text, name)  # (3m, 3)
    return vertices, np.arange(len(vertices), dtype=np.int64).reshape(-1, 3)


def _facet(records: list[tuple[int, list[str]]], start: int, name: str,
           corners: list[list[str]], corner_lines: list[int]) -> int:
    """Check the seven lines of one triangle from ``start``, keep its corners; return the next position."""
    complete = len(corners) // 3  # triangles before this one
    for offset, keyword in enumerate(FACET_LINES):
        # The file ends here, or its last line is cut short (an interrupted download).
        if start + offset == len(records) or (start + offset == len(records) - 1 and
                                             records[-1][1][0].lower() != keyword):
            raise MeshInputError(
                f"{name}: the file ends inside the triangle that starts at line {records[start][0]} "
                f"(after {complete} complete triangles): a truncated file",
                line=records[-1][0],
            )
        line_no, words = records[start + offset]
        if words[0].lower() != keyword:
            expected = "'facet normal' or 'endsolid'" if offset == 0 else repr(keyword)
            raise _line_error(name, line_no, words, f"expected {expected} (an ASCII STL triangle is seven lines: "
                                                    f"{', '.join(FACET_LINES)})")
        if keyword == "vertex":
            if len(words) != 4:
                raise _line_error(name, line_no, words, "a vertex line needs 3 coordinates x y z")
            corners.append(words[1:])
            corner_lines.append(line_no)
    return start + len(FACET_LINES)


def _line_error(name: str, line_no: int, words: list[str], problem: str) -> MeshInputError:
    """The error for one bad line of an ASCII STL: the file, the line number, the line (cut short)."""
    quoted = " ".join(words)
    quoted = quoted if len(quoted) <= 80 else quoted[:77] + "..."
    return MeshInputError(f"{name}, line {line_no}: {problem}: {quoted!r}", line=line_no)
