"""Chapter 09 in a real JupyterLab: the Loop stepper's live 3D view follows its buttons.

The Loop stepper (like the QEM stepper and the Bezier surface editor) draws with a
``PaintedScene``, which replaces whole actors at each step instead of editing arrays in
place as the halfedge scene does. This test checks that the live trame view picks those
new actors up: run all cells, press **start** and **step**, and compare the frames.
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest

from tests.browser.test_lab_chapter03 import (
    FRAME_TIMEOUT,
    MIN_CHANGED_SHARE,
    MIN_COLOURS,
    MIN_STD,
    as_array,
    changed_share,
    drawn,
    open_and_run_all,
    wait_for,
)

pytestmark = pytest.mark.browser

NOTEBOOK = "09_loop_subdivision.ipynb"


class StepperInLab:
    """The first "Loop subdivision: step by step" output of the open notebook."""

    def __init__(self, page):
        self.output = page.locator(".jp-OutputArea-output").filter(has_text="Loop subdivision: step by step").first
        self.frame = self.output.locator("iframe").first

    def step_shown(self) -> int | None:
        match = re.search(r"step (\d+) of \d+", self.output.inner_text())
        return int(match.group(1)) if match else None

    def picture(self):
        png = self.frame.screenshot(animations="disabled", timeout=30_000)
        return png, as_array(png)

    def settled_picture(self, unlike, what: str):
        previous = None

        def ready():
            nonlocal previous
            png, picture = self.picture()
            std, colours = drawn(picture)
            ok = std >= MIN_STD and colours >= MIN_COLOURS
            if unlike is not None:
                ok = ok and changed_share(unlike, picture) >= MIN_CHANGED_SHARE
            stable = previous is not None and changed_share(previous, picture) < MIN_CHANGED_SHARE / 4
            previous = picture
            return (png, picture) if ok and stable else None

        return wait_for(ready, FRAME_TIMEOUT, what, interval=1.0)


def test_loop_stepper_buttons_redraw_the_live_3d_view(lab, browser_context, screenshot_dir):
    page = browser_context.new_page()
    console = []
    page.on("console", lambda message: console.append(f"{message.type}: {message.text}"))
    page.on("pageerror", lambda error: console.append(f"pageerror: {error}"))
    try:
        _drive(page, lab, screenshot_dir)
    except BaseException:
        try:
            page.screenshot(path=str(screenshot_dir / "failure-page.png"), full_page=False)
        except Exception:  # noqa: BLE001 - the original failure matters more
            pass
        print(f"screenshots so far, and failure-page.png: {screenshot_dir}")
        print("browser console:\n" + "\n".join(console[-40:]))
        print("JupyterLab log:\n" + lab.log_tail())
        raise
    finally:
        page.close()


def _drive(page, lab, shots: Path) -> None:
    open_and_run_all(page, lab, NOTEBOOK)

    stepper = StepperInLab(page)
    stepper.output.scroll_into_view_if_needed(timeout=30_000)
    stepper.output.locator("iframe, img").first.wait_for(state="visible", timeout=FRAME_TIMEOUT * 1000)
    if stepper.frame.count() == 0:
        pytest.fail("the Loop stepper shows a static image, not the live trame view")

    # The notebook's own cells left the stepper at the end; go back to step 0 first.
    before = None
    for button, expected in [("start", 0), ("step", 1), ("phase", 13)]:
        stepper.output.get_by_role("button", name=button, exact=True).click()
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
