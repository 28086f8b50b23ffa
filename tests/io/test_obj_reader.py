"""read_obj: what an OBJ file may contain, and what it gives back."""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np
import pytest

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io import ObjData, read_obj

MESHES = Path(__file__).resolve().parents[2] / "halfedge_edu" / "data"
SQUARE = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"


def read_text(text: str, **options) -> ObjData:
    return read_obj(io.StringIO(text), **options)


def test_vertices_and_faces_are_read_zero_based():
    data = read_text(SQUARE + "f 1 2 3\nf 1 3 4\n")
    assert data.vertices.dtype == np.float64 and data.vertices.shape == (4, 3)
    assert data.faces.dtype == np.int64
    assert data.faces.tolist() == [[0, 1, 2], [0, 2, 3]]
    np.testing.assert_array_equal(data.vertices[2], [1, 1, 0])


def test_face_lines_are_the_lines_of_the_f_records():
    data = read_text("# header\n" + SQUARE + "\nf 1 2 3\n# between\nf 1 3 4\n")
    assert data.face_lines.tolist() == [7, 9]


def test_w_coordinate_and_vertex_colours_are_ignored():
    data = read_text("v 1 2 3 0.5\nv 4 5 6 0.1 0.2 0.3\nv 7 8 9\nf 1 2 3\n")
    np.testing.assert_array_equal(data.vertices, [[1, 2, 3], [4, 5, 6], [7, 8, 9]])


@pytest.mark.parametrize("face", ["f 1 2 3", "f 1/1 2/2 3/3", "f 1//4 2//5 3//6", "f 1/1/4 2/2/5 3/3/6"])
def test_face_token_forms_give_the_vertex_index(face):
    data = read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n" + face + "\n")
    assert data.faces.tolist() == [[0, 1, 2]]


def test_negative_indices_count_back_from_the_vertices_defined_so_far():
    text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nf -3 -1 -2\n"
    data = read_text(text)
    # the second face's -1 is vertex 4 (index 3): it is counted at that line, not at the end
    assert data.faces.tolist() == [[0, 1, 2], [1, 3, 2]]


def test_positive_index_may_refer_to_a_vertex_defined_later():
    data = read_text("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n")
    assert data.faces.tolist() == [[0, 1, 2]]


def test_polygons_are_fan_triangulated_on_their_line():
    data = read_text(SQUARE + "v 0.5 1.5 0\nf 1 2 3 5 4\nf 1 2 3\n")
    assert data.faces.tolist() == [[0, 1, 2], [0, 2, 4], [0, 4, 3], [0, 1, 2]]
    assert data.face_lines.tolist() == [6, 6, 6, 7]
    assert data.n_polygons_triangulated == 1


def test_triangulate_false_rejects_a_polygon_naming_its_line():
    with pytest.raises(MeshInputError, match=r"line 6: a polygon with 4 vertices") as error:
        read_text(SQUARE + "f 1 2 3\nf 1 2 3 4\n", triangulate=False)
    assert error.value.line == 6


def test_comments_blank_lines_and_unused_records_are_skipped():
    text = (
        "# a comment\nmtllib cow.mtl\no cow\ng body\n\n   \ns off\nusemtl skin\n"
        "v 0 0 0  # trailing comment\nvt 0.5 0.5\nvn 0 0 1\nv 1 0 0\nv 0 1 0\nl 1 2\np 1\n"
        "f 1 2 3 # trailing\n"
    )
    data = read_text(text)
    assert data.faces.tolist() == [[0, 1, 2]]
    assert len(data.vertices) == 3


def test_crlf_line_ends_read_like_lf():
    text = SQUARE + "f 1 2 3\nf 1 3 4\n"
    crlf = read_obj(io.BytesIO(text.replace("\n", "\r\n").encode()))
    lf = read_text(text)
    np.testing.assert_array_equal(crlf.vertices, lf.vertices)
    np.testing.assert_array_equal(crlf.faces, lf.faces)
    np.testing.assert_array_equal(crlf.face_lines, lf.face_lines)


def test_backslash_continues_a_record_on_the_next_line():
    data = read_text("v 0 \\\n 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n2 3\nf 1 2 3\n")
    assert data.faces.tolist() == [[0, 1, 2], [0, 1, 2]]
    assert data.face_lines.tolist() == [5, 7]
    np.testing.assert_array_equal(data.vertices[0], [0, 0, 0])


def test_a_path_a_text_file_and_a_binary_file_give_the_same_data(tmp_path):
    path = tmp_path / "square.obj"
    path.write_text(SQUARE + "f 1 2 3\n")
    from_path = read_obj(path)
    from_str_path = read_obj(str(path))
    with open(path) as text_file, open(path, "rb") as binary_file:
        from_text, from_binary = read_obj(text_file), read_obj(binary_file)
    for data in (from_str_path, from_text, from_binary):
        np.testing.assert_array_equal(data.vertices, from_path.vertices)
        np.testing.assert_array_equal(data.faces, from_path.faces)
    assert from_path.source == "square.obj"


def test_missing_file_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        read_obj(tmp_path / "nowhere.obj")


def test_a_directory_is_an_unreadable_file(tmp_path):
    with pytest.raises(MeshInputError, match="cannot read"):
        read_obj(tmp_path)


def test_latin1_bytes_in_a_comment_are_harmless():
    data = read_obj(io.BytesIO(b"# caf\xe9 model\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"))
    assert data.faces.tolist() == [[0, 1, 2]]


def test_latin1_bytes_in_a_vertex_are_an_unparsable_number():
    with pytest.raises(MeshInputError, match=r"line 2: .* is not a number") as error:
        read_obj(io.BytesIO(b"v 0 0 0\nv 1 0 0\xe9\nv 0 1 0\nf 1 2 3\n"))
    assert error.value.line == 2


