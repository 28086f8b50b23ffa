"""Every widget of every chapter survives a student's clicks in a live JupyterLab (issue 11).

For each chapter with a widget: open it in the Lab as `make lab` starts it, run all
cells, then drive every widget from the state the notebook leaves it in, the way a
student does:

- buttons: clicked in a random order (fixed seed), each click checked (the panel and
  the picture settle; if the panel's text changed, the picture must have changed too),
  then a burst of rapid clicks without waiting, then checked again;
- dropdowns: every option and back; sliders: every value up and back down by keyboard;
- chapter 08's mesh dropdown 50 times and chapter 02's step slider 50 moves, after
  which the picture must still be a drawn picture (not blank, not stripes).

It fails on a kernel death (a restart or "dead" status of the notebook's kernel, or
the server log saying so), an error anywhere (a red status line in a widget, an error or
stderr output in a cell, a traceback or a shader error in the server log), a step whose
picture does not change when its table does, or a highlighted table row out of view.
Screenshots of each widget at a few states go to $HALFEDGE_EDU_SCREENSHOTS (or pytest's
temporary folder); the clicks made are printed per chapter.

Two depths, by ``HALFEDGE_EDU_BROWSER_DEPTH``: ``full`` (every slider through every
value and back, 6 checked random clicks and a burst of 12 per widget; about 14 minutes
on a loaded 2-core machine) and the default ``ci``, which keeps every button, every
dropdown option, chapter 08's 50 dropdown changes and chapter 02's 50 slider moves, but
takes other sliders through 8 key presses (4 up, 4 back) and fewer random clicks (each
button once and checked, one more at random, a burst of 6), so the whole
suite stays well inside CI's time. Run ``full`` before a release or after a widget change.
"""

from __future__ import annotations

import os
import random
import re
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest

from tests.browser.lab_page import (
    FRAME_TIMEOUT,
    as_array,
    changed_share,
    click_in_place,
    drawn,
    hold_still,
    in_view,
    open_and_run_all,
    reported_page,
)

pytestmark = pytest.mark.browser

SEED = 11
FULL = os.environ.get("HALFEDGE_EDU_BROWSER_DEPTH", "ci") == "full"
CHECKED_CLICKS = 6 if FULL else 1   # per widget with buttons: random extra clicks, each checked
RAPID_CLICKS = 12 if FULL else 6    # per widget with buttons: clicks in a burst, 80 ms apart
SLIDER_CAP = None if FULL else 8    # key presses per slider other than chapter 02's (None: every value)
DROPDOWN_CHANGES = 50       # chapter 08's mesh dropdown
SLIDER_MOVES = 50           # chapter 02's step slider (arrow keys, up and down)
SETTLE_TIMEOUT = 20.0       # seconds for a panel and its picture to settle after a click
BURST_TIMEOUT = 90.0        # seconds after a burst: the kernel works through every click in turn
QUIET = 0.6                 # seconds a no-op click is given to show a change
# A picture "changed" when this share of its pixels moved by more than
# lab_page.CHANGED_LEVEL in some channel.
# A step's picture must change in at least this share of its pixels. One QEM collapse of a
# short edge, seen in the whole-Spot view, changes 0.038 % of them (chapter 10, step 110
# -> 109, measured on the 600 x 450 picture); an unchanged picture changes none.
MIN_PICTURE_CHANGE = 0.0002
# Two frames closer than this are the same picture (the live view's own noise).
SAME_PICTURE = 0.00025
MIN_STD, MIN_COLOURS = 8.0, 48   # a drawn picture, not a blank one
KERNEL_DEATH = re.compile(r"KernelRestarter: restarting|Kernel restarted|kernel .* died|Segmentation fault",
                          re.IGNORECASE)
LOG_ERROR = re.compile(r"Traceback|Error setting '\w+' in shader|Exception in callback|Task exception")
ERROR_RED = "#B00020"       # the widgets' status line colour for an error (viz.widgets)
MARKED_ROW = "#FFF3D6"      # the background of a table's highlighted row (viz.widgets.table_html)

# Chapter notebook -> the least number of widgets it shows. Every chapter whose cells
# display a widget is listed.
CHAPTERS = {
    "00_setup_and_tour.ipynb": 1,
    "01_polygon_soup_and_obj.ipynb": 1,
    "02_building_halfedges.ipynb": 2,
    "03_navigating.ipynb": 1,
    "05_geometry_on_the_mesh.ipynb": 1,
    "06_flip_and_split.ipynb": 2,
    "07_edge_collapse.ipynb": 1,
    "08_link_condition.ipynb": 1,
    "09_loop_subdivision.ipynb": 1,
    "10_quadric_simplification.ipynb": 1,
    "11_isotropic_remeshing.ipynb": 1,
    "12_bezier.ipynb": 1,
    "13_putting_it_together.ipynb": 1,
}

