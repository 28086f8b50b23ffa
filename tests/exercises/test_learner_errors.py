"""When the learner's function raises, the check names the learner's own failing line and
hands over the failing case: ``result.mesh`` and ``result.rerun()``.

Also when the exception comes from another process (the grader's judge): then it carries
``learner_traceback``, the traceback formatted where the learner's code ran.
"""

from __future__ import annotations

import traceback

import numpy as np
import pytest

from halfedge_edu.exercises import check_flip, check_laplacian_step, check_one_ring
from halfedge_edu.exercises.harness import own_line


def flip_with_a_lookup_slip(mesh, e):
    """A flip that keeps its pointers in a dict keyed by the halfedges it gathered, then asks
    for one it never stored: the KeyError a learner sees as 'KeyError: np.int64(1)'."""
    h0 = 2 * e
    stored = {h0: int(mesh.halfedge_next[h0])}
    twin_next = stored[mesh.halfedge_next[h0 ^ 1]]    # the slip: never stored
    return twin_next


def test_an_exception_names_the_learners_own_line():
    result = check_flip(flip_with_a_lookup_slip)
    assert not result.passed and "raised KeyError" in result.message
    assert "of your flip_with_a_lookup_slip: `twin_next = stored[mesh.halfedge_next[h0 ^ 1]]" in result.message


def test_the_failing_case_is_handed_over_and_rerun_shows_the_learners_traceback():
    result = check_flip(flip_with_a_lookup_slip)
    assert result.mesh is not None and result.mesh.n_faces > 0
    with pytest.raises(KeyError) as raised:
        result.rerun()
    lines = "".join(traceback.format_tb(raised.value.__traceback__))
    assert "twin_next = stored[mesh.halfedge_next[h0 ^ 1]]" in lines


def test_rerun_works_on_a_fresh_copy_every_time():
    calls = []

    def smoothing_that_breaks_the_mesh(mesh):
        calls.append(mesh.positions.copy())
        mesh.positions[:] = 0.0
        raise ValueError("gave up")

    result = check_laplacian_step(smoothing_that_breaks_the_mesh)
    for _ in range(2):
        with pytest.raises(ValueError):
            result.rerun()
    assert len(calls) == 3 and np.array_equal(calls[1], calls[0]) and np.array_equal(calls[2], calls[0])


def test_a_stub_is_not_offered_a_rerun_sentence():
    def one_ring(mesh, v):
        raise NotImplementedError("write one_ring")

    result = check_one_ring(one_ring)
    assert "not finished yet" in result.message and "rerun" not in result.message


class LearnerError(Exception):
    """What the grader's judge raises in the check's process for a learner's exception."""


def test_an_exception_from_another_process_names_the_line_of_its_learner_traceback():
    text = ('Traceback (most recent call last):\n'
            '  File "/tmp/ipykernel_41/2871.py", line 7, in my_flip\n'
            '    nxt[h1] = lookup[h4]\n'
            'KeyError: 4\n')

    def proxy_flip(mesh, e):
        error = KeyError(4)
        error.learner_traceback = text
        raise error

    result = check_flip(proxy_flip)
    assert "It came from line 7 of your my_flip: `nxt[h1] = lookup[h4]`." in result.message
    error = LearnerError("boom")
    error.learner_traceback = text
    assert own_line(error) == " It came from line 7 of your my_flip: `nxt[h1] = lookup[h4]`."
