"""The step log: named elements, every pointer change in order, replay, and no cost when off."""

from __future__ import annotations

import pytest

from halfedge_edu.data import sample
from halfedge_edu.core.ops import OperationLog, PointerChange, collapse, flip, split
from halfedge_edu.core.ops import log as log_module
from tests.core.ops.helpers import assert_replay_gives

def logged(operation, mesh, *args, **kwargs):
    before = mesh.copy()
    log = OperationLog()
    result = operation(mesh, *args, log=log, **kwargs)
    assert_replay_gives(before, mesh, log)
    assert all(change.old != change.new for change in log.changes)
    return log, result


def test_flip_log_names_the_elements_of_the_picture():
    strip = sample("strip")  # edge 1 is 1 -> 2 in face 0 = (0, 1, 2); face 1 = (1, 3, 2)
    log, _ = logged(flip, strip, 1)
    assert log.operation == "flip" and log.edge == 1 and log.halfedge == 2
    assert list(log.named) == ["h0", "h1", "h2", "h3", "h4", "h5", "v0", "v1", "v2", "v3", "f0", "f1"]
    assert {name: index for name, (kind, index) in log.named.items() if kind == "vertex"} == {
        "v0": 1, "v1": 2, "v2": 0, "v3": 3,
    }
    assert log.named["f0"] == ("face", 0) and log.named["f1"] == ("face", 1)
    assert log.created == [] and log.deleted == []


def test_flip_log_lists_every_change_in_order_with_its_old_value():
    log, _ = logged(flip, sample("strip"), 1)
    assert log.changes[:2] == [
        PointerChange("halfedge", 2, "vertex", 1, 3),
        PointerChange("halfedge", 3, "vertex", 2, 0),
    ]
    fields = {change.field for change in log.changes}
    assert fields <= {"next", "prev", "vertex", "face", "halfedge"}
    assert [title for _, title in log.phases][0].startswith("turn the edge")


def test_describe_has_one_line_per_change():
    log, _ = logged(flip, sample("strip"), 1)
    text = log.describe()
    assert "halfedge 2 .vertex: 1 -> 3" in text.splitlines()
    change_lines = [line for line in text.splitlines() if " ." in line and "->" in line]
    assert len(change_lines) == len(log.changes)


def test_a_log_is_cleared_when_used_again():
    mesh, log = sample("octahedron"), OperationLog()
    flip(mesh, 0, log=log)
    between = mesh.copy()
    flip(mesh, 0, log=log)
    assert_replay_gives(between, mesh, log)


def test_replaying_part_of_the_log_gives_the_in_between_state():
    mesh = sample("strip")
    before = mesh.copy()
    log = OperationLog()
    flip(mesh, 1, log=log)
    halfway = before.copy()
    log.replay(halfway, 2)
    assert halfway.halfedge_vertex[2] == 3 and halfway.halfedge_vertex[3] == 0
    assert halfway.halfedge_next[2] == before.halfedge_next[2]


def _arrays(mesh):
    return [mesh.halfedge_next.copy(), mesh.halfedge_prev.copy(), mesh.halfedge_vertex.copy(),
            mesh.halfedge_face.copy(), mesh.vertex_halfedge.copy(), mesh.face_halfedge.copy()]


def test_replay_from_a_later_start_and_taking_back_give_the_in_between_states():
    mesh = sample("strip")
    before = mesh.copy()
    log = OperationLog()
    flip(mesh, 1, log=log)
    n = len(log.changes)
    for start in range(n + 1):
        for stop in range(start, n + 1):
            direct, stepped = before.copy(), before.copy()
            log.replay(direct, stop)
            log.replay(stepped, start)
            log.replay(stepped, stop, start=start)
            for a, b in zip(_arrays(direct), _arrays(stepped)):
                assert (a == b).all(), (start, stop)
            back = direct.copy()
            assert log.can_take_back(start, stop)
            log.take_back(back, start, stop)                 # from stop back to start
            at_start = before.copy()
            log.replay(at_start, start)
            for a, b in zip(_arrays(at_start), _arrays(back)):
                assert (a == b).all(), (stop, start)


def test_taking_back_a_created_element_is_refused():
    mesh = sample("strip")
    log = OperationLog()
    split(mesh, 1, log=log)
    assert not log.can_take_back(0, len(log.changes))
    with pytest.raises(ValueError, match="create or delete"):
        log.take_back(mesh, 0, len(log.changes))


def test_without_a_log_no_log_object_is_built(monkeypatch):
    def forbidden(*args, **kwargs):
        raise AssertionError("the plain operation built a log object")

    monkeypatch.setattr(log_module.LoggingWriter, "__init__", forbidden)
    monkeypatch.setattr(log_module.OperationLog, "begin", forbidden)
    monkeypatch.setattr(log_module.OperationLog, "name", forbidden)
    mesh = sample("octahedron")
    flip(mesh, 0)
    mesh.validate()


def test_a_refused_operation_leaves_the_log_empty():
    log = OperationLog()
    with pytest.raises(ValueError):
        flip(sample("tetrahedron"), 0, log=log)
    assert log.changes == [] and log.operation == ""


@pytest.mark.parametrize(("name", "edge"), [("octahedron", 0), ("strip", 0), ("strip", 1), ("lone_triangle", 0)])
def test_split_log_replays_and_names_the_new_elements(name, edge):
    log, m = logged(split, sample(name), edge)
    assert log.operation == "split" and log.named["m"] == ("vertex", m.index)
    assert ("vertex", m.index) in log.created and log.deleted == []
    assert list(log.named)[:4] == ["h0", "h1", "h2", "h3"]


def test_collapse_log_names_va_vb_and_the_halfedges_around_them():
    log, survivor = logged(collapse, sample("single_collapse"), 0)
    assert log.operation == "collapse" and log.halfedge == 0
    assert log.named["vA"] == ("vertex", survivor.index) and log.named["vB"] == ("vertex", 0)
    assert list(log.named)[:4] == ["vA", "vB", "h_BA", "h_AB"]
    for name in ("h_A_L", "h_L_B", "h_L_A", "h_B_L", "h_B_R", "h_R_A", "h_R_B", "h_A_R"):
        assert log.named[name][0] == "halfedge"
    assert log.named["vL"] == ("vertex", 4) and log.named["vR"] == ("vertex", 8)
    assert ("vertex", 0) in log.deleted and ("face", 0) in log.deleted and log.created == []
    assert log.changes[0].field == "position"
    assert any("removed" in note for note in log.notes)


@pytest.mark.parametrize(("name", "halfedge"), [("cube", 0), ("cube", 1), ("strip", 0), ("strip", 1), ("open_patch", 2)])
def test_collapse_log_replays_in_every_case(name, halfedge):
    mesh = sample(name)
    logged(collapse, mesh, mesh.halfedge(halfedge))


def test_an_empty_step_is_described_as_such():
    log, _ = logged(collapse, sample("cube"), 0)  # vB has degree 3: no other halfedge moves
    assert "(nothing to change here)" in log.describe()


def test_every_field_a_log_records_is_one_the_writer_stores():
    """Replay writes through the operations' own Writer: it must know every recorded field."""
    recorded = set()
    for operation, name, edge in ((flip, "octahedron", 0), (split, "open_patch", 0), (collapse, "single_collapse", 0)):
        log, _ = logged(operation, sample(name), edge)
        recorded |= {(c.kind, c.field) for c in log.changes if c.field not in ("created", "deleted")}
    assert ("vertex", "position") in recorded and ("halfedge", "next") in recorded
    assert recorded <= set(log_module.Writer.FIELDS)
