"""The mesh editor in a real JupyterLab: select an edge, flip it by button and by key,
and see the live 3D view redraw and the pointer diff appear; pick a face and a vertex by
right-clicking the view, and drag the vertex; six keys typed fast are six edits (l
smooths, z undoes).

The Lab is the shared ``lab`` fixture; this test writes its own small notebook into the
Lab's folder (a cube and an editor), so it does not wait for a whole chapter to run.
Screenshots go to ``$HALFEDGE_EDU_SCREENSHOTS`` (or pytest's temporary folder).
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import nbformat
import numpy as np
import pytest

import halfedge_edu as hx
from tests.browser.lab_page import (
    MIN_CHANGED_SHARE,
    MIN_COLOURS,
    MIN_STD,
    LiveViewInLab,
    changed_share,
    click_in_place,
    drag_by_hand,
    drawn,
    open_and_run_all,
    reported_page,
    wait_for,
)

pytestmark = pytest.mark.browser

NOTEBOOK = "mesh_editor.ipynb"
EDGE = 4           # an edge of the cube that can be flipped (edge 0 cannot: see can_flip(0))
FAST_KEYS = 6      # keys typed in a row ...
FAST_KEY_DELAY_MS = 15   # ... this far apart: faster than a kernel answers one
INFO_LINE = f"edge {EDGE}: halfedges {2 * EDGE} and {2 * EDGE + 1}"   # what the key i says


def write_notebook(folder: Path) -> None:
    notebook = nbformat.v4.new_notebook()
    notebook.cells = [
        nbformat.v4.new_code_cell("import halfedge_edu as hx\nfrom halfedge_edu.viz.editor import MeshEditor"),
        nbformat.v4.new_code_cell('editor = MeshEditor(hx.sample("cube"), select=("vertex", 0))\neditor'),
    ]
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(notebook, folder / NOTEBOOK)


class EditorInLab(LiveViewInLab):
    """The "Mesh editor" output of the open notebook: its panel text and its live view."""

    def __init__(self, page):
        super().__init__(page.locator(".jp-OutputArea-output").filter(has_text="Mesh editor").first)

    def selected(self) -> str | None:
        match = re.search(r"selected: (\w+ \d+)", self.output.inner_text())
        return match.group(1) if match else None

    def index_box(self):
        return self.output.locator("input[type=text]").first

    def keys_box(self):
        return self.output.get_by_placeholder(re.compile("^click, type"))

    def diff_rows(self) -> int:
        return self.output.locator("table tr").count() - 1


def test_editor_selects_an_edge_and_flips_it_by_button_and_key(lab, browser_context, screenshot_dir):
    write_notebook(lab.root)
    with reported_page(browser_context, lab, screenshot_dir, "editor-failure-page.png") as page:
        _drive(page, lab, screenshot_dir)


def _drive(page, lab, shots: Path) -> None:
    timings: dict[str, float] = {}
    clock = [time.monotonic()]

    def lap() -> float:
        now = time.monotonic()
        seconds, clock[0] = round(now - clock[0], 1), now
        return seconds

    open_and_run_all(page, lab, NOTEBOOK)
    editor = EditorInLab(page)
    editor.wait_for_live_view("the editor")
    stray = page.locator(".jp-OutputArea-output").filter(has_text="Using wasm_dir")
    assert stray.count() == 0, f"a stray line above the editor: {stray.first.inner_text()}"
    wait_for(lambda: editor.selected() == "vertex 0", 30, "the panel to show the first selection")
    png, before = editor.settled_picture(None, "the live view's first frame")
    (shots / "editor-0-start.png").write_bytes(png)
    timings["open and run"] = lap()

    # Select an edge by the index controls.
    editor.output.locator("select").first.select_option("edge")
    editor.index_box().fill(str(EDGE))
    click_in_place(editor.output.get_by_role("button", name="select", exact=True))
    wait_for(lambda: editor.selected() == f"edge {EDGE}", 30, f"the panel to show edge {EDGE} selected")
    png, selected = editor.settled_picture(before, "the live view to highlight the edge")
    (shots / "editor-1-selected.png").write_bytes(png)
    timings["select by index"] = lap()

    # Flip by button: the ends change as the library says, the diff table appears.
    cube = hx.sample("cube")
    cube.flip(EDGE)
    flipped_ends = [v.index for v in cube.edge(EDGE).vertices]
    click_in_place(editor.output.get_by_role("button", name="flip", exact=True))
    wait_for(lambda: "pointer diff" in editor.output.inner_text(), 30, "the pointer diff after 'flip'")
    assert f"flip of edge {EDGE}" in editor.output.inner_text()
    assert f"vertices {flipped_ends[0]} - {flipped_ends[1]}" in editor.output.inner_text()
    assert editor.diff_rows() >= 6, "the diff table lists the pointers the flip changed"
    png, flipped = editor.settled_picture(selected, "the live view to redraw after 'flip'")
    (shots / "editor-2-flipped-by-button.png").write_bytes(png)
    print(f"flip button: {changed_share(selected, flipped):.2%} of the view changed")
    timings["flip by button"] = lap()

    # Flip back by key: type f into the keys box.
    click_in_place(editor.keys_box())
    page.keyboard.type("f")
    cube.flip(EDGE)
    back_ends = [v.index for v in cube.edge(EDGE).vertices]
    wait_for(lambda: f"vertices {back_ends[0]} - {back_ends[1]}" in editor.output.inner_text(), 30,
             "the panel to show the edge flipped back after the key f")
    assert "undo: 2" in editor.output.inner_text()
    png, back = editor.settled_picture(flipped, "the live view to redraw after the key f")
    (shots / "editor-3-flipped-back-by-key.png").write_bytes(png)
    assert changed_share(flipped, back) >= MIN_CHANGED_SHARE
    (shots / "editor-4-panel.png").write_bytes(editor.output.screenshot(timeout=30_000))
    timings["flip by key"] = lap()

    # Type fast: six l are six smoothing steps, not seven, and six z undo them. The kernel
    # answers keys in the order they come, so once the i typed after them has said its
    # line, all the keys before it are in.
    undos = undo_count(editor)
    for keys, expected in [("l" * FAST_KEYS, undos + FAST_KEYS), ("z" * FAST_KEYS, undos)]:
        page.keyboard.type(keys + "i", delay=FAST_KEY_DELAY_MS)
        wait_for(lambda: INFO_LINE in editor.output.inner_text(), 30,
                 f"the key i to say the selected edge's pointers after {keys}")
        assert undo_count(editor) == expected, f"{keys} typed fast made {undo_count(editor) - undos} edits"
        click_in_place(editor.output.get_by_role("button", name="select", exact=True))   # clears the line
        wait_for(lambda: INFO_LINE not in editor.output.inner_text(), 30, "the info line to go")
        click_in_place(editor.keys_box())
    timings["keys typed fast"] = lap()

    # Pick a face by right-clicking the live view: the face under the pointer turns yellow.
    editor.output.locator("select").first.select_option("face")
    wait_for(lambda: "right-click the view to pick a face" in editor.output.inner_text(), 30,
             "the kernel to know that a face is to be picked")
    box = editor.frame.bounding_box()
    x, y = int(0.5 * box["width"]), int(0.5 * box["height"])
    assert yellow_share(back, x, y) < 0.5, "the face under the pointer is highlighted before the click"
    page.mouse.click(box["x"] + x, box["y"] + y, button="right")
    wait_for(lambda: (editor.selected() or "").startswith("face"), 30, "a right-click to select a face")
    png, picked = editor.settled_picture(back, "the live view to highlight the picked face")
    (shots / "editor-5-picked-face.png").write_bytes(png)
    share = yellow_share(picked, x, y)
    assert share > 0.5, f"{editor.selected()} is selected, but only {share:.0%} around the click is yellow"
    timings["pick by right-click"] = lap()

    # Pick a vertex, then drag the ball on it: the vertex moves.
    editor.output.locator("select").first.select_option("vertex")
    wait_for(lambda: "right-click the view to pick a vertex" in editor.output.inner_text(), 30,
             "the kernel to know that a vertex is to be picked")
    page.mouse.click(box["x"] + x, box["y"] + y, button="right")
    wait_for(lambda: (editor.selected() or "").startswith("vertex"), 30, "a right-click to select a vertex")
    png, handled = editor.settled_picture(picked, "the live view to show the vertex's handle")
    (shots / "editor-6-picked-vertex.png").write_bytes(png)
    vertex = editor.selected()
    hx_, hy = handle_centre(handled)
    drag_by_hand(page, box["x"] + hx_, box["y"] + hy, 40, 30)
    wait_for(lambda: f"{vertex} moved" in editor.output.inner_text(), 30, f"a drag to move {vertex}")
    png, dragged = editor.settled_picture(handled, "the live view to redraw the dragged vertex")
    (shots / "editor-7-dragged-vertex.png").write_bytes(png)
    # The kernel lives on: undo answers, and the view still draws the mesh.
    undos = undo_count(editor)
    click_in_place(editor.output.get_by_role("button", name="undo", exact=True))
    wait_for(lambda: f"undo: {undos - 1}" in editor.output.inner_text(), 30, "undo after the drag")
    png, undone = editor.settled_picture(dragged, "the live view to redraw after undo")
    std, colours = drawn(undone)
    assert std >= MIN_STD and colours >= MIN_COLOURS, "the view is blank after undoing the drag"
    (shots / "editor-8-drag-undone.png").write_bytes(png)
    timings["pick a vertex and drag it"] = lap()
    print(f"right-click picked {editor.selected()}; seconds: {timings}")
    print(f"screenshots in {shots}")


def undo_count(editor: EditorInLab) -> int:
    return int(re.search(r"undo: (\d+)", editor.output.inner_text()).group(1))


def handle_centre(picture: np.ndarray) -> tuple[int, int]:
    """(x, y) of the middle of the drag handle (reddish purple ball, HANDLE_COLOUR, shaded)."""
    red, green, blue = picture[..., 0], picture[..., 1], picture[..., 2]
    ys, xs = np.nonzero((red > 120) & (red > green + 40) & (blue > green + 15))
    assert len(xs) > 20, "no drag handle on the selected vertex"
    return int(np.median(xs)), int(np.median(ys))


def yellow_share(picture: np.ndarray, x: int, y: int, half: int = 7) -> float:
    """The share of pixels around (x, y) in the highlighted face's yellow (role "face",
    #F0E442, shaded), not the grey surface or an arrow."""
    patch = picture[y - half : y + half + 1, x - half : x + half + 1].reshape(-1, 3)
    red, green, blue = patch[:, 0], patch[:, 1], patch[:, 2]
    return float(((red > 150) & (green > 130) & (blue < 0.7 * green)).mean())
