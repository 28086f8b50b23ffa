"""Chapter 12 in a real JupyterLab: drag a control point of the de Casteljau viewer in
its live 3D view, and see the picture redraw and the point on the curve change.

Run all cells, find the ball on ``P_1`` in the viewer's trame view, drag it up and to the
right with the mouse, and wait for the panel's text: ``P_1`` has moved, the other
control points have not, and ``C(t)`` is de Casteljau's point of the moved polygon.
Then **reset** puts the arch back. Last, the surface editor must show what the
chapter's cells did to it: its sliders once sent stale values back from the browser and
moved a control point by themselves. Screenshots go to ``$HALFEDGE_EDU_SCREENSHOTS`` (or
pytest's temporary folder).
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import numpy as np
import pytest
from scipy import ndimage

from halfedge_edu.algorithms.bezier import de_casteljau
from tests.browser.lab_page import (
    FRAME_TIMEOUT,
    MIN_CHANGED_SHARE,
    LiveViewInLab,
    changed_share,
    click_in_place,
    drag_by_hand,
    open_and_run_all,
    reported_page,
    wait_for,
)

pytestmark = pytest.mark.browser

NOTEBOOK = "12_bezier.ipynb"
ARCH = [(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 0.0)]     # the chapter's arch, as the viewer shows it
DRAG = (40, -30)                                             # pixels: right and up


class SurfaceEditorInLab:
    """The last "Bezier surface: move a control point" output of the open notebook."""

    def __init__(self, page):
        self.output = page.locator(".jp-OutputArea-output").filter(has_text="Bezier surface: move a control point").last

    def selected(self) -> str | None:
        match = re.search(r"selected: (P\[\d\]\[\d\] at \([^()]*\))", self.output.inner_text())
        return match.group(1) if match else None


class CurveViewerInLab(LiveViewInLab):
    """The de Casteljau viewer's output (the one with a live view) in the open notebook."""

    def __init__(self, page):
        super().__init__(page.locator(".jp-OutputArea-output").filter(has_text="degree 3 curve at t =")
                         .filter(has=page.locator("iframe")).first)

    def control_points(self) -> list[tuple[float, float]]:
        match = re.search(r"control points: (.*)", self.output.inner_text())
        assert match, "the panel does not list the control points"
        return [tuple(float(c) for c in pair.split(", ")) for pair in re.findall(r"\(([^()]*)\)", match.group(1))]

    def curve_point(self) -> tuple[str, tuple[float, float]] | None:
        match = re.search(r"point on the curve: C\(([\d.]+)\) = \(([^()]*)\)", self.output.inner_text())
        if not match:
            return None
        return match.group(1), tuple(float(c) for c in match.group(2).split(", "))


def test_dragging_a_control_point_redraws_the_curve_and_its_point(lab, browser_context, screenshot_dir):
    with reported_page(browser_context, lab, screenshot_dir, "bezier-failure-page.png") as page:
        _drive(page, lab, screenshot_dir)


