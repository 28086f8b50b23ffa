"""What a PLY or OFF file's header declares, checked against what the file holds.

trimesh reads PLY and OFF by their header's counts: it takes the first ``n_vertices``
records as vertices and the next ``n_faces`` as faces, whatever the file holds. So a
header that lies gives another mesh with no error. One vertex too many turns the first
face record into a vertex and drops a face; one face too few drops the last face (a
hole); records after the declared ones are never read. These checks run before trimesh
reads the file and refuse such a file, naming the declared and the found counts; a
file that passes reads exactly as it says. (trimesh still does the reading: these
formats are not taught, and trimesh reads their many property types.)

What "holds" means, per encoding, the way trimesh reads it:

- ASCII PLY and OFF: one record per line (blank lines and, in OFF, ``#`` comments are
  not records; trimesh reads them the same way). Each record must have the number of
  values its element declares: a PLY vertex as many as its properties, a face one
  more than its list's first number; an OFF vertex 3 (``x y z``, 6 or 7 in COFF with a
  colour), a face ``n`` followed by ``n`` indices (and up to 4 colour values). Values are
  numbers in OBJ's syntax (no ``nan``, ``inf`` or ``1_000``).
- Binary PLY: the records' sizes (from the property types, and each list's count)
  must add up to exactly the bytes after the header.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io.obj import OBJ_NUMBER

__all__ = ["check_off", "check_ply"]

#: Bytes of each PLY property type (the names of the PLY specification and their aliases).
PLY_TYPE_BYTES = {
    "char": 1, "uchar": 1, "int8": 1, "uint8": 1, "short": 2, "ushort": 2, "int16": 2, "uint16": 2,
    "int": 4, "uint": 4, "int32": 4, "uint32": 4, "float": 4, "float32": 4, "float16": 2,
    "double": 8, "float64": 8, "int64": 8, "uint64": 8,
}

#: numpy type of each PLY list-count type (how many entries a list has).
PLY_COUNT_TYPES = {
    "char": "i1", "uchar": "u1", "int8": "i1", "uint8": "u1", "short": "i2", "ushort": "u2", "int16": "i2",
    "uint16": "u2", "int": "i4", "uint": "u4", "int32": "i4", "uint32": "u4", "int64": "i8", "uint64": "u8",
}

#: A word (white space around it) that is not one whole number in OBJ's syntax: one
#: search over a whole file, linear in its length.
_NOT_A_NUMBER = re.compile(rf"(?<!\S)(?!(?:{OBJ_NUMBER.pattern})(?!\S))\S+")


@dataclass
class _Property:
    """One ``property`` line: a scalar, or a list with the type of its count."""

    name: str
    size: int  # bytes of the scalar, or of each list entry
    count_type: str | None = None  # numpy type of a list's count; None for a scalar


@dataclass
class _Element:
    """One ``element`` line and its properties."""

    name: str
    count: int
    line: int
    properties: list[_Property] = field(default_factory=list)


def _plural(count: int, word: str) -> str:
    return f"{count} {word}" if count == 1 else f"{count} {'vertices' if word == 'vertex' else word + 's'}"


def _declared(elements: list[_Element]) -> str:
    """``"5 vertices and 4 faces"``: the header's counts, for a message."""
    parts = [_plural(element.count, element.name) for element in elements]
    return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]


def _first_not_a_number(lines: list[str]) -> tuple[int, str] | None:
    """``(index, word)`` of the first line with a word that is not a number, or None.

    One search over the whole text, not a Python loop over every word.
    """
    text = "\n".join(lines)
    found = _NOT_A_NUMBER.search(text)
    if found is None:
        return None
    return text.count("\n", 0, found.start()), found.group()


def _whole_number(word: str) -> int:
    """``word`` as a count (digits only), or -1 for anything else (``3.5``, ``1e400``, ``-2``)."""
    return int(word) if word.isascii() and word.isdigit() else -1


def _quoted(line: str) -> str:
    """A record for a message, cut short so a message stays one readable line."""
    line = line.strip()
    return repr(line if len(line) <= 80 else line[:77] + "...")


