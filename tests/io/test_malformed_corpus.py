"""Every file in tests/data/malformed/ must fail with the error its header announces.

Each file starts with three comment lines, for example::

    # expect: MeshInputError at line 8
    # message: vertex index 0 is not allowed
    # why: OBJ indices start at 1

(``with no line`` for problems that belong to no line: an empty or binary file.)
The files are read with ``hx.load``, so problems found while building the mesh
(degenerate faces, flipped faces, non-manifold edges) must name the line too.

Some files are in the encodings and line endings the reader decides about (a UTF-8
byte-order mark, CR or mixed line ends, Latin-1, UTF-16, UTF-32): their headers are
written in the same encoding, and read back here with the encoding the file is in.
"""

from __future__ import annotations

import codecs
import re
from pathlib import Path

import pytest

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io import load

CORPUS = Path(__file__).resolve().parents[1] / "data" / "malformed"
FILES = sorted(CORPUS.glob("*.obj"))


def file_lines(path: Path) -> list[str]:
    """The file's lines as an editor shows them, whatever its encoding and line ends."""
    data = path.read_bytes()
    if data.startswith((codecs.BOM_UTF32_LE, codecs.BOM_UTF32_BE)):
        text = data.decode("utf-32")
    elif data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        text = data.decode("utf-16")
    elif data[1:2] == b"\x00" and data[:1] == b"#":  # UTF-16 little-endian without a mark
        text = data.decode("utf-16-le")
    else:
        text = data.decode("utf-8", errors="replace")
    return re.split(r"\r\n|\r|\n", text.removeprefix("\ufeff"))


def expectation(path: Path) -> tuple[int | None, str]:
    """(line, message part) announced in the file's header; (None, ...) for no line."""
    header = file_lines(path)[:2]
    if not header[0].startswith("# expect:"):  # the empty file cannot carry a header
        return None, "no faces"
    where = re.search(r"at line (\d+)|with no line", header[0])
    message = header[1].removeprefix("# message:").strip()
    return (int(where.group(1)) if where.group(1) else None), message


def test_the_corpus_has_a_file_for_each_kind_of_error():
    names = {path.stem for path in FILES}
    wanted = {
        "zero_index", "index_out_of_range", "negative_index_before_first_vertex", "unparsable_coordinate",
        "unparsable_face_index", "vertex_too_few_coordinates", "face_too_few_vertices", "nan_coordinate",
        "inf_coordinate", "binary_file", "empty", "no_faces", "degenerate_face", "flipped_face", "nonmanifold_edge",
        "utf8_bom_index_out_of_range", "cr_only_zero_index", "mixed_line_ends_bad_coordinate", "crlf_zero_index",
        "latin1_in_a_face", "utf16_le_bom", "utf16_be_bom", "utf16_le_no_bom", "utf32_bom", "unknown_record",
        "bare_numbers",
    }
    assert wanted <= names


@pytest.mark.parametrize("path", FILES, ids=[path.stem for path in FILES])
def test_malformed_file_raises_with_the_announced_line(path):
    line, message = expectation(path)
    with pytest.raises(MeshInputError) as error:
        load(path)
    assert error.value.line == line
    assert message in str(error.value)
    if line is not None:
        assert f"line {line}" in str(error.value)


@pytest.mark.parametrize(
    "path", [p for p in FILES if expectation(p)[0] is not None and "found when building" not in "".join(file_lines(p))],
    ids=lambda p: p.stem,
)
def test_parse_errors_quote_the_offending_line(path):
    line, _ = expectation(path)
    text = file_lines(path)[line - 1].split("#")[0].strip()
    with pytest.raises(MeshInputError) as error:
        load(path)
    assert text in str(error.value)
