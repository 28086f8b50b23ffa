"""Chapter 03 in a real JupyterLab: run all cells, click next and twin in the explorer,
and check from screenshots that the live 3D view drew the mesh and followed each click.

What a newcomer does after `make lab`. The expected halfedges come from the library
itself (``h.next``, ``h.twin``), the pictures from the trame view's own iframe.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest

import halfedge_edu as hx
from tests.browser.lab_page import (
    MIN_CHANGED_SHARE,
    MIN_COLOURS,
    MIN_STD,
    ExplorerInLab,
    changed_share,
    click_in_place,
    drawn,
    open_and_run_all,
    reported_page,
    wait_for,
)

pytestmark = pytest.mark.browser

NOTEBOOK = "03_navigating.ipynb"


def test_explorer_next_and_twin_move_the_arrow_in_the_live_3d_view(lab, browser_context, screenshot_dir):
    with reported_page(browser_context, lab, screenshot_dir) as page:
        _drive_chapter03(page, lab, screenshot_dir)


def _drive_chapter03(page, lab, shots: Path) -> None:
    open_and_run_all(page, lab, NOTEBOOK)

    explorer = ExplorerInLab(page, shots)
    # Live, not static: the view is trame's iframe, not the static mode's <img>.
    explorer.wait_for_live_view("the explorer")

    patch = hx.sample("open_patch")
    wait_for(lambda: explorer.current_halfedge() is not None, 30, "the explorer's pointer table")
    start = explorer.current_halfedge()
    png, before = explorer.settled_picture(None, "the live view's first frame")
    std, colours = drawn(before)
    assert std >= MIN_STD and colours >= MIN_COLOURS, f"blank view: std {std:.1f}, {colours} colours"
    explorer.save("0-start.png", png)

    # Noise floor: the same state, a moment later, must look the same.
    time.sleep(1.0)
    _, again = explorer.picture()
    noise = changed_share(before, again)
    assert noise < MIN_CHANGED_SHARE / 4, f"the view changes by itself ({noise:.2%} of pixels)"

    # The first click of the session must take effect (issue 11): "next" is the first
    # thing done to the explorer after "run all", with no warm-up click before it.
    expected = start
    for step, move in enumerate(["next", "twin"], start=1):
        expected = getattr(patch.halfedge(expected), move).index
        trail_before = explorer.trail()
        click_in_place(explorer.output.get_by_role("button", name=move, exact=True))
        wait_for(lambda: explorer.current_halfedge() == expected, 30,
                 f"the pointer table to show h = {expected} after '{move}'")
        assert explorer.trail() != trail_before and explorer.trail().endswith(f"-{move}-> h{expected}")
        png, after = explorer.settled_picture(before, f"the live view to redraw after '{move}'")
        share = changed_share(before, after)
        std, colours = drawn(after)
        assert std >= MIN_STD and colours >= MIN_COLOURS, f"blank view after {move}"
        assert share >= MIN_CHANGED_SHARE, f"'{move}' changed only {share:.2%} of the view"
        explorer.save(f"{step}-{move}.png", png)
        print(f"{move}: h {expected}, {share:.2%} of the view changed, std {std:.1f}, {colours} colours")
        before = after
    explorer.save("3-explorer-with-panel.png", explorer.output.screenshot(timeout=30_000))
    explorer.save("4-lab-page.png", page.screenshot())
    print(f"screenshots in {shots}")
