"""Operation steppers: step k is "before + the first k steps of the log", both ways."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from halfedge_edu.data import sample
from halfedge_edu.core.ops import OperationLog, split
from halfedge_edu.viz.arrows import HEAD, typical_edge_length
from halfedge_edu.viz.palette import ROLES, rgb
from halfedge_edu.viz.atlas import CollapseAtlas
from halfedge_edu.viz.steppers import CollapseStepper, FlipStepper, SplitStepper, group_changes

ARRAYS = ("halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face", "vertex_halfedge", "face_halfedge")


def _same_arrays(mesh, other) -> bool:
    return all(np.array_equal(getattr(mesh, name), getattr(other, name)) for name in ARRAYS)


@pytest.fixture
def flip_stepper(closing):
    widget = FlipStepper(sample("open_patch"), 12, mode="static")
    closing(widget)
    return widget


@pytest.mark.parametrize("button", ["step", "end"])
def test_a_move_past_the_end_says_why_it_does_not_move(flip_stepper, button):
    flip_stepper.go("end")
    flip_stepper.buttons[button].click()
    n = flip_stepper.n_steps
    assert flip_stepper.step_index == n
    assert f"step {n} of {n} is the last one" in flip_stepper._status.value


@pytest.mark.parametrize("button", ["back", "start"])
def test_a_move_before_the_start_says_why_it_does_not_move(flip_stepper, button):
    flip_stepper.buttons[button].click()
    assert flip_stepper.step_index == 0 and "this is the start" in flip_stepper._status.value
    flip_stepper.buttons["step"].click()
    assert "this is the start" not in flip_stepper._status.value


def test_step_zero_shows_the_gathered_elements_by_name(flip_stepper):
    text = flip_stepper.describe()
    assert text.startswith("flip of edge 12: step 0 of 17 (gather the elements)\n")
    assert "gathered: h0 = halfedge 24, h1 = halfedge 25" in text
    assert set(flip_stepper.scene.roles) >= {"named", "named_vertex", "named_face"}


def test_each_step_names_one_change_old_and_new(flip_stepper):
    flip_stepper.step()
    assert flip_stepper.describe().splitlines()[1] == "now: halfedge 24 (h0) .vertex: 7 (v0) -> 11 (v3)"
    assert list(flip_stepper.scene.roles["changed"]) == [24]
    assert list(flip_stepper.scene.roles["old_vertex"]) == [7]
    assert list(flip_stepper.scene.roles["new_vertex"]) == [11]


def test_last_step_is_the_mesh_after_the_operation(flip_stepper):
    flip_stepper.go("end")
    assert _same_arrays(flip_stepper.state, flip_stepper.result)


def test_going_back_to_the_start_restores_the_mesh_before(flip_stepper):
    flip_stepper.go("end")
    flip_stepper.go("start")
    assert _same_arrays(flip_stepper.state, flip_stepper.before)


def test_the_mesh_passed_in_is_never_changed(closing):
    mesh = sample("open_patch")
    before = mesh.copy()
    widget = FlipStepper(mesh, 12, mode="static")
    closing(widget)
    widget.go("end")
    assert _same_arrays(mesh, before)


def test_step_and_back_clamp_at_the_ends(flip_stepper):
    assert flip_stepper.back() == 0
    flip_stepper.go("end")
    assert flip_stepper.step() == flip_stepper.n_steps


def test_buttons_step_forward_and_back(flip_stepper):
    flip_stepper.buttons["step"].click()
    flip_stepper.buttons["step"].click()
    flip_stepper.buttons["back"].click()
    assert flip_stepper.step_index == 1


def test_phase_jumps_to_the_start_of_the_next_phase(flip_stepper):
    starts = flip_stepper.source.phase_steps()
    assert flip_stepper.go("phase") == starts[0]
    assert flip_stepper.go("phase") == starts[1]
    assert flip_stepper.go("phase back") == starts[0]


def test_bad_step_number_is_refused(flip_stepper):
    with pytest.raises(IndexError, match="steps run from 0 to 17"):
        flip_stepper.go(99)
    with pytest.raises(ValueError, match="unknown move 'sideways'"):
        flip_stepper.go("sideways")


def test_refused_flip_shows_the_reason_instead_of_steps(closing):
    mesh = sample("open_patch")
    boundary_edge = int(np.flatnonzero(mesh.halfedge_face < 0)[0]) >> 1
    widget = FlipStepper(mesh, boundary_edge, mode="static")
    closing(widget)
    assert widget.n_steps == 0
    assert widget.describe().startswith(f"flip of edge {boundary_edge}: refused (boundary-edge)\nreason: ")
    assert "refused" in widget.scene.roles


def test_creating_an_element_is_one_step_with_its_first_values():
    mesh = sample("open_patch")
    log = OperationLog()
    split(mesh, 12, log=log)
    groups = group_changes(log.changes)
    first = [log.changes[i] for i in range(*groups[0])]
    assert [(c.kind, c.field) for c in first] == [("vertex", "created"), ("vertex", "position")]
    edge = [log.changes[i] for i in range(*groups[1])]
    assert [c.field for c in edge] == ["created", "created", "created", "vertex", "vertex"]
    assert sum(stop - start for start, stop in groups) == len(log.changes)


def test_split_stepper_ends_with_one_more_vertex_three_edges_two_faces(closing):
    mesh = sample("open_patch")
    widget = SplitStepper(mesh, 12, mode="static")
    closing(widget)
    widget.go("end")
    state = widget.state
    assert (state.n_vertices, state.n_edges, state.n_faces) == (mesh.n_vertices + 1, mesh.n_edges + 3, mesh.n_faces + 2)
    state.validate()


def test_half_way_states_draw_without_error(closing):
    widget = SplitStepper(sample("open_patch"), 12, mode="static")
    closing(widget)
    for k in range(widget.n_steps + 1):
        widget.go(k)
        assert widget.screenshot().startswith(b"\x89PNG")


def test_stepper_on_the_bunny_draws_only_near_the_edge(bunny, closing):
    widget = FlipStepper(bunny, 5000, mode="static")
    closing(widget)
    widget.go("end")
    assert len(widget.scene.drawn_halfedges) < 2000
    assert {10000, 10001} <= set(widget.scene.drawn_halfedges.tolist())


def test_collapse_stepper_of_the_cube_keeps_euler_and_names_vA_vB(closing):
    widget = CollapseStepper(sample("cube"), 0, mode="static")
    closing(widget)
    assert "vB = vertex 0 is removed; vA = vertex 4 survives" in widget.describe()
    widget.go("end")
    state = widget.state
    assert (state.n_vertices, state.n_edges, state.n_faces) == (7, 15, 10)
    assert state.euler_characteristic == 2


def test_collapse_that_breaks_the_link_condition_is_shown_refused(closing):
    widget = CollapseStepper(sample("tetrahedron"), 0, mode="static")
    closing(widget)
    assert widget.describe().startswith("collapse of edge 0: refused (tetrahedron)")
    assert widget.buttons == {}


@pytest.fixture(scope="module")
def atlas():
    widget = CollapseAtlas(mode="static")
    yield widget
    widget.close()


def test_atlas_starts_with_both_cases_gathered(atlas):
    atlas.go("start")
    assert [s.step_index for s in atlas.steppers] == [0, 0]
    assert atlas.describe().splitlines()[0] == f"phase 0 of {len(atlas.phases)}: gather the elements"


def test_atlas_steps_both_cases_through_the_same_phase(atlas):
    atlas.go("start")
    atlas.step()
    atlas.step()
    assert atlas.phase == 2
    for stepper in atlas.steppers:              # exactly the changes of phases 1 and 2 applied
        applied = stepper.groups[stepper.step_index - 1][1] if stepper.step_index else 0
        assert applied == stepper.log.phases[2][0]


def test_atlas_end_is_every_collapse_done(atlas):
    atlas.go("end")
    assert all(s.step_index == s.n_steps for s in atlas.steppers)
    assert "V - E + F = 7 - 15 + 10 = 2" in atlas.describe()


def test_atlas_lists_each_refusal_with_its_rule(atlas):
    text = atlas.describe()
    for rule in ("tetrahedron", "both-ends-on-boundary", "lone-triangle"):
        assert f"({rule}):" in text


def test_atlas_picture_holds_every_case(atlas):
    picture = Image.open(io.BytesIO(atlas.screenshot()))
    assert picture.width >= 2 * 440


@pytest.mark.parametrize("mesh_name, boundary", [("cube", False), ("open_patch", True)])
def test_split_stepper_goes_to_any_step_from_any_step(closing, mesh_name, boundary):
    mesh = sample(mesh_name)
    edge = int(np.flatnonzero(mesh.halfedge_face < 0)[0]) >> 1 if boundary else 0
    widget = SplitStepper(mesh, edge, mode="static")
    closing(widget)
    for k in [widget.n_steps, 0, *range(7, widget.n_steps + 1), *range(widget.n_steps, -1, -1)]:
        assert widget.go(k) == k
        assert widget.screenshot().startswith(b"\x89PNG")
    widget.go("end")
    widget.buttons["start"].click()
    assert widget.step_index == 0 and widget._status.value.count("#B00020") == 0


def test_named_moves_stay_inside_the_steps(flip_stepper):
    flip_stepper.go("end")
    assert flip_stepper.go("step") == flip_stepper.n_steps
    flip_stepper.go("start")
    assert flip_stepper.go("back") == 0


def test_a_step_that_fails_to_draw_leaves_the_widget_where_it_was(flip_stepper, monkeypatch):
    flip_stepper.go(3)
    picture = flip_stepper.screenshot()
    calls = []

    def fail_once():
        calls.append(flip_stepper.step_index)
        if len(calls) == 1:
            raise ValueError("cannot draw")

    monkeypatch.setattr(flip_stepper.view, "update", fail_once)
    flip_stepper.buttons["step"].click()
    assert flip_stepper.step_index == 3
    assert "cannot draw" in flip_stepper._status.value
    assert "step 3 of 17" in flip_stepper.describe()
    assert calls == [4, 3]                  # the redraw of step 4 failed; step 3 was drawn again
    assert flip_stepper.screenshot() == picture


def _pointer_edges(mesh) -> set[tuple[int, int]]:
    """The live edges as the halfedges' ``.vertex`` pointers have them now: sorted vertex pairs."""
    ends = mesh.edge_vertices()[~mesh.edge_deleted]
    ends = ends[(ends >= 0).all(axis=1)]
    return {tuple(sorted(int(v) for v in pair)) for pair in ends}


