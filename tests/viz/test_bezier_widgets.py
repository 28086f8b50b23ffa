"""De Casteljau viewer and Bezier surface editor: driven from code, described in words."""

from __future__ import annotations

import numpy as np
import pytest

from halfedge_edu.algorithms.bezier import bezier_curve, bezier_surface_points, de_casteljau
from halfedge_edu.viz.bezier_widgets import BezierSurfaceEditor, DeCasteljauViewer

CUBIC = [[0, 0], [1, 2], [3, 2], [4, 0]]


def _grid():
    u, v = np.meshgrid(np.arange(4.0), np.arange(4.0), indexing="ij")
    grid = np.stack([u, v, np.zeros_like(u)], axis=-1)
    grid[1:3, 1:3, 2] = 1.0
    return grid


def test_the_viewer_lists_every_level_and_the_point_on_the_curve():
    viewer = DeCasteljauViewer(CUBIC, t=0.5)
    assert viewer.describe().splitlines() == [
        "degree 3 curve at t = 0.50: showing 3 of 3 levels",
        "control points: (0, 0) (1, 2) (3, 2) (4, 0)",
        "level 1: (0.5, 1) (2, 2) (3.5, 1)",
        "level 2: (1.25, 1.5) (2.75, 1.5)",
        "level 3: (2, 1.5)",
        "point on the curve: C(0.50) = (2, 1.5)",
    ]


def test_levels_are_shown_one_at_a_time():
    viewer = DeCasteljauViewer(CUBIC, t=0.25, levels=0)
    assert viewer.describe().splitlines()[1:] == ["control points: (0, 0) (1, 2) (3, 2) (4, 0)"]
    viewer.step()
    assert viewer.describe().splitlines()[-1] == "level 1: (0.25, 0.5) (1.5, 2) (3.25, 1.5)"
    viewer.back().back()
    assert viewer.shown_levels == 0


def test_the_t_slider_moves_the_point():
    viewer = DeCasteljauViewer(CUBIC)
    viewer.t_slider.value = 1.0
    assert np.allclose(viewer.point, CUBIC[-1])
    with pytest.raises(ValueError, match="between 0 and 1"):
        viewer.set_t(1.5)
    with pytest.raises(IndexError, match="levels run from 0 to 3"):
        viewer.show_levels(4)


def test_the_viewer_png_is_the_same_every_time():
    first = DeCasteljauViewer(CUBIC, t=0.3).screenshot()
    second = DeCasteljauViewer(CUBIC, t=0.3).screenshot()
    assert first[:8] == b"\x89PNG\r\n\x1a\n" and first == second


@pytest.fixture
def editor(closing):
    widget = BezierSurfaceEditor(_grid(), mode="static", resolution=9)
    closing(widget)
    return widget


def test_the_surface_passes_through_the_corner_control_points(editor):
    points = editor.surface.positions.reshape(9, 9, 3)
    for i, j in [(0, 0), (0, 3), (3, 0), (3, 3)]:
        assert np.allclose(points[-1 if i else 0, -1 if j else 0], editor.grid[i, j])


def test_moving_an_interior_point_keeps_the_boundary_curves(editor):
    rim_before = editor.surface.positions[editor.surface.vertex_is_boundary()].copy()
    editor.move(1, 2, [1.0, 2.0, 3.0])
    assert np.allclose(editor.surface.positions[editor.surface.vertex_is_boundary()], rim_before)
    assert np.allclose(editor.surface.positions.reshape(9, 9, 3), bezier_surface_points(editor.grid, 9))
    assert "moved: P[1][2]" in editor.describe()


def test_the_sliders_select_and_move_the_point(editor):
    editor.row_slider.value = 0
    editor.column_slider.value = 2
    assert editor.selected == (0, 2)
    editor.position_sliders[2].value = 1.5
    assert editor.grid[0, 2, 2] == 1.5
    assert editor.describe().splitlines()[1] == "selected: P[0][2] at (0, 2, 1.5) (was (0, 2, 0))"
    editor.reset()
    assert editor.position_sliders[2].value == 0.0 and "moved: none" in editor.describe()


def test_surface_point_is_de_casteljau_rows_then_column(editor):
    assert np.allclose(editor.surface_point(0.5, 0.5), bezier_surface_points(editor.grid, 3)[1, 1])


def test_both_widgets_have_a_large_preset(closing):
    viewer = DeCasteljauViewer(CUBIC, preset="large")
    assert viewer.screenshot()[:4] == b"\x89PNG"
    editor = BezierSurfaceEditor(_grid(), mode="static", preset="large", resolution=6)
    closing(editor)
    assert editor.scene.window_size == (1024, 768)


