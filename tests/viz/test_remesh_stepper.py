"""RemeshStepper: every snapshot is the real algorithm's state, described phase by phase."""

from __future__ import annotations

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.algorithms.remesh import PHASES, remesh
from halfedge_edu.data import sample
from halfedge_edu.viz.remesh_stepper import PhaseQuality, RemeshStepper, histogram_figure, histogram_png, phase_quality

L = 0.25


@pytest.fixture(scope="module")
def sphere():
    return sample("icosphere", subdivisions=2)


@pytest.fixture
def stepper(closing, sphere):
    widget = RemeshStepper(sphere, target_length=L, iterations=2, mode="static", window_size=(320, 240))
    closing(widget)
    return widget


def test_snapshots_are_the_input_then_every_phase_of_every_iteration(stepper):
    names = [(s.iteration, s.phase) for s in stepper.snapshots]
    assert names == [(0, "input")] + [(i, p) for i in (1, 2) for p in PHASES]
    assert stepper.n_steps == 2 * len(PHASES)


def test_the_last_snapshot_is_what_remesh_returns(stepper, sphere):
    reference = remesh(sphere, L, iterations=2)
    result = stepper.result
    assert (result.n_vertices, result.n_faces) == (reference.n_vertices, reference.n_faces)
    assert np.allclose(result.to_arrays()[0], reference.to_arrays()[0])


def test_step_zero_describes_the_input_with_its_quality(stepper):
    lines = stepper.describe().splitlines()
    assert lines[0].endswith("step 0 of 10, input")
    assert "L = 0.25" in lines[0]
    assert lines[-1].startswith("now: 162 vertices, 320 faces")


def test_a_split_says_how_many_edges_were_long_and_none_is_left(stepper):
    stepper.go((1, "split"))
    text = stepper.describe()
    assert "did: " in text and "edges were longer than 4/3 L" in text
    assert stepper.quality.n_long == 0


def test_no_edge_is_longer_than_four_thirds_L_after_a_collapse(stepper):
    stepper.go("collapse")
    assert stepper.phase == "collapse"
    assert stepper.quality.lengths.max() <= 4 / 3 + 1e-9
    assert "edges collapsed" in stepper.describe()


def test_a_flip_keeps_the_counts_and_lowers_the_degree_deviation(stepper):
    before = stepper.snapshots[stepper.index_of(1, "collapse")].quality
    stepper.go((1, "flip"))
    assert (stepper.quality.n_vertices, stepper.quality.n_faces) == (before.n_vertices, before.n_faces)
    assert stepper.quality.degree_deviation <= before.degree_deviation
    assert "edges flipped" in stepper.describe()


def test_smoothing_moves_no_boundary_vertex(closing):
    patch = remesh(sample("open_patch"), 0.4, iterations=0)
    widget = RemeshStepper(patch, target_length=0.4, iterations=1, mode="static", window_size=(240, 200))
    closing(widget)
    before = widget.snapshots[widget.index_of(1, "flip")].mesh
    widget.go((1, "smooth"))
    after = widget.state
    boundary = before.vertex_is_boundary()
    assert boundary.any()
    assert np.array_equal(after.positions[boundary], before.positions[boundary])
    assert f"the {int(boundary.sum())} boundary vertices stayed put" in widget.describe()


def test_go_by_phase_name_iteration_and_ends(stepper):
    assert stepper.go("smooth") == stepper.index_of(1, "smooth")
    assert stepper.go("iteration") == stepper.index_of(2, "smooth")
    assert stepper.go("smooth") == stepper.index_of(1, "smooth")    # none later: back to the first
    assert stepper.go("end") == stepper.n_steps
    assert stepper.step() == stepper.n_steps
    assert stepper.go("start") == 0 and stepper.back() == 0


def test_unknown_moves_are_refused_in_words(stepper):
    with pytest.raises(ValueError, match="unknown move"):
        stepper.go("sideways")
    with pytest.raises(ValueError, match="no phase 'flip' in iteration 3"):
        stepper.go((3, "flip"))
    with pytest.raises(IndexError, match="steps run from 0 to 10"):
        stepper.go(11)


