"""write_obj: 1-based, exact round trip, and no partial file on failure."""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np
import pytest

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io import read_obj, write_obj
from halfedge_edu.io.obj import atomic_output

MESHES = Path(__file__).resolve().parents[2] / "halfedge_edu" / "data"


@pytest.mark.parametrize("name", ["spot.obj", "stanford-bunny.obj"])
def test_round_trip_gives_exactly_the_same_arrays(tmp_path, name):
    original = read_obj(MESHES / name)
    write_obj(tmp_path / name, original.vertices, original.faces)
    again = read_obj(tmp_path / name)
    np.testing.assert_array_equal(again.vertices, original.vertices)
    np.testing.assert_array_equal(again.faces, original.faces)


def test_awkward_floats_survive_the_round_trip(tmp_path):
    vertices = np.array([[0.1, 1 / 3, -2e-300], [1e300, np.nextafter(1.0, 2.0), -0.0], [5e-324, 123456789.123456789, 7.0]])
    write_obj(tmp_path / "t.obj", vertices, [[0, 1, 2]])
    again = read_obj(tmp_path / "t.obj").vertices
    assert again.tobytes() == vertices.tobytes()  # bit for bit, the sign of -0.0 included


def test_indices_are_written_one_based_after_a_header():
    out = io.StringIO()
    write_obj(out, [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], header="a triangle\nfor the course")
    lines = out.getvalue().splitlines()
    assert lines[:2] == ["# a triangle", "# for the course"]
    assert lines[-1] == "f 1 2 3"
    assert "v 1.0 0.0 0.0" in lines


def test_no_header_when_header_is_none():
    out = io.StringIO()
    write_obj(out, [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], header=None)
    assert out.getvalue().splitlines()[0] == "v 0.0 0.0 0.0"


@pytest.mark.parametrize(
    "vertices, faces, message",
    [
        ([[0, 0, 0], [1, 0, 0]], [[0, 1, 2]], "face 0"),
        ([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]], [[0, 1, 2]], "vertex 2"),
        ([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]], "shape"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0.0, 1.0, 2.0]], "integer"),
    ],
)
def test_bad_arrays_raise_and_write_nothing(tmp_path, vertices, faces, message):
    with pytest.raises(MeshInputError, match=message):
        write_obj(tmp_path / "out.obj", vertices, faces)
    assert os.listdir(tmp_path) == []


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    target = tmp_path / "mesh.obj"
    target.write_text("old contents\n")
    with pytest.raises(RuntimeError):
        with atomic_output(target) as file:
            file.write("half of a new file")
            raise RuntimeError("disk full, say")
    assert target.read_text() == "old contents\n"
    assert os.listdir(tmp_path) == ["mesh.obj"]


def test_a_successful_write_replaces_the_file_with_normal_permissions(tmp_path):
    target = tmp_path / "mesh.obj"
    target.write_text("old contents\n")
    write_obj(target, [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    assert read_obj(target).faces.tolist() == [[0, 1, 2]]
    assert os.listdir(tmp_path) == ["mesh.obj"]
    umask = os.umask(0)
    os.umask(umask)
    assert target.stat().st_mode & 0o777 == 0o666 & ~umask