# JavaScript run in the page.
WATCH_KERNEL = """() => {
    const panel = window.jupyterapp.shell.currentWidget;
    window.__kernelStates = [];
    panel.sessionContext.statusChanged.connect((_, status) => window.__kernelStates.push(status));
    panel.sessionContext.connectionStatusChanged.connect((_, status) => window.__kernelStates.push('connection-' + status));
}"""
# Errors in cell outputs (not in the cells tagged "raises-exception", which show one on
# purpose), tracebacks written to stderr, e.g. by a widget callback, and stray lines
# such as trame-vtklocal's "Using wasm_dir: ..." above a chapter's first live view.
CELL_PROBLEMS = """() => window.jupyterapp.shell.currentWidget.content.widgets
    .filter(c => c.model.type === 'code')
    .filter(c => !(c.model.getMetadata('tags') || []).includes('raises-exception'))
    .flatMap(c => c.model.outputs.toJSON())
    .filter(o => o.output_type === 'error'
                 || (o.output_type === 'stream' && o.name === 'stderr' && /Traceback|Error/.test(String(o.text)))
                 || (o.output_type === 'stream' && /Using wasm_dir/.test(String(o.text))))
    .map(o => o.output_type === 'error' ? o.ename + ': ' + o.evalue : o.name + ': ' + String(o.text).slice(0, 300))"""
SHUT_DOWN_KERNEL = "() => window.jupyterapp.shell.currentWidget.sessionContext.shutdown()"
# Marked rows of an output's tables that are not inside their scrolling box's view.
ROWS_OUT_OF_VIEW = """(output) => {
    const out = [];
    for (const cell of output.querySelectorAll('td[style*="%s"]')) {
        const row = cell.getBoundingClientRect();
        for (let box = cell.parentElement; box && box !== output; box = box.parentElement) {
            const style = getComputedStyle(box);
            if (!/(auto|scroll|hidden)/.test(style.overflowY) || box.scrollHeight <= box.clientHeight + 1) continue;
            const view = box.getBoundingClientRect();
            if (row.top < view.top - 1 || row.bottom > view.bottom + 1) out.push(cell.innerText.slice(0, 60));
            break;
        }
    }
    return [...new Set(out)];
}""" % MARKED_ROW


def is_drawn(picture: np.ndarray) -> bool:
    """Whether ``picture`` passes :meth:`WidgetInLab.check`'s picture rules: not blank,
    not stripes."""
    std, colours = drawn(picture)
    return std >= MIN_STD and colours >= MIN_COLOURS and not striped(picture)


def striped(picture: np.ndarray) -> bool:
    """Full-frame vertical stripes, the broken-context picture: every column nearly one
    colour from top to bottom, while the columns differ from each other."""
    grey = picture.mean(axis=2)
    # Even the most varied columns (an object's, in a drawn picture) are flat.
    return float(np.percentile(grey.std(axis=0), 90)) < 2.0 and float(grey.std()) > MIN_STD


@dataclass
class Record:
    """What was done to one chapter's widgets, for the report and the failure message."""

    chapter: str
    clicks: dict[str, int] = field(default_factory=dict)

    def count(self, what: str, n: int = 1) -> None:
        self.clicks[what] = self.clicks.get(what, 0) + n

    def line(self) -> str:
        return f"{self.chapter}: " + ", ".join(f"{what} x{n}" for what, n in sorted(self.clicks.items()))