# -- moving control points of the curve (what a drag in the live view does) -------------


def test_moving_a_control_point_recomputes_the_curve_by_de_casteljau():
    viewer = DeCasteljauViewer(CUBIC, t=0.25, mode="static")
    picture = viewer.screenshot()
    moved = viewer.move_control_point(1, (1.5, 3.0))
    expected = np.array([[0, 0], [1.5, 3.0], [3, 2], [4, 0]], dtype=float)
    assert np.array_equal(moved, [1.5, 3.0]) and np.array_equal(viewer.control_points, expected)
    assert all(np.allclose(a, b) for a, b in zip(viewer.levels, de_casteljau(expected, 0.25)))
    assert np.allclose(viewer.curve, bezier_curve(expected, len(viewer.curve)))
    assert viewer.describe().splitlines()[-1] == "point on the curve: C(0.25) = (1.117, 1.547)"
    assert viewer.screenshot() != picture


def test_reset_puts_every_control_point_back():
    viewer = DeCasteljauViewer(CUBIC, t=0.5, mode="static")
    first = viewer.describe()
    viewer.move_control_point(0, (-1.0, 1.0))
    viewer.move_control_point(3, (5.0, 1.0))
    viewer.reset()
    assert np.array_equal(viewer.control_points, np.array(CUBIC, dtype=float))
    assert viewer.describe() == first


@pytest.mark.parametrize("index", [4, -1, 1.0, True])
def test_a_control_point_that_does_not_exist_is_refused_and_nothing_changes(index):
    viewer = DeCasteljauViewer(CUBIC, mode="static")
    before = viewer.describe()
    with pytest.raises(IndexError, match=r"no control point .*P_0 to P_3"):
        viewer.move_control_point(index, (1.0, 1.0))
    assert viewer.describe() == before


@pytest.mark.parametrize("position", [(np.nan, 1.0), (1.0, np.inf), (1.0, 2.0, 0.0), (1.0,)])
def test_a_position_that_is_not_two_finite_numbers_is_refused_and_nothing_changes(position):
    viewer = DeCasteljauViewer(CUBIC, mode="static")
    with pytest.raises(ValueError, match=r"P_2: .*two finite numbers"):
        viewer.move_control_point(2, position)
    assert np.array_equal(viewer.control_points, np.array(CUBIC, dtype=float))


def test_the_static_picture_says_dragging_needs_the_live_view():
    viewer = DeCasteljauViewer(CUBIC, mode="static")
    assert "dragging the control points needs the live view" in viewer.hint.value
    assert "move_control_point" in viewer.hint.value


def test_a_drag_moves_the_point_in_the_plane_and_a_bad_one_only_says_why():
    viewer = DeCasteljauViewer(CUBIC, t=0.5, mode="static")
    viewer._dragged(2, (3.5, 2.5, 0.2))            # a ball let go a little off the plane
    assert np.array_equal(viewer.control_points[2], [3.5, 2.5])
    viewer._dragged(2, (np.nan, 0.0, 0.0))
    assert "two finite numbers" in viewer.status.value
    assert np.array_equal(viewer.control_points[2], [3.5, 2.5])


def test_the_live_view_has_a_ball_on_every_control_point_that_follows_it(closing):
    viewer = DeCasteljauViewer(CUBIC, t=0.5, mode="live")
    closing(viewer)
    assert [handle.GetCenter() for handle in viewer.scene.handles] == [(x, y, 0.0) for x, y in CUBIC]
    picture = viewer.screenshot()
    viewer.move_control_point(1, (1.0, 3.0))
    assert viewer.scene.handles[1].GetCenter() == (1.0, 3.0, 0.0)
    assert viewer.screenshot() != picture
    assert "Drag a grey ball" in viewer.hint.value and "point on the curve" in viewer.legend.value


def test_a_release_that_did_not_move_a_ball_changes_nothing():
    viewer = DeCasteljauViewer(CUBIC, t=0.5, mode="static")
    viewer.move_control_point(1, (1.0, 2.5))
    viewer._dragged(0, (0.0, 0.0, 0.0))            # VTK's first release, reported to P_0's ball
    assert viewer.status.value.startswith("degree 3") and viewer.control_points[1, 1] == 2.5


def test_the_surface_sliders_report_to_the_kernel_only_when_let_go(editor):
    sliders = [editor.row_slider, editor.column_slider, *editor.position_sliders]
    assert [slider.continuous_update for slider in sliders] == [False] * 5
