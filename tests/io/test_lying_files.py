"""A file that does not say truthfully what it holds is refused, never loaded as another mesh.

STL, PLY and OFF files declare their own counts (a binary STL its triangles, PLY and
OFF headers their vertices and faces). Each case here damages one sound file the way
real files are damaged: a wrong count, an interrupted download, records after the
declared ones. Each must raise ``MeshInputError`` naming the file and both counts.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.core.errors import MeshInputError


@pytest.fixture(scope="module")
def sphere() -> hx.HalfedgeMesh:
    """162 vertices, 320 faces."""
    return hx.sample("icosphere")


def _export(mesh: hx.HalfedgeMesh, file_type: str, **options) -> bytes:
    exported = mesh.to_trimesh().export(file_type=file_type, **options)
    return exported if isinstance(exported, bytes) else exported.encode()


def _refused(tmp_path: Path, name: str, data: bytes, *parts: str) -> MeshInputError:
    """Write ``data`` as ``name``, load it, and check the error names the file and ``parts``."""
    path = tmp_path / name
    path.write_bytes(data)
    with pytest.raises(MeshInputError) as caught:
        hx.load(path)
    message = str(caught.value)
    assert message.startswith(name), message
    for part in parts:
        assert part in message, message
    return caught.value


def _changed(data: bytes, old: bytes, new: bytes) -> bytes:
    assert data.count(old) >= 1
    return data.replace(old, new, 1)


# ---- binary STL ------------------------------------------------------------------------

def _with_count(stl: bytes, count: int) -> bytes:
    return stl[:80] + count.to_bytes(4, "little") + stl[84:]


@pytest.mark.parametrize("count", [321, 1000, 4_000_000_000])
def test_a_binary_stl_whose_count_is_too_high_is_refused(tmp_path, sphere, count):
    data = _with_count(_export(sphere, "stl"), count)
    _refused(tmp_path, "high.stl", data, f"declares {count} triangles", "room for 320 triangles")


@pytest.mark.parametrize("count", [0, 1, 319])
def test_a_binary_stl_whose_count_is_too_low_is_refused(tmp_path, sphere, count):
    data = _with_count(_export(sphere, "stl"), count)
    _refused(tmp_path, "low.stl", data, f"declares {count} triangles", "room for 320 triangles")


def test_a_truncated_binary_stl_is_refused(tmp_path, sphere):
    data = _export(sphere, "stl")[:-20]
    _refused(tmp_path, "cut.stl", data, "declares 320 triangles", "room for 319 triangles and 30 bytes more")


def test_an_stl_shorter_than_its_header_is_refused(tmp_path, sphere):
    _refused(tmp_path, "stub.stl", _export(sphere, "stl")[:50], "50 bytes is too short")


def test_a_sound_binary_stl_still_loads_with_shared_corners_merged(tmp_path, sphere):
    path = tmp_path / "sound.stl"
    path.write_bytes(_export(sphere, "stl"))
    assert (hx.load(path).n_vertices, hx.load(path).n_faces) == (162, 320)


# ---- ASCII STL -------------------------------------------------------------------------

@pytest.mark.parametrize("fraction", [0.25, 0.5, 0.999])
def test_a_truncated_ascii_stl_is_refused(tmp_path, sphere, fraction):
    data = _export(sphere, "stl_ascii")
    _refused(tmp_path, "cut.stl", data[: int(len(data) * fraction)], "truncated")


def test_an_ascii_stl_without_endsolid_is_refused_after_its_complete_triangles(tmp_path, sphere):
    data = _export(sphere, "stl_ascii")
    data = data[: data.rindex(b"endsolid")]
    _refused(tmp_path, "open.stl", data, "after 320 complete triangles", "without 'endsolid'")


def test_records_after_endsolid_are_refused_naming_their_line(tmp_path, sphere):
    data = _export(sphere, "stl_ascii") + b"facet normal 0 0 1\n"
    error = _refused(tmp_path, "more.stl", data, "expected 'solid'", "'facet normal 0 0 1'")
    assert error.line == len(data.splitlines())


def test_a_line_out_of_order_in_an_ascii_stl_names_its_line(tmp_path):
    data = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n"
    error = _refused(tmp_path, "order.stl", data, "line 6", "expected 'vertex'")
    assert error.line == 6


def test_an_ascii_stl_coordinate_uses_obj_number_syntax(tmp_path):
    data = (b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1_0 0 0\nvertex 0 1 0\n"
            b"endloop\nendfacet\nendsolid t\n")
    _refused(tmp_path, "syntax.stl", data, "line 5", "'1_0' is not a number")


@pytest.mark.parametrize("line_end", [b"\r", b"\r\n", b"\n"])
def test_an_ascii_stl_reads_the_same_with_any_line_ending(tmp_path, sphere, line_end):
    path = tmp_path / "ends.stl"
    path.write_bytes(_export(sphere, "stl_ascii").replace(b"\n", line_end))
    mesh = hx.load(path)
    assert (mesh.n_vertices, mesh.n_faces) == (162, 320)


def test_several_solids_in_one_ascii_stl_are_one_mesh(tmp_path, sphere):
    text = _export(sphere, "stl_ascii")
    middle = text.index(b"\nfacet", len(text) // 2) + 1
    path = tmp_path / "two.stl"
    path.write_bytes(text[:middle] + b"endsolid a\nsolid b\n" + text[middle:])
    assert hx.load(path).n_faces == 320


# ---- PLY -------------------------------------------------------------------------------

@pytest.mark.parametrize("encoding", ["ascii", "binary"])
@pytest.mark.parametrize("old, new, parts", [
    (b"element vertex 162", b"element vertex 163", ["163 vertices and 320 faces"]),
    (b"element vertex 162", b"element vertex 161", ["161 vertices and 320 faces"]),
    (b"element face 320", b"element face 319", ["162 vertices and 319 faces", "after the declared"]),
    (b"element face 320", b"element face 321", ["162 vertices and 321 faces"]),
], ids=["one-vertex-too-many", "one-vertex-too-few", "one-face-too-few", "one-face-too-many"])
def test_a_ply_header_with_a_lying_count_is_refused(tmp_path, sphere, encoding, old, new, parts):
    data = _changed(_export(sphere, "ply", encoding=encoding), old, new)
    _refused(tmp_path, f"{encoding}.ply", data, *parts)


@pytest.mark.parametrize("encoding", ["ascii", "binary"])
def test_a_truncated_ply_is_refused(tmp_path, sphere, encoding):
    data = _export(sphere, "ply", encoding=encoding)
    _refused(tmp_path, "cut.ply", data[:-7], "162 vertices and 320 faces")


@pytest.mark.parametrize("encoding", ["ascii", "binary"])
def test_records_after_the_declared_ones_in_a_ply_are_refused(tmp_path, sphere, encoding):
    data = _export(sphere, "ply", encoding=encoding)
    extra = b"3 0 1 2\n" if encoding == "ascii" else b"\x03" + np.array([0, 1, 2], "<i4").tobytes()
    _refused(tmp_path, "more.ply", data + extra, "162 vertices and 320 faces", "after the declared")


def test_an_ascii_ply_vertex_line_that_is_a_face_names_its_line(tmp_path, sphere):
    data = _changed(_export(sphere, "ply", encoding="ascii"), b"element vertex 162", b"element vertex 163")
    error = _refused(tmp_path, "shifted.ply", data, "vertex 162 should have 3 values, this line has 4")
    assert error.line == 10 + 162 + 1


@pytest.mark.parametrize("encoding", ["ascii", "binary"])
def test_a_sound_ply_still_loads(tmp_path, sphere, encoding):
    path = tmp_path / "sound.ply"
    path.write_bytes(_export(sphere, "ply", encoding=encoding))
    mesh = hx.load(path)
    np.testing.assert_array_equal(mesh.to_arrays()[1], sphere.to_arrays()[1])


def test_a_binary_ply_of_mixed_polygons_is_walked_record_by_record(tmp_path):
    from halfedge_edu.io.headers import check_ply  # trimesh reads no mixed binary PLY: check the check

    header = (b"ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
              b"property float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n")
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]], "<f4").tobytes()
    faces = (b"\x04" + np.array([0, 1, 2, 3], "<i4").tobytes() + b"\x03" + np.array([1, 4, 2], "<i4").tobytes())
    check_ply(header.replace(b"face 3", b"face 2") + vertices + faces, "mixed.ply")  # sound: no error
    path = tmp_path / "mixed.ply"
    path.write_bytes(header + vertices + faces)
    with pytest.raises(MeshInputError, match="end inside face 2"):
        hx.load(path)


def test_an_ascii_ply_value_uses_obj_number_syntax(tmp_path, sphere):
    data = _export(sphere, "ply", encoding="ascii")
    first = data.index(b"end_header\n") + len(b"end_header\n")
    line = data[first: data.index(b"\n", first)]
    data = data.replace(line, b"nan" + line[line.index(b" "):], 1)
    error = _refused(tmp_path, "nan.ply", data, "line 11", "'nan' is not a number")
    assert error.line == 11


# ---- OFF -------------------------------------------------------------------------------

TETRAHEDRON_OFF = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"


def test_the_issues_off_with_one_vertex_too_many_is_refused(tmp_path):
    error = _refused(tmp_path, "issue.off", ("OFF\n5 4 0\n" + TETRAHEDRON_OFF).encode(),
                     "line 7", "vertex 4 should have 3 values", "5 vertices and 4 faces")
    assert error.line == 7


@pytest.mark.parametrize("counts, parts", [
    ("4 3 0", ["4 vertices and 3 faces (7 records)", "holds 8", "from line 10"]),
    ("4 5 0", ["4 vertices and 5 faces (9 records)", "holds only 8"]),
    ("5 3 0", ["line 7", "vertex 4 should have 3 values"]),
])
def test_an_off_with_lying_counts_is_refused(tmp_path, counts, parts):
    _refused(tmp_path, "lying.off", (f"OFF\n{counts}\n" + TETRAHEDRON_OFF).encode(), *parts)


def test_records_after_the_declared_ones_in_an_off_are_refused(tmp_path):
    data = ("OFF\n4 4 0\n" + TETRAHEDRON_OFF + "3 0 1 2\n").encode()
    _refused(tmp_path, "more.off", data, "holds 9", "1 record after the declared ones, from line 11")


def test_a_truncated_off_is_refused(tmp_path):
    data = ("OFF\n4 4 0\n" + TETRAHEDRON_OFF)[:-8].encode()
    _refused(tmp_path, "cut.off", data, "holds only 7")


def test_an_off_with_comments_and_blank_lines_still_loads(tmp_path):
    path = tmp_path / "commented.off"
    path.write_text("OFF\n# a tetrahedron\n4 4 0\n\n" + TETRAHEDRON_OFF.replace("3 1 2 3", "3 1 2 3  # last"))
    assert hx.load(path).n_faces == 4


# ---- every format the package writes still loads back as the same mesh --------------------

@pytest.mark.parametrize("suffix", [".obj", ".ply", ".off", ".stl", ".glb", ".gltf"])
def test_every_written_format_loads_back_as_the_same_mesh(tmp_path, sphere, suffix):
    path = tmp_path / f"sphere{suffix}"
    hx.save(sphere, path)
    back = hx.load(path)
    vertices, faces = sphere.to_arrays()
    got_vertices, got_faces = back.to_arrays()
    if suffix == ".stl":  # corners are merged back in order of first use: compare the triangles
        assert np.allclose(np.sort(got_vertices[got_faces].reshape(-1, 9), axis=0),
                           np.sort(vertices[faces].reshape(-1, 9), axis=0), atol=1e-6)
        return
    np.testing.assert_array_equal(got_faces, faces)
    np.testing.assert_allclose(got_vertices, vertices, atol=1e-6)


def test_the_empty_mesh_round_trips_through_stl(tmp_path):
    empty = hx.HalfedgeMesh.from_faces(np.zeros((0, 3)), np.zeros((0, 3), dtype=int))
    hx.save(empty, tmp_path / "empty.stl")
    assert hx.load(tmp_path / "empty.stl").n_faces == 0