# ---- PLY ------------------------------------------------------------------------------

def check_ply(data: bytes, name: str) -> None:
    """Refuse a PLY file whose header's counts do not match its data.

    Args:
        data: the whole file.
        name: the file name, for messages.

    Raises:
        MeshInputError: naming the file, the declared counts and what was found instead
            (a record with the wrong number of values, with its line; fewer records than
            declared; records or bytes after the declared ones).
    """
    end = re.search(rb"end_header[ \t]*(\r\n|\r|\n)", data)
    if not data.startswith(b"ply") or end is None:
        return  # not a PLY header we can check: trimesh says what is wrong with it
    header = data[: end.start()].decode("ascii", errors="replace").splitlines()
    encoding, elements = _ply_header(header, name)
    if encoding is None:
        return
    body = data[end.end():]
    if encoding == "ascii":
        _check_ply_ascii(body, elements, name, first_line=len(header) + 2)
    else:
        _check_ply_binary(body, elements, name, ">" if encoding == "binary_big_endian" else "<")


def _ply_header(header: list[str], name: str) -> tuple[str | None, list[_Element]]:
    """The header's format word and elements (None for a header these checks do not know)."""
    encoding = None
    elements: list[_Element] = []
    for line_no, line in enumerate(header, start=1):
        words = line.split()
        if not words:
            continue
        if words[0] == "format" and len(words) >= 2:
            encoding = words[1]
        elif words[0] == "element" and len(words) == 3:
            try:
                count = int(words[2])
            except ValueError:
                return None, []
            if count < 0:
                raise MeshInputError(f"{name}, line {line_no}: a negative count of {words[1]}: {_quoted(line)}",
                                     line=line_no)
            elements.append(_Element(words[1], count, line_no))
        elif words[0] == "property" and elements:
            if len(words) == 5 and words[1] == "list" and words[2] in PLY_COUNT_TYPES and words[3] in PLY_TYPE_BYTES:
                elements[-1].properties.append(_Property(words[4], PLY_TYPE_BYTES[words[3]], PLY_COUNT_TYPES[words[2]]))
            elif len(words) == 3 and words[1] in PLY_TYPE_BYTES:
                elements[-1].properties.append(_Property(words[2], PLY_TYPE_BYTES[words[1]]))
            else:
                return None, []  # a type trimesh may know and we do not: leave it to trimesh
    if encoding not in ("ascii", "binary_little_endian", "binary_big_endian"):
        return None, []
    return encoding, elements


def _check_ply_ascii(body: bytes, elements: list[_Element], name: str, first_line: int) -> None:
    """One line per record, each with as many values as its element declares."""
    text = body.decode("utf-8", errors="replace")
    lines = text.splitlines()  # as trimesh splits them
    while lines and not lines[-1].strip():
        lines.pop()  # blank lines at the end are not records
    declared_total = sum(element.count for element in elements)
    odd = _first_not_a_number(lines)
    if odd is not None:
        index, word = odd
        raise MeshInputError(
            f"{name}, line {first_line + index}: {word[:40]!r} is not a number (PLY values are numbers: sign, "
            f"digits, decimal point, exponent): {_quoted(lines[index])}",
            line=first_line + index,
        )
    start = 0
    for element in elements:
        records = lines[start: start + element.count]
        for offset, line in enumerate(records):
            words = line.split()
            wanted = _ply_values_wanted(element, words)
            if len(words) != wanted:
                line_no = first_line + start + offset
                should = f"should have {wanted}" if wanted >= 0 else "should be a count of 3 or more, then as many"
                raise MeshInputError(
                    f"{name}, line {line_no}: {element.name} {offset} {should} values, this line has "
                    f"{len(words)}: {_quoted(line)}; the header declares {_declared(elements)}, so a count "
                    f"in the header is wrong or the file is damaged",
                    line=line_no, element=(element.name, offset),
                )
        if len(records) < element.count:
            raise MeshInputError(
                f"{name}: the header declares {_declared(elements)} ({declared_total} records), but the file "
                f"holds {len(lines)}: it ends after {len(records)} of the {element.count} {element.name} records "
                f"(a truncated file or a wrong count)"
            )
        start += element.count
    if len(lines) > declared_total:
        raise MeshInputError(
            f"{name}, line {first_line + declared_total}: the header declares {_declared(elements)} "
            f"({declared_total} records), but the file holds {len(lines)}: "
            f"{_plural(len(lines) - declared_total, 'record')} after the declared ones (a count in the header is too low)",
            line=first_line + declared_total,
        )


