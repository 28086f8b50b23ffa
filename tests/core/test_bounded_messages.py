"""Messages that list elements name the first few and count the rest: their length does not grow with the input."""

from __future__ import annotations

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.core.errors import MAX_NAMED, MeshInputError, first_few

TRIANGLE = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])


def test_a_million_copies_of_one_face_give_a_short_error_naming_the_first_few():
    faces = np.zeros((1_000_000, 3), dtype=np.int64) + [0, 1, 2]
    with pytest.raises(MeshInputError) as caught:
        hx.HalfedgeMesh.from_faces(TRIANGLE, faces)
    message = str(caught.value)
    assert "has 1000000 faces (0, 1, 2, 3, 4, 5, 6, 7, ... and 999992 more)" in message
    assert len(message) < 300


def test_the_manifold_report_of_many_copies_names_the_first_few_faces_of_each_edge():
    faces = np.zeros((100_000, 3), dtype=np.int64) + [0, 1, 2]
    described = hx.manifold_report(faces).describe()
    assert "with faces [0, 1, 2, 3, 4, 5, 6, 7, ... and 99992 more]" in described
    assert len(described) < 2000


@pytest.mark.parametrize("items, total, expected", [
    (range(3), None, "0, 1, 2"),
    (range(MAX_NAMED), None, ", ".join(map(str, range(MAX_NAMED)))),
    (range(10), None, "0, 1, 2, 3, 4, 5, 6, 7, ... and 2 more"),
    ((str(i) for i in range(10**9)), 10**9, "0, 1, 2, 3, 4, 5, 6, 7, ... and 999999992 more"),
])
def test_first_few_names_at_most_eight_and_counts_the_rest(items, total, expected):
    assert first_few(items, total=total) == expected
