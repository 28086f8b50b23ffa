"""Widgets fit a laptop screen with JupyterLab's file browser open (issue 30).

At 1366 x 768 with the file browser open (JupyterLab's default) chapter 07's collapse
atlas was cut off on the right: its row of two views and a legend was wider than the
notebook. This test runs chapter 07 in the shared ``lab`` fixture at that size and
measures every part of the atlas (views, still pictures, texts, buttons): none reaches
past the notebook's visible width, none is squeezed so that its content spills out of
its box, and no two cover each other. Screenshots go to ``$HALFEDGE_EDU_SCREENSHOTS`` (or pytest's
temporary folder).
"""

from __future__ import annotations

import time

import pytest

from tests.browser.lab_page import hold_still, open_and_run_all, reported_page

pytestmark = pytest.mark.browser

LAPTOP = {"width": 1366, "height": 768}   # a common laptop screen
CHAPTER = "07_edge_collapse.ipynb"
ATLAS_TITLE = "Edge collapse: the cases side by side"   # CollapseAtlas.title
# What the test finds wrong with a widget's output area, run in the page: a part that
# reaches past the notebook's visible right edge (its scrolling panel, less a scroll
# bar), a box whose content is wider than the box (a row squeezed until its texts run
# into each other or are clipped), and two pictures or texts that cover each other.
PROBLEMS = """output => {
    const outer = window.jupyterapp.shell.currentWidget.content.node.querySelector('.jp-WindowedPanel-outer')
        || window.jupyterapp.shell.currentWidget.content.node;
    const right = Math.min(outer.getBoundingClientRect().left + outer.clientWidth, window.innerWidth);
    const shown = el => el.getClientRects().length > 0 && getComputedStyle(el).visibility !== 'hidden';
    const name = el => el.tagName === 'IFRAME' ? 'a view' : el.tagName === 'IMG' ? 'a picture'
        : JSON.stringify((el.innerText || '').trim().slice(0, 40));
    const problems = [];
    const parts = [...output.querySelectorAll('iframe, img, .widget-html-content, button')].filter(shown);
    for (const part of parts) {
        const box = part.getBoundingClientRect();
        if (box.right > right + 0.5) {
            problems.push(`${name(part)} ends at x = ${Math.round(box.right)}, past the notebook's ${Math.round(right)}`);
        }
    }
    for (const box of [...output.querySelectorAll('.widget-box, .widget-html')].filter(shown)) {
        if (box.scrollWidth > box.clientWidth + 1) {
            problems.push(`${name(box)} holds ${box.scrollWidth} px in ${box.clientWidth} px`);
        }
    }
    const leaves = parts.filter(part => !parts.some(other => other !== part && part.contains(other)));
    leaves.forEach((part, i) => leaves.slice(i + 1).forEach(other => {
        const a = part.getBoundingClientRect(), b = other.getBoundingClientRect();
        const width = Math.min(a.right, b.right) - Math.max(a.left, b.left);
        const height = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top);
        if (width > 1 && height > 1) problems.push(`${name(part)} and ${name(other)} overlap`);
    }));
    return {problems, parts: parts.length};
}"""


def test_on_a_laptop_screen_with_the_file_browser_open_chapter_07s_atlas_is_not_cut_off(
        lab, browser_context, screenshot_dir):
    with reported_page(browser_context, lab, screenshot_dir, "fit-atlas-failure-page.png") as page:
        clock = time.monotonic()
        page.set_viewport_size(LAPTOP)
        open_and_run_all(page, lab, CHAPTER)
        assert page.locator(".jp-FileBrowser").first.is_visible(), "the file browser is closed"
        atlas = page.locator(".jp-OutputArea-output").filter(has_text=ATLAS_TITLE).first
        views, stills = atlas.locator("iframe"), atlas.locator("img")
        views.first.wait_for(state="visible", timeout=60_000)
        for part, shot in ((views.first, "laptop-atlas-cases.png"), (stills.first, "laptop-atlas-refused.png")):
            part.evaluate("part => part.scrollIntoView({block: 'center'})")
            hold_still(part)
            (screenshot_dir / shot).write_bytes(page.screenshot())
        found = atlas.evaluate(PROBLEMS)
        assert (views.count(), stills.count()) == (2, 3), "the atlas shows two live cases and three refusals"
        assert found["parts"] > 10, f"only {found['parts']} parts of the atlas are visible"
        assert found["problems"] == [], f"the atlas does not fit at {LAPTOP}: {found['problems']}"
        print(f"laptop atlas test: {time.monotonic() - clock:.0f} s")
