"""The error types declare their attributes, and a refused operation fills them in."""

from __future__ import annotations

import pytest

import halfedge_edu as hx


def test_topology_error_defaults_when_no_rule_is_given():
    error = hx.TopologyError("not allowed")
    assert (error.reason, error.rule, error.elements, str(error)) == ("not allowed", None, (), "not allowed")


def test_refused_collapse_raises_the_checks_rule_and_elements(tetrahedron):
    check = tetrahedron.can_collapse(0)
    assert not check
    with pytest.raises(hx.TopologyError) as caught:
        tetrahedron.collapse(0)
    assert caught.value.rule == check.rule == "tetrahedron"
    assert caught.value.elements == check.elements
    assert caught.value.reason == check.reason


def test_invariant_and_input_errors_carry_their_element():
    invariant = hx.MeshInvariantError("next-cycle", ("halfedge", 3), "halfedge 3 ...")
    assert (invariant.rule, invariant.element, str(invariant)) == ("next-cycle", ("halfedge", 3), "[next-cycle] halfedge 3 ...")
    given = hx.MeshInputError("bad face", element=("face", 2), line=7)
    assert (given.element, given.line) == (("face", 2), 7)
    assert (hx.MeshInputError("unreadable").element, hx.MeshInputError("unreadable").line) == (None, None)
