"""Chapter 09 in a real JupyterLab: the Loop stepper's live 3D view follows its buttons.

The Loop stepper (like the QEM stepper and the Bezier surface editor) draws with a
``PaintedScene``, which replaces whole actors at each step instead of editing arrays in
place as the halfedge scene does. This test checks that the live trame view picks those
new actors up: run all cells, press **start** and **step**, and compare the frames.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from tests.browser.lab_page import (
    MIN_CHANGED_SHARE,
    StepperInLab,
    changed_share,
    click_in_place,
    open_and_run_all,
    reported_page,
    wait_for,
)

pytestmark = pytest.mark.browser

NOTEBOOK = "09_loop_subdivision.ipynb"
TITLE = "Loop subdivision: step by step"   # the stepper's panel title


def test_loop_stepper_buttons_redraw_the_live_3d_view(lab, browser_context, screenshot_dir):
    with reported_page(browser_context, lab, screenshot_dir) as page:
        _drive(page, lab, screenshot_dir)


def _drive(page, lab, shots: Path) -> None:
    open_and_run_all(page, lab, NOTEBOOK)

    stepper = StepperInLab(page, TITLE)
    stepper.wait_for_live_view("the Loop stepper")

    # The notebook's own cells left the stepper at the end; go back to step 0 first.
    before = None
    for button, expected in [("start", 0), ("step", 1), ("phase", 13)]:
        click_in_place(stepper.output.get_by_role("button", name=button, exact=True))
        wait_for(lambda: stepper.step_shown() == expected, 30, f"the panel to show step {expected}")
        png, after = stepper.settled_picture(before, f"the live view to redraw after '{button}'")
        (shots / f"loop-{expected}-{button}.png").write_bytes(png)
        if before is not None:
            share = changed_share(before, after)
            assert share >= MIN_CHANGED_SHARE, f"'{button}' changed only {share:.2%} of the view"
            print(f"{button}: step {expected}, {share:.2%} of the view changed")
        before = after
        time.sleep(0.5)
    print(f"screenshots in {shots}")
