"""Keyboard stepping (halfedge_edu.viz.keys): a key does what its button does.

The events are the dictionaries ipyevents sends from the browser for a ``keydown``
(its ``_send_dom_event``: the key fields, the modifier flags, the event type).
"""

from __future__ import annotations

import threading

import pytest
from tornado.ioloop import IOLoop

import halfedge_edu.viz.main_thread as main_thread
from halfedge_edu.data import sample
from halfedge_edu.viz import (
    CollapseAtlas,
    CollapseStepper,
    FlipStepper,
    HalfedgeExplorer,
    LoopStepper,
    OneRingViewer,
    QEMStepper,
    RemeshStepper,
    SplitStepper,
)
from halfedge_edu.viz.keys import key_name

ERROR_RED = "#B00020"       # the status line's colour for an error (viz.widgets)


def keydown(key: str, **modifiers: bool) -> dict:
    """A keydown event as ipyevents sends it for ``key`` (a ``KeyboardEvent.key``)."""
    flags = {name: modifiers.get(name, False) for name in ("altKey", "ctrlKey", "metaKey", "shiftKey")}
    return {"event": "keydown", "type": "keydown", "key": key, "code": "", "location": 0, "repeat": False,
            "timeStamp": 0.0, "target": {"tagName": "DIV", "id": "", "className": ""}, **flags}


def arrive(widget, event: dict) -> None:
    """Deliver ``event`` as a message from the browser reaches the ipyevents widget."""
    widget.key_area.event._handle_mouse_msg(None, event, None)


@pytest.fixture
def explorer(closing):
    widget = HalfedgeExplorer(sample("open_patch"), 5, mode="static")
    closing(widget)
    return widget


@pytest.fixture
def flip_stepper(closing):
    widget = FlipStepper(sample("open_patch"), 12, mode="static")
    closing(widget)
    return widget


# -- key names -------------------------------------------------------------------------------


def test_key_names_are_the_browsers_with_letters_in_lower_case_and_space_spelled_out():
    assert key_name(keydown("n")) == "n"
    assert key_name(keydown("N", shiftKey=True)) == "n"
    assert key_name(keydown(" ")) == "Space"
    assert key_name(keydown("ArrowRight")) == "ArrowRight"
    assert key_name(keydown("+", shiftKey=True)) == "+"


def test_a_key_with_ctrl_alt_or_meta_is_a_shortcut_and_has_no_name():
    for modifier in ("ctrlKey", "altKey", "metaKey"):
        assert key_name(keydown("n", **{modifier: True})) is None


def test_only_a_keydown_with_a_key_has_a_name():
    assert key_name({**keydown("n"), "event": "keyup"}) is None
    assert key_name({"event": "keydown"}) is None
    assert key_name({"event": "keydown", "key": ""}) is None


# -- the explorer ----------------------------------------------------------------------------


def test_n_p_t_in_a_browser_message_walk_the_explorer_and_redraw_it(explorer):
    h = explorer.halfedge
    picture = explorer.screenshot()
    arrive(explorer, keydown("n"))
    assert explorer.halfedge == h.next
    assert explorer.screenshot() != picture
    arrive(explorer, keydown("t"))
    assert explorer.halfedge == h.next.twin
    arrive(explorer, keydown("p"))
    assert explorer.halfedge == h.next.twin.prev
    assert explorer.describe().splitlines()[1] == (
        f"trail: h{h.index} -next-> h{h.next.index} -twin-> h{h.next.twin.index} -prev-> h{h.next.twin.prev.index}")


def test_arrow_right_and_space_step_and_arrow_left_undoes(explorer):
    h = explorer.halfedge
    assert explorer.press("ArrowRight") == "next"
    assert explorer.press(" ") == "next"
    assert explorer.halfedge == h.next.next
    assert explorer.press("ArrowLeft") == "back"
    assert explorer.halfedge == h.next
    assert explorer.trail == [h.index, h.next.index]


def test_a_key_the_explorer_does_not_use_changes_nothing(explorer):
    explorer.press("n")
    before, picture = explorer.describe(), explorer.screenshot()
    for event in (keydown("x"), keydown("Enter"), keydown("Escape"), keydown("n", ctrlKey=True),
                  {**keydown("n"), "event": "keyup"}, {"event": "keydown"}):
        arrive(explorer, event)
    assert explorer.describe() == before and explorer.screenshot() == picture
    assert ERROR_RED not in explorer._status.value


def test_back_at_the_start_of_the_trail_is_harmless(explorer):
    h = explorer.halfedge
    for _ in range(3):
        explorer.press("ArrowLeft")
    assert explorer.trail == [h.index]
    assert ERROR_RED not in explorer._status.value


def test_the_one_ring_viewer_turns_by_arrows_and_moves_to_the_tip_by_t(closing):
    viewer = OneRingViewer(sample("open_patch"), 4, mode="static")
    closing(viewer)
    h = viewer.current
    viewer.press("ArrowRight")
    assert viewer.current == h.prev.twin
    viewer.press("ArrowLeft")
    assert viewer.current == h
    viewer.press("t")
    assert viewer.vertex == h.tip


# -- the steppers ----------------------------------------------------------------------------


def test_arrows_home_and_end_move_the_step_counter(flip_stepper):
    last = flip_stepper.n_steps
    arrive(flip_stepper, keydown("ArrowRight"))
    assert flip_stepper.step_index == 1 and f"step 1 of {last}" in flip_stepper.describe()
    arrive(flip_stepper, keydown(" "))
    assert flip_stepper.step_index == 2
    arrive(flip_stepper, keydown("ArrowLeft"))
    assert flip_stepper.step_index == 1
    arrive(flip_stepper, keydown("End"))
    assert flip_stepper.step_index == last
    arrive(flip_stepper, keydown("Home"))
    assert flip_stepper.step_index == 0