def test_vertices_no_face_uses_are_kept_by_the_reader():
    data = read_text(SQUARE + "f 1 2 3\n")
    assert len(data.vertices) == 4


def test_spot_has_the_documented_counts():
    data = read_obj(MESHES / "spot.obj")
    assert data.vertices.shape == (2930, 3) and data.faces.shape == (5856, 3)
    assert data.faces.min() == 0 and data.faces.max() == 2929


def test_bunny_has_the_documented_counts():
    data = read_obj(MESHES / "stanford-bunny.obj")
    assert data.vertices.shape == (35947, 3) and data.faces.shape == (69451, 3)
    assert len(np.unique(data.faces)) == 34834
    assert data.n_polygons_triangulated == 0


def test_spot_reads_like_trimesh_reads_it():
    import trimesh

    data = read_obj(MESHES / "spot.obj")
    reference = trimesh.load(MESHES / "spot.obj", force="mesh", process=False, maintain_order=True)
    np.testing.assert_array_equal(data.vertices, reference.vertices)
    np.testing.assert_array_equal(data.faces, reference.faces)


# ---------------------------------------------------------------- encodings and line ends

TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


def test_a_utf8_byte_order_mark_is_dropped_and_the_first_vertex_kept():
    data = read_obj(io.BytesIO(b"\xef\xbb\xbf" + TRIANGLE.encode()))
    assert len(data.vertices) == 3
    np.testing.assert_array_equal(data.vertices[0], [0, 0, 0])
    assert data.faces.tolist() == [[0, 1, 2]]


def test_a_byte_order_mark_in_a_text_stream_is_dropped_too():
    assert len(read_text("\ufeff" + TRIANGLE).vertices) == 3


@pytest.mark.parametrize("line_end", ["\r", "\r\n"], ids=["cr-only", "crlf"])
def test_cr_and_crlf_line_ends_read_like_lf_with_the_same_line_numbers(line_end):
    text = "# a comment\n" + SQUARE + "f 1 2 3\n\nf 1 3 4\n"
    other = read_obj(io.BytesIO(text.replace("\n", line_end).encode()))
    lf = read_text(text)
    np.testing.assert_array_equal(other.vertices, lf.vertices)
    np.testing.assert_array_equal(other.faces, lf.faces)
    assert other.face_lines.tolist() == lf.face_lines.tolist() == [6, 8]


def test_mixed_line_ends_are_each_one_line_end():
    data = read_obj(io.BytesIO(b"v 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2 3\r"))
    assert data.faces.tolist() == [[0, 1, 2]]
    assert data.face_lines.tolist() == [4]


@pytest.mark.parametrize(
    "codec, prefix, name",
    [
        ("utf-16-le", b"\xff\xfe", "UTF-16"),
        ("utf-16-be", b"\xfe\xff", "UTF-16"),
        ("utf-16-le", b"", "UTF-16"),
        ("utf-16-be", b"", "UTF-16"),
        ("utf-32-le", b"\xff\xfe\x00\x00", "UTF-32"),
    ],
    ids=["utf16-le-bom", "utf16-be-bom", "utf16-le", "utf16-be", "utf32-le-bom"],
)
def test_utf16_and_utf32_are_refused_by_name(codec, prefix, name):
    with pytest.raises(MeshInputError, match=f"the file is {name} text; save it as UTF-8") as error:
        read_obj(io.BytesIO(prefix + TRIANGLE.encode(codec)))
    assert error.value.line is None


def test_other_nul_bytes_are_still_a_binary_file():
    with pytest.raises(MeshInputError, match="binary file"):
        read_obj(io.BytesIO(b"v 0 0 0\nv 1 0 0\x00\x00\x01\nv 0 1 0\nf 1 2 3\n"))


# ---------------------------------------------------------------- records: skipped or refused

@pytest.mark.parametrize(
    "record", ["vt 0.5 0.5", "vn 0 0 1", "vp 0.2", "g body", "o cow", "s 1", "mg 1", "usemtl skin",
               "mtllib cow.mtl", "l 1 2", "p 1", "cstype bspline", "deg 3", "curv 0 1 1 2", "end", "lod 2"],
)
def test_obj_records_without_triangles_are_skipped(record):
    data = read_text(f"v 0 0 0\n{record}\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    assert len(data.vertices) == 3 and data.faces.tolist() == [[0, 1, 2]]


@pytest.mark.parametrize("line", ["vx 0 1 0", "V 0 1 0", "0 1 0", "vertex 0 1 0", "\u200bv 0 1 0"])
def test_any_other_record_is_an_error_naming_its_line(line):
    with pytest.raises(MeshInputError, match="is not an OBJ record") as error:
        read_text(f"v 0 0 0\nv 1 0 0\n{line}\nv 0 1 0\nf 1 2 3\n")
    assert error.value.line == 3
    assert "line 3" in str(error.value)


# ---------------------------------------------------------------- only regular files

def test_a_fifo_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)
    with pytest.raises(MeshInputError, match="pipe.obj: is a FIFO .*not a regular file"):
        read_obj(fifo)


def test_a_link_to_a_device_is_refused_without_reading(tmp_path):
    link = tmp_path / "zero.obj"
    link.symlink_to("/dev/zero")
    with pytest.raises(MeshInputError, match="zero.obj: is a device or socket, not a regular file"):
        read_obj(link)


def test_a_link_to_a_regular_file_is_read(tmp_path):
    (tmp_path / "real.obj").write_text(TRIANGLE)
    (tmp_path / "link.obj").symlink_to(tmp_path / "real.obj")
    assert read_obj(tmp_path / "link.obj").faces.tolist() == [[0, 1, 2]]