def _drawn_edges(widget) -> set[tuple[int, int]]:
    return {(int(a), int(b)) for a, b in widget.scene.drawn_edges()}


def test_flip_pictures_draw_the_diagonal_only_when_its_pointers_have_it(closing):
    # The strip's edge 1 is the diagonal v0-v1 = (1, 2) of the quadrilateral (0, 1, 3, 2);
    # the flip turns it into (0, 3). Step 1 moves h0's origin, step 2 h1's.
    widget = FlipStepper(sample("strip"), 1, mode="static")
    closing(widget)
    old, new = (1, 2), (0, 3)
    # The faces being rewired are filled without outlines: every line is one of drawn_edges.
    assert not widget.scene.plotter.actors["local_surface"].prop.show_edges
    seen = {}
    for step in range(widget.n_steps + 1):
        widget.go(step)
        drawn = _drawn_edges(widget)
        assert drawn == _pointer_edges(widget.state), f"step {step}"
        seen[step] = (old in drawn, new in drawn)
    assert seen[0] == (True, False)
    assert seen[1] == (False, False)          # half turned: edge 1 lies along v3-v1, no diagonal yet
    assert all(seen[step] == (False, True) for step in range(2, widget.n_steps + 1))


@pytest.mark.parametrize("make", [
    lambda: SplitStepper(sample("open_patch"), 12, mode="static"),
    lambda: SplitStepper(sample("strip"), 0, mode="static"),
    lambda: CollapseStepper(sample("cube"), 0, mode="static"),
], ids=["split-inside", "split-boundary", "collapse"])
def test_every_step_draws_the_edges_its_pointers_have(closing, make):
    widget = make()
    closing(widget)
    for step in range(widget.n_steps + 1):
        widget.go(step)
        assert _drawn_edges(widget) == _pointer_edges(widget.state), f"step {step}"