def _ply_values_wanted(element: _Element, words: list[str]) -> int:
    """How many values a record of ``element`` with these words should have (-1: cannot tell)."""
    wanted = 0
    for prop in element.properties:
        if prop.count_type is None:
            wanted += 1
            continue
        if wanted >= len(words):
            return -1
        entries = _whole_number(words[wanted])
        if entries < _least_entries(element, prop):
            return -1
        wanted += 1 + entries
    return wanted


def _check_ply_binary(body: bytes, elements: list[_Element], name: str, byte_order: str) -> None:
    """The records' sizes must add up to exactly the bytes after the header, and every face
    list must name at least 3 vertices (a misread count can otherwise fall back into step)."""
    offset = 0
    for element in elements:
        found, offset, short_face = _walk_binary(body, offset, element, byte_order)
        if short_face:
            raise MeshInputError(
                f"{name}: face {found} has a list of fewer than 3 vertices, so the header's counts "
                f"({_declared(elements)}) do not match the data: a count is wrong or the file is damaged",
                element=("face", found),
            )
        if found < element.count:
            raise MeshInputError(
                f"{name}: the header declares {_declared(elements)}, but the {len(body)} bytes of data end "
                f"inside {element.name} {found} (a truncated file, or a count in the header is too high)"
            )
    if offset != len(body):
        raise MeshInputError(
            f"{name}: the header declares {_declared(elements)}, which take {offset} bytes, but the file has "
            f"{len(body)} bytes of data: {len(body) - offset} bytes after the declared records (a count in the "
            f"header is too low, or the file is damaged)"
        )


def _walk_binary(body: bytes, offset: int, element: _Element, byte_order: str) -> tuple[int, int, bool]:
    """``(records found, offset after them, stopped at a face of fewer than 3 vertices)``.

    Without lists every record has one size. With lists the first record's list counts
    give a size; if every record's counts agree (all triangles, say), that is one numpy
    check; otherwise the records are walked one by one.
    """
    if element.count == 0:
        return 0, offset, False
    size = _record_size(body, offset, element, byte_order)
    if size is None or size < 0:
        return 0, offset, size is not None
    end = offset + size * element.count
    if not any(prop.count_type for prop in element.properties):
        if end <= len(body):
            return element.count, end, False
        return (len(body) - offset) // size, len(body), False
    if end <= len(body) and _same_list_counts(body, offset, element, size, byte_order):
        return element.count, end, False
    for index in range(element.count):  # lists of different lengths: one record at a time
        size = _record_size(body, offset, element, byte_order)
        if size is None or offset + size > len(body):
            return index, len(body), False
        if size < 0:
            return index, offset, True
        offset += size
    return element.count, offset, False


def _record_size(body: bytes, offset: int, element: _Element, byte_order: str) -> int | None:
    """Bytes of the record at ``offset``: None if it runs past the data, -1 for a face of fewer than 3 vertices."""
    size = 0
    for prop in element.properties:
        if prop.count_type is None:
            size += prop.size
            continue
        count_type = np.dtype(byte_order + prop.count_type)
        if offset + size + count_type.itemsize > len(body):
            return None
        entries = int(np.frombuffer(body, dtype=count_type, count=1, offset=offset + size)[0])
        if entries < _least_entries(element, prop):
            return -1
        size += count_type.itemsize + entries * prop.size
    return size


def _least_entries(element: _Element, prop: _Property) -> int:
    """3 for a face's vertex list (a polygon has at least 3 corners), else 0."""
    return 3 if element.name == "face" and prop.name in ("vertex_indices", "vertex_index") else 0


