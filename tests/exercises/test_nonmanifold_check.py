"""Chapter 04's second exercise (UChicago P3): is a face list edge- or vertex-non-manifold?

The learner answers on a ``SoupTopology``, the structure that builds for any face list.
"""

from __future__ import annotations

import pytest

from halfedge_edu.exercises import check_nonmanifold
from halfedge_edu.exercises.chapter_checks import NONMANIFOLD_SLIPS, nonmanifold_cases
from halfedge_edu.core.soup import SoupTopology


def has_nonmanifold_edges(soup):
    """UChicago's rule in a learner's words: an edge is manifold with one or two faces."""
    return any(len(soup.faces_of_edge(a, b)) > 2 for a, b in soup.edges())


def has_nonmanifold_vertices(soup):
    """Grow one fan from a face at each vertex, across edges at that vertex; a face left over is a second fan."""
    for v in range(soup.n_vertices):
        faces = soup.faces_of_vertex(v)
        if not faces:
            continue
        fan, stack = {faces[0]}, [faces[0]]
        while stack:
            f = stack.pop()
            for u in soup.faces[f]:
                if u != v:
                    for g in soup.faces_of_edge(v, int(u)):
                        if g not in fan:
                            fan.add(g)
                            stack.append(g)
        if len(fan) < len(faces):
            return True
    return False


def test_the_learners_answer_passes_public_and_hidden_cases():
    assert check_nonmanifold(has_nonmanifold_edges, has_nonmanifold_vertices).passed
    for seed in (0, 1, 2, 3):
        result = check_nonmanifold(has_nonmanifold_edges, has_nonmanifold_vertices, seed=seed)
        assert result.passed and result.total == 4, result.message


def test_every_hidden_case_set_has_a_pinch_and_an_extra_page():
    for seed in (0, 5):
        soups = [SoupTopology(faces) for _, faces in nonmanifold_cases(seed)]
        assert [s.has_nonmanifold_edges() for s in soups] == [False, False, False, True]
        assert [s.has_nonmanifold_vertices() for s in soups][:3] == [False, False, True]


def two_faces_exactly(soup):
    """The slip: 'manifold' read as 'two faces on every edge', so a boundary edge counts as bad."""
    return any(len(soup.faces_of_edge(a, b)) != 2 for a, b in soup.edges())


def closed_ring_required(soup):
    """The slip: a vertex is called manifold only when its fan closes into a full ring."""
    for v in range(soup.n_vertices):
        for u in {int(u) for f in soup.faces_of_vertex(v) for u in soup.faces[f] if u != v}:
            if len(soup.faces_of_edge(v, u)) != 2:
                return True
    return has_nonmanifold_vertices(soup)


def connected_anywhere(soup):
    """The slip: a vertex's faces are 'one fan' when the surface joins them anywhere, not at the vertex."""
    for v in range(soup.n_vertices):
        faces = soup.faces_of_vertex(v)
        if not faces:
            continue
        reached, stack = {faces[0]}, [faces[0]]
        while stack:
            f = stack.pop()
            for k in range(3):
                a, b = int(soup.faces[f][k]), int(soup.faces[f][(k + 1) % 3])
                for g in soup.faces_of_edge(a, b):
                    if g not in reached:
                        reached.add(g)
                        stack.append(g)
        if not set(faces) <= reached:
            return True
    return False


SLIP_CODE = {
    "a boundary edge called non-manifold": (two_faces_exactly, has_nonmanifold_vertices),
    "a boundary vertex called non-manifold": (has_nonmanifold_edges, closed_ring_required),
    "faces connected anywhere instead of across edges at the vertex": (has_nonmanifold_edges, connected_anywhere),
}


@pytest.mark.parametrize("slip", sorted(SLIP_CODE))
def test_each_slip_is_refused_with_its_own_sentence(slip):
    sentences = {name: sentence.split("{")[0][:40] for name, _, sentence in NONMANIFOLD_SLIPS}
    assert set(sentences) == set(SLIP_CODE)
    result = check_nonmanifold(*SLIP_CODE[slip])
    assert not result.passed and sentences[slip] in result.message, result.message
    assert all(words not in result.message for name, words in sentences.items() if name != slip)


def test_a_function_that_says_false_everywhere_is_told_which_edge_has_three_faces():
    result = check_nonmanifold(lambda soup: False, has_nonmanifold_vertices)
    assert not result.passed and "Edge (0, 1) has 3 faces" in result.message


def test_the_vertex_question_is_not_asked_where_an_edge_is_non_manifold_as_uchicago_allows():
    """UChicago P3: 'You DO NOT need to check vertex manifoldness when the mesh is not edge manifold'."""
    calls = []

    def vertices_recording(soup):
        calls.append(soup.has_nonmanifold_edges())
        return has_nonmanifold_vertices(soup)

    assert check_nonmanifold(has_nonmanifold_edges, vertices_recording).passed
    assert calls and not any(calls)
