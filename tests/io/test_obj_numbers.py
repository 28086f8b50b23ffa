"""OBJ numbers are read with OBJ's syntax, as other OBJ readers read them, not Python's.

A coordinate: optional sign, digits with an optional decimal point, optional exponent.
An index: optional sign and digits. Anything else is an error naming its line.
"""

from __future__ import annotations

import io

import pytest

from halfedge_edu.core.errors import MeshInputError
from halfedge_edu.io import read_obj

TRIANGLE = "v {x} 0 0\nv 1 0 0\nv 0 1 0\nf {i} 2 3\n"


def _read(text: str):
    return read_obj(io.BytesIO(text.encode("utf-8")))


# A guard, not a reproduction: the stricter syntax must still read every form OBJ allows.
@pytest.mark.parametrize("word, value", [
    ("0", 0.0), ("-2", -2.0), ("+2", 2.0), ("1.5", 1.5), (".5", 0.5), ("5.", 5.0), ("-.5", -0.5),
    ("1e3", 1000.0), ("1E-3", 0.001), ("+1.5e+2", 150.0), ("2.e1", 20.0),
])
def test_obj_number_syntax_is_read(word, value):
    assert _read(TRIANGLE.format(x=word, i=1)).vertices[0, 0] == value


@pytest.mark.parametrize("word", ["1_000", "1_0.5", "\u0661", "\u0661\u0662", "1_0e1"])
def test_a_coordinate_outside_obj_number_syntax_names_its_line(word):
    with pytest.raises(MeshInputError, match=r"line 1: .* is not a number") as caught:
        _read(TRIANGLE.format(x=word, i=1))
    assert caught.value.line == 1


@pytest.mark.parametrize("token", ["1_0", "0_1", "\u0661", "1_0/2", "+1_0"])
def test_a_vertex_index_outside_obj_syntax_names_its_line(token):
    with pytest.raises(MeshInputError, match=r"line 4: .* is not a vertex index") as caught:
        _read(TRIANGLE.format(x=0, i=token))
    assert caught.value.line == 4