def _changed_pixels(widget) -> int:
    picture = np.asarray(Image.open(io.BytesIO(widget.screenshot())).convert("RGB"), dtype=np.int16)
    changed = np.array(rgb(ROLES["changed"].color), dtype=np.int16)
    return int((np.abs(picture - changed).max(axis=2) < 30).sum())


def test_the_arrow_that_changes_at_flip_step_1_is_drawn_apart_and_in_full(closing):
    widget = FlipStepper(sample("strip"), 1, mode="static")
    closing(widget)
    widget.go(1)                              # halfedge 2 (h0) now leaves v3: it runs along h5
    scene = widget.scene
    assert scene.roles["changed"].tolist() == [2]
    halfedges = scene.drawn_halfedges
    assert 2 in halfedges
    k = int(np.flatnonzero(halfedges == 2)[0])
    assert tuple(scene.arrow_colors[k]) == tuple(rgb(ROLES["changed"].color))
    points = scene.arrow_points                                       # (n, 7, 3)
    head = 2 * HEAD * typical_edge_length(widget.state)
    middle = points[k, [0, 5]].mean(axis=0)                           # half way from tail to tip
    for j, h in enumerate(halfedges):
        if j == k:
            continue
        tail, tip = points[j, 0], points[j, 5]
        t = np.clip((middle - tail) @ (tip - tail) / ((tip - tail) @ (tip - tail)), 0.0, 1.0)
        gap = float(np.linalg.norm(middle - (tail + t * (tip - tail))))
        assert gap > head, f"the arrow of halfedge 2 lies on that of halfedge {h} ({gap:.3f} apart)"
    # As long as a changed arrow that hides nothing: step 2 changes h1, which lies free.
    at_step_1 = _changed_pixels(widget)
    widget.go(2)
    assert at_step_1 >= 0.6 * _changed_pixels(widget)


