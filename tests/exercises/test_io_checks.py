"""Chapter 01's OBJ exercise: readers and writers in two valid styles pass, classic slips are named."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from halfedge_edu.exercises.chapter_checks import check_obj_io, check_obj_reader, check_obj_writer


class LoopStyleMesh:
    """The Loop assignment's way: a mesh class that parses a file line by line into
    triangles (polygons cut into fans) and writes itself back, coordinates with %f."""

    def __init__(self) -> None:
        self.positions: list[tuple[float, float, float]] = []
        self.triangles: list[tuple[int, int, int]] = []

    def parse(self, text: str) -> None:
        for raw in text.splitlines():
            tokens = raw.split("#")[0].split()
            if tokens and tokens[0] == "v":
                x, y, z = tokens[1:4]
                self.positions.append((float(x), float(y), float(z)))
            elif tokens and tokens[0] == "f":
                ids = []
                for token in tokens[1:]:
                    number = int(token.split("/")[0])
                    ids.append(number - 1 if number > 0 else len(self.positions) + number)
                for k in range(1, len(ids) - 1):
                    self.triangles.append((ids[0], ids[k], ids[k + 1]))

    def dump(self) -> str:
        out = "".join("v %f %f %f\n" % p for p in self.positions)
        return out + "".join("f " + " ".join(str(i + 1) for i in face) + "\n" for face in self.triangles)


def loop_style_read(source):
    mesh = LoopStyleMesh()
    mesh.parse(Path(source).read_text() if isinstance(source, Path) else source)
    return np.array(mesh.positions).reshape(-1, 3), mesh.triangles


def loop_style_write(vertices, faces):
    mesh = LoopStyleMesh()
    mesh.positions = [tuple(p) for p in np.asarray(vertices).tolist()]
    mesh.triangles = [tuple(int(i) for i in face) for face in faces]
    return mesh.dump()


_CORNER = re.compile(r"(-?\d+)(?:/\d*)*")


def polygon_style_read(source):
    """Another valid style: regular expressions, polygons kept whole, an ndarray of vertices."""
    text = source.read_text() if isinstance(source, Path) else source
    vertices, faces = [], []
    for line in re.split(r"\r\n|\n|\r", text):
        record = line.partition("#")[0].split()
        if record[:1] == ["v"]:
            vertices.append(record[1:4])
        elif record[:1] == ["f"]:
            numbers = [int(_CORNER.fullmatch(corner).group(1)) for corner in record[1:]]
            faces.append([n - 1 if n > 0 else len(vertices) + n for n in numbers])
    return np.array(vertices, dtype=np.float64).reshape(-1, 3), faces


def polygon_style_write(vertices, faces):
    rows = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices, dtype=float).tolist()]
    rows += ["f " + " ".join(str(int(i) + 1) for i in face) for face in faces]
    return "\n".join(rows) + "\n"


@pytest.mark.parametrize(("read", "write"), [(loop_style_read, loop_style_write),
                                             (polygon_style_read, polygon_style_write)],
                         ids=["loop-assignment-style", "polygon-style"])
def test_a_right_reader_and_writer_pass_in_either_style(read, write):
    for result in (check_obj_reader(read), check_obj_writer(write), check_obj_io(read, write)):
        assert result and result.message.startswith("All good!"), result.message


def test_the_round_trip_runs_the_learners_own_functions():
    result = check_obj_io(polygon_style_read, polygon_style_write)
    assert "round trip" in result.checked


# --------------------------------------------------------------------------------------
# Wrong readers: each is the right one with one classic slip
# --------------------------------------------------------------------------------------

def read_keeping_one_based_indices(source):
    vertices, faces = polygon_style_read(source)
    return vertices, [[i + 1 for i in face] for face in faces]


def read_negative_from_the_end_of_the_file(source):
    text = source.read_text() if isinstance(source, Path) else source
    records = [line.split("#")[0].split() for line in text.splitlines()]
    vertices = [[float(x) for x in r[1:4]] for r in records if r[:1] == ["v"]]
    faces = [[int(c.split("/")[0]) - 1 if int(c.split("/")[0]) > 0 else len(vertices) + int(c.split("/")[0])
              for c in r[1:]] for r in records if r[:1] == ["f"]]
    return np.array(vertices), faces


def read_dropping_the_last_line(source):
    text = source.read_text() if isinstance(source, Path) else source
    lines = text.split("\n")[:-1]        # the slip: assumes every line ends in "\n"
    return polygon_style_read("\n".join(lines))


def read_taking_the_last_number_of_a_corner(source):
    text = source.read_text() if isinstance(source, Path) else source
    vertices, faces = [], []
    for line in text.splitlines():
        record = line.split("#")[0].split()
        if record[:1] == ["v"]:
            vertices.append([float(x) for x in record[1:4]])
        elif record[:1] == ["f"]:
            numbers = [int(corner.split("/")[-1]) for corner in record[1:]]   # the slip: the normal
            faces.append([n - 1 if n > 0 else len(vertices) + n for n in numbers])
    return np.array(vertices), faces


def read_vt_lines_as_vertices(source):
    text = source.read_text() if isinstance(source, Path) else source
    vertices = [[float(x) for x in (line.split()[1:4] + ["0"])[:3]] for line in text.splitlines()
                if line.startswith("v")]      # the slip: "vt" and "vn" start with "v" too
    return np.array(vertices).reshape(-1, 3), polygon_style_read(source)[1]


def read_skipping_polygons(source):
    vertices, faces = polygon_style_read(source)
    return vertices, [face for face in faces if len(face) == 3]


@pytest.mark.parametrize(("read", "where", "named"), [
    (read_keeping_one_based_indices, "one triangle", "subtract 1"),
    (read_negative_from_the_end_of_the_file, "negative indices", "from the end of the whole file"),
    (read_dropping_the_last_line, "no line break at the end", "has no line break after it, and your read_obj "
                                                              "dropped it"),
    (read_taking_the_last_number_of_a_corner, "vt/vn records and v/vt/vn corners", "took the normal index"),
    (read_vt_lines_as_vertices, "vt/vn records and v/vt/vn corners", "read the 'vt' and 'vn' lines as vertices"),
])
def test_a_wrong_reader_is_refused_naming_its_mistake(read, where, named):
    result = check_obj_reader(read)
    assert not result and result.mesh_name == where and named in result.message, result.message


def test_a_reader_that_cannot_split_corners_is_accepted_by_the_loop_spec_and_told_the_rule():
    """The Loop assignment asks only for 'v', 'f' and '#' lines: raising on 'v/vt/vn' corners is
    turning down what it does not ask for, so the check passes and says what chapter 01 adds."""
    def read_int_of_whole_corner(source):
        vertices, _ = polygon_style_read(source)
        text = source.read_text() if isinstance(source, Path) else source
        return vertices, [[int(c) - 1 for c in line.split("#")[0].split()[1:]]
                          for line in text.splitlines() if line.startswith("f ")]

    result = check_obj_reader(read_int_of_whole_corner)
    assert result.passed and "Loop assignment's OBJ spec" in result.message
    assert "raised ValueError on vt/vn records and v/vt/vn corners" in result.message
    assert "the vertex is the number before the first '/'" in result.message


def test_a_reader_skipping_polygons_is_accepted_by_the_loop_spec_which_allows_it():
    result = check_obj_reader(read_skipping_polygons)
    assert result.passed and "skipped a face of four corners ('a quad')" in result.message
    assert "as that assignment allows" in result.message


def loop_spec_read_obj(source):
    """A reader written to the Loop assignment's words: 'v', 'f' and '#' lines, triangles only."""
    text = source.read_text() if isinstance(source, Path) else source
    vertices, faces = [], []
    for line in text.splitlines():
        if line.startswith("#"):
            continue
        parts = line.split()
        if parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            if len(parts) != 4:
                raise ValueError("this reader reads triangles only")
            faces.append([int(x) - 1 for x in parts[1:]])
    return np.array(vertices), faces


