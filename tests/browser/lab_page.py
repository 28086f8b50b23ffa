"""What the Lab browser tests share: a page that reports its failures, running a notebook,
waiting, clicking without racing JupyterLab's layout, and reading a widget's live 3D view.

The fixtures (``lab``, ``browser_context``, ``screenshot_dir``) live in conftest.py; this
module holds the helpers the tests call on the page those fixtures give them.
"""

from __future__ import annotations

import io
import re
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pytest

RUN_ALL_TIMEOUT = 240       # seconds, for every cell of a chapter (chapter 03's bunny included)
FRAME_TIMEOUT = 60          # seconds, for a live view to draw or redraw

# A drawn view: a grey mesh with coloured arrows on a plain background.
MIN_STD = 8.0               # grey-level standard deviation; a blank frame has ~0
MIN_COLOURS = 64            # distinct colours; a blank or one-colour frame has a handful
# A click redraws something somewhere else: the share of pixels that changed by more
# than CHANGED_LEVEL in some channel.
CHANGED_LEVEL = 40
MIN_CHANGED_SHARE = 0.002   # 0.2 % of the view (the arrows are thin)
STILL_FOR = 1.0             # seconds a control must stand still before it is clicked
STILL_FOR_IN_VIEW = 0.3     # seconds a control already in view must stand still before a click
CONSOLE_LINES = 40          # browser console lines printed with a failure


# -- pictures ------------------------------------------------------------------------

def as_array(png: bytes) -> np.ndarray:
    """A PNG screenshot as an (height, width, 3) int16 array (signed, so differences work)."""
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)


def drawn(picture: np.ndarray) -> tuple[float, int]:
    """(grey-level standard deviation, number of distinct colours)."""
    grey = picture.mean(axis=2)
    # Each colour packed into one integer (0xRRGGBB): the same count as np.unique over
    # rows of three, in a third of the time (0.13 s against 0.42 s on a 600 x 450
    # picture of random colours), which the many checks of a browser test add up.
    rgb = picture.astype(np.int32)
    colours = np.unique((rgb[..., 0] << 16) | (rgb[..., 1] << 8) | rgb[..., 2])
    return float(grey.std()), len(colours)


def changed_share(a: np.ndarray, b: np.ndarray) -> float:
    """The share of pixels that differ by more than CHANGED_LEVEL in some channel
    (1.0 when the pictures differ in size)."""
    if a.shape != b.shape:
        return 1.0
    return float((np.abs(a - b).max(axis=2) > CHANGED_LEVEL).mean())


# -- waiting and clicking ------------------------------------------------------------

def wait_for(condition: Callable[[], Any], timeout: float, what: str, interval: float = 0.5) -> Any:
    """Call ``condition()`` until it returns something truthy and return that; fail
    naming ``what`` after ``timeout`` seconds."""
    deadline = time.monotonic() + timeout
    while True:
        result = condition()
        if result:
            return result
        if time.monotonic() > deadline:
            pytest.fail(f"timed out after {timeout:.0f} s waiting for {what}")
        time.sleep(interval)


def hold_still(control, timeout: float = FRAME_TIMEOUT) -> None:
    """Scroll ``control`` (a Playwright locator) into view and wait until it has stood
    still for ``STILL_FOR`` seconds: after that, a mouse event sent to where it is lands
    on it. See :func:`click_in_place` for why the page moves after a scroll."""
    # A control already wholly in view needs no scroll, so no layout shift follows; it
    # must only not be moving (an output above it may still be growing) for a moment.
    # This keeps the many clicks on buttons in view about a second faster each.
    still_for = STILL_FOR_IN_VIEW if in_view(control.page, control) else STILL_FOR
    control.scroll_into_view_if_needed(timeout=timeout * 1000)
    last = {"box": None, "since": time.monotonic()}

    def standing_still() -> bool:
        box, now = control.bounding_box(), time.monotonic()
        if box != last["box"]:
            last.update(box=box, since=now)
        return box is not None and now - last["since"] >= still_for

    wait_for(standing_still, timeout, "the control to stop moving after the scroll", interval=0.25)


def in_view(page, control) -> bool:
    """Whether ``control`` lies wholly inside the page's viewport (so a click on it
    needs no scroll)."""
    box, viewport = control.bounding_box(), page.viewport_size
    return (box is not None and viewport is not None and box["x"] >= 0 and box["y"] >= 0
            and box["x"] + box["width"] <= viewport["width"] and box["y"] + box["height"] <= viewport["height"])


def click_in_place(control, timeout: float = FRAME_TIMEOUT) -> None:
    """Click ``control`` (a widget's button, say) once it is in view and has stopped moving.

    JupyterLab (4.x, windowing mode "contentVisibility", the default) lays out the cells
    out of view with an estimated height and measures them once they scroll into view,
    so the page shifts just after a scroll. Playwright's ``click`` scrolls a button into
    view and then sends the mouse to where the button was: after such a shift the mouse
    events land elsewhere (measured: none of them reached the notebook's document, the
    view's iframe took them), no click fires and the kernel never hears of it. That was
    issue 11's "first click of a fresh Lab session is lost": the first click is the one
    that scrolls. Scrolling first and waiting until the button stands still for
    ``STILL_FOR`` seconds (:func:`hold_still`) removes the race.
    """
    hold_still(control, timeout)
    control.click(timeout=timeout * 1000)


