"""The debugging lab's classic bugs: each is caught, by validate() or by its check, with a
message that names the rule; each right version beside it passes the same test."""

from __future__ import annotations

import pytest

from halfedge_edu.exercises import check_collapse, check_flip
from halfedge_edu.exercises.classic_bugs import BUGS, catch, check_loop_split, loop_split_right

NAMES = sorted(BUGS)


def test_the_lab_has_at_least_eight_bugs_each_named_as_wrong():
    assert len(BUGS) >= 8
    for name, bug in BUGS.items():
        assert bug.wrong.__name__ == name and bug.wrong.__doc__.startswith("WRONG"), name
        assert not bug.right.__doc__.startswith("WRONG"), bug.right.__name__


@pytest.mark.parametrize("name", NAMES)
def test_each_bug_is_caught_with_a_message_naming_its_rule(name):
    bug = BUGS[name]
    caught = catch(bug)
    assert caught is not None, f"{name} was not caught"
    assert caught.rule == bug.rule
    assert f"[{bug.rule}]" in caught.message
    kind, index = caught.element
    assert kind in ("vertex", "halfedge", "face") and index >= 0


@pytest.mark.parametrize("name", NAMES)
def test_the_right_version_beside_each_bug_passes(name):
    bug = BUGS[name]
    assert catch(bug, bug.right) is None
    if bug.caught_by == "validate":
        bug.demo(bug.right).validate()


@pytest.mark.parametrize("name", [n for n in NAMES if n.startswith("flip_")])
def test_the_flip_bugs_are_also_caught_by_check_flip_naming_the_rule(name):
    result = check_flip(BUGS[name].wrong)
    assert not result and f"breaks the rule {BUGS[name].rule}" in result.message


@pytest.mark.parametrize("name", [n for n in NAMES if n.startswith("collapse_")])
def test_the_collapse_bugs_are_also_caught_by_check_collapse_naming_the_rule(name):
    result = check_collapse(BUGS[name].wrong)
    assert not result and f"breaks the rule {BUGS[name].rule}" in result.message


def test_the_endless_ring_is_stopped_by_the_time_limit():
    caught = catch(BUGS["one_ring_endless_at_the_boundary"])
    assert "did not return within" in caught.message and "start halfedge" in caught.message
    assert caught.mesh.vertex(caught.element[1]).is_boundary


def test_the_right_loop_split_is_loops_connectivity():
    import halfedge_edu as hx

    octahedron = hx.sample("octahedron")
    ours = loop_split_right(octahedron.copy())
    reference = hx.loop_subdivide(octahedron)
    assert check_loop_split(loop_split_right) == ""
    assert (ours.n_vertices, ours.n_edges, ours.n_faces) == (reference.n_vertices, reference.n_edges, reference.n_faces)
    assert sorted(ours.vertex_degrees()) == sorted(reference.vertex_degrees())