STATE_ARRAYS = ARRAYS + ("positions", "vertex_deleted", "edge_deleted", "face_deleted")


@pytest.mark.parametrize("make", [
    lambda: SplitStepper(sample("open_patch"), 12, mode="static"),
    lambda: CollapseStepper(sample("cube"), 0, mode="static"),
    lambda: FlipStepper(sample("open_patch"), 12, mode="static"),
], ids=["split", "collapse", "flip"])
def test_a_state_reached_from_the_one_shown_before_is_the_replay_from_the_start(closing, make):
    """Steps forward apply the changes since the state shown; steps back undo them (or
    replay from the start across a created or deleted element): in any order of moves,
    each state equals the mesh before with the step's changes replayed."""
    widget = make()
    closing(widget)
    n = widget.n_steps
    moves = [1, 2, 3, 2, 1, 0, n, n - 1, 2, 5, 4, n, 0, 3, n - 2, n - 3, 1]
    for step in moves:
        widget.go(min(step, n))
        expected = widget.before.copy()
        widget.log.replay(expected, widget.groups[widget.step_index - 1][1] if widget.step_index else 0)
        state = widget.state
        assert all(np.array_equal(getattr(state, name), getattr(expected, name)) for name in STATE_ARRAYS)
        assert (state.n_vertices, state.n_edges, state.n_faces) == (expected.n_vertices, expected.n_edges,
                                                                    expected.n_faces)


def test_every_step_back_from_every_later_step_gives_the_replayed_state(closing):
    """The cube's collapse writes halfedge 2's prev twice: undoing must go newest first."""
    widget = CollapseStepper(sample("cube"), 0, mode="static")
    closing(widget)
    for later in range(1, widget.n_steps + 1):
        for earlier in range(later):
            widget.go(later)
            widget.go(earlier)
            expected = widget.before.copy()
            widget.log.replay(expected, widget.groups[earlier - 1][1] if earlier else 0)
            assert all(np.array_equal(getattr(widget.state, name), getattr(expected, name))
                       for name in STATE_ARRAYS), (later, earlier)