class WidgetInLab:
    """One output area holding a widget: its controls, its text and its pictures."""

    def __init__(self, page, output, name: str, shots: Path):
        self.page, self.output, self.name, self.shots = page, output, name, shots

    # -- reading ---------------------------------------------------------------------

    def text(self) -> str:
        return self.output.inner_text(timeout=30_000)

    def tables(self) -> list[str]:
        """The text of the widget's tables (pointer values, changes, queue, quality)."""
        return self.output.locator("table").all_inner_texts()

    def views(self) -> list:
        """The pictures: live views (trame iframes) and static images, largest first."""
        found = self.output.locator("iframe, img").all()
        sizes = [(box["width"] * box["height"] if (box := v.bounding_box()) else 0.0) for v in found]
        return [v for size, v in sorted(zip(sizes, found), key=lambda p: -p[0]) if size >= 100 * 80]

    def pictures(self) -> list[np.ndarray]:
        return [as_array(v.screenshot(animations="disabled", timeout=30_000)) for v in self.views()]

    def state(self) -> tuple[str, list[str], list[np.ndarray]]:
        """The widget's whole text, its tables' text and its pictures."""
        return self.text(), self.tables(), self.pictures()

    def save(self, label: str) -> None:
        self.output.scroll_into_view_if_needed(timeout=30_000)
        self.output.screenshot(path=str(self.shots / f"{self.name}-{label}.png"), timeout=30_000)

    # -- checking --------------------------------------------------------------------

    def check(self, what: str, settled: tuple | None = None) -> None:
        """No red status line, every picture drawn (not blank, not stripes), the marked
        table rows in view. ``settled``: the :meth:`state` that :meth:`settle` just
        returned, whose pictures are the settled ones (they were taken after the text
        and equal the frame before them), so they need not be taken again: a picture
        costs a screenshot of each view, the most expensive read of a check."""
        html = self.output.inner_html(timeout=30_000)
        if ERROR_RED in html:
            red = self.output.locator(f'[style*="{ERROR_RED}"]').all_inner_texts()
            pytest.fail(f"{self.name}, {what}: the widget shows an error: {red}")
        pictures = self.pictures() if settled is None else settled[2]
        for k, picture in enumerate(pictures):
            std, colours = drawn(picture)
            assert std >= MIN_STD and colours >= MIN_COLOURS, (
                f"{self.name}, {what}: picture {k} is blank (std {std:.1f}, {colours} colours)")
            assert not striped(picture), f"{self.name}, {what}: picture {k} is vertical stripes"
        hidden = self.output.evaluate(ROWS_OUT_OF_VIEW)
        assert not hidden, f"{self.name}, {what}: highlighted table rows out of view: {hidden}"

    def settle(self, before, what: str, timeout: float = SETTLE_TIMEOUT):
        """Wait until the text and the pictures stop changing; if a table changed since
        ``before`` (a :meth:`state`), the pictures must change too: a step whose picture
        does not follow its table fails. With ``before`` None, wait for them to stop
        changing and for every picture to be drawn (a live view's first frame)."""
        text0, tables0, pictures0 = before if before is not None else self.state()
        deadline = time.monotonic() + timeout
        started = time.monotonic()
        previous = None
        while True:
            now = self.state()
            text, tables, pictures = now
            table_moved = tables != tables0
            picture_moved = len(pictures) != len(pictures0) or any(
                changed_share(a, b) >= MIN_PICTURE_CHANGE for a, b in zip(pictures0, pictures))
            stable = previous is not None and previous[0] == text and all(
                changed_share(a, b) < SAME_PICTURE for a, b in zip(previous[2], pictures))
            quiet = time.monotonic() - started > QUIET
            if stable and (before is None or picture_moved or (not table_moved and quiet)):
                # A live view draws its first frame a while after it appears, and a blank
                # frame can stand still for a moment: as left by the notebook, wait for
                # drawn pictures too (past the deadline, hand back what there is, and
                # :meth:`check` says it is blank).
                if before is not None or all(is_drawn(p) for p in pictures) or time.monotonic() > deadline:
                    return now
            if time.monotonic() > deadline:
                if table_moved and not picture_moved:
                    pytest.fail(f"{self.name}, {what}: the table changed but the picture did not "
                                f"within {timeout:.0f} s")
                pytest.fail(f"{self.name}, {what}: the widget did not settle within {timeout:.0f} s")
            previous = now
            time.sleep(0.25)

    # -- driving ---------------------------------------------------------------------

    def buttons(self) -> list:
        return [b for b in self.output.locator("button.jupyter-button").all() if b.is_enabled()]

    def drive_buttons(self, rng: random.Random, record: Record) -> None:
        """Checked clicks in random order, then a rapid burst, then a last check.

        A checked click is made with :func:`click_in_place` (scrolled into view, then
        clicked once the button stands still): a click lost to JupyterLab's layout shift
        after a scroll would change nothing, and :meth:`settle` takes a click that
        changes nothing for a quiet no-op, so it would pass unnoticed. The burst clicks
        at once, holding a button still first only if it is out of view.
        """
        buttons = self.buttons()
        labels = [b.inner_text().strip() or b.get_attribute("title") or "?" for b in buttons]
        order = list(range(len(buttons))) + [rng.randrange(len(buttons)) for _ in range(CHECKED_CLICKS)]
        rng.shuffle(order)
        state = self.state()
        for k in order:
            click_in_place(buttons[k], timeout=30)
            record.count(f"{self.name} '{labels[k]}'")
            state = self.settle(state, f"after '{labels[k]}'")
            self.check(f"after '{labels[k]}'", state)
        self.save("checked")
        for _ in range(RAPID_CLICKS):
            k = rng.randrange(len(buttons))
            if not in_view(self.page, buttons[k]):
                hold_still(buttons[k], timeout=30)
            buttons[k].click(timeout=30_000)
            record.count(f"{self.name} '{labels[k]}' (rapid)")
            time.sleep(0.08)
        state = self.settle(state, "after a burst of clicks", timeout=BURST_TIMEOUT)
        self.check("after a burst of clicks", state)
        self.save("burst")

    def drive_dropdowns(self, record: Record, changes: int | None = None) -> None:
        """Every option and back (or ``changes`` changes, cycling through the options)."""
        for select in self.output.locator(".widget-dropdown select").all():
            options = select.locator("option").all_text_contents()
            first = select.input_value()
            sequence = options[1:] + options[::-1] if changes is None else [
                options[(k + 1) % len(options)] for k in range(changes)]
            state = self.state()
            for k, option in enumerate(sequence):
                select.select_option(label=option, timeout=30_000)
                record.count(f"{self.name} dropdown")
                if changes is None or k % 10 == 9:
                    state = self.settle(state, f"after choosing {option!r}")
                    self.check(f"after choosing {option!r}", state)
                else:
                    time.sleep(0.3)
            select.select_option(value=first, timeout=30_000)
            state = self.settle(state, "after the dropdown's first option again")
            self.check("after the dropdown's first option again", state)

    def drive_sliders(self, record: Record, moves: int | None = None) -> None:
        """Each slider by keyboard through all its values up and back down (or ``moves``
        key presses, up and down), checking every few moves."""
        for handle in self.output.locator(".widget-slider .noUi-handle").all():
            low = int(float(handle.get_attribute("aria-valuemin")))
            high = int(float(handle.get_attribute("aria-valuemax")))
            value = int(float(handle.get_attribute("aria-valuenow")))
            span = high - low
            if span <= 0:
                continue
            count = 2 * span if moves is None else moves
            keys = []
            if count < 2 * span:
                # Too few presses for every value: half of them up, then as many back down.
                up = "ArrowRight" if value < high else "ArrowLeft"
                down = "ArrowLeft" if up == "ArrowRight" else "ArrowRight"
                keys = [up] * (count // 2) + [down] * (count - count // 2)
                count = 0
            for _ in range(count):
                # Up to the top, then down to the bottom, then up again: every value, both ways.
                key = "ArrowRight" if (not keys or keys[-1] == "ArrowRight") and value < high else (
                    "ArrowLeft" if value > low else "ArrowRight")
                value += 1 if key == "ArrowRight" else -1
                keys.append(key)
            handle.focus()
            state = self.state()
            for k, key in enumerate(keys):
                handle.press(key)
                record.count(f"{self.name} slider")
                if k % 10 == 9 or k == len(keys) - 1:
                    state = self.settle(state, f"after {k + 1} slider moves")
                    self.check(f"after {k + 1} slider moves", state)
                else:
                    time.sleep(0.15)

    def drive_text(self, record: Record) -> None:
        """A text box (chapter 01's OBJ file): break it, then put it back."""
        for box in self.output.locator(".widget-textarea textarea:not([disabled])").all():
            good = box.input_value()
            state = self.state()
            box.fill(good.replace("v 0 1 0", "v 0 one 0"))
            box.blur()
            record.count(f"{self.name} text edit")
            broken = self.settle(state, "after breaking the file")
            assert "Not a mesh" in broken[0], f"{self.name}: a broken file is not reported"
            self.save("broken-file")
            box.fill(good)
            box.blur()
            record.count(f"{self.name} text edit")
            mended = self.settle(broken, "after mending the file")
            self.check("after mending the file", mended)


def kernel_problems(page, lab, log_start: int) -> list[str]:
    states = page.evaluate("() => window.__kernelStates || []")
    found = [f"kernel status {s}" for s in states if s in ("restarting", "autorestarting", "dead", "terminating")]
    log = lab.log.read_text(errors="replace")[log_start:]
    found += [f"server log: {line.strip()}" for line in log.splitlines()
              if KERNEL_DEATH.search(line) or LOG_ERROR.search(line)]
    return found


#: Chapter 13's MeshEditor (recognised by its keys box) is driven by its own browser test,
#: tests/browser/test_editor.py, which picks, flips by button and key, drags and undoes:
#: its float position sliders follow the selection and are not a "through every value" slider.
EDITOR_KEYS_BOX = 'input[placeholder="click, type f s c l u"]'


#: JavaScript: number the output areas that hold a control someone can operate (the
#: editor aside, see above) with a ``data-widget-under-test`` attribute, and count them.
MARK_WIDGET_OUTPUTS = """([controls, editorKeys]) => {
    const found = [...document.querySelectorAll('.jp-OutputArea-output')]
        .filter(o => o.querySelector(controls) && !o.querySelector(editorKeys));
    found.forEach((o, k) => o.setAttribute('data-widget-under-test', String(k)));
    return found.length;
}"""


def widget_outputs(page) -> list:
    """The output areas that hold a widget someone can operate (the editor aside, see above).

    Each is found again by an attribute set on it now, not by its place among the page's
    output areas (Playwright's ``.all()`` hands out ``nth(k)`` locators): an output area
    added above a widget while it is driven (a late-rendered output, a message) would
    otherwise turn the widget's locator into its neighbour's."""
    controls = ("button.jupyter-button, .widget-dropdown select, .widget-slider .noUi-handle, "
                ".widget-textarea textarea:not([disabled])")
    count = page.evaluate(MARK_WIDGET_OUTPUTS, [controls, EDITOR_KEYS_BOX])
    return [page.locator(f'[data-widget-under-test="{k}"]') for k in range(count)]


#: The chapters this module drives; test_lab_widgets_later.py drives the rest, so that
#: with pytest-xdist's --dist loadfile each half goes to a worker of its own (about 8
#: minutes each on 2 cores, against 16 in one module).
SPLIT_AT = "08"


@pytest.mark.parametrize("notebook", [notebook for notebook in sorted(CHAPTERS) if notebook < SPLIT_AT])
def test_every_widget_survives_a_students_clicks(notebook, lab, browser_context, screenshot_dir):
    drive_every_widget(notebook, lab, browser_context, screenshot_dir)


def drive_every_widget(notebook: str, lab, browser_context, screenshot_dir) -> None:
    """Run ``notebook`` in the Lab, then drive each of its widgets as a student would
    (dropdowns, sliders, text, buttons at random and in bursts), checking each picture
    and the kernel after every widget."""
    record = Record(notebook[:2])
    log_start = len(lab.log.read_text(errors="replace"))
    shots = screenshot_dir / notebook[:2]
    shots.mkdir(exist_ok=True)
    started = time.monotonic()
    with reported_page(browser_context, lab, shots) as page:
        page.set_default_timeout(60_000)
        try:
            open_and_run_all(page, lab, notebook)
            page.evaluate(WATCH_KERNEL)
            ran = time.monotonic() - started
            assert not (problems := page.evaluate(CELL_PROBLEMS)), f"cells wrote errors: {problems}"
            outputs = widget_outputs(page)
            assert len(outputs) >= CHAPTERS[notebook], (
                f"{notebook}: {len(outputs)} widgets found, expected at least {CHAPTERS[notebook]}")
            rng = random.Random(f"{SEED}-{notebook}")
            for k, output in enumerate(outputs):
                widget = WidgetInLab(page, output, f"w{k}", shots)
                output.scroll_into_view_if_needed(timeout=30_000)
                widget.check("as the notebook left it",
                             widget.settle(None, "as the notebook left it", timeout=FRAME_TIMEOUT))
                widget.save("0-as-left")
                if notebook.startswith("08"):
                    widget.drive_dropdowns(record, changes=DROPDOWN_CHANGES)
                else:
                    widget.drive_dropdowns(record)
                is_step_slider = notebook.startswith("02") and "step" in widget.text().lower() and \
                    output.locator(".widget-slider").count() and not output.locator("button.jupyter-button").count()
                widget.drive_sliders(record, moves=SLIDER_MOVES if is_step_slider else SLIDER_CAP)
                widget.drive_text(record)
                if widget.buttons():
                    widget.drive_buttons(rng, record)
                widget.save("9-end")
                assert not (problems := kernel_problems(page, lab, log_start)), f"after {widget.name}: {problems}"
            assert not (problems := page.evaluate(CELL_PROBLEMS)), f"cells wrote errors while driven: {problems}"
            print(f"{record.line()}\n  widgets: {len(outputs)}; run all {ran:.0f} s, "
                  f"driving {time.monotonic() - started - ran:.0f} s; screenshots in {shots}")
        except BaseException:
            print(f"clicks so far: {record.line()}")
            raise
        finally:
            try:
                page.evaluate(SHUT_DOWN_KERNEL)  # the next chapter gets the machine's cores
            except Exception:  # noqa: BLE001 - closing the page ends the session anyway
                pass