def test_keys_at_either_end_leave_the_stepper_there(flip_stepper):
    for key in ("ArrowLeft", "Home"):
        flip_stepper.press(key)
        assert flip_stepper.step_index == 0
    flip_stepper.press("End")
    for key in ("ArrowRight", " ", "PageDown", "End"):
        flip_stepper.press(key)
        assert flip_stepper.step_index == flip_stepper.n_steps
    assert ERROR_RED not in flip_stepper._status.value


def test_a_step_by_key_that_fails_leaves_the_stepper_where_it_was(flip_stepper, monkeypatch):
    flip_stepper.go(3)
    picture = flip_stepper.screenshot()

    def cannot_draw():
        raise ValueError("cannot draw")

    monkeypatch.setattr(flip_stepper.view, "update", cannot_draw)
    arrive(flip_stepper, keydown("ArrowRight"))            # no exception reaches the caller
    assert flip_stepper.step_index == 3 and "step 3 of" in flip_stepper.describe()
    assert "cannot draw" in flip_stepper._status.value
    assert flip_stepper.screenshot() == picture


def test_a_refused_operation_has_no_buttons_and_so_no_keys(closing):
    refused = CollapseStepper(sample("tetrahedron"), 0, mode="static")
    closing(refused)
    assert refused.key_area.keys == {} and refused.key_area.event is None
    assert refused.press("ArrowRight") is None
    assert "keys" not in refused.key_area.widget.children[0].value


def test_a_key_pressed_on_another_thread_steps_on_the_main_thread(flip_stepper, monkeypatch):
    """As a click does: ipykernel 7 delivers the browser's message on a subshell thread,
    and the step (which draws with VTK) is queued for the kernel's main thread."""
    loop = IOLoop(make_current=False)
    monkeypatch.setattr(main_thread, "kernel_loop", lambda: loop)
    stepped_on = []
    show = flip_stepper.view.update
    monkeypatch.setattr(flip_stepper.view, "update", lambda: (stepped_on.append(threading.current_thread()), show()))
    subshell = threading.Thread(target=arrive, args=(flip_stepper, keydown("ArrowRight")), name="subshell-test")
    subshell.start()
    subshell.join()
    assert flip_stepper.step_index == 0 and stepped_on == []   # queued, not run on the subshell
    loop.add_callback(loop.stop)
    loop.start()
    loop.close()
    assert flip_stepper.step_index == 1 and stepped_on == [threading.main_thread()]


def test_the_collapse_atlas_steps_every_case_one_phase_per_key(closing):
    atlas = CollapseAtlas(mode="static")
    closing(atlas)
    atlas.key_area.press("ArrowRight")
    assert atlas.phase == 1
    atlas.key_area.press("End")
    assert atlas.phase == len(atlas.phases)
    atlas.key_area.press("ArrowLeft")
    assert atlas.phase == len(atlas.phases) - 1
    atlas.key_area.press("Home")
    assert atlas.phase == 0


SMALL = (200, 150)          # pixels: every key redraws, and these tests only read the state
STEPPERS = {
    "flip": lambda: FlipStepper(sample("open_patch"), 12, mode="static", window_size=SMALL),
    "split": lambda: SplitStepper(sample("open_patch"), 12, mode="static", window_size=SMALL),
    "collapse": lambda: CollapseStepper(sample("cube"), 0, mode="static", window_size=SMALL),
    "loop": lambda: LoopStepper(sample("tetrahedron"), mode="static", window_size=SMALL),
    "qem": lambda: QEMStepper(sample("icosphere", subdivisions=1), 40, mode="static", window_size=SMALL),
    "remesh": lambda: RemeshStepper(sample("icosphere", subdivisions=1), iterations=1, mode="static", window_size=SMALL),
}
WALKERS = {
    "explorer": lambda: HalfedgeExplorer(sample("open_patch"), 5, mode="static", window_size=SMALL),
    "one ring": lambda: OneRingViewer(sample("open_patch"), 4, mode="static", window_size=SMALL),
}


@pytest.fixture(params=[*WALKERS, *STEPPERS])
def any_keyed_widget(request, closing):
    widget = {**WALKERS, **STEPPERS}[request.param]()
    closing(widget)
    return widget


@pytest.fixture(params=list(STEPPERS))
def any_stepper(request, closing):
    widget = STEPPERS[request.param]()
    closing(widget)
    return widget


def test_every_button_has_a_key_and_the_hint_names_each(any_keyed_widget):
    area = any_keyed_widget.key_area
    assert set(area.keys.values()) == set(any_keyed_widget.buttons) - {"go to"}
    assert area.keys == any_keyed_widget.KEYS
    hint = area.widget.children[0].value
    assert hint.startswith('<div') and "keys (pointer over here)" in hint
    for label in area.keys.values():
        assert f" {label}" in hint


def test_each_key_of_a_stepper_does_what_clicking_its_button_does(any_stepper):
    """From a step in the middle, each key lands where its button's click lands."""
    widget = any_stepper
    middle = widget.n_steps // 2
    for key, label in widget.KEYS.items():
        widget.go(middle)
        widget.buttons[label].click()
        by_button = widget.describe()
        widget.go(middle)
        widget.press(key)
        assert widget.describe() == by_button, f"{key} is not the same as clicking {label!r}"