def _drive(page, lab, shots: Path) -> None:
    started = time.monotonic()
    open_and_run_all(page, lab, NOTEBOOK)
    viewer = CurveViewerInLab(page)
    viewer.output.scroll_into_view_if_needed(timeout=30_000)
    viewer.frame.wait_for(state="visible", timeout=FRAME_TIMEOUT * 1000)
    wait_for(lambda: viewer.curve_point() is not None, 30, "the viewer's panel")
    assert viewer.control_points() == ARCH, "the chapter's cells should leave the arch as it started"
    t, start_point = viewer.curve_point()
    png, before = viewer.settled_picture(None, "the live view's first frame with its four balls",
                                         shows=lambda picture: find_balls(picture) is not None)
    (shots / "bezier-0-start.png").write_bytes(png)
    ran = time.monotonic()

    # Drag the ball on P_1 (the upper left one) up and to the right.
    x, y = ball_centres(before)[1]
    box = viewer.frame.bounding_box()
    drag_by_hand(page, box["x"] + x, box["y"] + y, *DRAG)
    wait_for(lambda: viewer.control_points()[1] != ARCH[1], 30, "the panel to show P_1 moved after the drag")
    moved = viewer.control_points()
    assert moved[0] == ARCH[0] and moved[2:] == ARCH[2:], f"only P_1 should move, the panel shows {moved}"
    assert moved[1][0] > ARCH[1][0] and moved[1][1] > ARCH[1][1], f"P_1 went {moved[1]}, not up and right"
    shown_t, point = viewer.curve_point()
    expected = de_casteljau(np.array(moved), float(shown_t))[-1][0]
    assert shown_t == t and point != start_point
    assert np.allclose(point, expected, atol=2e-3), f"C({t}) = {point}, de Casteljau gives {expected}"
    png, dragged = viewer.settled_picture(before, "the live view to redraw after the drag")
    (shots / "bezier-1-dragged.png").write_bytes(png)
    share = changed_share(before, dragged)
    assert share >= MIN_CHANGED_SHARE, f"the drag changed only {share:.2%} of the view"
    dragged_at = time.monotonic()

    # reset puts the arch back, in the text and in the picture.
    click_in_place(viewer.output.get_by_role("button", name="reset", exact=True))
    wait_for(lambda: viewer.control_points() == ARCH, 30, "the panel to show the arch again after 'reset'")
    assert viewer.curve_point() == (t, start_point)
    png, back = viewer.settled_picture(dragged, "the live view to redraw after 'reset'")
    (shots / "bezier-2-reset.png").write_bytes(png)
    (shots / "bezier-3-panel.png").write_bytes(viewer.output.screenshot(timeout=30_000))
    reset_at = time.monotonic()

    # The surface editor shows the chapter's last move, not a value its sliders sent back.
    editor = SurfaceEditorInLab(page)
    editor.output.scroll_into_view_if_needed(timeout=30_000)
    selected = wait_for(editor.selected, 30, "the surface editor's panel")
    time.sleep(2)
    assert editor.selected() == selected == "P[0][1] at (0, 1, 1)", \
        f"the chapter left P[0][1] at (0, 1, 1); the editor shows {editor.selected()}"
    print(f"P_1 dragged to {moved[1]}, C({t}) {start_point} -> {point}; {share:.2%} of the view changed; "
          f"seconds: open and run {ran - started:.1f}, drag {dragged_at - ran:.1f}, "
          f"reset {reset_at - dragged_at:.1f}; screenshots in {shots}")


def find_balls(picture: np.ndarray) -> list[tuple[float, float]] | None:
    """(row, column) centres of the four largest grey blobs: the drag balls (``HANDLE``,
    #555555, shaded), or None if the picture does not show four of at least 12 pixels."""
    red, green, blue = picture[..., 0], picture[..., 1], picture[..., 2]
    grey = (np.abs(red - green) < 14) & (np.abs(green - blue) < 14) & (red > 35) & (red < 118)
    solid = ndimage.binary_erosion(grey, iterations=2)          # the thin grey lines drop out
    labels, count = ndimage.label(solid)
    sizes = ndimage.sum(solid, labels, range(1, count + 1))
    if count < 4 or sorted(sizes)[-4] < 12:
        return None
    return [ndimage.center_of_mass(solid, labels, k + 1) for k in np.argsort(sizes)[::-1][:4]]


def ball_centres(picture: np.ndarray) -> list[tuple[int, int]]:
    """(x, y) of the drag balls, ordered P_0 .. P_3 for the arch:
    the two low ones are P_0 (left) and P_3, the two high ones P_1 (left) and P_2."""
    blobs = find_balls(picture)
    assert blobs is not None, "expected four balls in the picture"
    low, high = sorted(blobs, key=lambda c: -c[0])[:2], sorted(blobs, key=lambda c: -c[0])[2:]
    p0, p3 = sorted(low, key=lambda c: c[1])
    p1, p2 = sorted(high, key=lambda c: c[1])
    return [(int(round(c[1])), int(round(c[0]))) for c in (p0, p1, p2, p3)]