def test_buttons_drive_the_same_moves(stepper):
    stepper.buttons["step"].click()
    assert (stepper.iteration, stepper.phase) == (1, "split")
    stepper.buttons["iteration"].click()
    assert (stepper.iteration, stepper.phase) == (2, "split")
    stepper.buttons["end"].click()
    assert stepper.step_index == stepper.n_steps


def test_the_picture_marks_long_and_short_edges(stepper):
    layers = {layer.label: layer for layer in stepper.scene.layers}
    assert len(layers["longer than 4/3 L: to split"].items) == stepper.quality.n_long
    assert len(layers["shorter than 4/5 L: to collapse"].items) == stepper.quality.n_short


def test_the_static_view_and_the_display_carry_the_histograms(stepper):
    png = stepper.screenshot()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert stepper._histograms.value[:8] == b"\x89PNG\r\n\x1a\n"
    bundle = stepper._repr_mimebundle_()
    assert bundle["text/plain"] == stepper.describe()


def test_quality_counts_edges_against_the_target(sphere):
    quality = phase_quality(sphere, target_length=1.0)
    assert quality.n_edges == len(quality.lengths) == sphere.n_edges
    assert quality.n_long == 0 and quality.n_short == sphere.n_edges
    assert quality.degrees.tolist().count(5) == 12


def test_histogram_png_draws_any_number_of_meshes(sphere):
    png = histogram_png([sphere, sample("icosphere", subdivisions=1)], ["a", "b"], 0.3)
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def legend_covers(figure) -> list[str]:
    """What the histograms' legend covers, drawn with Agg: each bar it overlaps, any axes
    it reaches into, and "outside the figure" when it is cut off."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(figure).get_renderer()
    figure.draw(renderer)
    legend = figure.axes[-1].get_legend()
    box = legend.get_window_extent(renderer)
    covered = [f"axes {k}" for k, axis in enumerate(figure.axes) if box.overlaps(axis.get_window_extent(renderer))]
    covered += [f"bar of axes {k} at x = {patch.get_x():g}"
                for k, axis in enumerate(figure.axes) for patch in axis.patches
                if hasattr(patch, "get_x") and box.overlaps(patch.get_window_extent(renderer))]
    if not figure.bbox.contains(box.x0, box.y0) or not figure.bbox.contains(box.x1, box.y1):
        covered.append("outside the figure")
    return covered


def test_the_histograms_legend_covers_no_bar_in_chapter_11s_picture():
    rough = hx.simplify(sample("spot"), 1500)
    even = hx.remesh(rough, target_length=0.08, iterations=3)
    figure = histogram_figure([rough, even], ["after simplification", "remeshed (L = 0.08, 3 iterations)"], 0.08)
    assert legend_covers(figure) == []


def test_the_histograms_legend_covers_no_bar_when_every_bar_is_tall_at_the_left():
    """Skewed data: everything in the first bins, where an "upper left" legend would sit."""
    n = 200
    skewed = PhaseQuality(n_vertices=n, n_edges=n, n_faces=n, lengths=np.full(n, 0.01), degrees=np.full(n, 3),
                          on_boundary=np.zeros(n, bool), min_angles=np.full(n, 1.0), degree_deviation=3.0,
                          min_angle_mean=1.0)
    spread = phase_quality(sample("icosphere", subdivisions=2), 0.25)
    labels = ["input", "a long label: iteration 2, project", "iteration 2, smooth"]
    for size in ((8.4, 2.5), (6.0, 2.5)):
        assert legend_covers(histogram_figure([skewed, spread, skewed], labels, 0.25, size=size)) == []


def test_the_steppers_histograms_legend_covers_no_bar(stepper):
    stepper.go((2, "smooth"))
    labels = ["input", "iteration 2, smooth"]
    figure = histogram_figure([stepper.snapshots[0].quality, stepper.quality], labels, L)
    assert legend_covers(figure) == []


def test_iteration_from_the_input_ends_iteration_one(stepper):
    stepper.go("start")
    assert stepper.go("iteration") == stepper.index_of(1, "project")


def test_iteration_in_the_last_iteration_stays_and_says_why(stepper):
    split_two = stepper.index_of(2, "split")
    stepper.go(split_two)
    assert stepper.go("iteration") == split_two
    assert "iteration 2 is the last one" in stepper._status.value