def drag_by_hand(page, x: float, y: float, dx: float, dy: float, steps: int = 8) -> None:
    """Press the left button at page point (x, y), move it by (dx, dy) and let go, at a
    hand's pace: a short rest after pressing, ``steps`` moves 60 ms apart, a rest before
    letting go (about 0.9 s in all, as a student's drag).

    Playwright's own ``mouse.move(..., steps=8)`` sends every event within a few
    milliseconds. A live view passes them to the kernel's VTK interactor over the
    websocket; under CI's load the release was once lost that way (the ball stayed
    selected where it was dragged to, and its callback never ran), which no hand can do.
    """
    page.mouse.move(x, y)
    time.sleep(0.2)
    page.mouse.down()
    time.sleep(0.2)
    for k in range(1, steps + 1):
        page.mouse.move(x + dx * k / steps, y + dy * k / steps)
        time.sleep(0.06)
    time.sleep(0.3)
    page.mouse.up()


def hover_in_place(control, timeout: float = FRAME_TIMEOUT) -> None:
    """Move the mouse pointer over ``control`` once it is in view and has stopped moving:
    a hover sends the pointer to where the control is, so it races the layout shift
    after a scroll just as :func:`click_in_place` describes."""
    hold_still(control, timeout)
    control.hover(timeout=timeout * 1000)


# -- the page and the notebook -------------------------------------------------------

@contextmanager
def reported_page(browser_context, lab, shots: Path, failure_shot: str = "failure-page.png") -> Iterator:
    """A new page of ``browser_context`` that records its browser console; if the block
    fails, save a screenshot of the page as ``shots / failure_shot`` and print the last
    console lines and the JupyterLab log's tail. The page is closed in any case."""
    page = browser_context.new_page()
    console: list[str] = []
    page.on("console", lambda message: console.append(f"{message.type}: {message.text}"))
    page.on("pageerror", lambda error: console.append(f"pageerror: {error}"))
    try:
        yield page
    except BaseException:
        try:
            page.screenshot(path=str(shots / failure_shot), full_page=False)
        except Exception:  # noqa: BLE001 - the original failure matters more
            pass
        print(f"screenshots so far, and {failure_shot}: {shots}")
        print("browser console:\n" + "\n".join(console[-CONSOLE_LINES:]))
        print("JupyterLab log:\n" + lab.log_tail())
        raise
    finally:
        page.close()


def open_and_run_all(page, lab, notebook: str) -> None:
    """Open ``notebook`` in the Lab, clear its stored outputs, run every cell, and
    fail if any cell raised (other than those tagged "raises-exception", which show an
    error on purpose). Clearing first means stored (static) outputs cannot pass for live
    ones."""
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


# -- a widget with a live view -------------------------------------------------------

class LiveViewInLab:
    """An output area of the open notebook holding a widget with a live 3D view.

    ``output`` is the output area (a Playwright locator), ``frame`` the trame view's
    iframe in it. Subclasses choose ``output`` and add what their panel's text says.
    """

    def __init__(self, output):
        self.output = output
        self.frame = output.locator("iframe").first

    def wait_for_live_view(self, name: str) -> None:
        """Scroll the output into view, wait for its view to show, and fail if the view
        is a static image rather than the live trame view."""
        self.output.scroll_into_view_if_needed(timeout=30_000)
        self.output.locator("iframe, img").first.wait_for(state="visible", timeout=FRAME_TIMEOUT * 1000)
        if self.frame.count() == 0:
            pytest.fail(f"{name} shows a static image, not the live trame view: the kernel chose "
                        "static mode (see halfedge_edu.viz.renderer.choose_mode)")

    def picture(self) -> tuple[bytes, np.ndarray]:
        """A screenshot of the live view: (PNG bytes, the picture as an array)."""
        png = self.frame.screenshot(animations="disabled", timeout=30_000)
        return png, as_array(png)

    def settled_picture(self, unlike: np.ndarray | None, what: str,
                        shows: Callable[[np.ndarray], bool] | None = None) -> tuple[bytes, np.ndarray]:
        """A drawn picture (that differs from ``unlike``, and of which ``shows`` is true,
        if given), once two frames in a row agree.

        ``shows`` says what the picture must show before a test reads it: a live view
        under load can stand still for a moment on a frame sent at low quality while the
        full one is on its way (seen once: a blurred, magnified still of part of the
        scene, which the drawn-picture test alone passes)."""
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
            if ok and stable and shows is not None:
                ok = shows(picture)
            return (png, picture) if ok and stable else None

        return wait_for(ready, FRAME_TIMEOUT, what, interval=1.0)


class StepperInLab(LiveViewInLab):
    """A stepper widget (Loop, flip, ...): the first output whose text has ``title``."""

    def __init__(self, page, title: str):
        super().__init__(page.locator(".jp-OutputArea-output").filter(has_text=title).first)

    def step_shown(self) -> int | None:
        """The step the panel's "step N of M" line shows."""
        match = re.search(r"step (\d+) of \d+", self.output.inner_text())
        return int(match.group(1)) if match else None


class ExplorerInLab(LiveViewInLab):
    """The first "Halfedge explorer" output of the open notebook; its screenshots go to
    ``shots``."""

    def __init__(self, page, shots: Path):
        super().__init__(page.locator(".jp-OutputArea-output").filter(has_text="Halfedge explorer").first)
        self.page = page
        self.shots = shots

    def current_halfedge(self) -> int | None:
        """The value in the pointer table's ``h`` row."""
        rows = self.output.locator("table tr").all_inner_texts()
        for row in rows:
            cells = row.split("\t")
            if len(cells) >= 2 and cells[0].strip() == "h":
                return int(cells[1].strip())
        return None

    def trail(self) -> str:
        """The panel's trail of moves (``h7 -next-> h8 ...``)."""
        match = re.search(r"trail:?\s*(.*)", self.output.inner_text())
        return match.group(1).strip() if match else ""

    def save(self, name: str, png: bytes) -> Path:
        """Write ``png`` as ``shots / name``."""
        path = self.shots / name
        path.write_bytes(png)
        return path