def _same_list_counts(body: bytes, offset: int, element: _Element, size: int, byte_order: str) -> bool:
    """Do all ``element.count`` records from ``offset`` have the first record's list counts?"""
    records = np.frombuffer(body, dtype=np.uint8, count=size * element.count, offset=offset).reshape(-1, size)
    position = 0
    for prop in element.properties:
        if prop.count_type is None:
            position += prop.size
            continue
        count_type = np.dtype(byte_order + prop.count_type)
        counts = records[:, position: position + count_type.itemsize].copy().view(count_type).ravel()
        if (counts != counts[0]).any():
            return False
        position += count_type.itemsize + int(counts[0]) * prop.size
    return True


# ---- OFF ------------------------------------------------------------------------------

def check_off(data: bytes, name: str) -> None:
    """Refuse an OFF file whose counts line does not match its records.

    Args:
        data: the whole file.
        name: the file name, for messages.

    Raises:
        MeshInputError: naming the file, the declared counts and what was found (a
            record with the wrong number of values, with its line; fewer or more
            records than declared).
    """
    text = data.decode("utf-8", errors="replace")
    records = []  # (line number, words) of every line that holds something, as trimesh reads them
    for line_no, line in enumerate(text.splitlines(), start=1):
        words = line.split("#", 1)[0].split()
        if words:
            records.append((line_no, words))
    if not records or not re.fullmatch(r"C?OFF", records[0][1][0]):
        return  # not an OFF header we can check: trimesh says what is wrong with it
    coloured = records[0][1][0] == "COFF"
    counts = records[0][1][1:] or (records[1][1] if len(records) > 1 else [])
    body = records[1:] if records[0][1][1:] else records[2:]
    try:
        n_vertices, n_faces = int(counts[0]), int(counts[1])
    except (IndexError, ValueError):
        return  # trimesh refuses a malformed counts line by itself
    if n_vertices < 0 or n_faces < 0:
        raise MeshInputError(f"{name}: the counts line declares {n_vertices} vertices and {n_faces} faces: "
                             f"a count cannot be negative")
    odd = _first_not_a_number([" ".join(words) for _, words in body])
    if odd is not None:
        index, word = odd
        line_no, words = body[index]
        raise MeshInputError(f"{name}, line {line_no}: {word[:40]!r} is not a number: {_quoted(' '.join(words))}",
                             line=line_no)
    declared = f"{_plural(n_vertices, 'vertex')} and {_plural(n_faces, 'face')}"
    vertex_sizes = (3, 6, 7) if coloured else (3,)
    for index, (line_no, words) in enumerate(body[:n_vertices]):
        if len(words) not in vertex_sizes:
            raise MeshInputError(
                f"{name}, line {line_no}: vertex {index} should have {' or '.join(map(str, vertex_sizes))} values "
                f"(x y z{' and a colour' if coloured else ''}), this line has {len(words)}: "
                f"{_quoted(' '.join(words))}; the counts line declares {declared}, so a count is wrong "
                f"or the file is damaged",
                line=line_no, element=("vertex", index),
            )
    for index, (line_no, words) in enumerate(body[n_vertices: n_vertices + n_faces]):
        corners = _whole_number(words[0])
        if not (corners >= 3 and corners + 1 <= len(words) <= corners + 5):
            raise MeshInputError(
                f"{name}, line {line_no}: face {index} should be a count n of at least 3 and n vertex indices "
                f"(and up to 4 colour values), this line is not: {_quoted(' '.join(words))}; the counts line "
                f"declares {declared}, so a count is wrong or the file is damaged",
                line=line_no, element=("face", index),
            )
    if len(body) != n_vertices + n_faces:
        found = len(body)
        if found < n_vertices + n_faces:
            what = f"only {found}: the file ends early (a truncated file, or a count is too high)"
        else:
            what = (f"{found}: {_plural(found - n_vertices - n_faces, 'record')} after the declared ones, from line "
                    f"{body[n_vertices + n_faces][0]} (a count is too low)")
        raise MeshInputError(
            f"{name}: the counts line declares {declared} ({n_vertices + n_faces} records), but the file holds {what}"
        )
