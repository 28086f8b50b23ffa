"""Chapter 03 in a real JupyterLab: run all cells, click next and twin in the explorer,
and check from screenshots that the live 3D view drew the mesh and followed each click.

What a newcomer does after `make lab`. The expected halfedges come from the library
itself (``h.next``, ``h.twin``), the pictures from the trame view's own iframe.
"""

from __future__ import annotations

import io
import re
import time
from pathlib import Path

import numpy as np
import pytest

import halfedge_edu as hx

pytestmark = pytest.mark.browser

NOTEBOOK = "03_navigating.ipynb"
RUN_ALL_TIMEOUT = 240       # seconds, for every cell of the chapter (the bunny included)
FRAME_TIMEOUT = 60          # seconds, for the live view to draw or redraw

# A drawn view: a grey mesh with coloured arrows on a plain background.
MIN_STD = 8.0               # grey-level standard deviation; a blank frame has ~0
MIN_COLOURS = 64            # distinct colours; a blank or one-colour frame has a handful
# A click redraws the current halfedge somewhere else: the share of pixels that
# changed by more than CHANGED_LEVEL in some channel.
CHANGED_LEVEL = 40
MIN_CHANGED_SHARE = 0.002   # 0.2 % of the view (the arrows are thin)
STILL_FOR = 1.0             # seconds a button must stand still before it is clicked


def as_array(png: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)


def drawn(picture: np.ndarray) -> tuple[float, int]:
    """(grey-level standard deviation, number of distinct colours)."""
    grey = picture.mean(axis=2)
    colours = np.unique(picture.reshape(-1, 3), axis=0)
    return float(grey.std()), len(colours)


def changed_share(a: np.ndarray, b: np.ndarray) -> float:
    if a.shape != b.shape:
        return 1.0
    return float((np.abs(a - b).max(axis=2) > CHANGED_LEVEL).mean())


def click_in_place(button, timeout: float = FRAME_TIMEOUT) -> None:
    """Click ``button`` once it is in view and has stopped moving.

    JupyterLab (4.x, windowing mode "contentVisibility", the default) lays out the cells
    out of view with an estimated height and measures them once they scroll into view,
    so the page shifts just after a scroll. Playwright's ``click`` scrolls a button into
    view and then sends the mouse to where the button was: after such a shift the mouse
    events land elsewhere (measured: none of them reached the notebook's document, the
    view's iframe took them), no click fires and the kernel never hears of it. That was
    issue 11's "first click of a fresh Lab session is lost": the first click is the one
    that scrolls. Scrolling first and waiting until the button stands still for
    ``STILL_FOR`` seconds removes the race.
    """
    button.scroll_into_view_if_needed(timeout=timeout * 1000)
    last = {"box": None, "since": time.monotonic()}

    def standing_still() -> bool:
        box, now = button.bounding_box(), time.monotonic()
        if box != last["box"]:
            last.update(box=box, since=now)
        return box is not None and now - last["since"] >= STILL_FOR

    wait_for(standing_still, timeout, "the button to stop moving after the scroll", interval=0.25)
    button.click(timeout=timeout * 1000)


def wait_for(condition, timeout: float, what: str, interval: float = 0.5):
    """Call ``condition()`` until it returns something truthy; fail with ``what``."""
    deadline = time.monotonic() + timeout
    while True:
        result = condition()
        if result:
            return result
        if time.monotonic() > deadline:
            pytest.fail(f"timed out after {timeout:.0f} s waiting for {what}")
        time.sleep(interval)


class ExplorerInLab:
    """The first "Halfedge explorer" output of the open notebook."""

    def __init__(self, page, shots: Path):
        self.page = page
        self.shots = shots
        self.output = page.locator(".jp-OutputArea-output").filter(has_text="Halfedge explorer").first
        self.frame = self.output.locator("iframe").first

    def current_halfedge(self) -> int | None:
        """The value in the pointer table's ``h`` row."""
        rows = self.output.locator("table tr").all_inner_texts()
        for row in rows:
            cells = row.split("\t")
            if len(cells) >= 2 and cells[0].strip() == "h":
                return int(cells[1].strip())
        return None

    def trail(self) -> str:
        match = re.search(r"trail:?\s*(.*)", self.output.inner_text())
        return match.group(1).strip() if match else ""

    def picture(self) -> tuple[bytes, np.ndarray]:
        png = self.frame.screenshot(animations="disabled", timeout=30_000)
        return png, as_array(png)

    def settled_picture(self, unlike: np.ndarray | None, what: str) -> tuple[bytes, np.ndarray]:
        """A drawn picture (that differs from ``unlike``), once two frames in a row agree."""
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

    def save(self, name: str, png: bytes) -> Path:
        path = self.shots / name
        path.write_bytes(png)
        return path


def test_explorer_next_and_twin_move_the_arrow_in_the_live_3d_view(lab, browser_context, screenshot_dir):
    page = browser_context.new_page()
    console = []
    page.on("console", lambda message: console.append(f"{message.type}: {message.text}"))
    page.on("pageerror", lambda error: console.append(f"pageerror: {error}"))
    try:
        _drive_chapter03(page, lab, screenshot_dir, console)
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


def open_and_run_all(page, lab, notebook: str) -> None:
    """Open ``notebook`` in the Lab, clear its stored outputs, run every cell, and
    fail if any cell raised (other than those tagged "raises-exception", which show an error on purpose). Clearing first means stored (static) outputs cannot pass
    for live ones."""
    page.goto(lab.open_url(notebook), timeout=120_000)
    # The notebook is open and its kernel is up.
    page.wait_for_function(
        """() => {
            const app = window.jupyterapp;
            const panel = app && app.shell.currentWidget;
            const kernel = panel && panel.sessionContext && panel.sessionContext.session
                && panel.sessionContext.session.kernel;
            return kernel && kernel.status === 'idle' && panel.context.isReady;
        }""",
        polling=500, timeout=120_000,
    )
    page.evaluate("() => window.jupyterapp.commands.execute('notebook:clear-all-cell-outputs')")
    page.evaluate("() => { window.jupyterapp.commands.execute('notebook:run-all-cells'); }")
    page.wait_for_function(
        """() => {
            const panel = window.jupyterapp.shell.currentWidget;
            const kernel = panel.sessionContext.session.kernel;
            const cells = panel.content.widgets.filter(c => c.model.type === 'code');
            return kernel.status === 'idle' && cells.every(c => c.model.executionCount !== null);
        }""",
        polling=500, timeout=RUN_ALL_TIMEOUT * 1000,
    )
    errors = page.evaluate(
        """() => window.jupyterapp.shell.currentWidget.content.widgets
            .filter(c => c.model.type === 'code')
            .filter(c => !(c.model.getMetadata('tags') || []).includes('raises-exception'))
            .flatMap(c => c.model.outputs.toJSON())
            .filter(o => o.output_type === 'error')
            .map(o => o.ename + ': ' + o.evalue)"""
    )
    assert not errors, f"cells raised: {errors}"


def _drive_chapter03(page, lab, shots: Path, console: list[str]) -> None:
    open_and_run_all(page, lab, NOTEBOOK)

    explorer = ExplorerInLab(page, shots)
    explorer.output.scroll_into_view_if_needed(timeout=30_000)
    # Live, not static: the view is trame's iframe, not the static mode's <img>.
    explorer.output.locator("iframe, img").first.wait_for(state="visible", timeout=FRAME_TIMEOUT * 1000)
    if explorer.frame.count() == 0:
        pytest.fail("the explorer shows a static image, not the live trame view: the kernel chose "
                    "static mode (see halfedge_edu.viz.renderer.choose_mode)")

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
