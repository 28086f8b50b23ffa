"""Every file in tests/data/malformed/ must fail with the error its header announces.

Each file starts with three comment lines, for example::

    # expect: MeshInputError at line 8
    # message: vertex index 0 is not allowed
    # why: OBJ indices start at 1

(``with no line`` for problems that belong to no line: an empty or binary file.)
The files are read with ``hx.load``, so problems found while building the mesh
(degenerate faces, flipped faces, non-manifold edges) must name the line too.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io import load

CORPUS = Path(__file__).resolve().parents[1] / "data" / "malformed"
FILES = sorted(CORPUS.glob("*.obj"))


def expectation(path: Path) -> tuple[int | None, str]:
    """(line, message part) announced in the file's header; (None, ...) for no line."""
    header = path.read_bytes().split(b"\n", 3)[:2]
    if not header[0].startswith(b"# expect:"):  # the empty file cannot carry a header
        return None, "no faces"
    where = re.search(r"at line (\d+)|with no line", header[0].decode())
    message = header[1].decode().removeprefix("# message:").strip()
    return (int(where.group(1)) if where.group(1) else None), message


def test_the_corpus_has_a_file_for_each_kind_of_error():
    names = {path.stem for path in FILES}
    wanted = {
        "zero_index", "index_out_of_range", "negative_index_before_first_vertex", "unparsable_coordinate",
        "unparsable_face_index", "vertex_too_few_coordinates", "face_too_few_vertices", "nan_coordinate",
        "inf_coordinate", "binary_file", "empty", "no_faces", "degenerate_face", "flipped_face", "nonmanifold_edge",
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
    "path", [p for p in FILES if expectation(p)[0] is not None and "found when building" not in p.read_text(errors="replace")],
    ids=lambda p: p.stem,
)
def test_parse_errors_quote_the_offending_line(path):
    line, _ = expectation(path)
    text = path.read_text().splitlines()[line - 1].split("#")[0].strip()
    with pytest.raises(MeshInputError) as error:
        load(path)
    assert text in str(error.value)