def loop_spec_write_obj(vertices, faces):
    """A writer of the Loop assignment's triangle meshes: three corners per face."""
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices).tolist()]
    lines += [f"f {face[0] + 1} {face[1] + 1} {face[2] + 1}" for face in faces]
    return "\n".join(lines) + "\n"


def test_a_reader_and_writer_of_the_loop_assignments_spec_get_full_marks_and_the_convention_named():
    for seed in (None, 1, 2):
        result = check_obj_io(loop_spec_read_obj, loop_spec_write_obj, seed=seed)
        assert result.passed, result.message
        assert "Your read_obj follows the Loop assignment's OBJ spec" in result.message
        assert "Your write_obj follows the Loop assignment's OBJ spec" in result.message
        assert result.total == len(result.checked)


def test_a_loop_spec_reader_still_fails_on_what_the_spec_asks():
    def one_based(source):
        vertices, faces = loop_spec_read_obj(source)
        return vertices, [[i + 1 for i in face] for face in faces]

    result = check_obj_io(one_based, loop_spec_write_obj)
    assert not result.passed and result.mesh_name == "one triangle" and "subtract 1" in result.message


def test_a_reader_of_text_only_is_told_to_accept_a_path():
    result = check_obj_reader(lambda source: polygon_style_read(str(source)))
    assert not result and result.mesh_name.startswith("spot.obj") and "pathlib.Path" in result.message


# --------------------------------------------------------------------------------------
# Wrong writers
# --------------------------------------------------------------------------------------

def test_a_writer_of_zero_based_indices_is_told_to_add_one():
    def write_zero_based(vertices, faces):
        return polygon_style_write(vertices, [[int(i) - 1 for i in face] for face in faces])

    result = check_obj_writer(write_zero_based)
    assert not result and "index 0" in result.message and "write each index + 1" in result.message


def test_a_writer_of_too_few_digits_is_told_to_write_more():
    def write_two_decimals(vertices, faces):
        rows = ["v %.2f %.2f %.2f" % tuple(p) for p in np.asarray(vertices).tolist()]
        return "\n".join(rows) + "\n" + polygon_style_write(np.zeros((0, 3)), faces)

    result = check_obj_writer(write_two_decimals)
    assert not result and "vertex 1" in result.message and "repr(x)" in result.message


def test_a_writer_that_turns_faces_around_is_told_the_order_matters():
    def write_reversed(vertices, faces):
        return polygon_style_write(vertices, [list(face)[::-1] for face in faces])

    result = check_obj_writer(write_reversed)
    assert not result and "orientation" in result.message


def test_a_writer_that_returns_nothing_is_told_to_return_the_text():
    result = check_obj_writer(lambda vertices, faces: None)
    assert not result and "should return the file's text" in result.message


def test_a_stub_is_not_finished_and_a_blank_is_named():
    def stub(source):
        raise NotImplementedError("write read_obj")

    def blank(vertices, faces):
        return ...

    assert "not finished yet" in check_obj_io(stub, polygon_style_write).message
    assert "still has blanks" in check_obj_io(polygon_style_read, blank).message
