"""Keyboard stepping in a real JupyterLab (issue 13): with the mouse pointer over a
widget's panel, ``n`` and ``t`` move the explorer and the arrows step a flip stepper;
the panel's text and the live 3D view both follow, and JupyterLab does not take the keys.

The Lab is the shared ``lab`` fixture; this test writes its own small notebook into the
Lab's folder (an explorer and a flip stepper on the open patch), so it does not wait for
a whole chapter to run. The expected halfedges come from the library (``h.next``,
``h.twin``). Screenshots go to ``$HALFEDGE_EDU_SCREENSHOTS`` (or pytest's temporary folder).
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import nbformat
import pytest

import halfedge_edu as hx
from tests.browser.lab_page import (
    MIN_CHANGED_SHARE,
    ExplorerInLab,
    StepperInLab,
    changed_share,
    hold_still,
    hover_in_place,
    in_view,
    open_and_run_all,
    reported_page,
    wait_for,
)

pytestmark = pytest.mark.browser

NOTEBOOK = "keyboard_stepping.ipynb"
START = 7           # the explorer's first halfedge (as chapter 03's)
FLIP_EDGE = 12      # an interior edge of the open patch
KEY_TIMEOUT = 30    # seconds for the panel to answer a key
FLIP_TITLE = "Edge flip: step by step"   # the flip stepper's panel title


def write_notebook(folder: Path) -> None:
    notebook = nbformat.v4.new_notebook()
    notebook.cells = [
        nbformat.v4.new_code_cell("import halfedge_edu as hx\nfrom halfedge_edu.viz import FlipStepper, HalfedgeExplorer"),
        nbformat.v4.new_code_cell(f'explorer = HalfedgeExplorer(hx.sample("open_patch"), halfedge={START})\nexplorer'),
        nbformat.v4.new_code_cell(f'stepper = FlipStepper(hx.sample("open_patch"), {FLIP_EDGE}, window_size=(480, 360))\n'
                                  "stepper"),
    ]
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(notebook, folder / NOTEBOOK)


def notebook_state(page) -> tuple[int, int]:
    """(number of cells, index of the active cell): what a key taken by JupyterLab would change."""
    return tuple(page.evaluate(
        "() => { const nb = window.jupyterapp.shell.currentWidget.content;"
        " return [nb.widgets.length, nb.activeCellIndex]; }"))


def test_keys_move_the_explorer_and_step_the_stepper_in_a_live_lab(lab, browser_context, screenshot_dir):
    write_notebook(lab.root)
    with reported_page(browser_context, lab, screenshot_dir, "keyboard-failure-page.png") as page:
        _drive(page, lab, screenshot_dir)


def _drive(page, lab, shots: Path) -> None:
    clock = time.monotonic()
    open_and_run_all(page, lab, NOTEBOOK)
    explorer = ExplorerInLab(page, shots)
    explorer.wait_for_live_view("the explorer")
    assert "keys (pointer over here)" in explorer.output.inner_text(), "no key hint under the buttons"
    wait_for(lambda: explorer.current_halfedge() == START, 30, "the explorer's pointer table")
    png, before = explorer.settled_picture(None, "the live view's first frame")
    explorer.save("keys-0-start.png", png)

    # The pointer over the pointer table: the key area takes the keyboard focus (which
    # makes the explorer's cell the active one, as a click in its output would).
    hover_in_place(explorer.output.locator("table").first)
    cells = wait_for(lambda: notebook_state(page) if notebook_state(page)[1] == 1 else None, 10,
                     "the explorer's cell to become the active one")
    patch = hx.sample("open_patch")
    expected = START
    for step, key, move in [(1, "n", "next"), (2, "t", "twin")]:
        expected = getattr(patch.halfedge(expected), move).index
        page.keyboard.press(key)
        wait_for(lambda: explorer.current_halfedge() == expected, KEY_TIMEOUT,
                 f"the pointer table to show h = {expected} after the key {key}")
        assert explorer.trail().endswith(f"-{move}-> h{expected}")
        png, after = explorer.settled_picture(before, f"the live view to redraw after the key {key}")
        share = changed_share(before, after)
        assert share >= MIN_CHANGED_SHARE, f"the key {key} changed only {share:.2%} of the view"
        explorer.save(f"keys-{step}-{key}.png", png)
        print(f"key {key}: h {expected}, {share:.2%} of the view changed")
        before = after
    assert notebook_state(page) == cells, "JupyterLab took a key (a cell was added or the active cell moved)"
    explorer.save("keys-3-explorer-with-panel.png", explorer.output.screenshot(timeout=30_000))

    stepper = StepperInLab(page, FLIP_TITLE)
    stepper.output.scroll_into_view_if_needed(timeout=30_000)
    wait_for(lambda: stepper.step_shown() == 0, 30, "the flip stepper's step counter")
    _, shown = stepper.settled_picture(None, "the flip stepper's first frame")
    hover_in_place(stepper.output.locator("table").first)
    cells = wait_for(lambda: notebook_state(page) if notebook_state(page)[1] == 2 else None, 10,
                     "the stepper's cell to become the active one")
    for key, expected_step in [("ArrowRight", 1), ("ArrowRight", 2), ("ArrowLeft", 1)]:
        page.keyboard.press(key)
        wait_for(lambda: stepper.step_shown() == expected_step, KEY_TIMEOUT,
                 f"the step counter to show step {expected_step} after {key}")
        png, shown = stepper.settled_picture(shown, f"the flip stepper's view to redraw after {key}")
        (shots / f"keys-flip-{expected_step}-{key}.png").write_bytes(png)
    assert re.search(r"step 1 of \d+", stepper.output.inner_text())
    assert notebook_state(page) == cells, "JupyterLab took an arrow key"
    print(f"keyboard test: {time.monotonic() - clock:.0f} s; screenshots in {shots}")


LAPTOP = {"width": 1366, "height": 768}   # a common laptop screen


def test_on_a_laptop_screen_with_the_file_browser_open_the_pointer_table_sits_beside_the_view(
        lab, browser_context, screenshot_dir):
    """Issue 30: at 1366 x 768 with JupyterLab's file browser open (its default) the
    pointer table went below the 3D view, never on screen together with it."""
    write_notebook(lab.root)
    with reported_page(browser_context, lab, screenshot_dir, "laptop-failure-page.png") as page:
        clock = time.monotonic()
        page.set_viewport_size(LAPTOP)
        open_and_run_all(page, lab, NOTEBOOK)
        assert page.locator(".jp-FileBrowser").first.is_visible(), "the file browser is closed"
        explorer = ExplorerInLab(page, screenshot_dir)
        explorer.wait_for_live_view("the explorer")
        wait_for(lambda: explorer.current_halfedge() == START, 30, "the explorer's pointer table")
        table = explorer.output.locator("table").first
        explorer.frame.evaluate("frame => frame.scrollIntoView({block: 'start'})")
        hold_still(table)
        view, rows = explorer.frame.bounding_box(), table.bounding_box()
        explorer.settled_picture(None, "the explorer's view to draw the mesh")
        explorer.save("laptop-explorer.png", page.screenshot())
        assert rows["x"] >= view["x"] + view["width"], f"the pointer table {rows} is not beside the view {view}"
        assert in_view(page, explorer.frame) and in_view(page, table), \
            f"the view {view} and the pointer table {rows} are not on a {LAPTOP} screen together"
        print(f"laptop layout test: {time.monotonic() - clock:.0f} s")
